//! The scenario file as written: its top-level keys split into the scenario's own (`config`,
//! `end`, `step`) and an inline machine config (every other section, exactly as in a config file).
//!
//! The split happens inside one deserialization of the text, so errors keep the TOML parser's
//! line and column and `serde_path_to_error`'s key path, for the steps and the inline config
//! alike, and the inline config accepts whatever sections `Config` accepts.

use std::fmt;

use axes::command::{AxisInput, Command};
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, Visitor};
use serde::Deserialize;

use crate::config::Config;

/// The scenario's own top-level keys.
pub(super) const SCENARIO_KEYS: [&str; 3] = ["config", "end", "step"];

/// A parsed scenario file, not yet checked.
#[derive(Debug, Default)]
pub(super) struct ScenarioFile {
    /// `config = "path"`, relative to the scenario file.
    pub config_path: Option<String>,
    pub end: Option<f64>,
    pub steps: Vec<StepSpec>,
    /// The inline config; meaningful only when `inline_sections` is not empty.
    pub inline: Config,
    /// Config sections the file gave (in the parser's order, not necessarily the file's).
    pub inline_sections: Vec<String>,
}

/// One `[[step]]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct StepSpec {
    pub at: f64,
    #[serde(default)]
    pub command: Option<Command>,
    /// With `command`: the command must be refused with this error code.
    #[serde(default)]
    pub expect_error: Option<String>,
    #[serde(default)]
    pub force: Option<ForceSpec>,
    #[serde(default)]
    pub expect: Option<ExpectSpec>,
}

/// `force = { axis, input, value }` or `force = { di, value }`; no `value` releases the input.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ForceSpec {
    #[serde(default)]
    pub axis: Option<u16>,
    #[serde(default)]
    pub input: Option<AxisInput>,
    #[serde(default)]
    pub di: Option<u16>,
    #[serde(default)]
    pub value: Option<bool>,
}

/// `expect = { … }`: every condition given must hold.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ExpectSpec {
    #[serde(default)]
    pub axis: Option<u16>,
    #[serde(default)]
    pub state: Option<axes::AxisState>,
    /// Actual position (`act_pos`).
    #[serde(default)]
    pub position: Option<f64>,
    /// Actual velocity (`act_vel`).
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub command_position: Option<f64>,
    #[serde(default)]
    pub command_velocity: Option<f64>,
    #[serde(default)]
    pub following_error: Option<f64>,
    /// Edges latched by the axis's capture channels (`capture_arm`).
    #[serde(default)]
    pub captures: Option<f64>,
    /// The actual position of the axis's newest latch.
    #[serde(default)]
    pub capture_position: Option<f64>,
    /// Outputs fired by the compare channels on the axis (`compare_start`).
    #[serde(default)]
    pub compare_outputs: Option<f64>,
    /// The position sent to the drive (`output_pos`: planned + compensation).
    #[serde(default)]
    pub output_position: Option<f64>,
    /// The correction of compensation after the planner.
    #[serde(default)]
    pub compensation: Option<f64>,
    /// A gantry axis's deviation from its master (`gantry_deviation`, issue 12 item 6).
    #[serde(default)]
    pub gantry_deviation: Option<f64>,
    /// Seconds the last finished move's command changed (`move_time`; HIMC GetMoveTime).
    #[serde(default)]
    pub move_time: Option<f64>,
    /// Seconds from the end of that move until in position (HIMC GetSettlingTime).
    #[serde(default)]
    pub settling_time: Option<f64>,
    /// The user frame's origin offset: commanded − motor position (HIMC GetPosOffset).
    #[serde(default)]
    pub position_offset: Option<f64>,
    /// Whole turns of a rollover axis past its range's start (HIMC GetRolloverTurns).
    #[serde(default)]
    pub rollover_turns: Option<f64>,
    /// The drive's torque as a fraction of rated torque (HIMC MoveTrq, GetCurrFb).
    #[serde(default)]
    pub torque: Option<f64>,
    /// The level of the axis's Z-phase output, 0 or 1 (`z_compare_start`, HMC SwitchTZ).
    #[serde(default)]
    pub z_output: Option<f64>,
    /// The HMC position-compensation offset (`compensation_offset_trigger`).
    #[serde(default)]
    pub compensation_offset: Option<f64>,
    /// The HMC add axis (`add_axis_set`): its index, or 255 for none (HMC_GetAddAxis).
    #[serde(default)]
    pub add_axis: Option<f64>,
    /// Allowed |seen − expected| of the numbers above; 0 (exact) when absent.
    #[serde(default)]
    pub tolerance: Option<f64>,
    #[serde(default)]
    pub flags: Vec<String>,
    #[serde(default)]
    pub not_flags: Vec<String>,
    /// Name of the axis's last error; `""` = none.
    #[serde(default)]
    pub error: Option<String>,
    /// The phase of the gear or cam whose slave the axis is: `waiting`, `engaging`, `in_sync`,
    /// or `none` when it is no slave (issue 12).
    #[serde(default)]
    pub coupling: Option<String>,
    /// The kind of that coupling: `gear`, `cam`, `superimpose`, `tangential`, or `none`.
    #[serde(default)]
    pub coupling_kind: Option<String>,
    /// A tangential axis: the tangent angle it tracks, axis units (within `tolerance`).
    #[serde(default)]
    pub tangent_angle: Option<f64>,
    /// With `command_state`: the step whose command is meant.
    #[serde(default)]
    pub step: Option<usize>,
    #[serde(default)]
    pub command_state: Option<String>,
    #[serde(default)]
    pub di: Option<u16>,
    #[serde(default, rename = "do")]
    pub do_: Option<u16>,
    /// With `di` or `do`: the level.
    #[serde(default)]
    pub value: Option<bool>,
    /// The axis's PT/PVT buffer: points it can take now (NMC `MtPtGetSpace` space).
    #[serde(default)]
    pub stream_space: Option<u16>,
    /// Points it holds (NMC `MtPtGetSpace` used).
    #[serde(default)]
    pub stream_used: Option<u16>,
    /// Its stream runs.
    #[serde(default)]
    pub stream_running: Option<bool>,
    /// Times it ran dry while moving.
    #[serde(default)]
    pub stream_underruns: Option<u32>,
    /// An axis group (coordinated motion): the conditions below are about it.
    #[serde(default)]
    pub group: Option<u16>,
    /// The group's state (`standby`, `moving`, `halted`, `stopping`, `error_stop`, `disabled`).
    #[serde(default)]
    pub group_state: Option<String>,
    /// The group's commanded path position, one coordinate per member (within `tolerance`).
    #[serde(default)]
    pub group_position: Option<Vec<f64>>,
    /// Every member in position and the path at rest with nothing queued.
    #[serde(default)]
    pub in_position: Option<bool>,
    /// The `user_segment` of the motion running or last run.
    #[serde(default)]
    pub user_segment: Option<u32>,
}

