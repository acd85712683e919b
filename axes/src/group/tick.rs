//! A group's work in one tick (engine stage 2, before the other machine-level planners), and
//! the ways a path ends: done, dropped, or faulted.

use path::planner::{Motion, PathEvent, PathState, PlannerError};
use path::MAX_AXES;

use super::polar::PolarSetpoints;
use super::queue::{Entry, Item, Wait};
use super::{axis_limits, Env, Group, ResultAxis};
use crate::axis::{Feed, MotionAction, MotionSubmission, Overrides};
use crate::command::{
    CommandId, CommandKind, CommandState, EngineError, ErrorKind, PositionCondition,
    PositionSource, StopMode,
};
use crate::profile::MotionState;
use crate::status::{AxisState, GroupFault, GroupState};

/// The fault stop's slot of the result axis, after the members' (at most [`MAX_AXES`]).
pub(super) const RESULT_SLOT: usize = MAX_AXES;
/// Slots of a fault stop: the members and the result axis.
pub(super) const FAULT_STOP_SLOTS: usize = MAX_AXES + 1;

impl Group {
    /// One tick. Reads the members as the previous tick left them, the digital inputs (waits)
    /// and the members' parameter versions; writes the members' feeds for this tick, buffered
    /// outputs, single-axis moves started by the path, and the ledger. In order:
    ///
    /// 1. members' limits to the planner if a parameter changed;
    /// 2. a member in trouble → ErrorStop (the whole group stops);
    /// 3. a buffered wait the path stands at: met → go on, timed out → ErrorStop;
    /// 4. an aborting motion waiting for rest starts once the path is at rest;
    /// 5. nothing left: the members are let go (the tick after their last setpoint, so they
    ///    take it first), Moving/Stopping → Standby;
    /// 6. else the planner steps, its events are acted on, and every member is fed.
    pub(super) fn step(&mut self, env: &mut Env) {
        match self.state {
            GroupState::Disabled => return,
            GroupState::ErrorStop => {
                self.step_fault_stop(env);
                return;
            }
            _ => {}
        }
        if self.off_path {
            // Frozen at the break, the members elsewhere: nothing to feed until a move back.
            return;
        }
        self.refresh_limits(env.axes);
        if let Some(fault) = self.member_fault(env.axes) {
            if self.stops_along_path() {
                self.begin_fault_stop(env, fault);
                self.step_fault_stop(env);
            } else {
                self.fault(env, fault);
            }
            return;
        }
        if self.watch_stop_inputs(env) {
            return;
        }
        self.check_wait(env);
        if self.state == GroupState::ErrorStop {
            return;
        }
        if self.jog.is_some() {
            self.step_jog(env);
            return;
        }
        self.start_pending(env);
        self.advance_staging(env);
        if self.is_idle() {
            self.settle(env);
            return;
        }
        if self.staging.is_busy() && self.planner.is_idle() && !self.feeding {
            // A spline accepted at rest is still under construction: nothing moves yet.
            return;
        }
        self.follow_live_speed(env.axes);
        let mut events = std::mem::take(&mut self.events);
        events.clear();
        // The members are fed from the planner's state in place (not a copy of it each tick):
        // acting on the events does not touch the planner.
        self.planner.step(&mut events);
        for event in events.drain(..) {
            self.on_event(env, event);
        }
        self.events = events;
        self.fire_distance_outputs(env);
        if let Err((k, axis, error)) = self.feed(env) {
            let cause = GroupFault::Member {
                axis,
                error: error.kind(),
            };
            if self.stops_along_path() {
                let state = *self.planner.state();
                self.begin_fault_stop(env, cause);
                // This tick's point for the members after the one that refused it.
                self.feed_on_path(env, &state, k + 1);
            } else {
                self.fault(env, cause);
            }
            return;
        }
        self.feeding = true;
    }

    /// Nothing queued, waited for or pending, and the path at rest.
    pub(super) fn is_idle(&self) -> bool {
        self.planner.is_idle()
            && !self.staging.is_busy()
            && self.waiting.is_none()
            && self.pending.is_none()
            && self.jog.is_none()
    }

    /// Give the planner the members' limits again when one of their parameters changed (each
    /// tick, and before a motion is queued: the planner plans a motion when it is pushed).
    fn refresh_limits(&mut self, axes: &[crate::axis::Axis]) {
        let version = self
            .members
            .iter()
            .filter_map(|&a| axes.get(a as usize))
            .map(|a| a.params_version())
            .sum();
        if version == self.params_version {
            return;
        }
        self.params_version = version;
        self.push_axis_limits(axes);
    }

