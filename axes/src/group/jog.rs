//! Group jogs (HIMC JogGroup and JogGroupAxis, digest 004 §8.2.7–8.2.8): the whole group moves
//! along one fixed direction in group coordinates — one coordinate of a coordinate system, or
//! one member — at a signed velocity, until it is stopped.
//!
//! A jog runs beside the path planner, which stays idle meanwhile: a 1-D
//! [`crate::profile::Profile`] towards a velocity goal along the jog coordinate `s` is planned
//! when a jog command (or a stop, a halt, an override) arrives, from the state fed last, and
//! each tick only samples it (one sample, then each member gets `origin + s·direction`). The
//! limits along `s` are the group's acceleration, deceleration and jerk, cut so that no member
//! exceeds its own velocity, acceleration or jerk (docs/decisions.md, "Group jog").

use path::geometry::{Line, Segment};
use path::planner::{AxisLimits, PathLimits};
use path::{Point, MAX_AXES};

use super::tick::follow;
use super::{Env, Group};
use crate::command::{bounded, CommandId, CommandState, CoordinateSystem, EngineError, Reply};
use crate::profile::{Goal, Limits, MotionState, Options, Profile};
use crate::status::{GroupFault, GroupState};

/// A jog in progress.
#[derive(Clone, Debug)]
pub(super) struct Jog {
    /// The jog command running (a new jog takes its place).
    pub id: CommandId,
    /// Group coordinates where `s` = 0.
    origin: Point,
    /// Group coordinates per unit of `s`.
    direction: Point,
    /// Limits along `s` (see [`Group::jog_limits`]).
    limits: Limits,
    /// The largest acceleration along `s` the members allow (a stop's deceleration is cut
    /// to it).
    members_acceleration: f64,
    /// The commanded signed velocity, before the override.
    velocity: f64,
    profile: Profile,
    /// Seconds into `profile`, and its segment cursor.
    t: f64,
    cursor: usize,
    /// The state along `s` fed last (a new plan starts there).
    last: MotionState,
    /// Ends at rest, with this state of its command (a stop, a halt, a jog at velocity 0).
    ending: Option<CommandState>,
}

impl Jog {
    /// The signed velocity along the jog coordinate fed last.
    pub fn velocity(&self) -> f64 {
        self.last.v
    }

    pub fn acceleration(&self) -> f64 {
        self.last.a
    }

    /// Group coordinates per unit of the jog coordinate.
    pub fn direction(&self) -> &Point {
        &self.direction
    }

    /// The length along the jog coordinate travelled from now to rest when a stop with
    /// `deceleration` is issued `delay` seconds from now (`Group::stop_jog` cuts it to the
    /// members' own acceleration): until then the jog may still speed up (by at most its
    /// acceleration limit), then it brakes.
    pub fn stopping_distance(&self, delay: f64, deceleration: f64) -> f64 {
        let sign = if self.last.v < 0.0 { -1.0 } else { 1.0 };
        let delay = delay.max(0.0);
        let a = self.last.a * sign;
        let a1 = if self.limits.jerk.is_finite() {
            (a.max(0.0) + self.limits.jerk * delay).min(self.limits.acceleration.max(a))
        } else {
            a.max(0.0)
        };
        let v1 = self.last.v.abs() + a1 * delay;
        v1 * delay
            + path::planner::braking_distance(
                v1,
                a1,
                deceleration.min(self.members_acceleration),
                self.limits.jerk,
            )
    }

    /// Plan from the state fed last to the signed velocity `target` with `limits`.
    fn replan(&mut self, target: f64, limits: Limits) -> Result<(), String> {
        let limits = Limits {
            // A velocity goal beyond `velocity` is cut to it; the velocity also scales the
            // planner's units, so it must be positive even for a ramp to rest.
            velocity: if limits.velocity.is_finite() {
                limits.velocity
            } else {
                target.abs().max(self.last.v.abs()).max(1.0)
            },
            ..limits
        };
        let start = MotionState {
            a: self.last.a,
            ..self.last
        };
        self.profile = Profile::plan(
            start,
            Goal::Velocity { target },
            &limits,
            &Options::default(),
        )
        .map_err(|e| e.to_string())?;
        self.t = 0.0;
        self.cursor = 0;
        Ok(())
    }
}

/// The smallest of `group` and each member's `own / |direction_k|` (the limit along `s` that
/// keeps every member within its own).
fn along(direction: &Point, dims: usize, group: f64, own: impl Fn(usize) -> f64) -> f64 {
    direction
        .iter()
        .take(dims)
        .enumerate()
        .filter(|(_, d)| **d != 0.0)
        .map(|(k, d)| own(k) / d.abs())
        .fold(group, f64::min)
}

