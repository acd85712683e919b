//! The mcemu config file (ARCHITECTURE §6): TOML, every key known, and every error naming the
//! file, the key path and the reason.
//!
//! ```toml
//! [machine]              # name, period (s), clock, seed
//! [[axes]]               # axes::config::AxisConfig: params, pulse, encoder, plant, switches
//! [io]                   # I/O images and bindings
//! [[drives]]             # CiA 402 drives bound to axes
//! [frontends.control]    # one section per front-end: enabled, bind, its own settings
//! ```

use std::fmt;
use std::net::SocketAddr;
use std::path::Path;
use std::str::FromStr;

use axes::cia402::DriveConfig;
use axes::config::{AxisConfig, EngineConfig, GroupsConfig, IoConfig, MAX_PERIOD, MIN_PERIOD};
use axes::runtime::ClockMode;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The embedded default machine (`mcemu run` without `--config`).
pub const DEFAULT_CONFIG: &str = include_str!("../../fixtures/default.toml");
pub const DEFAULT_CONFIG_NAME: &str = "fixtures/default.toml (embedded)";

/// The machines of `fixtures/`, embedded so that `mcemu run --machine NAME` needs no checkout
/// (an installed binary, the Python package): (name, config text).
pub const SHIPPED_MACHINES: &[(&str, &str)] = &[
    ("default", DEFAULT_CONFIG),
    ("cia402-can", include_str!("../../fixtures/cia402-can.toml")),
    ("cpu226h", include_str!("../../fixtures/cpu226h.toml")),
    (
        "gaochuan-gcn",
        include_str!("../../fixtures/gaochuan-gcn.toml"),
    ),
    (
        "gaochuan-gcn-ecat",
        include_str!("../../fixtures/gaochuan-gcn-ecat.toml"),
    ),
    ("himc", include_str!("../../fixtures/himc.toml")),
    (
        "hollysys-mc",
        include_str!("../../fixtures/hollysys-mc.toml"),
    ),
];

/// A shipped machine's config text and the name errors give it
/// (`fixtures/himc.toml (embedded)`), or an error listing the shipped names.
pub fn shipped_machine(name: &str) -> Result<(&'static str, String), ConfigError> {
    SHIPPED_MACHINES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(n, text)| (*text, format!("fixtures/{n}.toml (embedded)")))
        .ok_or_else(|| ConfigError {
            file: "the command line".into(),
            key: "--machine".into(),
            reason: format!(
                "`{name}` is not a shipped machine ({})",
                SHIPPED_MACHINES
                    .iter()
                    .map(|(n, _)| *n)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        })
}

/// A machine config file. Every section is optional; unknown keys are errors.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Config {
    /// The machine as a whole.
    #[serde(default)]
    pub machine: MachineConfig,
    /// The axes, numbered from 0 in file order.
    #[serde(default)]
    pub axes: Vec<AxisConfig>,
    /// Machine I/O images.
    #[serde(default)]
    pub io: IoConfig,
    /// CiA 402 drives, each bound to an axis; slave numbers are positions in this list.
    #[serde(default)]
    pub drives: Vec<DriveConfig>,
    /// Axis groups (coordinated motion): how many may exist and the defaults of `group_create`.
    #[serde(default)]
    pub groups: GroupsConfig,
    /// Cam tables defined at start (`[[cam_tables]]`), as the `cam_table` command defines
    /// them: `table` number, `points` (`{ master, slave }`, at least 2, master strictly
    /// increasing) and `interpolation` (`linear`, `cubic` or `follow`).
    #[serde(default)]
    pub cam_tables: Vec<axes::command::CamTableDefine>,
    /// The front-ends, one section each.
    #[serde(default)]
    pub frontends: FrontendsConfig,
}

/// The machine as a whole.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MachineConfig {
    /// Shown in `mcemu run` and the control API.
    pub name: String,
    /// Servo period, seconds (62.5 µs … 10 ms).
    pub period: f64,
    /// `realtime`, `virtual` (advances only when asked) or `scaled:K` (K × real time).
    pub clock: ClockSetting,
    /// Seed of every random process (encoder noise, injected faults).
    pub seed: u64,
    /// Directory for state that outlives a run (Modbus memory areas marked `persist`),
    /// relative to the config file. Absent: `$XDG_STATE_HOME/mcemu/<name>` (else
    /// `~/.local/state/mcemu/<name>`); `mcemu run --state-dir` overrides both.
    pub state_dir: Option<String>,
}

