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
    /// Slave = k1 · master 1 + k2 · master 2 (HMC SuperimposeEx).
    Superimpose,
    /// Tracks the tangent angle of a group's path (HMC MoveTang).
    Tangential,
    /// A gantry slave (issue 12 item 6): `gantry` holds its record.
    Gantry,
    /// An NMC Follow slave (FIFOs of segments): `Snapshot::follows` holds its record.
    Follow,
}

impl CouplingKind {
    /// The snake_case name (JSON, traces, scenario `expect`).
    pub const fn name(self) -> &'static str {
        match self {
            CouplingKind::Gear => "gear",
            CouplingKind::Cam => "cam",
            CouplingKind::Superimpose => "superimpose",
            CouplingKind::Tangential => "tangential",
            CouplingKind::Gantry => "gantry",
            CouplingKind::Follow => "follow",
        }
    }
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
    /// Superimposed and tangential: the second master (the tangent plane's second axis).
    #[serde(default)]
    pub master2: Option<AxisIndex>,
    /// Superimposed: k2 (`ratio` is k1; HMC_GetSuperimposeRatio1/2).
    #[serde(default)]
    pub ratio2: f64,
    /// Tangential: the tangent angle tracked, axis units, offset included
    /// (HMC_GetMoveTangDestDirection).
    #[serde(default)]
    pub angle: f64,
    /// Tangential: angle − the axis's setpoint (HMC_GetMoveTangDeviation).
    #[serde(default)]
    pub deviation: f64,
    /// Gantry slave: offset, deviation, limits and the pair view.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gantry: Option<GantryStatus>,
    /// Gear: servo periods the slave runs behind (HMC_GetGearPhaseOffset).
    #[serde(default)]
    pub phase_offset: u32,
    /// Tangential: HMC_GetMoveTangCornerState, 0 no lift, 1 manual corner mode and the path
    /// running, 2 manual and the path standing at a corner stop.
    #[serde(default)]
    pub corner_state: u8,
}
