//! The status record of an axis group (issue 11 item 7): what a snapshot, the control API, a
//! trace and a scenario `expect` read of a group. A leaf like the axis record: it names only
//! the leaf types, so the group module above it and the snapshot beside it can both use it.

use serde::{Deserialize, Serialize};

use crate::types::{AxisIndex, CommandId, CoordinateSystem, ErrorKind, GroupId, MAX_GROUP_AXES};

/// PLCopen Part 4 group state (HIMC §3.1: Disabled, Standby, Moving, Halted?, Stopping,
/// ErrorStop).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GroupState {
    /// Created, not enabled: motion is refused.
    #[default]
    Disabled,
    /// Enabled and at rest with nothing queued: motion is accepted.
    Standby,
    /// The path is being executed (the members are fed, in SynchronizedMotion).
    Moving,
    /// `group_halt`: decelerating to, or at, rest on the path; the queue is kept and
    /// `group_continue` goes on.
    Halted,
    /// `group_stop`: decelerating to rest; the queue is dropped; motion is refused until at rest.
    Stopping,
    /// A member faulted, refused a setpoint or was disabled, or an emergency stop: the path was
    /// dropped; `group_reset` once the causes are gone.
    ErrorStop,
}

impl GroupState {
    /// snake_case name, as in traces and JSON.
    pub const fn name(self) -> &'static str {
        match self {
            GroupState::Disabled => "disabled",
            GroupState::Standby => "standby",
            GroupState::Moving => "moving",
            GroupState::Halted => "halted",
            GroupState::Stopping => "stopping",
            GroupState::ErrorStop => "error_stop",
        }
    }

    /// The state called `name` (scenario `expect`).
    pub fn from_name(name: &str) -> Option<GroupState> {
        [
            GroupState::Disabled,
            GroupState::Standby,
            GroupState::Moving,
            GroupState::Halted,
            GroupState::Stopping,
            GroupState::ErrorStop,
        ]
        .into_iter()
        .find(|s| s.name() == name)
    }
}

impl std::fmt::Display for GroupState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a group went to ErrorStop: kept until `group_reset` clears it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "cause", rename_all = "snake_case")]
pub enum GroupFault {
    /// A member axis faulted, hit a limit, was disabled or stopped, or refused a setpoint;
    /// `error` is what the axis reported.
    Member { axis: AxisIndex, error: ErrorKind },
    /// `group_emergency_stop`.
    EmergencyStop,
    /// A buffered wait (`group_wait_input`, `group_wait_position`) ran out of time.
    WaitTimeout { command: CommandId },
}

/// A move protection between two groups, as each of them reports it (NMC
/// `NMC_GetMvProtectSts`: 0 not enabled, 1 no interference, 2 interference).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InterferenceStatus {
    /// The group is in no move protection.
    #[default]
    NotEnabled,
    /// Guarded; the groups are apart.
    Clear,
    /// The protection is stopping a group (or retreating one) because the distance would fall
    /// below the protection distance.
    Interference,
}

/// One group after a tick. `Copy` (fixed arrays of [`MAX_GROUP_AXES`]) so that refreshing a
/// snapshot does not allocate; [`GroupStatus::axes`] and [`GroupStatus::position`] give the
/// slices of its members.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GroupStatus {
    pub group: GroupId,
    pub state: GroupState,
    /// HMC's result axis (digest 000 §4.3), if the group has one.
    pub result_axis: Option<AxisIndex>,
    /// Number of member axes, 1–9.
    pub axis_count: u8,
    /// Member axes in group-coordinate order (the first `axis_count`).
    pub members: [AxisIndex; MAX_GROUP_AXES],
    /// Commanded path position in group coordinates: each member's commanded position minus
    /// the group's origin offset (NMC orgFlag/offset).
    pub coordinates: [f64; MAX_GROUP_AXES],
    /// The origin offset of each coordinate.
    pub origin: [f64; MAX_GROUP_AXES],
    /// The coordinate system of moves that name none (`group_set_coordinate_system`).
    pub coordinate_system: CoordinateSystem,
    /// `coordinates` in that system (HIMC GetGrpPoseCmd).
    pub frame_position: [f64; MAX_GROUP_AXES],
    /// The move protection the group is in (the first, by protection number).
    pub interference: InterferenceStatus,
    /// Its current distance between the two protected axes (0 when not enabled).
    pub interference_distance: f64,
    /// Commanded velocity and acceleration along the path.
    pub path_velocity: f64,
    pub path_acceleration: f64,
    /// The command (motion, or buffered wait) being executed.
    pub current_command: Option<CommandId>,
    /// Ordinal of the motion being executed, counted from 1 since the group was created (0:
    /// none started yet).
    pub segment: u64,
    /// The `user_segment` number of the motion being executed or last executed (NMC
    /// CrdGetUserSegNo), 0 when it gave none.
    pub user_segment: u32,
    /// Entries in the group queue (motions and buffered commands, the running one included) and
    /// places left.
    pub queue_used: u32,
    pub queue_free: u32,
    /// Path length to the end of the last queued motion.
    pub remaining_length: f64,
    /// Every member in position and the path at rest with nothing queued.
    pub in_position: bool,
    /// Path velocity override (1 = 100 %).
    pub override_factor: f64,
    /// The last refused group command's error, or the error that ended the path.
    pub last_error: Option<ErrorKind>,
    /// Why the group is in ErrorStop (kept until a successful `group_reset`).
    pub fault: Option<GroupFault>,
    /// HMC's merge speed tolerance ratio (HMC_GetMergeSpeedTolerRatio, digest 000 §3.4); 0
    /// without a result axis.
    #[serde(default)]
    pub merge_speed_tolerance: f64,
    /// Motions queued now may take the result axis's merge (`mergeable`; false for a group
    /// without a result axis, which never merges).
    #[serde(default)]
    pub mergeable: bool,
    /// The polar transform is set (`group_set_polar_transform`): `coordinates` are the
    /// program's Cartesian point, the rotary and feed members' positions θ and r.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub polar: bool,
}

impl GroupStatus {
    /// The member axes, in group-coordinate order.
    pub fn axes(&self) -> &[AxisIndex] {
        self.members
            .get(..usize::from(self.axis_count))
            .unwrap_or(&self.members)
    }

    /// The commanded position in the selected coordinate system, one coordinate per member.
    pub fn frame_position(&self) -> &[f64] {
        self.frame_position
            .get(..usize::from(self.axis_count))
            .unwrap_or(&self.frame_position)
    }

    /// The commanded path position, one coordinate per member.
    pub fn position(&self) -> &[f64] {
        self.coordinates
            .get(..usize::from(self.axis_count))
            .unwrap_or(&self.coordinates)
    }
}
