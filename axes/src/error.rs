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
        }
    }
}
