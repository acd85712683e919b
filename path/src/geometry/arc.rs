//! Circular arcs in a plane of N-D space, with optional linear motion of the remaining axes
//! (helices). One representation serves every vendor's arc: the constructors differ only in
//! how they find the centre, the plane and the sweep.
//!
//! `p(θ) = c + r·(cos θ·u + sin θ·v) + (θ / sweep)·h`, θ from 0 to `sweep`, where `u` points
//! from the centre to the start, `v` is the in-plane unit vector 90° ahead in the direction of
//! travel, and `h` is the linear displacement of the axes outside the plane. θ is proportional
//! to path length, so `s → θ` is one multiplication.

use super::{norm, sub, GeometryError, PathPoint, POINT_TOLERANCE};
use crate::{Point, MAX_AXES};

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

impl Arc {
    /// The arc from `start` around `center` to `end` in the plane of axes `plane.0` (x) and
    /// `plane.1` (y), turning `turn`, after `extra_turns` full turns. Start = end in the plane
    /// is a full circle (plus the extra turns). The other axes move linearly from `start` to
    /// `end` (a helix). The centre must be equidistant from start and end within
    /// [`POINT_TOLERANCE`] + 1e-9 × radius.
    pub fn from_center(
        start: Point,
        end: Point,
        center: Point,
        plane: (usize, usize),
        turn: Turn,
        extra_turns: u32,
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        let (i, j) = plane;
        if dims == 0 || dims > MAX_AXES {
            return Err(GeometryError::Dimensions { dims });
        }
        if i == j || i >= dims || j >= dims {
            return Err(GeometryError::Invalid(
                "the arc's plane needs two different axes of the group",
            ));
        }
        for (name, p) in [("start", &start), ("end", &end), ("center", &center)] {
            if let Some(&value) = p.iter().find(|c| !c.is_finite()) {
                return Err(GeometryError::NotFinite { name, value });
            }
        }
        let (sx, sy) = (start[i] - center[i], start[j] - center[j]);
        let (ex, ey) = (end[i] - center[i], end[j] - center[j]);
        let radius = sx.hypot(sy);
        let r_end = ex.hypot(ey);
        if radius <= POINT_TOLERANCE {
            return Err(GeometryError::Invalid(
                "the arc's centre is its start point",
            ));
        }
        if (radius - r_end).abs() > POINT_TOLERANCE + 1e-9 * radius {
            return Err(GeometryError::Invalid(
                "the arc's centre is not equidistant from its start and end",
            ));
        }
        let ccw = turn == Turn::Ccw;
        let a0 = sy.atan2(sx);
        let a1 = ey.atan2(ex);
        let tau = std::f64::consts::TAU;
        let mut sweep = if ccw { a1 - a0 } else { a0 - a1 };
        sweep = sweep.rem_euclid(tau);
        let chord = (ex - sx).hypot(ey - sy);
        if chord <= POINT_TOLERANCE || sweep < 1e-12 {
            sweep = tau;
        }
        sweep += tau * extra_turns as f64;
        let mut u = [0.0; MAX_AXES];
        let mut v = [0.0; MAX_AXES];
        u[i] = sx / radius;
        u[j] = sy / radius;
        // v is u turned 90° in the direction of travel.
        let sign = if ccw { 1.0 } else { -1.0 };
        v[i] = -u[j] * sign;
        v[j] = u[i] * sign;
        let mut center_full = start;
        center_full[i] = center[i];
        center_full[j] = center[j];
        let mut h = sub(&end, &start);
        h[i] = 0.0;
        h[j] = 0.0;
        Ok(Arc::from_parts(
            center_full,
            u,
            v,
            radius,
            sweep,
            h,
            end,
            dims,
        ))
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

    /// Norm of the curvature vector (1/radius for a flat arc, less for a helix).
    pub fn curvature(&self) -> f64 {
        if self.length > 0.0 {
            self.radius * (self.sweep / self.length).powi(2)
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
            return self.sample_at(self.sweep, self.end);
        }
        let theta = self.sweep * s / self.length;
        let (sin, cos) = theta.sin_cos();
        let f = theta / self.sweep;
        let mut p = [0.0; MAX_AXES];
        for (k, out) in p.iter_mut().enumerate() {
            *out =
                self.center[k] + self.radius * (cos * self.u[k] + sin * self.v[k]) + f * self.h[k];
        }
        self.sample_at(theta, p)
    }

    fn sample_at(&self, theta: f64, p: Point) -> PathPoint {
        let (sin, cos) = theta.sin_cos();
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