impl Group {
    /// `group_jog`: the direction of coordinate `coordinate` of `system` (default: the
    /// selected one) in group coordinates, at the members' present position. Exact for a rigid
    /// frame's translations; orientation coordinates of a rotated frame and NMC's XYZA move
    /// along the direction they have where the jog starts (docs/decisions.md, "Group jog").
    pub(super) fn coordinate_direction(
        &self,
        env: &Env,
        coordinate: usize,
        system: Option<CoordinateSystem>,
    ) -> Result<Point, EngineError> {
        let unit = self.unit(coordinate, "coordinate")?;
        let map = self.frame_map(env, system)?;
        let here = self.current_position(env.axes);
        let from = map.point_from_machine(&here);
        let mut to = from;
        for (t, u) in to.iter_mut().zip(unit) {
            *t += u;
        }
        let invalid = |reason: String| EngineError::InvalidPath {
            group: self.id,
            reason,
        };
        let line = Line::new(from, to, self.dims()).map_err(|e| invalid(e.to_string()))?;
        let moved = map.segment_to_machine(self.id, here, Segment::Line(line), self.dims())?;
        let mut direction = moved.end();
        for (d, h) in direction.iter_mut().zip(here) {
            *d -= h;
        }
        Ok(direction)
    }

    /// The unit vector of coordinate `k` (`group_jog_axis`: member `k`); refused beyond the
    /// group's coordinates (digest 004 TV 54).
    pub(super) fn unit(&self, k: usize, name: &'static str) -> Result<Point, EngineError> {
        let mut unit = [0.0; MAX_AXES];
        match unit.get_mut(k).filter(|_| k < self.dims()) {
            Some(u) => *u = 1.0,
            None => {
                return Err(EngineError::InvalidArgument {
                    name,
                    value: k as f64,
                    reason: "must be below the group's number of coordinates",
                })
            }
        }
        Ok(unit)
    }

    /// Start a jog along `direction` at the signed `velocity`, or change the running jog's
    /// velocity (a ramp from the present one). Only from Standby or while jogging: a jog
    /// while a path runs is refused (docs/decisions.md, "Group jog").
    pub(super) fn jog(
        &mut self,
        env: &mut Env,
        direction: Point,
        velocity: f64,
    ) -> Result<Reply, EngineError> {
        let velocity = bounded("velocity", velocity)?;
        if self.polar.is_some() {
            return Err(self.state_error(
                "jog under the polar transform (its members do not move along a coordinate)",
            ));
        }
        match self.state {
            GroupState::Standby => {}
            GroupState::Moving if self.jog.is_some() => {}
            GroupState::Moving | GroupState::Halted => {
                return Err(EngineError::GroupState {
                    group: self.id,
                    state: self.state,
                    action: "jog while a path runs (stop it first)",
                })
            }
            GroupState::Disabled | GroupState::Stopping | GroupState::ErrorStop => {
                return Err(EngineError::GroupState {
                    group: self.id,
                    state: self.state,
                    action: "jog",
                })
            }
        }
        let (limits, members_acceleration) = self.jog_limits(env, &direction);
        let previous = self.jog.take();
        let mut next = match &previous {
            // The same direction: the velocity changes by a ramp from the present state.
            Some(jog) if jog.direction == direction => jog.clone(),
            Some(_) => {
                self.jog = previous;
                return Err(EngineError::GroupState {
                    group: self.id,
                    state: self.state,
                    action: "jog along another coordinate while a jog runs (stop it first)",
                });
            }
            None if velocity == 0.0 => {
                // Nothing to stop: done at once.
                let id = env.ledger.allocate();
                env.ledger.finish(id, CommandState::Done);
                return Ok(Reply::Accepted { id });
            }
            None => Jog {
                id: 0,
                origin: self.current_position(env.axes),
                direction,
                limits,
                members_acceleration,
                velocity: 0.0,
                profile: Profile::hold(0.0),
                t: 0.0,
                cursor: 0,
                last: MotionState::default(),
                ending: None,
            },
        };
        next.limits = limits;
        next.members_acceleration = members_acceleration;
        next.velocity = velocity;
        next.ending = (velocity == 0.0).then_some(CommandState::Done);
        if let Err(reason) = next.replan(velocity * self.override_factor, limits) {
            // A running jog goes on as it was planned.
            self.jog = previous;
            return Err(EngineError::InvalidPath {
                group: self.id,
                reason,
            });
        }
        next.id = env.ledger.allocate();
        if let Some(old) = previous {
            env.ledger.finish(old.id, CommandState::Aborted);
        }
        let id = next.id;
        self.jog = Some(next);
        self.state = GroupState::Moving;
        Ok(Reply::Accepted { id })
    }

