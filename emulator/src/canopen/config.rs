//! `[frontends.canopen]` and `[frontends.socketcand]`: the CAN bus of a machine, the CiA 402
//! drives that are nodes on it, and the transports that reach it.

use std::net::SocketAddr;

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
    pub log: String,
    /// The nodes: one per CiA 402 drive served on the bus.
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

/// `[[frontends.canopen.nodes]]`: one CiA 402 drive as a CANopen node.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CanopenNodeConfig {
    /// Node id, 1 … 127; 255: an unconfigured LSS slave that a master commissions over LSS
    /// (CiA 305: switch state, configure node id, inquire identity).
    pub node_id: u8,
    /// The drive: its position in `[[drives]]` (the slave number). Its `master` must be
    /// `external`.
    pub drive: usize,
    /// The EDS whose objects the node adds to the drive's dictionary (PDO defaults,
    /// store/restore …): a shipped one by name (`cia402-drive`, `ct-e10`) or a `.eds`/`.dcf`
    /// path relative to the config file.
    #[serde(default = "default_eds")]
    pub eds: String,
    /// Heartbeat producer time at power-on (0x1017, ms); absent: the EDS's default.
    #[serde(default)]
    pub heartbeat_ms: Option<u16>,
}

fn default_eds() -> String {
    "cia402-drive".into()
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
}

impl Default for SocketcandFrontendConfig {
    fn default() -> Self {
        SocketcandFrontendConfig {
            enabled: true,
            bind: SocketAddr::from(([127, 0, 0, 1], 29536)),
            max_connections: 16,
        }
    }
}
