//! The progress of a `gantry_home` (HMC_GantryInit), as `Snapshot::gantry_homes` shows it.

use serde::{Deserialize, Serialize};

use crate::types::AxisIndex;

/// Where a gantry homing is (HMC_GetGantryInitState, manual §4.4.11.6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GantryHomePhase {
    /// One axis searches its reference, the others following it (HMC state 1).
    #[default]
    Homing,
    /// The gantry returns to the first axis's reference (2).
    ReturnBack,
    /// Every axis is redefined at once (3).
    DefPos,
    /// Each axis moves on its own onto its reference (4).
    Compensate,
    /// Aligned (5).
    Finish,
    /// Ended early: a step was refused, stopped or faulted, or the deviation was over the
    /// limit (HMC: "偏差超出阈值时，指令结束").
    Failed,
}

impl GantryHomePhase {
    /// HMC_GetGantryInitState's value; a failed run reads 0xFFFFFFFF.
    pub fn hmc_state(self) -> u32 {
        match self {
            GantryHomePhase::Homing => 1,
            GantryHomePhase::ReturnBack => 2,
            GantryHomePhase::DefPos => 3,
            GantryHomePhase::Compensate => 4,
            GantryHomePhase::Finish => 5,
            GantryHomePhase::Failed => u32::MAX,
        }
    }
}

/// One `gantry_home`, running or ended.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GantryHomeStatus {
    pub axes: Vec<AxisIndex>,
    pub phase: GantryHomePhase,
    /// The axis searching its reference (phase `homing`).
    pub homing_axis: Option<AxisIndex>,
    /// Per axis, once all have homed: how far the first axis stood from its reference when
    /// this axis stood on its own (the gantry's skew; 0 for the first axis).
    pub deviations: Vec<f64>,
    /// Why it failed.
    pub error: Option<String>,
}
