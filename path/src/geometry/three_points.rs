//! Arcs and circles through three points in N-D space, in the points' own plane (HMC
//! `MoveCircle` mode 0 and `MoveSpherical` mode 0/2, NMC `CrdArcPPPEx`/`CrdArc3DEx`/
//! `CrdCirclePPP`, CPU 226H `MC_3P_CIRCLE_*`, HIMC `Arc2D`).

use std::f64::consts::TAU;

use super::{
    add, check_dims, check_finite, distance, dot, norm, scale, sub, Arc, GeometryError, Line,
    Segment, POINT_TOLERANCE,
};
use crate::{Point, MAX_AXES};

/// The circle through three points: its centre, radius and the orthonormal pair (u, v) of its
/// plane with u from the centre to `start` and v oriented so that travelling from `start`
/// through `via` (sweep `to_via`) reaches `end` after `to_end` > `to_via` radians.
struct Circumcircle {
    center: Point,
    radius: f64,
    u: Point,
    v: Point,
    to_end: f64,
}

/// `None` when the three points are collinear: `via` within [`POINT_TOLERANCE`] + 1e-9 ×
/// chord of the line through `start` and `end` (the arc would have a radius too large to
/// sample precisely, and the line is within that distance of it).
fn circumcircle(start: &Point, via: &Point, end: &Point) -> Option<Circumcircle> {
    let a = sub(via, start);
    let b = sub(end, start);
    let (aa, bb, ab) = (dot(&a, &a), dot(&b, &b), dot(&a, &b));
    // Distance of the farther of via/end from the line through start and the other: the
    // triangle's height, from its doubled area √(aa·bb − ab²).
    let area2 = (aa * bb - ab * ab).max(0.0).sqrt();
    let longest = aa.max(bb).max(dot(&sub(end, via), &sub(end, via))).sqrt();
    if longest <= 0.0 || area2 / longest <= POINT_TOLERANCE + 1e-9 * longest {
        return None;
    }
    // centre = start + α·a + β·b with (centre − start)·a = aa/2 and ·b = bb/2.
    let det = aa * bb - ab * ab;
    let alpha = bb * (aa - ab) / (2.0 * det);
    let beta = aa * (bb - ab) / (2.0 * det);
    let offset = add(&scale(&a, alpha), &scale(&b, beta));
    let center = add(start, &offset);
    let radius = norm(&offset);
    let u = scale(&offset, -1.0 / radius);
    // v: the unit vector of the plane ⟂ u, from whichever of via/end is farther off u's line.
    let perp = |p: &Point| {
        let w = sub(p, &center);
        sub(&w, &scale(&u, dot(&w, &u)))
    };
    let (pv, pe) = (perp(via), perp(end));
    let pick = if norm(&pv) >= norm(&pe) { pv } else { pe };
    let mut v = scale(&pick, 1.0 / norm(&pick));
    let angle = |p: &Point, v: &Point| {
        let w = sub(p, &center);
        dot(&w, v).atan2(dot(&w, &u)).rem_euclid(TAU)
    };
    let (mut to_via, mut to_end) = (angle(via, &v), angle(end, &v));
    if to_via > to_end {
        // Going the other way round meets via first.
        v = scale(&v, -1.0);
        to_via = TAU - to_via;
        to_end = TAU - to_end;
    }
    debug_assert!(to_via <= to_end);
    Some(Circumcircle {
        center,
        radius,
        u,
        v,
        to_end,
    })
}

fn check_points(dims: usize, points: [(&'static str, &Point); 3]) -> Result<(), GeometryError> {
    check_dims(dims)?;
    for (name, p) in points {
        check_finite(name, p)?;
        if p.iter().skip(dims).any(|&c| c != 0.0) {
            return Err(GeometryError::Invalid(
                "a point has coordinates past the path's axes",
            ));
        }
    }
    for (x, y) in [(0, 1), (1, 2), (0, 2)] {
        let ((nx, px), (ny, py)) = (points[x], points[y]);
        if distance(px, py) <= POINT_TOLERANCE {
            return Err(GeometryError::Coincident {
                first: nx,
                second: ny,
            });
        }
    }
    Ok(())
}

impl Segment {
    /// The arc from `start` through `via` to `end`, in the plane of the three points (any of
    /// the first `dims` axes). Collinear points with `via` between the others give the line
    /// `start → end` (HMC `MoveCircle` mode 0, digest 000 §4.3); collinear points with `via`
    /// outside are refused (no arc or line passes through them in that order), and so are
    /// coincident points. Start = end is refused as coincident: a full circle through three
    /// points is [`Arc::circle_through`] (CPU 226H `FULL = 1`, NMC `CrdCirclePPP` and HMC
    /// `MoveSpherical` mode 2 all take it as a separate command). CPU 226H TV-32, HIMC TV 42.
    pub fn through_points(
        start: Point,
        via: Point,
        end: Point,
        dims: usize,
    ) -> Result<Segment, GeometryError> {
        check_points(dims, [("start", &start), ("via", &via), ("end", &end)])?;
        let Some(c) = circumcircle(&start, &via, &end) else {
            let chord = sub(&end, &start);
            let along = dot(&sub(&via, &start), &chord) / dot(&chord, &chord);
            if !(0.0..=1.0).contains(&along) {
                return Err(GeometryError::Invalid(
                    "the three points are on one line and the via point is not between the others",
                ));
            }
            return Ok(Segment::Line(Line::new(start, end, dims)?));
        };
        Ok(Segment::Arc(Arc::from_parts(
            c.center,
            c.u,
            c.v,
            c.radius,
            c.to_end,
            [0.0; MAX_AXES],
            end,
            dims,
        )))
    }
}

impl Arc {
    /// The full circle from `start` through `second` and `third` back to `start`, in their
    /// plane, visiting them in that order (CPU 226H `MC_3P_CIRCLE_*` with `FULL = 1`, digest
    /// 003 §2.16; NMC `CrdCirclePPP`; HMC `MoveSpherical` mode 2). Collinear or coincident
    /// points are refused: they fix no circle.
    pub fn circle_through(
        start: Point,
        second: Point,
        third: Point,
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        check_points(
            dims,
            [("start", &start), ("second", &second), ("third", &third)],
        )?;
        let c = circumcircle(&start, &second, &third).ok_or(GeometryError::Invalid(
            "the three points of a circle are on one line",
        ))?;
        Ok(Arc::from_parts(
            c.center,
            c.u,
            c.v,
            c.radius,
            TAU,
            [0.0; MAX_AXES],
            start,
            dims,
        ))
    }
}
