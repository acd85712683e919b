//! The group family (issue 11): commands on a group of axes that move on one path, named after
//! PLCopen Part 4 in snake_case (`group_create`, `move_linear_absolute` …).
//!
//! Coordinates (`position`, `distance`, `end_point`, `aux_point`, `offset`) have one number per
//! member axis, in the order of the group's `axes`. Kinematic limits given in a motion apply to
//! that motion only and are along the path; where absent, the group parameters apply
//! (`group_set_parameter`). Every member's own velocity, acceleration and jerk limits hold
//! whatever the path asks for.

use serde::{Deserialize, Serialize};

use crate::status::PositionSource;
use crate::types::MAX_GROUP_AXES;

/// A set of group coordinates (indices 0–8 into a group's `axes`, as `plane`); in JSON a list
/// of indices, `[3, 4]`. A bit set, so that the motion commands stay small (a command is moved
/// by value through the servo queue).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CoordinateSet(u16);

impl CoordinateSet {
    /// The set of `indices`; `None` if one is not below 9 (a group has at most 9 coordinates).
    pub fn from_indices(indices: &[usize]) -> Option<CoordinateSet> {
        indices.iter().try_fold(CoordinateSet(0), |set, &k| {
            (k < MAX_GROUP_AXES).then_some(CoordinateSet(set.0 | 1 << k))
        })
    }

    pub fn is_empty(&self) -> bool {
        self.0 == 0
    }

    pub fn contains(&self, k: usize) -> bool {
        k < MAX_GROUP_AXES && self.0 & (1 << k) != 0
    }

    /// The indices, ascending.
    pub fn iter(self) -> impl Iterator<Item = usize> {
        (0..MAX_GROUP_AXES).filter(move |&k| self.contains(k))
    }
}

impl Serialize for CoordinateSet {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter())
    }
}

impl<'de> Deserialize<'de> for CoordinateSet {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let indices = Vec::<usize>::deserialize(deserializer)?;
        CoordinateSet::from_indices(&indices).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "group coordinates are indices 0 to {} into the group's axes, not {indices:?}",
                MAX_GROUP_AXES - 1
            ))
        })
    }
}
use super::{
    command_from, AxisIndex, CoordinateSystem, GroupDeleteTransform, GroupId,
    GroupSetCoordinateSystem, GroupSetCoordinateTransform, GroupSetRotaryTransform,
    GroupSetXyzaTransform, MoveProtectionDisable, MoveProtectionEnable,
};
use super::{GroupBufferedHalt, GroupPulseOutput, GroupSetAnalogOutput, GroupStopInput};
use super::{GroupDeletePolarTransform, GroupSetPolarTransform};
use super::{GroupJog, GroupJogAxis};

/// Make a group of 1–9 axes (PLCopen MC_AddAxisToGroup ×n; HIMC SetupGroup without the enable;
/// NMC CrdSetMtSys). The group starts Disabled.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupCreate {
    pub group: GroupId,
    pub axes: Vec<AxisIndex>,
    /// Entries the group queue holds, 1–1024 (default: the `[groups]` config, 512).
    #[serde(default)]
    pub queue_capacity: Option<u32>,
    /// Segments the look-ahead plans over (default: the `[groups]` config, 64).
    #[serde(default)]
    pub lookahead: Option<u32>,
    /// HMC's result axis (合轴, digest 000 §4.3): an axis outside the group (usually a
    /// virtual one) whose position grows by the path length the group travels and whose
    /// `speed`, `accel`, `decel` and `jerk` are the path limits of motions that give none. It
    /// is bound to the group like a member (IN_GROUP, no single-axis motion; its fault stops
    /// the group).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub result_axis: Option<AxisIndex>,
    /// Group coordinates that are orientation angles (HIMC's A, B, C: `[3, 4, 5]`, digest 004
    /// §8.3.7): a line's change of them is limited by the group's angular profile
    /// (`angular_velocity` …) while the other coordinates keep the linear one; the move takes
    /// the longer of the two. Default none: every coordinate is linear.
    #[serde(default, skip_serializing_if = "CoordinateSet::is_empty")]
    pub orientation: CoordinateSet,
}

