//! One-dimensional trajectory generators (ARCHITECTURE §3.6).
//!
//! [`Profile::plan`] computes a time-optimal profile from any start state `(p, v, a)` to a
//! [`Goal`] under [`Limits`]. With `jerk = ∞` the profile is a trapezoid (piecewise constant
//! acceleration); with a finite jerk it is the jerk-limited S-curve (up to 7 phases, plus the
//! phases needed to bring an out-of-limit start back inside). Planning is closed-form or a
//! bounded root search: no allocation, no iteration per tick. Sampling is a polynomial
//! evaluation. [`Profile::plan_for_duration`] plans the same move stretched to a given duration
//! ≥ the time-optimal one (Ruckig's step 2, for synchronized moves; see `fixed_duration`).
//!
//! Vendor rules (HMC trapezoid/triangle and JerkMode, NMC smoothCoef, CPU 226H linear ramps)
//! are expressed as choices of `Limits`/`Options` plus [`MovingAverage`] (see [`rules`]).
//!
//! Semantics the manuals leave open are recorded in `docs/decisions.md` ("Profiles"); in short:
//! - the acceleration limit applies while |v| grows, the deceleration limit while it shrinks;
//!   a ramp through v = 0 is one ramp when both are equal and is split at v = 0 otherwise;
//! - the peak velocity is `velocity`; an end velocity or start velocity above it is lowered to
//!   it, and so is the target of a velocity goal;
//! - a position goal's end velocity points in the direction of the final approach, which is
//!   the side of the target the axis would stop on if it braked now.

mod fixed_duration;
mod plan;
mod ramp;
pub mod rules;
mod smoothing;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_fixed_duration;
#[cfg(test)]
mod tests_ruckig;

pub use fixed_duration::{DurationError, DURATION_TOL};
pub use smoothing::{MovingAverage, SmoothingError, MAX_WINDOW_TICKS};

use plan::{Plan, MAX_PHASES};
use ramp::Lim;

/// Kinematic state of the commanded motion.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MotionState {
    pub p: f64,
    pub v: f64,
    pub a: f64,
}

/// Profile value at one instant.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    pub p: f64,
    pub v: f64,
    pub a: f64,
    pub j: f64,
}

/// Kinematic limits. All strictly positive; `jerk = f64::INFINITY` plans a trapezoid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Cruise velocity (magnitude).
    pub velocity: f64,
    /// Acceleration magnitude used while |v| grows.
    pub acceleration: f64,
    /// Acceleration magnitude used while |v| shrinks.
    pub deceleration: f64,
    pub jerk: f64,
}

/// Where the profile goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Goal {
    /// Arrive at `target`, moving at `end_velocity` (a magnitude, in the direction of travel;
    /// usually 0). The profile ends there; the caller then stops (NMC endVel, CPU 226H MIN_SPEED).
    Position { target: f64, end_velocity: f64 },
    /// Reach the signed velocity `target` with zero acceleration and keep it.
    Velocity { target: f64 },
}

/// What to do when a position goal can no longer be reached without passing it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Overshoot {
    /// Brake through, come back, and arrive exactly (time-optimally).
    #[default]
    Reverse,
    /// HMC §2.3.1 quirk: keep braking with the given limits; when the target is reached the
    /// velocity jumps to zero and the profile ends there.
    JumpToZeroAtTarget,
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Options {
    /// Starting from rest (|v| below this), the velocity jumps to this magnitude in the direction
    /// of travel (NMC startVel, CPU 226H MIN_SPEED). 0 = no jump.
    pub start_velocity: f64,
    pub overshoot: Overshoot,
}

/// Why a plan was refused. The engine validates limits before planning, so these are a second
/// line of defence; they never panic.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum PlanError {
    #[error("{name} = {value}: must be a positive number")]
    InvalidLimit { name: &'static str, value: f64 },
    #[error("{name} = {value}: must be finite")]
    NotFinite { name: &'static str, value: f64 },
    #[error("{name} = {value}: must not be negative")]
    Negative { name: &'static str, value: f64 },
    /// The inputs are finite but so far apart (e.g. a velocity of 1e200 with an acceleration
    /// of 1e-200) that the profile does not fit in `f64`.
    #[error("the profile's values do not fit in f64 (limits or start state too extreme)")]
    Unrepresentable,
}

/// Phases of constant jerk; ramp 1 (≤ 6 when split at v = 0) + cruise + ramp 2 (≤ 6).
const MAX_SEGMENTS: usize = MAX_PHASES;

/// One phase of constant jerk, as its state at its start time `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Segment {
    t: f64,
    p: f64,
    v: f64,
    a: f64,
    j: f64,
}

/// The state at the start of a segment (its start time is kept apart, so that the search
/// reads one compact array).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct State {
    p: f64,
    v: f64,
    a: f64,
    j: f64,
}

