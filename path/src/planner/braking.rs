//! Where a stop issued now would take the path: how far it brakes (a closed form from the
//! path's velocity and acceleration) and how far that brings it along a direction, on the
//! queued path itself rather than on the tangent (a guard between two paths uses both:
//! issue 11, NMC `SetMvProtect`, digest 001 §3.7).

use super::queue::Entry;
use super::reach::{ramp_distance, settle};
use super::{MarkerKind, PathPlanner};
use crate::geometry::{dot, Segment};
use crate::Point;

/// Samples per segment piece when bounding a curve's extent along a direction (lines are
/// exact); the bound is at most 1/32 of the piece's length above the true one.
const EXTENT_SAMPLES: usize = 16;

/// The path length a 1-D motion at velocity `v ≥ 0` and acceleration `a` (positive: speeding
/// up) travels before rest when it brakes with `deceleration` and `jerk` (`∞`: none): first
/// the acceleration is brought to 0 at full jerk, then a fastest ramp to rest. ∞ when the
/// deceleration is not a positive number.
pub fn braking_distance(v: f64, a: f64, deceleration: f64, jerk: f64) -> f64 {
    let v = v.max(0.0);
    if v <= 0.0 && a <= 0.0 {
        return 0.0;
    }
    if deceleration.is_nan() || deceleration <= 0.0 {
        return f64::INFINITY;
    }
    let (v1, s1) = settle(v, a.max(0.0), jerk);
    s1.max(0.0) + ramp_distance(v1, 0.0, deceleration, jerk)
}

/// An upper bound on the largest `direction · p(s)` for `s` in `[s0, s1]` of `segment`: exact
/// on a line (its ends), else the samples with the most the function can rise
/// between two of them (`|direction · t| ≤ |direction|`, so between samples `h` apart it
/// stays below `(f(a) + f(b) + h·|direction|)/2`).
fn extent(segment: &Segment, s0: f64, s1: f64, direction: &Point) -> f64 {
    let f = |s: f64| dot(direction, &segment.sample(s).p);
    if matches!(segment, Segment::Line(_)) {
        return f(s0).max(f(s1));
    }
    let slope = dot(direction, direction).sqrt();
    let h = (s1 - s0) / EXTENT_SAMPLES as f64;
    let mut best = f(s0);
    let mut previous = best;
    for k in 1..=EXTENT_SAMPLES {
        let s = if k == EXTENT_SAMPLES {
            s1
        } else {
            s0 + h * k as f64
        };
        let here = f(s);
        best = best.max(0.5 * (previous + here + h * slope));
        previous = here;
    }
    best
}

impl PathPlanner {
    /// How much `direction · position` can grow while the path travels the next `length` of
    /// its queue from where it is (≥ 0; 0 at rest or when the queued path turns away): the
    /// closest a stop now can bring the path toward something in `direction`, on the path it
    /// will really follow (corner blends included), not on the tangent. The path stops at a
    /// `Hold` marker, so the walk does too. Work: the queued motions within `length`, a few
    /// samples each.
    pub fn advance_toward(&self, direction: &Point, length: f64) -> f64 {
        if length.is_nan() || length <= 0.0 {
            return 0.0;
        }
        let here = dot(direction, &self.state.position);
        let mut best = here;
        let mut left = length;
        let mut s0 = self.exec.as_ref().map_or(0.0, |e| e.s);
        for entry in &self.queue {
            if left <= 0.0 {
                break;
            }
            match entry {
                Entry::Marker {
                    kind: MarkerKind::Hold,
                    ..
                } => break,
                Entry::Marker { .. } => {}
                Entry::Motion(m) => {
                    let s1 = (s0 + left).min(m.length);
                    if s1 > s0 {
                        best = best.max(extent(&m.segment, s0, s1, direction));
                        left -= s1 - s0;
                    }
                    s0 = 0.0;
                }
            }
        }
        (best - here).max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn braking_distance_is_the_ramp_to_rest_after_the_acceleration_settles() {
        // Trapezoid: v²/2d.
        assert_eq!(braking_distance(10.0, 5.0, 100.0, f64::INFINITY), 0.5);
        assert_eq!(braking_distance(0.0, 0.0, 100.0, 1e3), 0.0);
        assert_eq!(braking_distance(1.0, 0.0, 0.0, 1e3), f64::INFINITY);
        // Still speeding up: the settle adds distance.
        assert!(braking_distance(10.0, 50.0, 100.0, 1e3) > braking_distance(10.0, 0.0, 100.0, 1e3));
    }
}