    /// Give the planner each member's own limits, every acceleration the smallest of them with
    /// `smallest_axis_acceleration` (CPU 226H, digest 003 §2.0 tip 3).
    pub(super) fn push_axis_limits(&mut self, axes: &[crate::axis::Axis]) {
        let member = |a: &u16| axes.get(usize::from(*a)).map(axis_limits);
        let smallest = self.smallest_acceleration.then(|| {
            self.members
                .iter()
                .filter_map(member)
                .map(|l| l.acceleration)
                .fold(f64::INFINITY, f64::min)
        });
        // Under the polar transform X and Y are in the feed axis's units: its limits hold for
        // both (the motion's own limits keep the two members within theirs, `polar`).
        let plane = self.polar.map(|p| (p.plane_slots(), p.feed_slot()));
        for (k, a) in self.members.iter().enumerate() {
            let a = match plane {
                Some((slots, feed)) if slots.contains(&k) => self.members.get(feed).unwrap_or(a),
                _ => a,
            };
            if let Some(mut limits) = member(a) {
                if let Some(acceleration) = smallest {
                    limits.acceleration = acceleration;
                }
                self.planner.set_axis_limits(k, limits);
            }
        }
    }

    /// The path is done: let the members go and return to Standby once every member's output
    /// has arrived (a smoothing window or command filter plays out after the path's last
    /// setpoint; digest 004 §2.14: the filters "modify PG commands", so the group still moves).
    fn settle(&mut self, env: &mut Env) {
        if self.feeding {
            self.release(env);
        }
        self.running = None;
        if self.members_arriving(env.axes) {
            return;
        }
        self.finish_arriving(env);
        if matches!(self.state, GroupState::Moving | GroupState::Stopping) {
            self.state = GroupState::Standby;
        }
    }

    /// A member's output is still behind its command (smoothing or a command filter).
    fn members_arriving(&self, axes: &[crate::axis::Axis]) -> bool {
        self.members
            .iter()
            .filter_map(|&a| axes.get(usize::from(a)))
            .any(|a| !a.output_settled())
    }

    /// The path's last motion, held until the members arrived, is done.
    fn finish_arriving(&mut self, env: &mut Env) {
        if let Some(id) = self.arriving.take() {
            env.ledger.finish(id, CommandState::Done);
        }
    }

    /// Stop feeding the members: each ramps to rest with its own `decel` (a member at rest
    /// simply stands) and is free of the feed. Ends a fault stop along the path too.
    pub(super) fn release(&mut self, env: &mut Env) {
        self.feeding = false;
        self.fault_stop = None;
        for a in self.bound_axes() {
            release_member(env, a);
        }
    }

    /// Feed every member this tick's point of the path (axis = group coordinate + origin; the
    /// polar transform's two members θ and r), then the result axis. A refusal names the slot
    /// (member coordinate, or [`RESULT_SLOT`]).
    fn feed(&mut self, env: &mut Env) -> Result<(), (usize, u16, EngineError)> {
        let state = self.planner.state();
        let polar = self.polar.as_mut().map(|p| p.map(state, &self.origin));
        // One pass over the members and the path's coordinates (this runs every tick).
        let (mut ctx, axes) = env.context();
        let coordinates = state
            .position
            .iter()
            .zip(&state.velocity)
            .zip(&state.acceleration)
            .zip(&self.origin);
        for (k, (&a, (((p, v), acc), o))) in self.members.iter().zip(coordinates).enumerate() {
            if let Some(axis) = axes.get_mut(usize::from(a)) {
                let setpoint = polar.and_then(|m| m.get(k)).unwrap_or(MotionState {
                    p: p + o,
                    v: *v,
                    a: *acc,
                });
                axis.feed(&mut ctx, Feed::Follow(setpoint))
                    .map_err(|e| (k, a, e))?;
            }
        }
        feed_result_axis(&mut self.result, self.length_ratio, env, state)
            .map_err(|(a, e)| (RESULT_SLOT, a, e))
    }

