//! [`PathPlanner`]: moves a point along a queue of segments, one servo period per
//! [`PathPlanner::step`], under each segment's path limits and every axis's own limits, with
//! look-ahead over the queued segments and blending at their junctions (issue 11 items 3–4).
//!
//! Inputs, in any order between steps: [`PathPlanner::push_motion`] and
//! [`PathPlanner::push_marker`] (append to the queue), [`PathPlanner::set_override`],
//! [`PathPlanner::halt`] / [`PathPlanner::resume`], [`PathPlanner::stop`],
//! [`PathPlanner::abort`], [`PathPlanner::release_hold`], [`PathPlanner::reset_position`],
//! [`PathPlanner::set_axis_limits`], and the vendor rules [`PathPlanner::set_corner_angles`],
//! [`PathPlanner::set_lookahead_limits`], [`PathPlanner::set_merge_rule`].
//! Output: [`PathPlanner::step`] advances one period, returns the new [`PathState`] and appends
//! what happened during the period ([`PathEvent`]s, in order) to the caller's vector.
//! Queries: [`PathPlanner::state`], [`PathPlanner::queued`], [`PathPlanner::queue_end`],
//! [`PathPlanner::is_idle`], [`PathPlanner::remaining_length`],
//! [`PathPlanner::stopping_distance`] and [`PathPlanner::advance_toward`] (a guard), and for
//! benchmarks
//! [`PathPlanner::starts_last_step`] and [`PathPlanner::lookahead_visits`].
//!
//! How (docs/decisions.md, "Path planner (issue 11)"): each motion runs a 1-D
//! `profile::Profile` along its path length (`execution`), under path limits derived from the
//! axes (`limits`); its end velocity comes from a backward look-ahead pass (`lookahead`) over
//! junction velocities (`junction`: PLCopen Part 4 buffer modes, the corner rule) and corner
//! arcs (`blend`), all decided when a motion is pushed (`push`). Work per step is closed form
//! and bounded: at most one re-plan, and per motion started (≤ [`MAX_STARTS_PER_STEP`]) one
//! profile plan and at most one look-ahead pass over the window — no iterative solve
//! (LinuxCNC PR #4154). No allocation per step once the queue has grown.

use std::collections::VecDeque;

use crate::geometry::{norm, sub, Segment, POINT_TOLERANCE};
use crate::{Point, MAX_AXES};

mod blend;
mod braking;
mod execution;
mod freeze;
mod junction;
mod limits;
mod lookahead;
mod merge;
mod push;
mod queue;
mod reach;

pub use braking::braking_distance;
use execution::Execution;
pub use execution::MAX_STARTS_PER_STEP;
pub use merge::MergeRule;
use queue::Entry;

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

impl PlannerConfig {
    /// Default look-ahead depth (LinuxCNC's is 50; issue 11 asks for at least 64).
    pub const DEFAULT_LOOKAHEAD: usize = 64;
    /// Default queue capacity (issue 11 item 1).
    pub const DEFAULT_CAPACITY: usize = 512;
    /// Largest queue capacity (issue 11 item 1).
    pub const MAX_CAPACITY: usize = 1024;

    /// `dims` axes with the same limits, the default look-ahead and capacity.
    pub fn uniform(dims: usize, axis: AxisLimits, period: f64) -> PlannerConfig {
        PlannerConfig {
            dims,
            axes: [axis; MAX_AXES],
            period,
            lookahead: Self::DEFAULT_LOOKAHEAD,
            capacity: Self::DEFAULT_CAPACITY,
        }
    }
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

/// The corner-angle rule of HMC merge (`HMC_SetMergeAngle(axis, decelAngle, stopAngle)`,
/// digest 000 §3.4) and NMC look-ahead (`slowAng`, `stopAng`, digest 001 §3.9), for junctions
/// without corner geometry. θ is the angle between the directions before and after the
/// junction, radians: below `slow` the buffer mode's velocity applies; from `slow` to `stop`
/// it is scaled by `k = (θ − stop)/(slow − stop)`; from `stop` on the path stops there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerAngles {
    pub slow: f64,
    pub stop: f64,
}

