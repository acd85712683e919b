//! A group's path time by a dry run of the engine itself (NMC `NMC_CrdStartExeTimeCalc` /
//! `_NMC_CrdGetExeTime`, digest 001 §2.7 (11)–(12)): the commands are applied and the machine
//! stepped, with everything a whole-machine [`Checkpoint`](super::machine::Checkpoint) saves,
//! until the group is at rest; then all of it is put back. The count is what running the
//! commands takes, tick for tick, because it is the same code running them: the path planner's
//! look-ahead, blending, arcs, dwells and buffered I/O, the members' own limits.
//!
//! Left out of the dry run: the registered machine-level planners and the samplers (their
//! state is not checkpointed), and the runtime's observers and fieldbuses (the runtime calls
//! them around each real step, never here: a drive mastered from outside the engine gets no
//! frames meanwhile). The tick counter is put back too.

use super::{Engine, Stages};
use crate::command::{Command, EngineError, EstimateGroupTime, GroupId, MachineCommand, Reply};
use crate::status::GroupState;

/// Servo periods a dry run may step before it gives up (a path waiting on an input that never
/// comes would run for ever): 10⁶, a quarter of an hour at 1 ms. The work is done between two
/// ticks of the servo thread, so the bound is also the longest pause a dry run may cause.
pub const MAX_DRY_RUN_TICKS: u64 = 1_000_000;

impl Engine {
    /// `estimate_group_time`: the servo periods from now until `group` is at rest after
    /// `commands` (applied in order, as an atomic batch would be), as `Reply::Value`. The
    /// engine is left exactly as it was. A command refused, a group that faults on the way or
    /// a path longer than [`MAX_DRY_RUN_TICKS`] is an error.
    pub(super) fn estimate_group_time(
        &mut self,
        c: EstimateGroupTime,
    ) -> Result<Reply, EngineError> {
        if self.groups.get(c.group).is_none() {
            return Err(EngineError::UnknownGroup { group: c.group });
        }
        // What a checkpoint does not put back cannot be in a dry run.
        if let Some(index) = c.commands.iter().position(|k| {
            matches!(
                k,
                Command::Sampling(_) | Command::Machine(MachineCommand::EstimateGroupTime(_))
            )
        }) {
            return Err(EngineError::item(
                "commands",
                index,
                EngineError::InvalidArgument {
                    name: "commands",
                    value: index as f64,
                    reason: "a dry run holds no sampling command and no other estimate",
                },
            ));
        }
        let checkpoint = self.checkpoint(super::machine::Scope::Machine);
        let tick = self.tick;
        let result = self.dry_run(c.group, c.commands);
        self.rollback(checkpoint);
        self.tick = tick;
        result.map(|ticks| Reply::Value {
            value: ticks as f64,
        })
    }

    /// Apply `commands`, then step until `group` is neither moving nor stopping; the number of
    /// steps taken.
    fn dry_run(&mut self, group: GroupId, commands: Vec<Command>) -> Result<u64, EngineError> {
        for (index, command) in commands.into_iter().enumerate() {
            self.apply(command)
                .map_err(|e| EngineError::item("commands", index, e))?;
        }
        let mut ticks = 0;
        loop {
            let state = self
                .groups
                .get(group)
                .map(|g| g.state())
                .ok_or(EngineError::UnknownGroup { group })?;
            match state {
                GroupState::Moving | GroupState::Stopping => {}
                GroupState::ErrorStop => {
                    return Err(EngineError::InvalidPath {
                        group,
                        reason: format!("the group faulted after {ticks} ticks of the dry run"),
                    })
                }
                GroupState::Disabled | GroupState::Standby | GroupState::Halted => {
                    return Ok(ticks)
                }
            }
            if ticks >= MAX_DRY_RUN_TICKS {
                return Err(EngineError::InvalidPath {
                    group,
                    reason: format!("the path does not end within {MAX_DRY_RUN_TICKS} ticks"),
                });
            }
            self.advance(Stages::DryRun);
            ticks += 1;
        }
    }
}
