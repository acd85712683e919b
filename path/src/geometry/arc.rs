//! Circular arcs in a plane of N-D space, with optional linear motion of the remaining axes
//! (helices). One representation serves every vendor's arc: the constructors differ only in
//! how they find the centre, the plane and the sweep.
//!
//! `p(θ) = c + r·(cos θ·u + sin θ·v) + (θ / sweep)·h`, θ from 0 to `sweep`, where `u` points
//! from the centre to the start, `v` is the in-plane unit vector 90° ahead in the direction of
//! travel, and `h` is the linear displacement of the axes outside the plane. θ is proportional
//! to path length, so `s → θ` is one multiplication.

use std::f64::consts::TAU;

use super::arc_center::{in_plane_of, normal_basis, sweep_for};
use super::{
    add, check_number, check_planar, dot, norm, radius_tolerance, scale, sub, GeometryError,
    PathPoint, MIN_SWEEP, POINT_TOLERANCE,
};
use crate::frames::Transform;
use crate::{Point, MAX_AXES};

/// A circular arc or helix (see the module doc).
///
/// Inputs: one constructor (they differ in how the centre, plane and sweep are given; see
/// [`crate::geometry`]). Outputs, in any order: [`Arc::length`], [`Arc::sample`],
/// [`Arc::end`] (exactly as programmed), [`Arc::curvature`], [`Arc::max_tangent`];
/// [`Arc::trimmed`] and [`Arc::transformed`] make new arcs.
#[derive(Clone, Debug, PartialEq)]
pub struct Arc {
    center: Point,
    u: Point,
    v: Point,
    radius: f64,
    /// Swept angle, radians, > 0 (more than 2π for extra turns).
    sweep: f64,
    /// Linear displacement over the whole arc, orthogonal to `u` and `v`.
    h: Point,
    end: Point,
    length: f64,
    dims: usize,
}

/// Which way an arc turns, seen from the positive side of its plane's normal (for the plane of
/// axes (i, j): counter-clockwise turns from +i toward +j).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turn {
    Ccw,
    Cw,
}

impl Turn {
    /// `"cw"` or `"ccw"` (any case), as the JSON commands spell it; `None` for anything else.
    pub fn from_name(name: &str) -> Option<Turn> {
        if name.eq_ignore_ascii_case("ccw") {
            Some(Turn::Ccw)
        } else if name.eq_ignore_ascii_case("cw") {
            Some(Turn::Cw)
        } else {
            None
        }
    }

    /// +1 for counter-clockwise, −1 for clockwise: the sign of the swept angle.
    pub fn sign(self) -> f64 {
        match self {
            Turn::Ccw => 1.0,
            Turn::Cw => -1.0,
        }
    }

    /// The direction of a signed angle (> 0 counter-clockwise; 0 counts as counter-clockwise).
    pub fn of_angle(angle: f64) -> Turn {
        if angle < 0.0 {
            Turn::Cw
        } else {
            Turn::Ccw
        }
    }
}

impl Arc {
    /// The arc from `start` around `center` to `end` in the plane of axes `plane.0` (x) and
    /// `plane.1` (y), turning `turn`, after `extra_turns` full turns. Start = end in the plane
    /// is a full circle (plus the extra turns): NMC `ArcCenterEx` with target = start (digest
    /// 001 §4.4, TV 43). The other axes move linearly from `start` to `end` (a helix; NMC D8
    /// and HMC MoveND extra axes ride along the same way). The centre must be equidistant from
    /// start and end within [`POINT_TOLERANCE`] + 1e-9 × radius.
    pub fn from_center(
        start: Point,
        end: Point,
        center: Point,
        plane: (usize, usize),
        turn: Turn,
        extra_turns: u32,
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        Arc::around_in_plane(start, end, center, plane, dims, |theta, closed| {
            Ok((turn, sweep_for(turn, extra_turns, theta, closed)))
        })
    }

