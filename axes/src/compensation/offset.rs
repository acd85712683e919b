//! HMC axis position compensation (manual §4.4.12: HMC_SetAxisCompenPos, _SetAxisCompenPara,
//! _TrigAxisCompens, _StopAxisCompens, _GetAxisCompenState; digest 000 §4.4): an offset of
//! the axis's output, moved on command by its own 1-D profile, added after the planner with the
//! other corrections (so `cmd_pos`, HMC DPos, does not show it; `output_pos` and the motor do).
//!
//! Per tick the work is one profile sample.

use crate::profile::{Goal, Limits, MotionState, Options, Profile};

use crate::command::{CompensationOffsetProfile, MAX_MAGNITUDE};
use crate::error::EngineError;

#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Offset {
    /// The amount the next trigger moves by (HMC dCompenVal).
    amount: f64,
    limits: Option<Limits>,
    /// Where the offset stands and how it moves, after the last tick.
    now: MotionState,
    running: Option<Run>,
}

#[derive(Clone, Debug, PartialEq)]
struct Run {
    plan: Profile,
    target: f64,
    /// Seconds since the plan's start, and the servo period.
    t: f64,
    period: f64,
    segment: usize,
}

impl Offset {
    pub(super) fn set_amount(&mut self, axis: u32, amount: f64) -> Result<(), EngineError> {
        if !amount.is_finite() || amount.abs() > MAX_MAGNITUDE {
            return Err(bad(
                axis,
                format!("offset amount = {amount}: must be a finite number within ±1e12"),
            ));
        }
        self.amount = amount;
        Ok(())
    }

    /// New limits; a move in progress is replanned from where it stands ("实时生效").
    pub(super) fn set_profile(
        &mut self,
        axis: u32,
        c: &CompensationOffsetProfile,
    ) -> Result<(), EngineError> {
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 && v <= MAX_MAGNITUDE {
                Ok(v)
            } else {
                Err(bad(
                    axis,
                    format!("offset {name} = {v}: must be a finite number > 0"),
                ))
            }
        };
        let limits = Limits {
            velocity: positive("velocity", c.velocity)?,
            acceleration: positive("acceleration", c.acceleration)?,
            deceleration: positive("deceleration", c.deceleration)?,
            jerk: if c.s_curve {
                positive("jerk", c.jerk)?
            } else {
                f64::INFINITY
            },
        };
        let replanned = match &self.running {
            Some(r) => Some(plan(axis, self.now, r.target, &limits, r.period)?),
            None => None,
        };
        self.limits = Some(limits);
        if replanned.is_some() {
            self.running = replanned;
        }
        Ok(())
    }

    /// Start a move by the amount from where the offset stands (a move in progress is
    /// abandoned there).
    pub(super) fn trigger(&mut self, axis: u32, period: f64) -> Result<(), EngineError> {
        let limits = self.limits.ok_or_else(|| {
            bad(
                axis,
                "no offset profile: send compensation_offset_profile first".into(),
            )
        })?;
        let target = self.now.p + self.amount;
        self.running = Some(plan(axis, self.now, target, &limits, period)?);
        Ok(())
    }

    /// Stop at once where it stands.
    pub(super) fn stop(&mut self) {
        self.running = None;
        self.now.v = 0.0;
        self.now.a = 0.0;
    }

    /// This tick's offset.
    pub(super) fn step(&mut self) -> f64 {
        if let Some(r) = self.running.as_mut() {
            r.t += r.period;
            if r.t >= r.plan.duration() {
                // Exactly the target at the end, not the plan's rounding of it.
                self.now = MotionState {
                    p: r.target,
                    v: 0.0,
                    a: 0.0,
                };
                self.running = None;
            } else {
                let s = r.plan.sample_from(r.t, &mut r.segment);
                self.now = MotionState {
                    p: s.p,
                    v: s.v,
                    a: s.a,
                };
            }
        }
        self.now.p
    }

    pub(super) fn position(&self) -> f64 {
        self.now.p
    }

    /// HMC GetAxisCompenState 1.
    pub(super) fn is_moving(&self) -> bool {
        self.running.is_some()
    }
}

fn plan(
    axis: u32,
    from: MotionState,
    target: f64,
    limits: &Limits,
    period: f64,
) -> Result<Run, EngineError> {
    let plan = Profile::plan(
        from,
        Goal::Position {
            target,
            end_velocity: 0.0,
        },
        limits,
        &Options::default(),
    )
    .map_err(|e| bad(axis, format!("the offset's move cannot be planned: {e}")))?;
    Ok(Run {
        plan,
        target,
        t: 0.0,
        period,
        segment: 0,
    })
}

fn bad(axis: u32, reason: String) -> EngineError {
    EngineError::InvalidCompensation { axis, reason }
}
