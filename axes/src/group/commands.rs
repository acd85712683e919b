//! Group commands (issue 11 items 1, 3, 5, 8): each checked completely before it changes
//! anything, so a refused command leaves the group (and every other) as it was.

use path::planner::{CornerAngles, MarkerKind, MergeRule, PathPlanner};
use path::MAX_AXES;

use super::frames::FrameMap;
use super::queue::{GroupQueue, Item};
use super::segment::{self, CircularFields, PathRequest, PendingMotion};
use super::{
    planner_config, Env, Group, GroupFrames, Groups, ResultAxis, DEFAULT_ANGULAR_LIMITS,
    DEFAULT_PATH_LIMITS,
};
use crate::command::{
    bounded, finite, nonnegative, positive, AxisIndex, CommandState, CoordinateSystem, EngineError,
    GroupAxisMove, GroupCommand, GroupCreate, GroupDwell, GroupId, GroupParameter, GroupSetOutput,
    GroupWaitInput, GroupWaitPosition, Reply,
};
use crate::config::MAX_GROUP_QUEUE;
use crate::param::ParamId;
use crate::status::{AxisState, GroupFault, GroupState, InterferenceStatus};

/// The path velocity override is below this (NMC CrdSetOverride: (0, 10), TV 51).
pub const MAX_OVERRIDE: f64 = 10.0;

impl Groups {
    /// Apply one group command at the current tick.
    pub(crate) fn apply(
        &mut self,
        env: &mut Env,
        command: GroupCommand,
    ) -> Result<Reply, EngineError> {
        let id = command.group();
        match command {
            GroupCommand::Create(c) => self.create(env, c),
            GroupCommand::Delete(c) => self.delete(env, c.group),
            GroupCommand::ProtectionEnable(c) => self.enable_protection(c),
            GroupCommand::ProtectionDisable(c) => self.disable_protection(c.protection),
            GroupCommand::BufferedHalt(c) if self.get(c.target).is_none() => {
                Err(EngineError::UnknownGroup { group: c.target })
            }
            other => {
                let Some(id) = id else {
                    return Ok(Reply::Done);
                };
                let g = self.get_mut(id)?;
                let result = g.apply(env, other);
                if let Err(e) = &result {
                    // The group's status shows its last refusal, as an axis's does.
                    g.last_error = Some(e.kind());
                }
                result
            }
        }
    }