/// A planned 1-D profile. `Copy`, fixed size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Profile {
    /// Segment start times; unused slots are +∞, so the search needs no length.
    starts: [f64; MAX_SEGMENTS],
    states: [State; MAX_SEGMENTS],
    len: u8,
    duration: f64,
    /// For t ≥ duration: p = end_p + end_v·(t − duration), v = end_v.
    end_p: f64,
    end_v: f64,
    /// Velocity just before `duration`.
    arrival_v: f64,
    goal: Goal,
}

/// The planner's units: velocity and acceleration limits 1 (Ruckig issue #27: pulse-sized
/// limits such as jerk 1e10, acceleration 1e6 must not reach the solver). Physical value =
/// normalised value × the scale of its kind.
#[derive(Clone, Copy, Debug)]
struct Scale {
    v: f64,
    a: f64,
    t: f64,
    p: f64,
    j: f64,
    /// The limits in these units.
    lim: Lim,
}

impl Scale {
    fn new(limits: &Limits) -> Result<Scale, PlanError> {
        let v = limits.velocity;
        let a = limits.acceleration;
        let t = v / a;
        let p = v * t;
        let j = a / t;
        let lim = Lim::new(1.0, 1.0, limits.deceleration / a, limits.jerk / j);
        let usable = |x: f64| x.is_finite() && x > 0.0;
        let jerk_usable = lim.jerk > 0.0; // may be +∞
        if usable(t) && usable(p) && usable(j) && usable(lim.dec) && jerk_usable {
            Ok(Scale { v, a, t, p, j, lim })
        } else {
            Err(PlanError::Unrepresentable)
        }
    }
}

impl Profile {
    /// Plan from `start` to `goal`.
    pub fn plan(
        start: MotionState,
        goal: Goal,
        limits: &Limits,
        options: &Options,
    ) -> Result<Profile, PlanError> {
        Profile::plan_with(start, goal, limits, options, false)
    }

    /// Plan to arrive at `target` moving *forward* (from `start.p` toward `target`) at
    /// `end_velocity`, even when the start is too fast to stop before the target: where
    /// [`Profile::plan`] would approach from the far side (its end velocity points the way of
    /// the final approach), this passes the target without turning back. For the path planner
    /// (issue 11), whose motions end at a junction velocity and may be shorter than the
    /// braking distance. The caller checks that `end_velocity` can be reached within the
    /// distance; if it cannot, the profile passes the target, comes back and arrives moving
    /// forward.
    pub fn plan_passing(
        start: MotionState,
        target: f64,
        end_velocity: f64,
        limits: &Limits,
    ) -> Result<Profile, PlanError> {
        let goal = Goal::Position {
            target,
            end_velocity,
        };
        Profile::plan_with(start, goal, limits, &Options::default(), true)
    }

    fn plan_with(
        start: MotionState,
        goal: Goal,
        limits: &Limits,
        options: &Options,
        forward: bool,
    ) -> Result<Profile, PlanError> {
        validate(start, goal, limits, options)?;
        let scale = Scale::new(limits)?;
        let lim = scale.lim;
        let mut v0 = start.v / scale.v;
        // A trapezoid's acceleration jumps, so the start acceleration does not matter.
        let mut a0 = if limits.jerk.is_finite() {
            start.a / scale.a
        } else {
            0.0
        };
        let start_velocity = (options.start_velocity / scale.v).min(1.0);

        let mut plan = Plan::new();
        let end_p = match goal {
            Goal::Position {
                target,
                end_velocity,
            } => {
                let d = (target - start.p) / scale.p;
                if start_velocity > 0.0 && d != 0.0 && v0.abs() < start_velocity {
                    // NMC startVel / CPU 226H MIN_SPEED: the motion starts at this speed.
                    v0 = start_velocity.copysign(d);
                    a0 = 0.0;
                }
                if d == 0.0 && v0 == 0.0 && a0 == 0.0 {
                    return Ok(Profile {
                        goal,
                        ..Profile::hold(target)
                    });
                }
                let e = (end_velocity / scale.v).min(1.0);
                let jump = options.overshoot == Overshoot::JumpToZeroAtTarget;
                plan::position(v0, a0, d, e, &lim, jump, forward, &mut plan);
                Some(target)
            }
            Goal::Velocity { target } => {
                let vt = (target / scale.v).clamp(-1.0, 1.0);
                if start_velocity > 0.0 && vt != 0.0 && v0.abs() < start_velocity {
                    v0 = start_velocity.min(vt.abs()).copysign(vt);
                    a0 = 0.0;
                }
                plan::velocity(v0, a0, vt, &lim, &mut plan);
                None
            }
        };
        Profile::assemble(start.p, goal, &plan, &scale, limits, end_p)
    }

