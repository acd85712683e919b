//! Per-tick supervision (limits, following error, drive alarm, encoder loss, the HMC error
//! mask) and command progress (completion, stop ramps, the next command).

use super::{setup::Route, unbinding_velocity, Activity, Axis, Context, Ramp, RunGoal, Source};
use crate::command::{CommandState, Direction, ErrorKind, StopMode};
use crate::homing::{HomingInputs, MotionRequest};
use crate::hw::switch::Edge;
use crate::param::{axis_status_word, ParamId, AXIS_STATUS_WORD_FLAGS};
use crate::profile::{Goal, Limits, Options, Profile};
use crate::status::AxisFlags;

/// The live and latched flags supervision sets or reads: with none of them set and nothing
/// over a limit, a tick of supervision changes only the following-error counters.
const SUPERVISED: AxisFlags = AXIS_STATUS_WORD_FLAGS
    .union(AxisFlags::SW_LIMIT_CONFIG)
    .union(AxisFlags::BOTH_LIMITS)
    .union(AxisFlags::DRIVE_ALARM)
    .union(AxisFlags::ENCODER_LOSS)
    .union(AxisFlags::COMPENSATION_LIMIT);

impl Axis {
    pub(super) fn supervise(&mut self, ctx: &mut Context) {
        if self.supervision_quiet() {
            // What the checks below do on such a tick (the following error within its limit).
            self.fe_over = 0;
            self.fe_ok = self.fe_ok.saturating_add(1);
            return;
        }
        self.supervise_in_full(ctx);
    }

    /// The common tick, decided by one expression: no limit input, inside the soft limits, the
    /// following error within its limit, no drive alarm or encoder loss, the compensation within
    /// its limit, and no flag set that supervision would clear or act on. Then every check below
    /// finds nothing to do.
    #[inline]
    fn supervision_quiet(&self) -> bool {
        let (i, p) = (&self.inputs, self.cmd.p);
        let outside_soft = match self.setup.soft_limits {
            Some((fs, rs)) => !(rs < p && p < fs),
            None => false,
        };
        let limit = self.setup.fe_limit;
        let fe_over = self.enabled && limit > 0.0 && (p - self.act_pos).abs() > limit;
        let unusual = i.limit_pos
            || i.limit_neg
            || i.drive_alarm
            || outside_soft
            || fe_over
            || self.forces.encoder_loss == Some(true)
            || self.compensation_over_limit()
            || (self.flags | self.latched).intersects(SUPERVISED);
        !unusual
    }

    #[inline(never)]
    fn supervise_in_full(&mut self, ctx: &mut Context) {
        let homing = matches!(&self.activity, Activity::Running(r) if r.goal == RunGoal::Homing);
        // The live flags are built in a local and stored once: single-bit updates in place
        // compile to byte-wide read-modify-writes, and reading the whole word back right after
        // stalls on store forwarding (measured: a third of this function's time).
        let mut live = self.flags;
        self.supervise_limits(ctx, homing, &mut live);
        self.supervise_following_error(ctx, &mut live);
        self.supervise_faults(ctx, &mut live);
        self.supervise_compensation(ctx);
        self.flags = live;
    }

    fn supervise_limits(&mut self, ctx: &mut Context, homing: bool, live: &mut AxisFlags) {
        let finite = self.finite_travel();
        let ignore_hw = self.setup.ignore_hw_limits;
        // Hard limits (HMC LimitState bits 0/1, NMC LMTP/LMTN, HIMC IsHWRL/IsHWLL).
        let (lp, ln) = if finite {
            (self.inputs.limit_pos, self.inputs.limit_neg)
        } else {
            (false, false)
        };
        live.put(AxisFlags::HW_LIMIT_POS, lp);
        live.put(AxisFlags::HW_LIMIT_NEG, ln);
        if self.setup.limit_latch {
            // NMC: the flag stays until NMC_MtClrError after the input clears.
            if lp {
                self.latched |= AxisFlags::HW_LIMIT_POS;
            }
            if ln {
                self.latched |= AxisFlags::HW_LIMIT_NEG;
            }
        }
        // Soft limits on the commanded position (HMC §3.3.5: Dpos ≥ FSLimit).
        let (soft_on, (fs, rs)) = match self.setup.soft_limits {
            Some(limits) => (finite && !homing, limits),
            None => (false, (0.0, 0.0)),
        };
        let bad_config = soft_on && fs <= rs;
        live.put(AxisFlags::SW_LIMIT_CONFIG, bad_config);
        let (sp, sn) = if soft_on && !bad_config {
            (self.cmd.p >= fs, self.cmd.p <= rs)
        } else {
            (false, false)
        };
        live.put(AxisFlags::SW_LIMIT_POS, sp);
        live.put(AxisFlags::SW_LIMIT_NEG, sn);
        live.put(AxisFlags::BOTH_LIMITS, (lp && ln) || (sp && sn));
        if homing || !self.enabled {
            // Homing runs into switches on purpose; its state machine decides.
            return;
        }
        let hard = !ignore_hw;
        let v = self.raw.v;
        if v > 0.0 && (sp || (hard && lp)) {
            self.limit_stop(ctx, Direction::Positive);
        } else if v < 0.0 && (sn || (hard && ln)) {
            self.limit_stop(ctx, Direction::Negative);
        }
    }

