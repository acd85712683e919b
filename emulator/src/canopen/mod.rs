//! The CANopen front-end of a machine: the CiA 402 drives and map-backed axes named in
//! `[frontends.canopen]` as nodes on one CAN bus, reached through SocketCAN and/or socketcand.
//! This module resolves and checks the config (EDS files, node ids, drives, maps) for
//! `mcemu validate` and `mcemu run` alike; [`serve`] runs it.

pub mod buslog;
pub mod config;
pub mod mapped;
mod mapped_node;
pub mod serve;
mod wire;

use axes::cia402::DriveMaster;
use axes::od::ObjectDictionary;
use mcemu_canopen::cia402::DriveNodeSpec;
use mcemu_canopen::eds::Eds;
use mcemu_canopen::NodeConfig;
use mcemu_frontend::{Artefacts, AxisRef, Located};
use mcemu_modbus::map::{Binding, UnitMap};

use crate::config::{Config, ConfigError};
use config::CanopenNodeConfig;
use mapped::Backed;

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

/// A node whose manufacturer objects are a register map's holding registers (`axis` + `map`).
pub struct MappedNodeSpec {
    pub config: NodeConfig,
    /// The axis (index) the map is compiled for.
    pub axis: usize,
    /// The EDS's dictionary for the node id.
    pub od: ObjectDictionary,
    /// Its objects in 0x2000–0x23FF and their registers.
    pub backed: Vec<Backed>,
    /// Backed objects a DCF configures (`ParameterValue`): their power-on value is the file's,
    /// not the map's.
    pub configured: Vec<u16>,
    pub map: UnitMap,
    /// The stored parameter image from an earlier run, if any.
    pub stored_image: Option<Vec<u8>>,
}

/// The nodes of `[frontends.canopen]`: CiA 402 drives (served inside the servo tick) and
/// map-backed axes (served by a task of their own).
#[derive(Default)]
pub struct NodeSpecs {
    pub drives: Vec<DriveNodeSpec>,
    pub mapped: Vec<MappedNodeSpec>,
}

/// The nodes of `[frontends.canopen]`, ready for the binding (none when the section is absent).
pub fn node_specs(config: &Config, file: &str) -> Result<NodeSpecs, ConfigError> {
    let Some(c) = config.frontends.canopen.as_ref() else {
        return Ok(NodeSpecs::default());
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
    let mut specs = NodeSpecs::default();
    let mut ids: Vec<u8> = Vec::new();
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
        if ids.contains(&n.node_id) {
            return Err(error(
                key("node_id"),
                format!("node {} is listed twice", n.node_id),
            ));
        }
        ids.push(n.node_id);
        match (n.drive, &n.axis, &n.map) {
            (Some(drive), None, None) => {
                specs
                    .drives
                    .push(drive_spec(config, file, i, n, drive, &specs.drives)?)
            }
            (None, Some(axis), Some(map)) => {
                let spec = mapped_spec(config, file, i, n, axis, map)?;
                if specs.mapped.iter().any(|m| m.axis == spec.axis) {
                    return Err(error(
                        key("axis"),
                        format!("axis {} is already a node", spec.axis),
                    ));
                }
                specs.mapped.push(spec);
            }
            (Some(_), _, _) => {
                return Err(error(
                    key("drive"),
                    "a node is either a CiA 402 drive (`drive`) or a map-backed axis (`axis` + \
                     `map`), not both"
                        .into(),
                ))
            }
            (None, Some(_), None) => {
                return Err(error(
                    key("map"),
                    "a map-backed node needs the register map that gives its objects' meaning \
                     (`map = \"ct-e10-servo\"` …)"
                        .into(),
                ))
            }
            (None, None, Some(_)) => {
                return Err(error(
                    key("axis"),
                    "a map-backed node needs the axis its map is compiled for".into(),
                ))
            }
            (None, None, None) => {
                return Err(error(
                    key("drive"),
                    "missing: give `drive` (a CiA 402 drive in [[drives]]) or `axis` + `map` (a \
                     map-backed node)"
                        .into(),
                ))
            }
        }
    }
    Ok(specs)
}

