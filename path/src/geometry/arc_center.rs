//! Arcs by centre and end point, in an axis plane or about a 3-D normal, with the vendors'
//! ways of counting turns: a direction plus extra turns (NMC `ArcCenterEx`/`HelixCenterEx`,
//! HMC `MoveCircle`/`MoveHelical`) or HIMC's signed `turns` (`Circle2D`, `CircleAbs`).

use std::f64::consts::TAU;

use super::{
    add, check_axis, check_dims, check_finite, check_number, check_planar, dot, scale, sub, Arc,
    GeometryError, Turn, POINT_TOLERANCE,
};
use super::{radius_tolerance, MIN_SWEEP};
use crate::{Point, MAX_AXES};

/// The unit vectors of axes `plane.0` and `plane.1`: counter-clockwise turns from the first
/// toward the second.
pub(crate) fn plane_basis(plane: (usize, usize)) -> (Point, Point) {
    let mut e1 = [0.0; MAX_AXES];
    let mut e2 = [0.0; MAX_AXES];
    if let Some(x) = e1.get_mut(plane.0) {
        *x = 1.0;
    }
    if let Some(y) = e2.get_mut(plane.1) {
        *y = 1.0;
    }
    (e1, e2)
}

/// `center` moved into the plane through `start` spanned by `e1`, `e2` (orthonormal): start's
/// coordinates plus the centre's in-plane offset. An axis-plane centre keeps its own in-plane
/// coordinates; a 3-D centre off that plane is projected along the normal.
pub(crate) fn in_plane_of(start: &Point, center: &Point, e1: &Point, e2: &Point) -> Point {
    let d = sub(center, start);
    add(
        start,
        &add(&scale(e1, dot(&d, e1)), &scale(e2, dot(&d, e2))),
    )
}

/// The sweep of an arc turning `turn` that ends `theta` radians counter-clockwise from its
/// start (in `[0, 2π)`), after `extra_turns` more turns; a closed arc (end = start) or a
/// sweep lost to rounding is a full turn (NMC `ArcCenterEx` with target = start, TV 43).
pub(crate) fn sweep_for(turn: Turn, extra_turns: u32, theta: f64, closed: bool) -> f64 {
    let mut sweep = match turn {
        Turn::Ccw => theta,
        Turn::Cw => (TAU - theta).rem_euclid(TAU),
    };
    if closed || sweep < MIN_SWEEP || TAU - sweep < MIN_SWEEP {
        sweep = TAU;
    }
    sweep + TAU * f64::from(extra_turns)
}

/// HIMC's `turns` (digest 004 §2.7, `Circle2D` §8.2.17, `CircleAbs` §8.5.3): with θ the
/// counter-clockwise angle from start to end, the signed angle is θ for turns 0 and 1,
/// θ + (turns − 1)·2π for turns ≥ 2 and θ + turns·2π for turns < 0 (the manual's table for
/// θ = 210°: −2 → −510°, −1 → −150°, 0 and 1 → 210°, 2 → 570°). Start = end is θ = 0, so
/// turns 0 and 1 give no motion (refused, as HIMC's "central angle too small") and turns 2
/// is one full turn.
pub fn himc_turns_angle(theta: f64, turns: i32) -> f64 {
    let k = match turns {
        t if t >= 1 => f64::from(t - 1),
        0 => 0.0,
        t => f64::from(t),
    };
    theta + k * TAU
}

impl Arc {
    /// The arc around `center` (in start's plane, orthonormal `e1`, `e2` with
    /// counter-clockwise from `e1` toward `e2`) from `start` to `end`, where `choose` turns the
    /// counter-clockwise angle θ ∈ [0, 2π) of the end and whether the arc is closed into the
    /// direction and sweep. The components of `end − start` off the plane move linearly.
    pub(crate) fn around(
        start: Point,
        end: Point,
        center: Point,
        e1: Point,
        e2: Point,
        dims: usize,
        choose: impl FnOnce(f64, bool) -> Result<(Turn, f64), GeometryError>,
    ) -> Result<Arc, GeometryError> {
        let d = sub(&start, &center);
        let (a, b) = (dot(&d, &e1), dot(&d, &e2));
        let radius = a.hypot(b);
        if radius <= POINT_TOLERANCE {
            return Err(GeometryError::Invalid(
                "the arc's centre is its start point",
            ));
        }
        let f = sub(&end, &center);
        let (fa, fb) = (dot(&f, &e1), dot(&f, &e2));
        if (radius - fa.hypot(fb)).abs() > radius_tolerance(radius) {
            return Err(GeometryError::Invalid(
                "the arc's centre is not equidistant from its start and end",
            ));
        }
        let u = add(&scale(&e1, a / radius), &scale(&e2, b / radius));
        let w = add(&scale(&e1, -b / radius), &scale(&e2, a / radius));
        let theta = dot(&f, &w).atan2(dot(&f, &u)).rem_euclid(TAU);
        let closed = (fa - a).hypot(fb - b) <= POINT_TOLERANCE;
        let (turn, sweep) = choose(theta, closed)?;
        if !sweep.is_finite() || sweep < MIN_SWEEP {
            return Err(GeometryError::Invalid("the arc's angle is 0"));
        }
        let v = scale(&w, turn.sign());
        let delta = sub(&end, &start);
        let h = sub(
            &delta,
            &add(&scale(&e1, dot(&delta, &e1)), &scale(&e2, dot(&delta, &e2))),
        );
        Ok(Arc::from_parts(center, u, v, radius, sweep, h, end, dims))
    }

