//! Motion commands of an axis: submitting, queueing and starting moves (PLCopen buffer modes,
//! HMC §2.2), and stopping, halting, resuming, retargeting, cancelling and redefining position.

use super::*;

impl Axis {
    /// Accept a motion command: validate, then start it now (aborting) or queue it (buffered).
    pub(crate) fn submit(
        &mut self,
        ctx: &mut Context,
        request: MotionSubmission,
    ) -> Result<Reply, EngineError> {
        match self.try_submit(ctx, request) {
            Ok(r) => Ok(r),
            Err(e) => {
                if e.kind() == ErrorKind::LimitActive {
                    // NMC BIT_AXIS_MVERR: "motion cannot start".
                    self.latched |= AxisFlags::MOTION_ERROR;
                }
                self.refuse(e)
            }
        }
    }

    pub(super) fn try_submit(
        &mut self,
        ctx: &mut Context,
        request: MotionSubmission,
    ) -> Result<Reply, EngineError> {
        self.check_not_fed()?;
        self.check_can_move()?;
        Self::check_overrides(&request.overrides)?;
        match &request.action {
            MotionAction::MoveAbsolute { position } => {
                bounded("position", *position)?;
            }
            MotionAction::MoveRelative { distance } => {
                bounded("distance", *distance)?;
            }
            MotionAction::MoveVelocity { velocity } => {
                bounded("velocity", *velocity)?;
            }
            MotionAction::Home(_) | MotionAction::Stream => {}
        }
        if self.halted && request.buffer_mode == BufferMode::Aborting {
            self.halted = false;
        }
        match request.buffer_mode {
            BufferMode::Aborting => {
                let direction = self.direction_of(&request.action, self.raw.p);
                self.admit(direction)?;
                self.check_soft_limit_target(&request.action, self.raw.p)?;
                if let MotionAction::Home(spec) = &request.action {
                    // Refuse a homing the axis cannot do before anything is aborted.
                    self.start_homing(ctx.tick, spec)?;
                }
                self.abort_all(ctx, CommandState::Aborted);
                let id = ctx.ledger.allocate();
                self.zero_length_id = None;
                self.fifo.push(Queued {
                    id,
                    kind: request.kind,
                    action: request.action,
                    overrides: request.overrides,
                });
                self.start_now(ctx)?;
                Ok(Reply::Accepted { id })
            }
            BufferMode::Buffered => {
                // HMC §10.7: consecutive zero-length moves share one id.
                let zero_length = matches!(request.action, MotionAction::MoveRelative { distance } if distance == 0.0);
                if zero_length {
                    if let Some(id) = self.zero_length_id {
                        if self.fifo.position_of(id).is_some() {
                            return Ok(Reply::Accepted { id });
                        }
                    }
                }
                if self.fifo.is_full() {
                    return Err(EngineError::QueueFull {
                        axis: self.index,
                        depth: self.fifo.depth() as u16,
                    });
                }
                let id = ctx.ledger.allocate();
                self.zero_length_id = zero_length.then_some(id);
                self.fifo.push(Queued {
                    id,
                    kind: request.kind,
                    action: request.action,
                    overrides: request.overrides,
                });
                if matches!(self.activity, Activity::Idle) {
                    self.start_now(ctx)?;
                }
                Ok(Reply::Accepted { id })
            }
        }
    }

    /// Direction a command would move in, from position `from`.
    pub(super) fn direction_of(&self, action: &MotionAction, from: f64) -> Option<Direction> {
        let delta = match action {
            MotionAction::MoveAbsolute { position } => self.unwrap_target(*position, from) - from,
            MotionAction::MoveRelative { distance } => *distance,
            MotionAction::MoveVelocity { velocity } => *velocity,
            MotionAction::Home(_) => 0.0,
            MotionAction::Stream => self.stream.initial_direction(),
        };
        direction_of_travel(delta)
    }

