//! Transport settings, one struct per config section: `[frontends.modbus_tcp]`,
//! `[frontends.modbus_rtu]`, `[frontends.modbus_rtu_over_tcp]`. Every key is optional.

use std::net::SocketAddr;
use std::time::Duration;

use mcemu_frontend::bound::{AtLimit, Bound};
use serde::{Deserialize, Serialize};

use crate::faults::FaultSpec;

/// `[frontends.modbus_tcp]`: Modbus TCP server (MBAP framing).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields, default)]
pub struct TcpConfig {
    /// Serve this front-end.
    pub enabled: bool,
    /// Address to listen on (502 is the registered port, but needs privileges).
    pub bind: SocketAddr,
    /// Open connections at most; what happens to one beyond it is `at_limit`'s.
    pub max_connections: usize,
    /// What a new connection meets while `max_connections` are open.
    pub at_limit: AtLimit,
    /// Close a connection that sends nothing for this long (ms; 0 = never).
    pub idle_timeout_ms: u64,
    /// Close a connection whose started frame is not complete this long after its first byte,
    /// or that does not take a reply in this time (ms; 0 = never).
    pub frame_timeout_ms: u64,
    /// Faults in force from the start (see `faults` in the crate docs).
    pub faults: Vec<FaultSpec>,
    /// The register map every unit uses unless it names its own: a shipped map by name
    /// (`generic`, `himc`, `hollysys-mc`, `ct-e10-servo`) or a `.toml` path relative to the
    /// config file.
    pub map: String,
    /// Axes the map's per-axis blocks repeat for, by index or name, in block order; all the
    /// machine's axes when empty.
    pub axes: Vec<AxisRef>,
    /// Units with their own id, map or axes (a multi-drop of drives). Empty: one unit that answers
    /// every unit id.
    pub units: Vec<UnitConfig>,
}

impl Default for TcpConfig {
    fn default() -> Self {
        TcpConfig {
            enabled: true,
            bind: SocketAddr::from(([127, 0, 0, 1], 1502)),
            max_connections: 16,
            at_limit: AtLimit::EvictIdle,
            idle_timeout_ms: 60_000,
            frame_timeout_ms: 5_000,
            faults: Vec::new(),
            map: "generic".into(),
            axes: Vec::new(),
            units: Vec::new(),
        }
    }
}

/// Axis references are the front-end kit's, shared with every front-end that names axes.
pub use mcemu_frontend::AxisRef;

/// `[[frontends.modbus_*.units]]`: one unit (slave address) of a front-end.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct UnitConfig {
    /// Unit identifier (TCP) or slave address (RTU, 1 … 247).
    pub id: u8,
    /// This unit's map; the section's `map` when absent.
    #[serde(default)]
    pub map: Option<String>,
    /// This unit's axes; the section's `axes` when empty.
    #[serde(default)]
    pub axes: Vec<AxisRef>,
}

/// `[frontends.modbus_rtu_over_tcp]`: RTU frames (address, PDU, CRC) over TCP.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields, default)]
pub struct RtuOverTcpConfig {
    /// Serve this front-end.
    pub enabled: bool,
    /// Address to listen on.
    pub bind: SocketAddr,
    /// Open connections at most; what happens to one beyond it is `at_limit`'s.
    pub max_connections: usize,
    /// What a new connection meets while `max_connections` are open.
    pub at_limit: AtLimit,
    /// Close a connection that sends nothing for this long (ms; 0 = never).
    pub idle_timeout_ms: u64,
    /// Close a connection whose started frame is not complete this long after its first byte,
    /// or that does not take a reply in this time (ms; 0 = never).
    pub frame_timeout_ms: u64,
    /// A frame whose length cannot be predicted from its function code ends after this much
    /// silence (ms); it is then checked by its CRC like any other.
    pub silence_ms: u64,
    /// Faults in force from the start.
    pub faults: Vec<FaultSpec>,
    /// The register map every unit uses unless it names its own: a shipped map by name
    /// (`generic`, `himc`, `hollysys-mc`, `ct-e10-servo`) or a `.toml` path relative to the
    /// config file.
    pub map: String,
    /// Axes the map's per-axis blocks repeat for, by index or name, in block order; all the
    /// machine's axes when empty.
    pub axes: Vec<AxisRef>,
    /// Units with their own id, map or axes (a multi-drop of drives). Empty: one unit at
    /// address 1.
    pub units: Vec<UnitConfig>,
}

