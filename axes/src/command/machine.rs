//! The machine family: commands about the whole machine, or several axes at once, rather than
//! one axis, group or slave (issue 11 item 6: HIMC DisableAll/StopAll/EStop §2.7–2.9, HMC
//! DriveEnable/ClearAllErr §4.1/§4.9, NMC MtUpdateMulti/MtStopMulti/MovePtpAbsPack8 §2.5).
//!
//! Every command here acts between two ticks: what it changes, it changes for all its axes at
//! once, so they all see the same first tick.

use serde::{Deserialize, Serialize};

use super::{
    command_from, AxisCommand, AxisIndex, BufferMode, Command, CommandId, GantryHome, GroupId,
    InputStopClear, InputStopSet, MoveAbsolute, MoveRelative, MoveVelocity, PositionWatchClear,
    PositionWatchSet, StopMode, WatchdogKick, WatchdogSet,
};

/// State of a command by id. Ids are engine-wide, so the query is too. JSON `type`:
/// `command_state`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GetCommandState {
    pub id: CommandId,
}

/// One move of a [`MoveTogether`]: the single-axis motion command it would be on its own, with
/// the same JSON (`{"type": "move_absolute", "axis": 0, "position": 100.0}` …).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum TogetherMove {
    MoveAbsolute(MoveAbsolute),
    MoveRelative(MoveRelative),
    MoveVelocity(MoveVelocity),
}

impl TogetherMove {
    /// The axis the move addresses.
    pub fn axis(&self) -> AxisIndex {
        match self {
            TogetherMove::MoveAbsolute(MoveAbsolute { axis, .. })
            | TogetherMove::MoveRelative(MoveRelative { axis, .. })
            | TogetherMove::MoveVelocity(MoveVelocity { axis, .. }) => *axis,
        }
    }

    pub fn buffer_mode(&self) -> BufferMode {
        match self {
            TogetherMove::MoveAbsolute(MoveAbsolute { buffer_mode, .. })
            | TogetherMove::MoveRelative(MoveRelative { buffer_mode, .. })
            | TogetherMove::MoveVelocity(MoveVelocity { buffer_mode, .. }) => *buffer_mode,
        }
    }
}

impl From<TogetherMove> for AxisCommand {
    fn from(m: TogetherMove) -> AxisCommand {
        match m {
            TogetherMove::MoveAbsolute(c) => AxisCommand::MoveAbsolute(c),
            TogetherMove::MoveRelative(c) => AxisCommand::MoveRelative(c),
            TogetherMove::MoveVelocity(c) => AxisCommand::MoveVelocity(c),
        }
    }
}

/// Start several axes' moves in the same tick, all or none (NMC `MtUpdateMulti` and
/// `MovePtpAbsPack8`, digest 001 TV27–28). One move per axis; each must be `aborting`. If one
/// would be refused (axis absent, disabled, in error, fed, limit, bad number), none starts and
/// the error names the move's index. The reply lists the moves' command ids in order.
/// JSON `type`: `move_together`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveTogether {
    pub moves: Vec<TogetherMove>,
}

/// Stop several axes in the same tick (NMC `MtStopMulti`), each as a single `stop` would, with
/// one mode and deceleration for all. JSON `type`: `stop_axes`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopAxes {
    pub axes: Vec<AxisIndex>,
    #[serde(default)]
    pub mode: StopMode,
    #[serde(default)]
    pub deceleration: Option<f64>,
}

/// Stop every axis (HIMC `StopAll`, digest 004 §2.8, §3.4): by default with the kill
/// deceleration (`fast_decel`, mode `abrupt`); the axes stay enabled, their queues are cleared,
/// nothing is latched. JSON `type`: `stop_all`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopAll {
    #[serde(default = "kill_deceleration")]
    pub mode: StopMode,
    #[serde(default)]
    pub deceleration: Option<f64>,
}

fn kill_deceleration() -> StopMode {
    StopMode::Abrupt
}

impl Default for StopAll {
    fn default() -> Self {
        StopAll {
            mode: kill_deceleration(),
            deceleration: None,
        }
    }
}