impl CornerAngles {
    /// HMC's defaults: π/6 and π/2.
    pub const HMC_DEFAULT: CornerAngles = CornerAngles {
        slow: std::f64::consts::FRAC_PI_6,
        stop: std::f64::consts::FRAC_PI_2,
    };

    /// The factor on the junction velocity for a direction change of `theta` radians.
    pub fn factor(&self, theta: f64) -> f64 {
        if theta < self.slow {
            1.0
        } else if theta >= self.stop {
            0.0
        } else {
            ((theta - self.stop) / (self.slow - self.stop)).clamp(0.0, 1.0)
        }
    }
}

/// HIMC's look-ahead limits (`SetGrpLookAheadPrm(gid, prm_id, value)`: 0 corner acceleration,
/// 1 arc acceleration, 2 chord error; digest 004 §2.7, §8.1.4 Table 8.1.4.2), and NMC's
/// `accMax` and `centAcc` (digest 001 §3.9). Each is off when `None`; they only ever lower
/// the path speed below what the axes' own limits allow.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LookaheadLimits {
    /// Acceleration allowed for the direction change at a junction without corner geometry
    /// (HIMC A_corner, default 5000 mm/s²; NMC accMax): the junction speed is at most
    /// `A_corner·T/|t₁ − t₂|`, the same rule as the axes' own (see `junction::corner_cap`).
    pub corner_acceleration: Option<f64>,
    /// Centripetal acceleration on curves (HIMC A_arc, default 100 mm/s²; NMC centAcc):
    /// `v ≤ √(A_arc·r)`.
    pub arc_acceleration: Option<f64>,
    /// Largest chord error ε of one servo period's chord on a curve (HIMC, off by default):
    /// `v ≤ 2·r·acos(1 − ε/r)/T`. With `chord_error_bands`, the error of radii up to the
    /// first band edge.
    pub chord_error: Option<f64>,
    /// NMC's arc-section table (`TArcSecSetting`, digest 001 §3.9: "[0,r0]→err0;
    /// [r0,r1]→err1; [r1,+max]→err2"): radii above `edges[0]` take `errors[0]`, above
    /// `edges[1]` `errors[1]` (`None`: no chord limit in that band; see
    /// [`ChordErrorBands::error_for`]). Off when `None` or both edges are 0: then `chord_error`
    /// holds at every radius.
    pub chord_error_bands: Option<ChordErrorBands>,
    /// The speed one coordinate may have at a corner: `(coordinate, speed)` (NMC
    /// `NMC_CrdSetFourthAxisToTurnVel`, the A axis of 4-D interpolation: "若大于该速度，则需要进行
    /// 降速处理"). Where the direction turns at a junction without a blend, the junction
    /// speed is at most `speed / max(|t₁[k]|, |t₂[k]|)`.
    pub corner_coordinate_velocity: Option<(usize, f64)>,
}

/// The radius bands of a chord error table above its first band (see
/// [`LookaheadLimits::chord_error_bands`]): the band edges (ascending: the caller's to keep)
/// and the error of each band.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ChordErrorBands {
    pub edges: [f64; 2],
    pub errors: [Option<f64>; 2],
}

impl ChordErrorBands {
    /// The chord error of a curve of radius `r`; `first` up to the first edge. Both edges 0:
    /// no bands (`first` everywhere); a second edge not above the first: no second band.
    pub fn error_for(&self, r: f64, first: Option<f64>) -> Option<f64> {
        let [r0, r1] = self.edges;
        if r0 <= 0.0 && r1 <= 0.0 {
            first
        } else if r1 > r0 && r > r1 {
            self.errors[1]
        } else if r > r0 {
            self.errors[0]
        } else {
            first
        }
    }
}

impl LookaheadLimits {
    /// HIMC's defaults (digest 004 §3: 5000 mm/s², 100 mm/s², chord error off).
    pub const HIMC_DEFAULT: LookaheadLimits = LookaheadLimits {
        corner_acceleration: Some(5000.0),
        arc_acceleration: Some(100.0),
        chord_error: None,
        chord_error_bands: None,
        corner_coordinate_velocity: None,
    };