/// Dissolve a group (HIMC UngrpAllAxes); its axes are free again. Refused while it moves.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupDelete {
    pub group: GroupId,
}

/// Disabled → Standby, if every member is enabled (PLCopen MC_GroupEnable).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupEnable {
    pub group: GroupId,
}

/// → Disabled: the path is dropped and the members ramp to rest (MC_GroupDisable).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupDisable {
    pub group: GroupId,
}

/// ErrorStop → Standby once the causes are gone (MC_GroupReset, HIMC ResetGroup).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupReset {
    pub group: GroupId,
}

/// How a group motion joins the motion queued before it (PLCopen Part 4 buffer modes, HIMC
/// BM_*). The default is `buffered`: the group queue is a program of segments (HIMC, NMC).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GroupBufferMode {
    /// Stop the path (group deceleration), drop the queue, then start this motion.
    Aborting,
    /// Stop exactly at the end of the previous motion, then start.
    #[default]
    Buffered,
    /// Pass the junction at the lower of the two motions' velocities.
    BlendingLow,
    /// … at the previous motion's velocity.
    BlendingPrevious,
    /// … at this motion's velocity.
    BlendingNext,
    /// … at the higher of the two.
    BlendingHigh,
}

/// The corner geometry of a blended junction (PLCopen transition modes, HIMC TM_*, G64 P).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TransitionMode {
    /// Through the corner point.
    #[default]
    None,
    /// Round the corner, starting at most this path distance before it.
    CornerDistance(f64),
    /// Round the corner, passing it at most this far away.
    CornerDeviation(f64),
}

/// Move along a straight line to a point in group coordinates (MC_MoveLinearAbsolute).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveLinearAbsolute {
    pub group: GroupId,
    pub position: Vec<f64>,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    /// Along the path; 0 = trapezoid.
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: GroupBufferMode,
    #[serde(default)]
    pub transition: TransitionMode,
    /// A number the status reports while this motion runs (NMC CrdGetUserSegNo).
    #[serde(default)]
    pub user_segment: Option<u32>,
    /// Group coordinates (indices into the group's `axes`, as `plane`) that move in
    /// proportion but do not count in the path length: velocity, acceleration, deceleration,
    /// jerk and the result axis's travel are measured over the other coordinates (HMC MoveND
    /// independent axes; HMC_MoveHelical modes 4/5/7 count the arc plane only).
    #[serde(default, skip_serializing_if = "CoordinateSet::is_empty")]
    pub independent: CoordinateSet,
    /// The coordinate system the positions are given in (default: the group's, which is
    /// `mcs` until `group_set_coordinate_system`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coordinate_system: Option<CoordinateSystem>,
}

/// Move along a straight line by a distance from where the previous motion ends
/// (MC_MoveLinearRelative).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveLinearRelative {
    pub group: GroupId,
    pub distance: Vec<f64>,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: GroupBufferMode,
    #[serde(default)]
    pub transition: TransitionMode,
    #[serde(default)]
    pub user_segment: Option<u32>,
    /// Group coordinates (indices into the group's `axes`, as `plane`) that move in
    /// proportion but do not count in the path length: velocity, acceleration, deceleration,
    /// jerk and the result axis's travel are measured over the other coordinates (HMC MoveND
    /// independent axes; HMC_MoveHelical modes 4/5/7 count the arc plane only).
    #[serde(default, skip_serializing_if = "CoordinateSet::is_empty")]
    pub independent: CoordinateSet,
    /// The coordinate system the positions are given in (default: the group's, which is
    /// `mcs` until `group_set_coordinate_system`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coordinate_system: Option<CoordinateSystem>,
}

/// What `aux_point` (and `radius`) of a circular move mean (PLCopen MC_CircMode).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CircleMode {
    /// `aux_point` is the centre (HIMC ArcCenter, NMC ArcXYC, HMC MoveCircle).
    #[default]
    Center,
    /// `radius` gives the circle: > 0 the minor arc, < 0 the major arc (NMC ArcXYR).
    Radius,
    /// `aux_point` is a point on the arc between start and end (MC_3P_CIRCLE, HMC 3-point).
    Border,
}

