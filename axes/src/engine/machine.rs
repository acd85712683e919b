//! Machine-wide commands (issue 11 item 6) and atomic batches: commands that change several
//! axes between the same two ticks, all or none.
//!
//! All-or-nothing is done by a [`Checkpoint`]: the state a command may change (the axes it
//! names, the I/O image, the drives, the command ledger) is saved before it is applied and
//! put back if any part is refused, so a refused command or batch leaves the engine exactly as
//! it was (bit for bit: the next ticks are those of an engine that never saw it). Cheap checks
//! that need no state (empty lists, duplicate or absent axes, a bad deceleration) come first
//! and need no checkpoint.

use super::{Engine, Io, Slave};
use crate::axis::fifo::LedgerMark;
use crate::axis::Axis;
use crate::cia402::{DriveMaster, PowerTarget};
use crate::command::{
    positive, AxisCommand, AxisIndex, BufferMode, Command, Disable, EmergencyStopAll, Enable,
    EngineError, GetCommandState, MachineCommand, MoveTogether, Reply, Reset, Stop, StopAll,
    StopAxes, StopMode, TogetherMove,
};
use crate::coupling::Couplings;
use crate::group::Groups;
use crate::trigger::Triggers;

/// Commands one atomic batch ([`Engine::apply_batch`]) may carry: it is applied inside one
/// servo period, so its size bounds the work done there.
pub const MAX_ATOMIC_COMMANDS: usize = 1024;

/// What a command may change, saved before it is applied (see the module doc).
pub(super) struct Checkpoint {
    /// Copies of the axes the command may change, by index.
    axes: Vec<(usize, Axis)>,
    /// The axis groups and whether they wait for drives to power up (a whole-machine
    /// checkpoint: a batch may carry group commands).
    groups: Option<(Groups, bool)>,
    /// The gears and cams (issue 12), with the groups: a batch may carry coupling commands.
    couplings: Option<Couplings>,
    /// The capture and compare channels (a whole-machine checkpoint: a batch may arm them).
    triggers: Option<Triggers>,
    /// Streams armed to start on an input (`stream_start_on_input` may be in a batch).
    input_starts: Option<Vec<super::stream_inputs::InputStart>>,
    /// `gantry_home` runs (a batch may start one).
    gantry_homes: Option<Vec<super::gantry_home::GantryHoming>>,
    /// The E-stop input binding (`set_estop_input` may be in a batch).
    estop_input: Option<super::estop_input::EstopInput>,
    /// The watchdog and input stops (a batch may arm them).
    guards: Option<crate::guard::Guards>,
    io: Option<Io>,
    slaves: Option<Vec<Slave>>,
    ledger: LedgerMark,
}

/// Which state a [`Checkpoint`] saves.
pub(super) enum Scope<'a> {
    /// These axes only (motion commands touch nothing else but the ledger).
    Axes(&'a [usize]),
    /// Every axis and the drives (power commands route through the drives).
    AxesAndDrives,
    /// Everything a command can change.
    Machine,
}

impl Engine {
    /// Apply `commands` in order between the same two ticks, all or none: if one is refused,
    /// the engine is put back as it was before the first (bit for bit) and the error names the
    /// refused command's index (`EngineError::Item`, list "commands"). Replies are those the
    /// commands would get one by one, in order; ids refused with the batch are issued again.
    pub fn apply_batch(&mut self, commands: Vec<Command>) -> Result<Vec<Reply>, EngineError> {
        if commands.is_empty() {
            return Err(EngineError::InvalidArgument {
                name: "commands",
                value: 0.0,
                reason: "an atomic batch needs at least one command",
            });
        }
        if commands.len() > MAX_ATOMIC_COMMANDS {
            return Err(EngineError::InvalidArgument {
                name: "commands",
                value: commands.len() as f64,
                reason: "more than 1024 commands in one atomic batch",
            });
        }
        let checkpoint = self.checkpoint(Scope::Machine);
        let mut replies = Vec::with_capacity(commands.len());
        for (index, command) in commands.into_iter().enumerate() {
            match self.apply(command) {
                Ok(reply) => replies.push(reply),
                Err(e) => {
                    self.rollback(checkpoint);
                    return Err(EngineError::item("commands", index, e));
                }
            }
        }
        self.commit(checkpoint);
        Ok(replies)
    }

