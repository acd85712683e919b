//! Axis limits → path limits for one segment (issue 11 item 3).
//!
//! The path speed `v` moves axis `k` at `t_k·v` and accelerates it by
//! `a_k = t_k·a_t + n_k·κ·v²` (tangential plus centripetal; `n` the unit normal, `κ` the
//! curvature). So:
//! - velocity: `v ≤ V_k / max|t_k|` for every axis;
//! - on a line (`κ = 0`): `a_t ≤ A_k / |t_k|`, jerk `≤ J_k / |t_k|`;
//! - on a curve: `t` and `n` are orthonormal, so `t_k² + n_k² ≤ 1` (Bessel) and by
//!   Cauchy–Schwarz `|a_k| ≤ √(a_t² + (κv²)²)`. Splitting each axis's budget in quadrature,
//!   `a_t ≤ A_k/√2` and `κ·v² ≤ A_k/√2`, keeps `|a_k| ≤ A_k` (HIMC arc speed √(A_arc·r),
//!   digest 004 §3). An axis that barely moves tangentially may take more:
//!   `a_t ≤ A_k·(1 − 1/√2)/max|t_k|` also keeps `|a_k| ≤ A_k`; the larger bound is used.
//! - the velocity is at most `length / period`, so a motion lasts at least about one period
//!   and a step starts a bounded number of motions (dense G-code).
//!
//! Jerk on curves is not bounded by the axes' jerk limits: the centripetal acceleration
//! changes with `a_t` and steps where the curvature steps (see docs/decisions.md).

use super::{AxisLimits, PathLimits};
use crate::geometry::Segment;

/// Path limits of one motion, once the axes have had their say. The velocity cap does not
/// depend on the override; `programmed_velocity` is what the override scales.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct MotionLimits {
    pub programmed_velocity: f64,
    /// Physical cap on the path speed anywhere on the segment (axes, curvature, period).
    pub velocity_cap: f64,
    pub acceleration: f64,
    pub deceleration: f64,
    pub jerk: f64,
}

pub(super) fn motion_limits(
    segment: &Segment,
    programmed: &PathLimits,
    axes: &[AxisLimits],
    period: f64,
) -> MotionLimits {
    let curvature = segment.max_curvature();
    let mut velocity_cap = f64::INFINITY;
    let mut acceleration = programmed.acceleration;
    let mut deceleration = programmed.deceleration;
    let mut jerk = programmed.jerk;
    for (axis, lim) in axes.iter().enumerate() {
        let tangent = segment.max_tangent(axis);
        if tangent.is_nan() || tangent <= 0.0 {
            // The axis does not move on this segment (its curvature component is 0 too).
            continue;
        }
        velocity_cap = velocity_cap.min(lim.velocity / tangent);
        let along = if curvature > 0.0 {
            let split = lim.acceleration * std::f64::consts::FRAC_1_SQRT_2;
            velocity_cap = velocity_cap.min((split / curvature).sqrt());
            split.max((lim.acceleration - split) / tangent)
        } else {
            lim.acceleration / tangent
        };
        acceleration = acceleration.min(along);
        deceleration = deceleration.min(along);
        jerk = jerk.min(lim.jerk / tangent);
    }
    let length = segment.length();
    velocity_cap = velocity_cap.min(length / period);
    MotionLimits {
        programmed_velocity: programmed.velocity,
        velocity_cap,
        acceleration,
        deceleration,
        jerk,
    }
}

/// Whether `limits` are usable path limits: positive, finite (jerk may be `+∞`).
pub(super) fn check_path_limits(limits: &PathLimits) -> Result<(), &'static str> {
    let ok = |x: f64| x > 0.0 && x.is_finite();
    if !ok(limits.velocity) {
        return Err("the path velocity must be a positive finite number");
    }
    if !ok(limits.acceleration) || !ok(limits.deceleration) {
        return Err("the path acceleration and deceleration must be positive finite numbers");
    }
    if limits.jerk.is_nan() || limits.jerk <= 0.0 {
        return Err("the path jerk must be positive (∞ for none)");
    }
    Ok(())
}

/// Whether `limits` are usable axis limits: positive, finite (jerk may be `+∞`).
pub(super) fn check_axis_limits(limits: &AxisLimits) -> Result<(), &'static str> {
    let ok = |x: f64| x > 0.0 && x.is_finite();
    if !ok(limits.velocity)
        || !ok(limits.acceleration)
        || (limits.jerk.is_nan() || limits.jerk <= 0.0)
    {
        return Err("axis limits must be positive (velocity and acceleration finite)");
    }
    Ok(())
}
