//! Junction velocities between two queued motions (issue 11 item 4).
//!
//! Two parts: what the buffer mode asks for (PLCopen Part 4 buffer modes; HIMC BM_*, digest
//! 004 §3), which the override scales, and what the axes allow (a physical cap, fixed when
//! the motions are queued). The look-ahead takes the lower of the two.

use super::{AxisLimits, Join};
use crate::{Point, MAX_AXES};

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

/// The least share of the axes' acceleration the motions beside a corner keep; the corner's
/// velocity step takes the rest. A step `Δv_k` at a junction shows in the finite-difference
/// acceleration of the ticks around it as up to `Δv_k/T` on top of the continuous
/// acceleration, so a step within `(1 − m)·A_k·T` and a continuous `|a_k| ≤ m·A_k` keep it
/// within `A_k` (docs/decisions.md, "Corner and curvature steps").
pub(super) const CORNER_MOTION_SHARE: f64 = 0.5;

/// Relative margin on the motions' share, against rounding of the sum.
const SHARE_MARGIN: f64 = 1e-9;

/// The corner rule at a junction without corner geometry (Transition::None), the direction
/// stepping from `before` to `after`, passed at most at `v_limit` (both motions' velocity
/// caps): `(cap, share)`. Every axis's velocity step `v·|t1_k − t2_k|` must fit in one period
/// of the part of its acceleration the motions leave it, `(1 − share)·A_k·T` (HIMC corner
/// acceleration, digest 004 §3; NMC TLookaheadPara accMax, digest 001 §2.7/§3.7). The
/// motions keep `share = 1 − σ` of the axes' acceleration, `σ = max_k v_limit·|Δt_k|/(A_k·T)`
/// the step's own need at `v_limit`, but at least [`CORNER_MOTION_SHARE`] (then the cap
/// binds); a nearly tangent junction thus costs the motions almost nothing. Tangent
/// junctions: `(∞, 1)`.
pub(super) fn corner_rule(
    before: &Point,
    after: &Point,
    axes: &[AxisLimits],
    period: f64,
    v_limit: f64,
) -> (f64, f64) {
    let mut need: f64 = 0.0;
    for (k, lim) in axes.iter().enumerate() {
        let (b, a) = (before.get(k).copied(), after.get(k).copied());
        let step = (b.unwrap_or(0.0) - a.unwrap_or(0.0)).abs();
        if step > TANGENT_TOLERANCE {
            need = need.max(v_limit * step / (lim.acceleration * period));
        }
    }
    if need <= 0.0 {
        return (f64::INFINITY, 1.0);
    }
    let share = if need.is_nan() {
        CORNER_MOTION_SHARE
    } else {
        ((1.0 - need) * (1.0 - SHARE_MARGIN)).max(CORNER_MOTION_SHARE)
    };
    let mut cap = f64::INFINITY;
    for (k, lim) in axes.iter().enumerate() {
        let (b, a) = (before.get(k).copied(), after.get(k).copied());
        let step = (b.unwrap_or(0.0) - a.unwrap_or(0.0)).abs();
        if step > TANGENT_TOLERANCE {
            cap = cap.min((1.0 - share) * lim.acceleration * period / step);
        }
    }
    (cap, share)
}

/// What the axes' jerk allows where the curvature vector steps from `before` to `after` (a
/// line into a tangent arc, arcs of other radii, a corner arc's ends): every axis's
/// centripetal acceleration steps by `v²·|κ1_k − κ2_k|`, which must fit in one period of its
/// jerk, `J_k·T` — the corner rule one derivative up. So `v ≤ √(J_k·T / |Δκ_k|)`; no cap
/// for an axis without a jerk limit.
pub(super) fn curvature_cap(
    before: &Point,
    after: &Point,
    axes: &[AxisLimits],
    period: f64,
) -> f64 {
    let mut cap = f64::INFINITY;
    for (k, lim) in axes.iter().enumerate() {
        let (b, a) = (before.get(k).copied(), after.get(k).copied());
        let step = (b.unwrap_or(0.0) - a.unwrap_or(0.0)).abs();
        if step > 0.0 && lim.jerk.is_finite() {
            cap = cap.min((lim.jerk * period / step).sqrt());
        }
    }
    cap
}

/// The axes' limits with their acceleration scaled by `share` (for the motions beside a
/// corner that steps the direction).
pub(super) fn with_acceleration_share(axes: &[AxisLimits], share: f64) -> [AxisLimits; MAX_AXES] {
    let mut out = [AxisLimits {
        velocity: 1.0,
        acceleration: 1.0,
        jerk: f64::INFINITY,
    }; MAX_AXES];
    for (o, a) in out.iter_mut().zip(axes) {
        *o = AxisLimits {
            acceleration: a.acceleration * share,
            ..*a
        };
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_right_angle_shares_the_acceleration_between_the_step_and_the_motions() {
        let axes = [AxisLimits {
            velocity: 100.0,
            acceleration: 1000.0,
            jerk: f64::INFINITY,
        }; 2];
        let mut x = [0.0; crate::MAX_AXES];
        let mut y = [0.0; crate::MAX_AXES];
        x[0] = 1.0;
        y[1] = 1.0;
        // Fast enough for the step to need more than half: half each.
        assert_eq!(corner_rule(&x, &y, &axes, 1e-3, 100.0), (0.5, 0.5));
        assert_eq!(
            corner_rule(&x, &x, &axes, 1e-3, 100.0),
            (f64::INFINITY, 1.0)
        );
        // Slow: the step needs 0.1·A·T at most, the motions keep (almost) 0.9.
        let (cap, share) = corner_rule(&x, &y, &axes, 1e-3, 0.1);
        assert!(
            (share - 0.9).abs() < 1e-6 && cap >= 0.1 * (1.0 - 1e-6),
            "{cap} {share}"
        );
        assert_eq!(mode_velocity(Join::BlendingHigh, 1.0, 2.0), 2.0);
        assert_eq!(mode_velocity(Join::BlendingLow, 1.0, 2.0), 1.0);
    }
}
