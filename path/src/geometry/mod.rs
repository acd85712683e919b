//! The geometry of path segments, parametrised by path length `s`.
//!
//! Every segment answers the same questions, so the planner never asks which kind it has:
//! its [`Segment::length`], and at any `s` in `[0, length]` a [`PathPoint`]: the position, the
//! unit tangent `dp/ds` and the curvature vector `d²p/ds²` (its norm is 1/radius). Lines and
//! arcs (with helices) are closed form; curves through points are tabulated when built, so a
//! sample is a bounded lookup.
//!
//! All vectors are [`Point`]s; a path of `dims` axes leaves the components past `dims` at 0.

use crate::{Point, MAX_AXES};

mod arc;
mod line;

pub use arc::{Arc, Turn};
pub use line::Line;

/// Two points closer than this (in user units) are the same point; an arc's centre must be
/// this close to equidistant from its start and end (relative to the radius: see [`Arc`]).
pub const POINT_TOLERANCE: f64 = 1e-9;

/// Why a segment cannot be built. Each names what is wrong, for the engine's typed error.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum GeometryError {
    #[error("{name} = {value}: must be a finite number")]
    NotFinite { name: &'static str, value: f64 },
    #[error("{0}")]
    Invalid(&'static str),
    #[error("{dims} axes: a path has 1 to 9")]
    Dimensions { dims: usize },
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
}

impl Segment {
    /// Path length, user units (the Euclidean length over all the path's axes).
    pub fn length(&self) -> f64 {
        match self {
            Segment::Line(l) => l.length(),
            Segment::Arc(a) => a.length(),
        }
    }

    /// Number of axes.
    pub fn dims(&self) -> usize {
        match self {
            Segment::Line(l) => l.dims(),
            Segment::Arc(a) => a.dims(),
        }
    }

    /// The point, tangent and curvature at path length `s`, clamped to `[0, length]`.
    pub fn sample(&self, s: f64) -> PathPoint {
        match self {
            Segment::Line(l) => l.sample(s),
            Segment::Arc(a) => a.sample(s),
        }
    }

    /// The part of the segment from path length `s0` to `s1` (clamped, `s0 ≤ s1`), sampled
    /// by its own `s` from 0; `s1 = length` keeps the exact end point.
    pub fn trimmed(&self, s0: f64, s1: f64) -> Segment {
        match self {
            Segment::Line(l) => Segment::Line(l.trimmed(s0, s1)),
            Segment::Arc(a) => Segment::Arc(a.trimmed(s0, s1)),
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
        }
    }

    /// The largest curvature anywhere on the segment (0 for a line).
    pub fn max_curvature(&self) -> f64 {
        match self {
            Segment::Line(_) => 0.0,
            Segment::Arc(a) => a.curvature(),
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