    /// A limit in the direction of travel: the running command ends in error and the axis stops
    /// with the limit deceleration (HMC §3.3.5 FastDecel, `limit_decel_mode`).
    fn limit_stop(&mut self, ctx: &mut Context, direction: Direction) {
        if matches!(self.activity, Activity::Ramping(Ramp::Limit(d)) if d == direction) {
            return;
        }
        if matches!(
            self.activity,
            Activity::Ramping(Ramp::Stop(StopMode::Emergency) | Ramp::Fault)
        ) {
            return;
        }
        self.end_running(ctx, CommandState::Error(ErrorKind::LimitReached));
        self.halted = false;
        self.last_error = Some(ErrorKind::LimitReached);
        self.latched |= AxisFlags::MOTION_ERROR;
        let decel = self.limit_decel();
        self.plan_stop(ctx.tick, decel);
        self.activity = Activity::Ramping(Ramp::Limit(direction));
    }

    /// HMC §3.3.3: one tick over FELimit sets the warning, `fe_fault_cycles` consecutive ticks
    /// latch the fault; the warning clears after `fe_warning_clear_cycles` good ticks.
    fn supervise_following_error(&mut self, ctx: &mut Context, live: &mut AxisFlags) {
        let limit = self.setup.fe_limit;
        let fe = (self.cmd.p - self.act_pos).abs();
        if self.enabled && limit > 0.0 && fe > limit {
            self.fe_over = self.fe_over.saturating_add(1);
            self.fe_ok = 0;
            *live |= AxisFlags::FE_WARNING;
            if self.fe_over >= self.setup.fe_fault_cycles
                && !self.latched.contains(AxisFlags::FE_FAULT)
            {
                self.latched |= AxisFlags::FE_FAULT;
                if !self.flag(ParamId::IgnoreFe) {
                    let action = self.param(ParamId::FeAction) as u32;
                    if action & 1 != 0 {
                        self.fault_disable(ctx, AxisFlags::FE_FAULT);
                    } else if action & 2 != 0 {
                        self.fault_stop(ctx, AxisFlags::FE_FAULT);
                    }
                }
            }
        } else {
            self.fe_over = 0;
            self.fe_ok = self.fe_ok.saturating_add(1);
            if self.fe_ok >= self.setup.fe_warning_clear_cycles {
                live.remove(AxisFlags::FE_WARNING);
            }
        }
    }

    fn supervise_faults(&mut self, ctx: &mut Context, live: &mut AxisFlags) {
        if self.inputs.drive_alarm && !self.latched.contains(AxisFlags::DRIVE_ALARM) {
            // A drive in alarm removes power itself.
            self.latched |= AxisFlags::DRIVE_ALARM;
            self.fault_disable(ctx, AxisFlags::DRIVE_ALARM);
        }
        live.put(AxisFlags::DRIVE_ALARM, self.inputs.drive_alarm);
        let lost = self.forces.encoder_loss.unwrap_or(false);
        live.put(AxisFlags::ENCODER_LOSS, lost);
        if lost && !self.latched.contains(AxisFlags::ENCODER_LOSS) && self.class.can_move() {
            // Feedback wire break: the drive cannot run without it (CiA 402 0x7305).
            self.latched |= AxisFlags::ENCODER_LOSS;
            self.fault_disable(ctx, AxisFlags::ENCODER_LOSS);
        }
        // HMC §3.3.4: AxisStatus & AxisErrMask ≠ 0 switches the drive off.
        // Most ticks no flag the word reads is set: then it is 0 and nothing is masked.
        if self.enabled && (*live | self.latched).intersects(AXIS_STATUS_WORD_FLAGS) {
            let word = axis_status_word(*live | self.latched);
            let mask = self.setup.axis_err_mask;
            let hit = word & mask;
            if hit != 0 {
                let mut causes = AxisFlags::empty();
                if hit & 1 != 0 && !self.flag(ParamId::IgnoreFe) {
                    causes |= AxisFlags::FE_FAULT;
                }
                if hit & 2 != 0 {
                    causes |= AxisFlags::FE_WARNING;
                }
                if hit & 4 != 0 {
                    causes |= AxisFlags::PARAMETER_ERROR;
                }
                if hit & 8 != 0 {
                    causes |= (*live | self.latched)
                        & (AxisFlags::HW_LIMIT_POS
                            | AxisFlags::HW_LIMIT_NEG
                            | AxisFlags::SW_LIMIT_POS
                            | AxisFlags::SW_LIMIT_NEG);
                }
                if !causes.is_empty() {
                    self.latched |= causes;
                    self.fault_disable(ctx, causes);
                }
            }
        }
    }

