//! NMC's polar machine on a group (`group_set_polar_transform`; digest 001 C3§10.5
//! "极坐标转换: 用户数据是按照直角坐标描述, 实际机械机构是一个旋转轴和一个进给轴"). The planner
//! stays Cartesian: each tick the plane's point (origin included) is fed to the rotary member
//! as θ and to the feed member as r (`path::frames::polar`), θ on the branch nearest the
//! previous tick's. Each motion's path limits are cut when it is accepted so that both members
//! stay within their own velocity and acceleration (docs/decisions.md, "Polar machine").

use path::frames::polar::{from_polar, polar_bounds, to_polar, unwrapped_angle};
use path::geometry::Segment;
use path::planner::{PathLimits, PathState};
use path::Point;

use super::{axis_limits, Group};
use crate::axis::Axis;
use crate::command::{bounded, EngineError, GroupSetPolarTransform, Reply};
use crate::profile::MotionState;

/// The polar transform of a group: which coordinates are X and Y, which member slots turn and
/// feed, and the angle the rotary member is on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PolarMachine {
    plane: (usize, usize),
    /// Member slots (group coordinates) of the rotary and the feed axis: `plane` in some order.
    rotary: usize,
    feed: usize,
    units_per_radian: f64,
    /// θ fed last (rad, unwrapped): the next tick's θ is on the branch nearest it.
    theta: f64,
    /// θ where the last queued motion ends: a line leaving the pole must point there.
    queued_theta: f64,
}

/// This tick's setpoints of the rotary and the feed slot.
#[derive(Clone, Copy, Debug)]
pub(super) struct PolarSetpoints {
    rotary: (usize, MotionState),
    feed: (usize, MotionState),
}

impl PolarSetpoints {
    /// The setpoint of member slot `k`, if it is one of the two.
    pub fn get(&self, k: usize) -> Option<MotionState> {
        [self.rotary, self.feed]
            .into_iter()
            .find(|(slot, _)| *slot == k)
            .map(|(_, s)| s)
    }
}

impl PolarMachine {
    /// The plane's point of `p` (group coordinates) plus the origin.
    fn cartesian(&self, p: &Point, origin: &Point) -> [f64; 2] {
        let (i, j) = self.plane;
        [p[i] + origin[i], p[j] + origin[j]]
    }

    /// This tick's setpoints for the planner's `state`; θ follows on from last tick's.
    pub fn map(&mut self, state: &PathState, origin: &Point) -> PolarSetpoints {
        let (i, j) = self.plane;
        let polar = to_polar(
            self.cartesian(&state.position, origin),
            [state.velocity[i], state.velocity[j]],
            [state.acceleration[i], state.acceleration[j]],
            self.theta,
        );
        self.theta = polar.theta;
        let k = self.units_per_radian;
        PolarSetpoints {
            rotary: (
                self.rotary,
                MotionState {
                    p: polar.theta * k,
                    v: polar.omega * k,
                    a: polar.alpha * k,
                },
            ),
            feed: (
                self.feed,
                MotionState {
                    p: polar.r,
                    v: polar.r_dot,
                    a: polar.r_ddot,
                },
            ),
        }
    }

    /// `p`, the members' positions less the origin, made group coordinates: the plane's two
    /// slots (θ and r less their origins) become the Cartesian point less the origin.
    pub fn cartesian_from_members(self, p: &mut Point, origin: &Point) {
        let theta = (p[self.rotary] + origin[self.rotary]) / self.units_per_radian;
        let [x, y] = from_polar(theta, p[self.feed] + origin[self.feed]);
        let (i, j) = self.plane;
        p[i] = x - origin[i];
        p[j] = y - origin[j];
    }

    /// The path limits of `segment` cut so that the rotary and the feed member keep within
    /// `rotary` and `feed` (their own limits): with b = the segment's bounds, the rotary turns
    /// at most v·b.dθ and accelerates at most v²·b.d²θ + a·b.dθ, the feed moves at most v and
    /// accelerates at most v²·b.d²r + a; half of each acceleration goes to each term.
    fn cut(
        &self,
        segment: &Segment,
        origin: &Point,
        limits: PathLimits,
        rotary: path::planner::AxisLimits,
        feed: path::planner::AxisLimits,
    ) -> Result<PathLimits, String> {
        let (i, j) = self.plane;
        let b = polar_bounds(
            segment,
            self.plane,
            (origin[i], origin[j]),
            self.queued_theta,
        )
        .map_err(|e| e.to_string())?;
        let omega = rotary.velocity / self.units_per_radian.abs();
        let alpha = rotary.acceleration / self.units_per_radian.abs() / 2.0;
        let over = |limit: f64, rate: f64| {
            if rate > 0.0 {
                limit / rate
            } else {
                f64::INFINITY
            }
        };
        let velocity = limits
            .velocity
            .min(feed.velocity)
            .min(over(omega, b.dtheta))
            .min(over(alpha, b.d2theta).sqrt())
            .min(over(feed.acceleration / 2.0, b.d2r).sqrt());
        let acceleration = (feed.acceleration / 2.0).min(over(alpha, b.dtheta));
        Ok(PathLimits {
            velocity,
            acceleration: limits.acceleration.min(acceleration),
            deceleration: limits.deceleration.min(acceleration),
            jerk: limits.jerk,
        })
    }
}

