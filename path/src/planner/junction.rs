//! Junction velocities between two queued motions (issue 11 item 4).
//!
//! Two parts: what the buffer mode asks for (PLCopen Part 4 buffer modes; HIMC BM_*, digest
//! 004 §3), which the override scales, and what the axes allow (a physical cap, fixed when
//! the motions are queued). The look-ahead takes the lower of the two.

use super::{AxisLimits, Join};
use crate::geometry::PathPoint;
use crate::MAX_AXES;

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

/// The least share of the axes' acceleration (and jerk) the motions beside a junction keep;
/// the junction's step takes the rest. A step `Δv_k` at a junction shows in the
/// finite-difference acceleration of the ticks around it as up to `Δv_k/T` on top of the
/// continuous acceleration, so a step within `(1 − m)·A_k·T` and a continuous `|a_k| ≤ m·A_k`
/// keep it within `A_k` (docs/decisions.md, "Corner and curvature steps"); the jerk likewise
/// (see [`junction_rule`]).
pub(super) const CORNER_MOTION_SHARE: f64 = 0.5;

/// Relative margin on the motions' share, against rounding of the sum.
const SHARE_MARGIN: f64 = 1e-9;

/// What a junction allows: the highest path speed through it, and the shares of the axes'
/// acceleration and jerk the motions on both sides keep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct JunctionRule {
    pub cap: f64,
    pub acceleration_share: f64,
    pub jerk_share: f64,
}

/// The share the motions keep when the step needs `need` of the budget at the highest
/// speed it could be passed at: all but that, at least [`CORNER_MOTION_SHARE`].
fn motion_share(need: f64) -> f64 {
    if need <= 0.0 {
        1.0
    } else if need.is_nan() {
        CORNER_MOTION_SHARE
    } else {
        ((1.0 - need) * (1.0 - SHARE_MARGIN)).max(CORNER_MOTION_SHARE)
    }
}

/// The junction rule where the path passes from `before` (the end of one motion) to `after`
/// (the start of the next) at most at `v_limit` (both motions' velocity caps). Two steps
/// can happen there in one tick, at path speed `v` (the path acceleration is 0 at every
/// motion's ends):
/// - the direction steps (a corner without geometry): every axis's velocity steps by
///   `v·|Δt_k|`. In the finite-difference acceleration of the ticks around it that is up to
///   `v·|Δt_k|/T`, so it must fit in `(1 − m_a)·A_k·T` while the motions keep `m_a` of the
///   acceleration (HIMC corner acceleration, digest 004 §3; NMC TLookaheadPara accMax,
///   digest 001 §2.7/§3.7);
/// - the curvature vector steps (line → arc, arcs of other radii, a corner arc's ends):
///   every axis's acceleration steps by `v²·|Δκ_k|`.
///
/// In the third finite difference (jerk) a velocity step `Δv` weighs at most `Δv/T²` and an
/// acceleration step `Δa` at most `¾·Δa/T` (the third difference of a ramp, and of a
/// parabola, started between two ticks), so `v·|Δt_k|/T² + ¾·v²·|Δκ_k|/T ≤ (1 − m_j)·J_k`
/// while the motions keep `m_j` of the jerk. The shares are `m = 1 − σ`, `σ` the step's own
/// need at `v_limit`, but at least [`CORNER_MOTION_SHARE`] (then the cap binds): a nearly
/// tangent junction costs the motions almost nothing. With a jerk limit a true corner is
/// passed at a crawl (`≈ J_k·T²/2`): an axis whose acceleration is continuous cannot
/// turn a corner moving. Axes without a jerk limit have no jerk rule. Smooth junctions:
/// `(∞, 1, 1)`.
pub(super) fn junction_rule(
    before: &PathPoint,
    after: &PathPoint,
    axes: &[AxisLimits],
    period: f64,
    v_limit: f64,
) -> JunctionRule {
    let steps = |k: usize| {
        let dt = (before.t.get(k).copied().unwrap_or(0.0) - after.t.get(k).copied().unwrap_or(0.0))
            .abs();
        let dk = (before.k.get(k).copied().unwrap_or(0.0) - after.k.get(k).copied().unwrap_or(0.0))
            .abs();
        (if dt > TANGENT_TOLERANCE { dt } else { 0.0 }, dk)
    };
    let t2 = period * period;
    let (mut need_a, mut need_j): (f64, f64) = (0.0, 0.0);
    for (k, lim) in axes.iter().enumerate() {
        let (dt, dk) = steps(k);
        if dt > 0.0 {
            need_a = need_a.max(v_limit * dt / (lim.acceleration * period));
        }
        if lim.jerk.is_finite() && (dt > 0.0 || dk > 0.0) {
            let j = v_limit * dt / t2 + 0.75 * v_limit * v_limit * dk / period;
            need_j = need_j.max(j / lim.jerk);
        }
    }
    let acceleration_share = motion_share(need_a);
    let jerk_share = motion_share(need_j);
    let mut cap = f64::INFINITY;
    for (k, lim) in axes.iter().enumerate() {
        let (dt, dk) = steps(k);
        if dt > 0.0 {
            cap = cap.min((1.0 - acceleration_share) * lim.acceleration * period / dt);
        }
        if lim.jerk.is_finite() && (dt > 0.0 || dk > 0.0) {
            // c2·v² + c1·v = r, the positive root in the form without cancellation.
            let (c2, c1) = (0.75 * dk / period, dt / t2);
            let r = (1.0 - jerk_share) * lim.jerk;
            let v = 2.0 * r / (c1 + (c1 * c1 + 4.0 * c2 * r).sqrt());
            if !v.is_nan() {
                cap = cap.min(v);
            }
        }
    }
    JunctionRule {
        cap,
        acceleration_share,
        jerk_share,
    }
}