/// Which way an arc turns, seen from the positive side of its plane's normal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ArcDirection {
    Cw,
    #[default]
    Ccw,
}

/// Move on a circular arc (MC_MoveCircularAbsolute): points in group coordinates. The arc
/// lies in the plane of the group coordinates `plane` (default `[0, 1]`), or about `normal` (a
/// vector over the first three coordinates); the other coordinates move linearly (a helix).
/// `turns` adds full turns (a start equal to the end is a full circle).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveCircularAbsolute {
    pub group: GroupId,
    #[serde(default)]
    pub mode: CircleMode,
    #[serde(default)]
    pub aux_point: Vec<f64>,
    #[serde(default)]
    pub radius: Option<f64>,
    pub end_point: Vec<f64>,
    #[serde(default)]
    pub direction: ArcDirection,
    #[serde(default)]
    pub plane: Option<[usize; 2]>,
    #[serde(default)]
    pub normal: Option<Vec<f64>>,
    #[serde(default)]
    pub turns: u32,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: GroupBufferMode,
    #[serde(default)]
    pub transition: TransitionMode,
    #[serde(default)]
    pub user_segment: Option<u32>,
    /// Group coordinates (indices into the group's `axes`, as `plane`) that move in
    /// proportion but do not count in the path length: velocity, acceleration, deceleration,
    /// jerk and the result axis's travel are measured over the other coordinates (HMC MoveND
    /// independent axes; HMC_MoveHelical modes 4/5/7 count the arc plane only).
    #[serde(default, skip_serializing_if = "CoordinateSet::is_empty")]
    pub independent: CoordinateSet,
    /// The coordinate system the positions are given in (default: the group's, which is
    /// `mcs` until `group_set_coordinate_system`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coordinate_system: Option<CoordinateSystem>,
}

/// [`MoveCircularAbsolute`] with `aux_point` and `end_point` relative to the arc's start
/// (MC_MoveCircularRelative).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveCircularRelative {
    pub group: GroupId,
    #[serde(default)]
    pub mode: CircleMode,
    #[serde(default)]
    pub aux_point: Vec<f64>,
    #[serde(default)]
    pub radius: Option<f64>,
    pub end_point: Vec<f64>,
    #[serde(default)]
    pub direction: ArcDirection,
    #[serde(default)]
    pub plane: Option<[usize; 2]>,
    #[serde(default)]
    pub normal: Option<Vec<f64>>,
    #[serde(default)]
    pub turns: u32,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: GroupBufferMode,
    #[serde(default)]
    pub transition: TransitionMode,
    #[serde(default)]
    pub user_segment: Option<u32>,
    /// Group coordinates (indices into the group's `axes`, as `plane`) that move in
    /// proportion but do not count in the path length: velocity, acceleration, deceleration,
    /// jerk and the result axis's travel are measured over the other coordinates (HMC MoveND
    /// independent axes; HMC_MoveHelical modes 4/5/7 count the arc plane only).
    #[serde(default, skip_serializing_if = "CoordinateSet::is_empty")]
    pub independent: CoordinateSet,
    /// The coordinate system the positions are given in (default: the group's, which is
    /// `mcs` until `group_set_coordinate_system`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coordinate_system: Option<CoordinateSystem>,
}

/// Decelerate to rest along the path and drop the queue (MC_GroupStop). `deceleration`
/// defaults to the group parameter.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupStop {
    pub group: GroupId,
    #[serde(default)]
    pub deceleration: Option<f64>,
}

/// Decelerate to rest along the path and keep the queue (MC_GroupInterrupt, HIMC HaltGroup).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupHalt {
    pub group: GroupId,
    #[serde(default)]
    pub deceleration: Option<f64>,
}

/// Go on after a halt (MC_GroupContinue).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupContinue {
    pub group: GroupId,
}

