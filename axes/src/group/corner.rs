//! HMC's corner stop for a tangential axis (HMC_MoveTangConfigCornerMode, manual §4.4.9.2;
//! digest 000 §4.4 "Tangential tracking", TV 62): where the direction in the tracked plane
//! turns at a junction by more than the angle limit, the path stops exactly at the junction
//! and waits there until it is released (`tangential_corner_continue`), so that the tool can be
//! lifted and the tangential axis turned to the next motion's start direction
//! (`tangential_corner_follow_next`).
//!
//! The decision is made when the next motion is queued ("提前判断", judged in advance): a Hold
//! marker goes in front of it. A buffered non-motion command between the two motions clears
//! the last direction: "由于非插补类指令的起始切向角不可预判 … 在该指令的衔接处按照不抬刀处理"
//! (such a junction is not a corner stop).

use path::geometry::Segment;
use path::planner::MarkerKind;

use super::queue::Item;
use super::{Env, Group};
use crate::command::{CommandState, EngineError, GroupId};

/// Directions shorter than this (a segment that does not move in the plane) have no angle.
const DIRECTION_FLOOR: f64 = 1e-12;

/// A group's corner-stop rule, set by the tangential axis's corner mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerStop {
    /// The plane's two group coordinates.
    pub plane: [usize; 2],
    /// The direction change (radians) above which the path stops at a junction.
    pub angle_limit: f64,
}

/// The path stands at a corner stop: the direction (radians, in the plane) the next motion
/// starts in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerWait {
    pub next_direction: f64,
}

/// The plane direction (radians) of the unit tangent `t`, or `None` when the segment does not
/// move in the plane there.
fn plane_direction(t: &[f64], plane: [usize; 2]) -> Option<f64> {
    let x = t.get(plane[0]).copied().unwrap_or(0.0);
    let y = t.get(plane[1]).copied().unwrap_or(0.0);
    (x.hypot(y) > DIRECTION_FLOOR).then(|| y.atan2(x))
}

/// The angle between two directions, radians in [0, π].
fn turn(from: f64, to: f64) -> f64 {
    let d = (to - from).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

impl Group {
    /// Set or clear the corner-stop rule (motions queued from now on).
    pub fn set_corner_stop(&mut self, rule: Option<CornerStop>) {
        self.corner_stop = rule;
    }

    /// Where the path stands at a corner stop, if it does.
    pub fn corner_wait(&self) -> Option<CornerWait> {
        match self.waiting.as_ref().map(|w| &w.item) {
            Some(Item::CornerStop { next_direction }) => Some(CornerWait {
                next_direction: *next_direction,
            }),
            _ => None,
        }
    }

    /// Release a corner stop: the path goes on with the next step. Refused unless the path
    /// stands at one.
    pub fn release_corner(&mut self) -> Result<(), EngineError> {
        if self.corner_wait().is_none() {
            return Err(not_at_corner(self.id));
        }
        self.corner_released = true;
        Ok(())
    }

    /// Before `segment` is queued: a corner stop in front of it where the rule asks for one.
    /// Remembers the segment's end direction for the next junction.
    pub(super) fn queue_corner_stop(
        &mut self,
        env: &mut Env,
        segment: &Segment,
    ) -> Result<(), EngineError> {
        let Some(rule) = self.corner_stop else {
            self.last_direction = None;
            return Ok(());
        };
        let start = plane_direction(&segment.sample(0.0).t, rule.plane);
        let end = plane_direction(&segment.sample(segment.length()).t, rule.plane);
        if let (Some(before), Some(after)) = (self.last_direction, start) {
            if turn(before, after) > rule.angle_limit {
                // Room for the stop and the motion behind it (the caller checked for one).
                if self.queued() + 1 >= self.queue.capacity() as usize {
                    return Err(EngineError::GroupQueueFull {
                        group: self.id,
                        capacity: self.queue.capacity(),
                    });
                }
                let id = env.ledger.allocate();
                let item = Item::CornerStop {
                    next_direction: after,
                };
                if let Err(e) = self.push_marker(id, item, MarkerKind::Hold) {
                    env.ledger.finish(id, CommandState::Error(e.kind()));
                    return Err(e);
                }
            }
        }
        // A segment that does not move in the plane keeps the direction before it.
        self.last_direction = end.or(self.last_direction);
        Ok(())
    }
}

impl super::Groups {
    /// A group by number, to change (the tangential axis's corner mode).
    pub fn group_mut(&mut self, id: GroupId) -> Option<&mut Group> {
        self.groups.iter_mut().find(|g| g.id == id)
    }
}

/// The error of a corner command while the group's path does not stand at a corner stop.
pub(crate) fn not_at_corner(group: GroupId) -> EngineError {
    EngineError::InvalidGroup {
        group,
        reason: "the path does not stand at a corner stop".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_turn_is_the_smaller_angle_between_directions() {
        use std::f64::consts::PI;
        assert!((turn(0.0, PI / 2.0) - PI / 2.0).abs() < 1e-12);
        assert!((turn(3.0, -3.0) - (2.0 * PI - 6.0)).abs() < 1e-12);
        assert_eq!(plane_direction(&[0.0, 0.0, 1.0], [0, 1]), None);
        assert_eq!(plane_direction(&[1.0, 0.0], [0, 1]), Some(0.0));
    }
}
