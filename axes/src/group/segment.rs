//! Group motion commands → path segments and their limits (`path::geometry`,
//! `path::planner`). Everything a command carries is checked here, before anything is queued:
//! coordinate counts, finite numbers, positive limits, and the geometry's own refusals.

use path::geometry::{add, Arc, Curve, GeometryError, Line, Segment, SplineBuild, Turn};
use path::planner::{Join, PathLimits, Transition};
use path::{Point, MAX_AXES};

use super::frames::FrameMap;
use crate::command::{
    bounded, finite, nonnegative, positive, ArcDirection, CircleMode, CommandId, CoordinateSet,
    EngineError, GroupBufferMode, GroupId, MoveCircularAbsolute, MoveCircularAngle,
    MoveCircularRelative, MoveEllipse, MoveLinearAbsolute, MoveLinearRelative, MoveSpline,
    TransitionMode,
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
    /// An arc about `center` through `angle` radians (HIMC ArcAngle2D).
    CenterAngle {
        center: Point,
        angle: f64,
        plane: (usize, usize),
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
    /// The group coordinates that count in the path length (all but the motion's
    /// `independent` ones).
    pub counted: Counted,
    /// The group's orientation coordinates and their angular profile (HIMC
    /// SetGrpAngMotionProfile), set by the group when it takes the motion.
    pub angular: Option<AngularProfile>,
    /// The motion gives its own velocity (else the group's default, live with a result axis).
    pub velocity_given: bool,
}

/// HIMC's angular TCP profile (digest 004 §8.3.7): the orientation coordinates of a group
/// (A, B, C) and the limits their change is held to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct AngularProfile {
    pub coordinates: Counted,
    pub limits: PathLimits,
}

/// What a motion's segment gives the planner and the group: the counted share of its length
/// (the result axis's travel, stops over the counted coordinates) and its limits along the
/// path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Share {
    pub ratio: f64,
    pub limits: PathLimits,
}

/// Which group coordinates count in a motion's path length: its velocity, acceleration,
/// deceleration and jerk are measured over them, and the result axis travels their length
/// (HMC MoveND: `ucLineNum` path axes and `ucSelfNum` independent axes; HMC_MoveHelical modes
/// 4/5/7: the arc plane only; digest 000 §4.3, TV 17, TV 19).
pub(super) type Counted = [bool; MAX_AXES];

/// Every coordinate counts (no independent coordinates).
pub(super) const ALL_COUNTED: Counted = [true; MAX_AXES];

/// The counted coordinates of a motion of a group of `dims` axes whose `independent` group
/// coordinates do not count: each index names a coordinate, and one at least must count.
pub(super) fn counted_coordinates(
    group: GroupId,
    independent: CoordinateSet,
    dims: usize,
) -> Result<Counted, EngineError> {
    let mut counted = ALL_COUNTED;
    for k in independent.iter() {
        match counted.get_mut(k).filter(|_| k < dims) {
            Some(c) => *c = false,
            None => {
                return Err(EngineError::InvalidPath {
                    group,
                    reason: format!("independent coordinate {k} is not one of the group's {dims}"),
                })
            }
        }
    }
    if counted.iter().take(dims).all(|c| !c) {
        return Err(EngineError::InvalidPath {
            group,
            reason: "every coordinate is independent: none is left to measure the path by".into(),
        });
    }
    Ok(counted)
}

/// Largest component, relative to the radius, that an arc's plane may have on coordinates on
/// the other side of the counted/independent split and still be taken as lying on one side.
const PLANE_SPLIT_TOLERANCE: f64 = 1e-9;

/// The share of `segment`'s length that its `counted` coordinates make: counted length /
/// length, in (0, 1]. Exact along the whole segment for lines and for arcs whose plane lies
/// within the counted coordinates or within the independent ones (both grow in proportion to
/// the path length); an arc whose plane straddles the split, and splines and ellipses with
/// independent coordinates, are refused (their counted length is not proportional).
pub(super) fn length_ratio(
    group: GroupId,
    segment: &Segment,
    counted: &Counted,
) -> Result<f64, EngineError> {
    let ratio = counted_share(group, segment, counted)?;
    if !(ratio > 0.0 && ratio.is_finite()) {
        return Err(EngineError::InvalidPath {
            group,
            reason: "the counted coordinates do not move: the path length would be 0".into(),
        });
    }
    Ok(ratio)
}