/// Drop the path at once, stop every member with its `fast_decel`, go to ErrorStop (HIMC
/// EStop for one group). `keep_path` (NMC CrdEstopMtn, "急停(并不清空指令缓冲区)"): the path
/// is frozen where it is instead, its queue kept; the reset returns to Halted, a linear move
/// back to the break goes in front of what is left, and `group_continue` finishes the path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupEmergencyStop {
    pub group: GroupId,
    #[serde(default, skip_serializing_if = "is_false")]
    pub keep_path: bool,
}

fn is_false(v: &bool) -> bool {
    !*v
}

/// Path velocity override, (0, 10) (NMC CrdSetOverride; HIMC SetGrpVelScale 0–100 % is 0–1).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetOverride {
    pub group: GroupId,
    pub factor: f64,
}

/// Set the group's origin offset: group coordinate = member's commanded position − offset
/// (NMC orgFlag/offset). Only while nothing is queued.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetOrigin {
    pub group: GroupId,
    pub offset: Vec<f64>,
}

/// A group parameter: the path limits of motions that do not give their own, and the vendors'
/// look-ahead rules (off until set; they apply to motions queued afterwards).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GroupParameter {
    Velocity,
    Acceleration,
    Deceleration,
    /// 0 = trapezoid along the path.
    Jerk,
    /// Corner angle below which a blended junction keeps its speed, radians (HMC
    /// `HMC_SetMergeAngle` decelAngle, digest 000 §3.4; NMC slowAng, digest 001 §3.9). Setting
    /// it or `corner_stop_angle` turns the rule on, the other at HMC's default (π/6, π/2).
    CornerSlowAngle,
    /// Corner angle from which a blended junction stops, radians (HMC stopAngle; NMC stopAng).
    CornerStopAngle,
    /// Acceleration for the direction change at a corner (HIMC look-ahead prm 0; NMC accMax);
    /// 0 = off.
    CornerAcceleration,
    /// Centripetal acceleration on arcs, `v ≤ √(A·r)` (HIMC prm 1; NMC centAcc); 0 = off.
    ArcAcceleration,
    /// Largest chord error per servo period on arcs (HIMC prm 2); 0 = off. With radius bands
    /// (`chord_error_radius_1` or `_2` set), the error of radii up to the first edge.
    ChordError,
    /// NMC's arc-section table (`TArcSecSetting` r0, r1, err1, err2; digest 001 §3.9): radii
    /// above `chord_error_radius_1` take `chord_error_band_1`, above `chord_error_radius_2`
    /// `chord_error_band_2` (errors 0 = no limit in that band). The bands are on while either
    /// radius is positive; keep them ascending.
    ChordErrorRadius1,
    ChordErrorRadius2,
    ChordErrorBand1,
    ChordErrorBand2,
    /// The speed the fourth coordinate (index 3, NMC's A) may have at a corner: where the
    /// direction turns at an unblended junction the path slows so that it is not exceeded
    /// (NMC `NMC_CrdSetFourthAxisToTurnVel`, digest 001 §2.7); 0 = off (the default).
    FourthCoordinateCornerVelocity,
    /// HMC's stop after a member's limit or fault (digest 000 §4.3, §6.1 (b)/(c)): the path
    /// decelerates to rest with max(`deceleration`, this value) — the result axis's FastDecel —
    /// and the members still on the path stay on it. 0 = off (the default, NMC and HIMC: the
    /// path is dropped and each member ramps down on its own).
    FaultDeceleration,
    /// 1: every member's acceleration limit is the smallest of the members' (CPU 226H, digest
    /// 003 §2.0 tip 3: a two-axis instruction accelerates its long axis at the smaller of the
    /// two axes' max accel, TV-15); 0: each member its own (the default).
    SmallestAxisAcceleration,
    /// The angular profile of the group's `orientation` coordinates (HIMC
    /// SetGrpAngMotionProfile, digest 004 §8.3.7; defaults 360 deg/s, 1800 deg/s² up and down,
    /// jerk 36 000 deg/s³ from the 50 ms smoothing time).
    AngularVelocity,
    AngularAcceleration,
    AngularDeceleration,
    /// 0 = trapezoid.
    AngularJerk,
    /// HMC_SetMergeSpeedTolerRatio, [0, 1], default 0 (digest 000 §3.4; manual §4.4.7.6): a
    /// corner-angle factor of at least 1 − value counts as 1, so short lines drawn from coarse
    /// points no longer make the merged path's speed ripple. Groups with a result axis only.
    MergeSpeedTolerance,
    /// 1 (default): motions queued from now on take the result axis's merge (lines, arcs in a
    /// coordinate plane); 0: they do not, at either end (HMC_Move3D/MoveAbs3D(Ex), manual
    /// §4.3.1.5–4.3.1.8: "本指令目前暂不支持 merge 功能", this command does not support merge).
    /// Groups with a result axis only.
    Mergeable,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetParameter {
    pub group: GroupId,
    pub name: GroupParameter,
    pub value: f64,
}

