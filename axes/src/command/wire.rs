//! The flat wire form of [`super::Command`]: one internally tagged enum in the order the
//! variants had before the families existed. The order matters: serde lists the variants in that order in its
//! "unknown variant" message, which the control API and the scenario loader show to users.

use serde::{Deserialize, Serialize};

use super::StreamStartOnInput;
use super::{
    AxisCommand, Cancel, Disable, DisableAll, EmergencyStopAll, Enable, EnableAll,
    ForceAnalogInput, ForceDigitalInput, ForceInput, GetCommandState, GetParameter, Halt, Home,
    InjectFollowingError, IoCommand, MachineCommand, ModifyTarget, MoveAbsolute, MoveRelative,
    MoveTogether, MoveVelocity, PulseDigitalOutput, ReadObject, Reset, ResetAll, Resume,
    SetParameter, SetPosition, SlaveCommand, Stop, StopAll, StopAxes, StreamSetpoint,
    WriteAnalogOutput, WriteDigitalOutput, WriteObject,
};
use super::{
    CamIn, CamOut, CamTableDefine, CouplingCommand, GantryDisable, GantryEnable, GearIn, GearOut,
    GearSetRatio, HandwheelIn, HandwheelOut, HandwheelTurn,
};
use super::{
    CaptureArm, CaptureArmThreshold, CaptureClear, CompareFire, CompareStart, CompareStop,
    TriggerCommand,
};
use super::{
    CompensationBacklash, CompensationClear, CompensationCommand, CompensationDisable,
    CompensationEnable, CompensationLeadScrew, CompensationTable,
};
use super::{
    FollowClear, FollowConfig, FollowOut, FollowPush, FollowStart, FollowSwitch, HandwheelSetRatio,
};
use super::{
    GroupAxisMove, GroupCommand, GroupContinue, GroupCreate, GroupDelete, GroupDisable, GroupDwell,
    GroupEmergencyStop, GroupEnable, GroupHalt, GroupReset, GroupSetOrigin, GroupSetOutput,
    GroupSetOverride, GroupSetParameter, GroupStop, GroupWaitInput, GroupWaitPosition,
    MoveCircularAbsolute, MoveCircularAngle, MoveCircularRelative, MoveEllipse, MoveLinearAbsolute,
    MoveLinearRelative, MoveSpline,
};
use super::{GroupBufferedHalt, GroupPulseOutput, GroupSetAnalogOutput, GroupStopInput};
use super::{
    GroupDeleteTransform, GroupSetCoordinateSystem, GroupSetCoordinateTransform,
    GroupSetRotaryTransform, GroupSetXyzaTransform, MoveProtectionDisable, MoveProtectionEnable,
};
use super::{GroupJog, GroupJogAxis};
use super::{PtPush, PvtMove, PvtPush, StreamClear, StreamCommand, StreamConfig, StreamStart};
use super::{
    SamplingCommand, SamplingConfigure, SamplingRead, SamplingStart, SamplingStop,
    SamplingTriggerNow,
};
use super::{SuperimposeIn, SuperimposeOut, SuperimposeSetRatios, TangentialIn, TangentialOut};