impl<'de> Deserialize<'de> for ScenarioFile {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(FileVisitor)
    }
}

struct FileVisitor;

impl<'de> Visitor<'de> for FileVisitor {
    type Value = ScenarioFile;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a scenario: config, end, [[step]] and optionally inline config sections")
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<ScenarioFile, A::Error> {
        let mut split = Split {
            map,
            file: ScenarioFile::default(),
            sections: &[],
        };
        let inline = Config::deserialize(&mut split)?;
        let mut file = split.file;
        file.inline = inline;
        Ok(file)
    }
}

/// Hands `Config`'s deserializer the top-level entries that are config sections and keeps the
/// scenario's own for itself.
struct Split<A> {
    map: A,
    file: ScenarioFile,
    /// `Config`'s field names, as its `Deserialize` reports them.
    sections: &'static [&'static str],
}

impl<'de, A: MapAccess<'de>> Deserializer<'de> for &mut Split<A> {
    type Error = A::Error;

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, A::Error> {
        self.sections = fields;
        visitor.visit_map(self)
    }

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, A::Error> {
        visitor.visit_map(self)
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        option unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier
        ignored_any
    }
}

impl<'de, A: MapAccess<'de>> MapAccess<'de> for &mut Split<A> {
    type Error = A::Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, A::Error> {
        loop {
            let key_seed = KeySeed {
                sections: self.sections,
            };
            let Some(key) = self.map.next_key_seed(key_seed)? else {
                return Ok(None);
            };
            match key.as_str() {
                "config" => {
                    self.file.config_path = Some(self.map.next_value::<ConfigPath>()?.0);
                }
                "end" => self.file.end = Some(self.map.next_value()?),
                "step" => self.file.steps = self.map.next_value()?,
                _ => {
                    self.file.inline_sections.push(key.clone());
                    let key = de::value::StringDeserializer::<A::Error>::new(key);
                    return seed.deserialize(key).map(Some);
                }
            }
        }
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, A::Error> {
        self.map.next_value_seed(seed)
    }
}

/// A top-level key: the scenario's own or a config section. Refused here, inside the parser's
/// key handling, so that the error points at the key's line.
struct KeySeed {
    sections: &'static [&'static str],
}

impl<'de> DeserializeSeed<'de> for KeySeed {
    type Value = String;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<String, D::Error> {
        let key = String::deserialize(d)?;
        if SCENARIO_KEYS.contains(&key.as_str()) || self.sections.contains(&key.as_str()) {
            return Ok(key);
        }
        let list = |keys: &[&str]| {
            keys.iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        Err(de::Error::custom(format!(
            "unknown key `{key}`: a scenario has {}, and for an inline machine the config \
             sections {}",
            list(&SCENARIO_KEYS),
            list(self.sections)
        )))
    }
}

/// `config = "path"`; a table there is the likely mistake of nesting an inline machine.
struct ConfigPath(String);

impl<'de> Deserialize<'de> for ConfigPath {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct PathVisitor;
        impl<'de> Visitor<'de> for PathVisitor {
            type Value = ConfigPath;

            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("the path of a config file")
            }

            fn visit_str<E: de::Error>(self, v: &str) -> Result<ConfigPath, E> {
                Ok(ConfigPath(v.to_string()))
            }

            fn visit_map<A: MapAccess<'de>>(self, _: A) -> Result<ConfigPath, A::Error> {
                Err(de::Error::custom(
                    "`config` is the path of a config file; an inline machine's sections go at \
                     the top level ([machine], [[axes]] …), not under [config]",
                ))
            }
        }
        d.deserialize_any(PathVisitor)
    }
}