    /// Feed member `a` (group coordinate `k`) this tick's point of the path (`polar`: the
    /// polar transform's setpoints of this tick).
    fn feed_member(
        &self,
        env: &mut Env,
        state: &PathState,
        polar: Option<&PolarSetpoints>,
        k: usize,
        a: u16,
    ) -> Result<(), EngineError> {
        let (Some(p), Some(v), Some(acc), Some(o)) = (
            state.position.get(k),
            state.velocity.get(k),
            state.acceleration.get(k),
            self.origin.get(k),
        ) else {
            return Ok(());
        };
        let (mut ctx, axes) = env.context();
        let Some(axis) = axes.get_mut(a as usize) else {
            return Ok(());
        };
        let setpoint = polar.and_then(|m| m.get(k)).unwrap_or(MotionState {
            p: p + o,
            v: *v,
            a: *acc,
        });
        axis.feed(&mut ctx, Feed::Follow(setpoint))
    }

    /// HMC's rule applies to a member's trouble (see [`Group::begin_fault_stop`]):
    /// `fault_deceleration` is set and the path moves.
    fn stops_along_path(&self) -> bool {
        self.fault_deceleration.is_some()
            && self.feeding
            && self.planner.state().path_velocity > 0.0
    }

    /// A member in trouble stops the whole group and puts it in ErrorStop (issue 11 item 3).
    /// By default (NMC; HIMC §3.6: "the group drops out of sync") the path is dropped at once
    /// ([`Group::fault`]). With `fault_deceleration` set, HMC's rule (digest 000 §4.3, §6.1
    /// (b)/(c), §9 item 12: the whole interpolation is cancelled): the path decelerates to rest
    /// with max(group deceleration, fault_deceleration), the members still on it stay on it,
    /// and the member in trouble, which has left the path, stops on its own
    /// (docs/decisions.md, "Group safety").
    fn begin_fault_stop(&mut self, env: &mut Env, cause: GroupFault) {
        let fast = self.fault_deceleration.unwrap_or(0.0);
        let kind = self.enter_error_stop(cause);
        self.end_commands(env, CommandState::Error(kind));
        self.planner.resume();
        self.planner.stop(self.defaults.deceleration.max(fast));
        let mut left = [false; FAULT_STOP_SLOTS];
        if let GroupFault::Member { axis, .. } = cause {
            let k = self.members.iter().position(|&a| a == axis);
            let k = k.or((self.result_axis() == Some(axis)).then_some(RESULT_SLOT));
            if let Some(flag) = k.and_then(|k| left.get_mut(k)) {
                *flag = true;
                release_member(env, axis);
            }
        }
        self.fault_stop = Some(left);
    }

    /// One tick of HMC's fault stop (see [`Group::begin_fault_stop`]): the path decelerates and
    /// feeds the members still on it; a member that leaves it (its own limit, fault or stop)
    /// is let go; at rest every member is let go.
    fn step_fault_stop(&mut self, env: &mut Env) {
        let Some(mut left) = self.fault_stop else {
            return;
        };
        let result = self.result_axis().map(|a| (RESULT_SLOT, a));
        for (k, a) in self.members.iter().copied().enumerate().chain(result) {
            let on_path = env
                .axes
                .get(a as usize)
                .is_some_and(|x| x.state() == AxisState::SynchronizedMotion);
            if let (false, Some(flag @ false)) = (on_path, left.get_mut(k)) {
                *flag = true;
                release_member(env, a);
            }
        }
        self.fault_stop = Some(left);
        let everyone_left = left.iter().take(self.members.len()).all(|&l| l);
        // At rest: done, even where the stop ended at a buffered wait, which holds the planner
        // (its queue is not dropped there, and the wait is never released).
        let at_rest = self.planner.state().path_velocity == 0.0;
        if self.planner.is_idle() || at_rest || everyone_left {
            let mut events = std::mem::take(&mut self.events);
            events.clear();
            self.planner.abort(&mut events);
            self.events = events;
            self.release(env);
            return;
        }
        // The commands were ended when the trouble came: the planner's events are not acted on.
        let mut events = std::mem::take(&mut self.events);
        events.clear();
        let state = *self.planner.step(&mut events);
        events.clear();
        self.events = events;
        self.feed_on_path(env, &state, 0);
    }

    /// Feed this tick's point to the members from coordinate `from` on that are still on the
    /// path of a fault stop; one that refuses it leaves the path and is let go.
    fn feed_on_path(&mut self, env: &mut Env, state: &PathState, from: usize) {
        let Some(mut left) = self.fault_stop else {
            return;
        };
        // The polar setpoints once a tick: the member that refused this tick's point took them.
        let polar = if from == 0 {
            self.polar.as_mut().map(|p| p.map(state, &self.origin))
        } else {
            self.polar.map(|mut p| p.map(state, &self.origin))
        };
        for (k, &a) in self.members.iter().enumerate().skip(from) {
            if left.get(k) == Some(&false)
                && self.feed_member(env, state, polar.as_ref(), k, a).is_err()
            {
                if let Some(flag) = left.get_mut(k) {
                    *flag = true;
                }
                release_member(env, a);
            }
        }
        // The result axis follows the path's deceleration too (digest 000 §6.1 (b)).
        if from <= RESULT_SLOT && !left[RESULT_SLOT] {
            if let Err((a, _)) = feed_result_axis(&mut self.result, self.length_ratio, env, state) {
                left[RESULT_SLOT] = true;
                release_member(env, a);
            }
        }
        self.fault_stop = Some(left);
    }

