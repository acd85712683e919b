//! NMC Follow commands (issue 12 item 2; digest 001 §2.17, §4.7, S-FOLLOW, TV 59): per slave
//! axis two FIFOs of up to 32 segments (master distance, slave distance, segment type), a loop
//! count, FIFO switching and a start when the master crosses a position. Each command maps onto
//! one NMC call (or, for `follow_config`, onto the setters NMC_MtFollowSetMaster, SetLoopCount,
//! SetEvent and SetDir, each of which sends only its own fields).

use serde::{Deserialize, Serialize};

use super::{AxisIndex, CamPoint, Direction, MasterSource};
pub use crate::status::{FollowDirection, FollowEvent};

/// FIFOs per Follow slave (NMC FollowPushData `fifoNo` 0/1).
pub const FOLLOW_FIFOS: u8 = 2;
/// Segments per Follow FIFO (NMC FollowGetSpace: "32 segments each").
pub const FOLLOW_FIFO_SEGMENTS: u16 = 32;

/// Set a Follow slave's master, loop count, start event or direction filter: each field
/// given replaces its setting, the others keep theirs (NMC FollowSetMaster(master,
/// masterType): `master` + `master_source`; FollowSetLoopCount: `loop_count`, 0 = for ever;
/// FollowSetEvent(eventType, masterDir, pos): `event`, `start_direction`, `start_position`;
/// FollowSetDir: `direction`, with `both` for 0). Refused while the Follow runs. JSON `type`:
/// `follow_config`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowConfig {
    pub axis: AxisIndex,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub master: Option<AxisIndex>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub master_source: Option<MasterSource>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loop_count: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub event: Option<FollowEvent>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_position: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_direction: Option<Direction>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<FollowDirection>,
}

/// Append segments to FIFO `fifo` (0 or 1) of `axis` (NMC FollowPushData(masterPos, slavePos,
/// type, fifoNo), one point per call there). Each point's `master` and `slave` are measured
/// from the FIFO's start point (0, 0), cumulative (S-FOLLOW pushes running sums), masters
/// strictly increasing; `segment` is the point's type (normal, even, stop, continuous). All or
/// none: a push beyond the 32 segments is refused whole. JSON `type`: `follow_push`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowPush {
    pub axis: AxisIndex,
    pub fifo: u8,
    pub points: Vec<CamPoint>,
}

/// Empty FIFO `fifo` of `axis` (NMC FollowClear); refused for the FIFO a running Follow runs.
/// JSON `type`: `follow_clear`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowClear {
    pub axis: AxisIndex,
    pub fifo: u8,
}

/// Start the Follow of every axis in `axes`, all or none, in the same tick (NMC
/// FollowStart(axis, syncAxCnts, syncAxArray): the first axis and the others). JSON `type`:
/// `follow_start`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowStart {
    pub axes: Vec<AxisIndex>,
}

/// Switch each axis's Follow to its other FIFO at the end of the current pass through the
/// running one (NMC FollowSwitch). JSON `type`: `follow_switch`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowSwitch {
    pub axes: Vec<AxisIndex>,
}

/// End the Follow of `axis`: the slave keeps its velocity and ramps to rest with its `decel`,
/// as `cam_out` (NMC MtStop on a Follow slave). The FIFOs keep their data. JSON `type`:
/// `follow_out`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowOut {
    pub axis: AxisIndex,
}
