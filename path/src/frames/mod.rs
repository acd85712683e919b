//! Frames: rigid transforms between a group's program coordinates and its machine
//! coordinates (issue 11 item 1).
//!
//! - [`Transform`]: a rigid transform of path points, `p ↦ R·p + t`, with `t` on every axis and
//!   `R` a rotation of 2 or 3 chosen axes: HIMC's 6-D `{X, Y, Z, A, B, C}` poses
//!   ([`Transform::from_himc_pose`], digest 004 §2.7, TV 56), a 2-D rotation about a point
//!   ([`Transform::rotation_about`]), NMC's per-group origin offset (`orgFlag`/`offset[]`,
//!   digest 001 §4.4: a [`Transform::translation`]). Compose, invert, apply to points and
//!   vectors; [`crate::geometry::Segment::transformed`] moves a whole segment exactly.
//! - [`FrameChain`]: HIMC's MCS → OFFSET → WCSn → PCS chain (digest 004 §2.7 Table 8.1.2.1):
//!   set each link's pose, pick the links a move uses ([`FrameSelection`], HIMC's `coord_sys`
//!   bits), convert points both ways and get the composite PCS → MCS transform.
//! - [`RotaryTransform`] and [`XyzaTransform`]: NMC's transforms that follow a rotary axis
//!   (`CrdSetTransRotate`, `CrdSetTransXYZA`, digest 001 §2.10 S-TRANS-ROTATE/S-TRANS-XYZA).
//! - [`polar`]: NMC's polar machine (`CrdSetTransPolar`), the non-rigid (x, y) → (θ, r) map of
//!   each tick's point and the bounds of its rates along a segment.
//!
//! Pure values: nothing here allocates or keeps state beyond its fields.

use crate::checks::{check_axis, check_dims, check_finite, check_number, GeometryError};
use crate::{Point, MAX_AXES};

mod chain;
pub mod polar;
mod rotary;

pub use chain::{Frame, FrameChain, FrameSelection, WCS_COUNT};
pub use rotary::{xyza_tool_offset, RotaryTransform, XyzaTransform};

/// A rigid transform of path points: `p ↦ R·p + t`.
///
/// Inputs: the constructors' offsets and angles (radians, except [`Transform::from_himc_pose`]
/// which takes HIMC's degrees). Outputs: [`Transform::apply`] (points),
/// [`Transform::apply_vector`] (directions: rotation only), [`Transform::compose`],
/// [`Transform::inverse`]. `R` is always a rotation (orthonormal, determinant +1), so the
/// inverse is exact up to rounding and lengths, angles and arcs are kept.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// `R`, row-major: `out[i] = Σ_j rotation[i][j]·p[j]`.
    rotation: [[f64; MAX_AXES]; MAX_AXES],
    translation: Point,
}

impl Default for Transform {
    fn default() -> Self {
        Transform::identity()
    }
}

fn identity_matrix() -> [[f64; MAX_AXES]; MAX_AXES] {
    let mut m = [[0.0; MAX_AXES]; MAX_AXES];
    for (i, row) in m.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    m
}

/// The rotation `Rz(yaw)·Ry(pitch)·Rx(roll)` (radians): fixed-axis roll about x, then pitch
/// about y, then yaw about z (HIMC's roll-pitch-yaw, Tait-Bryan ZYX, digest 004 §2.7).
pub fn rpy_matrix(roll: f64, pitch: f64, yaw: f64) -> [[f64; 3]; 3] {
    let (sa, ca) = roll.sin_cos();
    let (sb, cb) = pitch.sin_cos();
    let (sc, cc) = yaw.sin_cos();
    [
        [cc * cb, cc * sb * sa - sc * ca, cc * sb * ca + sc * sa],
        [sc * cb, sc * sb * sa + cc * ca, sc * sb * ca - cc * sa],
        [-sb, cb * sa, cb * ca],
    ]
}