    /// Digest 004 §2.13: compensation over `compensation_limit` is a fault (eERR_AXIS_COMP_LIMIT).
    /// The manual gives no reaction; the axis stops as for a following-error fault with a stop
    /// reaction, its output held at the limit meanwhile (decisions.md).
    fn supervise_compensation(&mut self, ctx: &mut Context) {
        if self.enabled
            && self.compensation_over_limit()
            && !self.latched.contains(AxisFlags::COMPENSATION_LIMIT)
        {
            self.latched |= AxisFlags::COMPENSATION_LIMIT;
            self.fault_stop(ctx, AxisFlags::COMPENSATION_LIMIT);
        }
    }

    /// A fault that removes power: commands end, the axis goes to ErrorStop.
    pub(super) fn fault_disable(&mut self, ctx: &mut Context, cause: AxisFlags) {
        self.blocking |= cause;
        self.last_error = Some(ErrorKind::Fault);
        self.power_off(ctx, CommandState::Error(ErrorKind::Fault));
    }

    /// A fault with a stop reaction: commands end, the axis decelerates and stays in ErrorStop.
    fn fault_stop(&mut self, ctx: &mut Context, cause: AxisFlags) {
        self.blocking |= cause;
        self.last_error = Some(ErrorKind::Fault);
        self.abort_all(ctx, CommandState::Error(ErrorKind::Fault));
        let decel = self.param(ParamId::FastDecel);
        self.plan_stop(ctx.tick, decel);
        self.activity = Activity::Ramping(Ramp::Fault);
    }

    /// Completion of the running command, the end of ramps, homing, and the next command.
    pub(super) fn progress(&mut self, ctx: &mut Context) {
        // Ask the current source: supervision may have replaced the one sampled this tick.
        let profile_done = self.source_done(ctx.tick);
        let stream_dry = std::mem::take(&mut self.stream_dry);
        match &self.activity {
            Activity::Idle | Activity::Streaming => {}
            Activity::Ramping(ramp) => {
                let ramp = *ramp;
                if self.motion_done(ctx.tick) {
                    self.source = Source::Hold;
                    self.target_pos = self.raw.p;
                    match ramp {
                        Ramp::Stop(_) | Ramp::Fault => self.activity = Activity::Idle,
                        Ramp::Cancel | Ramp::Limit(_) => self.start_head(ctx),
                    }
                }
            }
            Activity::Running(run) => match run.goal {
                RunGoal::Homing => self.progress_homing(ctx),
                RunGoal::Stream => self.progress_stream(ctx, stream_dry),
                RunGoal::Velocity { .. } => {
                    if self.halted && profile_done {
                        self.source = Source::Hold;
                    }
                }
                RunGoal::Position { .. } => {
                    if self.halted {
                        if profile_done {
                            self.source = Source::Hold;
                        }
                        return;
                    }
                    if !profile_done || !self.output_settled() {
                        return;
                    }
                    if !self.completion_reached(ctx.tick) {
                        return;
                    }
                    self.source = Source::Hold;
                    self.end_running(ctx, CommandState::Done);
                    self.start_head(ctx);
                }
            },
        }
    }

    /// HMC §3.3 CmdStopMode: 0 done when the command position arrives; 1 also waits for
    /// |FE| < StopFETol, at most `cmd_stop_max_time`.
    fn completion_reached(&mut self, tick: u64) -> bool {
        if self.param(ParamId::CmdStopMode) == 0.0 {
            return true;
        }
        let arrived = match &mut self.activity {
            Activity::Running(run) => *run.arrived_at.get_or_insert(tick),
            _ => tick,
        };
        let fe = (self.cmd.p - self.act_pos).abs();
        let waited = (tick - arrived) as f64 * self.period;
        fe < self.param(ParamId::StopFeTol) || waited >= self.param(ParamId::CmdStopMaxTime)
    }