impl Default for MachineConfig {
    fn default() -> Self {
        MachineConfig {
            name: "mcemu".into(),
            period: 1e-3,
            clock: ClockSetting(ClockMode::Realtime),
            seed: 0,
            state_dir: None,
        }
    }
}

/// A clock as written in a config or on the command line: `realtime`, `virtual`, `scaled:K`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClockSetting(pub ClockMode);

impl FromStr for ClockSetting {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "realtime" => Ok(ClockSetting(ClockMode::Realtime)),
            "virtual" => Ok(ClockSetting(ClockMode::Virtual)),
            _ => {
                let k = s
                    .strip_prefix("scaled:")
                    .and_then(|k| k.parse::<f64>().ok())
                    .ok_or_else(|| {
                        format!("`{s}` is not a clock: use realtime, virtual or scaled:K")
                    })?;
                let (lo, hi) = (axes::runtime::MIN_SCALE, axes::runtime::MAX_SCALE);
                if k.is_finite() && (lo..=hi).contains(&k) {
                    Ok(ClockSetting(ClockMode::Scaled(k)))
                } else {
                    Err(format!("scale {k} is outside {lo} … {hi}"))
                }
            }
        }
    }
}

impl fmt::Display for ClockSetting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            ClockMode::Realtime => f.write_str("realtime"),
            ClockMode::Virtual => f.write_str("virtual"),
            ClockMode::Scaled(k) => write!(f, "scaled:{k}"),
        }
    }
}

impl Serialize for ClockSetting {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for ClockSetting {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

impl schemars::JsonSchema for ClockSetting {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "ClockSetting".into()
    }

    fn inline_schema() -> bool {
        true
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "type": "string",
            "pattern": "^(realtime|virtual|scaled:[0-9.eE+-]+)$"
        })
    }
}

/// The front-ends, one section each.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct FrontendsConfig {
    /// The HTTP control API and dashboard.
    pub control: ControlConfig,
    /// Modbus TCP server (register maps of the controller's variables or of a drive).
    pub modbus_tcp: Option<mcemu_modbus::config::TcpConfig>,
    /// Modbus RTU slave on a pty mcemu creates or a serial device (e.g. one end of a `socat`
    /// pty pair).
    pub modbus_rtu: Option<mcemu_modbus::config::RtuConfig>,
    /// Modbus RTU frames over TCP.
    pub modbus_rtu_over_tcp: Option<mcemu_modbus::config::RtuOverTcpConfig>,
    /// CANopen slaves on a SocketCAN interface (e.g. `vcan0`).
    pub canopen: Option<crate::canopen::config::CanopenConfig>,
    /// CANopen over the socketcand TCP protocol, for hosts without SocketCAN.
    pub socketcand: Option<crate::canopen::config::SocketcandFrontendConfig>,
    /// NMC protocol over TCP (network controllers, `NMC_DevOpenByIP`): what mcemu's
    /// `nmc_lib20` library reaches.
    pub nmc: Option<crate::nmc::config::NmcConfig>,
    /// NMC protocol on a Unix socket (PCIe/GCE cards, `NMC_DevOpen` by index).
    pub nmc_local: Option<crate::nmc::config::NmcLocalConfig>,
    /// HIMC Native ASCII server (HMPL calls as text; the controller's port is 3999).
    pub ascii_native: Option<mcemu_ascii::config::NativeConfig>,
    /// HIMC User ASCII server (declarative command patterns; the controller's port is 4000).
    pub ascii_user: Option<mcemu_ascii::user::config::UserConfig>,
}

/// The HTTP control API (ARCHITECTURE §6).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ControlConfig {
    /// Serve the control API.
    pub enabled: bool,
    /// Address to listen on; 127.0.0.1 unless you mean to expose the back door.
    pub bind: SocketAddr,
    /// Open connections at most; further clients wait in the kernel's backlog. Keep it above
    /// `max_requests`, so a client can still connect to hear the 503.
    pub max_connections: usize,
    /// Requests handled at once; beyond it the API answers 503.
    pub max_requests: usize,
    /// Rows a trace recording may hold (rows = ticks × recorded axes); at the cap the
    /// recording stops at a whole tick.
    pub trace_max_rows: usize,
    /// Dashboard streams (`GET /api/v1/stream`) open at once; a further one is answered 503.
    pub stream_max_clients: usize,
    /// The token every API request must carry (`Authorization: Bearer …`). Absent: none on
    /// 127.0.0.1 or ::1, and one generated and printed at start on any other address.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub token: Option<String>,
}

