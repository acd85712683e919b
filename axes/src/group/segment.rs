//! Group motion commands → path segments and their limits (`path::geometry`,
//! `path::planner`). Everything a command carries is checked here, before anything is queued:
//! coordinate counts, finite numbers, positive limits, and the geometry's own refusals.

use path::geometry::{Arc, Curve, Line, Segment, Turn};
use path::planner::{Join, PathLimits, Transition};
use path::{Point, MAX_AXES};

use super::frames::FrameMap;
use crate::command::{
    bounded, nonnegative, positive, ArcDirection, CircleMode, CommandId, EngineError,
    GroupBufferMode, GroupId, MoveCircularAbsolute, MoveCircularRelative, MoveEllipse,
    MoveLinearAbsolute, MoveLinearRelative, MoveSpline, TransitionMode,
};

/// Where a motion goes, in group coordinates (checked, `dims` components used).
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Geometry {
    Linear {
        point: Point,
        relative: bool,
    },
    Circular {
        mode: CircleMode,
        aux: Point,
        radius: Option<f64>,
        end: Point,
        turn: Turn,
        plane: (usize, usize),
        normal: Option<[f64; 3]>,
        turns: u32,
        relative: bool,
    },
    /// Through `points` after the start (HMC MoveSplineND).
    Spline {
        points: Vec<Point>,
        relative: bool,
    },
    /// A full ellipse around `center` (NMC CrdEllipse).
    Ellipse {
        center: Point,
        ratio: f64,
        turn: Turn,
        plane: (usize, usize),
        relative: bool,
    },
}

/// A checked motion command, before it has a start point.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct PathRequest {
    pub geometry: Geometry,
    pub limits: PathLimits,
    pub join: Join,
    pub transition: Transition,
    pub aborting: bool,
    pub user_segment: u32,
    /// The positions' coordinate system, resolved when the command was accepted.
    pub frame: FrameMap,
}

/// An aborting motion accepted while the path was moving: it starts when the path is at rest.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct PendingMotion {
    pub id: CommandId,
    pub request: PathRequest,
}

/// The kinematic fields every group motion has.
pub(super) struct Kinematics {
    pub velocity: Option<f64>,
    pub acceleration: Option<f64>,
    pub deceleration: Option<f64>,
    pub jerk: Option<f64>,
}

/// The [`Kinematics`] of any group motion command (they all have these four fields).
macro_rules! kinematics {
    ($c:expr) => {
        Kinematics {
            velocity: $c.velocity,
            acceleration: $c.acceleration,
            deceleration: $c.deceleration,
            jerk: $c.jerk,
        }
    };
}

/// The path limits of a motion: its own, else the group's. `jerk = 0` is a trapezoid.
pub(super) fn path_limits(
    k: &Kinematics,
    defaults: &PathLimits,
) -> Result<PathLimits, EngineError> {
    let pick = |name: &'static str, v: Option<f64>, d: f64| match v {
        Some(v) => positive(name, bounded(name, v)?),
        None => Ok(d),
    };
    let jerk = match k.jerk {
        Some(j) => jerk_value(j)?,
        None => defaults.jerk,
    };
    Ok(PathLimits {
        velocity: pick("velocity", k.velocity, defaults.velocity)?,
        acceleration: pick("acceleration", k.acceleration, defaults.acceleration)?,
        deceleration: pick("deceleration", k.deceleration, defaults.deceleration)?,
        jerk,
    })
}

/// A jerk from a command or parameter: ≥ 0, and 0 means none (a trapezoid).
pub(super) fn jerk_value(j: f64) -> Result<f64, EngineError> {
    let j = nonnegative("jerk", j)?;
    Ok(if j == 0.0 { f64::INFINITY } else { j })
}

