//! HMC merge (digest 000 §3.4, §6.7: "for interpolations the result axis's Merge value
//! applies") and HMC's merge-angle bounds (TV 38), for groups with a result axis (HMC's
//! 合轴: only HMC programs name one).
//!
//! A motion queued `buffered` (the default, HMC's "each block finishes on its own") behind a
//! mergeable motion takes the blending join of the result axis's `merge` parameter, read when
//! it is queued: 1 this block's speed (`blending_previous`), 2 the next block's
//! (`blending_next`), 3 the lower (`blending_low`), 4 the higher (`blending_high`); 0 keeps
//! it buffered. An explicit blending mode is kept. Merge does not round corners (no
//! transition): the path passes through the junction point, slowed by the corner angles
//! (HMC_SetMergeAngle, on by default for these groups at HMC's π/6, π/2).
//!
//! HMC's further rules (the planner's `MergeRule`, on for these groups): a merge whose
//! velocity the motions after the junction cannot take is dropped for an exact stop (manual
//! §10.6 (8): the next command is `HMC_MoveEx(1)`), and the speed-ripple suppression ratio
//! (`merge_speed_tolerance`, HMC_SetMergeSpeedTolerRatio, §4.4.7.6). `mergeable` 0 marks the
//! motions queued next as not merging at either end (HMC_Move3D/MoveAbs3D(Ex)).

use path::geometry::Segment;
use path::planner::{CornerAngles, Join, MergeRule};

use super::Group;
use crate::axis::Axis;
use crate::command::{EngineError, GroupParameter};
use crate::param::ParamId;

/// HMC_SetMergeAngle's bounds (digest 000 §3.4, TV 38): decel angle ≤ π/6, stop angle ≤ π/2.
const MAX_DECEL_ANGLE: f64 = std::f64::consts::FRAC_PI_6;
const MAX_STOP_ANGLE: f64 = std::f64::consts::FRAC_PI_2;

/// Largest component, relative to 1, that an arc's plane vectors or helix may have off two
/// coordinates and the arc still count as a planar MoveCircle.
const PLANAR_TOLERANCE: f64 = 1e-12;

/// Whether HMC merges at the end of `segment` (digest 000 §3.4 "eligible command sequences"):
/// lines (Move2D, MoveND) and arcs in a coordinate plane (MoveCircle). Helices, spherical arcs
/// (a plane not of two coordinates), splines and ellipses are not mergeable.
pub(super) fn mergeable(segment: &Segment) -> bool {
    match segment {
        Segment::Line(_) => true,
        Segment::Arc(a) => {
            let (u, v) = a.basis();
            let used = u
                .iter()
                .zip(&v)
                .filter(|(x, y)| x.abs() > PLANAR_TOLERANCE || y.abs() > PLANAR_TOLERANCE)
                .count();
            let helix = a.helix().iter().any(|h| h.abs() > PLANAR_TOLERANCE);
            used <= 2 && !helix
        }
        Segment::Curve(_) => false,
    }
}

impl Group {
    /// The join a motion gets: `requested`, or with a result axis whose `merge` is on, a
    /// `buffered` motion behind a mergeable one (both mergeable) takes the merge's blending.
    pub(super) fn merged_join(&self, axes: &[Axis], requested: Join, segment: &Segment) -> Join {
        if requested != Join::Buffered
            || !self.last_mergeable
            || !self.merge_eligible
            || !mergeable(segment)
        {
            return requested;
        }
        let Some(axis) = self.result_axis().and_then(|a| axes.get(usize::from(a))) else {
            return requested;
        };
        match axis.params().get(ParamId::Merge) as i64 {
            1 => Join::BlendingPrevious,
            2 => Join::BlendingNext,
            3 => Join::BlendingLow,
            4 => Join::BlendingHigh,
            _ => requested,
        }
    }

    /// `merge_speed_tolerance` (HMC_SetMergeSpeedTolerRatio, [0, 1]) or `mergeable` (0 or 1)
    /// of a group with a result axis.
    pub(super) fn set_merge_parameter(
        &mut self,
        name: GroupParameter,
        value: f64,
    ) -> Result<(), EngineError> {
        if self.result.is_none() {
            return Err(EngineError::InvalidArgument {
                name: "name",
                value,
                reason: "HMC's merge parameters need a group with a result axis",
            });
        }
        if name == GroupParameter::Mergeable {
            if value != 0.0 && value != 1.0 {
                return Err(EngineError::InvalidArgument {
                    name: "value",
                    value,
                    reason: "must be 0 (motions do not merge) or 1 (they may)",
                });
            }
            self.merge_eligible = value == 1.0;
            return Ok(());
        }
        // NaN fails the range check too.
        if !(0.0..=1.0).contains(&value) {
            return Err(EngineError::InvalidArgument {
                name: "value",
                value,
                reason: "HMC's merge speed tolerance ratio is 0 to 1",
            });
        }
        let rule = MergeRule {
            speed_tolerance: value,
        };
        // In range, so the planner accepts it.
        let _ = self.planner.set_merge_rule(Some(rule));
        Ok(())
    }

    /// HMC's merge-angle bounds for a group with a result axis (TV 38: `(0.6, 1.0)` and
    /// `(0.5, 0.4)` are refused); the planner's own check (0 ≤ slow ≤ stop ≤ π) follows.
    pub(super) fn check_merge_angles(&self, angles: &CornerAngles) -> Result<(), EngineError> {
        if self.result.is_none() {
            return Ok(());
        }
        let (value, reason) = if angles.slow > MAX_DECEL_ANGLE {
            (
                angles.slow,
                "HMC's merge decel angle is at most π/6 radians",
            )
        } else if angles.stop > MAX_STOP_ANGLE {
            (angles.stop, "HMC's merge stop angle is at most π/2 radians")
        } else {
            return Ok(());
        };
        Err(EngineError::InvalidArgument {
            name: "value",
            value,
            reason,
        })
    }
}