    fn create(&mut self, env: &mut Env, c: GroupCreate) -> Result<Reply, EngineError> {
        let group = c.group;
        let invalid = |reason: String| EngineError::InvalidGroup { group, reason };
        if self.get(group).is_some() {
            return Err(invalid("exists already".into()));
        }
        if self.groups.len() >= usize::from(self.config.max_groups) {
            return Err(invalid(format!(
                "at most {} groups may exist at once ([groups] max_groups)",
                self.config.max_groups
            )));
        }
        if c.axes.is_empty() || c.axes.len() > MAX_AXES {
            return Err(invalid(format!(
                "a group has 1 to {MAX_AXES} axes, not {}",
                c.axes.len()
            )));
        }
        for (k, &a) in c.axes.iter().enumerate() {
            check_joins(env, group, a, "axis")?;
            if c.axes.get(..k).is_some_and(|before| before.contains(&a)) {
                return Err(invalid(format!("axis {a} is listed twice")));
            }
        }
        if let Some(r) = c.result_axis {
            // HMC's result axis (合轴, digest 000 §4.3) measures the members' path: another axis.
            if c.axes.contains(&r) {
                return Err(invalid(format!(
                    "axis {r} is a member: the result axis is another axis, which travels the \
                     path length"
                )));
            }
            check_joins(env, group, r, "result axis")?;
        }
        if let Some(k) = c.orientation.iter().find(|&k| k >= c.axes.len()) {
            return Err(invalid(format!(
                "orientation coordinate {k} is not one of the group's {}",
                c.axes.len()
            )));
        }
        let capacity = c.queue_capacity.unwrap_or(self.config.queue_capacity);
        if !(1..=MAX_GROUP_QUEUE).contains(&capacity) {
            return Err(EngineError::InvalidArgument {
                name: "queue_capacity",
                value: f64::from(capacity),
                reason: "must be 1 to 1024",
            });
        }
        let lookahead = c.lookahead.unwrap_or(self.config.lookahead.min(capacity));
        if !(1..=capacity).contains(&lookahead) {
            return Err(EngineError::InvalidArgument {
                name: "lookahead",
                value: f64::from(lookahead),
                reason: "must be 1 to the queue capacity",
            });
        }
        let config = planner_config(&c.axes, env.axes, env.period, capacity, lookahead);
        let mut g = Group {
            id: group,
            members: c.axes,
            result: c.result_axis.map(|axis| ResultAxis {
                axis,
                position: 0.0,
                travelled: 0.0,
            }),
            length_ratio: 1.0,
            speed_basis: None,
            state: GroupState::Disabled,
            planner: PathPlanner::new(config, [0.0; MAX_AXES]).map_err(|e| {
                EngineError::InvalidPath {
                    group,
                    reason: e.to_string(),
                }
            })?,
            queue: GroupQueue::new(capacity),
            origin: [0.0; MAX_AXES],
            frames: GroupFrames::default(),
            polar: None,
            defaults: DEFAULT_PATH_LIMITS,
            orientation: c.orientation,
            angular: DEFAULT_ANGULAR_LIMITS,
            fault_deceleration: None,
            fault_stop: None,
            off_path: false,
            return_motion: None,
            smallest_acceleration: false,
            override_factor: 1.0,
            feeding: false,
            running: None,
            arriving: None,
            segment: 0,
            user_segment: 0,
            waiting: None,
            pending: None,
            last_mergeable: false,
            merge_eligible: true,
            corner_stop: None,
            last_direction: None,
            corner_released: false,
            staging: super::staging::Staging::new(self.config.spline_spans_per_tick),
            jog: None,
            last_error: None,
            fault: None,
            params_version: 0,
            events: Vec::new(),
            interference: (InterferenceStatus::NotEnabled, 0.0),
            buffered_io: Default::default(),
        };
        if g.result.is_some() {
            // HMC's merge angles are on by default (digest 000 §3.4, TV 38: π/6 and π/2), and
            // its merge rules (§10.6 (8), no ripple suppression).
            let _ = g.planner.set_corner_angles(Some(CornerAngles::HMC_DEFAULT));
            let _ = g.planner.set_merge_rule(Some(MergeRule::HMC_DEFAULT));
        }
        g.params_version = g
            .members
            .iter()
            .filter_map(|&a| env.axes.get(a as usize))
            .map(|a| a.params_version())
            .sum();
        for a in g.bound_axes() {
            if let Some(axis) = env.axes.get_mut(a as usize) {
                axis.set_group(Some(group));
            }
        }
        let at = self.groups.partition_point(|x| x.id < group);
        self.groups.insert(at, g);
        Ok(Reply::Done)
    }

    fn delete(&mut self, env: &mut Env, group: GroupId) -> Result<Reply, EngineError> {
        let g = self.get_mut(group)?;
        g.require(
            &[
                GroupState::Disabled,
                GroupState::Standby,
                GroupState::ErrorStop,
            ],
            "be deleted while its path runs",
        )?;
        g.drop_all(env, CommandState::Aborted);
        for a in g.bound_axes() {
            if let Some(axis) = env.axes.get_mut(a as usize) {
                axis.set_group(None);
            }
        }
        self.groups.retain(|x| x.id != group);
        self.forget_protections(group);
        Ok(Reply::Done)
    }
}

