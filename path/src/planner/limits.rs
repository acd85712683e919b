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

use super::{AxisLimits, LookaheadLimits, PathLimits};
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
    rules: &LookaheadLimits,
) -> MotionLimits {
    let curvature = segment.max_curvature();
    let mut velocity_cap = f64::INFINITY;
    let mut acceleration = programmed.acceleration;
    let mut deceleration = programmed.deceleration;
    let mut jerk = programmed.jerk;
    // The lowest jerk limit of the axes that move here, for the curvature rule below.
    let mut curve_jerk = programmed.jerk;
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
        curve_jerk = curve_jerk.min(lim.jerk);
    }
    if curvature > 0.0 && curve_jerk.is_finite() {
        // On a circle at speed v the acceleration vector v²κ turns at vκ: jerk v³κ². HMC caps
        // curve speed at (Jerk/κ²)^(1/3) (digest 000 §3.5, `HMC_ClcJerk`); so does mcemu, with
        // the lowest of the path's and the moving axes' jerk limits.
        velocity_cap = velocity_cap.min((curve_jerk / (curvature * curvature)).cbrt());
    }
    // The vendors' look-ahead limits on curves (HIMC arc acceleration, chord error).
    velocity_cap = velocity_cap.min(rules.curve_cap(curvature, period));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Arc, Line, Turn};
    use crate::MAX_AXES;

    fn p(x: f64, y: f64) -> crate::Point {
        let mut out = [0.0; MAX_AXES];
        out[0] = x;
        out[1] = y;
        out
    }

    const AXES: [AxisLimits; 2] = [
        AxisLimits {
            velocity: 60.0,
            acceleration: 600.0,
            jerk: 6000.0,
        },
        AxisLimits {
            velocity: 100.0,
            acceleration: 1000.0,
            jerk: f64::INFINITY,
        },
    ];

    const FAST: PathLimits = PathLimits {
        velocity: 1e6,
        acceleration: 1e6,
        deceleration: 1e6,
        jerk: f64::INFINITY,
    };

    #[test]
    fn a_diagonal_line_takes_each_axis_limit_over_its_direction_component() {
        // Direction (0.6, 0.8): x allows 60/0.6 = 100, y 100/0.8 = 125.
        let line = Segment::Line(Line::new(p(0.0, 0.0), p(30.0, 40.0), 2).unwrap());
        let l = motion_limits(&line, &FAST, &AXES, 1e-3, &LookaheadLimits::default());
        assert!((l.velocity_cap - 100.0).abs() < 1e-9);
        assert!((l.acceleration - 1000.0).abs() < 1e-9);
        assert!((l.deceleration - 1000.0).abs() < 1e-9);
        assert!((l.jerk - 10_000.0).abs() < 1e-9);
        // The programmed limits win when lower; a 0.05 mm line is capped at 50 mm/s at 1 kHz.
        let short = Segment::Line(Line::new(p(0.0, 0.0), p(0.03, 0.04), 2).unwrap());
        let l = motion_limits(&short, &FAST, &AXES, 1e-3, &LookaheadLimits::default());
        assert!((l.velocity_cap - 50.0).abs() < 1e-9);
    }

    #[test]
    fn an_arc_splits_each_axis_budget_in_quadrature() {
        let arc = Segment::Arc(
            Arc::from_center(
                p(10.0, 0.0),
                p(10.0, 0.0),
                p(0.0, 0.0),
                (0, 1),
                Turn::Ccw,
                0,
                2,
            )
            .unwrap(),
        );
        let l = motion_limits(&arc, &FAST, &AXES, 1e-3, &LookaheadLimits::default());
        let split = 600.0 * std::f64::consts::FRAC_1_SQRT_2;
        // v²/r ≤ A_x/√2: v ≤ √(424.3·10) = 65.1, above x's 60 mm/s: the velocity limit wins.
        assert!((l.velocity_cap - 60.0).abs() < 1e-9);
        assert!((l.acceleration - split).abs() < 1e-9);
        let slow = [AxisLimits {
            acceleration: 100.0,
            ..AXES[0]
        }; 2];
        let l = motion_limits(&arc, &FAST, &slow, 1e-3, &LookaheadLimits::default());
        assert!(
            (l.velocity_cap - (100.0 * std::f64::consts::FRAC_1_SQRT_2 * 10.0).sqrt()).abs() < 1e-9
        );
    }
}