    /// The arc from `start` to `end` of radius `|radius|` in the plane `plane`, turning `turn`:
    /// `radius > 0` takes the minor arc (≤ 180°), `radius < 0` the major arc (≥ 180°), as NMC
    /// `CrdArcRadiusEx` (digest 001 §4.4, TV 44–45) and CPU 226H `MC_CIRCLE_*` RADIUS
    /// (digest 003 §2.14, TV-31). A radius below half the chord is refused unless within
    /// rounding ([`POINT_TOLERANCE`] + 1e-9 × radius), where it is taken as exactly half (a
    /// semicircle). Start = end in the plane is refused: a full circle needs its centre. The
    /// other axes move linearly (a helix), as in [`Arc::from_center`].
    pub fn from_radius(
        start: Point,
        end: Point,
        radius: f64,
        plane: (usize, usize),
        turn: Turn,
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        let (i, j) = plane;
        check_planar(plane, dims, &[("start", &start), ("end", &end)])?;
        check_number("radius", radius)?;
        let (dx, dy) = (end[i] - start[i], end[j] - start[j]);
        let chord = dx.hypot(dy);
        if chord <= POINT_TOLERANCE {
            return Err(GeometryError::Invalid(
                "an arc by radius needs an end different from its start in the plane (a full circle needs a centre)",
            ));
        }
        let r = radius.abs();
        let half_chord = chord / 2.0;
        if r < half_chord - radius_tolerance(r) {
            return Err(GeometryError::RadiusTooSmall {
                radius: r,
                half_chord,
            });
        }
        let r = r.max(half_chord);
        // The centre lies on the chord's perpendicular bisector, at `rise` from the midpoint;
        // for a counter-clockwise minor arc on the left of start → end (the arc then turns
        // < 180° about it), and each of "clockwise" and "major" moves it to the other side.
        let rise = (r * r - half_chord * half_chord).max(0.0).sqrt();
        let (nx, ny) = (-dy / chord, dx / chord);
        let side = turn.sign() * radius.signum();
        let cx = start[i] + dx / 2.0 + side * rise * nx;
        let cy = start[j] + dy / 2.0 + side * rise * ny;
        let minor = 2.0 * (half_chord / r).min(1.0).asin();
        let sweep = if radius > 0.0 { minor } else { TAU - minor };
        Ok(Arc::planar(start, end, (cx, cy), plane, turn, sweep, dims))
    }

    /// The arc from `start` about `center` (its in-plane coordinates; the others are ignored)
    /// through the signed angle `angle` (radians: > 0 counter-clockwise, < 0 clockwise, any
    /// magnitude, so more than one turn is allowed), as HIMC `ArcAngle2D` (digest 004 §2.7,
    /// TV 44, which gives degrees: the caller converts). The other axes stay where they are.
    /// The end point is computed.
    pub fn from_center_angle(
        start: Point,
        center: Point,
        angle: f64,
        plane: (usize, usize),
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        let (i, j) = plane;
        check_planar(plane, dims, &[("start", &start), ("center", &center)])?;
        check_number("angle", angle)?;
        let radius = (start[i] - center[i]).hypot(start[j] - center[j]);
        if radius <= POINT_TOLERANCE {
            return Err(GeometryError::Invalid(
                "the arc's centre is its start point",
            ));
        }
        if angle.abs() < MIN_SWEEP {
            return Err(GeometryError::Invalid("the arc's angle is 0"));
        }
        let turn = Turn::of_angle(angle);
        let a1 = (start[j] - center[j]).atan2(start[i] - center[i]) + angle;
        let mut end = start;
        end[i] = center[i] + radius * a1.cos();
        end[j] = center[j] + radius * a1.sin();
        Ok(Arc::planar(
            start,
            end,
            (center[i], center[j]),
            plane,
            turn,
            angle.abs(),
            dims,
        ))
    }

