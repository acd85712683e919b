//! NMC's polar machine (digest 001 C3§10.5, "极坐标转换: 用户数据是按照直角坐标描述, 实际机械机构
//! 是一个旋转轴和一个进给轴"): the program is Cartesian (x, y), the machine a rotary axis at
//! θ = atan2(y, x) and a feed axis at r = √(x² + y²). Not rigid, so it is applied to each
//! tick's point ([`to_polar`]), not to whole segments; [`polar_bounds`] says how fast θ and r
//! can change along a segment, so that the path speed can be held to the two axes' limits.
//!
//! Pure functions of their arguments.

use std::f64::consts::TAU;

use crate::checks::GeometryError;
use crate::geometry::Segment;

/// Radii up to this are the pole: θ is undefined there and the reference angle is kept.
pub const POLE_RADIUS: f64 = 1e-9;

/// Samples of a curved segment when its distance from the pole is bounded.
const CURVE_SAMPLES: usize = 1024;

/// A Cartesian point and its motion in polar coordinates: θ (rad) on a continuous branch and
/// its derivatives, r and its derivatives.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Polar {
    pub theta: f64,
    pub omega: f64,
    pub alpha: f64,
    pub r: f64,
    pub r_dot: f64,
    pub r_ddot: f64,
}

/// atan2(y, x) on the branch nearest `reference` (never a 2π jump from it); `reference`
/// itself at the pole.
pub fn unwrapped_angle(x: f64, y: f64, reference: f64) -> f64 {
    if x.hypot(y) <= POLE_RADIUS {
        return reference;
    }
    let a = y.atan2(x);
    a + TAU * ((reference - a) / TAU).round()
}

/// Position `p`, velocity `v` and acceleration `a` in (x, y) → polar, θ on the branch nearest
/// `reference`. At the pole θ is `reference` and every rate is 0.
pub fn to_polar(p: [f64; 2], v: [f64; 2], a: [f64; 2], reference: f64) -> Polar {
    let [x, y] = p;
    let r = x.hypot(y);
    let theta = unwrapped_angle(x, y, reference);
    if r <= POLE_RADIUS {
        return Polar {
            theta,
            r,
            ..Polar::default()
        };
    }
    let r2 = r * r;
    // r²·θ' = p × v and r·r' = p · v; differentiate once more for θ'' and r''.
    let omega = (x * v[1] - y * v[0]) / r2;
    let r_dot = (x * v[0] + y * v[1]) / r;
    Polar {
        theta,
        omega,
        alpha: (x * a[1] - y * a[0]) / r2 - 2.0 * omega * r_dot / r,
        r,
        r_dot,
        r_ddot: r * omega * omega + (x * a[0] + y * a[1]) / r,
    }
}

/// (θ, r) → (x, y).
pub fn from_polar(theta: f64, r: f64) -> [f64; 2] {
    [r * theta.cos(), r * theta.sin()]
}

/// Bounds over a segment of the polar coordinates' rates per path length `s`: |dθ/ds|,
/// |d²θ/ds²| and |d²r/ds²| (|dr/ds| ≤ 1 always). At path speed `v` and acceleration `a` the
/// rotary axis turns at most `v·dtheta` and accelerates at most `v²·d2theta + a·dtheta`; the
/// feed axis at most `v` and `v²·d2r + a`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PolarBounds {
    pub dtheta: f64,
    pub d2theta: f64,
    pub d2r: f64,
}

