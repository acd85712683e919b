//! Engine configuration: the machine the engine simulates. Deserialized from the `[machine]`,
//! `[[axes]]` and `[io]` parts of an mcemu config file; every struct refuses unknown keys.
//!
//! Semantic checks (ranges, cross-field rules) happen in [`EngineConfig::validate`], which names
//! the offending key path so the binary can say "file, key, reason".

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::cia402::DriveConfig;
use crate::param::{ParamAccess, ParamId};

/// Shortest and longest servo period (ARCHITECTURE §3.1).
pub const MIN_PERIOD: f64 = 62.5e-6;
pub const MAX_PERIOD: f64 = 10e-3;

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EngineConfig {
    /// Servo period in seconds, 62.5 µs … 10 ms.
    #[serde(default = "default_period")]
    pub period: f64,
    /// Seed of every random process (encoder noise, injected faults).
    #[serde(default)]
    pub seed: u64,
    #[serde(default)]
    pub axes: Vec<AxisConfig>,
    #[serde(default)]
    pub io: IoConfig,
    /// CiA 402 drives, each bound to an axis; slave numbers are positions in this list.
    #[serde(default)]
    pub drives: Vec<DriveConfig>,
    /// Axis groups (issue 11): how many, and the defaults of `group_create`.
    #[serde(default)]
    pub groups: GroupsConfig,
    /// Cam tables defined at start, as `cam_table` commands would define them (issue 12).
    /// Checked when the engine is built (`Engine::new`).
    #[serde(default)]
    pub cam_tables: Vec<crate::command::CamTableDefine>,
}

fn default_period() -> f64 {
    1e-3
}

impl Default for EngineConfig {
    fn default() -> Self {
        EngineConfig {
            period: default_period(),
            seed: 0,
            axes: Vec::new(),
            io: IoConfig::default(),
            drives: Vec::new(),
            groups: GroupsConfig::default(),
            cam_tables: Vec::new(),
        }
    }
}

/// Most entries a group queue may hold (HIMC SetGrpQueueSize: 2^10).
pub const MAX_GROUP_QUEUE: u32 = 1024;

/// The `[groups]` section: limits and defaults of the axis groups (issue 11).
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GroupsConfig {
    /// How many groups may exist at once (1–64).
    pub max_groups: u16,
    /// Entries a group queue holds (motions and buffered commands) when `group_create` gives no
    /// `queue_capacity`: 1–1024 (HIMC: 512).
    pub queue_capacity: u32,
    /// Segments the look-ahead plans over when `group_create` gives no `lookahead`: 1 up to the
    /// queue capacity (default 64).
    pub lookahead: u32,
    /// Spline spans a group constructs per servo tick, and at most per `move_spline` applied:
    /// 1–1000 (default 8). A longer spline starts that many ticks later, so the tick's work
    /// stays bounded.
    pub spline_spans_per_tick: u32,
}

impl Default for GroupsConfig {
    fn default() -> Self {
        GroupsConfig {
            max_groups: 8,
            queue_capacity: 512,
            lookahead: 64,
            spline_spans_per_tick: 8,
        }
    }
}

impl GroupsConfig {
    fn validate(&self) -> Result<(), ConfigError> {
        if !(1..=64).contains(&self.max_groups) {
            return Err(ConfigError::new(
                "groups.max_groups",
                format!("{} is outside 1 … 64", self.max_groups),
            ));
        }
        if !(1..=MAX_GROUP_QUEUE).contains(&self.queue_capacity) {
            return Err(ConfigError::new(
                "groups.queue_capacity",
                format!("{} is outside 1 … {MAX_GROUP_QUEUE}", self.queue_capacity),
            ));
        }
        if !(1..=self.queue_capacity).contains(&self.lookahead) {
            return Err(ConfigError::new(
                "groups.lookahead",
                format!(
                    "{} is outside 1 … queue_capacity ({})",
                    self.lookahead, self.queue_capacity
                ),
            ));
        }
        if !(1..=1000).contains(&self.spline_spans_per_tick) {
            return Err(ConfigError::new(
                "groups.spline_spans_per_tick",
                format!("{} is outside 1 … 1000", self.spline_spans_per_tick),
            ));
        }
        Ok(())
    }
}