    /// HIMC: a target beyond a soft limit is refused up front (`sw_limit_reject_targets`).
    pub(super) fn check_soft_limit_target(
        &self,
        action: &MotionAction,
        from: f64,
    ) -> Result<(), EngineError> {
        if !self.flag(ParamId::SwLimitRejectTargets)
            || self.flag(ParamId::IgnoreSwLimits)
            || !self.finite_travel()
        {
            return Ok(());
        }
        let target = match action {
            MotionAction::MoveAbsolute { position } => *position,
            MotionAction::MoveRelative { distance } => from + distance,
            _ => return Ok(()),
        };
        let (fs, rs) = (self.param(ParamId::FsLimit), self.param(ParamId::RsLimit));
        if target > fs || target < rs {
            return Err(EngineError::InvalidArgument {
                name: "position",
                value: target,
                reason: "beyond a software limit",
            });
        }
        Ok(())
    }

    /// An absolute target on a cyclic axis becomes an unwrapped target by `move_abs_mode`
    /// (HMC §2.4 MoveAbsMode, digest 000 TV63).
    pub(in crate::axis) fn unwrap_target(&self, target: f64, from: f64) -> f64 {
        let mode = self.param(ParamId::RepMode) as i64;
        if mode == 0 {
            return target;
        }
        let dist = self.param(ParamId::RepDist);
        let period = if mode == 1 { dist } else { 2.0 * dist };
        let here = self.wrap(from);
        let forward = (target - here).rem_euclid(period);
        let delta = match self.param(ParamId::MoveAbsMode) as i64 {
            1 => {
                if forward <= period / 2.0 {
                    forward
                } else {
                    forward - period
                }
            }
            2 => forward,
            3 => {
                if forward == 0.0 {
                    0.0
                } else {
                    forward - period
                }
            }
            4 => {
                if self.direction >= 0.0 || forward == 0.0 {
                    forward
                } else {
                    forward - period
                }
            }
            // 0: within the current range, no wrap.
            _ => target - here,
        };
        from + delta
    }

    /// Start the FIFO head (if any) from the current state. Commands that cannot start end with
    /// an error and the next one is tried, so a bad command never blocks the queue.
    pub(in crate::axis) fn start_head(&mut self, ctx: &mut Context) {
        loop {
            let Some(head) = self.fifo.front().cloned() else {
                self.activity = Activity::Idle;
                self.source = Source::Hold;
                self.target_pos = self.raw.p;
                return;
            };
            match self.start(ctx, &head) {
                Ok(()) => return,
                Err(e) => {
                    self.fifo.pop_front();
                    self.last_error = Some(e.kind());
                    self.latched |= AxisFlags::MOTION_ERROR;
                    ctx.ledger.finish(head.id, CommandState::Error(e.kind()));
                }
            }
        }
    }

    /// Start the command just put at the FIFO head, for a caller waiting on the reply: if it
    /// cannot start, it leaves the FIFO with its error, the axis comes to rest, and the caller
    /// gets the error.
    pub(super) fn start_now(&mut self, ctx: &mut Context) -> Result<(), EngineError> {
        let Some(head) = self.fifo.front().cloned() else {
            return Ok(());
        };
        let Err(e) = self.start(ctx, &head) else {
            return Ok(());
        };
        self.fifo.pop_front();
        ctx.ledger.finish(head.id, CommandState::Error(e.kind()));
        self.activity = Activity::Idle;
        if self.source_at_rest() {
            self.source = Source::Hold;
        } else {
            self.plan_stop(ctx.tick, self.param(ParamId::Decel));
            self.activity = Activity::Ramping(Ramp::Cancel);
        }
        Err(e)
    }

