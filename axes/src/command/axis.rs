//! The axis family: commands that address one axis.

use serde::{Deserialize, Serialize};

use super::{
    command_from, AxisIndex, AxisInput, BufferMode, CancelScope, PositionFrame, Setpoint, StopMode,
};
use crate::homing::HomingQuirks;
use crate::param::ParamId;
use crate::status::AxisFlags;

/// Power the drive (PLCopen MC_Power on).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Enable {
    pub axis: AxisIndex,
}

/// Remove drive power; the motor coasts to the plant's rest, the FIFO is cleared.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Disable {
    pub axis: AxisIndex,
}

/// Clear latched errors whose cause is gone; leave ErrorStop when none remain.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Reset {
    pub axis: AxisIndex,
}

/// Clear only the latched faults in `faults` whose cause is gone (NMC_MtClrStsByBits); the
/// other latches stay. A fault of `faults` whose cause remains stays latched and is reported.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResetFaults {
    pub axis: AxisIndex,
    pub faults: AxisFlags,
}

/// Move to an absolute position (PLCopen MC_MoveAbsolute).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveAbsolute {
    pub axis: AxisIndex,
    pub position: f64,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: BufferMode,
}

/// Move by a distance (PLCopen MC_MoveRelative).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveRelative {
    pub axis: AxisIndex,
    pub distance: f64,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: BufferMode,
}

/// Run at a signed velocity until stopped (jog; HMC_Forward/Reverse, NMC JOG, HIMC MoveVel).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveVelocity {
    pub axis: AxisIndex,
    pub velocity: f64,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: BufferMode,
}

/// Stop and clear the FIFO.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stop {
    pub axis: AxisIndex,
    #[serde(default)]
    pub mode: StopMode,
    #[serde(default)]
    pub deceleration: Option<f64>,
}

/// Pause: decelerate to zero velocity and keep the plan (HIMC Halt).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Halt {
    pub axis: AxisIndex,
    #[serde(default)]
    pub deceleration: Option<f64>,
}

/// Continue a halted plan (HIMC Resume).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Resume {
    pub axis: AxisIndex,
}

/// Home with a CiA 402 method (1–14, 17–30, 33–35, 37). Absent values come from the
/// `home_*` parameters; vendor modes map onto methods and quirks in `homing::vendor`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Home {
    pub axis: AxisIndex,
    #[serde(default)]
    pub method: Option<i16>,
    #[serde(default)]
    pub switch_velocity: Option<f64>,
    #[serde(default)]
    pub zero_velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub offset: Option<f64>,
    /// Seconds; 0 means no timeout.
    #[serde(default)]
    pub timeout: Option<f64>,
    /// Vendor behaviour layered on the CiA 402 method (see `homing::vendor`).
    #[serde(default)]
    pub quirks: HomingQuirks,
    #[serde(default)]
    pub buffer_mode: BufferMode,
}

impl Home {
    /// `home` of `axis` with every setting of `spec` (a vendor mode mapped by
    /// `homing::vendor`), aborting.
    pub fn with_spec(axis: AxisIndex, spec: &crate::homing::HomingSpec) -> Home {
        Home {
            axis,
            method: Some(spec.method),
            switch_velocity: Some(spec.switch_velocity),
            zero_velocity: Some(spec.zero_velocity),
            acceleration: Some(spec.acceleration),
            offset: Some(spec.offset),
            timeout: Some(spec.timeout),
            quirks: spec.quirks,
            buffer_mode: BufferMode::default(),
        }
    }
}

/// Redefine the current position without moving.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SetPosition {
    pub axis: AxisIndex,
    pub position: f64,
    #[serde(default)]
    pub frame: PositionFrame,
}

/// Write an axis parameter.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SetParameter {
    pub axis: AxisIndex,
    pub name: ParamId,
    pub value: f64,
    /// HMC rule (HMC §3.5.1): a negative value is made positive and a zero one restored to
    /// the default, both latching `PARAMETER_ERROR`, instead of being refused.
    #[serde(default)]
    pub lenient: bool,
}

/// Read an axis parameter.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GetParameter {
    pub axis: AxisIndex,
    pub name: ParamId,
}

