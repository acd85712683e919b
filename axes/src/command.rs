//! Commands into the engine, and the replies and errors that come back (ARCHITECTURE §3.5).
//!
//! Front-ends change the engine only through [`Command`] values and get back
//! `Result<Reply, EngineError>`. The JSON/TOML shape of `Command` (tag `type`, snake_case) is the
//! one scenarios and the control API use, so it is part of mcemu's public interface.

use serde::{Deserialize, Serialize};

use crate::homing::{HomingError, HomingQuirks};
use crate::od::{OdError, Value};
use crate::param::ParamId;
use crate::status::{AxisFlags, AxisState};

/// Index of an axis in the machine, from 0.
pub type AxisIndex = u16;

/// Identifier of a queued motion command. Engine-wide, increasing from 1; 0 is never used.
pub type CommandId = u32;

/// PLCopen buffer mode of a motion command (ARCHITECTURE §3.5).
///
/// Blending modes (Low/Previous/Next/High) arrive with multi-axis motion; the FIFO already keeps
/// the queued commands a look-ahead needs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BufferMode {
    /// Abort what the axis is doing (and everything queued) and start now.
    #[default]
    Aborting,
    /// Append to the axis FIFO; start when the commands before it are done (HMC §2.2).
    Buffered,
}

/// How a stop decelerates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopMode {
    /// Decelerate with the command's deceleration, else the axis `decel` (NMC_MtStop, MC_Stop).
    #[default]
    Smooth,
    /// Decelerate with `fast_decel`; latches nothing (NMC_MtAbruptStop).
    Abrupt,
    /// Decelerate with `fast_decel` and latch `ESTOP`: the axis needs a reset before it moves
    /// again (NMC_MtEstp, HIMC StopAll).
    Emergency,
    /// Velocity jumps to zero in the current tick (CPU 226H E_STOP, HMC CancelMode 2).
    Immediate,
}

/// Which coordinate `set_position` redefines. Redefining never moves the motor.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PositionFrame {
    /// Commanded and actual position shift together; the following error is kept (HMC_DefPos).
    #[default]
    Both,
    /// Only the commanded (planned) position (NMC_MtSetAxisPos).
    Commanded,
    /// Only the actual (encoder) position (NMC_MtSetEncPos).
    Actual,
}

/// Which queued commands `cancel` removes (HMC_Cancel, HMC §4.2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CancelScope {
    /// The command after the running one.
    Next,
    /// The running command (it stops with `decel`); the next one then starts.
    #[default]
    Current,
    /// The running command and everything queued.
    All,
}

/// A simulated input of one axis that the control API or a scenario can force.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisInput {
    LimitPos,
    LimitNeg,
    Home,
    Index,
    /// The drive's alarm output as seen by the controller.
    DriveAlarm,
    /// Encoder feedback lost: counts freeze while the motor may still move.
    EncoderLoss,
}