/// Buffered: set a digital output when the path reaches this point of the queue; the path does
/// not slow down for it (NMC CrdBufDO).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetOutput {
    pub group: GroupId,
    pub channel: u16,
    pub value: bool,
}

/// Buffered: stop here and wait (NMC CrdBufDelay).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupDwell {
    pub group: GroupId,
    pub seconds: f64,
}

/// Buffered: stop here until a digital input has `level` (NMC CrdBufWaitDI); past `timeout`
/// seconds the group goes to ErrorStop.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupWaitInput {
    pub group: GroupId,
    pub channel: u16,
    pub level: bool,
    #[serde(default)]
    pub timeout: Option<f64>,
}

/// Buffered: stop here until `axis`'s actual position is within `tolerance` of `position`
/// (default: the axis's `in_position_window`), or with `condition` at most / at least
/// `position` (NMC CrdBufWaitPos); past `timeout` seconds the group goes to ErrorStop.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupWaitPosition {
    pub group: GroupId,
    pub axis: AxisIndex,
    pub position: f64,
    #[serde(default)]
    pub tolerance: Option<f64>,
    #[serde(default)]
    pub timeout: Option<f64>,
    #[serde(default, skip_serializing_if = "is_default")]
    pub condition: PositionCondition,
    /// Which position is compared (default: the actual one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<PositionSource>,
}

fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

/// When a position wait is met.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PositionCondition {
    /// Within the tolerance of the position.
    #[default]
    Within,
    /// At or below the position.
    AtMost,
    /// At or above the position.
    AtLeast,
}

/// Buffered: a single-axis absolute move of an axis outside the group that starts when the
/// path reaches this point (with the next segment, NMC CrdBufAxMoveEx).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupAxisMove {
    pub group: GroupId,
    pub axis: AxisIndex,
    pub position: f64,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
}

/// Move along a spline from where the previous motion ends through `points` (HMC
/// `MoveSplineND`, digest 000 §4.3): the natural cubic spline through the start and the points,
/// parametrised by chord length; points on one line in order make a line. `relative`: the
/// points are distances from the start. At most 1000 points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveSpline {
    pub group: GroupId,
    pub points: Vec<Vec<f64>>,
    /// Group coordinates (indices) that are not part of the spline's shape: they move from
    /// the start to the last point's values in proportion to the length along the spline
    /// through the other coordinates, and do not count in the path length (HMC MoveSplineND
    /// with independent axes, NMC D8; their values at the points before the last are not
    /// used).
    #[serde(default, skip_serializing_if = "CoordinateSet::is_empty")]
    pub independent: CoordinateSet,
    #[serde(default)]
    pub relative: bool,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: GroupBufferMode,
    #[serde(default)]
    pub transition: TransitionMode,
    #[serde(default)]
    pub user_segment: Option<u32>,
    /// The coordinate system the positions are given in (default: the group's, which is
    /// `mcs` until `group_set_coordinate_system`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coordinate_system: Option<CoordinateSystem>,
}

