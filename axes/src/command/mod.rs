//! Commands into the engine, and the replies and errors that come back (ARCHITECTURE §3.5).
//!
//! Front-ends change the engine only through [`Command`] values and get back
//! `Result<Reply, EngineError>`. The JSON/TOML shape of `Command` (tag `type`, snake_case) is the
//! one scenarios and the control API use, so it is part of mcemu's public interface.

use serde::{Deserialize, Serialize};

use crate::od::Value;

// Defined below `command` in the module chain (docs/architecture.md) and re-exported here, so
// that `axes::command::EngineError` and friends keep their paths.
pub use crate::error::EngineError;
pub use crate::types::{
    AxisIndex, CommandId, CommandKind, CoordinateSystem, Direction, ErrorKind, GroupId,
    MasterSource, StreamMode,
};

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
    /// Decelerate with `fast_decel`; latches nothing (NMC_MtAbruptStop, HIMC StopAll's kill
    /// deceleration).
    Abrupt,
    /// Decelerate with `fast_decel` and latch `ESTOP`: the axis needs a reset before it moves
    /// again (NMC_MtEstp).
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

mod add_axis;
mod axis;
mod compensation;
mod coupling;
mod follow;
mod gantry;
mod group;
mod group_frames;
mod group_io;
mod group_jog;
mod guard;
mod handwheel;
mod io;
mod machine;
mod sampling;
mod slave;
mod stream;
mod superimpose;
mod trigger;
mod wire;

pub use add_axis::AddAxisSet;
pub use axis::{
    AxisCommand, Cancel, Disable, Enable, ForceInput, GetParameter, Halt, Home,
    InjectFollowingError, ModifyTarget, MoveAbsolute, MoveRelative, MoveVelocity, Reset,
    ResetFaults, Resume, SetParameter, SetPosition, Stop, StreamSetpoint,
};
pub use compensation::{
    BacklashDirection, CompensationBacklash, CompensationClear, CompensationCommand,
    CompensationDisable, CompensationEnable, CompensationInterpolation, CompensationKind,
    CompensationLeadScrew, CompensationOffsetAmount, CompensationOffsetProfile,
    CompensationOffsetStop, CompensationOffsetTrigger, CompensationReference, CompensationTable,
    FilterDisable, FilterInputShaping, FilterVsf, ReferenceSource,
};
pub use coupling::{
    CamIn, CamInterpolation, CamOut, CamPoint, CamTableDefine, CamTableLink, CouplingCommand,
    FollowSegment, GearIn, GearOut, GearSetRatio,
};
pub use follow::{
    FollowClear, FollowConfig, FollowDirection, FollowEvent, FollowOut, FollowPush, FollowStart,
    FollowSwitch, FOLLOW_FIFOS, FOLLOW_FIFO_SEGMENTS,
};
pub use gantry::{
    GantryDisable, GantryEnable, GantryHome, GantrySetPid, GantrySetPosition, MAX_GANTRY_HOME_AXES,
    MAX_GANTRY_SLAVES,
};
pub use group::{
    ArcDirection, CircleMode, CoordinateSet, GroupAxisMove, GroupBufferMode, GroupCommand,
    GroupContinue, GroupCreate, GroupDelete, GroupDisable, GroupDwell, GroupEmergencyStop,
    GroupEnable, GroupHalt, GroupParameter, GroupReset, GroupSetOrigin, GroupSetOutput,
    GroupSetOverride, GroupSetParameter, GroupStop, GroupWaitInput, GroupWaitPosition,
    MoveCircularAbsolute, MoveCircularAngle, MoveCircularRelative, MoveEllipse, MoveLinearAbsolute,
    MoveLinearRelative, MoveSpline, PositionCondition, TransitionMode,
};
pub use group_frames::{GroupDeletePolarTransform, GroupSetPolarTransform};
pub use group_frames::{
    GroupDeleteTransform, GroupSetCoordinateSystem, GroupSetCoordinateTransform,
    GroupSetRotaryTransform, GroupSetXyzaTransform, MoveProtectionDisable, MoveProtectionEnable,
    ProtectionMode,
};
pub use group_io::{GroupBufferedHalt, GroupPulseOutput, GroupSetAnalogOutput, GroupStopInput};
pub use group_jog::{GroupJog, GroupJogAxis};
pub use guard::{
    GuardInput, InputStopClear, InputStopSet, OutputLevel, PositionWatchClear, PositionWatchSet,
    WatchdogKick, WatchdogSet, MAX_INPUT_STOPS,
};
pub use handwheel::{
    HandwheelExcess, HandwheelIn, HandwheelOut, HandwheelSetRatio, HandwheelTurn,
    HANDWHEEL_EXTERNAL_BASE, HANDWHEEL_EXTERNAL_ENCODERS,
};
pub use io::{
    AnalogSource, BindAnalogOutput, ForceAnalogInput, ForceDigitalInput, IoCommand,
    PulseDigitalOutput, WriteAnalogOutput, WriteDigitalOutput,
};
pub use machine::{
    DisableAll, EmergencyStopAll, EnableAll, EstimateGroupTime, GetCommandState, MachineCommand,
    MoveTogether, ResetAll, SetEstopInput, StopAll, StopAxes, TogetherMove,
};
pub use sampling::{
    SampledVariable, SamplerId, SamplingCommand, SamplingConfigure, SamplingRead, SamplingStart,
    SamplingStop, SamplingTrigger, SamplingTriggerNow, MAX_SAMPLED_VARIABLES, MAX_SAMPLERS,
    MAX_SAMPLE_VALUES,
};
pub use slave::{ReadObject, SlaveCommand, WriteObject};
pub use stream::{
    PtKind, PtPoint, PtPush, PvtMove, PvtPoint, PvtPush, StreamClear, StreamCommand, StreamConfig,
    StreamStart, StreamStartOnInput, MAX_PUSH_POINTS, MAX_PVT_MOVE_POINTS,
};
pub use superimpose::{
    SafeZMode, SuperimposeIn, SuperimposeOut, SuperimposeSetRatios, TangentialCornerContinue,
    TangentialCornerFollowNext, TangentialCornerMode, TangentialCornerModeKind, TangentialIn,
    TangentialOut,
};
pub use trigger::{
    CaptureArm, CaptureArmThreshold, CaptureClear, CaptureEdge, CaptureSource, CaptureWindow,
    CompareFire, CompareOutputMode, CompareStart, CompareStop, PositionSource, TriggerCommand,
    ZCompareStart, ZCompareStop,
};