    /// The profile of `plan` (normalised by `scale`) from position `p0`. `end_p` is a position
    /// goal's target; a velocity goal's profile continues from where its ramp ends.
    fn assemble(
        p0: f64,
        goal: Goal,
        plan: &Plan,
        scale: &Scale,
        limits: &Limits,
        end_p: Option<f64>,
    ) -> Result<Profile, PlanError> {
        let lim = &scale.lim;
        let end_v = match goal {
            Goal::Position { .. } => 0.0,
            Goal::Velocity { target } => target.clamp(-scale.v, scale.v),
        };
        let mut starts = [f64::INFINITY; MAX_SEGMENTS];
        let mut states = [State::default(); MAX_SEGMENTS];
        let (mut t, mut p) = (0.0, 0.0);
        let mut len = 0u8;
        // Plateaus and jerks are exactly the limits (scaling back could be off by an ulp).
        let exact = |x: f64, normalised: f64, physical: f64, scale: f64| {
            if x.abs() == normalised {
                physical.copysign(x)
            } else {
                x * scale
            }
        };
        for ((start_t, state), ph) in starts.iter_mut().zip(&mut states).zip(plan.phases()) {
            *start_t = t * scale.t;
            *state = State {
                p: p0 + p * scale.p,
                v: ph.v * scale.v,
                a: exact(ph.a, lim.dec, limits.deceleration, scale.a),
                j: exact(ph.j, lim.jerk, limits.jerk, scale.j),
            };
            p += ph.advance().0;
            t += ph.t;
            len += 1;
        }
        let end_p = end_p.unwrap_or(p0 + p * scale.p);
        let arrival_v = if matches!(goal, Goal::Velocity { .. }) {
            end_v
        } else {
            plan.end_velocity() * scale.v
        };
        let profile = Profile {
            starts,
            states,
            len,
            duration: t * scale.t,
            end_p,
            end_v,
            arrival_v,
            goal,
        };
        if profile.is_finite() {
            Ok(profile)
        } else {
            Err(PlanError::Unrepresentable)
        }
    }

    /// Standing still at `p`.
    pub fn hold(p: f64) -> Profile {
        Profile {
            starts: [f64::INFINITY; MAX_SEGMENTS],
            states: [State::default(); MAX_SEGMENTS],
            len: 0,
            duration: 0.0,
            end_p: p,
            end_v: 0.0,
            arrival_v: 0.0,
            goal: Goal::Position {
                target: p,
                end_velocity: 0.0,
            },
        }
    }

    /// Time until the goal is reached: for a position goal the end of motion, for a velocity
    /// goal the end of the ramp.
    #[inline]
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// State at time `t` after the start of the plan. For `t ≥ duration()`: a position goal
    /// returns exactly the target with v = a = j = 0; a velocity goal keeps moving at the target
    /// velocity. Times before 0 (and NaN) read as 0.
    #[inline]
    pub fn sample(&self, t: f64) -> Sample {
        self.sample_from(t, &mut 0)
    }

    /// `sample(t)` for a caller that samples at increasing times, as the servo loop does: the
    /// segment search resumes at `*segment` (from the previous call) instead of the first
    /// segment, and leaves the segment it found there. Any `*segment` value is safe; a time
    /// earlier than the hinted segment restarts the search.
    #[inline]
    pub fn sample_from(&self, t: f64, segment: &mut usize) -> Sample {
        let t = if t > 0.0 { t } else { 0.0 };
        if t >= self.duration {
            return self.after(t);
        }
        let mut i = (*segment).min(MAX_SEGMENTS - 1);
        if self.starts[i] > t {
            i = 0;
        }
        // Unused slots start at +∞, so this stops at the last segment.
        while i + 1 < MAX_SEGMENTS && self.starts[i + 1] <= t {
            i += 1;
        }
        *segment = i;
        let (t0, s) = (self.starts[i], &self.states[i]);
        let dt = t - t0;
        Sample {
            p: s.p + dt * (s.v + dt * (0.5 * s.a + dt * s.j * (1.0 / 6.0))),
            v: s.v + dt * (s.a + 0.5 * dt * s.j),
            a: s.a + dt * s.j,
            j: s.j,
        }
    }