    fn on_event(&mut self, env: &mut Env, event: PathEvent) {
        match event {
            PathEvent::Started { tag } => {
                // A motion queued while the members were still arriving: the one before is
                // done as far as the group goes.
                self.finish_arriving(env);
                let id = tag as CommandId;
                self.running = Some(id);
                self.segment += 1;
                if let Some(Entry {
                    item:
                        Item::Motion {
                            user_segment,
                            length_ratio,
                            speed_basis,
                        },
                    ..
                }) = self.queue.get(id)
                {
                    self.user_segment = *user_segment;
                    self.length_ratio = *length_ratio;
                    self.speed_basis = *speed_basis;
                }
            }
            PathEvent::Done { tag } => {
                let id = tag as CommandId;
                if self.queue.take(id).is_some() {
                    if self.planner.is_idle() && self.members_arriving(env.axes) {
                        // The path's end: done when the members' outputs get there.
                        self.arriving = Some(id);
                    } else {
                        env.ledger.finish(id, CommandState::Done);
                    }
                }
                if self.running == Some(id) {
                    self.running = None;
                }
            }
            PathEvent::Marker { tag, .. } => {
                let id = tag as CommandId;
                if let Some(entry) = self.queue.take(id) {
                    self.reach_marker(env, entry);
                }
            }
            PathEvent::Dropped { tag } => {
                let id = tag as CommandId;
                if self.queue.take(id).is_some() {
                    env.ledger.finish(id, CommandState::Aborted);
                }
                if self.running == Some(id) {
                    self.running = None;
                }
            }
            PathEvent::AtRest => {}
        }
    }

    /// The path reached a buffered command (issue 11 item 5).
    fn reach_marker(&mut self, env: &mut Env, entry: Entry) {
        let id = entry.id;
        let result = match &entry.item {
            Item::SetOutput { channel, value } => match env.outputs.get_mut(*channel as usize) {
                Some(out) => {
                    if *out != *value {
                        *out = *value;
                        env.outputs_changed = true;
                    }
                    Ok(())
                }
                None => Err(ErrorKind::InvalidChannel),
            },
            Item::AxisMove(c) => {
                let (mut ctx, axes) = env.context();
                match axes.get_mut(c.axis as usize) {
                    Some(axis) => axis
                        .submit(
                            &mut ctx,
                            MotionSubmission {
                                kind: CommandKind::MoveAbsolute,
                                action: MotionAction::MoveAbsolute {
                                    position: c.position,
                                },
                                overrides: Overrides {
                                    velocity: c.velocity,
                                    acceleration: c.acceleration,
                                    deceleration: c.deceleration,
                                    jerk: c.jerk,
                                },
                                buffer_mode: crate::command::BufferMode::Aborting,
                            },
                        )
                        .map(|_| ())
                        .map_err(|e| e.kind()),
                    None => Err(ErrorKind::InvalidAxis),
                }
            }
            Item::Dwell { .. }
            | Item::WaitInput { .. }
            | Item::WaitPosition { .. }
            | Item::CornerStop { .. } => {
                self.corner_released = false;
                self.waiting = Some(Wait {
                    id,
                    item: entry.item,
                    since: env.tick,
                });
                return;
            }
            Item::Motion { .. } => Ok(()),
            Item::Io { .. } => {
                if let Item::Io { action, at } = entry.item {
                    self.reach_io(env, id, action, at);
                }
                return;
            }
        };
        match result {
            Ok(()) => env.ledger.finish(id, CommandState::Done),
            Err(kind) => {
                self.last_error = Some(kind);
                env.ledger.finish(id, CommandState::Error(kind));
            }
        }
    }