/// A command into the engine. Serialized with `type` as the tag, e.g.
/// `{ "type": "move_absolute", "axis": 0, "position": 100.0 }`.
///
/// Kinematic limits given in a command (`velocity`, `acceleration`, `deceleration`, `jerk`) apply
/// to that command only; where they are absent the axis parameters (`speed`, `accel`, `decel`,
/// `jerk`, `jerk_mode`) apply. `jerk = 0` asks for a trapezoid.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum Command {
    /// Power the drive (PLCopen MC_Power on).
    Enable {
        axis: AxisIndex,
    },
    /// Remove drive power; the motor coasts to the plant's rest, the FIFO is cleared.
    Disable {
        axis: AxisIndex,
    },
    /// Clear latched errors whose cause is gone; leave ErrorStop when none remain.
    Reset {
        axis: AxisIndex,
    },
    MoveAbsolute {
        axis: AxisIndex,
        position: f64,
        #[serde(default)]
        velocity: Option<f64>,
        #[serde(default)]
        acceleration: Option<f64>,
        #[serde(default)]
        deceleration: Option<f64>,
        #[serde(default)]
        jerk: Option<f64>,
        #[serde(default)]
        buffer_mode: BufferMode,
    },
    MoveRelative {
        axis: AxisIndex,
        distance: f64,
        #[serde(default)]
        velocity: Option<f64>,
        #[serde(default)]
        acceleration: Option<f64>,
        #[serde(default)]
        deceleration: Option<f64>,
        #[serde(default)]
        jerk: Option<f64>,
        #[serde(default)]
        buffer_mode: BufferMode,
    },
    /// Run at a signed velocity until stopped (jog; HMC_Forward/Reverse, NMC JOG, HIMC MoveVel).
    MoveVelocity {
        axis: AxisIndex,
        velocity: f64,
        #[serde(default)]
        acceleration: Option<f64>,
        #[serde(default)]
        deceleration: Option<f64>,
        #[serde(default)]
        jerk: Option<f64>,
        #[serde(default)]
        buffer_mode: BufferMode,
    },
    /// Stop and clear the FIFO.
    Stop {
        axis: AxisIndex,
        #[serde(default)]
        mode: StopMode,
        #[serde(default)]
        deceleration: Option<f64>,
    },
    /// Pause: decelerate to zero velocity and keep the plan (HIMC Halt).
    Halt {
        axis: AxisIndex,
        #[serde(default)]
        deceleration: Option<f64>,
    },
    /// Continue a halted plan (HIMC Resume).
    Resume {
        axis: AxisIndex,
    },
    /// Home with a CiA 402 method (1–14, 17–30, 33–35, 37). Absent values come from the
    /// `home_*` parameters; vendor modes map onto methods and quirks in `homing::vendor`.
    Home {
        axis: AxisIndex,
        #[serde(default)]
        method: Option<i16>,
        #[serde(default)]
        switch_velocity: Option<f64>,
        #[serde(default)]
        zero_velocity: Option<f64>,
        #[serde(default)]
        acceleration: Option<f64>,
        #[serde(default)]
        offset: Option<f64>,
        /// Seconds; 0 means no timeout.
        #[serde(default)]
        timeout: Option<f64>,
        /// Vendor behaviour layered on the CiA 402 method (see `homing::vendor`).
        #[serde(default)]
        quirks: HomingQuirks,
        #[serde(default)]
        buffer_mode: BufferMode,
    },
    /// Redefine the current position without moving.
    SetPosition {
        axis: AxisIndex,
        position: f64,
        #[serde(default)]
        frame: PositionFrame,
    },
    SetParameter {
        axis: AxisIndex,
        name: ParamId,
        value: f64,
        /// HMC rule (HMC §3.5.1): a negative value is made positive and a zero one restored to
        /// the default, both latching `PARAMETER_ERROR`, instead of being refused.
        #[serde(default)]
        lenient: bool,
    },
    GetParameter {
        axis: AxisIndex,
        name: ParamId,
    },
    /// Change the target of the running position move (HMC_MoveModify / MoveModifyEx). With an
    /// empty FIFO it posts a new move instead.
    ModifyTarget {
        axis: AxisIndex,
        position: f64,
        #[serde(default)]
        relative: bool,
    },
    /// Remove queued or running commands (HMC_Cancel).
    Cancel {
        axis: AxisIndex,
        #[serde(default)]
        scope: CancelScope,
    },
    /// State of a command by id.
    CommandState {
        id: CommandId,
    },
    /// Force an axis input to a level, or release it to the simulation (`value` absent).
    ForceInput {
        axis: AxisIndex,
        input: AxisInput,
        #[serde(default)]
        value: Option<bool>,
    },
    /// Force a digital input channel, or release it (`value` absent).
    ForceDigitalInput {
        channel: u16,
        #[serde(default)]
        value: Option<bool>,
    },
    /// Set an analog input channel, or release it (`value` absent).
    ForceAnalogInput {
        channel: u16,
        #[serde(default)]
        value: Option<f64>,
    },
    WriteDigitalOutput {
        channel: u16,
        value: bool,
    },
    WriteAnalogOutput {
        channel: u16,
        value: f64,
    },
    /// Add `amount` user units between commanded and actual position, or remove it (`None`).
    InjectFollowingError {
        axis: AxisIndex,
        #[serde(default)]
        amount: Option<f64>,
    },
    /// Drive the axis from an external setpoint stream (CiA 402 CSP/CSV/CST, HMC_SetDposSwitch):
    /// the FIFO pauses while a stream is active; `setpoint` absent ends the stream. The axis is
    /// in SynchronizedMotion while streaming.
    Setpoint {
        axis: AxisIndex,
        #[serde(default)]
        setpoint: Option<Setpoint>,
    },
    /// Read an object of a slave's object dictionary.
    ReadObject {
        slave: u16,
        index: u16,
        subindex: u8,
    },
    /// Write an object of a slave's object dictionary.
    WriteObject {
        slave: u16,
        index: u16,
        subindex: u8,
        value: Value,
    },
}