    /// Cap on the path speed of a segment whose largest curvature is `curvature`.
    pub(crate) fn curve_cap(&self, curvature: f64, period: f64) -> f64 {
        if curvature <= 0.0 || !curvature.is_finite() {
            return f64::INFINITY;
        }
        let r = 1.0 / curvature;
        let mut cap = f64::INFINITY;
        if let Some(a) = self.arc_acceleration {
            cap = cap.min((a * r).sqrt());
        }
        let chord_error = match self.chord_error_bands {
            Some(b) => b.error_for(r, self.chord_error),
            None => self.chord_error,
        };
        if let Some(e) = chord_error {
            // Half the angle a chord of one period subtends when it is ε from the arc.
            let half = (1.0 - (e / r).min(1.0)).acos();
            cap = cap.min(2.0 * r * half / period);
        }
        cap
    }

    fn check(&self) -> Result<(), PlannerError> {
        if let Some(b) = self.chord_error_bands {
            if !b.edges.iter().all(|r| *r >= 0.0 && r.is_finite()) {
                return Err(PlannerError::Invalid(
                    "chord error band edges must be finite and ≥ 0",
                ));
            }
        }
        for v in [
            self.corner_acceleration,
            self.arc_acceleration,
            self.chord_error,
            self.corner_coordinate_velocity.map(|(_, v)| v),
        ]
        .into_iter()
        .chain(self.chord_error_bands.into_iter().flat_map(|b| b.errors))
        .flatten()
        {
            if !(v > 0.0 && v.is_finite()) {
                return Err(PlannerError::Invalid(
                    "look-ahead limits must be positive finite numbers",
                ));
            }
        }
        Ok(())
    }
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

/// A halt or stop in progress (PLCopen Part 4 MC_GroupHalt / MC_GroupStop).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Halt {
    /// Path deceleration; `None`: each motion's own.
    deceleration: Option<f64>,
    /// Drop the queue once at rest.
    stop: bool,
}

/// See the module doc.
#[derive(Clone, Debug)]
pub struct PathPlanner {
    config: PlannerConfig,
    state: PathState,
    queue: VecDeque<Entry>,
    /// Queued entries the caller pushed (blend arcs are not counted).
    user_entries: usize,
    override_factor: f64,
    /// The front motion's profile, once it has started.
    exec: Option<Execution>,
    /// Path velocity at the junction reached when no motion is executing (0 at rest).
    carry: f64,
    /// Where the path is when no motion is executing, and its last direction.
    position: Point,
    end_tangent: Point,
    /// The executing motion's profile is to be planned again from the current state.
    replan_pending: bool,
    halt: Option<Halt>,
    at_rest_reported: bool,
    hold_released: bool,
    starts_last_step: usize,
    /// Queue entries the look-ahead visited since the last step began (its work).
    lookahead_visits: usize,
    /// HMC merge angles / NMC slow and stop angles, if set.
    corner_angles: Option<CornerAngles>,
    /// HMC's merge rules, if set (`merge`).
    merge_rule: Option<MergeRule>,
    lookahead_limits: LookaheadLimits,
}

