//! The Modbus front-ends of a machine: each enabled section's units resolved (map by shipped
//! name or path, axes by index or name) and compiled against the machine, for `mcemu validate`
//! and `mcemu run` alike.

use mcemu_frontend::{axis_ref, Artefacts, AxisRef, Located};
use mcemu_modbus::config::UnitConfig;
use mcemu_modbus::map::{self, Binding, MachineShape, UnitMap};
use mcemu_modbus::state::{Framing, FrontendState};

pub mod serve;

use crate::config::{Config, ConfigError};

/// One unit ready to serve: its id (`None`: every id) and compiled map.
pub struct Unit {
    pub id: Option<u8>,
    pub map: UnitMap,
}

/// Every fault a Modbus section configures can be installed on its framing (corrupted bytes
/// only on RTU, codes that are exceptions …).
pub fn check_faults(config: &Config, file: &str) -> Result<(), ConfigError> {
    let f = &config.frontends;
    let sections = [
        (
            "modbus_tcp",
            Framing::Tcp,
            f.modbus_tcp.as_ref().map(|c| &c.faults),
        ),
        (
            "modbus_rtu",
            Framing::Rtu,
            f.modbus_rtu.as_ref().map(|c| &c.faults),
        ),
        (
            "modbus_rtu_over_tcp",
            Framing::RtuOverTcp,
            f.modbus_rtu_over_tcp.as_ref().map(|c| &c.faults),
        ),
    ];
    for (section, framing, faults) in sections {
        for (i, fault) in faults.into_iter().flatten().enumerate() {
            FrontendState::new(section, framing, std::slice::from_ref(fault)).map_err(|e| {
                ConfigError {
                    file: file.to_string(),
                    key: format!("frontends.{section}.faults[{i}]"),
                    reason: e.message,
                }
            })?;
        }
    }
    Ok(())
}

/// What the machine has, as the maps see it.
pub fn machine_shape(config: &Config) -> MachineShape {
    let io = &config.io;
    MachineShape {
        axes: config.axes.len(),
        digital_inputs: usize::from(io.digital_inputs),
        digital_outputs: usize::from(io.digital_outputs),
        analog_inputs: usize::from(io.analog_inputs),
        analog_outputs: usize::from(io.analog_outputs),
        slaves: config.drives.iter().map(|d| d.axis).collect(),
    }
}

/// Resolve and compile the units of section `section` (`modbus_tcp` …). `default_id` is the
/// id of the implicit unit when `units` is empty (`None` on TCP: every id). `file` is the
/// config file, which relative map paths start from.
pub fn units(
    config: &Config,
    file: &str,
    section: &str,
    map: &str,
    axes: &[AxisRef],
    units: &[UnitConfig],
    default_id: Option<u8>,
) -> Result<Vec<Unit>, ConfigError> {
    let error = |key: String, reason: String| ConfigError {
        file: file.to_string(),
        key,
        reason,
    };
    let names = config.axis_names();
    let resolve_axes = |refs: &[AxisRef], key: &str| {
        axis_ref::resolve_all(refs, &names).map_err(|e| error(key.to_string(), e.to_string()))
    };
    let implicit = [UnitConfig {
        id: default_id.unwrap_or(0),
        map: None,
        axes: Vec::new(),
    }];
    let list: &[UnitConfig] = if units.is_empty() { &implicit } else { units };
    let mut out = Vec::new();
    for (i, u) in list.iter().enumerate() {
        let key = |k: &str| {
            if units.is_empty() {
                format!("frontends.{section}.{k}")
            } else {
                format!("frontends.{section}.units[{i}].{k}")
            }
        };
        if !units.is_empty() && (u.id == 0 || u.id > 247) && section != "modbus_tcp" {
            return Err(error(
                key("id"),
                format!("{} is not a slave address (1 … 247)", u.id),
            ));
        }
        if out.iter().any(|o: &Unit| o.id == Some(u.id)) && !units.is_empty() {
            return Err(error(key("id"), format!("unit {} is listed twice", u.id)));
        }
        let map_name = u.map.as_deref().unwrap_or(map);
        let own_axes = if u.axes.is_empty() { axes } else { &u.axes };
        let axes_key = if u.axes.is_empty() {
            format!("frontends.{section}.axes")
        } else {
            key("axes")
        };
        let binding = Binding {
            axes: resolve_axes(own_axes, &axes_key)?,
        };
        let compiled = compile_map(config, file, map_name, &binding, &key("map"))?;
        let id = if units.is_empty() {
            default_id
        } else {
            Some(u.id)
        };
        out.push(Unit { id, map: compiled });
    }
    Ok(out)
}

/// The register maps a config can name: shipped in `mcemu_modbus`, or `.toml` files.
pub const MAPS: Artefacts = Artefacts {
    kind: "map",
    file_noun: "a map file",
    file_endings: &[".toml"],
    shipped: map::SHIPPED,
};

/// Compile map `map_name` (shipped name or path) for `binding` on this machine; `key` is the
/// config key that names the map, for errors.
pub fn compile_map(
    config: &Config,
    file: &str,
    map_name: &str,
    binding: &Binding,
    key: &str,
) -> Result<UnitMap, ConfigError> {
    let map = MAPS.load(map_name, file).map_err(|e| ConfigError {
        file: file.to_string(),
        key: key.to_string(),
        reason: e.to_string(),
    })?;
    let map_file = match &map.from {
        Located::Shipped { name, .. } => format!("{name} (shipped map)"),
        Located::File(path) => path.display().to_string(),
    };
    map::load(&map.text, &map_file, &machine_shape(config), binding).map_err(|e| ConfigError {
        file: e.file,
        key: e.key,
        reason: format!("{} (used by {file}: {key})", e.reason),
    })
}
