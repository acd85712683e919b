//! One-dimensional trajectory generators (ARCHITECTURE §3.6).
//!
//! [`Profile::plan`] computes a time-optimal profile from any start state `(p, v, a)` to a
//! [`Goal`] under [`Limits`]. With `jerk = ∞` the profile is a trapezoid (piecewise constant
//! acceleration); with a finite jerk it is the jerk-limited S-curve (up to 7 phases, plus the
//! phases needed to bring an out-of-limit start back inside). Planning is closed-form or a
//! bounded root search: no allocation, no iteration per tick. Sampling is a polynomial
//! evaluation.
//!
//! Vendor rules (HMC trapezoid/triangle and JerkMode, NMC smoothCoef, CPU 226H linear ramps)
//! are expressed as choices of `Limits`/`Options` plus [`MovingAverage`] (see `rules`).

pub mod rules;
mod smoothing;

pub use smoothing::MovingAverage;

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
}

/// A planned 1-D profile. `Copy`, fixed size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Profile {
    // Filled by the planner implementation.
    start: MotionState,
    target: f64,
}

impl Profile {
    /// Plan from `start` to `goal`.
    pub fn plan(
        start: MotionState,
        goal: Goal,
        limits: &Limits,
        options: &Options,
    ) -> Result<Profile, PlanError> {
        let _ = (goal, limits, options);
        Ok(Profile::hold(start.p))
    }

    /// Standing still at `p`.
    pub fn hold(p: f64) -> Profile {
        Profile {
            start: MotionState { p, v: 0.0, a: 0.0 },
            target: p,
        }
    }

    /// Time until the goal is reached: for a position goal the end of motion, for a velocity
    /// goal the end of the ramp.
    pub fn duration(&self) -> f64 {
        0.0
    }

    /// State at time `t` after the start of the plan. For `t ≥ duration()`: a position goal
    /// returns exactly the target with v = a = j = 0; a velocity goal keeps moving at the target
    /// velocity.
    pub fn sample(&self, t: f64) -> Sample {
        let _ = t;
        Sample {
            p: self.target,
            ..Sample::default()
        }
    }
}
