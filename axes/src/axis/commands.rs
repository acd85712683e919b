//! Commands addressed to one axis (ARCHITECTURE §3.5): validation, admission, the FIFO, and the
//! immediate ones (enable, stop, set parameter …).

use super::{
    apply_rollover, counts_per_unit, pulses_per_unit, setup::Setup, smoothing_window, Action,
    Activity, Axis, Context, Goal1, Overrides, Queued, Ramp, Run, Source,
};
use crate::command::{
    bounded, finite, positive, AxisInput, BufferMode, CancelScope, CommandKind, CommandState,
    Direction, EngineError, ErrorKind, PositionFrame, Reply, Setpoint, StopMode,
};
use crate::engine::Feed;
use crate::homing::{Homing, HomingHardware, HomingSpec};
use crate::hw::AxisClass;
use crate::param::{Access, ParamId};
use crate::profile::{Goal, MovingAverage, PlanError};
use crate::status::AxisFlags;

/// A motion request as it arrives, before it gets an id.
pub(crate) struct MotionRequest {
    pub kind: CommandKind,
    pub action: Action,
    pub overrides: Overrides,
    pub buffer_mode: BufferMode,
}

impl Axis {
    fn refuse<T>(&mut self, e: EngineError) -> Result<T, EngineError> {
        self.last_error = Some(e.kind());
        Err(e)
    }

    fn invalid_state(&self, action: &'static str) -> EngineError {
        EngineError::InvalidState {
            axis: self.index,
            state: self.state(),
            action,
        }
    }

    /// Refuse motion unless the axis can move now.
    fn check_can_move(&self) -> Result<(), EngineError> {
        if !self.class.can_move() {
            return Err(EngineError::Unsupported {
                what: format!(
                    "motion on axis {} of type {} (encoder-only or unused)",
                    self.index,
                    self.param(ParamId::AxisType)
                ),
            });
        }
        if !self.blocking.is_empty() {
            return Err(EngineError::AxisInError {
                axis: self.index,
                faults: self.blocking,
            });
        }
        if !self.enabled {
            return Err(EngineError::AxisDisabled { axis: self.index });
        }
        if self.class == AxisClass::ClosedLoop && !self.flag(ParamId::ServoLoop) {
            return Err(EngineError::Unsupported {
                what: format!(
                    "motion on axis {} with servo_loop = 0: in open loop the commanded position tracks the actual one (HMC §2.1)",
                    self.index
                ),
            });
        }
        if let Activity::Ramping(Ramp::Stop(_) | Ramp::Fault) = self.activity {
            return Err(self.invalid_state("start motion before the stop has finished"));
        }
        Ok(())
    }

    /// Refuse motion further into an active limit; motion out of it is fine (HMC §3.3.5,
    /// NMC §3.2 "reverse motion allowed, same direction blocked").
    pub(super) fn admit(&self, direction: Option<Direction>) -> Result<(), EngineError> {
        let Some(direction) = direction else {
            return Ok(());
        };
        let blocked = match direction {
            Direction::Positive => {
                self.flags.intersects(AxisFlags::SW_LIMIT_POS)
                    || (self.flags.contains(AxisFlags::HW_LIMIT_POS)
                        && !self.flag(ParamId::IgnoreHwLimits))
            }
            Direction::Negative => {
                self.flags.intersects(AxisFlags::SW_LIMIT_NEG)
                    || (self.flags.contains(AxisFlags::HW_LIMIT_NEG)
                        && !self.flag(ParamId::IgnoreHwLimits))
            }
        };
        if blocked {
            Err(EngineError::LimitActive {
                axis: self.index,
                direction,
            })
        } else {
            Ok(())
        }
    }

    fn check_overrides(o: &Overrides) -> Result<(), EngineError> {
        if let Some(v) = o.velocity {
            positive("velocity", bounded("velocity", v)?)?;
        }
        if let Some(a) = o.acceleration {
            positive("acceleration", a)?;
        }
        if let Some(d) = o.deceleration {
            positive("deceleration", d)?;
        }
        if let Some(j) = o.jerk {
            let j = finite("jerk", j)?;
            if j < 0.0 {
                return Err(EngineError::InvalidArgument {
                    name: "jerk",
                    value: j,
                    reason: "must be ≥ 0 (0 = trapezoid)",
                });
            }
        }
        Ok(())
    }

