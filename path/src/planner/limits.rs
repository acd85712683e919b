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
//! - jerk: on a line `j ≤ J_k / |t_k|`. On a curve the axis position is `x_k(s(t))`, so
//!   `d³x_k/dt³ = t_k·j + 3·κ_k·v·a + x'''_k·v³` (`x'''` = `dκ/ds`, the curvature vector's
//!   rate along the path: `κ²` on a circle, more on a blend or a spline). Each term gets a
//!   share of every moving axis's jerk `J` (the lowest): the speed term what it needs at the
//!   motion's velocity cap, at most [`CURVE_SPEED_JERK_SHARE`] (`v ≤ (½·J/|x'''|)^(1/3)`),
//!   and the other two half of the rest `f` each: `j ≤ f·J_k/|t_k|` and
//!   `|a| ≤ f·J/(3·κ·v_cap)` (at the highest speed the motion may run, so the product rule
//!   costs acceleration, not speed). Steps of curvature at the junctions are the junction
//!   rule's (`junction`).

use super::{AxisLimits, LookaheadLimits, PathLimits};

/// The most of every axis's jerk the speed term `x'''_k·v³` of a curve takes (module doc):
/// steady motion on an arc needs only it, so its speed is `(½)^(1/3) ≈ 0.79` of HMC's
/// `(J/κ²)^(1/3)` where the axes' jerk binds, and the path jerk and acceleration keep at
/// least a quarter each.
pub(super) const CURVE_SPEED_JERK_SHARE: f64 = 0.5;

/// Relative margin on the shares, against rounding of their sum.
const CURVE_SHARE_MARGIN: f64 = 1e-9;
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
    // The lowest jerk limit of the axes that move here, and of J_k/|t_k|, for the curve
    // rules below.
    let mut curve_jerk = f64::INFINITY;
    let mut curve_path_jerk = f64::INFINITY;
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
        if curvature > 0.0 {
            curve_path_jerk = curve_path_jerk.min(lim.jerk / tangent);
        } else {
            jerk = jerk.min(lim.jerk / tangent);
        }
        curve_jerk = curve_jerk.min(lim.jerk);
    }
    if curvature > 0.0 && programmed.jerk.is_finite() {
        // On a circle at speed v the acceleration vector v²κ turns at vκ: jerk v³κ². HMC caps
        // curve speed at (Jerk/κ²)^(1/3) with the path's jerk (digest 000 §3.5,
        // `HMC_ClcJerk`).
        velocity_cap = velocity_cap.min((programmed.jerk / (curvature * curvature)).cbrt());
    }
    // The vendors' look-ahead limits on curves (HIMC arc acceleration, chord error).
    velocity_cap = velocity_cap.min(rules.curve_cap(curvature, period));
    let length = segment.length();
    velocity_cap = velocity_cap.min(length / period);
    if curvature > 0.0 && curve_jerk.is_finite() {
        // The axes' own jerk on a curve (module doc): |x'''_k|·v³ first, within at most
        // half of the lowest moving axis's jerk …
        let rate = segment.max_curvature_rate();
        let mut speed_need = 0.0;
        if rate > 0.0 {
            velocity_cap = velocity_cap.min((CURVE_SPEED_JERK_SHARE * curve_jerk / rate).cbrt());
            let v = velocity_cap;
            speed_need = (rate * v * v * v / curve_jerk).clamp(0.0, CURVE_SPEED_JERK_SHARE);
        }
        // … then half of the rest each for t_k·j and 3·κ_k·v·a.
        let rest = 0.5 * (1.0 - speed_need) * (1.0 - CURVE_SHARE_MARGIN);
        jerk = jerk.min(rest * curve_path_jerk);
        if velocity_cap > 0.0 {
            let most = rest * curve_jerk / (3.0 * curvature * velocity_cap);
            if most > 0.0 {
                acceleration = acceleration.min(most);
                deceleration = deceleration.min(most);
            }
        }
    } else if curvature > 0.0 {
        jerk = jerk.min(curve_path_jerk);
    }
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

    /// The full circle of radius 10 about the origin, from (10, 0).
    fn full_circle_r10() -> Segment {
        Segment::Arc(
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
        )
    }

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
        let arc = full_circle_r10();
        // Without jerk limits (the jerk rules are the next test's).
        let axes = [
            AxisLimits {
                jerk: f64::INFINITY,
                ..AXES[0]
            },
            AXES[1],
        ];
        let l = motion_limits(&arc, &FAST, &axes, 1e-3, &LookaheadLimits::default());
        let split = 600.0 * std::f64::consts::FRAC_1_SQRT_2;
        // v²/r ≤ A_x/√2: v ≤ √(424.3·10) = 65.1, above x's 60 mm/s: the velocity limit wins.
        assert!((l.velocity_cap - 60.0).abs() < 1e-9);
        assert!((l.acceleration - split).abs() < 1e-9);
        let slow = [AxisLimits {
            acceleration: 100.0,
            ..axes[0]
        }; 2];
        let l = motion_limits(&arc, &FAST, &slow, 1e-3, &LookaheadLimits::default());
        assert!(
            (l.velocity_cap - (100.0 * std::f64::consts::FRAC_1_SQRT_2 * 10.0).sqrt()).abs() < 1e-9
        );
    }

    #[test]
    fn an_arc_shares_each_axis_jerk_between_the_three_terms() {
        // r = 10: κ = 0.1, |x'''| = κ² = 0.01; J = 6000 on x, ∞ on y.
        let arc = full_circle_r10();
        let fast = [
            AxisLimits {
                velocity: 1e6,
                ..AXES[0]
            },
            AxisLimits {
                velocity: 1e6,
                ..AXES[1]
            },
        ];
        let l = motion_limits(&arc, &FAST, &fast, 1e-3, &LookaheadLimits::default());
        // Speed: (½·6000/0.01)^(1/3) = 66.9 is above the quadrature cap √(424.3·10) = 65.1,
        // which wins and needs 0.01·65.1³/6000 = 0.46 of the jerk; the path jerk and the
        // product rule get half of the remaining 0.54 each.
        let quadrature = (600.0 * std::f64::consts::FRAC_1_SQRT_2 * 10.0).sqrt();
        assert!((l.velocity_cap - quadrature).abs() < 1e-9, "{l:?}");
        let rest = 0.5 * (1.0 - 0.01 * quadrature.powi(3) / 6000.0);
        let product = rest * 6000.0 / (3.0 * 0.1 * quadrature);
        assert!((l.acceleration / product - 1.0).abs() < 1e-6, "{l:?}");
        assert!((l.jerk / (rest * 6000.0) - 1.0).abs() < 1e-6, "{l:?}");
        // A lower jerk: the speed rule binds.
        let soft = [
            AxisLimits {
                jerk: 600.0,
                ..fast[0]
            },
            fast[1],
        ];
        let l = motion_limits(&arc, &FAST, &soft, 1e-3, &LookaheadLimits::default());
        assert!(
            (l.velocity_cap - (0.5f64 * 600.0 / 0.01).cbrt()).abs() < 1e-9,
            "{l:?}"
        );
    }
}
