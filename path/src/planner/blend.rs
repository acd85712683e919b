//! Corner geometry for blended junctions between two lines (issue 11 item 4; HIMC TM_*,
//! digest 004 §3; G64 P; PLCopen Part 4 transition modes): the corner is replaced by the arc
//! tangent to both lines, so the path has no direction step there and its speed is limited
//! only by the arc's curvature.
//!
//! For a turn of angle `α` between the lines and a tangent length `T` (the distance from the
//! corner at which the arc leaves each line): radius `R = T / tan(α/2)`, and the arc passes
//! the corner at `R·(1/cos(α/2) − 1)` (its deviation). Every point of the arc lies within `T`
//! of the corner, so the path never leaves the programmed polyline by more than `T`.

use super::Transition;
use crate::geometry::{dot, norm, Arc, Line};
use crate::{Point, MAX_AXES};

/// Turns smaller than this (radians) are straight: no arc is worth it. Turns closer than this
/// to a reversal get none either (the arc would be a point).
const MIN_TURN: f64 = 1e-6;

/// Tangent lengths below this (user units) are no blend.
const MIN_TANGENT: f64 = 1e-9;

/// The arc that rounds the corner between `first` and `second` (which starts where `first`
/// ends), and the tangent length to trim from each line. `None`: no arc (no corner
/// geometry asked for, a straight or reversing corner, or a tangent length of 0).
/// Corner distance `d`: `T = d`; corner deviation `e`: `R = e / (1/cos(α/2) − 1)`,
/// `T = R·tan(α/2)`. `T` is clamped to half of each line, so consecutive blends never overlap.
pub(super) fn corner_arc(
    first: &Line,
    second: &Line,
    transition: Transition,
    dims: usize,
) -> Option<(f64, Arc)> {
    let d1 = first.direction();
    let d2 = second.direction();
    let cos = dot(d1, d2).clamp(-1.0, 1.0);
    let turn = cos.acos();
    if !(MIN_TURN..=std::f64::consts::PI - MIN_TURN).contains(&turn) {
        return None;
    }
    let half = 0.5 * turn;
    let wanted = match transition {
        Transition::None => return None,
        Transition::CornerDistance(d) => d,
        Transition::CornerDeviation(e) => {
            let radius = e / (1.0 / half.cos() - 1.0);
            radius * half.tan()
        }
    };
    let tangent = wanted.min(0.5 * first.length()).min(0.5 * second.length());
    if (tangent.is_nan() || tangent <= MIN_TANGENT) || !tangent.is_finite() {
        return None;
    }
    let radius = tangent / half.tan();
    let corner = first.end();
    let mut normal = [0.0; MAX_AXES];
    for k in 0..MAX_AXES {
        normal[k] = d2[k] - cos * d1[k];
    }
    let n_len = norm(&normal);
    if n_len.is_nan() || n_len <= 0.0 {
        return None;
    }
    let mut start: Point = [0.0; MAX_AXES];
    let mut end: Point = [0.0; MAX_AXES];
    let mut center: Point = [0.0; MAX_AXES];
    let mut u: Point = [0.0; MAX_AXES];
    for k in 0..MAX_AXES {
        normal[k] /= n_len;
        start[k] = corner[k] - tangent * d1[k];
        end[k] = corner[k] + tangent * d2[k];
        center[k] = start[k] + radius * normal[k];
        u[k] = -normal[k];
    }
    let arc = Arc::from_parts(center, u, *d1, radius, turn, [0.0; MAX_AXES], end, dims);
    Some((tangent, arc))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sub;

    fn p(x: f64, y: f64) -> Point {
        let mut out = [0.0; MAX_AXES];
        out[0] = x;
        out[1] = y;
        out
    }

    #[test]
    fn a_right_angle_gets_a_quarter_circle_tangent_to_both_lines() {
        let a = Line::new(p(0.0, 0.0), p(10.0, 0.0), 2).unwrap();
        let b = Line::new(p(10.0, 0.0), p(10.0, 10.0), 2).unwrap();
        let (t, arc) = corner_arc(&a, &b, Transition::CornerDistance(2.0), 2).unwrap();
        assert_eq!(t, 2.0);
        assert!((arc.radius() - 2.0).abs() < 1e-12);
        assert!(norm(&sub(&arc.sample(0.0).p, &p(8.0, 0.0))) < 1e-12);
        assert!(norm(&sub(&arc.end(), &p(10.0, 2.0))) < 1e-12);
        let end = arc.sample(arc.length());
        assert!(norm(&sub(&end.t, b.direction())) < 1e-12);
        assert!(norm(&sub(&arc.sample(0.0).t, a.direction())) < 1e-12);
        // Deviation e: the arc's middle is e from the corner.
        let (_, arc) = corner_arc(&a, &b, Transition::CornerDeviation(0.5), 2).unwrap();
        let mid = arc.sample(arc.length() / 2.0).p;
        assert!((norm(&sub(&mid, &p(10.0, 0.0))) - 0.5).abs() < 1e-12);
    }
}
