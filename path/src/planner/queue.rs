//! The planner's queue: motions (with their look-ahead results) and markers, in path order.

use super::limits::MotionLimits;
use super::{Join, MarkerKind, PathLimits};
use crate::geometry::Segment;

/// One motion in the queue: a pushed motion, or part of one (a line trimmed by a corner
/// blend, or the blend arc itself, which reports the next motion's start).
#[derive(Clone, Debug)]
pub(super) struct QueuedMotion {
    pub segment: Segment,
    pub length: f64,
    pub tag: u64,
    /// How it joins the motion before it.
    pub join: Join,
    /// Its transition as pushed (a later push may round the corner after it).
    pub programmed: PathLimits,
    pub limits: MotionLimits,
    /// What the axes allow at its end junction; 0 until a next motion is queued.
    pub end_cap: f64,
    /// Look-ahead results: the highest velocity at its end and start from which the path can
    /// still stop by the end of the look-ahead window, with the override-independent caps only
    /// (`phys`) and with the buffer modes' velocities (`pref`, ≤ `phys`).
    pub end_phys: f64,
    pub end_pref: f64,
    pub start_phys: f64,
    pub start_pref: f64,
    /// Whether its start and end are reported (`Started`, `Done`); false for the parts of a
    /// blended motion that are not its first or last.
    pub reports_start: bool,
    /// The corner-angle factor on the velocity of the junction into it (1: none).
    pub entry_factor: f64,
    pub reports_done: bool,
    /// The share of the axes' acceleration its limits were planned with: below 1 beside a
    /// junction that steps the velocity (`junction::junction_rule`).
    pub acceleration_share: f64,
    /// The share of the axes' jerk its limits were planned with: below 1 beside a junction
    /// whose steps need part of it (`junction::junction_rule`).
    pub jerk_share: f64,
}

impl QueuedMotion {
    /// Cruise velocity under the override: the programmed velocity scaled, within the cap.
    pub fn cruise(&self, factor: f64) -> f64 {
        (factor * self.limits.programmed_velocity).min(self.limits.velocity_cap)
    }
}

#[derive(Clone, Debug)]
pub(super) enum Entry {
    Motion(Box<QueuedMotion>),
    Marker { tag: u64, kind: MarkerKind },
}