/// A full ellipse from where the previous motion ends, around `center`, back to the start (NMC
/// `CrdEllipse`, digest 001 §4.4): the semi-major axis is start − centre, the semi-minor axis
/// `ratio` × that (0.05 to 1), in the plane of group coordinates `plane` (default `[0, 1]`).
/// `relative`: `center` is relative to the start, as NMC gives it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveEllipse {
    pub group: GroupId,
    pub center: Vec<f64>,
    pub ratio: f64,
    #[serde(default)]
    pub direction: ArcDirection,
    #[serde(default)]
    pub plane: Option<[usize; 2]>,
    #[serde(default)]
    pub relative: bool,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: GroupBufferMode,
    #[serde(default)]
    pub transition: TransitionMode,
    #[serde(default)]
    pub user_segment: Option<u32>,
    /// The coordinate system the positions are given in (default: the group's, which is
    /// `mcs` until `group_set_coordinate_system`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coordinate_system: Option<CoordinateSystem>,
}

/// An arc from where the previous motion ends, about `center`, through `angle` degrees
/// (HIMC `ArcAngle2D`, digest 004 §8.2.16: > 0 counter-clockwise, < 0 clockwise, beyond ±360°
/// more than one turn), in the plane of group coordinates `plane` (default `[0, 1]`).
/// `relative`: `center` is relative to the start.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveCircularAngle {
    pub group: GroupId,
    pub center: Vec<f64>,
    /// Degrees, signed.
    pub angle: f64,
    #[serde(default)]
    pub plane: Option<[usize; 2]>,
    #[serde(default)]
    pub relative: bool,
    #[serde(default)]
    pub velocity: Option<f64>,
    #[serde(default)]
    pub acceleration: Option<f64>,
    #[serde(default)]
    pub deceleration: Option<f64>,
    #[serde(default)]
    pub jerk: Option<f64>,
    #[serde(default)]
    pub buffer_mode: GroupBufferMode,
    #[serde(default)]
    pub transition: TransitionMode,
    #[serde(default)]
    pub user_segment: Option<u32>,
    /// The coordinate system the positions are given in (default: the group's, which is
    /// `mcs` until `group_set_coordinate_system`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coordinate_system: Option<CoordinateSystem>,
}

/// A command on one axis group.
#[derive(Clone, Debug, PartialEq)]
pub enum GroupCommand {
    Create(GroupCreate),
    Delete(GroupDelete),
    Enable(GroupEnable),
    Disable(GroupDisable),
    Reset(GroupReset),
    MoveLinearAbsolute(MoveLinearAbsolute),
    MoveLinearRelative(MoveLinearRelative),
    MoveCircularAbsolute(MoveCircularAbsolute),
    MoveCircularRelative(MoveCircularRelative),
    Stop(GroupStop),
    Halt(GroupHalt),
    Continue(GroupContinue),
    EmergencyStop(GroupEmergencyStop),
    SetOverride(GroupSetOverride),
    SetOrigin(GroupSetOrigin),
    SetParameter(GroupSetParameter),
    SetOutput(GroupSetOutput),
    Dwell(GroupDwell),
    WaitInput(GroupWaitInput),
    WaitPosition(GroupWaitPosition),
    AxisMove(GroupAxisMove),
    MoveSpline(MoveSpline),
    MoveEllipse(MoveEllipse),
    MoveCircularAngle(MoveCircularAngle),
    SetCoordinateTransform(GroupSetCoordinateTransform),
    SetCoordinateSystem(GroupSetCoordinateSystem),
    SetRotaryTransform(GroupSetRotaryTransform),
    SetXyzaTransform(GroupSetXyzaTransform),
    DeleteTransform(GroupDeleteTransform),
    Jog(GroupJog),
    JogAxis(GroupJogAxis),
    PulseOutput(GroupPulseOutput),
    SetAnalogOutput(GroupSetAnalogOutput),
    StopInput(GroupStopInput),
    BufferedHalt(GroupBufferedHalt),
    SetPolarTransform(GroupSetPolarTransform),
    DeletePolarTransform(GroupDeletePolarTransform),
    /// Between two groups.
    ProtectionEnable(MoveProtectionEnable),
    ProtectionDisable(MoveProtectionDisable),
}

