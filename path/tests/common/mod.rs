//! Helpers shared by the path crate's integration tests.

// Each test binary uses its own subset.
#![allow(dead_code)]

use path::geometry::{norm, sub};
use path::{Point, MAX_AXES};

/// A point from its first coordinates (the rest 0).
pub fn p(c: &[f64]) -> Point {
    let mut out = [0.0; MAX_AXES];
    out[..c.len()].copy_from_slice(c);
    out
}

/// Whether two points are within `tol` of each other.
pub fn close(a: &Point, b: &Point, tol: f64) -> bool {
    norm(&sub(a, b)) <= tol
}