/// One axis: its parameters (any row of the table) and its simulated hardware.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AxisConfig {
    /// Shown in the control API and traces; default `axis<N>`.
    pub name: Option<String>,
    /// Slots of the command FIFO, the running command included (HMC: 64).
    pub fifo_depth: Option<u16>,
    /// Parameter values by name or vendor alias, e.g. `speed = 100.0`, `FELimit = 5`. Booleans
    /// read as 0/1 and enumerated parameters also take their value names (`axis_type =
    /// "stepper"`, `rep_mode = "finite"`).
    #[serde(deserialize_with = "deserialize_params")]
    #[cfg_attr(feature = "schema", schemars(schema_with = "params_schema"))]
    pub params: BTreeMap<ParamId, f64>,
    /// Pulse/direction output (stepper and bus-position types).
    pub pulse: PulseConfig,
    /// Incremental encoder on the motor.
    pub encoder: EncoderConfig,
    /// Drive and motor model.
    pub plant: PlantConfig,
    /// Limit and home switches.
    pub switches: SwitchesConfig,
}

/// `params` is a table of parameter names to numbers, booleans or enumerated value names.
#[cfg(feature = "schema")]
fn params_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    schemars::json_schema!({
        "type": "object",
        "additionalProperties": { "type": ["number", "boolean", "string"] }
    })
}

pub const DEFAULT_FIFO_DEPTH: u16 = 64;

/// A parameter value as written in a config: a number, a boolean, or an enumerated value's name.
#[derive(Deserialize)]
#[serde(untagged)]
enum ParamInput {
    Number(f64),
    Bool(bool),
    Name(String),
}

fn deserialize_params<'de, D>(deserializer: D) -> Result<BTreeMap<ParamId, f64>, D::Error>
where
    D: serde::Deserializer<'de>,
{
    use serde::de::Error;
    let raw = BTreeMap::<ParamId, ParamInput>::deserialize(deserializer)?;
    let mut out = BTreeMap::new();
    for (id, input) in raw {
        let value = match input {
            ParamInput::Number(v) => v,
            ParamInput::Bool(b) => f64::from(u8::from(b)),
            ParamInput::Name(name) => match id.def().kind {
                crate::param::Kind::Enum(values) => values
                    .iter()
                    .find(|(_, n)| n.eq_ignore_ascii_case(&name))
                    .map(|(code, _)| *code as f64)
                    .ok_or_else(|| {
                        let names: Vec<&str> = values.iter().map(|(_, n)| *n).collect();
                        D::Error::custom(format!(
                            "`{}` = \"{name}\": must be one of {}",
                            id.name(),
                            names.join(", ")
                        ))
                    })?,
                _ => {
                    return Err(D::Error::custom(format!(
                        "`{}` = \"{name}\": must be a number",
                        id.name()
                    )))
                }
            },
        };
        out.insert(id, value);
    }
    Ok(out)
}

/// Pulse/direction output (ARCHITECTURE §3.2).
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PulseConfig {
    /// Highest pulse frequency, Hz (HMC 2 MHz, CPU 226H 200 kHz). Faster commands are clamped
    /// and the pulses owed are sent later.
    pub max_frequency: f64,
    /// Invert the direction output.
    pub invert_direction: bool,
}

impl Default for PulseConfig {
    fn default() -> Self {
        PulseConfig {
            max_frequency: 2e6,
            invert_direction: false,
        }
    }
}

// Each hardware model owns its configuration (the hw modules sit below `config` in the module
// chain); re-exported here, where the axis configuration is assembled, under their old paths.
pub use crate::hw::encoder::EncoderConfig;
pub use crate::hw::plant::{PlantConfig, PlantModel};
pub use crate::hw::switch::{HomeSwitchConfig, SwitchConfig, SwitchesConfig};

/// Machine I/O images.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IoConfig {
    /// Number of digital input channels (DI 0 … n−1).
    pub digital_inputs: u16,
    /// Number of digital output channels.
    pub digital_outputs: u16,
    /// Number of analog input channels.
    pub analog_inputs: u16,
    /// Number of analog output channels.
    pub analog_outputs: u16,
    /// DI channels driven by an axis signal (the wiring of a switch to a general input).
    pub bindings: Vec<InputBinding>,
}