impl Default for RtuOverTcpConfig {
    fn default() -> Self {
        RtuOverTcpConfig {
            enabled: true,
            bind: SocketAddr::from(([127, 0, 0, 1], 1503)),
            max_connections: 16,
            at_limit: AtLimit::EvictIdle,
            idle_timeout_ms: 60_000,
            frame_timeout_ms: 5_000,
            silence_ms: 20,
            faults: Vec::new(),
            map: "generic".into(),
            axes: Vec::new(),
            units: Vec::new(),
        }
    }
}

/// Serial parity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum Parity {
    None,
    Even,
    Odd,
}

/// `[frontends.modbus_rtu]`: a Modbus RTU slave on a serial line.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields, default)]
pub struct RtuConfig {
    /// Serve this front-end.
    pub enabled: bool,
    /// `"pty"`: create a pseudo-terminal and print its `/dev/pts/N` for the client; otherwise
    /// a tty device to open (`/dev/ttyUSB0`, one end of a `socat` pty pair …).
    pub device: String,
    /// Line speed; it also sets the 3.5-character silence that ends a frame (1.75 ms above
    /// 19 200 baud).
    pub baud: u32,
    /// Modbus over Serial Line §2.5.1 makes even parity the default.
    pub parity: Parity,
    /// 1 or 2 (the specification asks for 2 without parity). Data bits are always 8.
    pub stop_bits: u8,
    /// Faults in force from the start.
    pub faults: Vec<FaultSpec>,
    /// The register map every unit uses unless it names its own: a shipped map by name
    /// (`generic`, `himc`, `hollysys-mc`, `ct-e10-servo`) or a `.toml` path relative to the
    /// config file.
    pub map: String,
    /// Axes the map's per-axis blocks repeat for, by index or name, in block order; all the
    /// machine's axes when empty.
    pub axes: Vec<AxisRef>,
    /// Units with their own id, map or axes (a multi-drop of drives). Empty: one unit at
    /// address 1.
    pub units: Vec<UnitConfig>,
}

impl Default for RtuConfig {
    fn default() -> Self {
        RtuConfig {
            enabled: true,
            device: "pty".into(),
            baud: 19_200,
            parity: Parity::Even,
            stop_bits: 1,
            faults: Vec::new(),
            map: "generic".into(),
            axes: Vec::new(),
            units: Vec::new(),
        }
    }
}

/// Connection rules shared by the TCP transports.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ConnectionLimits {
    pub bound: Bound,
    pub idle_timeout: Option<Duration>,
    pub frame_timeout: Option<Duration>,
}

fn millis(ms: u64) -> Option<Duration> {
    (ms > 0).then(|| Duration::from_millis(ms))
}

impl TcpConfig {
    pub(crate) fn limits(&self) -> ConnectionLimits {
        ConnectionLimits {
            bound: Bound {
                max_connections: self.max_connections.max(1),
                at_limit: self.at_limit,
            },
            idle_timeout: millis(self.idle_timeout_ms),
            frame_timeout: millis(self.frame_timeout_ms),
        }
    }
}

impl RtuOverTcpConfig {
    pub(crate) fn limits(&self) -> ConnectionLimits {
        ConnectionLimits {
            bound: Bound {
                max_connections: self.max_connections.max(1),
                at_limit: self.at_limit,
            },
            idle_timeout: millis(self.idle_timeout_ms),
            frame_timeout: millis(self.frame_timeout_ms),
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod unit_keys {
    use super::*;

    #[test]
    fn sections_name_maps_axes_and_units() {
        let c: RtuConfig = toml::from_str(
            r#"
device = "/dev/ttyUSB0"
map = "ct-e10-servo"
axes = ["e10_rtu"]
[[units]]
id = 2
[[units]]
id = 3
map = "fixtures/modbus/my-drive.toml"
axes = [5]
"#,
        )
        .unwrap();
        assert_eq!(c.map, "ct-e10-servo");
        assert_eq!(c.axes, [AxisRef::Name("e10_rtu".into())]);
        assert_eq!(c.units[0].map, None);
        assert_eq!(c.units[1].axes, [AxisRef::Index(5)]);
        let t = TcpConfig::default();
        assert_eq!((t.map.as_str(), t.units.len()), ("generic", 0));
        assert!(toml::from_str::<TcpConfig>("[[units]]\nid = 1\nmapp = \"x\"\n").is_err());
    }
}