    /// The 3-D arc from `start` about the axis through `center` along `normal`, turning
    /// `angle` radians by the right-hand rule about `normal` (< 0 turns the other way; any
    /// magnitude), in the space of path axes `axes` (x, y, z); the other axes stay put. As
    /// HIMC `CircleAbs` (digest 004 §2.7: the normal gives the direction, {0,0,1} is CCW).
    /// A centre off the plane through `start` ⟂ `normal` is projected onto it along the
    /// normal (the circle is the one `start` describes turning about that axis). The end point
    /// is computed.
    pub fn about_normal(
        start: Point,
        center: Point,
        normal: [f64; 3],
        angle: f64,
        axes: [usize; 3],
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        let (e1, e2) = normal_basis(&start, &start, &center, normal, axes, dims)?;
        check_number("angle", angle)?;
        if angle.abs() < MIN_SWEEP {
            return Err(GeometryError::Invalid("the arc's angle is 0"));
        }
        let turn = Turn::of_angle(angle);
        let sweep = angle.abs();
        let c = in_plane_of(&start, &center, &e1, &e2);
        // The end: start turned by `sweep` about the axis, found from the arc itself.
        let (sin, cos) = sweep.sin_cos();
        let d = sub(&start, &c);
        let (a, b) = (dot(&d, &e1), dot(&d, &e2));
        let rotated = add(
            &scale(&e1, a * cos - turn.sign() * b * sin),
            &scale(&e2, b * cos + turn.sign() * a * sin),
        );
        let end = add(&c, &rotated);
        Arc::around(start, end, c, e1, e2, dims, |_, _| Ok((turn, sweep)))
    }

    /// A planar arc from checked parts: the centre `(cx, cy)` in `plane`, the sweep (> 0) and
    /// the turn; the radius is start's distance from the centre, and the other axes move
    /// linearly from `start` to `end`.
    fn planar(
        start: Point,
        end: Point,
        (cx, cy): (f64, f64),
        plane: (usize, usize),
        turn: Turn,
        sweep: f64,
        dims: usize,
    ) -> Arc {
        let (i, j) = plane;
        let (sx, sy) = (start[i] - cx, start[j] - cy);
        let radius = sx.hypot(sy);
        let mut u = [0.0; MAX_AXES];
        let mut v = [0.0; MAX_AXES];
        u[i] = sx / radius;
        u[j] = sy / radius;
        // v is u turned 90° in the direction of travel.
        let sign = turn.sign();
        v[i] = -u[j] * sign;
        v[j] = u[i] * sign;
        let mut center_full = start;
        center_full[i] = cx;
        center_full[j] = cy;
        let mut h = sub(&end, &start);
        h[i] = 0.0;
        h[j] = 0.0;
        Arc::from_parts(center_full, u, v, radius, sweep, h, end, dims)
    }

    /// An arc from its parts (see the module doc). `u` and `v` must be orthonormal and `h`
    /// orthogonal to both; `center` is the centre at θ = 0 (the helix's start level). `end`
    /// is kept as the exact end point.
    #[allow(clippy::too_many_arguments)]
    pub fn from_parts(
        center: Point,
        u: Point,
        v: Point,
        radius: f64,
        sweep: f64,
        h: Point,
        end: Point,
        dims: usize,
    ) -> Arc {
        let length = (radius * sweep).hypot(norm(&h));
        Arc {
            center,
            u,
            v,
            radius,
            sweep,
            h,
            end,
            length,
            dims,
        }
    }

    pub fn length(&self) -> f64 {
        self.length
    }

    pub fn dims(&self) -> usize {
        self.dims
    }

    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Swept angle, radians (> 0).
    pub fn sweep(&self) -> f64 {
        self.sweep
    }

    pub fn center(&self) -> Point {
        self.center
    }

    pub fn end(&self) -> Point {
        self.end
    }

    /// The length of the circular part alone, `radius × sweep` (HMC `MoveHelical` modes
    /// 4/5/7 advance the result axis by this, not by the helix's length: digest 000 §4.3,
    /// TV 19).
    pub fn circle_length(&self) -> f64 {
        self.radius * self.sweep
    }

