//! A group's coordinate systems (issue 11 item 1): HIMC's frame chain MCS → OFFSET → WCSn →
//! PCS (digest 004 §2.7, TV 56–57) and NMC's rotary transforms (digest 001 §2.10,
//! S-TRANS-ROTATE, S-TRANS-XYZA), on the pure `path::frames` values.
//!
//! A move's positions are taken to group coordinates when the move is accepted: the planner
//! plans in group coordinates only. "MCS" is the group's coordinates (the members' commanded
//! positions less the NMC origin offset, which is zero unless `group_set_origin` set it).

use path::frames::{Frame, FrameChain, FrameSelection, Transform, XyzaTransform, WCS_COUNT};
use path::geometry::{Line, Segment};
use path::Point;

use crate::axis::Axis;
use crate::command::{
    bounded, AxisIndex, CoordinateSystem, EngineError, GroupId, GroupSetRotaryTransform,
    GroupSetXyzaTransform,
};

/// NMC `CrdSetTransRotate`: the table axis, the plane it turns and its centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rotary {
    pub table: AxisIndex,
    pub rad_per_unit: f64,
    pub plane: (usize, usize),
    pub center: (f64, f64),
}

impl Rotary {
    /// The workpiece → machine transform with the table at `position` (its axis's units):
    /// machine = centre + R(θ)·(p − centre), θ = position × rad/unit.
    fn at(&self, position: f64) -> Transform {
        Transform::rotation_about(self.plane, self.center, position * self.rad_per_unit)
            .unwrap_or_default()
    }
}

/// The NMC transform a group may have (one at a time, as NMC's coordinate system has).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum NmcTransform {
    Rotary(Rotary),
    Xyza(XyzaTransform),
}

/// How one accepted move's positions reach group coordinates.
// The rigid transform is the common case; boxing it would allocate for every accepted move.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub(super) enum FrameMap {
    /// A rigid transform (identity for the MCS): the segment built in the selected system is
    /// moved whole, so arcs keep their centre, plane or normal, radius and sweep.
    Rigid(Transform),
    /// NMC XYZA: the tool-tip offset depends on A, so it is not rigid when A moves.
    Xyza(XyzaTransform),
}

impl Default for FrameMap {
    fn default() -> Self {
        FrameMap::Rigid(Transform::identity())
    }
}

impl FrameMap {
    /// Group coordinates → the selected system.
    pub fn point_from_machine(&self, p: &Point) -> Point {
        match self {
            FrameMap::Rigid(t) => t.inverse().apply(p),
            FrameMap::Xyza(x) => x.from_machine(p),
        }
    }

    /// `segment`, built in the selected system from `point_from_machine(start)`, in group
    /// coordinates from `start`. XYZA: a line goes to the transformed end point (the tool tip
    /// is exact at both ends, the axes move linearly between them); a curve must keep A
    /// constant (then the offset is a translation and the curve moves whole).
    pub fn segment_to_machine(
        &self,
        group: GroupId,
        start: Point,
        segment: Segment,
        dims: usize,
    ) -> Result<Segment, EngineError> {
        let t = match self {
            FrameMap::Rigid(t) if t.is_identity() => return Ok(segment),
            FrameMap::Rigid(t) => *t,
            FrameMap::Xyza(x) => {
                if let Segment::Line(l) = &segment {
                    return Line::new(start, x.to_machine(&l.end()), dims)
                        .map(Segment::Line)
                        .map_err(|e| EngineError::InvalidPath {
                            group,
                            reason: e.to_string(),
                        });
                }
                let a_start = segment.start()[3];
                if (segment.end()[3] - a_start).abs() > 1e-12 {
                    return Err(EngineError::InvalidPath {
                        group,
                        reason: "in the xyza system an arc or curve keeps A constant".into(),
                    });
                }
                let mut offset = x.to_machine(&segment.start());
                for (o, p) in offset.iter_mut().zip(segment.start()) {
                    *o -= p;
                }
                Transform::translation(offset).unwrap_or_default()
            }
        };
        let mut moved = segment.transformed(&t);
        // The start is the path's own point, not its round trip through the transform.
        if let Segment::Line(l) = &moved {
            moved = Line::new(start, l.end(), dims)
                .map(Segment::Line)
                .map_err(|e| EngineError::InvalidPath {
                    group,
                    reason: e.to_string(),
                })?;
        }
        Ok(moved)
    }
}