impl PathPlanner {
    pub fn new(config: PlannerConfig, position: Point) -> Result<PathPlanner, PlannerError> {
        if config.dims == 0 || config.dims > MAX_AXES {
            return Err(PlannerError::Invalid("a path has 1 to 9 axes"));
        }
        for lim in config.axes.iter().take(config.dims) {
            limits::check_axis_limits(lim).map_err(PlannerError::Invalid)?;
        }
        if !(config.period > 0.0 && config.period.is_finite()) {
            return Err(PlannerError::Invalid(
                "the period must be a positive finite number",
            ));
        }
        if config.lookahead == 0 {
            return Err(PlannerError::Invalid(
                "the look-ahead needs at least 1 motion",
            ));
        }
        if config.capacity == 0 || config.capacity > PlannerConfig::MAX_CAPACITY {
            return Err(PlannerError::Invalid(
                "the queue capacity must be 1 to 1024",
            ));
        }
        if position.iter().any(|c| !c.is_finite()) {
            return Err(PlannerError::Invalid("the start position must be finite"));
        }
        let state = PathState {
            position,
            ..PathState::default()
        };
        // Room for the pushed entries plus one blend arc per motion: no allocation later.
        let queue = VecDeque::with_capacity(2 * config.capacity + 1);
        Ok(PathPlanner {
            config,
            state,
            queue,
            user_entries: 0,
            override_factor: 1.0,
            exec: None,
            carry: 0.0,
            position,
            end_tangent: [0.0; MAX_AXES],
            replan_pending: false,
            halt: None,
            at_rest_reported: false,
            corner_angles: None,
            merge_rule: None,
            lookahead_limits: LookaheadLimits::default(),
            hold_released: false,
            starts_last_step: 0,
            lookahead_visits: 0,
        })
    }

    pub fn config(&self) -> &PlannerConfig {
        &self.config
    }

    /// Where the path is (at rest, queue empty): the next motion starts here. Refused while
    /// moving.
    pub fn reset_position(&mut self, position: Point) -> Result<(), PlannerError> {
        if !self.is_idle() {
            return Err(PlannerError::Invalid(
                "the path position can only be set at rest with an empty queue",
            ));
        }
        if position.iter().any(|c| !c.is_finite()) {
            return Err(PlannerError::Invalid("the position must be finite"));
        }
        self.position = position;
        self.state.position = position;
        Ok(())
    }

    /// Change one axis's limits (a parameter changed); applies to motions pushed from now on.
    /// Limits that are not positive (velocity and acceleration finite) are ignored: the
    /// engine validates parameters before they get here.
    pub fn set_axis_limits(&mut self, axis: usize, limits: AxisLimits) {
        if limits::check_axis_limits(&limits).is_err() {
            return;
        }
        if let Some(l) = self.config.axes.get_mut(axis) {
            *l = limits;
        }
    }

    /// Append a motion. Its segment must start at [`PathPlanner::queue_end`].
    pub fn push_motion(&mut self, motion: Motion) -> Result<(), PlannerError> {
        self.check_motion(&motion)?;
        let end = self.queue_end();
        let gap = norm(&sub(&motion.segment.start(), &end));
        if gap.is_nan() || gap > POINT_TOLERANCE * (1.0 + norm(&end)) {
            return Err(PlannerError::Invalid(
                "the segment does not start where the queue ends",
            ));
        }
        limits::check_path_limits(&motion.limits).map_err(PlannerError::Invalid)?;
        match motion.transition {
            Transition::None => {}
            Transition::CornerDistance(x) | Transition::CornerDeviation(x) => {
                if !(x >= 0.0 && x.is_finite()) {
                    return Err(PlannerError::Invalid(
                        "the corner distance or deviation must be a finite number ≥ 0",
                    ));
                }
            }
        }
        let first_new = self.queue.len();
        let dirty = self.append_motion(motion);
        self.user_entries += 1;
        self.lookahead(dirty.min(first_new));
        Ok(())
    }

    pub fn push_marker(&mut self, tag: u64, kind: MarkerKind) -> Result<(), PlannerError> {
        self.check_room()?;
        self.queue.push_back(Entry::Marker { tag, kind });
        self.user_entries += 1;
        Ok(())
    }

    /// What any motion must be to enter the queue, wherever it goes: room for it, the path's
    /// axis count, a finite length.
    fn check_motion(&self, motion: &Motion) -> Result<(), PlannerError> {
        self.check_room()?;
        if motion.segment.dims() != self.config.dims {
            return Err(PlannerError::Invalid(
                "the segment's axis count differs from the path's",
            ));
        }
        if !motion.segment.length().is_finite() {
            return Err(PlannerError::Invalid("the segment's length is not finite"));
        }
        Ok(())
    }

