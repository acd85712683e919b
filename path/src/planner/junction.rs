//! Junction velocities between two queued motions (issue 11 item 4).
//!
//! Two parts: what the buffer mode asks for (PLCopen Part 4 buffer modes; HIMC BM_*, digest
//! 004 §3), which the override scales, and what the axes allow (a physical cap, fixed when
//! the motions are queued). The look-ahead takes the lower of the two.

use super::{AxisLimits, Join};
use crate::Point;

/// Direction changes below this (per axis, in tangent components) count as tangent: the
/// velocity step they make is below rounding.
const TANGENT_TOLERANCE: f64 = 1e-12;

/// The path velocity the buffer mode asks for at the junction into a motion joined by `join`,
/// given both motions' cruise velocities (override applied). PLCopen Part 4: BlendingLow →
/// the lower, BlendingPrevious → the first's, BlendingNext → the second's, BlendingHigh → the
/// higher; Buffered → an exact stop.
pub(super) fn mode_velocity(join: Join, previous: f64, next: f64) -> f64 {
    match join {
        Join::Buffered => 0.0,
        Join::BlendingLow => previous.min(next),
        Join::BlendingPrevious => previous,
        Join::BlendingNext => next,
        Join::BlendingHigh => previous.max(next),
    }
}

/// What the axes allow at a junction without corner geometry (Transition::None), the
/// direction stepping from `before` to `after`: the step of every axis's velocity,
/// `v·|t1_k − t2_k|`, must fit in one period of its acceleration, `A_k·T` (HIMC corner
/// acceleration, digest 004 §3; NMC TLookaheadPara accMax, digest 001 §2.7/§3.7). Tangent
/// junctions are not capped here (the segments' own caps apply).
pub(super) fn corner_cap(before: &Point, after: &Point, axes: &[AxisLimits], period: f64) -> f64 {
    let mut cap = f64::INFINITY;
    for (k, lim) in axes.iter().enumerate() {
        let (b, a) = (before.get(k).copied(), after.get(k).copied());
        let step = (b.unwrap_or(0.0) - a.unwrap_or(0.0)).abs();
        if step > TANGENT_TOLERANCE {
            cap = cap.min(lim.acceleration * period / step);
        }
    }
    cap
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_right_angle_caps_at_a_t_over_the_step() {
        let axes = [AxisLimits {
            velocity: 100.0,
            acceleration: 1000.0,
            jerk: f64::INFINITY,
        }; 2];
        let mut x = [0.0; crate::MAX_AXES];
        let mut y = [0.0; crate::MAX_AXES];
        x[0] = 1.0;
        y[1] = 1.0;
        assert_eq!(corner_cap(&x, &y, &axes, 1e-3), 1.0);
        assert_eq!(corner_cap(&x, &x, &axes, 1e-3), f64::INFINITY);
        assert_eq!(mode_velocity(Join::BlendingHigh, 1.0, 2.0), 2.0);
        assert_eq!(mode_velocity(Join::BlendingLow, 1.0, 2.0), 1.0);
    }
}