    /// [`Arc::around`] in the axis plane `plane`, after checking the input.
    pub(crate) fn around_in_plane(
        start: Point,
        end: Point,
        center: Point,
        plane: (usize, usize),
        dims: usize,
        choose: impl FnOnce(f64, bool) -> Result<(Turn, f64), GeometryError>,
    ) -> Result<Arc, GeometryError> {
        check_planar(
            plane,
            dims,
            &[("start", &start), ("end", &end), ("center", &center)],
        )?;
        let (e1, e2) = plane_basis(plane);
        let c = in_plane_of(&start, &center, &e1, &e2);
        Arc::around(start, end, c, e1, e2, dims, choose)
    }

    /// [`Arc::around`] in the plane ⟂ `normal` through `start` (axes `axes`), after checking
    /// the input.
    pub(crate) fn around_normal(
        start: Point,
        end: Point,
        center: Point,
        normal: [f64; 3],
        axes: [usize; 3],
        dims: usize,
        choose: impl FnOnce(f64, bool) -> Result<(Turn, f64), GeometryError>,
    ) -> Result<Arc, GeometryError> {
        let (e1, e2) = normal_basis(&start, &end, &center, normal, axes, dims)?;
        let c = in_plane_of(&start, &center, &e1, &e2);
        Arc::around(start, end, c, e1, e2, dims, choose)
    }

    /// HIMC `Circle2D` (digest 004 §2.7, §8.2.17, TV 45): the arc about `center` from `start`
    /// to `end` in `plane`, with the signed `turns` of [`himc_turns_angle`] (≥ 0
    /// counter-clockwise, < 0 clockwise). The other axes move linearly.
    pub fn from_center_turns(
        start: Point,
        end: Point,
        center: Point,
        plane: (usize, usize),
        turns: i32,
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        Arc::around_in_plane(start, end, center, plane, dims, |theta, closed| {
            himc_choice(if closed { 0.0 } else { theta }, turns)
        })
    }

    /// The arc about the axis through `center` along `normal` from `start` to `end`, in the
    /// space of path axes `axes` (x, y, z), turning `turn` about the normal (right-hand rule:
    /// counter-clockwise seen from its tip) plus `extra_turns` full turns; end = start is a
    /// full turn. `end`'s offset along the normal, and the other axes, move linearly (a helix:
    /// HIMC `CircleAbs` with target Z ≠ start Z). The centre is projected along the normal into
    /// start's plane; `end` must be at the radius from the axis.
    #[allow(clippy::too_many_arguments)]
    pub fn from_center_normal(
        start: Point,
        end: Point,
        center: Point,
        normal: [f64; 3],
        turn: Turn,
        extra_turns: u32,
        axes: [usize; 3],
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        Arc::around_normal(start, end, center, normal, axes, dims, |theta, closed| {
            Ok((turn, sweep_for(turn, extra_turns, theta, closed)))
        })
    }

    /// A helix (NMC `HelixCenterEx` `rounds`, HMC `MoveHelical`, digest 001 §4.4, 000 §4.3):
    /// [`Arc::from_center`] over `turns` ≥ 1 turns begun, i.e. the arc to the end's angle
    /// (a full turn when end = start in the plane) plus `turns − 1` full turns, while the
    /// other axes move linearly from start to end. NMC TV 46: end = start in XY, 5 turns.
    pub fn helix_turns(
        start: Point,
        end: Point,
        center: Point,
        plane: (usize, usize),
        turn: Turn,
        turns: u32,
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        let Some(extra) = turns.checked_sub(1) else {
            return Err(GeometryError::Invalid("a helix needs at least 1 turn"));
        };
        Arc::from_center(start, end, center, plane, turn, extra, dims)
    }