/// A group's frames: the HIMC chain, the NMC transform, and the selected system.
#[derive(Clone, Debug, Default)]
pub(super) struct GroupFrames {
    chain: FrameChain,
    nmc: Option<NmcTransform>,
    selected: CoordinateSystem,
}

/// The one link a selection names (`"offset"`, `"wcsN"`, `"pcs"`), if it names one.
fn link_of(frame: CoordinateSystem) -> Option<Frame> {
    match frame {
        CoordinateSystem::Chain {
            offset: true,
            wcs: None,
            pcs: false,
        } => Some(Frame::Offset),
        CoordinateSystem::Chain {
            offset: false,
            wcs: Some(n),
            pcs: false,
        } => Some(Frame::Wcs(n)),
        CoordinateSystem::Chain {
            offset: false,
            wcs: None,
            pcs: true,
        } => Some(Frame::Pcs),
        _ => None,
    }
}

fn undefined(group: GroupId, system: CoordinateSystem, reason: &'static str) -> EngineError {
    EngineError::UndefinedCoordinateSystem {
        group,
        system: system.to_string(),
        reason,
    }
}

impl GroupFrames {
    pub fn selected(&self) -> CoordinateSystem {
        self.selected
    }

    /// `group_set_coordinate_system`: checked as a move's selection would be.
    pub fn select(
        &mut self,
        group: GroupId,
        system: CoordinateSystem,
        dims: usize,
        axes: &[Axis],
    ) -> Result<(), EngineError> {
        self.resolve(group, system, dims, axes, None)?;
        self.selected = system;
        Ok(())
    }

    /// `group_set_coordinate_transform` (HIMC SetGrpCoordTrans): one link, a finite pose.
    pub fn set_link(
        &mut self,
        group: GroupId,
        frame: CoordinateSystem,
        pose: [f64; 6],
    ) -> Result<(), EngineError> {
        for v in pose {
            bounded("pose", v)?;
        }
        let link = link_of(frame)
            .filter(|l| !matches!(l, Frame::Wcs(n) if !(1..=WCS_COUNT).contains(&usize::from(*n))))
            .ok_or_else(|| {
                undefined(
                    group,
                    frame,
                    "is not one link: a transform is set on offset, wcs1 to wcs15 or pcs",
                )
            })?;
        self.chain
            .set(link, pose)
            .map_err(|e| EngineError::InvalidPath {
                group,
                reason: e.to_string(),
            })
    }

    /// The pose a link was set to (HIMC GetGrpCoordTrans, TV 57); `None` for a selection that
    /// is not one link.
    pub fn link_pose(&self, frame: CoordinateSystem) -> Option<[f64; 6]> {
        let link = link_of(frame)?;
        self.chain.pose(link).ok()
    }

    pub fn set_rotary(
        &mut self,
        c: &GroupSetRotaryTransform,
        members: &[AxisIndex],
        axes: &[Axis],
    ) -> Result<(), EngineError> {
        let group = c.group;
        let dims = members.len();
        if axes.get(usize::from(c.rotary_axis)).is_none() {
            return Err(EngineError::InvalidAxis {
                axis: u32::from(c.rotary_axis),
                count: axes.len() as u32,
            });
        }
        if members.contains(&c.rotary_axis) {
            return Err(EngineError::InvalidGroup {
                group,
                reason: format!(
                    "the rotary table axis {} is a member; it turns between segments (S-TRANS-ROTATE), not with the path",
                    c.rotary_axis
                ),
            });
        }
        let [i, j] = c.plane.unwrap_or([0, 1]);
        if i == j || i >= dims || j >= dims {
            return Err(EngineError::InvalidPath {
                group,
                reason: format!(
                    "plane [{i}, {j}] needs two different coordinates of the group's {dims}"
                ),
            });
        }
        let rotary = Rotary {
            table: c.rotary_axis,
            rad_per_unit: bounded("rad_per_unit", c.rad_per_unit)?,
            plane: (i, j),
            center: (
                bounded("center", c.center[0])?,
                bounded("center", c.center[1])?,
            ),
        };
        self.nmc = Some(NmcTransform::Rotary(rotary));
        Ok(())
    }

