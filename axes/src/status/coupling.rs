//! The status of one coupling (issue 12: gear, cam), as `Snapshot::couplings` carries it.

use serde::{Deserialize, Serialize};

use super::GantryStatus;
use crate::types::{AxisIndex, MasterSource};

/// Where a coupling is (PLCopen MC_GearIn/MC_CamIn outputs; HIMC IsInGear).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CouplingPhase {
    /// A cam waiting for its start (master position, input).
    #[default]
    Waiting,
    /// A gear in its clutch.
    Engaging,
    /// The slave follows the master exactly (PLCopen InGear / InSync).
    InSync,
}

impl CouplingPhase {
    pub const fn name(self) -> &'static str {
        match self {
            CouplingPhase::Waiting => "waiting",
            CouplingPhase::Engaging => "engaging",
            CouplingPhase::InSync => "in_sync",
        }
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CouplingKind {
    #[default]
    Gear,
    Cam,
    /// A gantry slave (issue 12 item 6): `gantry` holds its record.
    Gantry,
}

/// One coupling, by slave.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CouplingStatus {
    pub slave: AxisIndex,
    pub master: AxisIndex,
    pub kind: CouplingKind,
    pub master_source: MasterSource,
    pub phase: CouplingPhase,
    /// Gear: numerator / denominator (HIMC GetGearRatio, HMC_GetGearRatio). Cam: 0.
    pub ratio: f64,
    /// Cam: the table.
    pub table: Option<u16>,
    /// Cam: the span of the table the master is in (HMC_GetCamMasterPosIndex).
    pub table_index: u32,
    /// Periodic cam: the period the master is in, from 0 (NMC FollowGetLoopCount).
    pub cycle: i64,
    /// Gantry slave: offset, deviation, limits and the pair view.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gantry: Option<GantryStatus>,
}