/// [`length_ratio`], 0 allowed (the counted coordinates stand still). Where every other
/// coordinate stands still the whole length counts, whatever the segment.
fn counted_share(group: GroupId, segment: &Segment, counted: &Counted) -> Result<f64, EngineError> {
    let dims = segment.dims();
    let others_still = counted
        .iter()
        .take(dims)
        .enumerate()
        .all(|(k, &c)| c || segment.max_tangent(k) == 0.0);
    if others_still {
        return Ok(1.0);
    }
    let invalid = |reason: &str| EngineError::InvalidPath {
        group,
        reason: reason.to_string(),
    };
    let length = segment.length();
    if length <= 0.0 {
        return Ok(1.0);
    }
    // The part of a vector on the counted coordinates.
    let counted_norm = |v: &Point| -> f64 {
        v.iter()
            .zip(counted)
            .filter(|(_, &c)| c)
            .map(|(x, _)| x * x)
            .sum::<f64>()
            .sqrt()
    };
    let part = match segment {
        Segment::Line(l) => {
            let mut d = l.end();
            for (x, s) in d.iter_mut().zip(&l.start()) {
                *x -= s;
            }
            counted_norm(&d)
        }
        Segment::Arc(a) => {
            let (u, v) = a.basis();
            let (u_in, v_in) = (counted_norm(&u), counted_norm(&v));
            let circle = a.radius() * a.sweep();
            let in_plane =
                if u_in >= 1.0 - PLANE_SPLIT_TOLERANCE && v_in >= 1.0 - PLANE_SPLIT_TOLERANCE {
                    circle
                } else if u_in <= PLANE_SPLIT_TOLERANCE && v_in <= PLANE_SPLIT_TOLERANCE {
                    0.0
                } else {
                    return Err(invalid(
                        "the arc's plane has counted and independent coordinates: give both or \
                     neither of its plane coordinates as independent",
                    ));
                };
            in_plane.hypot(counted_norm(&a.helix()))
        }
        Segment::Curve(c) => {
            return c.counted_share(counted).ok_or_else(|| {
                invalid(
                    "a curve's shape must lie in its counted coordinates: independent and \
                     orientation coordinates move along a curve only in proportion (a spline's \
                     independent coordinates)",
                )
            })
        }
    };
    let ratio = part / length;
    Ok(if ratio.is_finite() {
        ratio.min(1.0)
    } else {
        0.0
    })
}

/// The spline through `nodes` whose coordinates that are not `counted` move in proportion
/// along it: the shape goes through the nodes' counted coordinates (the others held at the
/// start's), and the rest rise from the start to the last node's values in proportion to the
/// length along the shape (`Curve::lifted`), as they would along a line or an arc (HMC
/// MoveSplineND with independent axes, NMC D8). Built in steps ([`SplineBuild`]).
#[derive(Clone, Debug)]
pub(super) struct CountedSpline {
    build: SplineBuild,
    /// The independent coordinates' rise, if the motion has any.
    rise: Option<Point>,
    dims: usize,
}