impl Group {
    fn apply(&mut self, env: &mut Env, command: GroupCommand) -> Result<Reply, EngineError> {
        let defaults = self.motion_defaults(env.axes);
        match command {
            GroupCommand::Create(_)
            | GroupCommand::Delete(_)
            | GroupCommand::ProtectionEnable(_)
            | GroupCommand::ProtectionDisable(_) => Ok(Reply::Done),
            GroupCommand::SetCoordinateTransform(c) => {
                self.frames.set_link(self.id, c.frame, c.pose)?;
                Ok(Reply::Done)
            }
            GroupCommand::SetCoordinateSystem(c) => {
                self.frames
                    .select(self.id, c.coordinate_system, self.dims(), env.axes)?;
                Ok(Reply::Done)
            }
            GroupCommand::SetRotaryTransform(c) => {
                self.frames.set_rotary(&c, &self.members, env.axes)?;
                Ok(Reply::Done)
            }
            GroupCommand::SetXyzaTransform(c) => {
                self.frames.set_xyza(&c, self.dims())?;
                Ok(Reply::Done)
            }
            GroupCommand::DeleteTransform(_) => {
                self.frames.delete_nmc();
                Ok(Reply::Done)
            }
            GroupCommand::SetPolarTransform(c) => self.set_polar(env.axes, &c),
            GroupCommand::DeletePolarTransform(_) => self.delete_polar(env.axes),
            GroupCommand::Jog(c) => {
                let direction =
                    self.coordinate_direction(env, c.coordinate, c.coordinate_system)?;
                self.jog(env, direction, c.velocity)
            }
            GroupCommand::JogAxis(c) => {
                let direction = self.unit(c.member, "member")?;
                self.jog(env, direction, c.velocity)
            }
            GroupCommand::Enable(_) => self.enable(env),
            GroupCommand::Disable(_) => {
                self.drop_all(env, CommandState::Aborted);
                self.state = GroupState::Disabled;
                self.fault = None;
                Ok(Reply::Done)
            }
            GroupCommand::Reset(_) => self.reset(env),
            GroupCommand::MoveLinearAbsolute(c) => {
                let mut r = segment::linear_absolute(self.id, self.dims(), &c, &defaults)?;
                r.frame = self.frame_map(env, c.coordinate_system)?;
                if self.off_path {
                    return self.return_to_break(env, r);
                }
                self.require_accepts_motion()?;
                self.submit(env, r)
            }
            GroupCommand::MoveLinearRelative(c) => {
                self.require_accepts_motion()?;
                let mut r = segment::linear_relative(self.id, self.dims(), &c, &defaults)?;
                r.frame = self.frame_map(env, c.coordinate_system)?;
                self.submit(env, r)
            }
            GroupCommand::MoveCircularAbsolute(c) => {
                self.require_accepts_motion()?;
                let f = CircularFields::from(&c);
                let mut r = segment::circular(self.id, self.dims(), f, &defaults)?;
                r.frame = self.frame_map(env, c.coordinate_system)?;
                self.submit(env, r)
            }
            GroupCommand::MoveSpline(c) => {
                self.require_accepts_motion()?;
                let mut r = segment::spline(self.id, self.dims(), &c, &defaults)?;
                r.frame = self.frame_map(env, c.coordinate_system)?;
                self.submit(env, r)
            }
            GroupCommand::MoveCircularAngle(c) => {
                self.require_accepts_motion()?;
                let mut r = segment::circular_angle(self.id, self.dims(), &c, &defaults)?;
                r.frame = self.frame_map(env, c.coordinate_system)?;
                self.submit(env, r)
            }
            GroupCommand::MoveEllipse(c) => {
                self.require_accepts_motion()?;
                let mut r = segment::ellipse(self.id, self.dims(), &c, &defaults)?;
                r.frame = self.frame_map(env, c.coordinate_system)?;
                self.submit(env, r)
            }
            GroupCommand::MoveCircularRelative(c) => {
                self.require_accepts_motion()?;
                let f = CircularFields::from(&c);
                let mut r = segment::circular(self.id, self.dims(), f, &defaults)?;
                r.frame = self.frame_map(env, c.coordinate_system)?;
                self.submit(env, r)
            }
            GroupCommand::Stop(c) => {
                let decel = match c.deceleration {
                    Some(d) => positive("deceleration", d)?,
                    None => defaults.deceleration,
                };
                self.stop(env, decel)
            }
            GroupCommand::Halt(c) => {
                let decel = match c.deceleration {
                    Some(d) => Some(positive("deceleration", d)?),
                    None => None,
                };
                self.halt(decel, defaults.deceleration)
            }
            GroupCommand::Continue(_) => self.resume(),
            GroupCommand::EmergencyStop(c) => {
                if c.keep_path && self.emergency_stop_keeping_path(env) {
                    return Ok(Reply::Done);
                }
                // An e-stop of each member plus the group in ErrorStop; a disabled group stays
                // Disabled (as with `emergency_stop_all`), its members e-stopped all the same.
                if self.state != GroupState::Disabled {
                    self.fault(env, GroupFault::EmergencyStop);
                }
                self.emergency_stop_members(env);
                Ok(Reply::Done)
            }
            GroupCommand::SetOverride(c) => {
                let f = finite("factor", c.factor)?;
                if !(f > 0.0 && f < MAX_OVERRIDE) {
                    return Err(EngineError::InvalidArgument {
                        name: "factor",
                        value: f,
                        reason: "must be in (0, 10) (1 = 100 %)",
                    });
                }
                self.override_factor = f;
                self.follow_live_speed(env.axes);
                self.override_jog();
                Ok(Reply::Done)
            }
            GroupCommand::SetOrigin(c) => {
                let offset = segment::coordinates(self.id, "offset", &c.offset, self.dims())?;
                if !self.is_idle() {
                    return Err(EngineError::GroupState {
                        group: self.id,
                        state: self.state,
                        action: "change its origin while a path is queued",
                    });
                }
                self.origin = offset;
                Ok(Reply::Done)
            }
            GroupCommand::SetParameter(c) => {
                let d = &mut self.defaults;
                match c.name {
                    GroupParameter::Velocity => {
                        d.velocity = positive("velocity", bounded("velocity", c.value)?)?
                    }
                    GroupParameter::Acceleration => {
                        d.acceleration = positive("acceleration", c.value)?
                    }
                    GroupParameter::Deceleration => {
                        d.deceleration = positive("deceleration", c.value)?
                    }
                    GroupParameter::Jerk => d.jerk = segment::jerk_value(c.value)?,
                    GroupParameter::AngularVelocity => {
                        self.angular.velocity = positive("value", bounded("value", c.value)?)?
                    }
                    GroupParameter::AngularAcceleration => {
                        self.angular.acceleration = positive("value", c.value)?
                    }
                    GroupParameter::AngularDeceleration => {
                        self.angular.deceleration = positive("value", c.value)?
                    }
                    GroupParameter::AngularJerk => {
                        self.angular.jerk = segment::jerk_value(c.value)?
                    }
                    GroupParameter::CornerSlowAngle | GroupParameter::CornerStopAngle => {
                        let value = finite("value", c.value)?;
                        let mut angles = self
                            .planner
                            .corner_angles()
                            .unwrap_or(CornerAngles::HMC_DEFAULT);
                        if c.name == GroupParameter::CornerSlowAngle {
                            angles.slow = value;
                        } else {
                            angles.stop = value;
                        }
                        self.check_merge_angles(&angles)?;
                        self.planner.set_corner_angles(Some(angles)).map_err(|_| {
                            EngineError::InvalidArgument {
                                name: "value",
                                value,
                                reason: "corner angles need 0 ≤ slow ≤ stop ≤ π radians",
                            }
                        })?;
                    }
                    GroupParameter::FaultDeceleration => {
                        self.fault_deceleration = off_or_positive(c.value)?;
                    }
                    GroupParameter::SmallestAxisAcceleration => {
                        let value = finite("value", c.value)?;
                        if value != 0.0 && value != 1.0 {
                            return Err(EngineError::InvalidArgument {
                                name: "value",
                                value,
                                reason: "must be 0 (off) or 1 (on)",
                            });
                        }
                        self.smallest_acceleration = value == 1.0;
                        self.push_axis_limits(env.axes);
                    }
                    GroupParameter::MergeSpeedTolerance | GroupParameter::Mergeable => {
                        self.set_merge_parameter(c.name, c.value)?
                    }
                    GroupParameter::CornerAcceleration
                    | GroupParameter::ArcAcceleration
                    | GroupParameter::ChordError => {
                        let setting = off_or_positive(c.value)?;
                        let mut limits = self.planner.lookahead_limits();
                        match c.name {
                            GroupParameter::CornerAcceleration => {
                                limits.corner_acceleration = setting
                            }
                            GroupParameter::ArcAcceleration => limits.arc_acceleration = setting,
                            _ => limits.chord_error = setting,
                        }
                        // Positive and finite here, so the planner accepts it.
                        let _ = self.planner.set_lookahead_limits(limits);
                    }
                    GroupParameter::ChordErrorRadius1
                    | GroupParameter::ChordErrorRadius2
                    | GroupParameter::ChordErrorBand1
                    | GroupParameter::ChordErrorBand2 => {
                        let value = off_or_positive(c.value)?;
                        let mut limits = self.planner.lookahead_limits();
                        let mut bands = limits.chord_error_bands.unwrap_or_default();
                        match c.name {
                            GroupParameter::ChordErrorRadius1 => {
                                bands.edges[0] = value.unwrap_or(0.0)
                            }
                            GroupParameter::ChordErrorRadius2 => {
                                bands.edges[1] = value.unwrap_or(0.0)
                            }
                            GroupParameter::ChordErrorBand1 => bands.errors[0] = value,
                            _ => bands.errors[1] = value,
                        }
                        limits.chord_error_bands = Some(bands);
                        // Errors off or positive, edges ≥ 0 and finite: the planner accepts it.
                        let _ = self.planner.set_lookahead_limits(limits);
                    }
                    GroupParameter::FourthCoordinateCornerVelocity => {
                        let setting = off_or_positive(c.value)?;
                        let mut limits = self.planner.lookahead_limits();
                        limits.corner_coordinate_velocity = setting.map(|v| (3, v));
                        // Positive and finite here, so the planner accepts it.
                        let _ = self.planner.set_lookahead_limits(limits);
                    }
                }
                Ok(Reply::Done)
            }
            GroupCommand::SetOutput(c) => {
                let item = self.output_item(env, &c)?;
                self.submit_marker(env, item, MarkerKind::PassThrough)
            }
            GroupCommand::Dwell(c) => {
                let item = dwell_item(env, &c)?;
                self.submit_marker(env, item, MarkerKind::Hold)
            }
            GroupCommand::WaitInput(c) => {
                let item = wait_input_item(env, &c)?;
                self.submit_marker(env, item, MarkerKind::Hold)
            }
            GroupCommand::WaitPosition(c) => {
                let item = wait_position_item(env, &c)?;
                self.submit_marker(env, item, MarkerKind::Hold)
            }
            GroupCommand::AxisMove(c) => {
                let item = self.axis_move_item(env, c)?;
                self.submit_marker(env, item, MarkerKind::PassThrough)
            }
            GroupCommand::PulseOutput(c) => {
                let item = self.pulse_output_item(env, &c)?;
                self.submit_marker(env, item, MarkerKind::PassThrough)
            }
            GroupCommand::SetAnalogOutput(c) => {
                let item = self.analog_output_item(env, &c)?;
                self.submit_marker(env, item, MarkerKind::PassThrough)
            }
            GroupCommand::StopInput(c) => {
                let item = self.stop_input_item(env, &c)?;
                self.submit_marker(env, item, MarkerKind::PassThrough)
            }
            GroupCommand::BufferedHalt(c) => {
                let item = self.buffered_halt_item(&c)?;
                self.submit_marker(env, item, MarkerKind::PassThrough)
            }
        }
    }