/// Named `Command` like the type it stands for: serde writes this name in "expected internally
/// tagged enum Command" (a `rename` does not change that message).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
// `CommandState` is the JSON tag `command_state`.
#[allow(clippy::enum_variant_names)]
pub(super) enum Command {
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
    CommandState(GetCommandState),
    ForceInput(ForceInput),
    ForceDigitalInput(ForceDigitalInput),
    ForceAnalogInput(ForceAnalogInput),
    WriteDigitalOutput(WriteDigitalOutput),
    WriteAnalogOutput(WriteAnalogOutput),
    InjectFollowingError(InjectFollowingError),
    Setpoint(StreamSetpoint),
    ReadObject(ReadObject),
    WriteObject(WriteObject),
    // Issue 11 item 6, machine-wide commands (appended: the order above is users' error text).
    MoveTogether(MoveTogether),
    StopAxes(StopAxes),
    StopAll(StopAll),
    EnableAll(EnableAll),
    DisableAll(DisableAll),
    EmergencyStopAll(EmergencyStopAll),
    ResetAll(ResetAll),
    GroupCreate(GroupCreate),
    GroupDelete(GroupDelete),
    GroupEnable(GroupEnable),
    GroupDisable(GroupDisable),
    GroupReset(GroupReset),
    MoveLinearAbsolute(MoveLinearAbsolute),
    MoveLinearRelative(MoveLinearRelative),
    MoveCircularAbsolute(MoveCircularAbsolute),
    MoveCircularRelative(MoveCircularRelative),
    GroupStop(GroupStop),
    GroupHalt(GroupHalt),
    GroupContinue(GroupContinue),
    GroupEmergencyStop(GroupEmergencyStop),
    GroupSetOverride(GroupSetOverride),
    GroupSetOrigin(GroupSetOrigin),
    GroupSetParameter(GroupSetParameter),
    GroupSetOutput(GroupSetOutput),
    GroupDwell(GroupDwell),
    GroupWaitInput(GroupWaitInput),
    GroupWaitPosition(GroupWaitPosition),
    GroupAxisMove(GroupAxisMove),
    MoveSpline(MoveSpline),
    MoveEllipse(MoveEllipse),
    GroupSetCoordinateTransform(GroupSetCoordinateTransform),
    GroupSetCoordinateSystem(GroupSetCoordinateSystem),
    GroupSetRotaryTransform(GroupSetRotaryTransform),
    GroupSetXyzaTransform(GroupSetXyzaTransform),
    GroupDeleteTransform(GroupDeleteTransform),
    MoveProtectionEnable(MoveProtectionEnable),
    MoveProtectionDisable(MoveProtectionDisable),
    MoveCircularAngle(MoveCircularAngle),
    GroupJog(GroupJog),
    GroupJogAxis(GroupJogAxis),
    // Issue 12, couplings.
    GearIn(GearIn),
    GearSetRatio(GearSetRatio),
    GearOut(GearOut),
    CamTable(CamTableDefine),
    CamIn(CamIn),
    CamOut(CamOut),
    // Issue 12 items 4–5, capture and position compare.
    CaptureArm(CaptureArm),
    CaptureClear(CaptureClear),
    CompareStart(CompareStart),
    CompareStop(CompareStop),
    // Issue 12 item 3, PT/PVT streams.
    StreamConfig(StreamConfig),
    PtPush(PtPush),
    PvtPush(PvtPush),
    StreamClear(StreamClear),
    StreamStart(StreamStart),
    PvtMove(PvtMove),
    CompensationLeadScrew(CompensationLeadScrew),
    CompensationBacklash(CompensationBacklash),
    CompensationTable(CompensationTable),
    CompensationEnable(CompensationEnable),
    CompensationDisable(CompensationDisable),
    CompensationClear(CompensationClear),
    SamplingConfigure(SamplingConfigure),
    SamplingStart(SamplingStart),
    SamplingTrigger(SamplingTriggerNow),
    SamplingStop(SamplingStop),
    SamplingRead(SamplingRead),
    // Issue 12 item 9, superimposed motion and the tangential axis.
    SuperimposeIn(SuperimposeIn),
    SuperimposeSetRatios(SuperimposeSetRatios),
    SuperimposeOut(SuperimposeOut),
    TangentialIn(TangentialIn),
    TangentialOut(TangentialOut),
    // Issue 12 items 6–7, gantry and handwheel.
    GantryEnable(GantryEnable),
    GantryDisable(GantryDisable),
    HandwheelIn(HandwheelIn),
    HandwheelOut(HandwheelOut),
    HandwheelTurn(HandwheelTurn),
    // Issue 12 item 5, NMC manual compare output.
    CompareFire(CompareFire),
    // Issue 12 items 2 and 7, NMC Follow FIFOs and SetHandWheelRatio.
    FollowConfig(FollowConfig),
    FollowPush(FollowPush),
    FollowClear(FollowClear),
    FollowStart(FollowStart),
    FollowSwitch(FollowSwitch),
    FollowOut(FollowOut),
    HandwheelSetRatio(HandwheelSetRatio),
    StreamStartOnInput(StreamStartOnInput),
    CaptureArmThreshold(CaptureArmThreshold),
    // Issue 12 item 6, HMC_GantryInit.
    GantryHome(super::GantryHome),
    PulseDigitalOutput(PulseDigitalOutput),
    // HMC MoveTang corner mode (digest 000 §4.4).
    TangentialCornerMode(super::TangentialCornerMode),
    TangentialCornerFollowNext(super::TangentialCornerFollowNext),
    TangentialCornerContinue(super::TangentialCornerContinue),
    // HMC MoveLink / MoveFlexLink profiles (digest 000 §4.3).
    CamTableLink(super::CamTableLink),
    // NMC buffered I/O and stops (issue 13).
    GroupPulseOutput(GroupPulseOutput),
    GroupSetAnalogOutput(GroupSetAnalogOutput),
    GroupStopInput(GroupStopInput),
    GroupBufferedHalt(GroupBufferedHalt),
    // Issue 12 item 5, HMC SwitchTZ (Z-phase outputs).
    ZCompareStart(super::ZCompareStart),
    ZCompareStop(super::ZCompareStop),
    // Issue 12 item 6, HMC_GantryGroupDefPos and HMC_SetGantryAxisPID.
    GantrySetPosition(super::GantrySetPosition),
    GantrySetPid(super::GantrySetPid),
    // Issue 12 item 8, HMC axis position compensation.
    CompensationOffsetAmount(super::CompensationOffsetAmount),
    CompensationOffsetProfile(super::CompensationOffsetProfile),
    CompensationOffsetTrigger(super::CompensationOffsetTrigger),
    CompensationOffsetStop(super::CompensationOffsetStop),
    // Issue 13, NMC_MtClrStsByBits.
    ResetFaults(super::ResetFaults),
    // Issue 14, HIMC BindEMO: the E-stop input.
    SetEstopInput(super::SetEstopInput),
    // Issue 13, NMC: the execution-time dry run and the guards.
    EstimateGroupTime(super::EstimateGroupTime),
    WatchdogSet(super::WatchdogSet),
    WatchdogKick(super::WatchdogKick),
    InputStopSet(super::InputStopSet),
    InputStopClear(super::InputStopClear),
    PositionWatchSet(super::PositionWatchSet),
    PositionWatchClear(super::PositionWatchClear),
    // HMC_SetAddAxis (digest 000 §4.4).
    AddAxisSet(super::AddAxisSet),
    // Issue 14, HIMC chapter 15: command filters.
    FilterInputShaping(super::FilterInputShaping),
    FilterVsf(super::FilterVsf),
    FilterDisable(super::FilterDisable),
    // Issue 14, HIMC SetSlvAOParam ao_en_bind 1.
    BindAnalogOutput(super::BindAnalogOutput),
    // Issue 13, NMC CrdSetTransPolar: the polar machine.
    GroupSetPolarTransform(super::GroupSetPolarTransform),
    GroupDeletePolarTransform(super::GroupDeletePolarTransform),
}