/// Enable every axis that can move (HMC `DriveEnable(1)`, digest 000 §4.1), all or none: if one
/// would be refused (in error, drive alarm) none is enabled. Engine-mastered CiA 402 drives go
/// through their power state machine as a single `enable` does. JSON `type`: `enable_all`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnableAll {}

/// Disable every axis (HIMC `DisableAll`, digest 004 §2.7): queues and plans cleared.
/// JSON `type`: `disable_all`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DisableAll {}

/// Emergency stop of the whole machine (HIMC `EStop`, digest 004 §2.9, §1.10): every axis that
/// can move latches `ESTOP` and is disabled. The latch holds the axes in ErrorStop, so `enable`
/// and motion are refused until a `reset` / `reset_all`. JSON `type`: `emergency_stop_all`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EmergencyStopAll {}

/// Clear the latched errors of every axis whose cause is gone (HMC `ClearAllErr`, digest 000
/// §4.9). Each axis clears what it can; the first axis whose cause is still present is reported.
/// JSON `type`: `reset_all`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResetAll {}

/// Bind the machine's E-stop input (HIMC `BindEMO`, digest 004 §1.10, §9.2.6): digital input
/// `channel` reaching `level` from the other level applies `emergency_stop_all` in the tick that
/// reads it, before the planners run, so no axis takes a step on that tick's setpoints. Without
/// `channel`, no input is bound. A new binding starts from the input's level now: binding an
/// input already at `level` fires nothing until it leaves and comes back. JSON `type`:
/// `set_estop_input`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SetEstopInput {
    #[serde(default)]
    pub channel: Option<u16>,
    /// The active level (default high; an inverted input is active low).
    #[serde(default = "active_high")]
    pub level: bool,
}

fn active_high() -> bool {
    true
}

/// How many servo periods `group` takes to come to rest after `commands` (NMC
/// `_NMC_CrdGetExeTime`): a dry run of the engine itself, which is then put back exactly as it
/// was (`engine/estimate.rs`). The reply is `value`, in ticks. JSON `type`:
/// `estimate_group_time`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EstimateGroupTime {
    pub group: GroupId,
    #[serde(default)]
    pub commands: Vec<Command>,
}

/// A machine-wide command.
#[derive(Clone, Debug, PartialEq)]
pub enum MachineCommand {
    CommandState(GetCommandState),
    MoveTogether(MoveTogether),
    StopAxes(StopAxes),
    StopAll(StopAll),
    EnableAll(EnableAll),
    DisableAll(DisableAll),
    EmergencyStopAll(EmergencyStopAll),
    ResetAll(ResetAll),
    /// HMC_GantryInit (`command/gantry.rs`): a sequence over several axes.
    GantryHome(GantryHome),
    SetEstopInput(SetEstopInput),
    EstimateGroupTime(EstimateGroupTime),
    /// Guards (`command/guard.rs`): the watchdog and the input stops.
    WatchdogSet(WatchdogSet),
    WatchdogKick(WatchdogKick),
    InputStopSet(InputStopSet),
    InputStopClear(InputStopClear),
    PositionWatchSet(PositionWatchSet),
    PositionWatchClear(PositionWatchClear),
}

command_from!(
    MachineCommand,
    Machine,
    [
        GetCommandState => CommandState,
        MoveTogether => MoveTogether,
        StopAxes => StopAxes,
        StopAll => StopAll,
        EnableAll => EnableAll,
        DisableAll => DisableAll,
        EmergencyStopAll => EmergencyStopAll,
        ResetAll => ResetAll,
        GantryHome => GantryHome,
        SetEstopInput => SetEstopInput,
        EstimateGroupTime => EstimateGroupTime,
        WatchdogSet => WatchdogSet,
        WatchdogKick => WatchdogKick,
        InputStopSet => InputStopSet,
        InputStopClear => InputStopClear,
        PositionWatchSet => PositionWatchSet,
        PositionWatchClear => PositionWatchClear,
    ]
);
