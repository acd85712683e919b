//! [`PathPlanner`]: moves a point along a queue of segments, one servo period per
//! [`PathPlanner::step`], under each segment's path limits and every axis's own limits, with
//! look-ahead over the queued segments and blending at their junctions.
//!
//! Inputs, in any order between steps: [`PathPlanner::push_motion`] and
//! [`PathPlanner::push_marker`] (append to the queue), [`PathPlanner::set_override`],
//! [`PathPlanner::halt`] / [`PathPlanner::resume`], [`PathPlanner::stop`],
//! [`PathPlanner::abort`], [`PathPlanner::release_hold`], [`PathPlanner::reset_position`].
//! Output: [`PathPlanner::step`] advances one period, returns the new [`PathState`] and appends
//! what happened during the period ([`PathEvent`]s, in order) to the caller's vector.
//! Queries: [`PathPlanner::state`], [`PathPlanner::queued`], [`PathPlanner::queue_end`],
//! [`PathPlanner::is_idle`], [`PathPlanner::remaining_length`].
//!
//! Work per step is closed form and bounded (no iterative solve, LinuxCNC PR #4154); the
//! look-ahead runs when a segment is pushed, not per tick.

use crate::geometry::Segment;
use crate::{Point, MAX_AXES};

/// One axis's own limits, in the path's units (user units of the axis). `jerk = ∞`: none.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisLimits {
    pub velocity: f64,
    pub acceleration: f64,
    pub jerk: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct PlannerConfig {
    /// Number of axes of the path, 1–9.
    pub dims: usize,
    /// Limits of axis `0..dims` (the rest are ignored).
    pub axes: [AxisLimits; MAX_AXES],
    /// Servo period, seconds.
    pub period: f64,
    /// Segments the look-ahead plans over (≥ 64 by default).
    pub lookahead: usize,
    /// Most queued entries (motions and markers); default 512, at most 1024.
    pub capacity: usize,
}

/// Limits along the path for one motion. `jerk = ∞` plans a trapezoid along the path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathLimits {
    pub velocity: f64,
    pub acceleration: f64,
    pub deceleration: f64,
    pub jerk: f64,
}

/// How a motion joins the one queued before it (PLCopen Part 4 buffer modes, HIMC BM_*).
/// `Aborting` is the caller's business (it aborts the queue, then pushes the motion).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Join {
    /// Stop exactly at the end of the previous motion, then start.
    #[default]
    Buffered,
    /// Pass the junction at the lower of the two motions' velocities.
    BlendingLow,
    /// … at the previous motion's velocity.
    BlendingPrevious,
    /// … at this motion's velocity.
    BlendingNext,
    /// … at the higher of the two.
    BlendingHigh,
}

/// The geometry at a blended junction (HIMC TM_*, PLCopen transition modes, G64 P).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Transition {
    /// No corner geometry: the path goes through the corner point; the junction speed is
    /// what every axis's acceleration allows for the change of direction.
    #[default]
    None,
    /// Round the corner, starting at most this path distance before it (TMCornerDistance).
    CornerDistance(f64),
    /// Round the corner, passing it at most this far away (G64 P, max corner deviation).
    CornerDeviation(f64),
}

/// One queued motion.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    pub segment: Segment,
    pub limits: PathLimits,
    pub join: Join,
    pub transition: Transition,
    /// The caller's tag, reported back in [`PathEvent`]s and [`PathState::tag`].
    pub tag: u64,
}

/// What a queued marker does when the path reaches it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MarkerKind {
    /// Reported as the path passes it; the path does not slow down for it (a buffered DO, a
    /// single-axis move that starts with the next segment).
    PassThrough,
    /// The path stops exactly here and waits for [`PathPlanner::release_hold`] (dwell, wait
    /// for a DI or an axis position).
    Hold,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PlannerError {
    #[error("the queue is full ({capacity} entries)")]
    QueueFull { capacity: usize },
    #[error("{0}")]
    Invalid(&'static str),
}

/// Something that happened during one step, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathEvent {
    /// A motion became the one being executed.
    Started { tag: u64 },
    /// A motion reached its end (the next may already have started in the same step).
    Done { tag: u64 },
    /// A marker was reached (for `Hold`, the path is at rest there).
    Marker { tag: u64, kind: MarkerKind },
    /// A halt or stop has brought the path to rest.
    AtRest,
    /// A queued motion or marker was dropped by `stop` or `abort`.
    Dropped { tag: u64 },
}