impl From<Command> for super::Command {
    fn from(c: Command) -> super::Command {
        match c {
            Command::Enable(c) => super::Command::Axis(AxisCommand::Enable(c)),
            Command::Disable(c) => super::Command::Axis(AxisCommand::Disable(c)),
            Command::Reset(c) => super::Command::Axis(AxisCommand::Reset(c)),
            Command::MoveAbsolute(c) => super::Command::Axis(AxisCommand::MoveAbsolute(c)),
            Command::MoveRelative(c) => super::Command::Axis(AxisCommand::MoveRelative(c)),
            Command::MoveVelocity(c) => super::Command::Axis(AxisCommand::MoveVelocity(c)),
            Command::Stop(c) => super::Command::Axis(AxisCommand::Stop(c)),
            Command::Halt(c) => super::Command::Axis(AxisCommand::Halt(c)),
            Command::Resume(c) => super::Command::Axis(AxisCommand::Resume(c)),
            Command::Home(c) => super::Command::Axis(AxisCommand::Home(c)),
            Command::SetPosition(c) => super::Command::Axis(AxisCommand::SetPosition(c)),
            Command::SetParameter(c) => super::Command::Axis(AxisCommand::SetParameter(c)),
            Command::GetParameter(c) => super::Command::Axis(AxisCommand::GetParameter(c)),
            Command::ModifyTarget(c) => super::Command::Axis(AxisCommand::ModifyTarget(c)),
            Command::Cancel(c) => super::Command::Axis(AxisCommand::Cancel(c)),
            Command::CommandState(c) => super::Command::Machine(MachineCommand::CommandState(c)),
            Command::ForceInput(c) => super::Command::Axis(AxisCommand::ForceInput(c)),
            Command::ForceDigitalInput(c) => super::Command::Io(IoCommand::ForceDigitalInput(c)),
            Command::ForceAnalogInput(c) => super::Command::Io(IoCommand::ForceAnalogInput(c)),
            Command::WriteDigitalOutput(c) => super::Command::Io(IoCommand::WriteDigitalOutput(c)),
            Command::WriteAnalogOutput(c) => super::Command::Io(IoCommand::WriteAnalogOutput(c)),
            Command::PulseDigitalOutput(c) => super::Command::Io(IoCommand::PulseDigitalOutput(c)),
            Command::GroupPulseOutput(c) => super::Command::Group(GroupCommand::PulseOutput(c)),
            Command::GroupSetAnalogOutput(c) => {
                super::Command::Group(GroupCommand::SetAnalogOutput(c))
            }
            Command::GroupStopInput(c) => super::Command::Group(GroupCommand::StopInput(c)),
            Command::GroupBufferedHalt(c) => super::Command::Group(GroupCommand::BufferedHalt(c)),
            Command::InjectFollowingError(c) => {
                super::Command::Axis(AxisCommand::InjectFollowingError(c))
            }
            Command::Setpoint(c) => super::Command::Axis(AxisCommand::Setpoint(c)),
            Command::ReadObject(c) => super::Command::Slave(SlaveCommand::ReadObject(c)),
            Command::WriteObject(c) => super::Command::Slave(SlaveCommand::WriteObject(c)),
            Command::MoveTogether(c) => super::Command::Machine(MachineCommand::MoveTogether(c)),
            Command::StopAxes(c) => super::Command::Machine(MachineCommand::StopAxes(c)),
            Command::StopAll(c) => super::Command::Machine(MachineCommand::StopAll(c)),
            Command::EnableAll(c) => super::Command::Machine(MachineCommand::EnableAll(c)),
            Command::DisableAll(c) => super::Command::Machine(MachineCommand::DisableAll(c)),
            Command::EmergencyStopAll(c) => {
                super::Command::Machine(MachineCommand::EmergencyStopAll(c))
            }
            Command::ResetAll(c) => super::Command::Machine(MachineCommand::ResetAll(c)),
            Command::GantryHome(c) => super::Command::Machine(MachineCommand::GantryHome(c)),
            Command::EstimateGroupTime(c) => {
                super::Command::Machine(MachineCommand::EstimateGroupTime(c))
            }
            Command::WatchdogSet(c) => super::Command::Machine(MachineCommand::WatchdogSet(c)),
            Command::WatchdogKick(c) => super::Command::Machine(MachineCommand::WatchdogKick(c)),
            Command::InputStopSet(c) => super::Command::Machine(MachineCommand::InputStopSet(c)),
            Command::InputStopClear(c) => {
                super::Command::Machine(MachineCommand::InputStopClear(c))
            }
            Command::PositionWatchSet(c) => {
                super::Command::Machine(MachineCommand::PositionWatchSet(c))
            }
            Command::PositionWatchClear(c) => {
                super::Command::Machine(MachineCommand::PositionWatchClear(c))
            }
            Command::GroupCreate(c) => super::Command::Group(GroupCommand::Create(c)),
            Command::GroupDelete(c) => super::Command::Group(GroupCommand::Delete(c)),
            Command::GroupEnable(c) => super::Command::Group(GroupCommand::Enable(c)),
            Command::GroupDisable(c) => super::Command::Group(GroupCommand::Disable(c)),
            Command::GroupReset(c) => super::Command::Group(GroupCommand::Reset(c)),
            Command::MoveLinearAbsolute(c) => {
                super::Command::Group(GroupCommand::MoveLinearAbsolute(c))
            }
            Command::MoveLinearRelative(c) => {
                super::Command::Group(GroupCommand::MoveLinearRelative(c))
            }
            Command::MoveCircularAbsolute(c) => {
                super::Command::Group(GroupCommand::MoveCircularAbsolute(c))
            }
            Command::MoveCircularRelative(c) => {
                super::Command::Group(GroupCommand::MoveCircularRelative(c))
            }
            Command::GroupStop(c) => super::Command::Group(GroupCommand::Stop(c)),
            Command::GroupHalt(c) => super::Command::Group(GroupCommand::Halt(c)),
            Command::GroupContinue(c) => super::Command::Group(GroupCommand::Continue(c)),
            Command::GroupEmergencyStop(c) => super::Command::Group(GroupCommand::EmergencyStop(c)),
            Command::GroupSetOverride(c) => super::Command::Group(GroupCommand::SetOverride(c)),
            Command::GroupSetOrigin(c) => super::Command::Group(GroupCommand::SetOrigin(c)),
            Command::GroupSetParameter(c) => super::Command::Group(GroupCommand::SetParameter(c)),
            Command::GroupSetOutput(c) => super::Command::Group(GroupCommand::SetOutput(c)),
            Command::GroupDwell(c) => super::Command::Group(GroupCommand::Dwell(c)),
            Command::GroupWaitInput(c) => super::Command::Group(GroupCommand::WaitInput(c)),
            Command::GroupWaitPosition(c) => super::Command::Group(GroupCommand::WaitPosition(c)),
            Command::GroupAxisMove(c) => super::Command::Group(GroupCommand::AxisMove(c)),
            Command::MoveSpline(c) => super::Command::Group(GroupCommand::MoveSpline(c)),
            Command::MoveEllipse(c) => super::Command::Group(GroupCommand::MoveEllipse(c)),
            Command::MoveCircularAngle(c) => {
                super::Command::Group(GroupCommand::MoveCircularAngle(c))
            }
            Command::GroupSetCoordinateTransform(c) => {
                super::Command::Group(GroupCommand::SetCoordinateTransform(c))
            }
            Command::GroupSetCoordinateSystem(c) => {
                super::Command::Group(GroupCommand::SetCoordinateSystem(c))
            }
            Command::GroupSetRotaryTransform(c) => {
                super::Command::Group(GroupCommand::SetRotaryTransform(c))
            }
            Command::GroupSetXyzaTransform(c) => {
                super::Command::Group(GroupCommand::SetXyzaTransform(c))
            }
            Command::GroupDeleteTransform(c) => {
                super::Command::Group(GroupCommand::DeleteTransform(c))
            }
            Command::MoveProtectionEnable(c) => {
                super::Command::Group(GroupCommand::ProtectionEnable(c))
            }
            Command::MoveProtectionDisable(c) => {
                super::Command::Group(GroupCommand::ProtectionDisable(c))
            }
            Command::GroupJog(c) => super::Command::Group(GroupCommand::Jog(c)),
            Command::GroupJogAxis(c) => super::Command::Group(GroupCommand::JogAxis(c)),
            Command::GearIn(c) => super::Command::Coupling(CouplingCommand::GearIn(c)),
            Command::GearSetRatio(c) => super::Command::Coupling(CouplingCommand::GearSetRatio(c)),
            Command::GearOut(c) => super::Command::Coupling(CouplingCommand::GearOut(c)),
            Command::CamTable(c) => super::Command::Coupling(CouplingCommand::CamTable(c)),
            Command::CamIn(c) => super::Command::Coupling(CouplingCommand::CamIn(c)),
            Command::CamOut(c) => super::Command::Coupling(CouplingCommand::CamOut(c)),
            Command::SuperimposeIn(c) => super::Command::from(c),
            Command::SuperimposeSetRatios(c) => super::Command::from(c),
            Command::SuperimposeOut(c) => super::Command::from(c),
            Command::TangentialIn(c) => super::Command::from(c),
            Command::TangentialOut(c) => super::Command::from(c),
            Command::GantryEnable(c) => super::Command::from(c),
            Command::GantryDisable(c) => super::Command::from(c),
            Command::HandwheelIn(c) => super::Command::from(c),
            Command::HandwheelOut(c) => super::Command::from(c),
            Command::HandwheelTurn(c) => super::Command::from(c),
            Command::FollowConfig(c) => super::Command::from(c),
            Command::FollowPush(c) => super::Command::from(c),
            Command::FollowClear(c) => super::Command::from(c),
            Command::FollowStart(c) => super::Command::from(c),
            Command::FollowSwitch(c) => super::Command::from(c),
            Command::FollowOut(c) => super::Command::from(c),
            Command::HandwheelSetRatio(c) => super::Command::from(c),
            Command::StreamStartOnInput(c) => super::Command::from(c),
            Command::CaptureArmThreshold(c) => super::Command::from(c),
            Command::CaptureArm(c) => super::Command::Trigger(TriggerCommand::CaptureArm(c)),
            Command::CaptureClear(c) => super::Command::Trigger(TriggerCommand::CaptureClear(c)),
            Command::CompareStart(c) => super::Command::Trigger(TriggerCommand::CompareStart(c)),
            Command::CompareStop(c) => super::Command::Trigger(TriggerCommand::CompareStop(c)),
            Command::CompareFire(c) => super::Command::Trigger(TriggerCommand::CompareFire(c)),
            Command::StreamConfig(c) => super::Command::Stream(StreamCommand::Config(c)),
            Command::PtPush(c) => super::Command::Stream(StreamCommand::PtPush(c)),
            Command::PvtPush(c) => super::Command::Stream(StreamCommand::PvtPush(c)),
            Command::StreamClear(c) => super::Command::Stream(StreamCommand::Clear(c)),
            Command::StreamStart(c) => super::Command::Stream(StreamCommand::Start(c)),
            Command::PvtMove(c) => super::Command::Stream(StreamCommand::PvtMove(c)),
            Command::CompensationLeadScrew(c) => super::Command::from(c),
            Command::CompensationBacklash(c) => super::Command::from(c),
            Command::CompensationTable(c) => super::Command::from(c),
            Command::CompensationEnable(c) => super::Command::from(c),
            Command::CompensationDisable(c) => super::Command::from(c),
            Command::CompensationClear(c) => super::Command::from(c),
            Command::SamplingConfigure(c) => super::Command::from(c),
            Command::SamplingStart(c) => super::Command::from(c),
            Command::SamplingTrigger(c) => super::Command::from(c),
            Command::SamplingStop(c) => super::Command::from(c),
            Command::SamplingRead(c) => super::Command::from(c),
            Command::TangentialCornerMode(c) => super::Command::from(c),
            Command::TangentialCornerFollowNext(c) => super::Command::from(c),
            Command::TangentialCornerContinue(c) => super::Command::from(c),
            Command::CamTableLink(c) => super::Command::from(c),
            Command::ZCompareStart(c) => super::Command::from(c),
            Command::ZCompareStop(c) => super::Command::from(c),
            Command::GantrySetPosition(c) => super::Command::from(c),
            Command::GantrySetPid(c) => super::Command::from(c),
            Command::CompensationOffsetAmount(c) => super::Command::from(c),
            Command::CompensationOffsetProfile(c) => super::Command::from(c),
            Command::CompensationOffsetTrigger(c) => super::Command::from(c),
            Command::CompensationOffsetStop(c) => super::Command::from(c),
            Command::FilterInputShaping(c) => super::Command::from(c),
            Command::FilterVsf(c) => super::Command::from(c),
            Command::FilterDisable(c) => super::Command::from(c),
            Command::GroupSetPolarTransform(c) => super::Command::from(c),
            Command::GroupDeletePolarTransform(c) => super::Command::from(c),
            Command::ResetFaults(c) => super::Command::from(c),
            Command::SetEstopInput(c) => super::Command::from(c),
            Command::AddAxisSet(c) => super::Command::from(c),
            Command::BindAnalogOutput(c) => super::Command::from(c),
        }
    }
}