impl Default for IoConfig {
    fn default() -> Self {
        IoConfig {
            digital_inputs: 64,
            digital_outputs: 64,
            analog_inputs: 8,
            analog_outputs: 8,
            bindings: Vec::new(),
        }
    }
}

/// `di[channel]` follows `signal` of `axis`.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputBinding {
    /// The DI channel that follows the signal.
    pub channel: u16,
    /// The axis whose signal it follows.
    pub axis: u16,
    /// Which signal of the axis.
    pub signal: AxisSignal,
}

/// An axis signal that can be wired to a general input.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisSignal {
    /// The positive hard limit as the axis reads it.
    LimitPos,
    /// The negative hard limit as the axis reads it.
    LimitNeg,
    /// The home switch as the axis reads it.
    Home,
    /// The encoder index (Z) pulse.
    Index,
    /// The drive alarm.
    DriveAlarm,
}

/// A semantic config error: the key path (`axes[1].params.accel`) and why.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{key}: {reason}")]
pub struct ConfigError {
    pub key: String,
    pub reason: String,
}

impl ConfigError {
    pub fn new(key: impl Into<String>, reason: impl Into<String>) -> ConfigError {
        ConfigError {
            key: key.into(),
            reason: reason.into(),
        }
    }
}

impl EngineConfig {
    /// Check ranges and cross-field rules. Errors name the key path.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if !(MIN_PERIOD..=MAX_PERIOD).contains(&self.period) {
            return Err(ConfigError::new(
                "period",
                format!(
                    "{} s is outside {MIN_PERIOD} … {MAX_PERIOD} s (62.5 µs … 10 ms)",
                    self.period
                ),
            ));
        }
        for (i, axis) in self.axes.iter().enumerate() {
            axis.validate(&format!("axes[{i}]"))?;
        }
        self.groups.validate()?;
        let mut bound = vec![false; self.axes.len()];
        for (i, d) in self.drives.iter().enumerate() {
            let key = format!("drives[{i}]");
            d.validate()
                .map_err(|e| ConfigError::new(key.clone(), e.to_string()))?;
            match bound.get_mut(d.axis as usize) {
                None => {
                    return Err(ConfigError::new(
                        format!("{key}.axis"),
                        format!("axis {} does not exist ({} axes)", d.axis, self.axes.len()),
                    ))
                }
                Some(true) => {
                    return Err(ConfigError::new(
                        format!("{key}.axis"),
                        format!("axis {} already has a drive", d.axis),
                    ))
                }
                Some(b) => *b = true,
            }
        }
        let io = &self.io;
        for (i, b) in io.bindings.iter().enumerate() {
            if b.channel >= io.digital_inputs {
                return Err(ConfigError::new(
                    format!("io.bindings[{i}].channel"),
                    format!(
                        "DI {} does not exist (digital_inputs = {})",
                        b.channel, io.digital_inputs
                    ),
                ));
            }
            if b.axis as usize >= self.axes.len() {
                return Err(ConfigError::new(
                    format!("io.bindings[{i}].axis"),
                    format!("axis {} does not exist ({} axes)", b.axis, self.axes.len()),
                ));
            }
        }
        Ok(())
    }
}