/// The axes' limits with their acceleration and jerk scaled by the motion's shares (for the
/// motions beside a junction that steps).
pub(super) fn with_shares(
    axes: &[AxisLimits],
    acceleration_share: f64,
    jerk_share: f64,
) -> [AxisLimits; MAX_AXES] {
    let mut out = [AxisLimits {
        velocity: 1.0,
        acceleration: 1.0,
        jerk: f64::INFINITY,
    }; MAX_AXES];
    for (o, a) in out.iter_mut().zip(axes) {
        *o = AxisLimits {
            acceleration: a.acceleration * acceleration_share,
            jerk: a.jerk * jerk_share,
            ..*a
        };
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn heading(t: [f64; 2], k: [f64; 2]) -> PathPoint {
        let mut p = PathPoint::default();
        p.t[..2].copy_from_slice(&t);
        p.k[..2].copy_from_slice(&k);
        p
    }

    #[test]
    fn a_right_angle_shares_the_acceleration_between_the_step_and_the_motions() {
        let axes = [AxisLimits {
            velocity: 100.0,
            acceleration: 1000.0,
            jerk: f64::INFINITY,
        }; 2];
        let x = heading([1.0, 0.0], [0.0; 2]);
        let y = heading([0.0, 1.0], [0.0; 2]);
        // Fast enough for the step to need more than half: half each.
        let r = junction_rule(&x, &y, &axes, 1e-3, 100.0);
        assert_eq!((r.cap, r.acceleration_share, r.jerk_share), (0.5, 0.5, 1.0));
        let r = junction_rule(&x, &x, &axes, 1e-3, 100.0);
        assert_eq!((r.cap, r.acceleration_share), (f64::INFINITY, 1.0));
        // Slow: the step needs 0.1·A·T at most, the motions keep (almost) 0.9.
        let r = junction_rule(&x, &y, &axes, 1e-3, 0.1);
        assert!(
            (r.acceleration_share - 0.9).abs() < 1e-6 && r.cap >= 0.1 * (1.0 - 1e-6),
            "{r:?}"
        );
        assert_eq!(mode_velocity(Join::BlendingHigh, 1.0, 2.0), 2.0);
        assert_eq!(mode_velocity(Join::BlendingLow, 1.0, 2.0), 1.0);
    }

    #[test]
    fn with_a_jerk_limit_the_steps_fit_in_the_jerk_left_by_the_motions() {
        let axes = [AxisLimits {
            velocity: 100.0,
            acceleration: 1000.0,
            jerk: 1e5,
        }; 2];
        // A right angle: v·1/T² ≤ ½·J: v ≤ 0.05 at 1 kHz.
        let x = heading([1.0, 0.0], [0.0; 2]);
        let y = heading([0.0, 1.0], [0.0; 2]);
        let r = junction_rule(&x, &y, &axes, 1e-3, 100.0);
        assert!((r.cap - 0.05).abs() < 1e-12 && r.jerk_share == 0.5, "{r:?}");
        // A line into a tangent arc of radius 5: ¾·v²·0.2/T ≤ ½·J: v ≤ √(1000/3).
        let arc = heading([1.0, 0.0], [0.0, 0.2]);
        let r = junction_rule(&x, &arc, &axes, 1e-3, 100.0);
        assert!((r.cap - (1000.0f64 / 3.0).sqrt()).abs() < 1e-9, "{r:?}");
        assert_eq!(r.acceleration_share, 1.0);
    }
}
