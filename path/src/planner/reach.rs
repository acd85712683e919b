//! Closed-form distances and reachable velocities along the path, for the look-ahead and the
//! choice of each motion's end velocity.
//!
//! A "ramp" changes the path velocity from `v` to `w` with zero acceleration at both ends,
//! under an acceleration limit `a` and a jerk limit `j` (`∞`: a trapezoid ramp). The fastest
//! ramp is a symmetric S (or a constant-acceleration ramp), so its velocity is point-symmetric
//! about its middle and its distance is the mean velocity times its duration. Every function
//! here is a fixed number of arithmetic operations (no search): the look-ahead calls them per
//! queued motion, the execution once per motion start.

/// Relative safety margin on a reachable velocity: the profile crate solves the same problem
/// in its own normalised units, so a target exactly on the boundary could be missed by an ulp
/// and turn into an overshoot (a reversal of the path). 1e-9 of the velocity change is far
/// below anything a test or a user sees.
const MARGIN: f64 = 1e-9;

/// Duration of the fastest ramp changing the velocity by `dv ≥ 0`.
pub(super) fn ramp_time(dv: f64, a: f64, j: f64) -> f64 {
    if !j.is_finite() {
        dv / a
    } else if dv * j >= a * a {
        dv / a + a / j
    } else {
        2.0 * (dv / j).sqrt()
    }
}

/// Path distance of the fastest ramp from `v` to `w` (both ≥ 0).
pub(super) fn ramp_distance(v: f64, w: f64, a: f64, j: f64) -> f64 {
    0.5 * (v + w) * ramp_time((v - w).abs(), a, j)
}

/// The highest velocity `v ≥ w` from which a ramp reaches `w` within `length` (backward pass);
/// by symmetry also the highest velocity reachable from `w` by accelerating over `length`.
pub(super) fn reach(w: f64, length: f64, a: f64, j: f64) -> f64 {
    if length <= 0.0 || length.is_nan() {
        return w;
    }
    let v = if !j.is_finite() {
        (w * w + 2.0 * a * length).sqrt()
    } else {
        let c = a * a / j;
        // Distance at dv = c, where the S ramp gets a constant-acceleration middle.
        let at_c = (2.0 * w + c) * a / j;
        if length >= at_c {
            // (v² − w²)/(2a) + (v + w)·c/(2a) = length, solved for v.
            let k = c * w - w * w - 2.0 * a * length;
            0.5 * (-c + (c * c - 4.0 * k).max(0.0).sqrt())
        } else {
            // (v + w)·√((v − w)/j) = length; y = √((v − w)/j): j·y³ + 2w·y − length = 0, one
            // real root (Cardano), polished by two Newton steps against cancellation.
            let p = 2.0 * w / j;
            let q = -length / j;
            let big = (-0.5 * q + (0.25 * q * q + p * p * p / 27.0).sqrt()).cbrt();
            let mut y = if big > 0.0 {
                big - p / (3.0 * big)
            } else {
                0.0
            };
            for _ in 0..2 {
                let f = j * y * y * y + 2.0 * w * y - length;
                let df = 3.0 * j * y * y + 2.0 * w;
                if df > 0.0 {
                    y -= f / df;
                }
            }
            w + j * y.max(0.0) * y.max(0.0)
        }
    };
    if v.is_finite() && v > w {
        w + (v - w) * (1.0 - MARGIN)
    } else {
        w
    }
}

/// The lowest end velocity a ramp down from `v` reaches within `length` (0 when it can stop):
/// the root of `ramp_distance(v, w) = length` on the branch next to `w = v`. With a jerk limit
/// the distance is not monotonic in `w` near 0, so this is the lowest velocity of the
/// interval `[w, v]` that is entirely reachable, or 0.
pub(super) fn lowest_end(v: f64, length: f64, a: f64, j: f64) -> f64 {
    let length = length.max(0.0);
    if ramp_distance(v, 0.0, a, j) <= length {
        return 0.0;
    }
    let w = if !j.is_finite() {
        (v * v - 2.0 * a * length).max(0.0).sqrt()
    } else {
        let c = a * a / j;
        let disc = (2.0 * v + c) * (2.0 * v + c) - 8.0 * a * length;
        let quadratic = 0.5 * (c + disc.max(0.0).sqrt());
        if disc >= 0.0 && v - quadratic >= c {
            quadratic
        } else {
            // (2v − x)·√(x/j) = length, x = v − w; y = √(x/j): y³ − (2v/j)·y + length/j = 0.
            // The smallest positive root (trigonometric form: three real roots or none).
            let p = -2.0 * v / j;
            let q = length / j;
            let arg = (1.5 * q / p) * (-3.0 / p).sqrt();
            if !(-1.0..=1.0).contains(&arg) {
                return v;
            }
            let m = 2.0 * (-p / 3.0).sqrt();
            let theta = arg.acos() / 3.0;
            let mut y = f64::INFINITY;
            for k in 0..3 {
                let r = m * (theta - std::f64::consts::TAU * f64::from(k) / 3.0).cos();
                if r > 0.0 && r < y {
                    y = r;
                }
            }
            if !y.is_finite() {
                return v;
            }
            for _ in 0..2 {
                let f = y * y * y + p * y + q;
                let df = 3.0 * y * y + p;
                if df < 0.0 {
                    y -= f / df;
                }
            }
            v - j * y * y
        }
    };
    if w.is_finite() {
        (w + (v - w).abs() * MARGIN + f64::MIN_POSITIVE).clamp(0.0, v)
    } else {
        v
    }
}

/// Where a start state `(v, a)` with a jerk limit is once its acceleration is brought to 0 at
/// full jerk: `(velocity, distance)`. A trapezoid's acceleration steps, so it is `(v, 0)`.
pub(super) fn settle(v: f64, a: f64, j: f64) -> (f64, f64) {
    if !j.is_finite() || a == 0.0 {
        return (v, 0.0);
    }
    let t = a.abs() / j;
    let v1 = v + 0.5 * a * t;
    let s1 = v * t + 0.5 * a * t * t - a.signum() * j * t * t * t / 6.0;
    (v1, s1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reach_inverts_the_ramp_distance_in_both_regimes() {
        for &(w, length, a, j) in &[
            (0.0, 10.0, 100.0, f64::INFINITY),
            (5.0, 0.01, 100.0, 1000.0),
            (5.0, 50.0, 100.0, 1000.0),
            (0.0, 1e-4, 2000.0, 1e5),
            (30.0, 3.0, 2000.0, 1e5),
        ] {
            let v = reach(w, length, a, j);
            let d = ramp_distance(v, w, a, j);
            assert!(
                d <= length && d > length * (1.0 - 1e-6),
                "{w} {length}: {v} {d}"
            );
        }
    }

    #[test]
    fn lowest_end_inverts_the_ramp_distance_down() {
        for &(v, length, a, j) in &[
            (100.0, 10.0, 100.0, f64::INFINITY),
            (100.0, 1.0, 100.0, 1000.0),
            (100.0, 0.5, 1000.0, 1e4),
            (50.0, 0.05, 2000.0, 1e5),
        ] {
            let w = lowest_end(v, length, a, j);
            assert!(w > 0.0 && w < v);
            let d = ramp_distance(v, w, a, j);
            assert!(
                d <= length && d > length * (1.0 - 1e-6),
                "{v} {length}: {w} {d}"
            );
        }
        assert_eq!(lowest_end(1.0, 10.0, 100.0, 1000.0), 0.0);
    }
}