impl From<super::Command> for Command {
    fn from(c: super::Command) -> Command {
        match c {
            super::Command::Axis(AxisCommand::Enable(c)) => Command::Enable(c),
            super::Command::Axis(AxisCommand::Disable(c)) => Command::Disable(c),
            super::Command::Axis(AxisCommand::Reset(c)) => Command::Reset(c),
            super::Command::Axis(AxisCommand::ResetFaults(c)) => Command::ResetFaults(c),
            super::Command::Axis(AxisCommand::MoveAbsolute(c)) => Command::MoveAbsolute(c),
            super::Command::Axis(AxisCommand::MoveRelative(c)) => Command::MoveRelative(c),
            super::Command::Axis(AxisCommand::MoveVelocity(c)) => Command::MoveVelocity(c),
            super::Command::Axis(AxisCommand::Stop(c)) => Command::Stop(c),
            super::Command::Axis(AxisCommand::Halt(c)) => Command::Halt(c),
            super::Command::Axis(AxisCommand::Resume(c)) => Command::Resume(c),
            super::Command::Axis(AxisCommand::Home(c)) => Command::Home(c),
            super::Command::Axis(AxisCommand::SetPosition(c)) => Command::SetPosition(c),
            super::Command::Axis(AxisCommand::SetParameter(c)) => Command::SetParameter(c),
            super::Command::Axis(AxisCommand::GetParameter(c)) => Command::GetParameter(c),
            super::Command::Axis(AxisCommand::ModifyTarget(c)) => Command::ModifyTarget(c),
            super::Command::Axis(AxisCommand::Cancel(c)) => Command::Cancel(c),
            super::Command::Machine(MachineCommand::CommandState(c)) => Command::CommandState(c),
            super::Command::Axis(AxisCommand::ForceInput(c)) => Command::ForceInput(c),
            super::Command::Io(IoCommand::ForceDigitalInput(c)) => Command::ForceDigitalInput(c),
            super::Command::Io(IoCommand::ForceAnalogInput(c)) => Command::ForceAnalogInput(c),
            super::Command::Io(IoCommand::WriteDigitalOutput(c)) => Command::WriteDigitalOutput(c),
            super::Command::Io(IoCommand::WriteAnalogOutput(c)) => Command::WriteAnalogOutput(c),
            super::Command::Io(IoCommand::PulseDigitalOutput(c)) => Command::PulseDigitalOutput(c),
            super::Command::Io(IoCommand::BindAnalogOutput(c)) => Command::BindAnalogOutput(c),
            super::Command::Group(GroupCommand::PulseOutput(c)) => Command::GroupPulseOutput(c),
            super::Command::Group(GroupCommand::SetAnalogOutput(c)) => {
                Command::GroupSetAnalogOutput(c)
            }
            super::Command::Group(GroupCommand::StopInput(c)) => Command::GroupStopInput(c),
            super::Command::Group(GroupCommand::BufferedHalt(c)) => Command::GroupBufferedHalt(c),
            super::Command::Group(GroupCommand::SetPolarTransform(c)) => {
                Command::GroupSetPolarTransform(c)
            }
            super::Command::Group(GroupCommand::DeletePolarTransform(c)) => {
                Command::GroupDeletePolarTransform(c)
            }
            super::Command::Axis(AxisCommand::InjectFollowingError(c)) => {
                Command::InjectFollowingError(c)
            }
            super::Command::Axis(AxisCommand::Setpoint(c)) => Command::Setpoint(c),
            super::Command::Slave(SlaveCommand::ReadObject(c)) => Command::ReadObject(c),
            super::Command::Slave(SlaveCommand::WriteObject(c)) => Command::WriteObject(c),
            super::Command::Machine(MachineCommand::MoveTogether(c)) => Command::MoveTogether(c),
            super::Command::Machine(MachineCommand::StopAxes(c)) => Command::StopAxes(c),
            super::Command::Machine(MachineCommand::StopAll(c)) => Command::StopAll(c),
            super::Command::Machine(MachineCommand::EnableAll(c)) => Command::EnableAll(c),
            super::Command::Machine(MachineCommand::DisableAll(c)) => Command::DisableAll(c),
            super::Command::Machine(MachineCommand::EmergencyStopAll(c)) => {
                Command::EmergencyStopAll(c)
            }
            super::Command::Machine(MachineCommand::ResetAll(c)) => Command::ResetAll(c),
            super::Command::Machine(MachineCommand::GantryHome(c)) => Command::GantryHome(c),
            super::Command::Machine(MachineCommand::SetEstopInput(c)) => Command::SetEstopInput(c),
            super::Command::Machine(MachineCommand::EstimateGroupTime(c)) => {
                Command::EstimateGroupTime(c)
            }
            super::Command::Machine(MachineCommand::WatchdogSet(c)) => Command::WatchdogSet(c),
            super::Command::Machine(MachineCommand::WatchdogKick(c)) => Command::WatchdogKick(c),
            super::Command::Machine(MachineCommand::InputStopSet(c)) => Command::InputStopSet(c),
            super::Command::Machine(MachineCommand::InputStopClear(c)) => {
                Command::InputStopClear(c)
            }
            super::Command::Machine(MachineCommand::PositionWatchSet(c)) => {
                Command::PositionWatchSet(c)
            }
            super::Command::Machine(MachineCommand::PositionWatchClear(c)) => {
                Command::PositionWatchClear(c)
            }
            super::Command::Group(GroupCommand::Create(c)) => Command::GroupCreate(c),
            super::Command::Group(GroupCommand::Delete(c)) => Command::GroupDelete(c),
            super::Command::Group(GroupCommand::Enable(c)) => Command::GroupEnable(c),
            super::Command::Group(GroupCommand::Disable(c)) => Command::GroupDisable(c),
            super::Command::Group(GroupCommand::Reset(c)) => Command::GroupReset(c),
            super::Command::Group(GroupCommand::MoveLinearAbsolute(c)) => {
                Command::MoveLinearAbsolute(c)
            }
            super::Command::Group(GroupCommand::MoveLinearRelative(c)) => {
                Command::MoveLinearRelative(c)
            }
            super::Command::Group(GroupCommand::MoveCircularAbsolute(c)) => {
                Command::MoveCircularAbsolute(c)
            }
            super::Command::Group(GroupCommand::MoveCircularRelative(c)) => {
                Command::MoveCircularRelative(c)
            }
            super::Command::Group(GroupCommand::Stop(c)) => Command::GroupStop(c),
            super::Command::Group(GroupCommand::Halt(c)) => Command::GroupHalt(c),
            super::Command::Group(GroupCommand::Continue(c)) => Command::GroupContinue(c),
            super::Command::Group(GroupCommand::EmergencyStop(c)) => Command::GroupEmergencyStop(c),
            super::Command::Group(GroupCommand::SetOverride(c)) => Command::GroupSetOverride(c),
            super::Command::Group(GroupCommand::SetOrigin(c)) => Command::GroupSetOrigin(c),
            super::Command::Group(GroupCommand::SetParameter(c)) => Command::GroupSetParameter(c),
            super::Command::Group(GroupCommand::SetOutput(c)) => Command::GroupSetOutput(c),
            super::Command::Group(GroupCommand::Dwell(c)) => Command::GroupDwell(c),
            super::Command::Group(GroupCommand::WaitInput(c)) => Command::GroupWaitInput(c),
            super::Command::Group(GroupCommand::WaitPosition(c)) => Command::GroupWaitPosition(c),
            super::Command::Group(GroupCommand::AxisMove(c)) => Command::GroupAxisMove(c),
            super::Command::Group(GroupCommand::MoveSpline(c)) => Command::MoveSpline(c),
            super::Command::Group(GroupCommand::MoveEllipse(c)) => Command::MoveEllipse(c),
            super::Command::Group(GroupCommand::MoveCircularAngle(c)) => {
                Command::MoveCircularAngle(c)
            }
            super::Command::Group(GroupCommand::SetCoordinateTransform(c)) => {
                Command::GroupSetCoordinateTransform(c)
            }
            super::Command::Group(GroupCommand::SetCoordinateSystem(c)) => {
                Command::GroupSetCoordinateSystem(c)
            }
            super::Command::Group(GroupCommand::SetRotaryTransform(c)) => {
                Command::GroupSetRotaryTransform(c)
            }
            super::Command::Group(GroupCommand::SetXyzaTransform(c)) => {
                Command::GroupSetXyzaTransform(c)
            }
            super::Command::Group(GroupCommand::DeleteTransform(c)) => {
                Command::GroupDeleteTransform(c)
            }
            super::Command::Group(GroupCommand::ProtectionEnable(c)) => {
                Command::MoveProtectionEnable(c)
            }
            super::Command::Group(GroupCommand::ProtectionDisable(c)) => {
                Command::MoveProtectionDisable(c)
            }
            super::Command::Group(GroupCommand::Jog(c)) => Command::GroupJog(c),
            super::Command::Group(GroupCommand::JogAxis(c)) => Command::GroupJogAxis(c),
            super::Command::Coupling(CouplingCommand::GearIn(c)) => Command::GearIn(c),
            super::Command::Coupling(CouplingCommand::GearSetRatio(c)) => Command::GearSetRatio(c),
            super::Command::Coupling(CouplingCommand::GearOut(c)) => Command::GearOut(c),
            super::Command::Coupling(CouplingCommand::CamTable(c)) => Command::CamTable(c),
            super::Command::Coupling(CouplingCommand::CamIn(c)) => Command::CamIn(c),
            super::Command::Coupling(CouplingCommand::CamOut(c)) => Command::CamOut(c),
            super::Command::Coupling(CouplingCommand::SuperimposeIn(c)) => {
                Command::SuperimposeIn(c)
            }
            super::Command::Coupling(CouplingCommand::SuperimposeSetRatios(c)) => {
                Command::SuperimposeSetRatios(c)
            }
            super::Command::Coupling(CouplingCommand::SuperimposeOut(c)) => {
                Command::SuperimposeOut(c)
            }
            super::Command::Coupling(CouplingCommand::TangentialIn(c)) => Command::TangentialIn(c),
            super::Command::Coupling(CouplingCommand::TangentialOut(c)) => {
                Command::TangentialOut(c)
            }
            super::Command::Coupling(CouplingCommand::GantryEnable(c)) => Command::GantryEnable(c),
            super::Command::Coupling(CouplingCommand::GantryDisable(c)) => {
                Command::GantryDisable(c)
            }
            super::Command::Coupling(CouplingCommand::HandwheelIn(c)) => Command::HandwheelIn(c),
            super::Command::Coupling(CouplingCommand::HandwheelOut(c)) => Command::HandwheelOut(c),
            super::Command::Coupling(CouplingCommand::HandwheelTurn(c)) => {
                Command::HandwheelTurn(c)
            }
            super::Command::Coupling(CouplingCommand::FollowConfig(c)) => Command::FollowConfig(c),
            super::Command::Coupling(CouplingCommand::FollowPush(c)) => Command::FollowPush(c),
            super::Command::Coupling(CouplingCommand::FollowClear(c)) => Command::FollowClear(c),
            super::Command::Coupling(CouplingCommand::FollowStart(c)) => Command::FollowStart(c),
            super::Command::Coupling(CouplingCommand::FollowSwitch(c)) => Command::FollowSwitch(c),
            super::Command::Coupling(CouplingCommand::FollowOut(c)) => Command::FollowOut(c),
            super::Command::Coupling(CouplingCommand::HandwheelSetRatio(c)) => {
                Command::HandwheelSetRatio(c)
            }
            super::Command::Coupling(CouplingCommand::TangentialCornerMode(c)) => {
                Command::TangentialCornerMode(c)
            }
            super::Command::Coupling(CouplingCommand::TangentialCornerFollowNext(c)) => {
                Command::TangentialCornerFollowNext(c)
            }
            super::Command::Coupling(CouplingCommand::TangentialCornerContinue(c)) => {
                Command::TangentialCornerContinue(c)
            }
            super::Command::Coupling(CouplingCommand::CamTableLink(c)) => Command::CamTableLink(c),
            super::Command::Coupling(CouplingCommand::GantrySetPosition(c)) => {
                Command::GantrySetPosition(c)
            }
            super::Command::Coupling(CouplingCommand::GantrySetPid(c)) => Command::GantrySetPid(c),
            super::Command::Coupling(CouplingCommand::AddAxisSet(c)) => Command::AddAxisSet(c),
            super::Command::Trigger(TriggerCommand::CaptureArm(c)) => Command::CaptureArm(c),
            super::Command::Trigger(TriggerCommand::CaptureClear(c)) => Command::CaptureClear(c),
            super::Command::Trigger(TriggerCommand::CompareStart(c)) => Command::CompareStart(c),
            super::Command::Trigger(TriggerCommand::CompareStop(c)) => Command::CompareStop(c),
            super::Command::Trigger(TriggerCommand::CompareFire(c)) => Command::CompareFire(c),
            super::Command::Trigger(TriggerCommand::CaptureArmThreshold(c)) => {
                Command::CaptureArmThreshold(c)
            }
            super::Command::Trigger(TriggerCommand::ZCompareStart(c)) => Command::ZCompareStart(c),
            super::Command::Trigger(TriggerCommand::ZCompareStop(c)) => Command::ZCompareStop(c),
            super::Command::Stream(StreamCommand::Config(c)) => Command::StreamConfig(c),
            super::Command::Stream(StreamCommand::PtPush(c)) => Command::PtPush(c),
            super::Command::Stream(StreamCommand::PvtPush(c)) => Command::PvtPush(c),
            super::Command::Stream(StreamCommand::Clear(c)) => Command::StreamClear(c),
            super::Command::Stream(StreamCommand::Start(c)) => Command::StreamStart(c),
            super::Command::Stream(StreamCommand::PvtMove(c)) => Command::PvtMove(c),
            super::Command::Stream(StreamCommand::StartOnInput(c)) => {
                Command::StreamStartOnInput(c)
            }
            super::Command::Compensation(c) => match c {
                CompensationCommand::LeadScrew(c) => Command::CompensationLeadScrew(c),
                CompensationCommand::Backlash(c) => Command::CompensationBacklash(c),
                CompensationCommand::Table(c) => Command::CompensationTable(c),
                CompensationCommand::Enable(c) => Command::CompensationEnable(c),
                CompensationCommand::Disable(c) => Command::CompensationDisable(c),
                CompensationCommand::Clear(c) => Command::CompensationClear(c),
                CompensationCommand::OffsetAmount(c) => Command::CompensationOffsetAmount(c),
                CompensationCommand::OffsetProfile(c) => Command::CompensationOffsetProfile(c),
                CompensationCommand::OffsetTrigger(c) => Command::CompensationOffsetTrigger(c),
                CompensationCommand::OffsetStop(c) => Command::CompensationOffsetStop(c),
                CompensationCommand::FilterInputShaping(c) => Command::FilterInputShaping(c),
                CompensationCommand::FilterVsf(c) => Command::FilterVsf(c),
                CompensationCommand::FilterDisable(c) => Command::FilterDisable(c),
            },
            super::Command::Sampling(c) => match c {
                SamplingCommand::Configure(c) => Command::SamplingConfigure(c),
                SamplingCommand::Start(c) => Command::SamplingStart(c),
                SamplingCommand::Trigger(c) => Command::SamplingTrigger(c),
                SamplingCommand::Stop(c) => Command::SamplingStop(c),
                SamplingCommand::Read(c) => Command::SamplingRead(c),
            },
        }
    }
}