    pub(super) fn start(&mut self, ctx: &mut Context, q: &Queued) -> Result<(), EngineError> {
        let from = self.raw.p;
        self.admit(self.direction_of(&q.action, from))?;
        self.halted = false;
        let limits = self.limits_for(&q.overrides);
        let (goal, planner_goal) = match &q.action {
            MotionAction::MoveAbsolute { .. } | MotionAction::MoveRelative { .. } => {
                let target = match &q.action {
                    MotionAction::MoveAbsolute { position } => self.unwrap_target(*position, from),
                    MotionAction::MoveRelative { distance } => from + distance,
                    _ => from,
                };
                self.target_pos = target;
                if target != from {
                    self.direction = (target - from).signum();
                }
                (
                    RunGoal::Position { target },
                    Goal::Position {
                        target,
                        end_velocity: 0.0,
                    },
                )
            }
            MotionAction::MoveVelocity { velocity } => {
                if *velocity != 0.0 {
                    self.direction = velocity.signum();
                }
                self.target_pos = from;
                (
                    RunGoal::Velocity {
                        velocity: *velocity,
                    },
                    Goal::Velocity { target: *velocity },
                )
            }
            MotionAction::Home(spec) => {
                let homing = self.start_homing(ctx.tick, spec)?;
                self.activity = Activity::Running(Run {
                    id: q.id,
                    kind: q.kind,
                    goal: RunGoal::Homing,
                    overrides: q.overrides,
                    arrived_at: None,
                    homing: Some(Box::new(homing)),
                });
                self.target_pos = from;
                self.progress_homing(ctx);
                return Ok(());
            }
            MotionAction::Stream => {
                self.begin_stream(ctx.tick, q.id)?;
                return Ok(());
            }
        };
        self.plan(ctx.tick, planner_goal, limits)
            .map_err(plan_error)?;
        self.planned_limits = Some(limits);
        self.activity = Activity::Running(Run {
            id: q.id,
            kind: q.kind,
            goal,
            overrides: q.overrides,
            arrived_at: None,
            homing: None,
        });
        Ok(())
    }

    /// End the running command (if any) and everything queued with `state`.
    pub(in crate::axis) fn abort_all(&mut self, ctx: &mut Context, state: CommandState) {
        self.release_stream();
        for q in self.fifo.drain() {
            ctx.ledger.finish(q.id, state);
        }
        if matches!(self.activity, Activity::Running(_)) {
            self.activity = Activity::Idle;
        }
        self.halted = false;
        self.homing_phase = 0;
        self.zero_length_id = None;
    }

    /// End only the running command with `state`.
    pub(in crate::axis) fn end_running(&mut self, ctx: &mut Context, state: CommandState) {
        self.release_stream();
        if let Activity::Running(run) = &self.activity {
            let id = run.id;
            if self.fifo.front().map(|q| q.id) == Some(id) {
                self.fifo.pop_front();
            }
            ctx.ledger.finish(id, state);
            self.activity = Activity::Idle;
            self.homing_phase = 0;
        }
    }

    pub(crate) fn stop(
        &mut self,
        ctx: &mut Context,
        mode: StopMode,
        deceleration: Option<f64>,
    ) -> Result<Reply, EngineError> {
        if let Some(d) = deceleration {
            if let Err(e) = positive("deceleration", d) {
                return self.refuse(e);
            }
        }
        self.abort_all(ctx, CommandState::Aborted);
        if mode == StopMode::Emergency {
            // NMC_MtEstp: latches ESTP; the axis needs a reset before it moves again.
            self.latched |= AxisFlags::ESTOP;
            self.blocking |= AxisFlags::ESTOP;
        }
        if !self.enabled {
            self.activity = Activity::Idle;
            return Ok(Reply::Done);
        }
        match mode {
            StopMode::Immediate => {
                self.stop_immediately();
                self.activity = Activity::Idle;
            }
            StopMode::Smooth => {
                let decel = deceleration.unwrap_or(self.param(ParamId::Decel));
                self.plan_stop(ctx.tick, decel);
                self.activity = Activity::Ramping(Ramp::Stop(mode));
            }
            StopMode::Abrupt | StopMode::Emergency => {
                let decel = deceleration.unwrap_or(self.param(ParamId::FastDecel));
                self.plan_stop(ctx.tick, decel);
                self.activity = Activity::Ramping(Ramp::Stop(mode));
            }
        }
        if matches!(self.source, Source::Hold) {
            self.activity = Activity::Idle;
        }
        self.target_pos = self.raw.p;
        Ok(Reply::Done)
    }

