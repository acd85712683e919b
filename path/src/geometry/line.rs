//! Straight lines in N dimensions (HMC Move2D/3D/ND, NMC CrdLine*, HIMC Line, MC_LINE).

use super::{norm, sub, GeometryError, PathPoint};
use crate::frames::Transform;
use crate::{Point, MAX_AXES};

#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    start: Point,
    end: Point,
    /// Unit direction (0 when start = end).
    direction: Point,
    length: f64,
    dims: usize,
}

impl Line {
    /// The line from `start` to `end` over the first `dims` axes. A line of length 0 is allowed
    /// (the planner passes it in no time); the caller decides whether to refuse it.
    pub fn new(start: Point, end: Point, dims: usize) -> Result<Line, GeometryError> {
        if dims == 0 || dims > MAX_AXES {
            return Err(GeometryError::Dimensions { dims });
        }
        for (name, p) in [("start", &start), ("end", &end)] {
            if let Some(&value) = p.iter().find(|c| !c.is_finite()) {
                return Err(GeometryError::NotFinite { name, value });
            }
        }
        let delta = sub(&end, &start);
        let length = norm(&delta);
        let mut direction = [0.0; MAX_AXES];
        if length > 0.0 {
            for (d, x) in direction.iter_mut().zip(&delta) {
                *d = x / length;
            }
        }
        Ok(Line {
            start,
            end,
            direction,
            length,
            dims,
        })
    }

    pub fn length(&self) -> f64 {
        self.length
    }

    pub fn dims(&self) -> usize {
        self.dims
    }

    pub fn start(&self) -> Point {
        self.start
    }

    pub fn end(&self) -> Point {
        self.end
    }

    pub fn direction(&self) -> &Point {
        &self.direction
    }

    /// The part from path length `s0` to `s1` (clamped, `s0 ≤ s1`); `s1 = length` keeps the
    /// exact end.
    pub fn trimmed(&self, s0: f64, s1: f64) -> Line {
        let s0 = s0.clamp(0.0, self.length);
        let s1 = s1.clamp(s0, self.length);
        let start = self.sample(s0).p;
        let end = self.sample(s1).p;
        let mut l = self.clone();
        l.start = start;
        l.end = end;
        l.length = s1 - s0;
        l
    }

    /// The line moved by a rigid transform: exact, same length.
    pub fn transformed(&self, t: &Transform) -> Line {
        Line {
            start: t.apply(&self.start),
            end: t.apply(&self.end),
            direction: t.apply_vector(&self.direction),
            length: self.length,
            dims: self.dims,
        }
    }

    pub fn sample(&self, s: f64) -> PathPoint {
        let s = s.clamp(0.0, self.length);
        let mut p = self.start;
        if s >= self.length {
            p = self.end;
        } else {
            for (x, d) in p.iter_mut().zip(&self.direction) {
                *x += d * s;
            }
        }
        PathPoint {
            p,
            t: self.direction,
            k: [0.0; MAX_AXES],
        }
    }
}