    /// One tick of the homing state machine, and what it asks of the axis.
    pub(super) fn progress_homing(&mut self, ctx: &mut Context) {
        let inputs = self.homing_inputs(ctx.tick);
        let Activity::Running(run) = &mut self.activity else {
            return;
        };
        let Some(homing) = run.homing.as_mut() else {
            return;
        };
        let offset = homing.spec().offset;
        let out = homing.step(&inputs);
        if let Some(found) = out.home_found {
            // Before `set_home` moves the frame: both in the frame the run started in.
            let record = &mut self.homing_record;
            record.home_error = found - record.home_point.unwrap_or(0.0);
        }
        if let Some(at) = out.set_home {
            self.homing_record.home_point = Some(offset);
            // The home point reads `offset` from now on; the motor does not move.
            let delta = offset - at;
            self.shift_commanded(delta);
            self.act_offset += delta;
            self.act_pos += delta;
        }
        if let Some(request) = out.motion {
            self.execute_homing_motion(ctx.tick, request);
        }
        self.homing_phase = out.phase.code();
        if let Some(result) = out.done {
            self.source = Source::Hold;
            self.target_pos = self.raw.p;
            match result {
                Ok(()) => {
                    self.homing_record.failure = None;
                    self.flags |= AxisFlags::HOMED;
                    self.end_running(ctx, CommandState::Done);
                }
                Err(e) => {
                    self.homing_record.failure = Some(e.failure());
                    self.latched |= AxisFlags::HOMING_FAILED;
                    self.last_error = Some(ErrorKind::Homing);
                    self.end_running(ctx, CommandState::Error(ErrorKind::Homing));
                }
            }
            self.homing_phase = 0;
            self.start_head(ctx);
        }
    }

    /// Homing motion uses its own speeds and acceleration, not the axis profile parameters.
    fn execute_homing_motion(&mut self, tick: u64, request: MotionRequest) {
        let jerk = self.profile_jerk();
        let current = self.raw.v;
        let limits = |velocity: f64, acceleration: f64| Limits {
            velocity: unbinding_velocity(velocity, current),
            acceleration,
            deceleration: acceleration,
            jerk,
        };
        let planned = match request {
            MotionRequest::Velocity {
                velocity,
                acceleration,
            } => Profile::plan(
                self.raw,
                Goal::Velocity { target: velocity },
                &limits(velocity, acceleration),
                &Options::default(),
            ),
            MotionRequest::MoveTo {
                position,
                velocity,
                acceleration,
            } => Profile::plan(
                self.raw,
                Goal::Position {
                    target: position,
                    end_velocity: 0.0,
                },
                &limits(velocity, acceleration),
                &Options::default(),
            ),
            MotionRequest::Stop { deceleration } => {
                self.plan_stop(tick, deceleration);
                return;
            }
            MotionRequest::StopImmediately => {
                self.stop_immediately();
                return;
            }
        };
        self.source = match planned {
            Ok(profile) => Source::Profile {
                profile,
                origin: tick,
                shift: 0.0,
                segment: 0,
            },
            // The homing machine validated its speeds; should planning still fail, stand still.
            Err(_) => Source::Hold,
        };
    }

    /// Whether the current source has reached its goal at `tick` (a velocity goal: its ramp).
    pub(super) fn source_done(&self, tick: u64) -> bool {
        match &self.source {
            Source::Hold => true,
            Source::Profile {
                profile, origin, ..
            } => tick.saturating_sub(*origin) as f64 * self.period >= profile.duration(),
            Source::External(_) | Source::Fed(_) | Source::Stream { .. } => false,
        }
    }

    /// The commanded motion has reached its goal: the source, and the smoothing filter behind
    /// it (a smoothed command keeps moving for one window after the source stops).
    pub(super) fn motion_done(&self, tick: u64) -> bool {
        self.source_done(tick) && self.output_settled()
    }

    /// What the homing machine sees this tick (user frame, unwrapped).
    pub(super) fn homing_inputs(&self, tick: u64) -> HomingInputs {
        let motion_done = self.motion_done(tick);
        let i = &self.inputs;
        let (w, f) = (&self.setup, &self.forces);
        // Exact edges exist only for the axis's own, unforced switches (a capture latch); they
        // come in the physical frame.
        let offset = self.act_offset;
        let edge = |e: Option<Edge>, route: Route, forced: bool| {
            e.filter(|_| route == Route::Own && !forced)
                .map(|e| e.position + offset)
        };
        HomingInputs {
            time: tick as f64 * self.period,
            position: self.act_pos,
            velocity: self.raw.v,
            motion_done,
            limit_pos: i.limit_pos,
            limit_neg: i.limit_neg,
            home: i.home,
            home_edge: edge(i.home_edge, w.home, f.home.is_some()),
            limit_pos_edge: edge(i.limit_pos_edge, w.limit_pos, f.limit_pos.is_some()),
            limit_neg_edge: edge(i.limit_neg_edge, w.limit_neg, f.limit_neg.is_some()),
            index: i.index_at.map(|p| p + offset),
        }
    }
}