/// The bounds of [`PolarBounds`] for `segment` with x, y its coordinates `plane` plus
/// `offset`. A segment through the pole is refused (θ would jump by half a turn), and so is a
/// line leaving the pole in a direction other than `start_angle` (the rotary axis's angle
/// there, mod 2π); a line ending at the pole is radial and keeps θ. A curve is bounded from
/// samples (|dr/ds| ≤ 1 between them), so one that comes nearer the pole than its length / 2048
/// is refused too.
pub fn polar_bounds(
    segment: &Segment,
    plane: (usize, usize),
    offset: (f64, f64),
    start_angle: f64,
) -> Result<PolarBounds, GeometryError> {
    let (i, j) = plane;
    let at = |p: &crate::Point| {
        [
            p.get(i).copied().unwrap_or(0.0) + offset.0,
            p.get(j).copied().unwrap_or(0.0) + offset.1,
        ]
    };
    let length = segment.length();
    let p0 = at(&segment.start());
    let Segment::Line(line) = segment else {
        let mut nearest = f64::INFINITY;
        for k in 0..=CURVE_SAMPLES {
            let [x, y] = at(&segment.sample(length * k as f64 / CURVE_SAMPLES as f64).p);
            nearest = nearest.min(x.hypot(y));
        }
        let r = nearest - length / (2 * CURVE_SAMPLES) as f64;
        if r <= POLE_RADIUS {
            return Err(GeometryError::Invalid(
                "under the polar transform an arc or curve may not pass through or touch the pole",
            ));
        }
        let k = segment.max_curvature();
        return Ok(PolarBounds {
            dtheta: 1.0 / r,
            d2theta: k / r + 1.0 / (r * r),
            d2r: k + 1.0 / r,
        });
    };
    let d = line.direction();
    let u = [
        d.get(i).copied().unwrap_or(0.0),
        d.get(j).copied().unwrap_or(0.0),
    ];
    let uu = u[0] * u[0] + u[1] * u[1];
    if uu <= f64::EPSILON * f64::EPSILON || length == 0.0 {
        // The plane stands still: θ and r do not change.
        return Ok(PolarBounds::default());
    }
    let foot = (-(p0[0] * u[0] + p0[1] * u[1]) / uu).clamp(0.0, length);
    let nearest = (p0[0] + u[0] * foot).hypot(p0[1] + u[1] * foot);
    let cross = (p0[0] * u[1] - p0[1] * u[0]).abs();
    if nearest <= POLE_RADIUS {
        let [x1, y1] = at(&segment.end());
        if x1.hypot(y1) <= POLE_RADIUS {
            return Ok(PolarBounds::default());
        }
        if p0[0].hypot(p0[1]) <= POLE_RADIUS {
            let turn = (u[1].atan2(u[0]) - start_angle).rem_euclid(TAU);
            if turn.min(TAU - turn) <= 1e-9 {
                return Ok(PolarBounds::default());
            }
            return Err(GeometryError::Invalid(
                "under the polar transform a line leaving the pole must point where the rotary axis points (it would jump)",
            ));
        }
        return Err(GeometryError::Invalid(
            "under the polar transform a line may not pass through the pole (the rotary axis would turn half a turn at once)",
        ));
    }
    let r3 = nearest * nearest * nearest;
    Ok(PolarBounds {
        dtheta: cross / (nearest * nearest),
        d2theta: 2.0 * cross * uu.sqrt() / r3,
        d2r: cross * cross / r3,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Line, Segment};

    fn line(a: [f64; 2], b: [f64; 2]) -> Segment {
        let mut p = [0.0; crate::MAX_AXES];
        let mut q = [0.0; crate::MAX_AXES];
        p[..2].copy_from_slice(&a);
        q[..2].copy_from_slice(&b);
        Segment::Line(Line::new(p, q, 2).unwrap())
    }

    #[test]
    fn the_angle_stays_on_the_branch_nearest_the_reference() {
        let just_below_cut = unwrapped_angle(-1.0, -1e-3, std::f64::consts::PI - 1e-3);
        assert!((just_below_cut - (std::f64::consts::PI + 1e-3)).abs() < 1e-9);
        assert_eq!(unwrapped_angle(1.0, 0.0, 4.0 * TAU + 0.1), 4.0 * TAU);
        assert_eq!(unwrapped_angle(0.0, 0.0, 7.5), 7.5);
    }

    #[test]
    fn rates_match_the_derivatives_of_a_point_on_a_circle() {
        // x = R cos(wt), y = R sin(wt) at t = 0.3: θ' = w, θ'' = 0, r' = r'' = 0.
        let (radius, w, t) = (2.0, 0.7_f64, 0.3_f64);
        let (c, s) = ((w * t).cos(), (w * t).sin());
        let p = to_polar(
            [radius * c, radius * s],
            [-radius * w * s, radius * w * c],
            [-radius * w * w * c, -radius * w * w * s],
            0.0,
        );
        assert!((p.omega - w).abs() < 1e-12 && p.alpha.abs() < 1e-12);
        assert!(p.r_dot.abs() < 1e-12 && p.r_ddot.abs() < 1e-12);
        assert!((p.theta - w * t).abs() < 1e-12 && (p.r - radius).abs() < 1e-12);
    }

    #[test]
    fn the_pole_is_refused_unless_a_line_ends_there_or_leaves_it_straight() {
        assert!(polar_bounds(&line([-1.0, 0.0], [1.0, 0.0]), (0, 1), (0.0, 0.0), 0.0).is_err());
        let inward = polar_bounds(&line([1.0, 1.0], [0.0, 0.0]), (0, 1), (0.0, 0.0), 0.0);
        assert_eq!(inward.unwrap(), PolarBounds::default());
        let out = line([0.0, 0.0], [0.0, 1.0]);
        assert!(polar_bounds(&out, (0, 1), (0.0, 0.0), 0.0).is_err());
        let aligned = polar_bounds(&out, (0, 1), (0.0, 0.0), std::f64::consts::FRAC_PI_2);
        assert_eq!(aligned.unwrap(), PolarBounds::default());
    }

    #[test]
    fn a_line_past_the_pole_turns_fastest_at_its_nearest_point() {
        // y = 1 from x = −5 to 5: dθ/ds = 1/r² ≤ 1 at x = 0.
        let b = polar_bounds(&line([-5.0, 1.0], [5.0, 1.0]), (0, 1), (0.0, 0.0), 0.0).unwrap();
        assert!((b.dtheta - 1.0).abs() < 1e-12);
        assert!(b.d2theta >= 3.0 * 3f64.sqrt() / 8.0 && b.d2r >= 1.0 - 1e-12);
    }
}