    /// The limits along a jog `direction`: the group's acceleration, deceleration and jerk
    /// (the result axis's with one, as for motions; the angular profile's for a jog that only
    /// turns orientation coordinates, HIMC A, B, C), each cut so that no member exceeds its
    /// own limit; the velocity is only the members' bound. Also the members' own bound on the
    /// acceleration.
    fn jog_limits(&self, env: &Env, direction: &Point) -> (Limits, f64) {
        let turns_only = !self.orientation.is_empty()
            && direction
                .iter()
                .take(self.dims())
                .enumerate()
                .all(|(k, d)| *d == 0.0 || self.orientation.contains(k));
        let group: PathLimits = if turns_only {
            self.angular
        } else {
            self.motion_defaults(env.axes)
        };
        let own = self.planner.config().axes;
        let member = |k: usize, f: fn(&AxisLimits) -> f64| own.get(k).map_or(f64::INFINITY, f);
        let dims = self.dims();
        let acceleration = |g: f64| along(direction, dims, g, |k| member(k, |l| l.acceleration));
        let limits = Limits {
            velocity: along(direction, dims, f64::INFINITY, |k| {
                member(k, |l| l.velocity)
            }),
            acceleration: acceleration(group.acceleration),
            deceleration: acceleration(group.deceleration),
            jerk: along(direction, dims, group.jerk, |k| member(k, |l| l.jerk)),
        };
        (limits, acceleration(f64::INFINITY))
    }

    /// Ramp the running jog to rest with `deceleration` (along the jog coordinate, cut to the
    /// members' own); its command ends `aborted` at rest. False when no jog runs.
    pub(super) fn stop_jog(&mut self, deceleration: f64) -> bool {
        let Some(jog) = &mut self.jog else {
            return false;
        };
        let limits = Limits {
            deceleration: deceleration.min(jog.members_acceleration),
            ..jog.limits
        };
        jog.ending = Some(CommandState::Aborted);
        if jog.replan(0.0, limits).is_err() {
            // Unreachable with positive limits; at worst the jog stops at once.
            jog.profile = Profile::hold(jog.last.p);
            jog.last.v = 0.0;
            jog.last.a = 0.0;
        }
        self.state = GroupState::Stopping;
        true
    }

    /// A new override while jogging: the jog ramps to its velocity × the new factor.
    pub(super) fn override_jog(&mut self) {
        let factor = self.override_factor;
        if let Some(jog) = self.jog.as_mut().filter(|j| j.ending.is_none()) {
            let limits = jog.limits;
            // Planned before with the same limits, so this plan succeeds; if not, the jog
            // keeps its old plan.
            let _ = jog.replan(jog.velocity * factor, limits);
        }
    }

    /// One tick of a jog: sample the plan, feed every member (and the result axis the length
    /// travelled); at rest after a stop, the jog ends and the group goes to Standby. A refused
    /// setpoint stops the group as any member's trouble does.
    pub(super) fn step_jog(&mut self, env: &mut Env) {
        let Some(jog) = &mut self.jog else {
            return;
        };
        jog.t += env.period;
        let s = jog.profile.sample_from(jog.t, &mut jog.cursor);
        let travelled = (s.p - jog.last.p).abs();
        jog.last = MotionState {
            p: s.p,
            v: s.v,
            a: s.a,
        };
        let at_rest = jog.t >= jog.profile.duration() && s.v == 0.0;
        let ending = jog.ending.filter(|_| at_rest);
        let (origin, direction) = (jog.origin, jog.direction);
        let path = MotionState {
            p: s.p,
            v: s.v,
            a: s.a,
        };
        if let Err((axis, error)) = self.feed_jog(env, &origin, &direction, path, travelled) {
            self.fault(
                env,
                GroupFault::Member {
                    axis,
                    error: error.kind(),
                },
            );
            return;
        }
        self.feeding = true;
        if let Some(state) = ending {
            if let Some(jog) = self.jog.take() {
                env.ledger.finish(jog.id, state);
            }
        }
    }

    /// Feed each member its point of the jog and the result axis the length travelled.
    fn feed_jog(
        &mut self,
        env: &mut Env,
        origin: &Point,
        direction: &Point,
        s: MotionState,
        travelled: f64,
    ) -> Result<(), (u16, EngineError)> {
        for (k, &a) in self.members.iter().enumerate() {
            let (Some(o), Some(d), Some(shift)) =
                (origin.get(k), direction.get(k), self.origin.get(k))
            else {
                continue;
            };
            let setpoint = MotionState {
                p: o + s.p * d + shift,
                v: s.v * d,
                a: s.a * d,
            };
            follow(env, a, setpoint)?;
        }
        // HMC's result axis (digest 000 §4.3) grows by the length travelled, whichever way.
        let Some(r) = &mut self.result else {
            return Ok(());
        };
        r.position += travelled;
        let sign = if s.v < 0.0 { -1.0 } else { 1.0 };
        let setpoint = MotionState {
            p: r.position,
            v: s.v.abs(),
            a: s.a * sign,
        };
        follow(env, r.axis, setpoint)
    }
}
