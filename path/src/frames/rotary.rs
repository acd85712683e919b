//! NMC's transforms that follow a rotary axis (digest 001 §2.10 C3§10.5, S-TRANS-ROTATE and
//! S-TRANS-XYZA). The manual gives the calls and the example but no numbers; the sign
//! conventions below are our reading and are recorded in docs/decisions.md.

use super::Transform;
use crate::checks::{check_axis, check_number, GeometryError};
use crate::Point;

/// NMC `CrdSetTransRotate(crd, rotAxisNo, angleRadEqual, firstAxisInitPos, secAxisInitPos)`:
/// the workpiece sits on a rotary table (axis `rotary_axis`, `rad_per_unit` radians per user
/// unit) turning about `center` of the plane `plane`. A program point is fixed to the
/// workpiece, so at table angle θ the machine must go to `center + R(θ)·(p − center)`.
///
/// Inputs: the constructor; per point, the program point and the rotary axis's position.
/// Output: [`RotaryTransform::at`] (the transform at that angle) and
/// [`RotaryTransform::to_machine`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotaryTransform {
    pub plane: (usize, usize),
    pub center: (f64, f64),
    pub rotary_axis: usize,
    pub rad_per_unit: f64,
}

impl RotaryTransform {
    pub fn new(
        plane: (usize, usize),
        center: (f64, f64),
        rotary_axis: usize,
        rad_per_unit: f64,
    ) -> Result<RotaryTransform, GeometryError> {
        // Checks the plane and centre once (angle 0).
        Transform::rotation_about(plane, center, 0.0)?;
        check_axis(rotary_axis, crate::MAX_AXES)?;
        if rotary_axis == plane.0 || rotary_axis == plane.1 {
            return Err(GeometryError::Invalid(
                "the rotary axis cannot be one of the rotated plane's axes",
            ));
        }
        check_number("rad_per_unit", rad_per_unit)?;
        Ok(RotaryTransform {
            plane,
            center,
            rotary_axis,
            rad_per_unit,
        })
    }

    /// The transform at rotary position `rotary` (user units).
    pub fn at(&self, rotary: f64) -> Transform {
        Transform::rotation_about(self.plane, self.center, rotary * self.rad_per_unit)
            .unwrap_or_default()
    }

    /// The machine point for program point `p`, whose rotary-axis component is the table's
    /// position.
    pub fn to_machine(&self, p: &Point) -> Point {
        self.at(p.get(self.rotary_axis).copied().unwrap_or(0.0))
            .apply(p)
    }
}

/// NMC `CrdSetXYZAPara(crd, pulse2Rad, toolX, toolY)` with `CrdSetTransXYZA`: a tool on a
/// rotary A axis, its tip `tool` away from the A axis's centre line at A = 0. Turning A by θ
/// moves the tip by `(R(θ) − I)·tool`; to keep the tip on the program point the machine XY
/// goes to `p − (R(θ) − I)·tool` (the identity at A = 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct XyzaTransform {
    pub rad_per_unit: f64,
    pub tool: (f64, f64),
}

impl XyzaTransform {
    pub fn new(rad_per_unit: f64, tool: (f64, f64)) -> Result<XyzaTransform, GeometryError> {
        check_number("rad_per_unit", rad_per_unit)?;
        check_number("tool", tool.0)?;
        check_number("tool", tool.1)?;
        Ok(XyzaTransform { rad_per_unit, tool })
    }

    /// Machine (X, Y, Z, A) for the program point `p` (axes 0–3; A = axis 3).
    pub fn to_machine(&self, p: &Point) -> Point {
        let (s, c) = (p[3] * self.rad_per_unit).sin_cos();
        let (tx, ty) = self.tool;
        let mut out = *p;
        out[0] -= (c - 1.0) * tx - s * ty;
        out[1] -= s * tx + (c - 1.0) * ty;
        out
    }

    /// The program point of machine point `m` (the inverse of [`XyzaTransform::to_machine`]).
    pub fn from_machine(&self, m: &Point) -> Point {
        let (s, c) = (m[3] * self.rad_per_unit).sin_cos();
        let (tx, ty) = self.tool;
        let mut out = *m;
        out[0] += (c - 1.0) * tx - s * ty;
        out[1] += s * tx + (c - 1.0) * ty;
        out
    }
}

/// NMC `CrdSetXYZAToolCalc(crd, deltaTheta, deltaX, deltaY, &toolX, &toolY)`: the tool offset
/// from a measurement: turning A by `delta_theta` (radians) moved the tip by `(dx, dy)`, so
/// `(R(Δθ) − I)·tool = (dx, dy)`. Refused when Δθ is a whole number of turns (no information).
pub fn xyza_tool_offset(delta_theta: f64, dx: f64, dy: f64) -> Result<(f64, f64), GeometryError> {
    check_number("delta_theta", delta_theta)?;
    check_number("dx", dx)?;
    check_number("dy", dy)?;
    let (s, c) = delta_theta.sin_cos();
    // (R − I) = [[a, −s], [s, a]] with a = c − 1; its inverse is [[a, s], [−s, a]] / (a² + s²).
    let a = c - 1.0;
    let det = a * a + s * s;
    if det < 1e-18 {
        return Err(GeometryError::Invalid(
            "a rotation of whole turns says nothing about the tool offset",
        ));
    }
    Ok(((a * dx + s * dy) / det, (-s * dx + a * dy) / det))
}