/// The path's commanded state after the last step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathState {
    /// Position, velocity and acceleration of every axis.
    pub position: Point,
    pub velocity: Point,
    pub acceleration: Point,
    /// Path length travelled since the planner was made (grows, never resets).
    pub travelled: f64,
    /// Path velocity and acceleration (along the tangent).
    pub path_velocity: f64,
    pub path_acceleration: f64,
    /// Tag of the motion being executed, if any.
    pub tag: Option<u64>,
    /// Motions completed since the planner was made.
    pub completed: u64,
    /// Waiting at a `Hold` marker (its tag).
    pub holding: Option<u64>,
    /// Halted (or halting): the queue is kept, the path waits for `resume`.
    pub halted: bool,
}

/// See the module doc.
#[derive(Debug)]
pub struct PathPlanner {
    config: PlannerConfig,
    state: PathState,
}

impl PathPlanner {
    pub fn new(config: PlannerConfig, position: Point) -> Result<PathPlanner, PlannerError> {
        let state = PathState {
            position,
            ..PathState::default()
        };
        Ok(PathPlanner { config, state })
    }

    pub fn config(&self) -> &PlannerConfig {
        &self.config
    }

    /// Where the path is (at rest, queue empty): the next motion starts here. Refused while
    /// moving.
    pub fn reset_position(&mut self, position: Point) -> Result<(), PlannerError> {
        self.state.position = position;
        Ok(())
    }

    /// Change one axis's limits (a parameter changed); applies to motions pushed from now on.
    pub fn set_axis_limits(&mut self, axis: usize, limits: AxisLimits) {
        if let Some(l) = self.config.axes.get_mut(axis) {
            *l = limits;
        }
    }

    /// Append a motion. Its segment must start at [`PathPlanner::queue_end`].
    pub fn push_motion(&mut self, motion: Motion) -> Result<(), PlannerError> {
        let _ = motion;
        Err(PlannerError::Invalid("the path planner is not built yet"))
    }

    pub fn push_marker(&mut self, tag: u64, kind: MarkerKind) -> Result<(), PlannerError> {
        let _ = (tag, kind);
        Err(PlannerError::Invalid("the path planner is not built yet"))
    }

    /// The end point of the last queued motion, or the current position when none is queued.
    pub fn queue_end(&self) -> Point {
        self.state.position
    }

    /// Path velocity scale, (0, 10] (NMC CrdSetOverride; HIMC SetGrpVelScale 0–100 % is
    /// 0–1). Takes effect at once, within every limit.
    pub fn set_override(&mut self, factor: f64) {
        let _ = factor;
    }

    /// Decelerate to rest along the path with `deceleration` (None: each motion's own) and
    /// keep the queue; [`PathPlanner::resume`] goes on.
    pub fn halt(&mut self, deceleration: Option<f64>) {
        let _ = deceleration;
        self.state.halted = true;
    }

    pub fn resume(&mut self) {
        self.state.halted = false;
    }

    /// Decelerate to rest along the path with `deceleration`, then drop the queue.
    pub fn stop(&mut self, deceleration: f64) {
        let _ = deceleration;
    }

    /// Stop at once where the path is (velocity 0 this tick) and drop the queue; for a fault
    /// the caller has already handled (the axes stop on their own).
    pub fn abort(&mut self, events: &mut Vec<PathEvent>) {
        let _ = events;
    }

    /// Go on past the `Hold` marker the path waits at.
    pub fn release_hold(&mut self) {
        self.state.holding = None;
    }

    /// Advance one period.
    pub fn step(&mut self, events: &mut Vec<PathEvent>) -> &PathState {
        let _ = events;
        &self.state
    }

    pub fn state(&self) -> &PathState {
        &self.state
    }

    /// Queued entries (the motion being executed counts).
    pub fn queued(&self) -> usize {
        0
    }

    /// Nothing queued and at rest.
    pub fn is_idle(&self) -> bool {
        true
    }

    /// Path length left to the end of the last queued motion.
    pub fn remaining_length(&self) -> f64 {
        0.0
    }
}