impl Group {
    /// `group_set_polar_transform`: the group must hold no motion (the planner's coordinates
    /// change meaning), the rotary and the feed axis are the members of the plane's two
    /// coordinates. θ starts on the rotary axis's position, so no whole turn is undone.
    pub(super) fn set_polar(
        &mut self,
        axes: &[Axis],
        c: &GroupSetPolarTransform,
    ) -> Result<Reply, EngineError> {
        self.check_polar_change("set the polar transform while it holds a motion")?;
        let dims = self.dims();
        let [i, j] = c.plane.unwrap_or([0, 1]);
        if i == j || i >= dims || j >= dims {
            return Err(EngineError::InvalidPath {
                group: self.id,
                reason: format!(
                    "plane [{i}, {j}] needs two different coordinates of the group's {dims}"
                ),
            });
        }
        let slot = |a| self.members.iter().position(|&m| m == a);
        let (rotary, feed) = match (slot(c.rotary), slot(c.feed)) {
            (Some(r), Some(f)) if r != f && [r, f].contains(&i) && [r, f].contains(&j) => (r, f),
            _ => {
                return Err(EngineError::InvalidGroup {
                    group: self.id,
                    reason: format!(
                        "the rotary ({}) and the feed axis ({}) must be the members of plane coordinates {i} and {j}",
                        c.rotary, c.feed
                    ),
                })
            }
        };
        let units_per_radian = bounded("rotary_units_per_radian", c.rotary_units_per_radian)?;
        if units_per_radian == 0.0 {
            return Err(EngineError::InvalidPath {
                group: self.id,
                reason: "rotary_units_per_radian must not be 0".into(),
            });
        }
        let mut polar = PolarMachine {
            plane: (i, j),
            rotary,
            feed,
            units_per_radian,
            theta: 0.0,
            queued_theta: 0.0,
        };
        polar.resync(&self.members, axes);
        self.polar = Some(polar);
        self.push_axis_limits(axes);
        Ok(Reply::Done)
    }

    /// `group_delete_polar_transform`: the members are Cartesian again.
    pub(super) fn delete_polar(&mut self, axes: &[Axis]) -> Result<Reply, EngineError> {
        if self.polar.is_some() {
            self.check_polar_change("delete the polar transform while it holds a motion")?;
            self.polar = None;
            self.push_axis_limits(axes);
        }
        Ok(Reply::Done)
    }

    fn check_polar_change(&self, action: &'static str) -> Result<(), EngineError> {
        if self.is_idle() && !self.feeding {
            Ok(())
        } else {
            Err(self.state_error(action))
        }
    }

    /// The path limits of a motion on `segment` under the polar transform (unchanged without
    /// it); a segment through the pole is refused.
    pub(super) fn polar_limits(
        &self,
        axes: &[Axis],
        segment: &Segment,
        limits: PathLimits,
    ) -> Result<PathLimits, EngineError> {
        let Some(polar) = &self.polar else {
            return Ok(limits);
        };
        let member = |k: usize| {
            self.members
                .get(k)
                .and_then(|&a| axes.get(usize::from(a)))
                .map(axis_limits)
        };
        let (Some(rotary), Some(feed)) = (member(polar.rotary), member(polar.feed)) else {
            return Ok(limits);
        };
        polar
            .cut(segment, &self.origin, limits, rotary, feed)
            .map_err(|reason| EngineError::InvalidPath {
                group: self.id,
                reason,
            })
    }

    /// A motion ending at `end` was queued: the next one starts at its angle.
    pub(super) fn polar_queued(&mut self, end: &Point) {
        if let Some(polar) = &mut self.polar {
            let [x, y] = polar.cartesian(end, &self.origin);
            polar.queued_theta = unwrapped_angle(x, y, polar.queued_theta);
        }
    }

    /// At rest before a path starts: θ from the rotary member's position (it may have been
    /// moved or re-based between paths).
    pub(super) fn polar_resync(&mut self, axes: &[Axis]) {
        if let Some(polar) = &mut self.polar {
            polar.resync(&self.members, axes);
        }
    }
}

impl PolarMachine {
    fn resync(&mut self, members: &[crate::command::AxisIndex], axes: &[Axis]) {
        let position = members
            .get(self.rotary)
            .and_then(|&a| axes.get(usize::from(a)))
            .map_or(0.0, |a| a.commanded().p);
        self.theta = position / self.units_per_radian;
        self.queued_theta = self.theta;
    }

    /// The plane's two slots, whose planner limits are the feed axis's (X and Y are in its
    /// units).
    pub fn feed_slot(&self) -> usize {
        self.feed
    }

    pub fn plane_slots(&self) -> [usize; 2] {
        [self.plane.0, self.plane.1]
    }
}
