//! Input checks shared by [`crate::geometry`] and [`crate::frames`], and the error they give.
//! Below both modules, so that neither imports the other for them.

use crate::{Point, MAX_AXES};

/// Why a segment cannot be built. Each names what is wrong, for the engine's typed error.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum GeometryError {
    #[error("{name} = {value}: must be a finite number")]
    NotFinite { name: &'static str, value: f64 },
    #[error("{0}")]
    Invalid(&'static str),
    #[error("{dims} axes: a path has 1 to 9")]
    Dimensions { dims: usize },
    #[error("axis {axis} is not one of the path's {dims} axes")]
    AxisOutOfRange { axis: usize, dims: usize },
    #[error("{first} and {second} are the same point")]
    Coincident {
        first: &'static str,
        second: &'static str,
    },
    #[error(
        "radius {radius} is smaller than half the chord ({half_chord}): no arc joins the points"
    )]
    RadiusTooSmall { radius: f64, half_chord: f64 },
}

/// Checks a path's axis count (1 to [`MAX_AXES`]).
pub fn check_dims(dims: usize) -> Result<(), GeometryError> {
    if dims == 0 || dims > MAX_AXES {
        return Err(GeometryError::Dimensions { dims });
    }
    Ok(())
}

/// Checks that every component of `p` is finite.
pub fn check_finite(name: &'static str, p: &Point) -> Result<(), GeometryError> {
    match p.iter().find(|c| !c.is_finite()) {
        Some(&value) => Err(GeometryError::NotFinite { name, value }),
        None => Ok(()),
    }
}

/// Checks that a number is finite.
pub fn check_number(name: &'static str, value: f64) -> Result<(), GeometryError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(GeometryError::NotFinite { name, value })
    }
}

/// Checks that `axis` is one of the first `dims` axes.
pub fn check_axis(axis: usize, dims: usize) -> Result<(), GeometryError> {
    if axis >= dims {
        return Err(GeometryError::AxisOutOfRange { axis, dims });
    }
    Ok(())
}
