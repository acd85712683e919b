//! Gantry commands (issue 12 item 6): a master and up to 7 slaves that receive the master's
//! command (HMC_GantrySynchro, digest 000 §4.4; NMC SetGantryMaster/SetGantrySlave, digest 001
//! §2.10; HIMC EnableGantryPair, digest 004 §2.6). PLCopen has no gantry block.

use serde::{Deserialize, Serialize};

use super::AxisIndex;

/// Most slaves of one gantry (HMC: ucSlaveAxisNum ≤ 7).
pub const MAX_GANTRY_SLAVES: usize = 7;

/// Gang `slaves` to `master`: each slave's commanded position is the master's plus the offset
/// between them at this command, and single-axis motion of a slave is refused until
/// `gantry_disable`. The deviation (slave − master actual, less that offset) over
/// `warning_limit` sets `gantry_warning` (HMC AxisStatus bit 5); over `fault_limit` latches
/// `gantry_fault` on the master (bit 6), which stops with its `fast_decel` and the slaves with
/// it. A limit of 0 is no limit. JSON `type`: `gantry_enable`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GantryEnable {
    pub master: AxisIndex,
    /// 1 to 7 slaves, each once, none the master.
    pub slaves: Vec<AxisIndex>,
    #[serde(default)]
    pub warning_limit: f64,
    #[serde(default)]
    pub fault_limit: f64,
    /// HIMC `EnableGantryPair` (digest 004 §2.6, TV 38): refuse unless the master and every
    /// slave are disabled. The pair is made at rest; `enable` of the master then enables the
    /// slaves too (TV 39), as it does on any gantry.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub require_disabled: bool,
    /// HMC GantrySynchro ucMode 1, "closed-loop (cross-coupling) sync" (manual §4.4.11.1):
    /// each slave's command is also corrected by a PID on its deviation, gains per slave by
    /// `gantry_set_pid` (default Kp 1, Ki 0, Kd 0, §4.4.11.3). Off: open loop (ucMode 0).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub closed_loop: bool,
}

/// Release the slaves of `master`'s gantry: each decelerates to rest with its `decel` from the
/// velocity it has (as `gear_out`) and takes single-axis motion again (HMC GantrySynchro cancel, NMC DelGantryGroup, HIMC DisableGantryPair). JSON
/// `type`: `gantry_disable`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GantryDisable {
    pub master: AxisIndex,
}

/// Most axes one `gantry_home` aligns (HMC_GantryInit: ucAxisNum ≤ 8).
pub const MAX_GANTRY_HOME_AXES: usize = 8;

/// Home a gantry's axes together and align them (HMC_GantryInit, manual §4.4.11.2, digest 000
/// §4.4 "Gantry"). In the order given, each axis homes on its own home switch with HMC_Home
/// (`instruction` `home`) or HMC_HomeEx (`home_ex`) mode `home_mode` (0–5, digest 000 §5) and
/// its own `speed`, `creep_speed` and `accel`, while the other axes follow it as a gantry;
/// then the whole gantry returns to where the first axis found its reference; then every axis
/// is redefined at once so that its reference reads `reference_position`; then, if no axis
/// is more than `position_error` (0 = no limit) from the first, each axis moves on its own to
/// `reference_position`, which aligns the gantry on its reference switches. Progress and the
/// deviations found are `Snapshot::gantry_homes` (HMC_GetGantryInitState). A stop, fault or
/// refusal of any step ends it as `failed`. JSON `type`: `gantry_home`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GantryHome {
    /// 2 to 8 axes, each once; none in a gantry, group or coupling.
    pub axes: Vec<AxisIndex>,
    #[serde(default = "default_instruction")]
    pub instruction: crate::homing::vendor::HmcInstruction,
    #[serde(default)]
    pub home_mode: u8,
    pub reference_position: f64,
    #[serde(default)]
    pub position_error: f64,
}

fn default_instruction() -> crate::homing::vendor::HmcInstruction {
    crate::homing::vendor::HmcInstruction::Home
}

/// Redefine the positions of every axis of `master`'s gantry at once: the master and each
/// slave read `position` (commanded position; the actual position moves with it, the following
/// error kept), nothing moves, and the slaves' offsets become 0 (HMC_GantryGroupDefPos, manual
/// §4.4.11.5, digest 000 §4.4 "Gantry"). Refused unless `master` is a gantry's master. JSON
/// `type`: `gantry_set_position`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GantrySetPosition {
    pub master: AxisIndex,
    pub position: f64,
}

/// The gains of gantry slave `axis`'s deviation correction (HMC_SetGantryAxisPID, manual
/// §4.4.11.3): in a `closed_loop` gantry the slave's command moves by a correction whose rate
/// (units/s) is −(kp·e + ki·∫e dt + kd·de/dt), e its deviation; so kp is per second (default
/// 1), ki per second², kd dimensionless. Refused unless `axis` is a gantry slave; allowed on an
/// open-loop gantry, where it takes effect only if the gantry is made closed-loop again. The
/// integral and the correction so far are kept. JSON `type`: `gantry_set_pid`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GantrySetPid {
    pub axis: AxisIndex,
    pub kp: f64,
    #[serde(default)]
    pub ki: f64,
    #[serde(default)]
    pub kd: f64,
}