    /// Machine-wide commands. Each `*_everything` function is the one place its command reaches
    /// every axis and every group.
    pub(super) fn apply_machine_command(
        &mut self,
        command: MachineCommand,
    ) -> Result<Reply, EngineError> {
        match command {
            MachineCommand::CommandState(GetCommandState { id }) => {
                // Looked up in every axis's queue, then in the ledger of finished commands.
                let state = self
                    .axes
                    .iter()
                    .find_map(|a| a.queued_state(id))
                    .or_else(|| self.groups.queued_state(id))
                    .or_else(|| self.ledger.lookup(id))
                    .ok_or(EngineError::UnknownCommand { id })?;
                Ok(Reply::CommandState { id, state })
            }
            MachineCommand::MoveTogether(c) => self.move_together(c),
            MachineCommand::StopAxes(c) => self.stop_axes(c),
            MachineCommand::StopAll(StopAll { mode, deceleration }) => {
                check_deceleration(deceleration)?;
                self.stop_everything(mode, deceleration);
                Ok(Reply::Done)
            }
            MachineCommand::EnableAll(_) => self.enable_everything(),
            MachineCommand::DisableAll(_) => {
                self.disable_everything();
                Ok(Reply::Done)
            }
            MachineCommand::EmergencyStopAll(EmergencyStopAll {}) => {
                self.emergency_stop_everything();
                Ok(Reply::Done)
            }
            MachineCommand::ResetAll(_) => self.reset_everything(),
            MachineCommand::GantryHome(c) => self.start_gantry_home(c),
            MachineCommand::SetEstopInput(c) => self.set_estop_input(c),
            MachineCommand::EstimateGroupTime(c) => self.estimate_group_time(c),
            MachineCommand::WatchdogSet(c) => self.set_watchdog(c),
            MachineCommand::WatchdogKick(c) => {
                self.guards.kick_watchdog(c.deadline);
                Ok(Reply::Done)
            }
            MachineCommand::InputStopSet(c) => self.set_input_stop(c),
            MachineCommand::InputStopClear(c) => {
                self.guards.clear_input_stop(c.slot);
                Ok(Reply::Done)
            }
            MachineCommand::PositionWatchSet(c) => self.set_position_watch(c),
            MachineCommand::PositionWatchClear(c) => {
                self.guards.clear_position_watch(c.axis);
                Ok(Reply::Done)
            }
        }
    }

    /// NMC `MtUpdateMulti` / `MovePtpAbsPack8` (digest 001 §2.5, TV27–28): every move starts
    /// between the same two ticks, so all axes leave on the same tick; one refusal and none
    /// starts (the axes keep doing what they did).
    fn move_together(
        &mut self,
        MoveTogether { moves }: MoveTogether,
    ) -> Result<Reply, EngineError> {
        if moves.is_empty() {
            return Err(EngineError::InvalidArgument {
                name: "moves",
                value: 0.0,
                reason: "move_together needs at least one move",
            });
        }
        let axes = self.distinct_axes("moves", moves.iter().map(TogetherMove::axis))?;
        for (index, m) in moves.iter().enumerate() {
            if m.buffer_mode() != BufferMode::Aborting {
                return Err(EngineError::item(
                    "moves",
                    index,
                    EngineError::Unsupported {
                        what: "buffer_mode `buffered` in move_together: moves that start \
                               together abort what their axes are doing"
                            .into(),
                    },
                ));
            }
        }
        let checkpoint = self.checkpoint(Scope::Axes(&axes));
        let mut ids = Vec::with_capacity(moves.len());
        for (index, m) in moves.into_iter().enumerate() {
            match self.apply_axis_command(AxisCommand::from(m)) {
                Ok(Reply::Accepted { id }) => ids.push(id),
                // Motion commands reply `Accepted`; anything else has no id to report.
                Ok(_) => {}
                Err(e) => {
                    self.rollback(checkpoint);
                    return Err(EngineError::item("moves", index, e));
                }
            }
        }
        self.commit(checkpoint);
        Ok(Reply::AcceptedAll { ids })
    }

