//! The CANopen front-end of a machine: the CiA 402 drives named in `[frontends.canopen]` as
//! nodes on one CAN bus, reached through SocketCAN and/or socketcand. This module resolves and
//! checks the config (EDS files, node ids, drives) for `mcemu validate` and `mcemu run` alike;
//! [`serve`] runs it.

pub mod config;
pub mod serve;

use std::path::Path;

use axes::cia402::DriveMaster;
use mcemu_canopen::cia402::DriveNodeSpec;
use mcemu_canopen::eds::Eds;
use mcemu_canopen::NodeConfig;

use crate::config::{Config, ConfigError};

/// EDS files embedded in the binary, by name.
pub const SHIPPED_EDS: [(&str, &str); 2] = [
    (
        "cia402-drive",
        include_str!("../../../fixtures/canopen/cia402-drive.eds"),
    ),
    (
        "ct-e10",
        include_str!("../../../fixtures/canopen/ct-e10.eds"),
    ),
];

/// The nodes of `[frontends.canopen]`, ready for the binding (empty when the section is absent).
pub fn node_specs(config: &Config, file: &str) -> Result<Vec<DriveNodeSpec>, ConfigError> {
    let Some(c) = config.frontends.canopen.as_ref() else {
        return Ok(Vec::new());
    };
    let error = |key: String, reason: String| ConfigError {
        file: file.to_string(),
        key,
        reason,
    };
    let f = &config.frontends;
    if f.socketcand.as_ref().is_some_and(|s| s.enabled) && !c.enabled {
        return Err(error(
            "frontends.socketcand.enabled".into(),
            "socketcand serves the bus of [frontends.canopen], which is disabled".into(),
        ));
    }
    if c.bitrate > 0 && config.machine.clock.0 == axes::runtime::ClockMode::Virtual {
        return Err(error(
            "frontends.canopen.bitrate".into(),
            "the bus timing model runs on a realtime or scaled clock; set bitrate = 0 for a \
             virtual one"
                .into(),
        ));
    }
    if c.bitrate > 0 && mcemu_can::BitTiming::new(c.bitrate).is_none() {
        return Err(error(
            "frontends.canopen.bitrate".into(),
            format!("{} bit/s is not a CAN bit rate", c.bitrate),
        ));
    }
    let mut specs: Vec<DriveNodeSpec> = Vec::new();
    for (i, n) in c.nodes.iter().enumerate() {
        let key = |k: &str| format!("frontends.canopen.nodes[{i}].{k}");
        // 255: an unconfigured LSS slave (CiA 305), which a master commissions over LSS.
        if !((1..=127).contains(&n.node_id) || n.node_id == 255) {
            return Err(error(
                key("node_id"),
                format!(
                    "{} is not a node id (1 … 127, or 255 for an unconfigured LSS slave)",
                    n.node_id
                ),
            ));
        }
        if specs.iter().any(|s| s.config.node_id == n.node_id) {
            return Err(error(
                key("node_id"),
                format!("node {} is listed twice", n.node_id),
            ));
        }
        if specs.iter().any(|s| s.slave == n.drive) {
            return Err(error(
                key("drive"),
                format!("drive {} is already a node", n.drive),
            ));
        }
        let drive = config.drives.get(n.drive).ok_or_else(|| {
            error(
                key("drive"),
                format!(
                    "drive {} does not exist (the machine has {} [[drives]])",
                    n.drive,
                    config.drives.len()
                ),
            )
        })?;
        if drive.master != DriveMaster::External {
            return Err(error(
                key("drive"),
                format!(
                    "drive {} is mastered by the engine (master = \"engine\"); a CANopen master \
                     needs master = \"external\"",
                    n.drive
                ),
            ));
        }
        let eds = load_eds(&n.eds, file).map_err(|reason| error(key("eds"), reason))?;
        // An unconfigured node's $NODEID values are resolved as node 1; the node moves its
        // COB-IDs to the id LSS gives it (reset communication).
        let eds_node = if n.node_id == 255 { 1 } else { n.node_id };
        let objects = eds.entry_defs(eds_node).map_err(|e| ConfigError {
            file: e.file.to_string(),
            key: String::new(),
            reason: format!("{e} (used by {file}: {})", key("eds")),
        })?;
        let mut node = NodeConfig {
            node_id: n.node_id,
            device_name: drive.name.clone(),
            ..NodeConfig::default()
        };
        node.identity.vendor_id = drive.vendor_id;
        node.identity.product_code = drive.product_code;
        node.identity.revision = drive.revision;
        node.identity.serial = drive.serial;
        if let Some(ms) = n.heartbeat_ms {
            node.heartbeat_ms = ms;
        }
        specs.push(DriveNodeSpec {
            slave: n.drive,
            config: node,
            objects,
            stored_image: None,
        });
    }
    Ok(specs)
}

/// A shipped EDS by name, or a file relative to the config file's directory.
fn load_eds(name: &str, config_file: &str) -> Result<Eds, String> {
    if !(name.ends_with(".eds") || name.ends_with(".dcf")) {
        let text = SHIPPED_EDS
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, t)| *t)
            .ok_or_else(|| {
                let names: Vec<&str> = SHIPPED_EDS.iter().map(|(n, _)| *n).collect();
                format!(
                    "`{name}` is not a shipped EDS ({}); a file's path ends in .eds or .dcf",
                    names.join(", ")
                )
            })?;
        return Eds::parse(&format!("{name}.eds (shipped)"), text).map_err(|e| e.to_string());
    }
    let base = Path::new(config_file).parent().unwrap_or(Path::new(""));
    Eds::load(base.join(name)).map_err(|e| e.to_string())
}