    /// Disabled → Standby when every member is enabled and at rest (PLCopen MC_GroupEnable).
    pub(super) fn enable(&mut self, env: &Env) -> Result<Reply, EngineError> {
        match self.state {
            GroupState::Disabled => {}
            GroupState::ErrorStop => {
                return Err(EngineError::GroupState {
                    group: self.id,
                    state: self.state,
                    action: "be enabled before a reset",
                })
            }
            _ => return Ok(Reply::Done),
        }
        if let Some((axis, state)) = self.member_not_ready(env.axes) {
            return Err(EngineError::GroupMember {
                group: self.id,
                axis,
                state,
                action: "enable the group",
            });
        }
        self.state = GroupState::Standby;
        self.fault = None;
        Ok(Reply::Done)
    }

    /// ErrorStop → Standby once every member is enabled and at rest (HIMC ResetGroup: "only
    /// after all errors are cleared"), or → Disabled when every member is disabled without a
    /// fault ([`Group::reset_target`]); other states: nothing to do.
    pub(super) fn reset(&mut self, env: &mut Env) -> Result<Reply, EngineError> {
        if self.state != GroupState::ErrorStop {
            return Ok(Reply::Done);
        }
        let target = self.reset_target(env.axes).map_err(|(axis, state)| {
            EngineError::GroupCauseStillPresent {
                group: self.id,
                axis,
                state,
            }
        })?;
        // An e-stop that kept the path: halted on it, to return and go on. Reset to Disabled
        // (every member disabled), the kept path is dropped: nothing could return to it.
        if self.off_path && target != GroupState::Standby {
            self.drop_all(env, CommandState::Aborted);
        }
        self.state = match target {
            GroupState::Standby if self.off_path => GroupState::Halted,
            other => other,
        };
        self.fault = None;
        self.last_error = None;
        // Buffered E-stop inputs were armed by the program that ended here.
        self.clear_stop_inputs();
        Ok(Reply::Done)
    }