impl Transform {
    pub fn identity() -> Transform {
        Transform {
            rotation: identity_matrix(),
            translation: [0.0; MAX_AXES],
        }
    }

    /// `p ↦ p + offset` (NMC `orgFlag = 1` with `offset[]`: user coordinates are machine
    /// coordinates minus the offset, so user → machine adds it).
    pub fn translation(offset: Point) -> Result<Transform, GeometryError> {
        check_finite("offset", &offset)?;
        Ok(Transform {
            translation: offset,
            ..Transform::identity()
        })
    }

    /// The rotation by `angle` (radians, counter-clockwise from `plane.0` toward `plane.1`)
    /// about the point `center` of that plane; the other axes are unchanged.
    pub fn rotation_about(
        plane: (usize, usize),
        center: (f64, f64),
        angle: f64,
    ) -> Result<Transform, GeometryError> {
        let (i, j) = plane;
        check_axis(i, MAX_AXES)?;
        check_axis(j, MAX_AXES)?;
        if i == j {
            return Err(GeometryError::Invalid(
                "a rotation's plane needs two different axes",
            ));
        }
        check_number("angle", angle)?;
        check_number("center", center.0)?;
        check_number("center", center.1)?;
        let (s, c) = angle.sin_cos();
        let mut t = Transform::identity();
        t.rotation[i][i] = c;
        t.rotation[i][j] = -s;
        t.rotation[j][i] = s;
        t.rotation[j][j] = c;
        // Fix the centre: t = c − R·c.
        t.translation[i] = center.0 - (c * center.0 - s * center.1);
        t.translation[j] = center.1 - (s * center.0 + c * center.1);
        Ok(t)
    }

    /// The 3-D rotation `m` (a rotation matrix; checked orthonormal with determinant +1 to
    /// 1e-9) acting on path axes `axes` (x, y, z), then the translation `offset`.
    pub fn from_rotation(
        m: [[f64; 3]; 3],
        axes: [usize; 3],
        offset: Point,
    ) -> Result<Transform, GeometryError> {
        for &a in &axes {
            check_axis(a, MAX_AXES)?;
        }
        if axes[0] == axes[1] || axes[1] == axes[2] || axes[0] == axes[2] {
            return Err(GeometryError::Invalid(
                "a 3-D rotation needs three different axes",
            ));
        }
        check_finite("offset", &offset)?;
        for row in &m {
            for &x in row {
                check_number("rotation", x)?;
            }
        }
        for a in 0..3 {
            for b in 0..3 {
                let d: f64 = (0..3).map(|k| m[k][a] * m[k][b]).sum();
                let want = if a == b { 1.0 } else { 0.0 };
                if (d - want).abs() > 1e-9 {
                    return Err(GeometryError::Invalid("the matrix is not a rotation"));
                }
            }
        }
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        if det < 0.0 {
            return Err(GeometryError::Invalid(
                "the matrix is a reflection, not a rotation",
            ));
        }
        let mut t = Transform::identity();
        for (r, &ar) in axes.iter().enumerate() {
            for (c, &ac) in axes.iter().enumerate() {
                t.rotation[ar][ac] = m[r][c];
            }
        }
        t.translation = offset;
        Ok(t)
    }

    /// HIMC's 6-D transform `{X, Y, Z, A, B, C}` with lengths and radians: `p ↦ R·p + t` on
    /// path axes 0, 1, 2 with `R = Rz(yaw)·Ry(pitch)·Rx(roll)` ([`rpy_matrix`]) and
    /// `t = (x, y, z)`. TV 56: `(400, 200, 0, 0, 0, 45°)` takes (10, 10) to (400, 214.142136).
    pub fn from_xyzrpy(
        x: f64,
        y: f64,
        z: f64,
        roll: f64,
        pitch: f64,
        yaw: f64,
    ) -> Result<Transform, GeometryError> {
        for (name, v) in [("roll", roll), ("pitch", pitch), ("yaw", yaw)] {
            check_number(name, v)?;
        }
        let mut offset = [0.0; MAX_AXES];
        offset[0] = x;
        offset[1] = y;
        offset[2] = z;
        let m = rpy_matrix(roll, pitch, yaw);
        // Built directly: rpy_matrix is a rotation by construction.
        check_finite("offset", &offset)?;
        let mut t = Transform::identity();
        for (r, row) in m.iter().enumerate() {
            t.rotation[r][..3].copy_from_slice(row);
        }
        t.translation = offset;
        Ok(t)
    }