    pub(crate) fn halt(
        &mut self,
        ctx: &mut Context,
        deceleration: Option<f64>,
    ) -> Result<Reply, EngineError> {
        if let Some(d) = deceleration {
            if let Err(e) = positive("deceleration", d) {
                return self.refuse(e);
            }
        }
        match &self.activity {
            Activity::Running(run) if run.goal == RunGoal::Homing => {
                let e = self.invalid_state("halt while homing");
                return self.refuse(e);
            }
            Activity::Running(run) if run.goal == RunGoal::Stream => {
                // A stream runs on its own clock: it cannot pause and resume.
                let e = self.invalid_state("halt a PT/PVT stream (stop it instead)");
                return self.refuse(e);
            }
            Activity::Running(_) => {}
            _ => return Ok(Reply::Done),
        }
        self.halted = true;
        let decel = deceleration.unwrap_or(self.param(ParamId::Decel));
        self.plan_stop(ctx.tick, decel);
        Ok(Reply::Done)
    }

    pub(crate) fn resume(&mut self, ctx: &mut Context) -> Result<Reply, EngineError> {
        if !self.halted {
            return Ok(Reply::Done);
        }
        if let Err(e) = self.check_can_move() {
            return self.refuse(e);
        }
        self.halted = false;
        if let Activity::Running(run) = &self.activity {
            if let Some(goal) = Self::run_goal(run) {
                let limits = self.limits_for(&run.overrides);
                self.planned_limits = Some(limits);
                let _ = self.plan(ctx.tick, goal, limits);
            }
        }
        Ok(Reply::Done)
    }

    /// HMC_MoveModify / MoveModifyEx: change the target of the running position move.
    pub(crate) fn modify_target(
        &mut self,
        ctx: &mut Context,
        position: f64,
        relative: bool,
    ) -> Result<Reply, EngineError> {
        if let Err(e) = bounded("position", position) {
            return self.refuse(e);
        }
        let running = match &self.activity {
            Activity::Running(run) => Some((run.id, run.goal, run.overrides)),
            _ => None,
        };
        match running {
            None if self.fifo.is_empty() => {
                // HMC: with an empty FIFO it posts a MoveAbs (mode 0) or a Move (mode 1).
                let action = if relative {
                    MotionAction::MoveRelative { distance: position }
                } else {
                    MotionAction::MoveAbsolute { position }
                };
                let kind = if relative {
                    CommandKind::MoveRelative
                } else {
                    CommandKind::MoveAbsolute
                };
                self.submit(
                    ctx,
                    MotionSubmission {
                        kind,
                        action,
                        overrides: Overrides::default(),
                        buffer_mode: BufferMode::Buffered,
                    },
                )
            }
            Some((id, RunGoal::Position { .. }, overrides)) => {
                // MoveModifyEx mode 1: new target = current DPos + value.
                let target = if relative {
                    self.raw.p + position
                } else {
                    self.unwrap_target(position, self.raw.p)
                };
                if let Err(e) = self.admit(direction_of_travel(target - self.raw.p)) {
                    return self.refuse(e);
                }
                if let Activity::Running(run) = &mut self.activity {
                    run.goal = RunGoal::Position { target };
                    run.arrived_at = None;
                }
                self.target_pos = target;
                self.halted = false;
                let limits = self.limits_for(&overrides);
                self.planned_limits = Some(limits);
                if self
                    .plan(
                        ctx.tick,
                        Goal::Position {
                            target,
                            end_velocity: 0.0,
                        },
                        limits,
                    )
                    .is_err()
                {
                    return self.refuse(EngineError::InvalidArgument {
                        name: "position",
                        value: position,
                        reason: "no profile reaches it with the current limits",
                    });
                }
                Ok(Reply::Accepted { id })
            }
            _ => self.refuse(EngineError::Unsupported {
                what: "modify_target: the running command is not a position move (HMC returns 0xFFFFFFFE)"
                    .into(),
            }),
        }
    }