    /// The frame map of a move accepted now, in `system` (else the group's selection). The
    /// rotary table's position is where its last queued `group_axis_move` leaves it, else its
    /// commanded position (docs/decisions.md, "Group frames").
    pub(super) fn frame_map(
        &self,
        env: &Env,
        system: Option<CoordinateSystem>,
    ) -> Result<FrameMap, EngineError> {
        let system = system.unwrap_or(self.frames.selected());
        let table = self.frames.table_axis().and_then(|axis| {
            (self.staging.last_axis_move(axis)).or_else(|| self.queue.last_axis_move(axis))
        });
        self.frames
            .resolve(self.id, system, self.dims(), env.axes, table)
    }

    fn check_room(&self) -> Result<(), EngineError> {
        if self.queued() >= self.queue.capacity() as usize {
            Err(EngineError::GroupQueueFull {
                group: self.id,
                capacity: self.queue.capacity(),
            })
        } else {
            Ok(())
        }
    }

    /// Queue a checked motion, or (aborting while the path runs) stop the path and start it
    /// at rest.
    pub(super) fn submit(
        &mut self,
        env: &mut Env,
        mut request: PathRequest,
    ) -> Result<Reply, EngineError> {
        request.angular = self.angular_profile();
        if request.aborting && !self.is_idle() {
            let id = env.ledger.allocate();
            // The new motion runs once the path is at rest: the group is Moving again.
            self.stop_path(env, self.motion_defaults(env.axes).deceleration);
            if self.state == GroupState::Halted {
                self.state = GroupState::Moving;
            }
            self.pending = Some(PendingMotion { id, request });
            return Ok(Reply::Accepted { id });
        }
        self.check_room()?;
        let id = self.place_motion(env, None, request)?;
        if self.state == GroupState::Standby {
            self.state = GroupState::Moving;
        }
        Ok(Reply::Accepted { id })
    }