    // ------------------------------------------------------------------ motion commands

    /// Accept a motion command: validate, then start it now (aborting) or queue it (buffered).
    pub(crate) fn submit(
        &mut self,
        ctx: &mut Context,
        request: MotionRequest,
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

    fn try_submit(
        &mut self,
        ctx: &mut Context,
        request: MotionRequest,
    ) -> Result<Reply, EngineError> {
        self.check_not_fed()?;
        self.check_can_move()?;
        Self::check_overrides(&request.overrides)?;
        match &request.action {
            Action::MoveAbsolute { position } => {
                bounded("position", *position)?;
            }
            Action::MoveRelative { distance } => {
                bounded("distance", *distance)?;
            }
            Action::MoveVelocity { velocity } => {
                bounded("velocity", *velocity)?;
            }
            Action::Home(_) => {}
        }
        if self.halted && request.buffer_mode == BufferMode::Aborting {
            self.halted = false;
        }
        match request.buffer_mode {
            BufferMode::Aborting => {
                let direction = self.direction_of(&request.action, self.raw.p);
                self.admit(direction)?;
                self.check_soft_limit_target(&request.action, self.raw.p)?;
                if let Action::Home(spec) = &request.action {
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
                let zero_length =
                    matches!(request.action, Action::MoveRelative { distance } if distance == 0.0);
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
    fn direction_of(&self, action: &Action, from: f64) -> Option<Direction> {
        let delta = match action {
            Action::MoveAbsolute { position } => self.unwrap_target(*position, from) - from,
            Action::MoveRelative { distance } => *distance,
            Action::MoveVelocity { velocity } => *velocity,
            Action::Home(_) => 0.0,
        };
        if delta > 0.0 {
            Some(Direction::Positive)
        } else if delta < 0.0 {
            Some(Direction::Negative)
        } else {
            None
        }
    }

    /// HIMC: a target beyond a soft limit is refused up front (`sw_limit_reject_targets`).
    fn check_soft_limit_target(&self, action: &Action, from: f64) -> Result<(), EngineError> {
        if !self.flag(ParamId::SwLimitRejectTargets)
            || self.flag(ParamId::IgnoreSwLimits)
            || !self.finite_travel()
        {
            return Ok(());
        }
        let target = match action {
            Action::MoveAbsolute { position } => *position,
            Action::MoveRelative { distance } => from + distance,
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
    pub(super) fn unwrap_target(&self, target: f64, from: f64) -> f64 {
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
    pub(super) fn start_head(&mut self, ctx: &mut Context) {
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
    fn start_now(&mut self, ctx: &mut Context) -> Result<(), EngineError> {
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

    fn start(&mut self, ctx: &mut Context, q: &Queued) -> Result<(), EngineError> {
        let from = self.raw.p;
        self.admit(self.direction_of(&q.action, from))?;
        self.halted = false;
        let limits = self.limits_for(&q.overrides);
        let (goal, planner_goal) = match &q.action {
            Action::MoveAbsolute { .. } | Action::MoveRelative { .. } => {
                let target = match &q.action {
                    Action::MoveAbsolute { position } => self.unwrap_target(*position, from),
                    Action::MoveRelative { distance } => from + distance,
                    _ => from,
                };
                self.target_pos = target;
                if target != from {
                    self.direction = (target - from).signum();
                }
                (
                    Goal1::Position { target },
                    Goal::Position {
                        target,
                        end_velocity: 0.0,
                    },
                )
            }
            Action::MoveVelocity { velocity } => {
                if *velocity != 0.0 {
                    self.direction = velocity.signum();
                }
                self.target_pos = from;
                (
                    Goal1::Velocity {
                        velocity: *velocity,
                    },
                    Goal::Velocity { target: *velocity },
                )
            }
            Action::Home(spec) => {
                let homing = self.start_homing(ctx.tick, spec)?;
                self.activity = Activity::Running(Run {
                    id: q.id,
                    kind: q.kind,
                    goal: Goal1::Homing,
                    overrides: q.overrides,
                    arrived_at: None,
                    homing: Some(Box::new(homing)),
                });
                self.target_pos = from;
                self.progress_homing(ctx);
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
    pub(super) fn abort_all(&mut self, ctx: &mut Context, state: CommandState) {
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
    pub(super) fn end_running(&mut self, ctx: &mut Context, state: CommandState) {
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

    // ------------------------------------------------------------------ immediate commands

    pub(crate) fn enable(&mut self, ctx: &mut Context) -> Result<Reply, EngineError> {
        if !self.class.can_move() {
            return self.refuse(EngineError::Unsupported {
                what: format!(
                    "enabling axis {} of type {}",
                    self.index,
                    self.param(ParamId::AxisType)
                ),
            });
        }
        if !self.blocking.is_empty() {
            return self.refuse(EngineError::AxisInError {
                axis: self.index,
                faults: self.blocking,
            });
        }
        if self.inputs.drive_alarm {
            return self.refuse(EngineError::AxisInError {
                axis: self.index,
                faults: AxisFlags::DRIVE_ALARM,
            });
        }
        if !self.enabled {
            self.enabled = true;
            self.plant.reset_loop();
            self.track_actual();
            self.activity = Activity::Idle;
            self.target_pos = self.raw.p;
            let _ = ctx;
        }
        Ok(Reply::Done)
    }

    pub(crate) fn disable(&mut self, ctx: &mut Context) -> Result<Reply, EngineError> {
        self.power_off(ctx, CommandState::Aborted);
        Ok(Reply::Done)
    }

    /// Remove power: the FIFO is cleared (HIMC Disable "clears existing path planning").
    pub(super) fn power_off(&mut self, ctx: &mut Context, state: CommandState) {
        self.abort_all(ctx, state);
        self.activity = Activity::Idle;
        self.enabled = false;
        self.source = Source::Hold;
        self.raw.v = 0.0;
        self.raw.a = 0.0;
    }

    /// Clear latched errors whose cause is gone; report those that remain.
    pub(crate) fn reset(&mut self, _ctx: &mut Context) -> Result<Reply, EngineError> {
        let present = self.fault_causes_present();
        let clearable = self.latched & !present;
        self.latched &= !clearable;
        self.blocking &= !clearable;
        if self.latched.contains(AxisFlags::FE_FAULT) && !present.contains(AxisFlags::FE_FAULT) {
            self.latched.remove(AxisFlags::FE_FAULT);
        }
        self.fe_over = 0;
        self.last_error = None;
        let remaining = self.latched & present;
        if remaining.is_empty() {
            Ok(Reply::Done)
        } else {
            self.refuse(EngineError::CauseStillPresent {
                axis: self.index,
                faults: remaining,
            })
        }
    }

    /// Latched faults whose cause is still there.
    fn fault_causes_present(&self) -> AxisFlags {
        let mut present = AxisFlags::empty();
        present.set(AxisFlags::DRIVE_ALARM, self.inputs.drive_alarm);
        present.set(
            AxisFlags::ENCODER_LOSS,
            self.forces.encoder_loss.unwrap_or(false),
        );
        let fe = (self.cmd.p - self.act_pos).abs();
        let limit = self.param(ParamId::FeLimit);
        present.set(AxisFlags::FE_FAULT, limit > 0.0 && fe > limit);
        present.set(AxisFlags::HW_LIMIT_POS, self.inputs.limit_pos);
        present.set(AxisFlags::HW_LIMIT_NEG, self.inputs.limit_neg);
        present.set(
            AxisFlags::SW_LIMIT_POS,
            self.flags.contains(AxisFlags::SW_LIMIT_POS),
        );
        present.set(
            AxisFlags::SW_LIMIT_NEG,
            self.flags.contains(AxisFlags::SW_LIMIT_NEG),
        );
        present
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
            Activity::Running(run) if run.goal == Goal1::Homing => {
                let e = self.invalid_state("halt while homing");
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
                    Action::MoveRelative { distance: position }
                } else {
                    Action::MoveAbsolute { position }
                };
                let kind = if relative {
                    CommandKind::MoveRelative
                } else {
                    CommandKind::MoveAbsolute
                };
                self.submit(
                    ctx,
                    MotionRequest {
                        kind,
                        action,
                        overrides: Overrides::default(),
                        buffer_mode: BufferMode::Buffered,
                    },
                )
            }
            Some((id, Goal1::Position { .. }, overrides)) => {
                // MoveModifyEx mode 1: new target = current DPos + value.
                let target = if relative {
                    self.raw.p + position
                } else {
                    self.unwrap_target(position, self.raw.p)
                };
                let direction = if target > self.raw.p {
                    Some(Direction::Positive)
                } else if target < self.raw.p {
                    Some(Direction::Negative)
                } else {
                    None
                };
                if let Err(e) = self.admit(direction) {
                    return self.refuse(e);
                }
                if let Activity::Running(run) = &mut self.activity {
                    run.goal = Goal1::Position { target };
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
            if run.goal == Goal1::Homing {
                let e = self.invalid_state("set the position while homing");
                return self.refuse(e);
            }
        }
        if let Some(f) = &self.smoothing {
            if !f.is_settled() {
                let e = self
                    .invalid_state("set the position while the smoothing filter is still moving");
                return self.refuse(e);
            }
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
    pub(super) fn shift_commanded(&mut self, delta: f64) {
        self.cmd_offset += delta;
        self.raw.p += delta;
        self.cmd.p += delta;
        self.target_pos += delta;
        if let Some(f) = self.smoothing.as_mut() {
            f.reset(self.cmd.p);
        }
        match &mut self.source {
            Source::Profile { shift, .. } => *shift += delta,
            Source::External(Setpoint::Position { position }) => *position += delta,
            Source::Fed(state) => state.p += delta,
            _ => {}
        }
        if let Activity::Running(run) = &mut self.activity {
            if let Goal1::Position { target } = &mut run.goal {
                *target += delta;
            }
        }
    }

    pub(crate) fn set_parameter(
        &mut self,
        id: ParamId,
        value: f64,
        lenient: bool,
    ) -> Result<Reply, EngineError> {
        match self.try_set_parameter(id, value, lenient) {
            Ok(()) => Ok(Reply::Done),
            Err(e) => self.refuse(e),
        }
    }

    fn try_set_parameter(
        &mut self,
        id: ParamId,
        value: f64,
        lenient: bool,
    ) -> Result<(), EngineError> {
        let def = id.def();
        let idle = self.fifo.is_empty() && matches!(self.activity, Activity::Idle);
        match def.access {
            Access::ReadOnly => return Err(EngineError::ReadOnlyParameter { name: def.name }),
            Access::WriteWhenIdle if !idle => {
                return Err(self.invalid_state("change this parameter while commands are queued"))
            }
            Access::WriteWhenDisabled if self.enabled => {
                return Err(self.invalid_state("change this parameter while enabled"))
            }
            _ => {}
        }
        let (value, corrected) = if lenient {
            def.lenient(value)?
        } else {
            (def.validate(value)?, false)
        };
        let refuse = |reason: String| EngineError::InvalidParameter {
            name: def.name,
            value,
            reason,
        };
        match id {
            ParamId::AxisType => {
                let class = AxisClass::of(value);
                if class.is_closed_loop()
                    != (self.plant.model() == crate::config::PlantModel::PositionLoop)
                {
                    return Err(refuse(
                        "the axis's plant model does not match: closed-loop types (20, 41, 51) need plant model `position_loop` and the others must not use it".into(),
                    ));
                }
                if self.enabled {
                    return Err(self.invalid_state("change the axis type while enabled"));
                }
                self.class = class;
            }
            ParamId::KsNumerator | ParamId::KsDenominator => {
                let other = if id == ParamId::KsNumerator {
                    self.param(ParamId::KsDenominator)
                } else {
                    self.param(ParamId::KsNumerator)
                };
                if other * value <= 0.0 {
                    return Err(refuse(
                        "Ks numerator and denominator must have the same sign (HMC_SetKs: Ks > 0)"
                            .into(),
                    ));
                }
            }
            ParamId::SmoothTime if !self.source_at_rest() => {
                return Err(
                    self.invalid_state("change the smoothing time while moving (HIMC SetSMTime)")
                );
            }
            ParamId::Rollover => {
                apply_rollover(&mut self.params, value);
                self.setup = Setup::from_params(&self.params);
                self.params_version += 1;
                return Ok(());
            }
            _ => {}
        }
        self.params.set_unchecked(id, value);
        self.setup = Setup::from_params(&self.params);
        self.params_version += 1;
        if corrected {
            // HMC §3.5.1: the corrected write latches AxisStatus bit 2.
            self.latched |= AxisFlags::PARAMETER_ERROR;
        }
        match id {
            ParamId::Units | ParamId::KsNumerator | ParamId::KsDenominator => {
                let motor = self.motor_position();
                self.pulse
                    .set_pulses_per_unit(pulses_per_unit(&self.params), motor);
            }
            ParamId::KeNumerator | ParamId::KeDenominator => {}
            _ => {}
        }
        if matches!(
            id,
            ParamId::Units | ParamId::KeNumerator | ParamId::KeDenominator
        ) {
            let motor = self.plant.position();
            let before = self.encoder.position();
            self.encoder
                .set_counts_per_unit(counts_per_unit(&self.params), motor);
            // Keep the user-frame actual position continuous across the rescale.
            self.encoder_pos = self.encoder.position();
            self.act_offset += before - self.encoder_pos;
        }
        if id == ParamId::SmoothTime {
            self.smoothing =
                smoothing_window(value, self.period).and_then(|n| MovingAverage::new(n).ok());
            if let Some(f) = self.smoothing.as_mut() {
                f.reset(self.raw.p);
            }
        }
        if matches!(
            id,
            ParamId::Speed
                | ParamId::Accel
                | ParamId::Decel
                | ParamId::Jerk
                | ParamId::JerkMode
                | ParamId::VelScale
                | ParamId::MaxVelocity
                | ParamId::MaxAccel
                | ParamId::AccelTime
                | ParamId::DecelTime
                | ParamId::StartVelocity
                | ParamId::HoldSpeed
        ) {
            self.limits_dirty = true;
        }
        Ok(())
    }

    pub(crate) fn get_parameter(&self, id: ParamId) -> f64 {
        crate::param::parameter_value(id, &self.status(), &self.params)
    }

    pub(crate) fn force_input(
        &mut self,
        input: AxisInput,
        value: Option<bool>,
    ) -> Result<Reply, EngineError> {
        let f = &mut self.forces;
        match input {
            AxisInput::LimitPos => f.limit_pos = value,
            AxisInput::LimitNeg => f.limit_neg = value,
            AxisInput::Home => f.home = value,
            AxisInput::Index => f.index = value,
            AxisInput::DriveAlarm => f.drive_alarm = value,
            AxisInput::EncoderLoss => f.encoder_loss = value,
        }
        Ok(Reply::Done)
    }

    pub(crate) fn inject_following_error(
        &mut self,
        amount: Option<f64>,
    ) -> Result<Reply, EngineError> {
        let amount = match amount {
            Some(a) => bounded("amount", a)?,
            None => 0.0,
        };
        self.injected_fe = amount;
        Ok(Reply::Done)
    }

    /// Start, update or end an external setpoint stream.
    pub(crate) fn setpoint(
        &mut self,
        ctx: &mut Context,
        setpoint: Option<Setpoint>,
    ) -> Result<Reply, EngineError> {
        if let Err(e) = self.check_not_fed() {
            return self.refuse(e);
        }
        let Some(sp) = setpoint else {
            self.end_stream(ctx);
            return Ok(Reply::Done);
        };
        let value = match sp {
            Setpoint::Position { position } => position,
            Setpoint::Velocity { velocity } => velocity,
            Setpoint::Torque { torque } => torque,
        };
        if let Err(e) = bounded("setpoint", value) {
            return self.refuse(e);
        }
        let toward = match sp {
            Setpoint::Position { position } => position - self.raw.p,
            Setpoint::Velocity { velocity } => velocity,
            Setpoint::Torque { torque } => torque,
        };
        self.start_stream(ctx, toward, Source::External(sp))?;
        Ok(Reply::Done)
    }

    /// Take this tick's setpoint from a machine-level planner (engine stage 2), or let go of
    /// the planner. Same rules as a `setpoint` stream: a fed axis is in SynchronizedMotion, its
    /// FIFO waits, and a setpoint into an active limit is refused.
    pub(crate) fn feed(&mut self, ctx: &mut Context, feed: Feed) -> Result<(), EngineError> {
        let state = match feed {
            Feed::Follow(state) => state,
            Feed::Release => {
                if matches!(self.source, Source::Fed(_)) {
                    self.end_stream(ctx);
                }
                return Ok(());
            }
        };
        for (name, value) in [
            ("position", state.p),
            ("velocity", state.v),
            ("acceleration", state.a),
        ] {
            if let Err(e) = bounded(name, value) {
                return self.refuse(e);
            }
        }
        self.start_stream(ctx, state.p - self.raw.p, Source::Fed(state))
    }

    /// Refuse single-axis commands that would take the command source from a machine-level
    /// planner (PLCopen: an axis in a group takes no single-axis motion).
    fn check_not_fed(&self) -> Result<(), EngineError> {
        if matches!(self.source, Source::Fed(_)) && matches!(self.activity, Activity::Streaming) {
            Err(self.invalid_state("take single-axis motion while a machine planner feeds it"))
        } else {
            Ok(())
        }
    }

    /// Make `source` the axis's command source if the axis may move `toward` (the sign is the
    /// direction); the first setpoint of a stream aborts everything else.
    fn start_stream(
        &mut self,
        ctx: &mut Context,
        toward: f64,
        source: Source,
    ) -> Result<(), EngineError> {
        if let Err(e) = self.check_can_move() {
            return self.refuse(e);
        }
        let direction = if toward > 0.0 {
            Some(Direction::Positive)
        } else if toward < 0.0 {
            Some(Direction::Negative)
        } else {
            None
        };
        if let Err(e) = self.admit(direction) {
            return self.refuse(e);
        }
        if !matches!(self.activity, Activity::Streaming) {
            self.abort_all(ctx, CommandState::Aborted);
            self.activity = Activity::Streaming;
        }
        self.source = source;
        Ok(())
    }

    /// End a stream: decelerate to rest with `decel`.
    fn end_stream(&mut self, ctx: &mut Context) {
        if matches!(self.activity, Activity::Streaming) {
            self.activity = Activity::Idle;
            self.plan_stop(ctx.tick, self.param(ParamId::Decel));
            if !matches!(self.source, Source::Hold) {
                self.activity = Activity::Ramping(Ramp::Cancel);
            }
        }
    }

    /// Start a homing run: validate it against the axis's inputs, then take its first step in
    /// this same tick (the homing contract).
    pub(super) fn start_homing(
        &mut self,
        tick: u64,
        spec: &HomingSpec,
    ) -> Result<Homing, EngineError> {
        let w = self.setup;
        let hardware = HomingHardware {
            limit_pos: w.limit_pos.exists(self.switches.has_limit_pos()),
            limit_neg: w.limit_neg.exists(self.switches.has_limit_neg()),
            home: w.home.exists(self.switches.has_home()),
            index: self.encoder.has_index(),
        };
        let inputs = self.homing_inputs(tick);
        let homing = Homing::start(spec, hardware, &inputs).map_err(EngineError::Homing)?;
        self.flags.remove(AxisFlags::HOMED);
        Ok(homing)
    }
}

/// A planner refusal as an engine error. Limits come from validated parameters and checked
/// overrides, so this is reached only with extreme but finite values.
fn plan_error(e: PlanError) -> EngineError {
    let (name, value, reason) = match e {
        PlanError::InvalidLimit { name, value } => (name, value, "must be a positive number"),
        PlanError::NotFinite { name, value } => (name, value, "must be finite"),
        PlanError::Negative { name, value } => (name, value, "must not be negative"),
        PlanError::Unrepresentable => (
            "profile",
            f64::NAN,
            "does not fit in f64: the limits or the distance are too extreme",
        ),
    };
    EngineError::InvalidArgument {
        name,
        value,
        reason,
    }
}