    /// NMC `MtStopMulti`: each axis stops as a single `stop` would, in the same tick. Every
    /// refusal is found before any axis stops (axes, deceleration), so none is partial.
    fn stop_axes(&mut self, c: StopAxes) -> Result<Reply, EngineError> {
        if c.axes.is_empty() {
            return Err(EngineError::InvalidArgument {
                name: "axes",
                value: 0.0,
                reason: "stop_axes needs at least one axis",
            });
        }
        check_deceleration(c.deceleration)?;
        let axes = self.distinct_axes("axes", c.axes.iter().copied())?;
        for axis in axes {
            self.stop_axis(axis, c.mode, c.deceleration);
        }
        Ok(Reply::Done)
    }

    /// Stop one axis whose index and deceleration were checked.
    fn stop_axis(&mut self, axis: usize, mode: StopMode, deceleration: Option<f64>) {
        // `stop` refuses only a bad deceleration, checked by the callers.
        let _ = self.apply_to_axis(AxisCommand::Stop(Stop {
            axis: axis as AxisIndex,
            mode,
            deceleration,
        }));
    }

    /// HIMC `StopAll` (digest 004 §2.8, §6.1 TV4): every axis stops with `mode` (default the
    /// kill deceleration, `fast_decel`), stays enabled, its queue cleared.
    /// Every moving group's path is dropped first; the groups stay enabled (Standby).
    fn stop_everything(&mut self, mode: StopMode, deceleration: Option<f64>) {
        // Groups first: their paths are dropped (they stay enabled), so each member stops by
        // this command like any axis rather than leaving its group in ErrorStop.
        self.with_groups(|groups, env| groups.drop_paths(env));
        for axis in 0..self.axes.len() {
            self.stop_axis(axis, mode, deceleration);
        }
    }

    /// HMC `DriveEnable(1)` (digest 000 §4.1) for every axis that can move, all or none: an
    /// axis that would refuse (error stop, drive alarm) leaves every axis and drive as it was,
    /// and the error names it. Engine-mastered drives are walked to Operation enabled as a
    /// single `enable` does (`route_power`). Encoder-only and unused axes are skipped.
    /// Then every Disabled group whose members are all enabled and at rest is enabled
    /// (Standby), as `group_enable` would; this comes after the last point of refusal, so the
    /// groups need no checkpoint. A member on an engine-mastered drive is powered ticks later:
    /// the groups are enabled again once the drives' walks have ended
    /// ([`Engine::enable_groups_once_powered`]; docs/decisions.md, "Group safety").
    fn enable_everything(&mut self) -> Result<Reply, EngineError> {
        let checkpoint = self.checkpoint(Scope::AxesAndDrives);
        for axis in 0..self.axes.len() {
            if !self.axes.get(axis).is_some_and(Axis::can_move) {
                continue;
            }
            let enable = AxisCommand::Enable(Enable {
                axis: axis as AxisIndex,
            });
            if let Err(e) = self.apply_axis_command(enable) {
                self.rollback(checkpoint);
                return Err(EngineError::item("axes", axis, e));
            }
        }
        self.commit(checkpoint);
        self.with_groups(|groups, env| groups.enable_all(env));
        self.groups_await_power = self.drives_powering_up();
        Ok(Reply::Done)
    }

    /// Some engine-mastered drive is walking to Operation enabled.
    fn drives_powering_up(&self) -> bool {
        self.slaves
            .iter()
            .any(|s| s.power == Some(PowerTarget::OperationEnabled))
    }