impl CountedSpline {
    fn new(
        nodes: &[Point],
        counted: &Counted,
        dims: usize,
    ) -> Result<CountedSpline, GeometryError> {
        let independent = |k: usize| k < dims && !counted.get(k).copied().unwrap_or(true);
        let (Some(first), Some(last)) = (nodes.first().copied(), nodes.last().copied()) else {
            return Ok(CountedSpline {
                build: SplineBuild::new(nodes, dims)?,
                rise: None,
                dims,
            });
        };
        if !(0..dims).any(independent) {
            return Ok(CountedSpline {
                build: SplineBuild::new(nodes, dims)?,
                rise: None,
                dims,
            });
        }
        let mut rise = [0.0; MAX_AXES];
        let mut shape = nodes.to_vec();
        for k in (0..dims).filter(|&k| independent(k)) {
            if let (Some(r), Some(a), Some(b)) = (rise.get_mut(k), first.get(k), last.get(k)) {
                *r = b - a;
            }
            for n in &mut shape {
                if let (Some(x), Some(a)) = (n.get_mut(k), first.get(k)) {
                    *x = *a;
                }
            }
        }
        Ok(CountedSpline {
            build: SplineBuild::new(&shape, dims)?,
            rise: Some(rise),
            dims,
        })
    }

    /// Visit up to `spans` more spans; returns how many were visited and whether none is left.
    pub fn advance(&mut self, spans: usize) -> (usize, bool) {
        let before = self.build.remaining();
        let done = self.build.advance(spans);
        (before - self.build.remaining(), done)
    }

    fn finish(self) -> Result<Segment, GeometryError> {
        let segment = self.build.finish()?;
        let Some(rise) = self.rise else {
            return Ok(segment);
        };
        match segment {
            Segment::Curve(c) => c.lifted(&rise).map(Segment::Curve),
            // Nodes on one line: the line with the rise is exactly proportional too.
            Segment::Line(l) => {
                Line::new(l.start(), add(&l.end(), &rise), self.dims).map(Segment::Line)
            }
            other => Ok(other),
        }
    }
}

/// A motion's segment from its start: built, or (a spline) still to construct.
pub(super) enum Construction {
    Done(Segment, Share),
    Spline(StagedSpline),
}