    fn submit_marker(
        &mut self,
        env: &mut Env,
        item: Item,
        kind: MarkerKind,
    ) -> Result<Reply, EngineError> {
        self.require_accepts_motion()?;
        self.check_room()?;
        self.sync_position(env)?;
        let id = self.accept_marker(env, item, kind)?;
        if self.state == GroupState::Standby {
            self.state = GroupState::Moving;
        }
        Ok(Reply::Accepted { id })
    }

    /// `group_stop`: decelerate along the path and drop the queue (MC_GroupStop).
    pub(super) fn stop(&mut self, env: &mut Env, deceleration: f64) -> Result<Reply, EngineError> {
        match self.state {
            GroupState::Disabled | GroupState::ErrorStop | GroupState::Standby => {
                return Ok(Reply::Done)
            }
            GroupState::Moving | GroupState::Halted | GroupState::Stopping => {}
        }
        if self.stop_jog(deceleration) {
            return Ok(Reply::Done);
        }
        self.stop_path(env, deceleration);
        self.state = GroupState::Stopping;
        Ok(Reply::Done)
    }

    /// Decelerate the path to rest and drop the queue (the planner reports the queued entries
    /// dropped); a wait in progress and an aborting motion not yet started end `aborted`. A
    /// halted path stops too: the halt gives way to the stop.
    fn stop_path(&mut self, env: &mut Env, deceleration: f64) {
        self.off_path = false;
        self.drop_distance_outputs(env, CommandState::Aborted);
        if let Some(wait) = self.waiting.take() {
            self.planner.release_hold();
            env.ledger.finish(wait.id, CommandState::Aborted);
        }
        if let Some(p) = self.pending.take() {
            env.ledger.finish(p.id, CommandState::Aborted);
        }
        self.abort_staged(env);
        self.planner.resume();
        // A deceleration over the counted coordinates, as the motion's limits are.
        self.planner.stop(deceleration / self.length_ratio);
    }