    /// The end of an `enable_all` whose engine-mastered drives powered their axes ticks later
    /// (after stage 4, while `groups_await_power`): once no drive walks to Operation enabled,
    /// every Disabled group whose members are all enabled is enabled. A disable in between
    /// leaves its member's group Disabled.
    pub(super) fn enable_groups_once_powered(&mut self) {
        if self.drives_powering_up() {
            return;
        }
        self.groups_await_power = false;
        self.with_groups(|groups, env| groups.enable_all(env));
    }

    /// HIMC `DisableAll` (digest 004 §2.7, §6.1 TV5): every axis disabled, queues and plans
    /// cleared; engine-mastered drives go through `route_power`.
    /// Every group is disabled (its path dropped) too.
    fn disable_everything(&mut self) {
        self.groups_await_power = false;
        self.with_groups(|groups, env| groups.disable_all(env));
        for axis in 0..self.axes.len() {
            // `disable` never refuses.
            let _ = self.apply_axis_command(AxisCommand::Disable(Disable {
                axis: axis as AxisIndex,
            }));
        }
    }

    /// HIMC `EStop` (digest 004 §2.9, §1.10): every axis that can move latches `ESTOP` (as
    /// NMC `MtEstp` does, digest 001 TV19) and is disabled at once (a category 0 stop). The
    /// latch holds the axes in ErrorStop: `enable` and motion are refused until `reset` /
    /// `reset_all` clears it (HIMC: "the user may re-enable"). An engine-mastered CiA 402 drive
    /// is not walked down by controlword (from Fault that walk is a fault reset, which would
    /// clear the latch): the latch is an axis fault to the drive, whose fault reaction (0x605E)
    /// stops the axis, powers it off and leaves the drive in Fault; a power walk in progress is
    /// dropped.
    /// Every enabled group goes to ErrorStop (`emergency_stop`) too.
    pub(super) fn emergency_stop_everything(&mut self) {
        self.groups_await_power = false;
        self.with_groups(|groups, env| groups.emergency_stop_all(env));
        for axis in 0..self.axes.len() {
            if !self.axes.get(axis).is_some_and(Axis::can_move) {
                continue;
            }
            self.stop_axis(axis, StopMode::Emergency, None);
            if let Some(slave) = self.engine_mastered_slave(axis) {
                slave.power = None;
                continue;
            }
            // `disable` never refuses.
            let _ = self.apply_axis_command(AxisCommand::Disable(Disable {
                axis: axis as AxisIndex,
            }));
        }
    }

    /// The drive bound to `axis`, if the engine masters its power (see `route_power`).
    fn engine_mastered_slave(&mut self, axis: usize) -> Option<&mut Slave> {
        let slave = self.axis_slave.get(axis).copied().flatten()?;
        self.slaves
            .get_mut(slave)
            .filter(|s| s.master == DriveMaster::Engine)
    }

    /// HMC `ClearAllErr` (digest 000 §4.9): every axis clears the latched errors whose cause
    /// is gone (engine-mastered drives in Fault are walked out of it, as by `reset`). Not all or
    /// none: each axis clears what it can, and the first axis whose cause is still present is
    /// the error.
    /// Then every group in ErrorStop is reset as by `group_reset`: Standby when its members are
    /// all enabled and at rest, Disabled when they are all disabled (after
    /// `emergency_stop_all`); the others stay (their members' errors are the ones reported).
    fn reset_everything(&mut self) -> Result<Reply, EngineError> {
        let mut first_error = None;
        for axis in 0..self.axes.len() {
            let reset = AxisCommand::Reset(Reset {
                axis: axis as AxisIndex,
            });
            if let Err(e) = self.apply_axis_command(reset) {
                first_error.get_or_insert(e);
            }
        }
        self.with_groups(|groups, env| groups.reset_all(env));
        first_error.map_or(Ok(Reply::Done), Err)
    }