fn drive_spec(
    config: &Config,
    file: &str,
    i: usize,
    n: &CanopenNodeConfig,
    slave: usize,
    done: &[DriveNodeSpec],
) -> Result<DriveNodeSpec, ConfigError> {
    let key = |k: &str| format!("frontends.canopen.nodes[{i}].{k}");
    let error = |key: String, reason: String| ConfigError {
        file: file.to_string(),
        key,
        reason,
    };
    if done.iter().any(|s| s.slave == slave) {
        return Err(error(
            key("drive"),
            format!("drive {slave} is already a node"),
        ));
    }
    let drive = config.drives.get(slave).ok_or_else(|| {
        error(
            key("drive"),
            format!(
                "drive {slave} does not exist (the machine has {} [[drives]])",
                config.drives.len()
            ),
        )
    })?;
    if drive.master != DriveMaster::External {
        return Err(error(
            key("drive"),
            format!(
                "drive {slave} is mastered by the engine (master = \"engine\"); a CANopen master \
                 needs master = \"external\""
            ),
        ));
    }
    let eds_name = n.eds.as_deref().unwrap_or(DEFAULT_DRIVE_EDS);
    let eds = load_eds(eds_name, file).map_err(|reason| error(key("eds"), reason))?;
    // An unconfigured node's $NODEID values are resolved as node 1; the node moves its COB-IDs
    // to the id LSS gives it (reset communication).
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
    Ok(DriveNodeSpec {
        slave,
        config: node,
        objects,
        stored_image: None,
    })
}

fn mapped_spec(
    config: &Config,
    file: &str,
    i: usize,
    n: &CanopenNodeConfig,
    axis: &AxisRef,
    map: &str,
) -> Result<MappedNodeSpec, ConfigError> {
    let key = |k: &str| format!("frontends.canopen.nodes[{i}].{k}");
    let error = |key: String, reason: String| ConfigError {
        file: file.to_string(),
        key,
        reason,
    };
    let axis = axis
        .resolve(&config.axis_names())
        .map_err(|e| error(key("axis"), e.to_string()))?;
    let unit_map = crate::modbus::compile_map(
        config,
        file,
        map,
        &Binding { axes: vec![axis] },
        &key("map"),
    )?;
    let eds_name = n.eds.as_deref().ok_or_else(|| {
        error(
            key("eds"),
            "a map-backed node needs the EDS of its objects (`eds = \"ct-e10\"` …)".into(),
        )
    })?;
    let eds = load_eds(eds_name, file).map_err(|reason| error(key("eds"), reason))?;
    let od = eds.dictionary(n.node_id).map_err(|e| ConfigError {
        file: e.file.to_string(),
        key: String::new(),
        reason: format!("{e} (used by {file}: {})", key("eds")),
    })?;
    let backed = mapped::backed_objects(&od, &unit_map).map_err(|reason| {
        error(
            key("eds"),
            format!("{reason} ({eds_name} served over map {map})"),
        )
    })?;
    let configured = backed
        .iter()
        .filter(|b| {
            eds.sub_object(b.index, 0)
                .is_some_and(|o| o.parameter_value.is_some())
        })
        .map(|b| b.index)
        .collect();
    let mut node = NodeConfig {
        node_id: n.node_id,
        device_name: config
            .axes
            .get(axis)
            .and_then(|a| a.name.clone())
            .unwrap_or_else(|| format!("axis {axis}")),
        ..NodeConfig::default()
    };
    if let Some(ms) = n.heartbeat_ms {
        node.heartbeat_ms = ms;
    }
    Ok(MappedNodeSpec {
        config: node,
        axis,
        od,
        backed,
        configured,
        map: unit_map,
        stored_image: None,
    })
}

const DEFAULT_DRIVE_EDS: &str = "cia402-drive";

/// The EDS files a config can name: shipped in the binary, or `.eds`/`.dcf` files.
pub const EDS_FILES: Artefacts = Artefacts {
    kind: "EDS",
    file_noun: "a file",
    file_endings: &[".eds", ".dcf"],
    shipped: &SHIPPED_EDS,
};

/// A shipped EDS by name, or a file relative to the config file's directory (read by
/// [`Eds::load`]: its size limit, its Latin-1 fallback, its errors).
fn load_eds(name: &str, config_file: &str) -> Result<Eds, String> {
    match EDS_FILES
        .locate(name, config_file)
        .map_err(|e| e.to_string())?
    {
        Located::Shipped { name, text } => {
            Eds::parse(&format!("{name}.eds (shipped)"), text).map_err(|e| e.to_string())
        }
        Located::File(path) => Eds::load(path).map_err(|e| e.to_string()),
    }
}

/// The file in the machine's state directory that holds node `node_id`'s stored parameters
/// (0x1010).
fn image_file(node_id: u8) -> String {
    format!("canopen/node-{node_id}.img")
}

/// Why the CAN bus could not start (besides its config and its transports' own errors).
#[derive(Debug, thiserror::Error)]
pub enum CanopenStartError {
    #[error("cannot start the parameter image writer: {0}")]
    StoreThread(#[source] std::io::Error),
    #[error("cannot install the nodes in the servo loop: {0}")]
    Fieldbus(#[from] axes::runtime::CallError),
    #[error("node {node_id}: {source}")]
    Node {
        node_id: u8,
        source: mcemu_canopen::NodeError,
    },
}