/// A spline under construction and the queue end it starts from.
#[derive(Clone, Debug)]
pub(super) struct StagedSpline {
    pub spline: CountedSpline,
    machine_start: Point,
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
    counted: Counted,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    let (join, aborting) = join_of(mode);
    Ok(PathRequest {
        geometry,
        limits: path_limits(&k, defaults)?,
        velocity_given: k.velocity.is_some(),
        join,
        transition: transition_of(transition)?,
        aborting,
        user_segment: user_segment.unwrap_or(0),
        counted,
        angular: None,
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
    let counted = counted_coordinates(group, c.independent, dims)?;
    linear(point, false, kinematics!(c), mode, counted, defaults)
}

pub(super) fn linear_relative(
    group: GroupId,
    dims: usize,
    c: &MoveLinearRelative,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    let point = coordinates(group, "distance", &c.distance, dims)?;
    let mode = (c.buffer_mode, c.transition, c.user_segment);
    let counted = counted_coordinates(group, c.independent, dims)?;
    linear(point, true, kinematics!(c), mode, counted, defaults)
}

/// A line to `point` (from the start when `relative`), with its buffer mode, transition and
/// user segment.
fn linear(
    point: Point,
    relative: bool,
    k: Kinematics,
    (buffer_mode, transition, user_segment): (GroupBufferMode, TransitionMode, Option<u32>),
    counted: Counted,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    request(
        Geometry::Linear { point, relative },
        k,
        buffer_mode,
        transition,
        user_segment,
        counted,
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
    pub independent: CoordinateSet,
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
                    independent: c.independent,
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
    let counted = counted_coordinates(group, c.independent, dims)?;
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
        counted,
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

/// Most points one `move_spline` carries (HMC: 1000 nodes). The curve is constructed when the
/// command is applied, on the servo thread: its lengths and bounds, about 50 evaluations per
/// point; its table rows are built span by span as the path reaches them (path::geometry's
/// curve module), so the bound keeps the accepting tick's work bounded.
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
    let counted = counted_coordinates(group, c.independent, dims)?;
    request(
        Geometry::Spline {
            points,
            relative: c.relative,
        },
        kinematics!(c),
        c.buffer_mode,
        c.transition,
        c.user_segment,
        counted,
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
        ALL_COUNTED,
        defaults,
    )
}

pub(super) fn circular_angle(
    group: GroupId,
    dims: usize,
    c: &MoveCircularAngle,
    defaults: &PathLimits,
) -> Result<PathRequest, EngineError> {
    let center = coordinates(group, "center", &c.center, dims)?;
    let (i, j) = plane_of(group, c.plane, dims)?;
    let degrees = finite("angle", c.angle)?;
    // HIMC gives no bound; a million degrees (2 778 turns) keeps the path length finite and
    // sane.
    if degrees.abs() > MAX_ANGLE_DEGREES {
        return Err(EngineError::InvalidArgument {
            name: "angle",
            value: degrees,
            reason: "must be within ±1e6 degrees",
        });
    }
    request(
        Geometry::CenterAngle {
            center,
            angle: degrees.to_radians(),
            plane: (i, j),
            relative: c.relative,
        },
        kinematics!(c),
        c.buffer_mode,
        c.transition,
        c.user_segment,
        ALL_COUNTED,
        defaults,
    )
}

/// `limits` over coordinates that make `ratio` of the path length, along the whole path.
fn along_path(limits: &PathLimits, ratio: f64) -> PathLimits {
    PathLimits {
        velocity: limits.velocity / ratio,
        acceleration: limits.acceleration / ratio,
        deceleration: limits.deceleration / ratio,
        jerk: limits.jerk / ratio,
    }
}

/// The smaller of each limit.
fn smaller(a: &PathLimits, b: &PathLimits) -> PathLimits {
    PathLimits {
        velocity: a.velocity.min(b.velocity),
        acceleration: a.acceleration.min(b.acceleration),
        deceleration: a.deceleration.min(b.deceleration),
        jerk: a.jerk.min(b.jerk),
    }
}

/// Largest |angle| of `move_circular_angle`, in degrees.
const MAX_ANGLE_DEGREES: f64 = 1e6;

impl PathRequest {
    /// The path limits the planner gets for a motion whose counted length is `length_ratio` of
    /// its path length: the motion's limits hold over the counted coordinates, so along the
    /// whole path they are larger by 1 / ratio (HMC MoveND: `Speed(i) = L(i)/D · Speed`, D over
    /// the path axes only). The members' own limits still cap the path.
    pub fn limits_along_path(&self, length_ratio: f64) -> PathLimits {
        along_path(&self.limits, length_ratio)
    }

    /// The segment from `start` (group coordinates) and its counted length per path length
    /// ([`length_ratio`]): built in the command's coordinate system from `start` seen there,
    /// then taken to group coordinates ([`FrameMap::segment_to_machine`]). The geometry's
    /// refusals (centre not equidistant, radius below half the chord,
    /// coincident points …) become `InvalidPath` with the geometry's reason.
    ///
    /// A spline's construction is only begun here (its checks and coefficients):
    /// [`PathRequest::finish`] ends it, after `StagedSpline::spline` has been advanced as far
    /// as wanted (`staging`).
    pub fn begin(
        &self,
        group: GroupId,
        machine_start: Point,
        dims: usize,
    ) -> Result<Construction, EngineError> {
        let start = self.frame.point_from_machine(&machine_start);
        if let Geometry::Spline { points, relative } = &self.geometry {
            let spline = self
                .counted_spline(start, points, *relative, dims)
                .map_err(|e| invalid_path(group, e))?;
            return Ok(Construction::Spline(StagedSpline {
                spline,
                machine_start,
            }));
        }
        let built = self.segment_in_frame(group, start, dims)?;
        let (segment, share) = self.to_machine(group, machine_start, built, dims)?;
        Ok(Construction::Done(segment, share))
    }

    /// The segment of a spline begun by [`PathRequest::begin`] (what is left of its
    /// construction done now), or the geometry's refusal (a cusp).
    pub fn finish(
        &self,
        group: GroupId,
        staged: StagedSpline,
        dims: usize,
    ) -> Result<(Segment, Share), EngineError> {
        let built = staged.spline.finish().map_err(|e| invalid_path(group, e))?;
        self.to_machine(group, staged.machine_start, built, dims)
    }

    /// A segment built in the command's coordinate system, taken to group coordinates
    /// ([`FrameMap::segment_to_machine`]), with its counted share.
    fn to_machine(
        &self,
        group: GroupId,
        machine_start: Point,
        built: Segment,
        dims: usize,
    ) -> Result<(Segment, Share), EngineError> {
        let segment = self
            .frame
            .segment_to_machine(group, machine_start, built, dims)?;
        let share = self.share(group, &segment)?;
        Ok((segment, share))
    }

    /// The spline through the start and `points` (offset from the start when `relative`).
    fn counted_spline(
        &self,
        start: Point,
        points: &[Point],
        relative: bool,
        dims: usize,
    ) -> Result<CountedSpline, GeometryError> {
        let mut nodes = Vec::with_capacity(points.len() + 1);
        nodes.push(start);
        nodes.extend(points.iter().map(|p| offset_from(&start, p, relative)));
        CountedSpline::new(&nodes, &self.counted, dims)
    }

    /// The counted share of `segment` and its limits along the path. With an angular profile
    /// (HIMC, digest 004 §8.3.7) the linear limits hold over the counted coordinates that are
    /// not orientation, the angular ones over the orientation coordinates, and the path takes
    /// the smaller of each limit, so neither profile is exceeded: the move lasts at least as
    /// long as the longer of the two, exactly as long where one binds every limit; a move that
    /// only turns runs on the angular profile alone (docs/decisions.md, "Group jog and angular
    /// profile").
    fn share(&self, group: GroupId, segment: &Segment) -> Result<Share, EngineError> {
        let Some(angular) = &self.angular else {
            let ratio = length_ratio(group, segment, &self.counted)?;
            return Ok(Share {
                ratio,
                limits: self.limits_along_path(ratio),
            });
        };
        let mut linear_coordinates = self.counted;
        let mut angular_coordinates = self.counted;
        for ((l, a), &o) in linear_coordinates
            .iter_mut()
            .zip(angular_coordinates.iter_mut())
            .zip(&angular.coordinates)
        {
            *l &= !o;
            *a &= o;
        }
        let linear = counted_share(group, segment, &linear_coordinates)?;
        let turning = counted_share(group, segment, &angular_coordinates)?;
        let limits = match (linear > 0.0, turning > 0.0) {
            (true, true) => smaller(
                &self.limits_along_path(linear),
                &along_path(&angular.limits, turning),
            ),
            (true, false) => self.limits_along_path(linear),
            (false, true) => along_path(&angular.limits, turning),
            (false, false) => {
                return Err(EngineError::InvalidPath {
                    group,
                    reason: "the counted coordinates do not move: the path length would be 0"
                        .into(),
                })
            }
        };
        Ok(Share {
            ratio: if linear > 0.0 { linear } else { turning },
            limits,
        })
    }

    /// The segment from `start`, all in the command's coordinate system.
    fn segment_in_frame(
        &self,
        group: GroupId,
        start: Point,
        dims: usize,
    ) -> Result<Segment, EngineError> {
        let offset = |p: &Point, relative: bool| offset_from(&start, p, relative);
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
            Geometry::Spline { points, relative } => self
                .counted_spline(start, points, *relative, dims)
                .and_then(CountedSpline::finish),
            Geometry::CenterAngle {
                center,
                angle,
                plane,
                relative,
            } => Arc::from_center_angle(start, offset(center, *relative), *angle, *plane, dims)
                .map(Segment::Arc),
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
        built.map_err(|e| invalid_path(group, e))
    }
}

/// `p`, or `start + p` when `relative`.
fn offset_from(start: &Point, p: &Point, relative: bool) -> Point {
    if relative {
        let mut out = *p;
        for (o, s) in out.iter_mut().zip(start) {
            *o += s;
        }
        out
    } else {
        *p
    }
}

/// The geometry's refusal as the engine's error.
fn invalid_path(group: GroupId, e: GeometryError) -> EngineError {
    EngineError::InvalidPath {
        group,
        reason: e.to_string(),
    }
}