    /// Norm of the curvature vector (1/radius for a flat arc, less for a helix).
    pub fn curvature(&self) -> f64 {
        if self.length > 0.0 {
            self.radius * (self.sweep / self.length).powi(2)
        } else {
            0.0
        }
    }

    /// Norm of `d³p/ds³`, the same everywhere on the arc: `r·w³` with `w = sweep/length`.
    pub fn curvature_rate(&self) -> f64 {
        if self.length > 0.0 {
            self.radius * (self.sweep / self.length).powi(3)
        } else {
            0.0
        }
    }

    /// Bound on |tangent component| of `axis` over the arc (the in-plane amplitude plus the
    /// linear part), ≤ 1.
    pub fn max_tangent(&self, axis: usize) -> f64 {
        if axis >= MAX_AXES || self.length <= 0.0 {
            return 0.0;
        }
        let w = self.radius * self.sweep / self.length;
        let amplitude = w * self.u[axis].hypot(self.v[axis]);
        (amplitude + self.h[axis].abs() / self.length).min(1.0)
    }

    pub fn sample(&self, s: f64) -> PathPoint {
        if self.length <= 0.0 {
            return PathPoint {
                p: self.end,
                ..PathPoint::default()
            };
        }
        let s = s.clamp(0.0, self.length);
        if s >= self.length {
            return self.sample_at(self.sweep.sin_cos(), self.end);
        }
        let theta = self.sweep * s / self.length;
        let (sin, cos) = theta.sin_cos();
        let f = theta / self.sweep;
        let mut p = [0.0; MAX_AXES];
        for (k, out) in p.iter_mut().enumerate() {
            *out =
                self.center[k] + self.radius * (cos * self.u[k] + sin * self.v[k]) + f * self.h[k];
        }
        // The same sine and cosine: a servo tick evaluates them once.
        self.sample_at((sin, cos), p)
    }

    /// The sample at angle θ given as `(sin θ, cos θ)`, with its point `p`.
    fn sample_at(&self, (sin, cos): (f64, f64), p: Point) -> PathPoint {
        let w = self.sweep / self.length;
        let mut t = [0.0; MAX_AXES];
        let mut k = [0.0; MAX_AXES];
        for a in 0..MAX_AXES {
            t[a] = self.radius * w * (-sin * self.u[a] + cos * self.v[a]) + self.h[a] / self.length;
            k[a] = -self.radius * w * w * (cos * self.u[a] + sin * self.v[a]);
        }
        PathPoint { p, t, k }
    }

    /// The part of the arc from path length `s0` to `s1` (clamped, `s0 ≤ s1`): same circle,
    /// start turned by θ(s0), sweep and linear part shortened. `s1 = length` keeps the exact end.
    pub fn trimmed(&self, s0: f64, s1: f64) -> Arc {
        let s0 = s0.clamp(0.0, self.length);
        let s1 = s1.clamp(s0, self.length);
        if self.length <= 0.0 {
            return self.clone();
        }
        let theta0 = self.sweep * s0 / self.length;
        let (sin, cos) = theta0.sin_cos();
        let f0 = s0 / self.length;
        let mut u = [0.0; MAX_AXES];
        let mut v = [0.0; MAX_AXES];
        let mut center = self.center;
        let mut h = [0.0; MAX_AXES];
        for k in 0..MAX_AXES {
            u[k] = cos * self.u[k] + sin * self.v[k];
            v[k] = -sin * self.u[k] + cos * self.v[k];
            center[k] += f0 * self.h[k];
            h[k] = self.h[k] * (s1 - s0) / self.length;
        }
        let end = if s1 >= self.length {
            self.end
        } else {
            self.sample(s1).p
        };
        let sweep = self.sweep * (s1 - s0) / self.length;
        Arc::from_parts(center, u, v, self.radius, sweep, h, end, self.dims)
    }