    /// A buffered wait: met → the path goes on; timed out → ErrorStop.
    fn check_wait(&mut self, env: &mut Env) {
        let Some(wait) = &self.waiting else {
            return;
        };
        let elapsed = env.tick.saturating_sub(wait.since);
        let (met, timeout) = match &wait.item {
            Item::Dwell { ticks } => (elapsed >= *ticks, None),
            Item::WaitInput {
                channel,
                level,
                timeout,
            } => (env.di.get(*channel as usize) == Some(level), *timeout),
            Item::WaitPosition {
                axis,
                position,
                tolerance,
                timeout,
                condition,
                source,
            } => (
                env.axes.get(*axis as usize).is_some_and(|a| {
                    let at = match source {
                        Some(PositionSource::Commanded) => a.commanded().p,
                        Some(PositionSource::Actual) | None => a.actual_position(),
                    };
                    match condition {
                        PositionCondition::Within => (at - position).abs() <= *tolerance,
                        PositionCondition::AtMost => at <= *position,
                        PositionCondition::AtLeast => at >= *position,
                    }
                }),
                *timeout,
            ),
            Item::CornerStop { .. } => (std::mem::take(&mut self.corner_released), None),
            Item::Motion { .. } | Item::SetOutput { .. } | Item::AxisMove(_) | Item::Io { .. } => {
                (true, None)
            }
        };
        let id = wait.id;
        if met {
            self.waiting = None;
            self.planner.release_hold();
            env.ledger.finish(id, CommandState::Done);
        } else if timeout.is_some_and(|t| elapsed >= t) {
            self.fault(env, GroupFault::WaitTimeout { command: id });
        }
    }

    /// An aborting motion accepted while the path moved starts once it is at rest.
    fn start_pending(&mut self, env: &mut Env) {
        if !(self.planner.is_idle() && self.waiting.is_none()) {
            return;
        }
        let Some(pending) = self.pending.take() else {
            return;
        };
        if let Err(e) = self.place_motion(env, Some(pending.id), pending.request) {
            self.last_error = Some(e.kind());
            env.ledger.finish(pending.id, CommandState::Error(e.kind()));
        }
    }

    /// Append a motion's segment (and its counted length share), built from the queue's end,
    /// to the planner and the mirror.
    pub(super) fn enqueue_segment(
        &mut self,
        env: &mut Env,
        id: CommandId,
        segment: path::geometry::Segment,
        share: super::segment::Share,
        request: &super::segment::PathRequest,
    ) -> Result<(), EngineError> {
        self.refresh_limits(env.axes);
        self.queue_corner_stop(env, &segment)?;
        let speed_basis = if request.velocity_given {
            None
        } else {
            self.result_speed(env.axes)
        };
        let join = self.merged_join(env.axes, request.join, &segment);
        let mergeable = self.merge_eligible && super::merge::mergeable(&segment);
        let limits = self.polar_limits(env.axes, &segment, share.limits)?;
        let end = segment.end();
        self.planner
            .push_motion(Motion {
                segment,
                limits,
                join,
                transition: request.transition,
                tag: u64::from(id),
            })
            .map_err(|e| self.planner_error(e))?;
        self.last_mergeable = mergeable;
        self.polar_queued(&end);
        self.queue.push(Entry {
            id,
            item: Item::Motion {
                user_segment: request.user_segment,
                length_ratio: share.ratio,
                speed_basis,
            },
        });
        Ok(())
    }

    /// At rest with nothing queued: the path starts where the members are.
    pub(super) fn sync_position(&mut self, env: &Env) -> Result<(), EngineError> {
        if self.planner.is_idle() && self.waiting.is_none() {
            self.polar_resync(env.axes);
            let here = self.current_position(env.axes);
            self.planner
                .reset_position(here)
                .map_err(|e| self.planner_error(e))?;
            let travelled = self.planner.state().travelled;
            if let Some(r) = &mut self.result {
                if let Some(axis) = env.axes.get(r.axis as usize) {
                    r.position = axis.commanded().p;
                }
                r.travelled = travelled;
            }
        }
        Ok(())
    }

    pub(super) fn planner_error(&self, e: PlannerError) -> EngineError {
        match e {
            PlannerError::QueueFull { capacity } => EngineError::GroupQueueFull {
                group: self.id,
                capacity: capacity as u32,
            },
            PlannerError::Invalid(reason) => EngineError::InvalidPath {
                group: self.id,
                reason: reason.to_string(),
            },
        }
    }

    /// Drop the path at once (the planner's abort), end every command the group holds
    /// (`running` with `running_state`, the rest aborted) and let the members go.
    pub(super) fn drop_all(&mut self, env: &mut Env, running_state: CommandState) {
        self.off_path = false;
        let mut events = std::mem::take(&mut self.events);
        events.clear();
        self.planner.abort(&mut events);
        self.events = events;
        self.end_commands(env, running_state);
        self.release(env);
    }