impl Default for ControlConfig {
    fn default() -> Self {
        ControlConfig {
            enabled: true,
            bind: SocketAddr::from(([127, 0, 0, 1], 8700)),
            max_connections: 128,
            max_requests: 64,
            trace_max_rows: 1_000_000,
            stream_max_clients: 4,
            token: None,
        }
    }
}

/// A config that cannot run: which file, which key, why.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub struct ConfigError {
    pub file: String,
    /// Key path, e.g. `axes[1].params.accel`; empty for the file as a whole.
    pub key: String,
    pub reason: String,
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.key.is_empty() {
            write!(f, "{}: {}", self.file, self.reason)
        } else {
            write!(f, "{}: {}: {}", self.file, self.key, self.reason)
        }
    }
}

impl Config {
    /// Read and check a config file.
    pub fn load(path: &Path) -> Result<Config, ConfigError> {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| ConfigError {
            file: file.clone(),
            key: String::new(),
            reason: format!("cannot read it: {e}"),
        })?;
        Config::parse(&text, &file)
    }

    /// Parse config text, apply `overrides` (`key.path=value`, as `mcemu run --set` takes them:
    /// the value is TOML, or a bare string), then check it. `file` names it in errors.
    pub fn parse_with(text: &str, file: &str, overrides: &[String]) -> Result<Config, ConfigError> {
        Config::parse_for_run(text, file, false, overrides)
    }

    /// [`Config::parse_with`], and first, with `any_port`, every front-end's TCP `bind` moved to
    /// port 0 on its host (`mcemu run --any-port`): each listener gets a free port and its
    /// `listening:` line says which. Test harnesses start machines side by side this way without
    /// knowing which front-ends a config has. `--set` still overrides a `bind` afterwards.
    pub fn parse_for_run(
        text: &str,
        file: &str,
        any_port: bool,
        overrides: &[String],
    ) -> Result<Config, ConfigError> {
        if overrides.is_empty() && !any_port {
            return Config::parse(text, file);
        }
        let error = |key: &str, reason: String| ConfigError {
            file: file.to_string(),
            key: key.to_string(),
            reason,
        };
        let mut table: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| error("", e.to_string().trim_end().to_string()))?;
        if any_port {
            bind_any_port(&mut table);
        }
        for o in overrides {
            let (key, value) = o.split_once('=').ok_or_else(|| {
                error(
                    o,
                    "--set takes key.path=value (e.g. frontends.control.bind=127.0.0.1:0)".into(),
                )
            })?;
            let key = key.trim();
            let value = value.trim();
            // A TOML value if it is one (numbers, booleans, quoted strings, arrays), else a string.
            let value = format!("v = {value}")
                .parse::<toml::Table>()
                .ok()
                .and_then(|mut t| t.remove("v"))
                .unwrap_or_else(|| toml::Value::String(value.to_string()));
            let mut at = &mut table;
            let parts: Vec<&str> = key.split('.').collect();
            let (last, path) = parts
                .split_last()
                .filter(|(l, _)| !l.is_empty())
                .ok_or_else(|| error(key, "--set needs a key".into()))?;
            for (depth, part) in path.iter().enumerate() {
                let entry = at
                    .entry(part.to_string())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()));
                at = entry.as_table_mut().ok_or_else(|| {
                    error(
                        &parts[..=depth].join("."),
                        "is not a table, so --set cannot reach into it".into(),
                    )
                })?;
            }
            at.insert(last.to_string(), value);
        }
        let text = toml::to_string(&table).map_err(|e| error("", e.to_string()))?;
        let with = match (any_port, overrides.is_empty()) {
            (true, true) => "--any-port",
            (true, false) => "--any-port and --set",
            (false, _) => "--set",
        };
        Config::parse(&text, &format!("{file} with {with}"))
    }

    /// Parse and check config text; `file` names it in errors.
    pub fn parse(text: &str, file: &str) -> Result<Config, ConfigError> {
        let error = |key: String, reason: String| ConfigError {
            file: file.to_string(),
            key,
            reason,
        };
        let deserializer = toml::Deserializer::parse(text)
            .map_err(|e| error(String::new(), e.to_string().trim_end().to_string()))?;
        let config: Config = serde_path_to_error::deserialize(deserializer).map_err(|e| {
            let key = match e.path().to_string() {
                p if p == "." => String::new(),
                p => p,
            };
            error(key, e.inner().to_string().trim_end().to_string())
        })?;
        config.check(file)?;
        Ok(config)
    }

    /// Check a config (after overrides such as `--period`); `file` names it in errors.
    pub fn check(&self, file: &str) -> Result<(), ConfigError> {
        self.validate().map_err(|(key, reason)| ConfigError {
            file: file.to_string(),
            key,
            reason,
        })?;
        crate::modbus::check_faults(self, file)?;
        crate::canopen::node_specs(self, file)?;
        // Register maps compile against this machine, or the config is refused.
        self.modbus_units(file).map(|_| ())
    }

    /// The embedded default machine.
    pub fn default_machine() -> Result<Config, ConfigError> {
        Config::parse(DEFAULT_CONFIG, DEFAULT_CONFIG_NAME)
    }

    /// What the engine needs of the config.
    pub fn engine_config(&self) -> EngineConfig {
        EngineConfig {
            period: self.machine.period,
            seed: self.machine.seed,
            axes: self.axes.clone(),
            io: self.io.clone(),
            drives: self.drives.clone(),
            groups: self.groups.clone(),
            cam_tables: self.cam_tables.clone(),
        }
    }

    /// The axes' names in index order (`None`: unnamed), as axis references see them.
    pub fn axis_names(&self) -> Vec<Option<&str>> {
        self.axes.iter().map(|a| a.name.as_deref()).collect()
    }

    /// The units of every Modbus section present, enabled or not (so a fixture's maps are
    /// checked before anyone enables them): (section, units).
    pub fn modbus_units(
        &self,
        file: &str,
    ) -> Result<Vec<(&'static str, Vec<crate::modbus::Unit>)>, ConfigError> {
        let f = &self.frontends;
        let mut out = Vec::new();
        if let Some(c) = f.modbus_tcp.as_ref() {
            let units =
                crate::modbus::units(self, file, "modbus_tcp", &c.map, &c.axes, &c.units, None)?;
            out.push(("modbus_tcp", units));
        }
        if let Some(c) = f.modbus_rtu.as_ref() {
            let units =
                crate::modbus::units(self, file, "modbus_rtu", &c.map, &c.axes, &c.units, Some(1))?;
            out.push(("modbus_rtu", units));
        }
        if let Some(c) = f.modbus_rtu_over_tcp.as_ref() {
            let units = crate::modbus::units(
                self,
                file,
                "modbus_rtu_over_tcp",
                &c.map,
                &c.axes,
                &c.units,
                Some(1),
            )?;
            out.push(("modbus_rtu_over_tcp", units));
        }
        Ok(out)
    }

    /// Semantic checks; an error is (key path, reason).
    fn validate(&self) -> Result<(), (String, String)> {
        let period = self.machine.period;
        if !(MIN_PERIOD..=MAX_PERIOD).contains(&period) {
            return Err((
                "machine.period".into(),
                format!("{period} s is outside {MIN_PERIOD} … {MAX_PERIOD} s (62.5 µs … 10 ms)"),
            ));
        }
        self.engine_config()
            .validate()
            .map_err(|e| (e.key, e.reason))?;
        let c = &self.frontends.control;
        for (key, value, max) in [
            ("max_connections", c.max_connections, 4096),
            ("max_requests", c.max_requests, 4096),
            ("trace_max_rows", c.trace_max_rows, 100_000_000),
            ("stream_max_clients", c.stream_max_clients, 64),
        ] {
            if !(1..=max).contains(&value) {
                return Err((
                    format!("frontends.control.{key}"),
                    format!("{value} is outside 1 … {max}"),
                ));
            }
        }
        if c.token
            .as_ref()
            .is_some_and(|t| t.is_empty() || !t.bytes().all(|b| b.is_ascii_graphic()))
        {
            return Err((
                "frontends.control.token".into(),
                "must be non-empty printable ASCII without spaces (it travels in a header)".into(),
            ));
        }
        let f = &self.frontends;
        if let Some(c) = &f.nmc {
            crate::nmc::config::check("nmc", c.max_connections, c.idle_timeout, &c.device)?;
        }
        if let Some(c) = &f.nmc_local {
            crate::nmc::config::check("nmc_local", c.max_connections, c.idle_timeout, &c.device)?;
        }
        if let Some(c) = f.ascii_user.as_ref().filter(|c| c.enabled) {
            c.grammar()
                .map_err(|e| (format!("frontends.ascii_user.{}", e.key), e.reason))?;
        }
        Ok(())
    }
}

