//! Leaf types of the engine: indices, ids and kinds that every layer names (status, homing,
//! errors, commands). This module imports nothing from the crate, so it can sit at the bottom of
//! the module chain (docs/architecture.md); `command` re-exports each type under its old path.

use serde::{Deserialize, Serialize};

/// Index of an axis in the machine, from 0.
pub type AxisIndex = u16;

/// Number of an axis group, chosen by the user at `group_create` (issue 11).
pub type GroupId = u16;

/// Most axes in one group (HIMC: 9, digest 004 §3; `path::MAX_AXES`).
pub const MAX_GROUP_AXES: usize = 9;

/// Identifier of a queued motion command. Engine-wide, increasing from 1; 0 is never used.
pub type CommandId = u32;

/// What kind of command occupies a FIFO slot; reported in status (HMC MCmdType/NCmdType).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CommandKind {
    MoveAbsolute,
    MoveRelative,
    MoveVelocity,
    Home,
    /// A drive-driven or externally streamed setpoint (CSP/CSV/CST, HMC_SetDposSwitch).
    External,
}

impl CommandKind {
    /// Stable numeric code used where a status word carries the kind (0 = idle).
    pub const fn code(self) -> u16 {
        match self {
            CommandKind::MoveAbsolute => 1,
            CommandKind::MoveRelative => 2,
            CommandKind::MoveVelocity => 3,
            CommandKind::Home => 4,
            CommandKind::External => 5,
        }
    }
}

/// Direction of travel or of a limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    Positive,
    Negative,
}

impl std::fmt::Display for Direction {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Direction::Positive => "positive",
            Direction::Negative => "negative",
        })
    }
}

/// The name of an [`EngineError`](crate::error::EngineError) variant without its data: `Copy`, so
/// it fits in status records and traces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorKind {
    InvalidAxis,
    UnknownParameter,
    InvalidParameter,
    ReadOnlyParameter,
    InvalidArgument,
    AxisDisabled,
    AxisInError,
    LimitActive,
    QueueFull,
    Unsupported,
    InvalidState,
    CauseStillPresent,
    UnknownCommand,
    Homing,
    Object,
    InvalidSlave,
    InvalidChannel,
    /// Not a refusal: a running command ended because a limit was reached.
    LimitReached,
    /// Not a refusal: a running command ended because of a fault (following error, alarm …).
    Fault,
    /// No such group, or a group definition that cannot be (issue 11).
    InvalidGroup,
    /// The group's state (or a member's) does not allow the command.
    GroupState,
}

impl ErrorKind {
    pub const fn name(self) -> &'static str {
        match self {
            ErrorKind::InvalidAxis => "invalid_axis",
            ErrorKind::UnknownParameter => "unknown_parameter",
            ErrorKind::InvalidParameter => "invalid_parameter",
            ErrorKind::ReadOnlyParameter => "read_only_parameter",
            ErrorKind::InvalidArgument => "invalid_argument",
            ErrorKind::AxisDisabled => "axis_disabled",
            ErrorKind::AxisInError => "axis_in_error",
            ErrorKind::LimitActive => "limit_active",
            ErrorKind::QueueFull => "queue_full",
            ErrorKind::Unsupported => "unsupported",
            ErrorKind::InvalidState => "invalid_state",
            ErrorKind::CauseStillPresent => "cause_still_present",
            ErrorKind::UnknownCommand => "unknown_command",
            ErrorKind::Homing => "homing",
            ErrorKind::Object => "object",
            ErrorKind::InvalidSlave => "invalid_slave",
            ErrorKind::InvalidChannel => "invalid_channel",
            ErrorKind::LimitReached => "limit_reached",
            ErrorKind::Fault => "fault",
            ErrorKind::InvalidGroup => "invalid_group",
            ErrorKind::GroupState => "group_state",
        }
    }
}