impl AxisConfig {
    fn validate(&self, key: &str) -> Result<(), ConfigError> {
        if self.fifo_depth == Some(0) {
            return Err(ConfigError::new(
                format!("{key}.fifo_depth"),
                "must be at least 1",
            ));
        }
        for (id, value) in &self.params {
            let def = id.def();
            if def.access == ParamAccess::ReadOnly {
                return Err(ConfigError::new(
                    format!("{key}.params.{}", def.name),
                    "is computed by the engine and cannot be configured",
                ));
            }
            if let Err(e) = def.validate(*value) {
                return Err(ConfigError::new(
                    format!("{key}.params.{}", def.name),
                    e.to_string(),
                ));
            }
        }
        let positive = |name: &str, v: f64| -> Result<(), ConfigError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(ConfigError::new(
                    format!("{key}.{name}"),
                    format!("{v} must be a positive number"),
                ))
            }
        };
        positive("pulse.max_frequency", self.pulse.max_frequency)?;
        if !(self.encoder.noise.is_finite() && self.encoder.noise >= 0.0) {
            return Err(ConfigError::new(
                format!("{key}.encoder.noise"),
                "must be a finite number ≥ 0",
            ));
        }
        if self.encoder.counts_per_rev > 0 && self.encoder.index_width == 0 {
            return Err(ConfigError::new(
                format!("{key}.encoder.index_width"),
                "must be at least 1 count when counts_per_rev is set",
            ));
        }
        positive("plant.time_constant", self.plant.time_constant)?;
        positive("plant.full_scale_velocity", self.plant.full_scale_velocity)?;
        let vtc = self.plant.velocity_time_constant;
        if !(vtc.is_finite() && vtc >= 0.0) {
            return Err(ConfigError::new(
                format!("{key}.plant.velocity_time_constant"),
                "must be a finite number ≥ 0",
            ));
        }
        let axis_type = self
            .params
            .get(&ParamId::AxisType)
            .copied()
            .unwrap_or(ParamId::AxisType.def().default);
        let closed_loop = crate::hw::AxisClass::of(axis_type).is_closed_loop();
        if closed_loop != (self.plant.model == PlantModel::PositionLoop) {
            return Err(ConfigError::new(
                format!("{key}.plant.model"),
                if closed_loop {
                    format!("axis type {axis_type} closes a position loop: the plant model must be `position_loop`")
                } else {
                    format!("`position_loop` needs a closed-loop axis type (20, 41 or 51), not {axis_type}")
                },
            ));
        }
        let sw = &self.switches;
        for (name, s) in [("limit_pos", &sw.limit_pos), ("limit_neg", &sw.limit_neg)] {
            if let Some(s) = s {
                if !s.position.is_finite() {
                    return Err(ConfigError::new(
                        format!("{key}.switches.{name}.position"),
                        "must be a finite number",
                    ));
                }
            }
        }
        if let (Some(p), Some(n)) = (&sw.limit_pos, &sw.limit_neg) {
            if p.position <= n.position {
                return Err(ConfigError::new(
                    format!("{key}.switches.limit_pos.position"),
                    format!(
                        "{} must be above the negative limit at {}",
                        p.position, n.position
                    ),
                ));
            }
        }
        if let Some(h) = &sw.home {
            if h.low.is_nan() || h.high.is_nan() || h.low > h.high || h.low == h.high {
                return Err(ConfigError::new(
                    format!("{key}.switches.home"),
                    format!("low ({}) must be below high ({})", h.low, h.high),
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_key_path() {
        let mut c = EngineConfig {
            period: 0.02,
            ..Default::default()
        };
        assert_eq!(c.validate().unwrap_err().key, "period");
        c.period = 1e-3;
        let mut axis = AxisConfig::default();
        axis.params.insert(ParamId::Accel, -1.0);
        c.axes.push(AxisConfig::default());
        c.axes.push(axis);
        let e = c.validate().unwrap_err();
        assert_eq!(e.key, "axes[1].params.accel");
        assert!(e.reason.contains("greater than 0"), "{}", e.reason);
    }

    #[test]
    fn params_take_booleans_and_enum_names() {
        let c: AxisConfig = serde_json::from_str(
            r#"{"params": {"axis_type": "stepper", "jerk_mode": true, "rep_mode": "FINITE", "speed": 5}}"#,
        )
        .unwrap();
        assert_eq!(c.params[&ParamId::AxisType], 10.0);
        assert_eq!(c.params[&ParamId::JerkMode], 1.0);
        assert_eq!(c.params[&ParamId::RepMode], 0.0);
        assert_eq!(c.params[&ParamId::Speed], 5.0);
        let e = serde_json::from_str::<AxisConfig>(r#"{"params": {"axis_type": "steper"}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("must be one of unused, virtual, stepper"), "{e}");
        assert!(serde_json::from_str::<AxisConfig>(r#"{"params": {"speed": "fast"}}"#).is_err());
    }

    #[test]
    fn params_deserialize_by_alias() {
        let c: AxisConfig =
            serde_json::from_str(r#"{"params": {"Speed": 10.0, "FELimit": 3}}"#).unwrap();
        assert_eq!(c.params[&ParamId::Speed], 10.0);
        assert_eq!(c.params[&ParamId::FeLimit], 3.0);
        assert!(serde_json::from_str::<AxisConfig>(r#"{"parms": {}}"#).is_err());
    }
}