    pub fn set_xyza(&mut self, c: &GroupSetXyzaTransform, dims: usize) -> Result<(), EngineError> {
        if dims < 4 {
            return Err(EngineError::InvalidGroup {
                group: c.group,
                reason: format!("the xyza transform needs X, Y, Z, A: 4 coordinates, not {dims}"),
            });
        }
        let x = XyzaTransform::new(
            bounded("rad_per_unit", c.rad_per_unit)?,
            (bounded("tool", c.tool[0])?, bounded("tool", c.tool[1])?),
        )
        .map_err(|e| EngineError::InvalidPath {
            group: c.group,
            reason: e.to_string(),
        })?;
        self.nmc = Some(NmcTransform::Xyza(x));
        Ok(())
    }

    /// `group_delete_transform`: a selection of it returns to the MCS.
    pub fn delete_nmc(&mut self) {
        self.nmc = None;
        if matches!(
            self.selected,
            CoordinateSystem::Rotary | CoordinateSystem::Xyza
        ) {
            self.selected = CoordinateSystem::MCS;
        }
    }

    /// The map for a move in `system` (the selected one when `None`), accepted now.
    /// `table_position`: where the rotary table will be when the move runs (the last queued
    /// move of its axis), else its commanded position now.
    pub fn resolve(
        &self,
        group: GroupId,
        system: CoordinateSystem,
        dims: usize,
        axes: &[Axis],
        table_position: Option<f64>,
    ) -> Result<FrameMap, EngineError> {
        match system {
            CoordinateSystem::Chain { offset, wcs, pcs } => {
                if wcs.is_some_and(|n| !(1..=WCS_COUNT).contains(&usize::from(n))) {
                    return Err(undefined(
                        group,
                        system,
                        "is not defined: the workpiece frames are wcs1 to wcs15",
                    ));
                }
                let t = self
                    .chain
                    .to_machine(FrameSelection { offset, wcs, pcs })
                    .unwrap_or_default();
                if !t.keeps(dims) {
                    return Err(undefined(
                        group,
                        system,
                        "moves positions into axes the group does not have (a rotation about X or Y needs 3 coordinates)",
                    ));
                }
                Ok(FrameMap::Rigid(t))
            }
            CoordinateSystem::Rotary => match self.nmc {
                Some(NmcTransform::Rotary(r)) => {
                    let position = table_position.unwrap_or_else(|| {
                        axes.get(usize::from(r.table))
                            .map_or(0.0, |a| a.commanded().p)
                    });
                    Ok(FrameMap::Rigid(r.at(position)))
                }
                _ => Err(undefined(
                    group,
                    system,
                    "is not defined: no rotary transform is set",
                )),
            },
            CoordinateSystem::Xyza => match self.nmc {
                Some(NmcTransform::Xyza(x)) => Ok(FrameMap::Xyza(x)),
                _ => Err(undefined(
                    group,
                    system,
                    "is not defined: no xyza transform is set",
                )),
            },
        }
    }

    /// The rotary table's axis, if the rotary transform is set.
    pub fn table_axis(&self) -> Option<AxisIndex> {
        match self.nmc {
            Some(NmcTransform::Rotary(r)) => Some(r.table),
            _ => None,
        }
    }

    /// `machine` (group coordinates) in the selected system, for the status; the machine
    /// point itself if the selection cannot be resolved.
    pub fn position_in_selected(
        &self,
        group: GroupId,
        machine: &Point,
        dims: usize,
        axes: &[Axis],
    ) -> Point {
        match self.resolve(group, self.selected, dims, axes, None) {
            Ok(map) => {
                let mut p = map.point_from_machine(machine);
                for x in p.iter_mut().skip(dims) {
                    *x = 0.0;
                }
                p
            }
            Err(_) => *machine,
        }
    }
}