    /// HMC `MoveCircle` modes 1 and 3 (digest 000 §4.3): the arc about `center` from `start`
    /// toward `toward`, which need not be on the circle: the end is where the ray from the
    /// centre through `toward` meets the circle, and `toward` = start is a full circle (HMC
    /// TV 14). `toward` at the centre is refused (no ray). The other axes move linearly to
    /// `toward`'s.
    pub fn from_center_toward(
        start: Point,
        toward: Point,
        center: Point,
        plane: (usize, usize),
        turn: Turn,
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        check_planar(
            plane,
            dims,
            &[("start", &start), ("end", &toward), ("center", &center)],
        )?;
        let (i, j) = plane;
        let radius = (start[i] - center[i]).hypot(start[j] - center[j]);
        let (dx, dy) = (toward[i] - center[i], toward[j] - center[j]);
        let reach = dx.hypot(dy);
        if reach <= POINT_TOLERANCE {
            return Err(GeometryError::Invalid(
                "the arc's end direction is its centre: no ray from the centre through it",
            ));
        }
        let mut end = toward;
        end[i] = center[i] + dx * radius / reach;
        end[j] = center[j] + dy * radius / reach;
        if (start[i] - end[i]).hypot(start[j] - end[j]) <= POINT_TOLERANCE {
            end[i] = start[i];
            end[j] = start[j];
        }
        Arc::from_center(start, end, center, plane, turn, 0, dims)
    }

    /// HIMC `CircleAbs`/`CircleRel` (digest 004 §2.7, §8.5.3): [`Arc::from_center_normal`]
    /// with HIMC's signed `turns` ([`himc_turns_angle`], θ counted about the normal).
    #[allow(clippy::too_many_arguments)]
    pub fn from_center_normal_turns(
        start: Point,
        end: Point,
        center: Point,
        normal: [f64; 3],
        turns: i32,
        axes: [usize; 3],
        dims: usize,
    ) -> Result<Arc, GeometryError> {
        Arc::around_normal(start, end, center, normal, axes, dims, |theta, closed| {
            himc_choice(if closed { 0.0 } else { theta }, turns)
        })
    }
}

fn himc_choice(theta: f64, turns: i32) -> Result<(Turn, f64), GeometryError> {
    let angle = himc_turns_angle(theta, turns);
    if angle.abs() < MIN_SWEEP {
        return Err(GeometryError::Invalid(
            "the arc's angle is 0 (HIMC turns 0 or 1 with end = start: use turns 2 for a full circle)",
        ));
    }
    Ok((Turn::of_angle(angle), angle.abs()))
}

/// Checks the inputs of a 3-D arc and returns an orthonormal pair (e1, e2) of the plane ⟂
/// `normal`, embedded in the path's axes, with e1 × e2 = normal.
pub(crate) fn normal_basis(
    start: &Point,
    end: &Point,
    center: &Point,
    normal: [f64; 3],
    axes: [usize; 3],
    dims: usize,
) -> Result<(Point, Point), GeometryError> {
    check_dims(dims)?;
    for &a in &axes {
        check_axis(a, dims)?;
    }
    if axes[0] == axes[1] || axes[1] == axes[2] || axes[0] == axes[2] {
        return Err(GeometryError::Invalid(
            "a 3-D arc needs three different axes of the group",
        ));
    }
    for (name, p) in [("start", start), ("end", end), ("center", center)] {
        check_finite(name, p)?;
    }
    let n = unit_normal(normal)?;
    // e1 ⟂ n from the coordinate axis least aligned with n; e2 = n × e1.
    let k = (0..3)
        .min_by(|&x, &y| n[x].abs().total_cmp(&n[y].abs()))
        .unwrap_or(0);
    let mut axis = [0.0; 3];
    axis[k] = 1.0;
    let e1 = normalized3(cross(n, axis));
    let e2 = cross(n, e1);
    let mut out1 = [0.0; MAX_AXES];
    let mut out2 = [0.0; MAX_AXES];
    for (c, &a) in axes.iter().enumerate() {
        out1[a] = e1[c];
        out2[a] = e2[c];
    }
    Ok((out1, out2))
}

/// `normal` scaled to length 1; a zero (or subnormal, or non-finite) vector is refused.
pub(crate) fn unit_normal(normal: [f64; 3]) -> Result<[f64; 3], GeometryError> {
    for &c in &normal {
        check_number("normal", c)?;
    }
    let len = normal[0].hypot(normal[1]).hypot(normal[2]);
    if len <= f64::MIN_POSITIVE.sqrt() || !len.is_finite() {
        return Err(GeometryError::Invalid("the arc's normal vector is 0"));
    }
    Ok(normal.map(|c| c / len))
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalized3(a: [f64; 3]) -> [f64; 3] {
    let len = a[0].hypot(a[1]).hypot(a[2]);
    if len > 0.0 {
        a.map(|c| c / len)
    } else {
        a
    }
}
