//! `NMC_SaveMotionConfig` (digest 001 §1.5, §2.2): the basic axis configuration — alarm,
//! limits, home level, soft limits, safety, following error, in-position band, pulse mode,
//! filters, encoder modes — saved in the machine's state directory (`nmc/<section>.json`,
//! replaced atomically) and applied again when mcemu starts and on `NMC_DevReset`. The same
//! text is what `NMC_SaveConfigToFile` writes and `NMC_LoadConfigFromFile` reads on the host
//! (`handlers/config_file.rs`).

use std::collections::BTreeMap;

use axes::command::{Command, SetParameter};
use axes::param::ParamId;
use axes::status::Snapshot;
use serde::{Deserialize, Serialize};

use super::service::NmcService;

/// The engine parameters the NMC configuration calls write (digest 001 §2.3, §2.6, §2.20).
const SAVED_PARAMS: [ParamId; 17] = [
    ParamId::DriveAlarmEnable,
    ParamId::DriveAlarmInvert,
    ParamId::FhLimitIn,
    ParamId::RhLimitIn,
    ParamId::LimitPosInvert,
    ParamId::LimitNegInvert,
    ParamId::HomeInvert,
    ParamId::IgnoreSwLimits,
    ParamId::FsLimit,
    ParamId::RsLimit,
    ParamId::FastDecel,
    ParamId::MaxVelocity,
    ParamId::MaxAccel,
    ParamId::FeLimit,
    ParamId::FeAction,
    ParamId::InPositionWindow,
    ParamId::InPositionTime,
];

/// One axis as saved: parameters by name, the kept pulse mode and filters.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
struct SavedAxis {
    params: BTreeMap<String, f64>,
    step_inv: i16,
    step_mode: i16,
    step_filter: u16,
    vel_filter: i16,
}

/// The file.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SavedConfig {
    axes: Vec<SavedAxis>,
    enc_mode: BTreeMap<u8, u16>,
}

fn file(service: &NmcService) -> String {
    format!("nmc/{}.json", service.section())
}

/// The configuration as `snapshot` and the service show it.
fn current(service: &NmcService, snapshot: &Snapshot) -> SavedConfig {
    let stored = service.stored();
    let axes = (0..snapshot.axes.len())
        .map(|a| {
            let params = snapshot.params.get(a).cloned().unwrap_or_default();
            let s = stored.axis(a);
            SavedAxis {
                params: SAVED_PARAMS
                    .iter()
                    .map(|id| (id.name().to_string(), params.get(*id)))
                    .collect(),
                step_inv: s.step_inv,
                step_mode: s.step_mode,
                step_filter: s.step_filter,
                vel_filter: s.vel_filter,
            }
        })
        .collect();
    SavedConfig {
        axes,
        enc_mode: stored.enc_mode.clone(),
    }
}

/// The configuration as text, the file's format (`NMC_SaveConfigToFile` writes the same, on
/// the host: digest 001 §1.5).
pub fn text(service: &NmcService, snapshot: &Snapshot) -> Result<String, String> {
    serde_json::to_string_pretty(&current(service, snapshot)).map_err(|e| e.to_string())
}

/// Save the configuration as `snapshot` and the service show it. An error names the file.
pub fn save(service: &NmcService, snapshot: &Snapshot) -> Result<(), String> {
    let dir = service
        .state_dir()
        .ok_or("mcemu has no state directory (--state-dir) to save to")?;
    let text = text(service, snapshot)?;
    let name = file(service);
    dir.write(&name, text.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", dir.display(&name)))
}

/// Forget the saved configuration (`NMC_SaveMotionConfig(dev, 0)`): the next start uses the
/// machine's.
pub fn forget(service: &NmcService) -> Result<(), String> {
    let Some(dir) = service.state_dir() else {
        return Ok(());
    };
    let path = dir.path().join(file(service));
    match std::fs::remove_file(&path) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(format!("cannot remove {}: {e}", path.display())),
    }
}

/// The saved configuration's engine commands (none if nothing was saved), the kept settings
/// restored into the service on the way. A file that cannot be read is reported and ignored.
pub fn restore(service: &NmcService) -> Vec<Command> {
    let Some(dir) = service.state_dir() else {
        return Vec::new();
    };
    let name = file(service);
    let bytes = match dir.read(&name) {
        Ok(None) => return Vec::new(),
        Ok(Some(bytes)) => bytes,
        Err(e) => {
            tracing::warn!(file = %dir.display(&name), "saved NMC motion config not read: {e}");
            return Vec::new();
        }
    };
    let count = service.engine.snapshot().axes.len();
    match parse(&bytes, count) {
        Ok(saved) => apply(service, saved),
        Err(e) => {
            tracing::warn!(file = %dir.display(&name), "saved NMC motion config not restored: {e}");
            Vec::new()
        }
    }
}

/// A configuration text checked for a machine of `axes` axes: the format, an axis count that
/// fits, finite known parameters.
pub fn parse(bytes: &[u8], axes: usize) -> Result<SavedConfig, String> {
    let saved: SavedConfig = serde_json::from_slice(bytes)
        .map_err(|e| format!("not an mcemu NMC configuration: {e}"))?;
    if saved.axes.len() > axes {
        return Err(format!(
            "the configuration has {} axes; the device has {axes}",
            saved.axes.len()
        ));
    }
    for (axis, a) in saved.axes.iter().enumerate() {
        for (name, value) in &a.params {
            if !ParamId::from_name(name).is_some_and(|id| SAVED_PARAMS.contains(&id)) {
                return Err(format!("axis {axis}: {name} is not a saved parameter"));
            }
            if !value.is_finite() {
                return Err(format!("axis {axis}: {name} = {value} is not finite"));
            }
        }
    }
    Ok(saved)
}

/// `saved`'s engine commands, its kept settings put into the service on the way.
pub fn apply(service: &NmcService, saved: SavedConfig) -> Vec<Command> {
    let count = service.engine.snapshot().axes.len();
    let mut stored = service.stored();
    let mut commands = Vec::new();
    for (axis, a) in saved.axes.iter().enumerate().take(count) {
        for (name, value) in &a.params {
            let Some(id) = ParamId::from_name(name).filter(|id| SAVED_PARAMS.contains(id)) else {
                continue;
            };
            if value.is_finite() {
                commands.push(
                    SetParameter {
                        axis: axis as u16,
                        name: id,
                        value: *value,
                        lenient: false,
                    }
                    .into(),
                );
            }
        }
        let s = stored.axis_mut(axis);
        (s.step_inv, s.step_mode) = (a.step_inv, a.step_mode);
        (s.step_filter, s.vel_filter) = (a.step_filter, a.vel_filter);
    }
    stored.enc_mode = saved.enc_mode;
    commands
}

/// Apply the saved configuration at start.
pub async fn restore_at_start(service: &NmcService) {
    let commands = restore(service);
    if commands.is_empty() {
        return;
    }
    if let Err(e) = service.engine.call_batch_async(commands).await {
        tracing::warn!("saved NMC motion config refused by the engine: {e}");
    }
}