    fn check_room(&self) -> Result<(), PlannerError> {
        if self.user_entries >= self.config.capacity {
            return Err(PlannerError::QueueFull {
                capacity: self.config.capacity,
            });
        }
        Ok(())
    }

    /// The end point of the last queued motion, or the current position when none is queued.
    pub fn queue_end(&self) -> Point {
        self.queue
            .iter()
            .rev()
            .find_map(|e| match e {
                Entry::Motion(m) => Some(m.segment.end()),
                Entry::Marker { .. } => None,
            })
            .unwrap_or(self.position)
    }

    /// Slow down at sharp corners between blended motions (HMC `HMC_SetMergeAngle`, digest 000
    /// §3.4; NMC `TLookaheadPara` slowAng/stopAng, digest 001 §3.9): applies to motions pushed
    /// from now on. `None` turns the rule off (the default). Refused unless
    /// `0 ≤ slow ≤ stop ≤ π`.
    pub fn set_corner_angles(&mut self, angles: Option<CornerAngles>) -> Result<(), PlannerError> {
        if let Some(a) = angles {
            let ok = |x: f64| (0.0..=std::f64::consts::PI).contains(&x);
            if !(ok(a.slow) && ok(a.stop) && a.slow <= a.stop) {
                return Err(PlannerError::Invalid(
                    "corner angles need 0 ≤ slow ≤ stop ≤ π radians",
                ));
            }
        }
        self.corner_angles = angles;
        Ok(())
    }

    pub fn corner_angles(&self) -> Option<CornerAngles> {
        self.corner_angles
    }

    /// Set the vendor look-ahead limits (see [`LookaheadLimits`]); they apply to motions pushed
    /// from now on. Refused unless every value set is positive and finite.
    pub fn set_lookahead_limits(&mut self, limits: LookaheadLimits) -> Result<(), PlannerError> {
        limits.check()?;
        self.lookahead_limits = limits;
        Ok(())
    }

    pub fn lookahead_limits(&self) -> LookaheadLimits {
        self.lookahead_limits
    }

    /// Path velocity scale, (0, 10] (NMC CrdSetOverride; HIMC SetGrpVelScale 0–100 % is
    /// 0–1). Takes effect at once, within every limit: the executing motion is planned again
    /// from its current state, so the speed changes with the path acceleration and
    /// deceleration (no velocity step). A factor above 10 counts as 10; NaN and factors ≤ 0
    /// are ignored (the engine refuses them with a typed error before they get here).
    pub fn set_override(&mut self, factor: f64) {
        if factor.is_nan() || factor <= 0.0 {
            return;
        }
        let factor = factor.min(10.0);
        if factor == self.override_factor {
            return;
        }
        self.override_factor = factor;
        self.lookahead(usize::MAX);
        if self.exec.is_some() {
            self.replan_pending = true;
        }
    }

    /// The override factor in effect.
    pub fn override_factor(&self) -> f64 {
        self.override_factor
    }

    /// Decelerate to rest along the path with `deceleration` (None: each motion's own) and
    /// keep the queue; [`PathPlanner::resume`] goes on. The deceleration never exceeds what
    /// the axes allow on the motion being executed; a deceleration that is not a positive
    /// number counts as None.
    pub fn halt(&mut self, deceleration: Option<f64>) {
        self.begin_halt(deceleration, false);
        self.state.halted = true;
    }

    pub fn resume(&mut self) {
        if self.halt.is_some_and(|h| !h.stop) {
            self.halt = None;
            self.state.halted = false;
            self.at_rest_reported = false;
            if self.exec.is_some() {
                self.replan_pending = true;
            }
        }
    }

    /// Decelerate to rest along the path with `deceleration`, then drop the queue.
    pub fn stop(&mut self, deceleration: f64) {
        self.begin_halt(Some(deceleration), true);
        self.state.halted = false;
    }

    fn begin_halt(&mut self, deceleration: Option<f64>, stop: bool) {
        let deceleration = deceleration.filter(|d| *d > 0.0);
        self.halt = Some(Halt { deceleration, stop });
        self.at_rest_reported = false;
        if self.exec.is_some() {
            self.replan_pending = true;
        }
    }