    #[inline]
    fn after(&self, t: f64) -> Sample {
        let p = if self.end_v == 0.0 {
            // Exactly the target, bit for bit.
            self.end_p
        } else {
            self.end_p + self.end_v * (t - self.duration)
        };
        Sample {
            p,
            v: self.end_v,
            a: 0.0,
            j: 0.0,
        }
    }

    /// The state the profile leaves the axis in, i.e. `sample(duration())`: a position goal's
    /// target at rest, or the end of a velocity goal's ramp.
    pub fn final_state(&self) -> MotionState {
        MotionState {
            p: self.end_p,
            v: self.end_v,
            a: 0.0,
        }
    }

    /// The velocity just before `duration()`: a position goal's signed end velocity (or, after
    /// [`Overshoot::JumpToZeroAtTarget`], the velocity that jumps to zero); a velocity goal's
    /// target.
    pub fn arrival_velocity(&self) -> f64 {
        self.arrival_v
    }

    /// The goal as planned (before clamping to the limits).
    pub fn goal(&self) -> Goal {
        self.goal
    }

    pub fn is_velocity_goal(&self) -> bool {
        matches!(self.goal, Goal::Velocity { .. })
    }

    /// Number of constant-jerk segments (0 for a hold or an empty ramp).
    pub fn segment_count(&self) -> usize {
        usize::from(self.len)
    }

    /// Start times of the segments, in order (the first is 0).
    pub fn segment_times(&self) -> impl Iterator<Item = f64> + '_ {
        self.starts.iter().take(self.segment_count()).copied()
    }

    /// The segments with their start times.
    fn segments(&self) -> impl Iterator<Item = Segment> + '_ {
        self.starts
            .iter()
            .zip(&self.states)
            .take(self.segment_count())
            .map(|(&t, s)| Segment {
                t,
                p: s.p,
                v: s.v,
                a: s.a,
                j: s.j,
            })
    }

    /// Whether every value, and every term `sample` adds up within a segment, is finite: then
    /// sampling cannot overflow into ∞ − ∞ = NaN.
    fn is_finite(&self) -> bool {
        let ends = self
            .starts
            .iter()
            .skip(1)
            .map(|&t| t.min(self.duration))
            .chain(std::iter::once(self.duration));
        self.duration.is_finite()
            && self.end_p.is_finite()
            && self.end_v.is_finite()
            && self.arrival_v.is_finite()
            && self.segments().zip(ends).all(|(s, end)| {
                let dt = end - s.t;
                let reach =
                    s.p.abs() + dt * (s.v.abs() + dt * (0.5 * s.a.abs() + dt * s.j.abs() / 6.0));
                s.t.is_finite() && reach.is_finite()
            })
    }
}

fn validate(
    start: MotionState,
    goal: Goal,
    limits: &Limits,
    options: &Options,
) -> Result<(), PlanError> {
    let positive = |name, value: f64| {
        // NaN fails the comparison too.
        if value > 0.0 {
            Ok(())
        } else {
            Err(PlanError::InvalidLimit { name, value })
        }
    };
    let finite = |name, value: f64| {
        if value.is_finite() {
            Ok(())
        } else {
            Err(PlanError::NotFinite { name, value })
        }
    };
    let magnitude = |name, value: f64| {
        finite(name, value)?;
        if value < 0.0 {
            Err(PlanError::Negative { name, value })
        } else {
            Ok(())
        }
    };
    positive("velocity", limits.velocity)?;
    positive("acceleration", limits.acceleration)?;
    positive("deceleration", limits.deceleration)?;
    positive("jerk", limits.jerk)?;
    finite("velocity", limits.velocity)?;
    finite("acceleration", limits.acceleration)?;
    finite("deceleration", limits.deceleration)?;
    finite("start position", start.p)?;
    finite("start velocity", start.v)?;
    finite("start acceleration", start.a)?;
    magnitude("start_velocity", options.start_velocity)?;
    match goal {
        Goal::Position {
            target,
            end_velocity,
        } => {
            finite("target position", target)?;
            magnitude("end_velocity", end_velocity)
        }
        Goal::Velocity { target } => finite("target velocity", target),
    }
}
