//! Simulated inputs, setpoint streams (external master), feeds from an engine stage above the
//! axes, and the start of homing.

use super::*;
use crate::command::MAX_MAGNITUDE;
use crate::profile::MotionState;

/// What a machine-level planner ([`crate::engine::MachinePlanner`]) asks of one axis for one
/// tick. Defined with the axis that takes it, below the engine in the module chain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Feed {
    /// Follow this commanded state this tick.
    Follow(MotionState),
    /// Stop being fed: the axis decelerates to rest with its `decel` and is free again.
    Release,
}

impl Axis {
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
        self.wiring_changed();
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
        self.admit_stream(ctx, toward)?;
        self.source = Source::External(sp);
        Ok(Reply::Done)
    }

    /// Take this tick's setpoint from a machine-level planner (engine stage 2), or let go of
    /// the planner. Same rules as a `setpoint` stream: a fed axis is in SynchronizedMotion, its
    /// FIFO waits, and a setpoint into an active limit is refused.
    #[inline]
    pub(crate) fn feed(&mut self, ctx: &mut Context, feed: Feed) -> Result<(), EngineError> {
        if let Feed::Follow(state) = feed {
            if self.follows_freely(&state) {
                if let Source::Fed(fed) = &mut self.source {
                    *fed = state;
                    return Ok(());
                }
            }
        }
        self.feed_checked(ctx, feed)
    }

    /// [`Axis::feed`] past its common tick: a release, the first setpoint, or one that some
    /// check may refuse. Out of line, so the common tick inlines into the caller's loop.
    #[inline(never)]
    fn feed_checked(&mut self, ctx: &mut Context, feed: Feed) -> Result<(), EngineError> {
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
        self.admit_stream(ctx, state.p - self.raw.p)?;
        // In place while fed: a whole `Source` (it can hold a profile, hundreds of bytes)
        // moved every tick for every member was a group tick's largest single cost.
        match &mut self.source {
            Source::Fed(fed) => *fed = state,
            other => *other = Source::Fed(state),
        }
        Ok(())
    }

    /// Whether the checks of `feed` below all pass for `state` on an axis already fed: every
    /// value within ±[`MAX_MAGNITUDE`] (NaN fails the comparison), streaming, free to move and
    /// on no limit in either direction. The common tick of a running path, decided without
    /// building a `Result` per check (a group tick's largest cost, once per member); anything
    /// else takes the checks, which give the same outcome and name the refusal.
    #[inline]
    fn follows_freely(&self, state: &MotionState) -> bool {
        let limits = AxisFlags::SW_LIMIT_POS
            | AxisFlags::SW_LIMIT_NEG
            | AxisFlags::HW_LIMIT_POS
            | AxisFlags::HW_LIMIT_NEG;
        state.p.abs() <= MAX_MAGNITUDE
            && state.v.abs() <= MAX_MAGNITUDE
            && state.a.abs() <= MAX_MAGNITUDE
            && matches!(self.activity, Activity::Streaming)
            && self.blocking.is_empty()
            && self.enabled
            && self.class.can_move()
            && !self.flags.intersects(limits)
            && (self.class != AxisClass::ClosedLoop || self.flag(ParamId::ServoLoop))
    }

    /// Refuse single-axis commands that would take the command source from a machine-level
    /// planner, or move an axis of a group (PLCopen Part 4: an axis in a group takes no
    /// single-axis motion).
    pub(super) fn check_not_fed(&self) -> Result<(), EngineError> {
        if let Some(group) = self.group {
            return Err(EngineError::AxisInGroup {
                axis: self.index,
                group,
            });
        }
        if let Some(master) = self.coupled {
            return Err(EngineError::AxisCoupled {
                axis: self.index,
                master,
            });
        }
        if self.handwheel {
            return Err(EngineError::AxisOnHandwheel { axis: self.index });
        }
        if matches!(self.source, Source::Fed(_)) && matches!(self.activity, Activity::Streaming) {
            Err(self.invalid_state("take single-axis motion while a machine planner feeds it"))
        } else {
            Ok(())
        }
    }

    /// Whether the axis may become a coupling's slave now: it can move (enabled, no fault),
    /// belongs to no group and follows no other master.
    pub(crate) fn check_can_couple(&self) -> Result<(), EngineError> {
        self.check_unclaimed()?;
        self.check_can_move()
    }

    /// Whether no coupling, handwheel or group claims the axis (what a coupling needs, power
    /// aside).
    pub(crate) fn check_unclaimed(&self) -> Result<(), EngineError> {
        if let Some(master) = self.coupled {
            return Err(EngineError::AlreadyCoupled {
                axis: self.index,
                master,
            });
        }
        if self.handwheel {
            return Err(EngineError::AxisOnHandwheel { axis: self.index });
        }
        if let Some(group) = self.group {
            return Err(EngineError::AxisInGroup {
                axis: self.index,
                group,
            });
        }
        Ok(())
    }

    /// Whether the axis may move `toward` (the sign is the direction) on a stream; the first
    /// setpoint of a stream aborts everything else. The caller then sets the command source.
    pub(super) fn admit_stream(
        &mut self,
        ctx: &mut Context,
        toward: f64,
    ) -> Result<(), EngineError> {
        if let Err(e) = self.check_can_move() {
            return self.refuse(e);
        }
        if let Err(e) = self.admit(direction_of_travel(toward)) {
            return self.refuse(e);
        }
        if !matches!(self.activity, Activity::Streaming) {
            self.abort_all(ctx, CommandState::Aborted);
            self.activity = Activity::Streaming;
        }
        Ok(())
    }

    /// End a stream: decelerate to rest with `decel`.
    pub(super) fn end_stream(&mut self, ctx: &mut Context) {
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
    pub(in crate::axis) fn start_homing(
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