fn join_of(mode: GroupBufferMode) -> (Join, bool) {
    match mode {
        GroupBufferMode::Aborting => (Join::Buffered, true),
        GroupBufferMode::Buffered => (Join::Buffered, false),
        GroupBufferMode::BlendingLow => (Join::BlendingLow, false),
        GroupBufferMode::BlendingPrevious => (Join::BlendingPrevious, false),
        GroupBufferMode::BlendingNext => (Join::BlendingNext, false),
        GroupBufferMode::BlendingHigh => (Join::BlendingHigh, false),
    }
}

fn transition_of(t: TransitionMode) -> Result<Transition, EngineError> {
    let nonneg = |name: &'static str, v: f64| {
        let v = bounded(name, v)?;
        if v < 0.0 {
            Err(EngineError::InvalidArgument {
                name,
                value: v,
                reason: "must be ≥ 0",
            })
        } else {
            Ok(v)
        }
    };
    Ok(match t {
        TransitionMode::None => Transition::None,
        TransitionMode::CornerDistance(d) => {
            Transition::CornerDistance(nonneg("corner_distance", d)?)
        }
        TransitionMode::CornerDeviation(e) => {
            Transition::CornerDeviation(nonneg("corner_deviation", e)?)
        }
    })
}

/// `coords` as a point of a group of `dims` axes: one finite number per axis.
pub(super) fn coordinates(
    group: GroupId,
    name: &'static str,
    coords: &[f64],
    dims: usize,
) -> Result<Point, EngineError> {
    if coords.len() != dims {
        return Err(EngineError::InvalidPath {
            group,
            reason: format!(
                "{name} has {} coordinates; the group has {dims} axes",
                coords.len()
            ),
        });
    }
    let mut p = [0.0; MAX_AXES];
    for (out, &c) in p.iter_mut().zip(coords) {
        *out = bounded(name, c)?;
    }
    Ok(p)
}

fn request(
    geometry: Geometry,
    k: Kinematics,
    mode: GroupBufferMode,
    transition: TransitionMode,
    user_segment: Option<u32>,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    let (join, aborting) = join_of(mode);
    Ok(PathRequest {
        geometry,
        limits: path_limits(&k, defaults)?,
        join,
        transition: transition_of(transition)?,
        aborting,
        user_segment: user_segment.unwrap_or(0),
        frame: FrameMap::default(),
    })
}

pub(super) fn linear_absolute(
    group: GroupId,
    dims: usize,
    c: &MoveLinearAbsolute,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    let point = coordinates(group, "position", &c.position, dims)?;
    let mode = (c.buffer_mode, c.transition, c.user_segment);
    linear(point, false, kinematics!(c), mode, defaults)
}

pub(super) fn linear_relative(
    group: GroupId,
    dims: usize,
    c: &MoveLinearRelative,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    let point = coordinates(group, "distance", &c.distance, dims)?;
    let mode = (c.buffer_mode, c.transition, c.user_segment);
    linear(point, true, kinematics!(c), mode, defaults)
}

/// A line to `point` (from the start when `relative`), with its buffer mode, transition and
/// user segment.
fn linear(
    point: Point,
    relative: bool,
    k: Kinematics,
    (buffer_mode, transition, user_segment): (GroupBufferMode, TransitionMode, Option<u32>),
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    request(
        Geometry::Linear { point, relative },
        k,
        buffer_mode,
        transition,
        user_segment,
        defaults,
    )
}

/// The fields of both circular commands (absolute and relative differ only in `relative`).
pub(super) struct CircularFields<'a> {
    pub mode: CircleMode,
    pub aux_point: &'a [f64],
    pub radius: Option<f64>,
    pub end_point: &'a [f64],
    pub direction: ArcDirection,
    pub plane: Option<[usize; 2]>,
    pub normal: Option<&'a [f64]>,
    pub turns: u32,
    pub kinematics: Kinematics,
    pub buffer_mode: GroupBufferMode,
    pub transition: TransitionMode,
    pub user_segment: Option<u32>,
    pub relative: bool,
}

