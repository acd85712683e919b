//! Corner geometry for blended junctions (issue 11 item 4; HIMC TM_*, digest 004 §3; G64 P;
//! PLCopen Part 4 transition modes): the corner is replaced by a short curve tangent to both
//! segments, so the path has no direction step there and its speed is limited only by the
//! curve's curvature.
//!
//! Between two lines ([`corner_arc`]): the arc tangent to both lines.
//! For a turn of angle `α` between the lines and a tangent length `T` (the distance from the
//! corner at which the arc leaves each line): radius `R = T / tan(α/2)`, and the arc passes
//! the corner at `R·(1/cos(α/2) − 1)` (its deviation). Every point of the arc lies within `T`
//! of the corner, so the path never leaves the programmed polyline by more than `T`.

use super::Transition;
use crate::geometry::{blend_control_points, distance, dot, norm, Arc, Curve, Line, Segment};
use crate::{Point, MAX_AXES};

/// Most trials of a shorter cut in [`corner_curve`] before the corner keeps its corner rule.
const BLEND_TRIES: usize = 8;

/// A corner rounded: the first segment without its end, the blend, the second segment
/// without its start.
pub(super) struct Rounded {
    pub head: Segment,
    pub blend: Segment,
    pub tail: Segment,
}

/// Round the corner between `first` and `second` (which starts where `first` ends), any
/// kinds of segment. Two lines get the tangent arc ([`corner_arc`], unchanged); a corner
/// with an arc or a curve gets the quintic G2 blend ([`Curve::blend`]) from the point a cut
/// `c` before the corner to the point `c` after it. Its deviation is bounded by the convex
/// hull of its control points: every control point within `tol` of the corner keeps the whole
/// blend within `tol` of the corner, hence of the programmed path (`tol` the corner distance
/// or the corner deviation). The cut starts at the line rule's tangent length (corner
/// distance `d`: `c = d`), at most half of either segment, and shrinks in proportion while a
/// control point lies farther than `tol` (≤ [`BLEND_TRIES`] closed-form trials, at push time).
pub(super) fn corner_curve(
    first: &Segment,
    second: &Segment,
    transition: Transition,
    dims: usize,
) -> Option<Rounded> {
    if let (Segment::Line(a), Segment::Line(b)) = (first, second) {
        let (tangent, arc) = corner_arc(a, b, transition, dims)?;
        return Some(Rounded {
            head: first.trimmed(0.0, first.length() - tangent),
            blend: Segment::Arc(arc),
            tail: second.trimmed(tangent, second.length()),
        });
    }
    let turn = dot(&first.end_tangent(), &second.start_tangent())
        .clamp(-1.0, 1.0)
        .acos();
    if !(MIN_TURN..=std::f64::consts::PI - MIN_TURN).contains(&turn) {
        return None;
    }
    let (tolerance, wanted) = match transition {
        Transition::None => return None,
        Transition::CornerDistance(d) => (d, d),
        Transition::CornerDeviation(e) => (e, tangent_for_deviation(e, 0.5 * turn)),
    };
    let (l1, l2) = (first.length(), second.length());
    let corner = first.end();
    let mut cut = wanted.min(0.5 * l1).min(0.5 * l2);
    for _ in 0..BLEND_TRIES {
        if cut.is_nan() || cut <= MIN_TANGENT || !cut.is_finite() {
            return None;
        }
        let head = first.trimmed(0.0, l1 - cut);
        let tail = second.trimmed(cut, l2);
        let from = head.sample(head.length());
        let to = tail.sample(0.0);
        let reach = blend_control_points(&from, &to)
            .iter()
            .map(|b| distance(b, &corner))
            .fold(0.0, f64::max);
        if reach <= tolerance {
            let blend = Curve::blend(&from, &to, dims).ok()?;
            return Some(Rounded { head, blend, tail });
        }
        // The reach grows about in proportion to the cut; aim a little inside.
        cut *= 0.9 * tolerance / reach;
    }
    None
}

/// The tangent length of the arc that passes a corner of half-turn `half` at `deviation`.
fn tangent_for_deviation(deviation: f64, half: f64) -> f64 {
    let radius = deviation / (1.0 / half.cos() - 1.0);
    radius * half.tan()
}

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
fn corner_arc(
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
        Transition::CornerDeviation(e) => tangent_for_deviation(e, half),
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
