//! The state of one NMC Follow slave (issue 12 item 2; digest 001 §2.17), as
//! `Snapshot::follows` carries it: what NMC FollowGetSpace, GetLoopCount, GetMaster, GetEvent
//! and GetDir read.

use serde::{Deserialize, Serialize};

use crate::types::{AxisIndex, Direction, MasterSource};

/// When a started Follow begins to move the slave (NMC FollowSetEvent `eventType`).
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FollowEvent {
    /// 1: at `follow_start`.
    #[default]
    Immediate,
    /// 2: when the master crosses `start_position` moving in `start_direction`.
    MasterCrossing,
}

/// Which master travel a Follow slave follows (NMC FollowSetDir: 0, > 0, < 0).
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FollowDirection {
    #[default]
    Both,
    Positive,
    Negative,
}

/// Where a Follow is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FollowState {
    /// Configured or filled, not started (or ended).
    #[default]
    Idle,
    /// Started, waiting for the master to cross the start position.
    Waiting,
    /// The slave follows the active FIFO.
    Running,
}

/// One Follow slave: its settings, its two FIFOs and its run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FollowStatus {
    pub axis: AxisIndex,
    /// None until `follow_config` names one.
    pub master: Option<AxisIndex>,
    pub master_source: MasterSource,
    /// 0 = for ever.
    pub loop_count: u32,
    /// `immediate` or `master_crossing`.
    pub event: FollowEvent,
    pub start_position: f64,
    pub start_direction: Option<Direction>,
    pub direction: FollowDirection,
    pub state: FollowState,
    /// The FIFO the slave follows (or will follow first).
    pub active_fifo: u8,
    /// Free segments of FIFO 0 and 1 (NMC FollowGetSpace).
    pub space: [u16; 2],
    /// Passes through the active FIFO completed (NMC FollowGetLoopCount during motion).
    pub loops_done: u32,
    /// The segment of the active FIFO the master is in.
    pub segment: u16,
    /// A `follow_switch` waits for the end of the current pass.
    pub switch_pending: bool,
}