/// A command into the engine, by family: what it addresses decides which stage of the engine
/// takes it ([`crate::Engine::apply`] dispatches on the family).
///
/// On the wire (JSON, TOML) a command is one flat object with `type` as the tag, e.g.
/// `{ "type": "move_absolute", "axis": 0, "position": 100.0 }`: the families are a Rust-side
/// grouping only, and the JSON is the same as before they existed (`axes/tests/command_json.rs`
/// pins it). Each command's fields are written once, in its struct (e.g. [`MoveAbsolute`]); the
/// family enums and the flat wire form wrap those structs.
///
/// Kinematic limits given in a command (`velocity`, `acceleration`, `deceleration`, `jerk`) apply
/// to that command only; where they are absent the axis parameters (`speed`, `accel`, `decel`,
/// `jerk`, `jerk_mode`) apply. `jerk = 0` asks for a trapezoid.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(from = "wire::Command", into = "wire::Command")]
pub enum Command {
    /// One axis: power, single-axis motion, homing, parameters, its simulated inputs, its
    /// setpoint stream.
    Axis(AxisCommand),
    /// Coordinated groups of axes (issue 11: `group_create`, `move_linear_absolute` …).
    Group(GroupCommand),
    /// Axis couplings: gear and cam (issue 12: `gear_in` …).
    Coupling(CouplingCommand),
    /// Corrections after the planner on one axis (issue 12 item 8: `compensation_set` …).
    Compensation(CompensationCommand),
    /// Data sampling into bounded buffers (issue 12 item 9: `sampling_configure` …).
    Sampling(SamplingCommand),
    /// The machine's digital and analog I/O image.
    Io(IoCommand),
    /// Capture channels and position-compare outputs (issue 12 items 4–5).
    Trigger(TriggerCommand),
    /// The object dictionaries of the CiA 402 drives on the engine's fieldbus.
    Slave(SlaveCommand),
    /// Machine-wide: queries across all axes (command states), and commands on several or all
    /// axes at once (start together, stop, enable, disable, emergency stop, reset all).
    Machine(MachineCommand),
    /// PT and PVT streams per axis (issue 12 item 3: `pt_push`, `stream_start` …).
    Stream(StreamCommand),
}

impl Command {
    /// The axis the command addresses, if it addresses one.
    pub fn axis(&self) -> Option<AxisIndex> {
        match self {
            Command::Axis(c) => Some(c.axis()),
            Command::Coupling(c) => c.axis(),
            Command::Trigger(TriggerCommand::CaptureArm(c)) => Some(c.axis),
            Command::Trigger(TriggerCommand::CaptureClear(c)) => Some(c.axis),
            Command::Trigger(TriggerCommand::CompareStart(c)) => Some(c.axis),
            Command::Trigger(TriggerCommand::CaptureArmThreshold(c)) => Some(c.axis),
            Command::Trigger(TriggerCommand::ZCompareStart(c)) => Some(c.axis),
            Command::Compensation(c) => Some(c.axis()),
            Command::Trigger(
                TriggerCommand::CompareStop(_)
                | TriggerCommand::CompareFire(_)
                | TriggerCommand::ZCompareStop(_),
            )
            | Command::Sampling(_)
            | Command::Group(_)
            | Command::Io(_)
            | Command::Slave(_)
            | Command::Machine(_) => None,
            Command::Stream(c) => c.axis(),
        }
    }
}

/// `impl From<$member> for $family` and `for Command`, so that a command struct converts into
/// the command it is (`Command::from(Enable { axis: 0 })`).
macro_rules! command_from {
    ($family:ident, $variant:ident, [$($member:ident => $member_variant:ident),* $(,)?]) => {
        impl From<$family> for $crate::command::Command {
            fn from(c: $family) -> $crate::command::Command {
                $crate::command::Command::$variant(c)
            }
        }
        $(
            impl From<$member> for $family {
                fn from(c: $member) -> $family {
                    $family::$member_variant(c)
                }
            }
            impl From<$member> for $crate::command::Command {
                fn from(c: $member) -> $crate::command::Command {
                    $crate::command::Command::$variant($family::$member_variant(c))
                }
            }
        )*
    };
}
pub(crate) use command_from;

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
    /// Several motion commands were accepted together (`move_together`): their ids, in the
    /// order of the moves.
    AcceptedAll {
        ids: Vec<CommandId>,
    },
    /// Recorded samples (`sampling_read`): `values` row by row, `variables` values per row,
    /// the first row being sample `from`.
    Samples {
        sampler: u16,
        from: u32,
        variables: u32,
        values: Vec<f64>,
    },
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

/// A number within ±[`MAX_MAGNITUDE`] and ≥ 0 (tolerances, corner distances, jerk where 0
/// means none).
pub(crate) fn nonnegative(name: &'static str, value: f64) -> Result<f64, EngineError> {
    let value = bounded(name, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(EngineError::InvalidArgument {
            name,
            value,
            reason: "must be ≥ 0",
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
