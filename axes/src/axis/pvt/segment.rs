//! One piece of a PT/PVT stream: a polynomial in time between two knots, in the stream's own
//! units (milliseconds, user units relative to the stream's start, units/ms, units/ms²).

use crate::command::PtKind;

/// Where and how fast the axis is at a time of the stream.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Knot {
    /// ms from the stream's start.
    pub t: f64,
    pub p: f64,
    /// units/ms.
    pub v: f64,
}

/// Position, velocity and acceleration (units, units/ms, units/ms²).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Kinematics {
    pub p: f64,
    pub v: f64,
    pub a: f64,
}

/// p(τ) = p0 + v0·τ + c2·τ² + c3·τ³ for τ = t − t0 ∈ [0, t1 − t0]; it passes (t1, p1) with
/// velocity v1 (up to rounding: the end knot itself is kept and used where it is reached).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Segment {
    pub t0: f64,
    pub t1: f64,
    pub p0: f64,
    pub p1: f64,
    pub v0: f64,
    pub v1: f64,
    c2: f64,
    c3: f64,
}

impl Segment {
    /// The cubic through both knots' positions and velocities (NMC PVT, digest 001 §4.7:
    /// "p = at³+bt²+ct+d per segment from (p,v,t) at both ends"). `b.t > a.t`.
    pub fn hermite(a: Knot, b: Knot) -> Segment {
        let h = b.t - a.t;
        let slope = (b.p - a.p) / h;
        Segment {
            t0: a.t,
            t1: b.t,
            p0: a.p,
            p1: b.p,
            v0: a.v,
            v1: b.v,
            c2: (3.0 * slope - 2.0 * a.v - b.v) / h,
            c3: (a.v + b.v - 2.0 * slope) / (h * h),
        }
    }

    /// The NMC PT segment from the chain's end `previous` to position `p` at time `t` (digest
    /// 001 §4.7, C3§3.1): constant acceleration, velocities by `kind`. A STOP or EVEN segment
    /// may start at another velocity than `previous` ended with (the manual's rule).
    pub fn pt(previous: Knot, t: f64, p: f64, kind: PtKind) -> Segment {
        let h = t - previous.t;
        let slope = (p - previous.p) / h;
        let (v0, v1) = match kind {
            PtKind::Normal => (previous.v, 2.0 * slope - previous.v),
            PtKind::Stop => (2.0 * slope, 0.0),
            PtKind::Even => (slope, slope),
        };
        Segment {
            t0: previous.t,
            t1: t,
            p0: previous.p,
            p1: p,
            v0,
            v1,
            c2: (v1 - v0) / (2.0 * h),
            c3: 0.0,
        }
    }

    pub fn end(&self) -> Knot {
        Knot {
            t: self.t1,
            p: self.p1,
            v: self.v1,
        }
    }

    /// The state at stream time `t` (meant for t0 ≤ t < t1; at t0 it is the start knot exactly).
    #[inline]
    pub fn sample(&self, t: f64) -> Kinematics {
        let tau = t - self.t0;
        let (c2, c3) = (self.c2, self.c3);
        Kinematics {
            p: self.p0 + tau * (self.v0 + tau * (c2 + tau * c3)),
            v: self.v0 + tau * (2.0 * c2 + 3.0 * c3 * tau),
            a: 2.0 * c2 + 6.0 * c3 * tau,
        }
    }

    /// The largest |velocity| and |acceleration| inside the segment (units/ms, units/ms²): the
    /// velocity is a parabola in τ, so its extremes are at the ends or at its vertex; the
    /// acceleration is linear.
    pub fn peaks(&self) -> (f64, f64) {
        let h = self.t1 - self.t0;
        let mut v = self.v0.abs().max(self.v1.abs());
        if self.c3 != 0.0 {
            let vertex = -self.c2 / (3.0 * self.c3);
            if vertex > 0.0 && vertex < h {
                v = v.max(self.sample(self.t0 + vertex).v.abs());
            }
        }
        let a0 = 2.0 * self.c2;
        let a1 = a0 + 6.0 * self.c3 * h;
        (v, a0.abs().max(a1.abs()))
    }

    /// Every coefficient is a finite number (a tiny Δt can overflow the slope).
    pub fn is_finite(&self) -> bool {
        [self.v0, self.v1, self.c2, self.c3]
            .iter()
            .all(|x| x.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hermite_segment_starts_and_ends_on_its_knots() {
        let a = Knot {
            t: 2.0,
            p: 1.0,
            v: -0.5,
        };
        let b = Knot {
            t: 7.0,
            p: 4.0,
            v: 2.0,
        };
        let s = Segment::hermite(a, b);
        let start = s.sample(2.0);
        assert_eq!((start.p, start.v), (1.0, -0.5));
        let end = s.sample(7.0);
        assert!((end.p - 4.0).abs() < 1e-12 && (end.v - 2.0).abs() < 1e-12);
    }

    #[test]
    fn pt_segments_follow_the_nmc_velocity_rules() {
        // digest 001 TV55: {10000, 30000, 40000} at {100, 200, 300} ms, NORMAL ×3.
        let mut k = Knot::default();
        let mut ends = Vec::new();
        for (t, p) in [(100.0, 10_000.0), (200.0, 30_000.0), (300.0, 40_000.0)] {
            let s = Segment::pt(k, t, p, PtKind::Normal);
            k = s.end();
            ends.push(k.v);
        }
        assert_eq!(ends, [200.0, 200.0, 0.0]);
        let stop = Segment::pt(Knot::default(), 10.0, 50.0, PtKind::Stop);
        assert_eq!((stop.v0, stop.v1), (10.0, 0.0));
        let even = Segment::pt(Knot::default(), 10.0, 50.0, PtKind::Even);
        assert_eq!((even.v0, even.v1), (5.0, 5.0));
    }

    #[test]
    fn peaks_include_the_velocity_vertex_inside_the_segment() {
        // Out and back: 0 → 0 with zero end velocities except a kick at the start.
        let s = Segment::hermite(
            Knot {
                t: 0.0,
                p: 0.0,
                v: 0.0,
            },
            Knot {
                t: 2.0,
                p: 3.0,
                v: 0.0,
            },
        );
        let (v, a) = s.peaks();
        // v(τ) = 6·(τ/2)(1 − τ/2)·3/2 peaks at τ = 1 with 2.25; a = ±4.5 at the ends.
        assert!((v - 2.25).abs() < 1e-12, "{v}");
        assert!((a - 4.5).abs() < 1e-12, "{a}");
    }
}