impl Command {
    /// The axis the command addresses, if it addresses one.
    pub fn axis(&self) -> Option<AxisIndex> {
        use Command::*;
        match self {
            Enable { axis }
            | Disable { axis }
            | Reset { axis }
            | MoveAbsolute { axis, .. }
            | MoveRelative { axis, .. }
            | MoveVelocity { axis, .. }
            | Stop { axis, .. }
            | Halt { axis, .. }
            | Resume { axis }
            | Home { axis, .. }
            | SetPosition { axis, .. }
            | SetParameter { axis, .. }
            | GetParameter { axis, .. }
            | ModifyTarget { axis, .. }
            | Cancel { axis, .. }
            | ForceInput { axis, .. }
            | InjectFollowingError { axis, .. }
            | Setpoint { axis, .. } => Some(*axis),
            CommandState { .. }
            | ForceDigitalInput { .. }
            | ForceAnalogInput { .. }
            | WriteDigitalOutput { .. }
            | WriteAnalogOutput { .. }
            | ReadObject { .. }
            | WriteObject { .. } => None,
        }
    }
}

/// One cycle's setpoint from an external master.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "mode", rename_all = "snake_case")]
pub enum Setpoint {
    /// Cyclic synchronous position, user units.
    Position { position: f64 },
    /// Cyclic synchronous velocity, user units/s.
    Velocity { velocity: f64 },
    /// Cyclic synchronous torque as a fraction of rated torque (1.0 = 100 %).
    Torque { torque: f64 },
}

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

/// Lifecycle of a motion command (HMC §2.2 HMC_GetCmdState).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CommandState {
    /// Queued behind the running command.
    Waiting,
    /// At the FIFO head, executing.
    Running,
    /// Finished normally.
    Done,
    /// Removed by a stop, cancel, aborting command, disable or fault before it finished.
    Aborted,
    /// Ended by an error (limit, fault, homing failure).
    Error(ErrorKind),
}

/// A successful reply.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "reply", rename_all = "snake_case")]
pub enum Reply {
    /// Done at once (enable, set parameter, stop issued, …).
    Done,
    /// A motion command was accepted: queued or started. Zero-length buffered moves reuse the id
    /// of the zero-length move just before them (HMC §10.7).
    Accepted {
        id: CommandId,
    },
    Value {
        value: f64,
    },
    CommandState {
        id: CommandId,
        state: CommandState,
    },
    Object {
        value: Value,
    },
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
}

/// The name of an [`EngineError`] variant without its data: `Copy`, so it fits in status records
/// and traces.
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
        }
    }
}

impl EngineError {
    pub fn kind(&self) -> ErrorKind {
        match self {
            EngineError::InvalidAxis { .. } => ErrorKind::InvalidAxis,
            EngineError::UnknownParameter { .. } => ErrorKind::UnknownParameter,
            EngineError::InvalidParameter { .. } => ErrorKind::InvalidParameter,
            EngineError::ReadOnlyParameter { .. } => ErrorKind::ReadOnlyParameter,
            EngineError::InvalidArgument { .. } => ErrorKind::InvalidArgument,
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
        }
    }
}

/// Largest magnitude of a position, distance, velocity or offset a command may carry, in user
/// units (per second): far beyond any machine, and small enough that position × scale stays
/// well inside f64 precision and the 64-bit pulse and encoder counters.
pub const MAX_MAGNITUDE: f64 = 1e12;

/// A finite number within ±[`MAX_MAGNITUDE`]: positions, distances, velocities, offsets.
pub(crate) fn bounded(name: &'static str, value: f64) -> Result<f64, EngineError> {
    let value = finite(name, value)?;
    if value.abs() <= MAX_MAGNITUDE {
        Ok(value)
    } else {
        Err(EngineError::InvalidArgument {
            name,
            value,
            reason: "outside ±1e12 user units",
        })
    }
}

/// Check that a number from a command is finite (and optionally positive) before it reaches a
/// planner. NaN and infinities never get past the front door.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, EngineError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(EngineError::InvalidArgument {
            name,
            value,
            reason: "must be a finite number",
        })
    }
}

/// A finite, strictly positive number.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, EngineError> {
    let value = finite(name, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(EngineError::InvalidArgument {
            name,
            value,
            reason: "must be greater than zero",
        })
    }
}