impl GroupCommand {
    /// The group the command addresses; `None` for the commands between two groups.
    pub fn group(&self) -> Option<GroupId> {
        Some(match self {
            GroupCommand::Create(c) => c.group,
            GroupCommand::Delete(c) => c.group,
            GroupCommand::Enable(c) => c.group,
            GroupCommand::Disable(c) => c.group,
            GroupCommand::Reset(c) => c.group,
            GroupCommand::MoveLinearAbsolute(c) => c.group,
            GroupCommand::MoveLinearRelative(c) => c.group,
            GroupCommand::MoveCircularAbsolute(c) => c.group,
            GroupCommand::MoveCircularRelative(c) => c.group,
            GroupCommand::Stop(c) => c.group,
            GroupCommand::Halt(c) => c.group,
            GroupCommand::Continue(c) => c.group,
            GroupCommand::EmergencyStop(c) => c.group,
            GroupCommand::SetOverride(c) => c.group,
            GroupCommand::SetOrigin(c) => c.group,
            GroupCommand::SetParameter(c) => c.group,
            GroupCommand::SetOutput(c) => c.group,
            GroupCommand::Dwell(c) => c.group,
            GroupCommand::WaitInput(c) => c.group,
            GroupCommand::WaitPosition(c) => c.group,
            GroupCommand::AxisMove(c) => c.group,
            GroupCommand::MoveSpline(c) => c.group,
            GroupCommand::MoveEllipse(c) => c.group,
            GroupCommand::MoveCircularAngle(c) => c.group,
            GroupCommand::SetCoordinateTransform(c) => c.group,
            GroupCommand::SetCoordinateSystem(c) => c.group,
            GroupCommand::SetRotaryTransform(c) => c.group,
            GroupCommand::SetXyzaTransform(c) => c.group,
            GroupCommand::DeleteTransform(c) => c.group,
            GroupCommand::Jog(c) => c.group,
            GroupCommand::JogAxis(c) => c.group,
            GroupCommand::PulseOutput(c) => c.group,
            GroupCommand::SetAnalogOutput(c) => c.group,
            GroupCommand::StopInput(c) => c.group,
            GroupCommand::BufferedHalt(c) => c.group,
            GroupCommand::SetPolarTransform(c) => c.group,
            GroupCommand::DeletePolarTransform(c) => c.group,
            GroupCommand::ProtectionEnable(_) | GroupCommand::ProtectionDisable(_) => return None,
        })
    }
}

command_from!(GroupCommand, Group, [
    GroupCreate => Create,
    GroupDelete => Delete,
    GroupEnable => Enable,
    GroupDisable => Disable,
    GroupReset => Reset,
    MoveLinearAbsolute => MoveLinearAbsolute,
    MoveLinearRelative => MoveLinearRelative,
    MoveCircularAbsolute => MoveCircularAbsolute,
    MoveCircularRelative => MoveCircularRelative,
    GroupStop => Stop,
    GroupHalt => Halt,
    GroupContinue => Continue,
    GroupEmergencyStop => EmergencyStop,
    GroupSetOverride => SetOverride,
    GroupSetOrigin => SetOrigin,
    GroupSetParameter => SetParameter,
    GroupSetOutput => SetOutput,
    GroupDwell => Dwell,
    GroupWaitInput => WaitInput,
    GroupWaitPosition => WaitPosition,
    GroupAxisMove => AxisMove,
    MoveSpline => MoveSpline,
    MoveEllipse => MoveEllipse,
    MoveCircularAngle => MoveCircularAngle,
    GroupSetCoordinateTransform => SetCoordinateTransform,
    GroupSetCoordinateSystem => SetCoordinateSystem,
    GroupSetRotaryTransform => SetRotaryTransform,
    GroupSetXyzaTransform => SetXyzaTransform,
    GroupDeleteTransform => DeleteTransform,
    GroupJog => Jog,
    GroupJogAxis => JogAxis,
    GroupPulseOutput => PulseOutput,
    GroupSetAnalogOutput => SetAnalogOutput,
    GroupStopInput => StopInput,
    GroupBufferedHalt => BufferedHalt,
    MoveProtectionEnable => ProtectionEnable,
    MoveProtectionDisable => ProtectionDisable,
    GroupSetPolarTransform => SetPolarTransform,
    GroupDeletePolarTransform => DeletePolarTransform,
]);