    /// HMC_Cancel: 0 next, 1 current, 2 all.
    pub(crate) fn cancel(
        &mut self,
        ctx: &mut Context,
        scope: CancelScope,
    ) -> Result<Reply, EngineError> {
        let running = matches!(self.activity, Activity::Running(_));
        match scope {
            CancelScope::Next => {
                let index = usize::from(running);
                if let Some(q) = self.fifo.remove(index) {
                    ctx.ledger.finish(q.id, CommandState::Aborted);
                }
            }
            CancelScope::Current | CancelScope::All => {
                if scope == CancelScope::All {
                    let keep = usize::from(running);
                    while self.fifo.len() > keep {
                        if let Some(q) = self.fifo.remove(keep) {
                            ctx.ledger.finish(q.id, CommandState::Aborted);
                        }
                    }
                }
                if running {
                    self.end_running(ctx, CommandState::Aborted);
                    self.halted = false;
                    match self.param(ParamId::CancelMode) as i64 {
                        // CancelMode 2: immediate stop (HMC §2.4; meant for linked commands).
                        2 => self.stop_immediately(),
                        _ => self.plan_stop(ctx.tick, self.param(ParamId::Decel)),
                    }
                    if matches!(self.source, Source::Hold) {
                        self.start_head(ctx);
                    } else {
                        self.activity = Activity::Ramping(Ramp::Cancel);
                    }
                }
            }
        }
        Ok(Reply::Done)
    }

    pub(crate) fn set_position(
        &mut self,
        position: f64,
        frame: PositionFrame,
    ) -> Result<Reply, EngineError> {
        if let Err(e) = bounded("position", position) {
            return self.refuse(e);
        }
        if let Activity::Running(run) = &self.activity {
            if run.goal == RunGoal::Homing {
                let e = self.invalid_state("set the position while homing");
                return self.refuse(e);
            }
        }
        if let (Some(group), Source::Fed(_)) = (self.group, &self.source) {
            // The group's path would jump by the shift; between paths the group re-bases on
            // the members' positions instead.
            return self.refuse(EngineError::AxisInGroup {
                axis: self.index,
                group,
            });
        }
        if let Some(f) = &self.smoothing {
            if !f.is_settled() {
                let e = self
                    .invalid_state("set the position while the smoothing filter is still moving");
                return self.refuse(e);
            }
        }
        if !self.filter_settled() {
            let e = self.invalid_state("set the position while the command filter is still moving");
            return self.refuse(e);
        }
        match frame {
            PositionFrame::Both => {
                let delta = position - self.wrap(self.cmd.p);
                self.shift_commanded(delta);
                self.act_offset += delta;
                self.act_pos += delta;
            }
            PositionFrame::Commanded => {
                let delta = position - self.wrap(self.cmd.p);
                self.shift_commanded(delta);
            }
            PositionFrame::Actual => {
                let delta = position - self.wrap(self.act_pos);
                self.act_offset += delta;
                self.act_pos += delta;
            }
        }
        Ok(Reply::Done)
    }

    /// Move the user frame of the commanded position by `delta` (the motor does not move).
    pub(in crate::axis) fn shift_commanded(&mut self, delta: f64) {
        self.cmd_offset += delta;
        self.raw.p += delta;
        self.cmd.p += delta;
        self.target_pos += delta;
        if let Some(f) = self.smoothing.as_mut() {
            f.reset(self.cmd.p);
        }
        let p = self.cmd.p;
        self.reset_command_filters(p);
        match &mut self.source {
            Source::Profile { shift, .. } => *shift += delta,
            Source::External(Setpoint::Position { position }) => *position += delta,
            Source::Fed(state) => state.p += delta,
            Source::Stream { base, .. } => *base += delta,
            _ => {}
        }
        if let Activity::Running(run) = &mut self.activity {
            if let RunGoal::Position { target } = &mut run.goal {
                *target += delta;
            }
        }
    }
}
