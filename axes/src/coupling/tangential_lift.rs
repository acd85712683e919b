//! The tangential axis's auto lift (HMC_MoveTangConfigCornerMode mode 2, digest 000 §4.4
//! "Tangential tracking"): at a corner stop of the tracked group (the same stops as the manual
//! mode, `group::corner`) the engine lifts Z to the safe position, turns the tangential axis
//! to the next motion's direction, brings Z back to where it was and releases the path —
//! what a user does by hand in manual mode. Corner state 4 while this runs, 3 otherwise.
//!
//! Z moves by an ordinary absolute move of its own, with its own `speed`, `accel` and
//! `decel` (the manual names no other profile). A Z that refuses a move or does not end
//! it at rest (disabled, a fault, a limit) leaves the path standing at the corner and the
//! corner state at 255, HMC's error value (decisions.md, "MoveTang auto lift").
//!
//! Run at the start of stage 3, before the axes step: each phase waits for what the last
//! tick left (Z at rest, the axis on its new angle), so the sequence takes whole ticks.

use super::{Couplings, Env, Law};
use crate::axis::{Axis, MotionAction, MotionSubmission, Overrides};
use crate::command::{AxisIndex, BufferMode, CommandKind, SafeZMode};
use crate::status::AxisState;

/// The auto lift of one tangential axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lift {
    z: AxisIndex,
    safe: f64,
    mode: SafeZMode,
    phase: Phase,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    /// The path runs (or stands elsewhere than at a corner stop).
    Running,
    /// Z moves up from `z_start`.
    Lifting { z_start: f64 },
    /// The axis turns to the next motion's direction.
    Turning { z_start: f64 },
    /// Z moves back down.
    Lowering,
    /// The corner was released; the path leaves it from the next tick.
    Released,
    /// Z could not move: the path stays at the corner.
    Failed,
}

impl Lift {
    pub(crate) fn new(z: AxisIndex, safe: f64, mode: SafeZMode) -> Lift {
        Lift {
            z,
            safe,
            mode,
            phase: Phase::Running,
        }
    }

    /// HMC_GetMoveTangCornerState in auto mode.
    pub(crate) fn corner_state(&self) -> u8 {
        match self.phase {
            Phase::Running | Phase::Released => 3,
            Phase::Lifting { .. } | Phase::Turning { .. } | Phase::Lowering => 4,
            Phase::Failed => 255,
        }
    }
}

/// Start an absolute move of Z to `position` with its own limits.
fn move_z(z: &mut Axis, ctx: &mut crate::axis::Context, position: f64) -> bool {
    z.submit(
        ctx,
        MotionSubmission {
            kind: CommandKind::MoveAbsolute,
            action: MotionAction::MoveAbsolute { position },
            overrides: Overrides::default(),
            buffer_mode: BufferMode::Aborting,
        },
    )
    .is_ok()
}

/// Where Z's move stands: `Some(true)` ended at rest, `Some(false)` cannot end (disabled,
/// stopped, a fault), `None` still moving.
fn z_done(z: &Axis) -> Option<bool> {
    match z.state() {
        AxisState::Standstill => Some(true),
        AxisState::DiscreteMotion => None,
        _ => Some(false),
    }
}

impl Couplings {
    /// Stage 3, before the axes step: advance each auto lift by what the last tick left.
    pub(super) fn run_auto_lifts(&mut self, env: &mut Env) {
        for c in &mut self.list {
            let Law::Tangential(t) = &mut c.law else {
                continue;
            };
            let at_corner = t.at_corner();
            let settled = t.deviation() == 0.0;
            let group = t.group();
            let Some(lift) = t.lift_mut() else {
                continue;
            };
            let Some(z) = env.axes.get_mut(lift.z as usize) else {
                lift.phase = Phase::Failed;
                continue;
            };
            let mut follow_next = false;
            lift.phase = match lift.phase {
                Phase::Running if at_corner => {
                    let z_start = z.commanded().p;
                    let to = match lift.mode {
                        SafeZMode::Incremental => z_start + lift.safe,
                        SafeZMode::Absolute => lift.safe,
                    };
                    if move_z(z, env.ctx, to) {
                        Phase::Lifting { z_start }
                    } else {
                        Phase::Failed
                    }
                }
                Phase::Lifting { z_start } => match z_done(z) {
                    Some(true) => {
                        follow_next = true;
                        Phase::Turning { z_start }
                    }
                    Some(false) => Phase::Failed,
                    None => Phase::Lifting { z_start },
                },
                // The axis holds its angle exactly once it has turned (`Tangential::step`).
                Phase::Turning { z_start } if settled => {
                    if move_z(z, env.ctx, z_start) {
                        Phase::Lowering
                    } else {
                        Phase::Failed
                    }
                }
                Phase::Lowering => match z_done(z) {
                    Some(true) => {
                        let released = env
                            .groups
                            .group_mut(group)
                            .is_some_and(|g| g.release_corner().is_ok());
                        if released {
                            Phase::Released
                        } else {
                            Phase::Failed
                        }
                    }
                    Some(false) => Phase::Failed,
                    None => Phase::Lowering,
                },
                Phase::Released if !at_corner => Phase::Running,
                other => other,
            };
            if follow_next {
                // The group stands at the corner (checked when the lift began).
                t.follow_next();
            }
        }
    }
}
