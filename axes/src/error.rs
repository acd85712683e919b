//! [`EngineError`]: why the engine refused a command or ended one. Below `param` and `command`
//! in the module chain, so that both can return it; `command` re-exports it under its old path.

use serde::Serialize;

use crate::homing::HomingError;
use crate::od::OdError;
use crate::status::{AxisFlags, AxisState, GroupState};
use crate::types::{AxisIndex, CommandId, Direction, ErrorKind, GroupId};

/// Why the engine refused a command or ended one. A closed set: dialects map each variant to
/// their own codes (Modbus exceptions, SDO aborts, NMC return codes, HIMC 0xCCNNVVVV …).
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize)]
#[serde(tag = "code", rename_all = "snake_case")]
pub enum EngineError {
    #[error("axis {axis} does not exist (the machine has {count} axes)")]
    InvalidAxis { axis: u32, count: u32 },
    #[error("unknown parameter `{name}`")]
    UnknownParameter { name: String },
    #[error("parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: String,
    },
    #[error("parameter `{name}` is read-only")]
    ReadOnlyParameter { name: &'static str },
    #[error("axis {axis}: compensation: {reason}")]
    InvalidCompensation { axis: u32, reason: String },
    /// Compensation that would output more than the axis's `compensation_limit` (digest 004
    /// §2.13, HIMC eERR_AXIS_COMP_LIMIT).
    #[error("axis {axis}: compensation {value} exceeds the limit {limit}")]
    CompensationLimit { axis: u32, value: f64, limit: f64 },
    #[error("sampler {sampler}: {reason}")]
    InvalidSampling { sampler: u16, reason: String },
    #[error("{name} = {value}: {reason}")]
    InvalidArgument {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    #[error("axis {axis} is disabled")]
    AxisDisabled { axis: AxisIndex },
    #[error("axis {axis} is in error stop ({faults})")]
    AxisInError { axis: AxisIndex, faults: AxisFlags },
    #[error("axis {axis}: {direction} limit active; motion further into it is refused")]
    LimitActive {
        axis: AxisIndex,
        direction: Direction,
    },
    #[error("axis {axis}: command queue full ({depth} commands)")]
    QueueFull { axis: AxisIndex, depth: u16 },
    #[error("unsupported: {what}")]
    Unsupported { what: String },
    #[error("axis {axis} is {state}: cannot {action}")]
    InvalidState {
        axis: AxisIndex,
        state: AxisState,
        action: &'static str,
    },
    #[error("axis {axis}: cannot clear {faults}: the cause is still present")]
    CauseStillPresent { axis: AxisIndex, faults: AxisFlags },
    #[error("no command with id {id}")]
    UnknownCommand { id: CommandId },
    #[error("homing: {0}")]
    Homing(HomingError),
    #[error("slave {slave}: {error}")]
    Object { slave: u16, error: OdError },
    #[error("slave {slave} does not exist (the machine has {count} slaves)")]
    InvalidSlave { slave: u16, count: u16 },
    #[error("I/O channel {channel} does not exist ({kind} has {count} channels)")]
    InvalidChannel {
        kind: &'static str,
        channel: u16,
        count: u16,
    },
    /// One item of a list in a command was refused, and with it the whole command: a move of a
    /// `move_together` (`list` = "moves"), an axis of `stop_axes` or `enable_all` ("axes"), a
    /// command of an atomic batch ("commands"). Nothing of the command was applied. Its
    /// [`EngineError::kind`] is the item's, so dialects map it as they map the item's refusal.
    #[error("{list}[{index}]: {error}")]
    Item {
        list: &'static str,
        /// `item` in JSON: the control API's `index` is the command's place in a request.
        #[serde(rename = "item")]
        index: u32,
        error: Box<EngineError>,
    },
    #[error("group {group} does not exist")]
    UnknownGroup { group: GroupId },
    #[error("group {group}: {reason}")]
    InvalidGroup { group: GroupId, reason: String },
    #[error("group {group} is {state}: cannot {action}")]
    GroupState {
        group: GroupId,
        state: GroupState,
        action: &'static str,
    },
    #[error("group {group}: member axis {axis} is {state}: cannot {action}")]
    GroupMember {
        group: GroupId,
        axis: AxisIndex,
        state: AxisState,
        action: &'static str,
    },
    #[error("group {group}: cannot reset: member axis {axis} is still {state}")]
    GroupCauseStillPresent {
        group: GroupId,
        axis: AxisIndex,
        state: AxisState,
    },
    #[error("axis {axis} is in group {group}: it takes no single-axis motion")]
    AxisInGroup { axis: AxisIndex, group: GroupId },
    #[error("group {group}: queue full ({capacity} entries)")]
    GroupQueueFull { group: GroupId, capacity: u32 },
    #[error("group {group}: {reason}")]
    InvalidPath { group: GroupId, reason: String },
    /// A selection of a system the group does not have (a WCS outside 1–15, an NMC transform
    /// not set), or a link that cannot be set that way (HIMC eERR_CRD_CMD_COORD_SYS_UNKNOWN).
    #[error("group {group}: coordinate system `{system}` {reason}")]
    UndefinedCoordinateSystem {
        group: GroupId,
        system: String,
        reason: &'static str,
    },
    /// A move protection that cannot be set up as given (NMC `SetMvProtect`).
    #[error("move protection {protection}: {reason}")]
    InvalidProtection { protection: u16, reason: String },
    /// A coupling whose slave would be its own master (issue 12).
    #[error("axis {axis} cannot be its own master")]
    CoupledToItself { axis: AxisIndex },
    /// `gear_in`/`cam_in`/`superimpose_in`/`tangential_in` on a slave that already follows a
    /// master.
    #[error("axis {axis} is already coupled to master axis {master}")]
    AlreadyCoupled { axis: AxisIndex, master: AxisIndex },
    /// Single-axis motion (or a group) for a coupled slave.
    #[error("axis {axis} is coupled to master axis {master}: it takes no single-axis motion")]
    AxisCoupled { axis: AxisIndex, master: AxisIndex },
    /// The master already follows the slave, directly or through other couplings.
    #[error("coupling axis {slave} to master axis {master} closes a loop in the master chain")]
    CouplingLoop { slave: AxisIndex, master: AxisIndex },
    /// `gear_out`, `cam_out`, `gear_set_ratio`, `superimpose_out`, `superimpose_set_ratios` or
    /// `tangential_out` on an axis that is not such a slave.
    #[error("axis {axis} is not {what}")]
    NotCoupled { axis: AxisIndex, what: &'static str },
    #[error("cam table {table} does not exist")]
    UnknownCamTable { table: u16 },
    #[error("cam table {table}: {reason}")]
    InvalidCamTable { table: u16, reason: String },
    /// HMC: "arrays must not be modified while the cam runs".
    #[error("cam table {table} is in use by the cam of axis {slave}")]
    CamTableInUse { table: u16, slave: AxisIndex },
    /// A capture or compare channel that cannot be set up as given (issue 12 items 4–5).
    #[error("{trigger} channel {channel}: {reason}")]
    InvalidTrigger {
        /// `capture` or `compare`.
        trigger: &'static str,
        channel: u8,
        reason: String,
    },
    /// A PT/PVT push with more points than the axis's buffer has room for (NMC `MtPtGetSpace`).
    #[error("axis {axis}: the PT/PVT buffer has room for {space} points, {count} pushed")]
    StreamFull {
        axis: AxisIndex,
        space: u16,
        count: u32,
    },
    /// A `gantry_enable` that cannot be set up as given (issue 12 item 6).
    #[error("gantry of master axis {master}: {reason}")]
    InvalidGantry {
        master: AxisIndex,
        reason: &'static str,
    },
    /// `gantry_enable` on a master that already leads a gantry.
    #[error("axis {master} already leads a gantry")]
    GantryExists { master: AxisIndex },
    /// Single-axis motion for an axis a handwheel drives (issue 12 item 7).
    #[error("axis {axis} is driven by a handwheel: it takes no single-axis motion")]
    AxisOnHandwheel { axis: AxisIndex },
    /// A handwheel input that is neither an axis's encoder nor an external encoder.
    #[error("handwheel input {input} does not exist (axes 0..{axes}, external encoders 256..{external_end})")]
    UnknownHandwheelInput {
        input: u16,
        axes: u32,
        external_end: u16,
    },
    /// A point of a PT/PVT push or move that cannot be run; none of the command's points was
    /// taken.
    #[error("axis {axis}: point {point}: {problem}")]
    StreamPoint {
        axis: AxisIndex,
        /// Index in the command's `points`.
        point: u32,
        problem: StreamPointProblem,
    },
    /// An NMC Follow command that cannot be applied as given (issue 12 item 2).
    #[error("follow of axis {axis}: {reason}")]
    InvalidFollow { axis: AxisIndex, reason: String },
    /// A Follow push with more segments than the FIFO has room for (NMC FollowGetSpace).
    #[error("axis {axis}: follow FIFO {fifo} has room for {space} segments, {count} pushed")]
    FollowFull {
        axis: AxisIndex,
        fifo: u8,
        space: u16,
        count: u32,
    },
}

/// What is wrong with one PT/PVT point ([`EngineError::StreamPoint`]). The HIMC dialect maps
/// the last three to `eERR_AXIS_PVT_MOTION_INVALID_TIME`, `_VEL_LIMIT` and `_ACC_LIMIT`.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error, Serialize)]
#[serde(tag = "problem", rename_all = "snake_case")]
pub enum StreamPointProblem {
    #[error("{name} = {value}: must be a finite number within ±1e12")]
    NotFinite { name: &'static str, value: f64 },
    #[error("a knot at time 0 must be the start itself: position 0, velocity 0")]
    StartMismatch,
    #[error("time {time_ms} ms is not after the point before it ({previous_ms} ms)")]
    TimeNotIncreasing { time_ms: f64, previous_ms: f64 },
    #[error("the segment to it reaches {velocity} units/s, beyond max_velocity {limit}")]
    VelocityLimit { velocity: f64, limit: f64 },
    #[error("the segment to it reaches {acceleration} units/s², beyond max_accel {limit}")]
    AccelerationLimit { acceleration: f64, limit: f64 },
}

impl EngineError {
    /// `error` as the refusal of item `index` of `list`.
    pub fn item(list: &'static str, index: usize, error: EngineError) -> EngineError {
        EngineError::Item {
            list,
            index: u32::try_from(index).unwrap_or(u32::MAX),
            error: Box::new(error),
        }
    }

    /// The refusal inside any [`EngineError::Item`] wrappers.
    pub fn innermost(&self) -> &EngineError {
        match self {
            EngineError::Item { error, .. } => error.innermost(),
            other => other,
        }
    }

    pub fn kind(&self) -> ErrorKind {
        match self {
            EngineError::InvalidAxis { .. } => ErrorKind::InvalidAxis,
            EngineError::UnknownParameter { .. } => ErrorKind::UnknownParameter,
            EngineError::InvalidParameter { .. } => ErrorKind::InvalidParameter,
            EngineError::ReadOnlyParameter { .. } => ErrorKind::ReadOnlyParameter,
            EngineError::InvalidArgument { .. } => ErrorKind::InvalidArgument,
            EngineError::InvalidCompensation { .. } => ErrorKind::InvalidArgument,
            EngineError::CompensationLimit { .. } => ErrorKind::InvalidState,
            EngineError::InvalidSampling { .. } => ErrorKind::InvalidArgument,
            EngineError::AxisDisabled { .. } => ErrorKind::AxisDisabled,
            EngineError::AxisInError { .. } => ErrorKind::AxisInError,
            EngineError::LimitActive { .. } => ErrorKind::LimitActive,
            EngineError::QueueFull { .. } => ErrorKind::QueueFull,
            EngineError::Unsupported { .. } => ErrorKind::Unsupported,
            EngineError::InvalidState { .. } => ErrorKind::InvalidState,
            EngineError::CauseStillPresent { .. } => ErrorKind::CauseStillPresent,
            EngineError::UnknownCommand { .. } => ErrorKind::UnknownCommand,
            EngineError::Homing(_) => ErrorKind::Homing,
            EngineError::Object { .. } => ErrorKind::Object,
            EngineError::InvalidSlave { .. } => ErrorKind::InvalidSlave,
            EngineError::InvalidChannel { .. } => ErrorKind::InvalidChannel,
            EngineError::Item { error, .. } => error.kind(),
            EngineError::UnknownGroup { .. } | EngineError::InvalidGroup { .. } => {
                ErrorKind::InvalidGroup
            }
            EngineError::GroupState { .. } | EngineError::GroupMember { .. } => {
                ErrorKind::GroupState
            }
            EngineError::GroupCauseStillPresent { .. } => ErrorKind::CauseStillPresent,
            EngineError::AxisInGroup { .. } => ErrorKind::InvalidState,
            EngineError::GroupQueueFull { .. } => ErrorKind::QueueFull,
            EngineError::InvalidPath { .. }
            | EngineError::UndefinedCoordinateSystem { .. }
            | EngineError::InvalidProtection { .. } => ErrorKind::InvalidArgument,
            EngineError::CoupledToItself { .. }
            | EngineError::CouplingLoop { .. }
            | EngineError::UnknownCamTable { .. }
            | EngineError::InvalidCamTable { .. } => ErrorKind::InvalidArgument,
            EngineError::AlreadyCoupled { .. }
            | EngineError::AxisCoupled { .. }
            | EngineError::NotCoupled { .. }
            | EngineError::CamTableInUse { .. } => ErrorKind::InvalidState,
            EngineError::InvalidTrigger { .. } | EngineError::StreamPoint { .. } => {
                ErrorKind::InvalidArgument
            }
            EngineError::StreamFull { .. } => ErrorKind::QueueFull,
            EngineError::InvalidGantry { .. } | EngineError::UnknownHandwheelInput { .. } => {
                ErrorKind::InvalidArgument
            }
            EngineError::GantryExists { .. } | EngineError::AxisOnHandwheel { .. } => {
                ErrorKind::InvalidState
            }
            EngineError::InvalidFollow { .. } => ErrorKind::InvalidArgument,
            EngineError::FollowFull { .. } => ErrorKind::QueueFull,
        }
    }
}