    /// [`Transform::from_xyzrpy`] from HIMC's array `{X, Y, Z, A, B, C}` with A, B, C in
    /// degrees, as `SetGrpCoordTrans` takes it (digest 004 §8.3.31).
    pub fn from_himc_pose(pose: [f64; 6]) -> Result<Transform, GeometryError> {
        let [x, y, z, a, b, c] = pose;
        Transform::from_xyzrpy(x, y, z, a.to_radians(), b.to_radians(), c.to_radians())
    }

    /// `R·p + t`.
    pub fn apply(&self, p: &Point) -> Point {
        let mut out = self.apply_vector(p);
        for (o, t) in out.iter_mut().zip(&self.translation) {
            *o += t;
        }
        out
    }

    /// `R·v`: a direction or displacement (tangents, curvature vectors, a helix's rise).
    pub fn apply_vector(&self, v: &Point) -> Point {
        let mut out = [0.0; MAX_AXES];
        for (o, row) in out.iter_mut().zip(&self.rotation) {
            *o = row.iter().zip(v).map(|(r, x)| r * x).sum();
        }
        out
    }

    /// `self ∘ inner`: first `inner`, then `self`.
    pub fn compose(&self, inner: &Transform) -> Transform {
        let mut rotation = [[0.0; MAX_AXES]; MAX_AXES];
        for (i, row) in rotation.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = (0..MAX_AXES)
                    .map(|k| self.rotation[i][k] * inner.rotation[k][j])
                    .sum();
            }
        }
        Transform {
            rotation,
            translation: self.apply(&inner.translation),
        }
    }

    /// The inverse: `p ↦ Rᵀ·(p − t)`.
    pub fn inverse(&self) -> Transform {
        let mut rotation = [[0.0; MAX_AXES]; MAX_AXES];
        for (i, row) in rotation.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = self.rotation[j][i];
            }
        }
        let mut t = Transform {
            rotation,
            translation: [0.0; MAX_AXES],
        };
        let back = t.apply_vector(&self.translation);
        t.translation = back.map(|x| -x);
        t
    }

    pub fn translation_part(&self) -> Point {
        self.translation
    }

    /// The rotation matrix, row-major.
    pub fn rotation_part(&self) -> [[f64; MAX_AXES]; MAX_AXES] {
        self.rotation
    }

    /// Whether the transform keeps a path of `dims` axes in its first `dims` axes (no
    /// rotation or translation into the axes past it). A transform that does not cannot be
    /// applied to that group's segments.
    pub fn keeps(&self, dims: usize) -> bool {
        if check_dims(dims).is_err() {
            return false;
        }
        let rotation_ok = self.rotation.iter().enumerate().all(|(i, row)| {
            row.iter()
                .enumerate()
                .all(|(j, &x)| (i < dims) == (j < dims) || x == 0.0)
        });
        rotation_ok && self.translation.iter().skip(dims).all(|&x| x == 0.0)
    }

    /// Checks [`Transform::keeps`] with a typed error.
    pub fn check_keeps(&self, dims: usize) -> Result<(), GeometryError> {
        check_dims(dims)?;
        if self.keeps(dims) {
            Ok(())
        } else {
            Err(GeometryError::Invalid(
                "the transform moves the path into axes the group does not have",
            ))
        }
    }

    pub fn is_identity(&self) -> bool {
        *self == Transform::identity()
    }
}
