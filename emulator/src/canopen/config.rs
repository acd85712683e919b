//! `[frontends.canopen]` and `[frontends.socketcand]`: the CAN bus of a machine, the CiA 402
//! drives that are nodes on it, and the transports that reach it.

use std::net::SocketAddr;

use mcemu_frontend::bound::AtLimit;
use mcemu_frontend::AxisRef;
use serde::{Deserialize, Serialize};

/// `[frontends.canopen]`: the machine's CAN bus with its CiA 402 drives as CANopen nodes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct CanopenConfig {
    /// Serve the bus.
    pub enabled: bool,
    /// SocketCAN interface bridged to the bus (`vcan0`, `can0`); empty: none (the bus is then
    /// reached through `[frontends.socketcand]` only). Also the bus name socketcand clients open.
    pub interface: String,
    /// When the interface cannot be opened (a kernel without CAN, no such interface), go on
    /// without it if socketcand serves the bus, rather than refuse to start.
    pub interface_optional: bool,
    /// Bit rate of the bus timing model (bit/s: frames take their bit time, arbitration by
    /// identifier, bus load); 0: frames take no time. Needs a realtime or scaled clock.
    pub bitrate: u32,
    /// A `candump -L` log of every frame on the bus, relative to the config file; empty: none.
    /// Created or truncated at start; `POST /api/v1/canopen/log/stop` ends it, `/start` begins
    /// another at run time.
    pub log: String,
    /// The nodes: CiA 402 drives and map-backed axes served on the bus.
    pub nodes: Vec<CanopenNodeConfig>,
}

impl Default for CanopenConfig {
    fn default() -> Self {
        CanopenConfig {
            enabled: true,
            interface: "vcan0".into(),
            interface_optional: true,
            bitrate: 0,
            log: String::new(),
            nodes: Vec::new(),
        }
    }
}

/// `[[frontends.canopen.nodes]]`: one CANopen node on the bus — a CiA 402 drive (`drive`), or an
/// axis whose parameters a Modbus register map defines (`axis` + `map`, e.g. the CT E10 servo:
/// object 0x2000 + n is holding register n of the map).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CanopenNodeConfig {
    /// Node id, 1 … 127; 255: an unconfigured LSS slave that a master commissions over LSS
    /// (CiA 305: switch state, configure node id, inquire identity).
    pub node_id: u8,
    /// The CiA 402 drive: its position in `[[drives]]` (the slave number). Its `master` must be
    /// `external`. Give either `drive` or `axis` + `map`.
    #[serde(default)]
    pub drive: Option<usize>,
    /// A map-backed node's axis: its index or `name`. Its objects 0x2000–0x23FF are holding
    /// registers 0x0000–0x03FF of `map` for this axis.
    #[serde(default)]
    pub axis: Option<AxisRef>,
    /// A map-backed node's register map: a shipped one by name (`ct-e10-servo` …) or a `.toml`
    /// path relative to the config file. Needs `axis`.
    #[serde(default)]
    pub map: Option<String>,
    /// The EDS whose objects the node serves (for a drive: those its dictionary lacks — PDO
    /// defaults, store/restore …): a shipped one by name (`cia402-drive`, `ct-e10`) or a
    /// `.eds`/`.dcf` path relative to the config file. Absent: `cia402-drive` for a drive; a
    /// map-backed node must name one.
    #[serde(default)]
    pub eds: Option<String>,
    /// Heartbeat producer time at power-on (0x1017, ms); absent: the EDS's default.
    #[serde(default)]
    pub heartbeat_ms: Option<u16>,
}

/// `[frontends.socketcand]`: the CAN bus over the socketcand protocol (python-can's
/// `socketcand` interface), for hosts without SocketCAN.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SocketcandFrontendConfig {
    /// Serve it (needs `[frontends.canopen]`, whose bus it serves under the interface's name).
    pub enabled: bool,
    /// Address to listen on (socketcand's port is 29536).
    pub bind: SocketAddr,
    /// Open connections at most.
    pub max_connections: usize,
    /// What a new client meets while `max_connections` are open.
    pub at_limit: AtLimit,
}

impl Default for SocketcandFrontendConfig {
    fn default() -> Self {
        SocketcandFrontendConfig {
            enabled: true,
            bind: SocketAddr::from(([127, 0, 0, 1], 29536)),
            max_connections: 16,
            at_limit: AtLimit::EvictIdle,
        }
    }
}