/// Change the target of the running position move (HMC_MoveModify / MoveModifyEx). With an
/// empty FIFO it posts a new move instead.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModifyTarget {
    pub axis: AxisIndex,
    pub position: f64,
    #[serde(default)]
    pub relative: bool,
}

/// Remove queued or running commands (HMC_Cancel).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cancel {
    pub axis: AxisIndex,
    #[serde(default)]
    pub scope: CancelScope,
}

/// Force an axis input to a level, or release it to the simulation (`value` absent).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceInput {
    pub axis: AxisIndex,
    pub input: AxisInput,
    #[serde(default)]
    pub value: Option<bool>,
}

/// Add `amount` user units between commanded and actual position, or remove it (`None`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InjectFollowingError {
    pub axis: AxisIndex,
    #[serde(default)]
    pub amount: Option<f64>,
}

/// Drive the axis from an external setpoint stream (CiA 402 CSP/CSV/CST, HMC_SetDposSwitch):
/// the FIFO pauses while a stream is active; `setpoint` absent ends the stream. The axis is
/// in SynchronizedMotion while streaming. JSON `type`: `setpoint`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StreamSetpoint {
    pub axis: AxisIndex,
    #[serde(default)]
    pub setpoint: Option<Setpoint>,
}

/// A command that addresses one axis. [`crate::Engine::apply`] hands it to that axis (through
/// the axis's drive first where the engine masters one, for power commands).
#[derive(Clone, Debug, PartialEq)]
pub enum AxisCommand {
    Enable(Enable),
    Disable(Disable),
    Reset(Reset),
    MoveAbsolute(MoveAbsolute),
    MoveRelative(MoveRelative),
    MoveVelocity(MoveVelocity),
    Stop(Stop),
    Halt(Halt),
    Resume(Resume),
    Home(Home),
    SetPosition(SetPosition),
    SetParameter(SetParameter),
    GetParameter(GetParameter),
    ModifyTarget(ModifyTarget),
    Cancel(Cancel),
    ForceInput(ForceInput),
    InjectFollowingError(InjectFollowingError),
    Setpoint(StreamSetpoint),
    ResetFaults(ResetFaults),
}

impl AxisCommand {
    /// The axis the command addresses.
    pub fn axis(&self) -> AxisIndex {
        match self {
            AxisCommand::Enable(Enable { axis })
            | AxisCommand::Disable(Disable { axis })
            | AxisCommand::Reset(Reset { axis })
            | AxisCommand::MoveAbsolute(MoveAbsolute { axis, .. })
            | AxisCommand::MoveRelative(MoveRelative { axis, .. })
            | AxisCommand::MoveVelocity(MoveVelocity { axis, .. })
            | AxisCommand::Stop(Stop { axis, .. })
            | AxisCommand::Halt(Halt { axis, .. })
            | AxisCommand::Resume(Resume { axis })
            | AxisCommand::Home(Home { axis, .. })
            | AxisCommand::SetPosition(SetPosition { axis, .. })
            | AxisCommand::SetParameter(SetParameter { axis, .. })
            | AxisCommand::GetParameter(GetParameter { axis, .. })
            | AxisCommand::ModifyTarget(ModifyTarget { axis, .. })
            | AxisCommand::Cancel(Cancel { axis, .. })
            | AxisCommand::ForceInput(ForceInput { axis, .. })
            | AxisCommand::InjectFollowingError(InjectFollowingError { axis, .. })
            | AxisCommand::Setpoint(StreamSetpoint { axis, .. })
            | AxisCommand::ResetFaults(ResetFaults { axis, .. }) => *axis,
        }
    }
}

command_from!(
    AxisCommand,
    Axis,
    [
        Enable => Enable,
        Disable => Disable,
        Reset => Reset,
        MoveAbsolute => MoveAbsolute,
        MoveRelative => MoveRelative,
        MoveVelocity => MoveVelocity,
        Stop => Stop,
        Halt => Halt,
        Resume => Resume,
        Home => Home,
        SetPosition => SetPosition,
        SetParameter => SetParameter,
        GetParameter => GetParameter,
        ModifyTarget => ModifyTarget,
        Cancel => Cancel,
        ForceInput => ForceInput,
        InjectFollowingError => InjectFollowingError,
        StreamSetpoint => Setpoint,
        ResetFaults => ResetFaults,
    ]
);