    /// The axes a list names, checked: each exists and appears once (CPU 226H TV-39: a second
    /// instruction on a busy axis is refused). Errors name the item.
    pub(super) fn distinct_axes(
        &self,
        list: &'static str,
        axes: impl Iterator<Item = AxisIndex>,
    ) -> Result<Vec<usize>, EngineError> {
        let count = self.axes.len();
        let mut seen = vec![false; count];
        let mut out = Vec::new();
        for (index, axis) in axes.enumerate() {
            let Some(slot) = seen.get_mut(axis as usize) else {
                return Err(EngineError::item(
                    list,
                    index,
                    EngineError::InvalidAxis {
                        axis: u32::from(axis),
                        count: count as u32,
                    },
                ));
            };
            if *slot {
                return Err(EngineError::item(
                    list,
                    index,
                    EngineError::InvalidArgument {
                        name: "axis",
                        value: f64::from(axis),
                        reason: "appears earlier in the list: one entry per axis",
                    },
                ));
            }
            *slot = true;
            out.push(axis as usize);
        }
        Ok(out)
    }

    pub(super) fn checkpoint(&mut self, scope: Scope) -> Checkpoint {
        let all = || 0..self.axes.len();
        let save = |indices: &mut dyn Iterator<Item = usize>| {
            indices
                .filter_map(|i| self.axes.get(i).map(|a| (i, a.clone())))
                .collect::<Vec<_>>()
        };
        let (axes, io, slaves) = match scope {
            Scope::Axes(list) => (save(&mut list.iter().copied()), None, None),
            Scope::AxesAndDrives => (save(&mut all()), None, Some(self.slaves.clone())),
            Scope::Machine => (
                save(&mut all()),
                Some(self.io.clone()),
                Some(self.slaves.clone()),
            ),
        };
        let groups =
            matches!(scope, Scope::Machine).then(|| (self.groups.clone(), self.groups_await_power));
        let couplings = matches!(scope, Scope::Machine).then(|| self.couplings.clone());
        let triggers = matches!(scope, Scope::Machine).then(|| self.triggers.clone());
        let input_starts = matches!(scope, Scope::Machine).then(|| self.input_starts.clone());
        let gantry_homes = matches!(scope, Scope::Machine).then(|| self.gantry_homes.clone());
        let estop_input = matches!(scope, Scope::Machine).then_some(self.estop_input);
        let guards = matches!(scope, Scope::Machine).then(|| self.guards.clone());
        Checkpoint {
            gantry_homes,
            estop_input,
            guards,
            axes,
            groups,
            couplings,
            triggers,
            input_starts,
            io,
            slaves,
            ledger: self.ledger.checkpoint(),
        }
    }

    pub(super) fn rollback(&mut self, checkpoint: Checkpoint) {
        for (index, axis) in checkpoint.axes {
            if let Some(slot) = self.axes.get_mut(index) {
                *slot = axis;
            }
        }
        if let Some((groups, await_power)) = checkpoint.groups {
            self.groups = groups;
            self.groups_await_power = await_power;
        }
        if let Some(couplings) = checkpoint.couplings {
            self.couplings = couplings;
        }
        if let Some(triggers) = checkpoint.triggers {
            self.triggers = triggers;
        }
        if let Some(starts) = checkpoint.input_starts {
            self.input_starts = starts;
        }
        if let Some(runs) = checkpoint.gantry_homes {
            self.gantry_homes = runs;
        }
        if let Some(estop_input) = checkpoint.estop_input {
            self.estop_input = estop_input;
        }
        if let Some(guards) = checkpoint.guards {
            self.guards = guards;
        }
        if let Some(io) = checkpoint.io {
            self.io = io;
        }
        if let Some(slaves) = checkpoint.slaves {
            self.slaves = slaves;
        }
        self.ledger.rollback(checkpoint.ledger);
    }

    pub(super) fn commit(&mut self, checkpoint: Checkpoint) {
        self.ledger.commit(checkpoint.ledger);
    }
}

fn check_deceleration(deceleration: Option<f64>) -> Result<(), EngineError> {
    if let Some(d) = deceleration {
        positive("deceleration", d)?;
    }
    Ok(())
}
