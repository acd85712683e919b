//! The geometry of path segments, parametrised by path length `s`.
//!
//! Every segment answers the same questions, so the planner never asks which kind it has:
//! its [`Segment::length`], and at any `s` in `[0, length]` a [`PathPoint`]: the position, the
//! unit tangent `dp/ds` and the curvature vector `d²p/ds²` (its norm is 1/radius). Lines and
//! arcs (with helices) are closed form; curves through points are tabulated when built, so a
//! sample is a bounded lookup.
//!
//! All vectors are [`Point`]s; a path of `dims` axes leaves the components past `dims` at 0.
//!
//! Constructors, by vendor rule (each validates its input into a [`GeometryError`]):
//! - lines: [`Line::new`] (any axes, extra axes in proportion: NMC D8, HMC MoveND);
//! - arcs in an axis plane: [`Arc::from_center`] (direction + extra turns; end = start is a
//!   full circle), [`Arc::from_radius`] (signed radius: NMC, CPU 226H),
//!   [`Arc::from_center_angle`] (HIMC ArcAngle2D), [`Arc::from_center_turns`] (HIMC
//!   Circle2D's signed turns), [`Arc::from_center_toward`] (HMC MoveCircle's projected end),
//!   [`Arc::helix_turns`] (NMC HelixCenterEx, HMC MoveHelical); the other axes move linearly;
//! - arcs through points: [`Segment::through_points`] (collinear → line, HMC),
//!   [`Arc::circle_through`] (full circle);
//! - 3-D arcs about a normal: [`Arc::about_normal`], [`Arc::from_center_normal`],
//!   [`Arc::from_center_normal_turns`] (HIMC CircleAbs);
//! - curves: [`Curve::spline`] (HMC MoveSplineND), [`Curve::ellipse`] (NMC CrdEllipse).
//!
//! Any segment moves to another frame exactly with [`Segment::transformed`]
//! ([`crate::frames`]).

use crate::frames::Transform;
use crate::{Point, MAX_AXES};

mod arc;
mod arc_center;
mod curve;
mod line;
mod three_points;

pub use arc::{Arc, Turn};
pub use arc_center::himc_turns_angle;
pub use curve::{
    blend_control_points, Curve, CurveKind, SplineBuild, ELLIPSE_RATIO, MAX_SPLINE_POINTS,
};
pub use line::Line;
// Defined below both `geometry` and `frames` (which checks its input the same way), and
// re-exported here where users look for them.
pub use crate::checks::{check_axis, check_dims, check_finite, check_number, GeometryError};

/// Two points closer than this (in user units) are the same point; an arc's centre must be
/// this close to equidistant from its start and end (relative to the radius: see [`Arc`]).
pub const POINT_TOLERANCE: f64 = 1e-9;

/// The smallest sweep an arc may be given explicitly (radians): below it the arc is a point
/// turning in place, which HIMC refuses too (`eERR_CRD_CMD_CIRC_ANGLE_SMALL`, digest 004 §5).
pub const MIN_SWEEP: f64 = 1e-12;

/// How far a centre may be from equidistant, or a radius below half the chord, before the
/// arc is refused: [`POINT_TOLERANCE`] plus 1e-9 of the radius (rounding of the caller's
/// arithmetic, not a second geometry).
pub(crate) fn radius_tolerance(radius: f64) -> f64 {
    POINT_TOLERANCE + 1e-9 * radius
}

/// Position, unit tangent and curvature vector at one path length.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathPoint {
    pub p: Point,
    /// `dp/ds`, a unit vector (0 for a segment of length 0).
    pub t: Point,
    /// `d²p/ds²`: points to the centre of curvature, norm = curvature (1/radius).
    pub k: Point,
}

/// One segment of a path.
#[derive(Clone, Debug, PartialEq)]
pub enum Segment {
    Line(Line),
    /// A circular arc in a plane, plus linear motion of the other axes (a helix).
    Arc(Arc),
    /// A spline through points or an ellipse, sampled through a length table.
    Curve(Curve),
}

impl Segment {
    /// Path length, user units (the Euclidean length over all the path's axes).
    pub fn length(&self) -> f64 {
        match self {
            Segment::Line(l) => l.length(),
            Segment::Arc(a) => a.length(),
            Segment::Curve(c) => c.length(),
        }
    }

    /// Number of axes.
    pub fn dims(&self) -> usize {
        match self {
            Segment::Line(l) => l.dims(),
            Segment::Arc(a) => a.dims(),
            Segment::Curve(c) => c.dims(),
        }
    }

    /// The point, tangent and curvature at path length `s`, clamped to `[0, length]`.
    pub fn sample(&self, s: f64) -> PathPoint {
        match self {
            Segment::Line(l) => l.sample(s),
            Segment::Arc(a) => a.sample(s),
            Segment::Curve(c) => c.sample(s),
        }
    }