    /// `group_halt`: decelerate along the path, keep the queue (HIMC HaltGroup).
    /// A jog has no path to keep: a halt stops it (docs/decisions.md, "Group jog").
    pub(super) fn halt(
        &mut self,
        deceleration: Option<f64>,
        defaults: f64,
    ) -> Result<Reply, EngineError> {
        if self.state == GroupState::Moving && self.stop_jog(deceleration.unwrap_or(defaults)) {
            return Ok(Reply::Done);
        }
        match self.state {
            // The path has ended and only the members' filtered outputs are still arriving:
            // nothing to halt, and the group goes to Standby when they arrive.
            GroupState::Moving if self.is_idle() => Ok(Reply::Done),
            GroupState::Moving => {
                self.planner
                    .halt(deceleration.map(|d| d / self.length_ratio));
                self.state = GroupState::Halted;
                Ok(Reply::Done)
            }
            GroupState::Standby | GroupState::Halted => Ok(Reply::Done),
            GroupState::Disabled | GroupState::Stopping | GroupState::ErrorStop => {
                Err(EngineError::GroupState {
                    group: self.id,
                    state: self.state,
                    action: "halt",
                })
            }
        }
    }

    /// `group_continue` after a halt.
    pub(super) fn resume(&mut self) -> Result<Reply, EngineError> {
        if self.off_path {
            return Err(EngineError::GroupState {
                group: self.id,
                state: self.state,
                action: "continue off the path (a linear move back to the break point first)",
            });
        }
        match self.state {
            GroupState::Halted => {
                self.planner.resume();
                self.state = GroupState::Moving;
                Ok(Reply::Done)
            }
            GroupState::Standby | GroupState::Moving => Ok(Reply::Done),
            GroupState::Disabled | GroupState::Stopping | GroupState::ErrorStop => {
                Err(EngineError::GroupState {
                    group: self.id,
                    state: self.state,
                    action: "continue",
                })
            }
        }
    }

    fn output_item(&self, env: &Env, c: &GroupSetOutput) -> Result<Item, EngineError> {
        if usize::from(c.channel) >= env.outputs.len() {
            return Err(EngineError::InvalidChannel {
                kind: "digital outputs",
                channel: c.channel,
                count: env.outputs.len() as u16,
            });
        }
        Ok(Item::SetOutput {
            channel: c.channel,
            value: c.value,
        })
    }

    fn axis_move_item(&self, env: &Env, c: GroupAxisMove) -> Result<Item, EngineError> {
        let count = env.axes.len() as u32;
        if env.axes.get(c.axis as usize).is_none() {
            return Err(EngineError::InvalidAxis {
                axis: u32::from(c.axis),
                count,
            });
        }
        if self.members.contains(&c.axis) {
            return Err(EngineError::InvalidGroup {
                group: self.id,
                reason: format!(
                    "axis {} is a member: it moves with the path, not on its own",
                    c.axis
                ),
            });
        }
        bounded("position", c.position)?;
        for (name, v) in [
            ("velocity", c.velocity),
            ("acceleration", c.acceleration),
            ("deceleration", c.deceleration),
        ] {
            if let Some(v) = v {
                positive(name, bounded(name, v)?)?;
            }
        }
        if let Some(j) = c.jerk {
            segment::jerk_value(j)?;
        }
        Ok(Item::AxisMove(c))
    }
}