/// `CircularFields` from either circular command: they differ only in `relative`.
macro_rules! circular_fields {
    ($command:ident, $relative:expr) => {
        impl<'a> From<&'a $command> for CircularFields<'a> {
            fn from(c: &'a $command) -> Self {
                CircularFields {
                    mode: c.mode,
                    aux_point: &c.aux_point,
                    radius: c.radius,
                    end_point: &c.end_point,
                    direction: c.direction,
                    plane: c.plane,
                    normal: c.normal.as_deref(),
                    turns: c.turns,
                    kinematics: kinematics!(c),
                    buffer_mode: c.buffer_mode,
                    transition: c.transition,
                    user_segment: c.user_segment,
                    relative: $relative,
                }
            }
        }
    };
}

circular_fields!(MoveCircularAbsolute, false);
circular_fields!(MoveCircularRelative, true);

pub(super) fn circular(
    group: GroupId,
    dims: usize,
    c: CircularFields,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    let invalid = |reason: String| EngineError::InvalidPath { group, reason };
    let end = coordinates(group, "end_point", c.end_point, dims)?;
    let aux = match c.mode {
        CircleMode::Radius if c.aux_point.is_empty() => [0.0; MAX_AXES],
        _ => coordinates(group, "aux_point", c.aux_point, dims)?,
    };
    let radius = match (c.mode, c.radius) {
        (CircleMode::Radius, Some(r)) => Some(bounded("radius", r)?),
        (CircleMode::Radius, None) => {
            return Err(invalid("mode \"radius\" needs a radius".into()));
        }
        (_, Some(_)) => {
            return Err(invalid(
                "a radius is given only with mode \"radius\"".into(),
            ))
        }
        (_, None) => None,
    };
    let (i, j) = plane_of(group, c.plane, dims)?;
    let normal = match c.normal {
        None => None,
        Some(n) => {
            if c.plane.is_some() {
                return Err(invalid("give a plane or a normal, not both".into()));
            }
            if c.mode != CircleMode::Center {
                return Err(invalid(
                    "a normal is given only with mode \"center\"".into(),
                ));
            }
            if dims < 3 {
                return Err(invalid(format!(
                    "a normal needs 3 coordinates; the group has {dims}"
                )));
            }
            let [x, y, z] = n else {
                return Err(invalid(format!(
                    "normal has {} components; it needs 3",
                    n.len()
                )));
            };
            Some([
                bounded("normal", *x)?,
                bounded("normal", *y)?,
                bounded("normal", *z)?,
            ])
        }
    };
    if c.turns > 0 && c.mode != CircleMode::Center {
        return Err(invalid(
            "extra turns are given only with mode \"center\"".into(),
        ));
    }
    request(
        Geometry::Circular {
            mode: c.mode,
            aux,
            radius,
            end,
            turn: match c.direction {
                ArcDirection::Ccw => Turn::Ccw,
                ArcDirection::Cw => Turn::Cw,
            },
            plane: (i, j),
            normal,
            turns: c.turns,
            relative: c.relative,
        },
        c.kinematics,
        c.buffer_mode,
        c.transition,
        c.user_segment,
        defaults,
    )
}

/// The plane of a circular or elliptic command: two different group coordinates, `[0, 1]`
/// when none is given.
fn plane_of(
    group: GroupId,
    plane: Option<[usize; 2]>,
    dims: usize,
) -> Result<(usize, usize), EngineError> {
    let [i, j] = plane.unwrap_or([0, 1]);
    if i == j || i >= dims || j >= dims {
        return Err(EngineError::InvalidPath {
            group,
            reason: format!(
                "plane [{i}, {j}] needs two different coordinates of the group's {dims}"
            ),
        });
    }
    Ok((i, j))
}

/// Most points one `move_spline` carries: the curve's length table is built when the command is
/// applied, on the servo thread, so the bound keeps that work bounded.
pub(super) const MAX_SPLINE_COMMAND_POINTS: usize = 1000;