    /// The part of the segment from path length `s0` to `s1` (clamped, `s0 ≤ s1`), sampled
    /// by its own `s` from 0; `s1 = length` keeps the exact end point.
    pub fn trimmed(&self, s0: f64, s1: f64) -> Segment {
        match self {
            Segment::Line(l) => Segment::Line(l.trimmed(s0, s1)),
            Segment::Arc(a) => Segment::Arc(a.trimmed(s0, s1)),
            Segment::Curve(c) => Segment::Curve(c.trimmed(s0, s1)),
        }
    }

    /// The segment moved by a rigid transform (program frame → machine frame): lines and arcs
    /// stay exact. The transform should keep the path in its axes
    /// ([`Transform::keeps`]`(self.dims())`); components it moves past them are kept but
    /// ignored by the path's dimension count.
    pub fn transformed(&self, t: &Transform) -> Segment {
        match self {
            Segment::Line(l) => Segment::Line(l.transformed(t)),
            Segment::Arc(a) => Segment::Arc(a.transformed(t)),
            Segment::Curve(c) => Segment::Curve(c.transformed(t)),
        }
    }

    pub fn start(&self) -> Point {
        self.sample(0.0).p
    }

    /// The end point, exactly as programmed (not computed from the length).
    pub fn end(&self) -> Point {
        match self {
            Segment::Line(l) => l.end(),
            Segment::Arc(a) => a.end(),
            Segment::Curve(c) => c.end(),
        }
    }

    pub fn start_tangent(&self) -> Point {
        self.sample(0.0).t
    }

    pub fn end_tangent(&self) -> Point {
        self.sample(self.length()).t
    }

    /// The largest |tangent component| of `axis` anywhere on the segment (≤ 1): the path speed
    /// `v` moves that axis at most `v ×` this.
    pub fn max_tangent(&self, axis: usize) -> f64 {
        match self {
            Segment::Line(l) => l.direction().get(axis).map_or(0.0, |c| c.abs()),
            Segment::Arc(a) => a.max_tangent(axis),
            Segment::Curve(c) => c.max_tangent(axis),
        }
    }

    /// The largest curvature anywhere on the segment (0 for a line).
    pub fn max_curvature(&self) -> f64 {
        match self {
            Segment::Line(_) => 0.0,
            Segment::Arc(a) => a.curvature(),
            Segment::Curve(c) => c.max_curvature(),
        }
    }

    /// The largest `|d³p/ds³|` (the rate of change of the curvature vector along the path)
    /// anywhere on the segment: 0 for a line, `r·w³` for an arc (`w` its angle per path
    /// length), an estimate from above for a curve. The planner bounds the axes' jerk with
    /// it (`v³·|d³p/ds³|` is the part of the jerk that the path speed alone makes).
    pub fn max_curvature_rate(&self) -> f64 {
        match self {
            Segment::Line(_) => 0.0,
            Segment::Arc(a) => a.curvature_rate(),
            Segment::Curve(c) => c.max_curvature_rate(),
        }
    }
}

/// Euclidean norm of the first `dims` components.
pub fn norm(v: &Point) -> f64 {
    v.iter().map(|c| c * c).sum::<f64>().sqrt()
}

pub fn sub(a: &Point, b: &Point) -> Point {
    let mut out = [0.0; MAX_AXES];
    for i in 0..MAX_AXES {
        out[i] = a[i] - b[i];
    }
    out
}

pub fn dot(a: &Point, b: &Point) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Checks a plane: two different axes of the path.
pub(crate) fn check_plane(plane: (usize, usize), dims: usize) -> Result<(), GeometryError> {
    check_axis(plane.0, dims)?;
    check_axis(plane.1, dims)?;
    if plane.0 == plane.1 {
        return Err(GeometryError::Invalid(
            "the arc's plane needs two different axes of the group",
        ));
    }
    Ok(())
}

/// Checks a planar construction's input: the axis count, the plane, and named points finite.
pub(crate) fn check_planar(
    plane: (usize, usize),
    dims: usize,
    points: &[(&'static str, &Point)],
) -> Result<(), GeometryError> {
    check_dims(dims)?;
    check_plane(plane, dims)?;
    points
        .iter()
        .try_for_each(|&(name, p)| check_finite(name, p))
}

pub fn add(a: &Point, b: &Point) -> Point {
    let mut out = [0.0; MAX_AXES];
    for i in 0..MAX_AXES {
        out[i] = a[i] + b[i];
    }
    out
}

/// `a · k`.
pub fn scale(a: &Point, k: f64) -> Point {
    a.map(|x| x * k)
}

/// Distance between two points.
pub fn distance(a: &Point, b: &Point) -> f64 {
    norm(&sub(a, b))
}

/// A point from a slice of up to 9 coordinates, checked finite.
pub fn point(name: &'static str, coords: &[f64]) -> Result<Point, GeometryError> {
    if coords.is_empty() || coords.len() > MAX_AXES {
        return Err(GeometryError::Dimensions { dims: coords.len() });
    }
    let mut p = [0.0; MAX_AXES];
    for (out, &c) in p.iter_mut().zip(coords) {
        if !c.is_finite() {
            return Err(GeometryError::NotFinite { name, value: c });
        }
        *out = c;
    }
    Ok(p)
}