    /// The arc moved by a rigid transform: centre and end moved, the plane's vectors and the
    /// helix's rise turned; radius, sweep and length unchanged, so the arc stays exact.
    pub fn transformed(&self, t: &Transform) -> Arc {
        Arc {
            center: t.apply(&self.center),
            u: t.apply_vector(&self.u),
            v: t.apply_vector(&self.v),
            h: t.apply_vector(&self.h),
            end: t.apply(&self.end),
            ..self.clone()
        }
    }

    /// The in-plane unit vectors (toward the start from the centre; 90° ahead).
    pub fn basis(&self) -> (Point, Point) {
        (self.u, self.v)
    }

    /// Linear displacement of the out-of-plane axes over the whole arc.
    pub fn helix(&self) -> Point {
        self.h
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(c: &[f64]) -> Point {
        let mut out = [0.0; MAX_AXES];
        out[..c.len()].copy_from_slice(c);
        out
    }

    #[test]
    fn a_quarter_circle_has_length_pi_r_over_2_and_ends_exactly() {
        let a = Arc::from_center(
            p(&[10.0, 0.0]),
            p(&[0.0, 10.0]),
            p(&[0.0, 0.0]),
            (0, 1),
            Turn::Ccw,
            0,
            2,
        )
        .unwrap();
        assert!((a.length() - 5.0 * std::f64::consts::PI).abs() < 1e-12);
        let mid = a.sample(a.length() / 2.0);
        let r = std::f64::consts::FRAC_1_SQRT_2 * 10.0;
        assert!((mid.p[0] - r).abs() < 1e-12 && (mid.p[1] - r).abs() < 1e-12);
        assert_eq!(a.sample(a.length()).p, p(&[0.0, 10.0]));
        assert!((norm(&mid.t) - 1.0).abs() < 1e-12);
        assert!((norm(&mid.k) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn start_equal_to_end_is_a_full_circle_and_cw_goes_the_other_way() {
        let a = Arc::from_center(
            p(&[10.0, 0.0]),
            p(&[10.0, 0.0]),
            p(&[0.0, 0.0]),
            (0, 1),
            Turn::Cw,
            0,
            2,
        )
        .unwrap();
        assert!((a.sweep() - std::f64::consts::TAU).abs() < 1e-12);
        assert!(a.sample(1.0).p[1] < 0.0);
    }

    #[test]
    fn a_helix_moves_the_third_axis_linearly() {
        let a = Arc::from_center(
            p(&[10.0, 0.0, 0.0]),
            p(&[10.0, 0.0, 5.0]),
            p(&[0.0, 0.0, 0.0]),
            (0, 1),
            Turn::Ccw,
            4,
            3,
        )
        .unwrap();
        assert!((a.sweep() - 5.0 * std::f64::consts::TAU).abs() < 1e-12);
        let half = a.sample(a.length() / 2.0);
        assert!((half.p[2] - 2.5).abs() < 1e-12);
        assert!((norm(&half.t) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_trimmed_arc_follows_the_original() {
        let a = Arc::from_center(
            p(&[10.0, 0.0, 0.0]),
            p(&[0.0, 10.0, 3.0]),
            p(&[0.0, 0.0, 0.0]),
            (0, 1),
            Turn::Ccw,
            1,
            3,
        )
        .unwrap();
        let t = a.trimmed(2.0, a.length() - 1.0);
        assert!((t.length() - (a.length() - 3.0)).abs() < 1e-9);
        for i in 0..=10 {
            let s = t.length() * i as f64 / 10.0;
            let (x, y) = (t.sample(s), a.sample(s + 2.0));
            assert!(norm(&sub(&x.p, &y.p)) < 1e-9 && norm(&sub(&x.t, &y.t)) < 1e-9);
        }
        assert_eq!(a.trimmed(1.0, a.length()).end(), a.end());
    }

    #[test]
    fn a_centre_not_equidistant_is_refused() {
        let e = Arc::from_center(
            p(&[10.0, 0.0]),
            p(&[0.0, 11.0]),
            p(&[0.0, 0.0]),
            (0, 1),
            Turn::Ccw,
            0,
            2,
        );
        assert!(matches!(e, Err(GeometryError::Invalid(_))));
    }
}