/// A group parameter that is 0 (off, None) or a positive number.
fn off_or_positive(value: f64) -> Result<Option<f64>, EngineError> {
    let value = finite("value", value)?;
    if value < 0.0 {
        return Err(EngineError::InvalidArgument {
            name: "value",
            value,
            reason: "must be 0 (off) or a positive number",
        });
    }
    Ok((value > 0.0).then_some(value))
}

/// An axis (a member, or the result axis: its `role`) may join `group`: it exists, belongs to
/// no group and is not moving.
fn check_joins(env: &Env, group: GroupId, a: AxisIndex, role: &str) -> Result<(), EngineError> {
    let axis = env.axes.get(a as usize).ok_or(EngineError::InvalidAxis {
        axis: u32::from(a),
        count: env.axes.len() as u32,
    })?;
    if let Some(other) = axis.group() {
        return Err(EngineError::InvalidGroup {
            group,
            reason: format!("{role} {a} is already in group {other}"),
        });
    }
    if let Some(master) = axis.coupled_master() {
        return Err(EngineError::AxisCoupled { axis: a, master });
    }
    let state = axis.state();
    if !matches!(
        state,
        AxisState::Disabled | AxisState::Standstill | AxisState::ErrorStop
    ) {
        return Err(EngineError::GroupMember {
            group,
            axis: a,
            state,
            action: "join a group while it moves",
        });
    }
    Ok(())
}

/// Seconds as whole ticks (rounded; ≥ 0, at most 1e9 s).
fn ticks(name: &'static str, seconds: f64, period: f64) -> Result<u64, EngineError> {
    let s = finite(name, seconds)?;
    if !(0.0..=1e9).contains(&s) {
        return Err(EngineError::InvalidArgument {
            name,
            value: s,
            reason: "must be 0 to 1e9 seconds",
        });
    }
    Ok((s / period).round() as u64)
}

fn dwell_item(env: &Env, c: &GroupDwell) -> Result<Item, EngineError> {
    Ok(Item::Dwell {
        ticks: ticks("seconds", c.seconds, env.period)?,
    })
}

fn timeout_ticks(env: &Env, timeout: Option<f64>) -> Result<Option<u64>, EngineError> {
    timeout
        .map(|t| {
            positive("timeout", t)?;
            ticks("timeout", t, env.period)
        })
        .transpose()
}

fn wait_input_item(env: &Env, c: &GroupWaitInput) -> Result<Item, EngineError> {
    if usize::from(c.channel) >= env.di.len() {
        return Err(EngineError::InvalidChannel {
            kind: "digital inputs",
            channel: c.channel,
            count: env.di.len() as u16,
        });
    }
    Ok(Item::WaitInput {
        channel: c.channel,
        level: c.level,
        timeout: timeout_ticks(env, c.timeout)?,
    })
}

/// The default tolerance of a position wait: the axis's `in_position_window`, or 1e-6 user
/// units where the window is 0 (docs/decisions.md, "Axis groups").
const MIN_WAIT_TOLERANCE: f64 = 1e-6;

fn wait_position_item(env: &Env, c: &GroupWaitPosition) -> Result<Item, EngineError> {
    let axis = env
        .axes
        .get(c.axis as usize)
        .ok_or(EngineError::InvalidAxis {
            axis: u32::from(c.axis),
            count: env.axes.len() as u32,
        })?;
    let position = bounded("position", c.position)?;
    let tolerance = match c.tolerance {
        Some(t) => nonnegative("tolerance", t)?,
        None => axis
            .params()
            .get(ParamId::InPositionWindow)
            .max(MIN_WAIT_TOLERANCE),
    };
    Ok(Item::WaitPosition {
        axis: c.axis,
        position,
        tolerance,
        timeout: timeout_ticks(env, c.timeout)?,
        condition: c.condition,
        source: c.source,
    })
}