    /// End every command the group holds: `running` (and a wait in progress) with
    /// `running_state`, the rest aborted.
    fn end_commands(&mut self, env: &mut Env, running_state: CommandState) {
        self.finish_arriving(env);
        if let Some(id) = self.running.take() {
            if self.queue.take(id).is_some() {
                env.ledger.finish(id, running_state);
            }
        }
        if let Some(wait) = self.waiting.take() {
            env.ledger.finish(wait.id, running_state);
        }
        for entry in self.queue.drain() {
            env.ledger.finish(entry.id, CommandState::Aborted);
        }
        if let Some(p) = self.pending.take() {
            env.ledger.finish(p.id, CommandState::Aborted);
        }
        self.abort_staged(env);
        if let Some(jog) = self.jog.take() {
            env.ledger.finish(jog.id, running_state);
        }
        self.drop_distance_outputs(env, CommandState::Aborted);
    }

    /// The whole group stops and goes to ErrorStop with `cause` (issue 11 item 3). The path is
    /// dropped at once and each member ramps down with its own `decel` (no longer coordinated:
    /// one member already left the path). docs/decisions.md, "Axis groups".
    pub(super) fn fault(&mut self, env: &mut Env, cause: GroupFault) {
        let kind = self.enter_error_stop(cause);
        self.drop_all(env, CommandState::Error(kind));
    }

    /// ErrorStop with `cause` kept until a reset; the error kind the group's commands end with.
    fn enter_error_stop(&mut self, cause: GroupFault) -> ErrorKind {
        let kind = match cause {
            GroupFault::Member { error, .. } => error,
            GroupFault::EmergencyStop | GroupFault::WaitTimeout { .. } => ErrorKind::Fault,
        };
        self.state = GroupState::ErrorStop;
        self.fault = Some(cause);
        self.last_error = Some(kind);
        kind
    }

    /// The members' (and the result axis's) part of `group_emergency_stop`: each gets the
    /// single-axis emergency stop (`stop` with mode `emergency`: `fast_decel`, ESTOP latched
    /// until the axis is reset, NMC MtEstp, digest 001 TV19), so the group's reset waits for
    /// their resets.
    pub(super) fn emergency_stop_members(&mut self, env: &mut Env) {
        for a in self.bound_axes() {
            let (mut ctx, axes) = env.context();
            if let Some(axis) = axes.get_mut(a as usize) {
                // A stop without a deceleration never refuses.
                let _ = axis.stop(&mut ctx, StopMode::Emergency, None);
            }
        }
    }
}

/// Feed the result axis (if the group has one) its start plus the counted path length
/// travelled, and the path velocity and acceleration over the counted coordinates (digest 000
/// §4.3: "the result axis's EndPos grows by the path length"). The travel of one tick counts at
/// `ratio`, the ratio of the motion executing at its end: where a motion starts mid-tick after
/// one with another ratio, the error is at most one tick's travel times the difference of the
/// two ratios.
fn feed_result_axis(
    result: &mut Option<ResultAxis>,
    ratio: f64,
    env: &mut Env,
    state: &PathState,
) -> Result<(), (u16, EngineError)> {
    let Some(r) = result else {
        return Ok(());
    };
    r.position += (state.travelled - r.travelled) * ratio;
    r.travelled = state.travelled;
    let setpoint = MotionState {
        p: r.position,
        v: state.path_velocity * ratio,
        a: state.path_acceleration * ratio,
    };
    follow(env, r.axis, setpoint)
}

/// Feed axis `a` (a member or the result axis) `setpoint`; a refusal names the axis.
pub(super) fn follow(
    env: &mut Env,
    a: u16,
    setpoint: MotionState,
) -> Result<(), (u16, EngineError)> {
    let (mut ctx, axes) = env.context();
    match axes.get_mut(a as usize) {
        Some(axis) => axis
            .feed(&mut ctx, Feed::Follow(setpoint))
            .map_err(|e| (a, e)),
        None => Ok(()),
    }
}

/// Let member `a` go of the feed: it ramps to rest with its own `decel` (release never
/// fails: it only ends a feed).
fn release_member(env: &mut Env, a: u16) {
    let (mut ctx, axes) = env.context();
    if let Some(axis) = axes.get_mut(a as usize) {
        let _ = axis.feed(&mut ctx, Feed::Release);
    }
}