    /// Stop at once where the path is (velocity 0 this tick) and drop the queue; for a fault
    /// the caller has already handled (the axes stop on their own).
    pub fn abort(&mut self, events: &mut Vec<PathEvent>) {
        self.drop_queue(events);
        self.halt = None;
        self.state.halted = false;
        self.at_rest_reported = false;
    }

    /// Go on past the `Hold` marker the path waits at.
    pub fn release_hold(&mut self) {
        if self.state.holding.is_some() {
            self.hold_released = true;
        }
    }

    /// Advance one period.
    pub fn step(&mut self, events: &mut Vec<PathEvent>) -> &PathState {
        self.advance(events);
        &self.state
    }

    /// An upper bound on the path length travelled from now to rest when a
    /// [`PathPlanner::stop`] with `deceleration` is issued `delay` seconds from now (a guard
    /// that checks once a period passes the period): until then the path may still speed up,
    /// at its acceleration now and, with a jerk limit, by `jerk·delay` more (never above the
    /// largest queued acceleration), up to the fastest queued cruise velocity; then it brakes with the lowest deceleration and jerk of
    /// every queued motion (a stop never brakes harder than a motion allows, and it may cross
    /// motion ends). Closed form over the queue: O(queued). A guard between two paths uses it
    /// (issue 11, NMC `SetMvProtect`).
    pub fn stopping_distance(&self, delay: f64, deceleration: f64) -> f64 {
        let v = self.state.path_velocity.max(0.0);
        let a = self.state.path_acceleration;
        if v <= 0.0 && a <= 0.0 {
            return 0.0;
        }
        let (mut dec, mut jerk, mut acc, mut top) = (deceleration, f64::INFINITY, 0.0_f64, v);
        for entry in &self.queue {
            if let Entry::Motion(m) = entry {
                dec = dec.min(m.limits.deceleration);
                jerk = jerk.min(m.limits.jerk);
                acc = acc.max(m.limits.acceleration);
                top = top.max(m.cruise(self.override_factor));
            }
        }
        let delay = delay.max(0.0);
        // The acceleration at the stop, and the speed then: v grows by at most that times
        // the delay (the acceleration only rises toward it), and not past the fastest queued
        // cruise velocity (a junction is never faster than both its motions').
        let a1 = if jerk.is_finite() {
            (a.max(0.0) + jerk * delay).min(acc.max(a))
        } else {
            a.max(0.0)
        };
        let v1 = (v + a1 * delay).min(top);
        let a1 = if v1 >= top { 0.0 } else { a1 };
        v1 * delay + braking_distance(v1, a1, dec, jerk)
    }

    pub fn state(&self) -> &PathState {
        &self.state
    }

    /// Queued entries (the motion being executed counts).
    pub fn queued(&self) -> usize {
        self.user_entries
    }

    /// Nothing queued and at rest.
    pub fn is_idle(&self) -> bool {
        self.queue.is_empty() && self.exec.is_none() && self.carry <= 0.0
    }

    /// Path length left to the end of the last queued motion.
    pub fn remaining_length(&self) -> f64 {
        let total: f64 = self
            .queue
            .iter()
            .map(|e| match e {
                Entry::Motion(m) => m.length,
                Entry::Marker { .. } => 0.0,
            })
            .sum();
        total - self.exec.as_ref().map_or(0.0, |e| e.s)
    }

    /// Path length the executing motion has covered (0 when none executes): how far past a
    /// marker reached during the last step the path is (the motion after it is the one executing).
    pub fn executed_length(&self) -> f64 {
        self.exec.as_ref().map_or(0.0, |e| e.s)
    }

    /// Motions started during the last step (bounded by [`MAX_STARTS_PER_STEP`]).
    pub fn starts_last_step(&self) -> usize {
        self.starts_last_step
    }

    /// Queue entries the look-ahead visited since the last step began (pushes after it
    /// included): the planning work, deterministic, for benchmarks and tests.
    pub fn lookahead_visits(&self) -> usize {
        self.lookahead_visits
    }
}