pub(super) fn spline(
    group: GroupId,
    dims: usize,
    c: &MoveSpline,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    if c.points.is_empty() || c.points.len() > MAX_SPLINE_COMMAND_POINTS {
        return Err(EngineError::InvalidPath {
            group,
            reason: format!(
                "a spline has 1 to {MAX_SPLINE_COMMAND_POINTS} points, not {}",
                c.points.len()
            ),
        });
    }
    let points = c
        .points
        .iter()
        .map(|p| coordinates(group, "points", p, dims))
        .collect::<Result<Vec<_>, _>>()?;
    request(
        Geometry::Spline {
            points,
            relative: c.relative,
        },
        kinematics!(c),
        c.buffer_mode,
        c.transition,
        c.user_segment,
        defaults,
    )
}

pub(super) fn ellipse(
    group: GroupId,
    dims: usize,
    c: &MoveEllipse,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    let center = coordinates(group, "center", &c.center, dims)?;
    let (i, j) = plane_of(group, c.plane, dims)?;
    request(
        Geometry::Ellipse {
            center,
            ratio: bounded("ratio", c.ratio)?,
            turn: match c.direction {
                ArcDirection::Ccw => Turn::Ccw,
                ArcDirection::Cw => Turn::Cw,
            },
            plane: (i, j),
            relative: c.relative,
        },
        kinematics!(c),
        c.buffer_mode,
        c.transition,
        c.user_segment,
        defaults,
    )
}

impl PathRequest {
    /// The segment from `start` (group coordinates): built in the command's coordinate system
    /// from `start` seen there, then taken to group coordinates ([`FrameMap::segment_to_machine`]).
    /// The geometry's refusals (centre not equidistant, radius below half the chord,
    /// coincident points …) become `InvalidPath` with the geometry's reason.
    pub fn segment(
        &self,
        group: GroupId,
        machine_start: Point,
        dims: usize,
    ) -> Result<Segment, EngineError> {
        let start = self.frame.point_from_machine(&machine_start);
        let built = self.segment_in_frame(group, start, dims)?;
        self.frame
            .segment_to_machine(group, machine_start, built, dims)
    }

    /// The segment from `start`, all in the command's coordinate system.
    fn segment_in_frame(
        &self,
        group: GroupId,
        start: Point,
        dims: usize,
    ) -> Result<Segment, EngineError> {
        let offset = |p: &Point, relative: bool| -> Point {
            if relative {
                let mut out = *p;
                for (o, s) in out.iter_mut().zip(&start) {
                    *o += s;
                }
                out
            } else {
                *p
            }
        };
        let built = match &self.geometry {
            Geometry::Linear { point, relative } => {
                Line::new(start, offset(point, *relative), dims).map(Segment::Line)
            }
            Geometry::Circular {
                mode,
                aux,
                radius,
                end,
                turn,
                plane,
                normal,
                turns,
                relative,
            } => {
                let end = offset(end, *relative);
                let aux = offset(aux, *relative);
                match (mode, normal) {
                    (CircleMode::Center, None) => {
                        Arc::from_center(start, end, aux, *plane, *turn, *turns, dims)
                            .map(Segment::Arc)
                    }
                    (CircleMode::Center, Some(n)) => {
                        Arc::from_center_normal(start, end, aux, *n, *turn, *turns, [0, 1, 2], dims)
                            .map(Segment::Arc)
                    }
                    (CircleMode::Radius, _) => {
                        Arc::from_radius(start, end, radius.unwrap_or(0.0), *plane, *turn, dims)
                            .map(Segment::Arc)
                    }
                    (CircleMode::Border, _) => Segment::through_points(start, aux, end, dims),
                }
            }
            Geometry::Spline { points, relative } => {
                let mut nodes = Vec::with_capacity(points.len() + 1);
                nodes.push(start);
                nodes.extend(points.iter().map(|p| offset(p, *relative)));
                Curve::spline(&nodes, dims)
            }
            Geometry::Ellipse {
                center,
                ratio,
                turn,
                plane,
                relative,
            } => Curve::ellipse(
                start,
                offset(center, *relative),
                *ratio,
                *plane,
                *turn,
                dims,
            ),
        };
        built.map_err(|e| EngineError::InvalidPath {
            group,
            reason: e.to_string(),
        })
    }
}