/// Every `frontends.<name>.bind = "host:port"` becomes `"host:0"`. Values that are not a
/// `host:port` string are left for the config check to report.
fn bind_any_port(table: &mut toml::Table) {
    let Some(frontends) = table.get_mut("frontends").and_then(|f| f.as_table_mut()) else {
        return;
    };
    for (_, section) in frontends.iter_mut() {
        let Some(bind) = section.as_table_mut().and_then(|s| s.get_mut("bind")) else {
            continue;
        };
        if let Some((host, port)) = bind.as_str().and_then(|b| b.rsplit_once(':')) {
            if port.parse::<u16>().is_ok() {
                *bind = toml::Value::String(format!("{host}:0"));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_machine_is_valid_and_an_unknown_name_lists_them() {
        for (name, text) in SHIPPED_MACHINES {
            let file = format!("fixtures/{name}.toml");
            if let Err(e) = Config::parse(text, &file) {
                panic!("{e}");
            }
        }
        let e = shipped_machine("gcn").unwrap_err();
        assert_eq!(e.key, "--machine");
        assert!(
            e.reason.contains("gaochuan-gcn, gaochuan-gcn-ecat, himc"),
            "{}",
            e.reason
        );
        assert_eq!(
            shipped_machine("himc").unwrap().1,
            "fixtures/himc.toml (embedded)"
        );
    }

    #[test]
    fn any_port_moves_every_tcp_bind_to_port_0_and_set_still_wins() {
        let text = "[machine]\nname = \"m\"\n[[axes]]\nname = \"x\"\n\
            [frontends.control]\nbind = \"127.0.0.1:8700\"\n\
            [frontends.modbus_tcp]\nbind = \"127.0.0.2:1502\"\n\
            [frontends.modbus_rtu_over_tcp]\nbind = \"127.0.0.1:1503\"\n";
        let set = ["frontends.modbus_rtu_over_tcp.bind=127.0.0.1:4711".to_string()];
        let config = Config::parse_for_run(text, "m.toml", true, &set).unwrap();
        let f = &config.frontends;
        assert_eq!(f.control.bind.to_string(), "127.0.0.1:0");
        let tcp = f.modbus_tcp.as_ref().map(|m| m.bind.to_string());
        assert_eq!(tcp.as_deref(), Some("127.0.0.2:0"), "the host is kept");
        let rtu = f.modbus_rtu_over_tcp.as_ref().map(|m| m.bind.to_string());
        assert_eq!(rtu.as_deref(), Some("127.0.0.1:4711"), "--set wins");
        let plain = Config::parse_for_run(text, "m.toml", false, &[]).unwrap();
        assert_eq!(plain.frontends.control.bind.to_string(), "127.0.0.1:8700");
    }

    #[test]
    fn the_embedded_default_machine_is_valid() {
        let c = Config::default_machine().unwrap();
        assert_eq!(c.axes.len(), 4);
        assert_eq!(c.machine.period, 1e-3);
        assert!(c.frontends.control.enabled);
    }

    #[test]
    fn errors_name_file_key_and_reason() {
        let e = Config::parse("[machine]\nperiod = 0.5\n", "m.toml").unwrap_err();
        assert_eq!(
            (e.file.as_str(), e.key.as_str()),
            ("m.toml", "machine.period")
        );
        let e = Config::parse("[[axes]]\n[axes.params]\naccel = -3\n", "m.toml").unwrap_err();
        assert_eq!(e.key, "axes[0].params.accel");
        assert!(e.reason.contains("greater than 0"), "{}", e.reason);
        let e = Config::parse("[[axes]]\nfifo_dept = 3\n", "m.toml").unwrap_err();
        assert_eq!(e.key, "axes[0].fifo_dept");
        assert!(e.reason.contains("unknown field"), "{}", e.reason);
        let e = Config::parse("[machine\n", "m.toml").unwrap_err();
        assert_eq!(e.key, "");
        assert!(e.to_string().starts_with("m.toml: TOML parse error"), "{e}");
        let e = Config::parse("[machine]\nclock = \"fast\"\n", "m.toml").unwrap_err();
        assert_eq!(e.key, "machine.clock");
        let e = Config::parse(
            "[[frontends.ascii_user.commands]]\npattern = \"GO %x\"\n",
            "m.toml",
        )
        .unwrap_err();
        assert_eq!(e.key, "frontends.ascii_user.commands[0].pattern");
        assert!(e.reason.contains("%x"), "{}", e.reason);
        let e = Config::parse("[frontends.nmc]\nmax_connections = 0\n", "m.toml").unwrap_err();
        assert_eq!(e.key, "frontends.nmc.max_connections");
        let e = Config::parse("[frontends.control]\nmax_requests = 0\n", "m.toml").unwrap_err();
        assert_eq!(e.key, "frontends.control.max_requests");
        assert!(e.reason.contains("outside 1"), "{}", e.reason);
        let c = Config::parse("[frontends.control]\ntrace_max_rows = 10\n", "m.toml").unwrap();
        assert_eq!(c.frontends.control.trace_max_rows, 10);
    }

    #[test]
    fn modbus_sections_are_checked_map_and_all() {
        let e = Config::parse(
            "[[axes]]\n[frontends.modbus_tcp]\nenabled = false\nmap = \"nope\"\n",
            "m.toml",
        )
        .unwrap_err();
        assert_eq!(e.key, "frontends.modbus_tcp.map");
        assert!(e.reason.contains("not a shipped map"), "{}", e.reason);
        let e = Config::parse(
            "[[axes]]\n[frontends.modbus_rtu]\nenabled = false\nmap = \"ct-e10-servo\"\n[[frontends.modbus_rtu.units]]\nid = 2\naxes = [\"e10\"]\n",
            "m.toml",
        )
        .unwrap_err();
        assert_eq!(e.key, "frontends.modbus_rtu.units[0].axes");
        // A map path is relative to the config file, and a missing one says so.
        let e = Config::parse(
            "[[axes]]\n[frontends.modbus_tcp]\nenabled = false\nmap = \"missing.toml\"\n",
            "/tmp/m.toml",
        )
        .unwrap_err();
        assert!(e.reason.contains("cannot read map"), "{}", e.reason);
    }

    #[test]
    fn canopen_nodes_are_a_drive_or_an_axis_with_a_map() {
        let node = |keys: &str| {
            format!(
                "[[axes]]\nname = \"e10\"\n[frontends.canopen]\nenabled = false\n\
                 [[frontends.canopen.nodes]]\nnode_id = 2\n{keys}"
            )
        };
        let error = |keys: &str| Config::parse(&node(keys), "m.toml").unwrap_err();
        let ok = Config::parse(
            &node("axis = \"e10\"\nmap = \"ct-e10-servo\"\neds = \"ct-e10\"\n"),
            "m.toml",
        );
        assert!(ok.is_ok(), "{ok:?}");
        let cases = [
            ("", "frontends.canopen.nodes[0].drive", "missing"),
            (
                "drive = 0\naxis = \"e10\"\nmap = \"ct-e10-servo\"\n",
                "frontends.canopen.nodes[0].drive",
                "not both",
            ),
            (
                "axis = \"e10\"\neds = \"ct-e10\"\n",
                "frontends.canopen.nodes[0].map",
                "needs the register map",
            ),
            (
                "map = \"ct-e10-servo\"\neds = \"ct-e10\"\n",
                "frontends.canopen.nodes[0].axis",
                "needs the axis",
            ),
            (
                "axis = \"x\"\nmap = \"ct-e10-servo\"\neds = \"ct-e10\"\n",
                "frontends.canopen.nodes[0].axis",
                "no axis is named `x`",
            ),
            (
                "axis = \"e10\"\nmap = \"ct-e10-servo\"\n",
                "frontends.canopen.nodes[0].eds",
                "needs the EDS",
            ),
            (
                "axis = \"e10\"\nmap = \"nope\"\neds = \"ct-e10\"\n",
                "frontends.canopen.nodes[0].map",
                "not a shipped map",
            ),
            // The generic map has no holding register 95 (P95): the EDS cannot be served over it.
            (
                "axis = \"e10\"\nmap = \"generic\"\neds = \"ct-e10\"\n",
                "frontends.canopen.nodes[0].eds",
                "which map `generic` does not have",
            ),
        ];
        for (keys, key, reason) in cases {
            let e = error(keys);
            assert_eq!(
                (e.file.as_str(), e.key.as_str()),
                ("m.toml", key),
                "{keys}: {e}"
            );
            assert!(e.reason.contains(reason), "{keys}: {e}");
        }
    }

    #[test]
    fn clocks_parse_and_print() {
        for s in ["realtime", "virtual", "scaled:2.5"] {
            assert_eq!(s.parse::<ClockSetting>().unwrap().to_string(), s);
        }
        assert!("scaled:0".parse::<ClockSetting>().is_err());
        assert!("scaled:x".parse::<ClockSetting>().is_err());
    }
}
