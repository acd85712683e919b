//! The Modbus front-ends of a machine: each enabled section's units resolved (map by shipped
//! name or path, axes by index or name) and compiled against the machine, for `mcemu validate`
//! and `mcemu run` alike.

use std::path::{Path, PathBuf};

use mcemu_modbus::config::{AxisRef, UnitConfig};
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
    let resolve_axes = |refs: &[AxisRef], key: &str| -> Result<Vec<usize>, ConfigError> {
        if refs.is_empty() {
            return Ok((0..config.axes.len()).collect());
        }
        refs.iter()
            .map(|r| match r {
                AxisRef::Index(i) if *i < config.axes.len() => Ok(*i),
                AxisRef::Index(i) => Err(error(
                    key.to_string(),
                    format!(
                        "axis {i} does not exist (the machine has {})",
                        config.axes.len()
                    ),
                )),
                AxisRef::Name(n) => config
                    .axes
                    .iter()
                    .position(|a| a.name.as_deref() == Some(n.as_str()))
                    .ok_or_else(|| error(key.to_string(), format!("no axis is named `{n}`"))),
            })
            .collect()
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

/// Compile map `map_name` (shipped name or path) for `binding` on this machine; `key` is the
/// config key that names the map, for errors.
pub fn compile_map(
    config: &Config,
    file: &str,
    map_name: &str,
    binding: &Binding,
    key: &str,
) -> Result<UnitMap, ConfigError> {
    let (text, map_file) = map_text(map_name, file).map_err(|reason| ConfigError {
        file: file.to_string(),
        key: key.to_string(),
        reason,
    })?;
    map::load(&text, &map_file, &machine_shape(config), binding).map_err(|e| ConfigError {
        file: e.file,
        key: e.key,
        reason: format!("{} (used by {file}: {key})", e.reason),
    })
}

/// A shipped map by name, or a `.toml` path relative to the config file's directory.
fn map_text(name: &str, config_file: &str) -> Result<(String, String), String> {
    if !name.ends_with(".toml") {
        return map::shipped(name)
            .map(|t| (t.to_string(), format!("{name} (shipped map)")))
            .ok_or_else(|| {
                let names: Vec<&str> = map::SHIPPED.iter().map(|(n, _)| *n).collect();
                format!(
                    "`{name}` is not a shipped map ({}); a map file's path ends in .toml",
                    names.join(", ")
                )
            });
    }
    let base = Path::new(config_file)
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let path: PathBuf = base.join(name);
    std::fs::read_to_string(&path)
        .map(|t| (t, path.display().to_string()))
        .map_err(|e| format!("cannot read map `{}`: {e}", path.display()))
}
