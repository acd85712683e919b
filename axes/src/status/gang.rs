//! The status of a gantry slave and of a handwheel (issue 12 items 6–7), as
//! `CouplingStatus::gantry` and `Snapshot::handwheels` carry them.

use serde::{Deserialize, Serialize};

use crate::types::AxisIndex;

/// One slave of a gantry, beside its master (`CouplingStatus` with kind `gantry`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GantryStatus {
    /// Slave − master commanded position at `gantry_enable`, held while ganged.
    pub offset: f64,
    /// (slave − master actual position) − `offset`, this tick.
    pub deviation: f64,
    pub warning_limit: f64,
    pub fault_limit: f64,
    /// |deviation| > `warning_limit` (HMC AxisStatus bit 5).
    pub warning: bool,
    /// HIMC's pair view with the master as RHS and this slave as LHS (digest 004 §2.6):
    /// (RHS + LHS) / 2 and (RHS − LHS) / 2 of the actual positions.
    pub linear: f64,
    pub yaw: f64,
    /// HMC GantrySynchro ucMode 1: the slave's command is corrected by its PID.
    #[serde(default)]
    pub closed_loop: bool,
    /// The correction's gains (HMC_GetGantryAxisPID): kp per second, ki per second², kd.
    #[serde(default)]
    pub kp: f64,
    #[serde(default)]
    pub ki: f64,
    #[serde(default)]
    pub kd: f64,
    /// What the correction adds to the slave's command next tick (0 in open loop).
    #[serde(default)]
    pub correction: f64,
}

/// One handwheel and the axis it drives (`Snapshot::handwheels`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct HandwheelStatus {
    pub axis: AxisIndex,
    pub input: u16,
    /// numerator / denominator: user units per count.
    pub ratio: f64,
    /// The input's count now.
    pub counts: i64,
    /// Where counts × ratio put the axis (less dropped travel).
    pub target: f64,
    /// target − the axis's commanded position: what it has still to catch up.
    pub lag: f64,
    /// Travel dropped because the wheel outran `velocity` (`excess = drop`), user units.
    pub dropped: f64,
}
