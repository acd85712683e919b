//! One axis: command FIFO, PLCopen state machine, limits, supervision, and the per-tick pipeline
//! (ARCHITECTURE §3.3–§3.5).
//!
//! Frames. The *physical* frame is the motor's (power-on) frame: the plant, the pulse counter,
//! the encoder and the switches live there. The *user* frame is what commands and status use:
//! `cmd_pos = motor_cmd + cmd_offset`, `act_pos = encoder_pos + act_offset`. `set_position` and
//! homing move the offsets, never the motor. Cyclic axes (`rep_mode` 1/2) are unwrapped
//! internally and wrapped only where positions enter or leave the engine.
//!
//! Per tick ([`Axis::step`]): command source → smoothing → output stage (pulses / setpoint /
//! servo loop) → plant → encoder → switches → supervision (limits, following error, alarms) →
//! command progress (completion, homing, next command) → status record.

mod add_axis;
mod command_filter;
mod commands;
mod compensation;
pub mod fifo;
mod gang;
mod latch;
mod move_timing;
mod pvt;
mod sampling;
mod setup;
mod stream_source;
mod supervision;

use crate::command::{
    AxisIndex, CommandId, CommandKind, CommandState, Direction, ErrorKind, GroupId, Setpoint,
    StopMode,
};
use crate::compensation::Compensation;
use crate::config::{AxisConfig, AxisSignal, PlantModel, DEFAULT_FIFO_DEPTH};
use crate::homing::{Homing, HomingFailure};
use crate::hw::encoder::EncoderTick;
use crate::hw::plant::{LoopGains, PlantInput};
use crate::hw::switch::Edge;
use crate::hw::{AxisClass, Encoder, Plant, PulseOutput, SwitchTick, Switches};
use crate::param::{ParamId, ParamSet};
use crate::profile::{
    Goal, Limits, MotionState, MovingAverage, Options, Overshoot, PlanError, Profile,
};
use crate::rng::Rng;
use crate::status::{AxisFlags, AxisState, AxisStatus, CommandRef, CouplingKind};

pub use commands::Feed;
pub(crate) use commands::MotionSubmission;
pub use fifo::{Fifo, Ledger, MotionAction, Overrides, Queued};
pub use latch::{SignalEdge, TriggerCounts};
use pvt::PvtStream;
use setup::Setup;

/// What the engine lends an axis for one tick or one command.
pub(crate) struct Context<'a> {
    /// Ticks since start, after this tick when stepping.
    pub tick: u64,
    /// The machine's digital inputs (after forcing and bindings).
    pub di: &'a [bool],
    pub ledger: &'a mut Ledger,
}

/// Where the commanded motion comes from.
// The profile is stored inline on purpose: one per axis, sampled every tick, no indirection.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug)]
enum Source {
    /// Standing at `raw.p`.
    Hold,
    /// A planned profile: `raw` at tick n = `profile.sample((n − origin)·period)` + `shift`.
    /// `segment` remembers where the last sample was, so each tick's search is O(1).
    Profile {
        profile: Profile,
        origin: u64,
        shift: f64,
        segment: usize,
    },
    /// Cyclic setpoints from a master (CiA 402 CSP/CSV/CST, HMC_SetDposVal).
    External(Setpoint),
    /// This tick's commanded state from a machine-level planner (engine stage 2: a group, a
    /// coupling). Taken as is for one tick; a tick without a new feed stands at its position.
    Fed(MotionState),
    /// The axis's PT/PVT stream (`Axis::stream`): `raw` at tick n = `base` + the stream at
    /// (n − origin)·period.
    Stream { origin: u64, base: f64 },
}

/// Why the axis decelerates to rest without a command owning the motion.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Ramp {
    /// An explicit stop: new motion is refused until it is done (PLCopen MC_Stop).
    Stop(StopMode),
    /// The running command was cancelled (HMC_Cancel); queued commands continue afterwards.
    Cancel,
    /// A limit ended the running command; queued commands continue afterwards (HMC §3.3.5).
    Limit(Direction),
    /// A fault with a stop reaction.
    Fault,
}

/// The goal of the running command.
#[derive(Clone, Copy, Debug, PartialEq)]
enum RunGoal {
    Position {
        target: f64,
    },
    Velocity {
        velocity: f64,
    },
    Homing,
    /// The PT/PVT stream runs to its last point.
    Stream,
}

#[derive(Clone, Debug)]
struct Run {
    id: CommandId,
    kind: CommandKind,
    goal: RunGoal,
    overrides: Overrides,
    /// Tick at which the commanded position arrived (for `cmd_stop_mode` 1).
    arrived_at: Option<u64>,
    homing: Option<Box<Homing>>,
}

#[derive(Clone, Debug)]
enum Activity {
    Idle,
    /// The FIFO head runs.
    Running(Run),
    Ramping(Ramp),
    /// External setpoints (a `setpoint` command stream or a machine-level planner's feed).
    Streaming,
}

/// Which physical input each logical input comes from, and what forced it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Forces {
    limit_pos: Option<bool>,
    limit_neg: Option<bool>,
    home: Option<bool>,
    index: Option<bool>,
    drive_alarm: Option<bool>,
    encoder_loss: Option<bool>,
}

/// Logical input levels of this tick and the exact physical edges behind them.
#[derive(Clone, Copy, Debug, Default)]
struct Inputs {
    limit_pos: bool,
    limit_neg: bool,
    home: bool,
    index: bool,
    drive_alarm: bool,
    hold: bool,
    /// Electrical levels at the axis's connector (after forcing and each sensor's wiring,
    /// before any routing or inversion by the controller): what a general input wired to the
    /// sensor reads.
    sensor_limit_pos: bool,
    sensor_limit_neg: bool,
    sensor_home: bool,
    sensor_alarm: bool,
    /// Exact raw edges and index position of this tick, physical frame.
    home_edge: Option<Edge>,
    limit_pos_edge: Option<Edge>,
    limit_neg_edge: Option<Edge>,
    index_at: Option<f64>,
}

/// What the axis remembers of its homing runs (NMC_MtGetHomeSts bits 3/4, NMC_MtGetHomeError).
#[derive(Clone, Copy, Debug, Default)]
struct HomingRecord {
    failure: Option<HomingFailure>,
    /// Where the last completed homing put its home point (its offset), in the frame it made;
    /// not moved by later redefinitions of the position: the controller keeps the number.
    home_point: Option<f64>,
    /// The home point the last run found minus `home_point` (0 before any was defined).
    home_error: f64,
}

/// One simulated axis.
#[derive(Clone)]
pub struct Axis {
    index: AxisIndex,
    name: String,
    /// The full table, out of line: the tick reads `setup`.
    params: Box<ParamSet>,
    class: AxisClass,
    period: f64,

    // Hardware (physical frame).
    pulse: PulseOutput,
    encoder: Encoder,
    plant: Plant,
    switches: Switches,
    limit_pos_active_low: bool,
    limit_neg_active_low: bool,
    home_active_low: bool,
    /// Motor position of a virtual axis (no plant).
    virtual_motor: f64,
    forces: Forces,
    setup: Setup,
    injected_fe: f64,

    // Frames.
    cmd_offset: f64,
    act_offset: f64,

    // Commanded motion (user frame, unwrapped).
    source: Source,
    /// Unsmoothed commanded state: what the planner plans from.
    raw: MotionState,
    raw_jerk: f64,
    /// Commanded state after smoothing: what the output stage follows.
    cmd: MotionState,
    smoothing: Option<MovingAverage>,
    /// Compensation after the planner (issue 12 item 8), out of line: most axes have none.
    compensation: Option<Box<Compensation>>,
    /// Input shaper / VSF after smoothing (issue 14), out of line: most axes have none.
    filters: Option<Box<crate::filter::CommandFilters>>,
    /// This tick's correction: the drive receives `cmd.p + correction` (digest 001 §4.1).
    correction: f64,
    act_pos: f64,
    act_vel: f64,
    /// The encoder's position after its last update (physical frame).
    encoder_pos: f64,
    /// 1/period.
    rate: f64,

    // Commands.
    /// The group the axis belongs to (issue 11): single-axis motion is refused while set.
    group: Option<GroupId>,
    /// The master of the coupling (issue 12) whose slave this axis is, and whether it is in
    /// sync: single-axis motion is refused while set.
    coupled: Option<AxisIndex>,
    in_sync: bool,
    /// What kind of coupling that is (the status and trace show it).
    coupling_kind: Option<CouplingKind>,
    /// Driven by a handwheel (issue 12 item 7): single-axis motion is refused while set.
    handwheel: bool,
    /// The HMC add axis whose travel is laid on this axis's own command (`add_axis_set`).
    add_axis: Option<AxisIndex>,
    /// Gantry (issue 12 item 6): this tick's deviation, and whether the master's latched
    /// gantry fault shows on this slave.
    gantry_deviation: f64,
    gantry_fault_shown: bool,
    fifo: Fifo,
    /// The PT/PVT buffer (issue 12 item 3), out of line: most axes never stream.
    stream: Box<PvtStream>,
    /// The stream ran dry while moving in this tick's sample (handled in `progress`).
    stream_dry: bool,
    activity: Activity,
    halted: bool,
    /// The id returned for the last zero-length buffered move, reused by the next one (HMC §10.7).
    zero_length_id: Option<CommandId>,
    /// The limits the running command was planned with, to notice live parameter changes.
    planned_limits: Option<Limits>,
    limits_dirty: bool,
    /// Changes of the dedicated inputs (negative limit, positive limit, home, index).
    input_edges: [u32; 4],
    /// The last full input refresh found nothing forced, no hold input and no limit or home
    /// routed to a general input, and neither the forces nor the setup changed since: a tick
    /// whose switches and index keep their levels leaves the inputs as they are. Cleared
    /// wherever the forces or the setup change (`wiring_changed`).
    plain_wiring: bool,

    // State.
    enabled: bool,
    flags: AxisFlags,
    latched: AxisFlags,
    /// Latched faults that hold the axis in ErrorStop.
    blocking: AxisFlags,
    inputs: Inputs,
    fe_over: u32,
    fe_ok: u32,
    in_window_for: f64,
    /// The last move's duration and settling time (HIMC GetMoveTime, GetSettlingTime).
    timing: move_timing::MoveTiming,
    direction: f64,
    params_version: u64,
    last_error: Option<ErrorKind>,
    homing_phase: u8,
    /// Homing's outcome beyond the flags: the reason the last run failed, the home point the
    /// last completed (non-trial) run defined, and the last run's new-minus-that difference.
    homing_record: HomingRecord,
    target_pos: f64,
    /// The last tick as a hardware latch saw it (capture, position compare).
    sweep: latch::Sweep,
    /// What the capture and compare channels on this axis report in its status.
    triggers: latch::TriggerCounts,
}

impl Axis {
    pub fn new(index: AxisIndex, config: &AxisConfig, period: f64, rng: &Rng) -> Axis {
        let mut params = ParamSet::default();
        for (id, value) in &config.params {
            params.set_unchecked(*id, *value);
        }
        // A configured rollover is the same as cyclic mode 1 (HIMC SetRollover).
        if let Some(rollover) = config.params.get(&ParamId::Rollover) {
            apply_rollover(&mut params, *rollover);
        }
        let class = AxisClass::of(params.get(ParamId::AxisType));
        let pulses_per_unit = pulses_per_unit(&params);
        let counts_per_unit = counts_per_unit(&params);
        let sw = &config.switches;
        let smoothing = smoothing_window(params.get(ParamId::SmoothTime), period);
        let mut axis = Axis {
            index,
            name: config
                .name
                .clone()
                .unwrap_or_else(|| format!("axis{index}")),
            class,
            period,
            pulse: PulseOutput::new(pulses_per_unit, config.pulse.max_frequency, period, 0.0),
            encoder: Encoder::new(
                &config.encoder,
                counts_per_unit,
                0.0,
                rng.fork(index as u64),
            ),
            plant: Plant::new(&config.plant, period, 0.0),
            switches: Switches::new(sw, 0.0),
            limit_pos_active_low: sw.limit_pos.as_ref().is_some_and(|s| s.active_low),
            limit_neg_active_low: sw.limit_neg.as_ref().is_some_and(|s| s.active_low),
            home_active_low: sw.home.as_ref().is_some_and(|s| s.active_low),
            virtual_motor: 0.0,
            forces: Forces::default(),
            setup: Setup::from_params(&params),
            injected_fe: 0.0,
            cmd_offset: 0.0,
            act_offset: 0.0,
            source: Source::Hold,
            raw: MotionState::default(),
            raw_jerk: 0.0,
            cmd: MotionState::default(),
            smoothing: smoothing.and_then(|n| MovingAverage::new(n).ok()),
            compensation: None,
            filters: None,
            correction: 0.0,
            act_pos: 0.0,
            act_vel: 0.0,
            encoder_pos: 0.0,
            rate: 1.0 / period,
            group: None,
            coupled: None,
            in_sync: false,
            coupling_kind: None,
            handwheel: false,
            add_axis: None,
            gantry_deviation: 0.0,
            gantry_fault_shown: false,
            fifo: Fifo::new(config.fifo_depth.unwrap_or(DEFAULT_FIFO_DEPTH)),
            stream: Box::default(),
            stream_dry: false,
            activity: Activity::Idle,
            halted: false,
            zero_length_id: None,
            planned_limits: None,
            limits_dirty: false,
            input_edges: [0; 4],
            plain_wiring: false,
            enabled: false,
            flags: AxisFlags::empty(),
            latched: AxisFlags::empty(),
            blocking: AxisFlags::empty(),
            inputs: Inputs::default(),
            fe_over: 0,
            fe_ok: 0,
            in_window_for: 0.0,
            timing: move_timing::MoveTiming::default(),
            direction: 1.0,
            params_version: 0,
            last_error: None,
            homing_phase: 0,
            homing_record: HomingRecord::default(),
            target_pos: 0.0,
            sweep: latch::Sweep::default(),
            triggers: latch::TriggerCounts::default(),
            params: Box::new(params),
        };
        if let Some(f) = axis.smoothing.as_mut() {
            f.reset(0.0);
        }
        axis.refresh_inputs(0.0, 0.0, &[], EncoderTick::default());
        axis
    }

    /// Whether the axis can be enabled and moved at all (not encoder-only or unused).
    pub fn can_move(&self) -> bool {
        self.class.can_move()
    }

    pub fn index(&self) -> AxisIndex {
        self.index
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    /// The electrical level of one of the axis's sensors, as a general input wired to it reads
    /// it (the HMC wires limit and home switches to DI channels: HMC_HwLimitConfig, HMC_Home).
    pub fn sensor(&self, signal: AxisSignal) -> bool {
        let i = &self.inputs;
        match signal {
            AxisSignal::LimitPos => i.sensor_limit_pos,
            AxisSignal::LimitNeg => i.sensor_limit_neg,
            AxisSignal::Home => i.sensor_home,
            AxisSignal::Index => i.index,
            AxisSignal::DriveAlarm => i.sensor_alarm,
        }
    }

    pub fn params(&self) -> &ParamSet {
        &self.params
    }

    /// Counts parameter changes (snapshots copy the parameters when it moves).
    pub fn params_version(&self) -> u64 {
        self.params_version
    }

    /// Physical motor position (for traces and tests; the user frame is in the status).
    pub fn motor_position(&self) -> f64 {
        match self.class {
            AxisClass::Virtual => self.virtual_motor,
            _ => self.plant.position(),
        }
    }

    pub fn fifo(&self) -> &Fifo {
        &self.fifo
    }

    /// The group the axis belongs to, if any.
    pub fn group(&self) -> Option<GroupId> {
        self.group
    }

    /// Join (`Some`) or leave (`None`) a group; the engine's group registry keeps this in step
    /// with its members.
    pub(crate) fn set_group(&mut self, group: Option<GroupId>) {
        self.group = group;
    }

    /// The master of the coupling this axis is the slave of, if any.
    pub fn coupled_master(&self) -> Option<AxisIndex> {
        self.coupled
    }

    /// Become a slave of `master` (`Some`), in sync or not, or stop being one (`None`); the
    /// engine's coupling registry keeps this in step with its couplings.
    pub(crate) fn set_coupled(&mut self, master: Option<AxisIndex>, in_sync: bool) {
        self.coupled = master;
        self.in_sync = in_sync && master.is_some();
        if master.is_none() {
            self.coupling_kind = None;
        }
    }

    /// The kind of the coupling just made with `set_coupled`.
    pub(crate) fn set_coupling_kind(&mut self, kind: CouplingKind) {
        self.coupling_kind = self.coupled.map(|_| kind);
    }

    /// The actual velocity (user units/s).
    pub fn actual_velocity(&self) -> f64 {
        self.act_vel
    }

    /// The encoder's reading in user units, without the `set_position` offset (NMC gear
    /// master type 3).
    pub fn encoder_position(&self) -> f64 {
        self.encoder_pos
    }

    /// The latched faults (cleared by `reset`).
    pub fn latched(&self) -> AxisFlags {
        self.latched
    }

    /// The live flags of the last tick's supervision (limits, warnings), without the ones
    /// [`Axis::status`] assembles.
    pub fn live_flags(&self) -> AxisFlags {
        self.flags
    }

    /// The actual position (user frame, unwrapped).
    pub fn actual_position(&self) -> f64 {
        self.act_pos
    }

    /// The unsmoothed commanded state (user frame, unwrapped): what a group's path starts from.
    pub fn commanded(&self) -> MotionState {
        self.raw
    }

    /// The commanded state the status shows: after smoothing and the command filter, a
    /// cyclic axis's position wrapped (`cmd_pos`, `cmd_vel`, `cmd_acc`).
    pub(crate) fn commanded_output(&self) -> MotionState {
        MotionState {
            p: self.wrap(self.cmd.p),
            ..self.cmd
        }
    }

    /// The actual position the status shows (`act_pos`: a cyclic axis's wrapped).
    pub(crate) fn actual_position_shown(&self) -> f64 {
        self.wrap(self.act_pos)
    }

    /// State of a command that is still in this axis's FIFO.
    pub(crate) fn queued_state(&self, id: CommandId) -> Option<CommandState> {
        let pos = self.fifo.position_of(id)?;
        let running = matches!(&self.activity, Activity::Running(r) if r.id == id);
        Some(if pos == 0 && running {
            CommandState::Running
        } else {
            CommandState::Waiting
        })
    }

    fn param(&self, id: ParamId) -> f64 {
        self.params.get(id)
    }

    fn flag(&self, id: ParamId) -> bool {
        self.params.flag(id)
    }

    fn finite_travel(&self) -> bool {
        self.setup.cyclic.is_none()
    }

    // ------------------------------------------------------------------ per tick

    /// Advance one servo period.
    pub(crate) fn step(&mut self, ctx: &mut Context) {
        if self.limits_dirty {
            self.limits_dirty = false;
            self.replan_for_new_limits(ctx.tick);
        }

        // 1. Command source.
        self.advance_source(ctx.tick);

        // 2. Smoothing (NMC smoothCoef / HIMC SMTime), then 2a. the command filter (input
        // shaper or VSF, digest 004 §2.14: "Smoothing time, VSF and InShape modify PG commands").
        let previous = self.cmd;
        let smoothed = match self.smoothing.as_mut() {
            Some(filter) => Some(filter.next(self.raw.p)),
            None => None,
        };
        let filtered = self
            .filter_command(smoothed.unwrap_or(self.raw.p))
            .or(smoothed);
        if let Some(p) = filtered {
            self.cmd = if self.output_settled() {
                // The output has arrived and stays: at rest from this tick on (the difference
                // below would still show the last step's motion).
                MotionState { p, v: 0.0, a: 0.0 }
            } else {
                let v = (p - previous.p) * self.rate;
                MotionState {
                    p,
                    v,
                    a: (v - previous.v) * self.rate,
                }
            };
        } else {
            self.cmd = self.raw;
        }

        // 2b. Compensation after the planner: the planned position stays as it is, the output
        // gets the correction (digest 001 §4.1, digest 004 §2.13).
        // Over the compensation limit the output is held at the limit (supervision stops the
        // axis): the drive is never sent more than the limit allows.
        if let Some(c) = self.compensation.as_deref_mut() {
            let correction = c.correction(self.index, self.cmd.p, self.cmd.v);
            let limit = self.setup.compensation_limit;
            self.correction = if limit > 0.0 {
                correction.clamp(-limit, limit)
            } else {
                correction
            };
        }

        // 3–5. Output stage, plant, encoder.
        let motor_before = self.motor_position();
        let act_before = self.act_pos;
        let encoder_tick = self.drive_motor();
        let motor_after = self.motor_position();

        // 6. Switches and inputs.
        // The sweep's fields are written in place (`refresh_inputs` keeps the inputs before).
        self.refresh_inputs(motor_before, motor_after, ctx.di, encoder_tick);

        // Disabled: the command follows the actual position (PLCopen), so nothing jumps on enable.
        if !self.enabled {
            self.track_actual();
        }
        let sweep = &mut self.sweep;
        sweep.motor = [motor_before, motor_after];
        sweep.cmd = [previous.p, self.cmd.p];
        sweep.act = [act_before, self.act_pos];

        // 7. Supervision.
        self.supervise(ctx);

        // 8. Command progress.
        self.progress(ctx);

        // 9. In-position timing. The status record itself is assembled when someone reads it
        // (`status`): a snapshot, a drive, a dialect — not by every axis every tick.
        self.update_in_position();
        self.timing
            .update(ctx.tick, self.period, self.moving(), self.in_position());
    }

    /// Sample the command source for this tick.
    fn advance_source(&mut self, tick: u64) {
        let dt = self.period;
        match &mut self.source {
            Source::Hold => {
                self.raw.v = 0.0;
                self.raw.a = 0.0;
                self.raw_jerk = 0.0;
            }
            Source::Profile {
                profile,
                origin,
                shift,
                segment,
            } => {
                let t = tick.saturating_sub(*origin) as f64 * dt;
                let s = profile.sample_from(t, segment);
                self.raw = MotionState {
                    p: s.p + *shift,
                    v: s.v,
                    a: s.a,
                };
                self.raw_jerk = s.j;
            }
            Source::External(setpoint) => {
                let before = self.raw;
                match *setpoint {
                    Setpoint::Position { position } => {
                        self.raw.p = position;
                        self.raw.v = (position - before.p) / dt;
                    }
                    Setpoint::Velocity { velocity } => {
                        self.raw.v = velocity;
                        self.raw.p += velocity * dt;
                    }
                    Setpoint::Torque { torque } => {
                        // Rated torque accelerates at `accel` (or `max_accel`); the motor speed is
                        // capped at `speed` (or `max_velocity`), as a drive's 0x6080 would.
                        let rated =
                            nonzero_or(self.param(ParamId::MaxAccel), self.param(ParamId::Accel));
                        let vmax = nonzero_or(
                            self.param(ParamId::MaxVelocity),
                            self.param(ParamId::Speed),
                        );
                        let v = (before.v + torque * rated * dt).clamp(-vmax, vmax);
                        self.raw.v = v;
                        self.raw.p += v * dt;
                    }
                }
                self.raw.a = (self.raw.v - before.v) / dt;
            }
            Source::Fed(state) => {
                self.raw_jerk = (state.a - self.raw.a) / dt;
                self.raw = *state;
                *state = MotionState {
                    p: state.p,
                    v: 0.0,
                    a: 0.0,
                };
            }
            Source::Stream { origin, base } => {
                let (origin, base) = (*origin, *base);
                self.advance_stream(tick, origin, base);
            }
        }
    }

    /// Output stage, plant and encoder for the commanded position of this tick.
    fn drive_motor(&mut self) -> EncoderTick {
        let motor_cmd = self.cmd.p + self.correction - self.cmd_offset;
        let enabled = self.enabled;
        match self.class {
            AxisClass::Virtual => {
                if enabled {
                    self.virtual_motor = motor_cmd;
                }
                let tick = self.encoder.update(self.virtual_motor);
                self.encoder_pos = self.encoder.position();
                // HMC §2.3: a virtual axis has MPos = DPos exactly, without encoder quantisation.
                let previous = self.act_pos;
                self.act_pos = self.virtual_motor + self.act_offset + self.injected_fe_sign()
                    - self.correction;
                self.act_vel = (self.act_pos - previous) * self.rate;
                return tick;
            }
            AxisClass::Unused => return EncoderTick::default(),
            _ => {}
        }
        let position = if self.class == AxisClass::Stepper && enabled {
            self.pulse.update(motor_cmd);
            self.pulse.position()
        } else {
            motor_cmd
        };
        let input = PlantInput {
            position,
            velocity: self.cmd.v,
            acceleration: self.cmd.a,
            measured_position: self.encoder_pos,
            measured_velocity: self.act_vel,
            enabled: enabled && self.class != AxisClass::EncoderOnly,
        };
        if self.plant.model() == PlantModel::PositionLoop {
            let gains = self.loop_gains();
            self.plant.update(&input, &gains);
        } else {
            self.plant.update(&input, &LoopGains::UNUSED);
        }
        let tick = self.encoder.update(self.plant.position());
        self.encoder_pos = self.encoder.position();
        let previous = self.act_pos;
        // The actual position is the load's: the compensation the motor made up for is taken
        // out again, so the following error compares like with like.
        self.act_pos =
            self.encoder_pos + self.act_offset + self.injected_fe_sign() - self.correction;
        self.act_vel = (self.act_pos - previous) * self.rate;
        tick
    }

    /// An injected following error shows as the actual position lagging the command.
    fn injected_fe_sign(&self) -> f64 {
        -self.injected_fe
    }

    fn loop_gains(&self) -> LoopGains {
        let p = &self.params;
        LoopGains {
            kp: p.get(ParamId::Kp),
            ki: p.get(ParamId::Ki),
            kd: p.get(ParamId::Kd),
            kov: p.get(ParamId::Kov),
            kvff: p.get(ParamId::Kvff),
            kaff: p.get(ParamId::Kaff),
            ko: p.get(ParamId::Ko),
            dac_high: p.get(ParamId::DacLimitHigh),
            dac_low: p.get(ParamId::DacLimitLow),
            pos_offset: p.get(ParamId::PosOffset),
            neg_offset: p.get(ParamId::NegOffset),
            zero_window: p.get(ParamId::ZeroWindow),
            open_loop_dac: (!p.flag(ParamId::ServoLoop)).then(|| p.get(ParamId::Dac)),
        }
    }

    /// While disabled (or open-loop), the commanded position follows the actual one.
    fn track_actual(&mut self) {
        let p = self.act_pos;
        self.raw = MotionState { p, v: 0.0, a: 0.0 };
        self.cmd = self.raw;
        self.cmd_offset = p + self.correction - self.motor_position();
        self.source = Source::Hold;
        if let Some(f) = self.smoothing.as_mut() {
            f.reset(p);
        }
        self.reset_command_filters(p);
        if self.class == AxisClass::Stepper {
            // Re-base the pulse counter so enabling emits no catch-up burst.
            self.pulse
                .set_pulses_per_unit(pulses_per_unit(&self.params), self.motor_position());
        }
    }

    /// Compute the logical input levels from the switches, forcing, routing and inversion.
    /// The common tick is decided here, inline; anything else goes to `refresh_inputs_full`.
    #[inline(always)]
    fn refresh_inputs(&mut self, from: f64, to: f64, di: &[bool], encoder: EncoderTick) {
        let switches = self.switches.update(from, to);
        if self.plain_wiring {
            let i = &self.inputs;
            // The common tick: no edge, no index, every level as it was. Routing, forcing and
            // inversion are those the last full refresh applied, so every input stays.
            let unchanged = switches.limit_pos_edge.is_none()
                && switches.limit_neg_edge.is_none()
                && switches.home_edge.is_none()
                && encoder.index_at.is_none()
                && switches.limit_pos ^ self.limit_pos_active_low == i.sensor_limit_pos
                && switches.limit_neg ^ self.limit_neg_active_low == i.sensor_limit_neg
                && switches.home ^ self.home_active_low == i.sensor_home
                && self.encoder.index() == i.index;
            if unchanged {
                self.sweep.levels_changed = false;
                let i = &mut self.inputs;
                i.home_edge = None;
                i.limit_pos_edge = None;
                i.limit_neg_edge = None;
                i.index_at = None;
                return;
            }
        }
        self.refresh_inputs_full(switches, di, encoder);
    }

    #[inline(never)]
    fn refresh_inputs_full(&mut self, switches: SwitchTick, di: &[bool], encoder: EncoderTick) {
        self.sweep.before = self.inputs;
        self.sweep.levels_changed = true;
        let SwitchTick {
            limit_pos: lp,
            limit_neg: ln,
            home,
            limit_pos_edge: lp_edge,
            limit_neg_edge: ln_edge,
            home_edge,
        } = switches;
        let f = self.forces;
        let w = self.setup;
        // Forcing sets the switch's actuation, which then goes through the same wiring.
        let lp_level = f.limit_pos.unwrap_or(lp) ^ self.limit_pos_active_low;
        let ln_level = f.limit_neg.unwrap_or(ln) ^ self.limit_neg_active_low;
        let home_level = f.home.unwrap_or(home) ^ self.home_active_low;
        let hold = w
            .hold
            .is_some_and(|ch| di.get(ch).copied().unwrap_or(false));
        if hold != self.inputs.hold {
            // HMC_HoldConfig: the hold input changes the speed of the running command.
            self.limits_dirty = true;
        }
        let next = Inputs {
            limit_pos: w
                .limit_pos
                .read(lp_level, di)
                .is_some_and(|v| v ^ w.limit_pos_invert),
            limit_neg: w
                .limit_neg
                .read(ln_level, di)
                .is_some_and(|v| v ^ w.limit_neg_invert),
            home: w
                .home
                .read(home_level, di)
                .is_some_and(|v| v ^ w.home_invert),
            index: f.index.unwrap_or_else(|| self.encoder.index()),
            drive_alarm: w.alarm_enabled && (f.drive_alarm.unwrap_or(false) ^ w.alarm_invert),
            hold,
            sensor_limit_pos: lp_level,
            sensor_limit_neg: ln_level,
            sensor_home: home_level,
            sensor_alarm: f.drive_alarm.unwrap_or(false),
            // Physical frame; only homing reads them (see `homing_inputs`).
            home_edge,
            limit_pos_edge: lp_edge,
            limit_neg_edge: ln_edge,
            index_at: encoder.index_at,
        };
        let was = &self.inputs;
        let changed = [
            was.limit_neg != next.limit_neg,
            was.limit_pos != next.limit_pos,
            was.home != next.home,
            was.index != next.index,
        ];
        for (n, c) in self.input_edges.iter_mut().zip(changed) {
            *n = n.wrapping_add(u32::from(c));
        }
        self.inputs = next;
        self.encoder.set_lost(f.encoder_loss.unwrap_or(false));
        let own = |route| !matches!(route, setup::Route::Di(_));
        self.plain_wiring = f == Forces::default()
            && w.hold.is_none()
            && own(w.limit_pos)
            && own(w.limit_neg)
            && own(w.home);
    }

    /// The forces or the input wiring changed: the next tick refreshes the inputs in full.
    pub(super) fn wiring_changed(&mut self) {
        self.plain_wiring = false;
    }

    // ------------------------------------------------------------------ planning

    /// The limits a command plans with: its overrides, else the axis parameters, with the
    /// velocity override, hold input, caps and vendor rules applied.
    fn limits_for(&self, o: &Overrides) -> Limits {
        let p = &self.params;
        let speed = o.velocity.unwrap_or(p.get(ParamId::Speed));
        let start = p.get(ParamId::StartVelocity);
        // CPU 226H tip 3 / HIMC SetAccTime: a ramp time gives the acceleration.
        let from_time = |time: f64, fallback: f64| {
            if time > 0.0 {
                ((speed - start).max(0.0) / time).max(f64::MIN_POSITIVE)
            } else {
                fallback
            }
        };
        let mut acceleration = o
            .acceleration
            .unwrap_or_else(|| from_time(p.get(ParamId::AccelTime), p.get(ParamId::Accel)));
        let mut deceleration = o
            .deceleration
            .unwrap_or_else(|| from_time(p.get(ParamId::DecelTime), p.get(ParamId::Decel)));
        let cap = p.get(ParamId::MaxAccel);
        if cap > 0.0 {
            acceleration = acceleration.min(cap);
            deceleration = deceleration.min(cap);
        }
        let mut velocity = speed * p.get(ParamId::VelScale) / 100.0;
        let vmax = p.get(ParamId::MaxVelocity);
        if vmax > 0.0 {
            velocity = velocity.min(vmax);
        }
        if self.inputs.hold {
            // HMC_HoldConfig: while the hold input is on, run at HoldSpeed (0 = pause).
            velocity = velocity.min(p.get(ParamId::HoldSpeed));
        }
        let jerk = match o.jerk {
            Some(j) if j > 0.0 => j,
            Some(_) => f64::INFINITY,
            None => self.profile_jerk(),
        };
        Limits {
            velocity,
            acceleration,
            deceleration,
            jerk,
        }
    }

    fn options(&self) -> Options {
        Options {
            start_velocity: self.param(ParamId::StartVelocity),
            overshoot: if self.param(ParamId::OvershootMode) == 1.0 {
                Overshoot::JumpToZeroAtTarget
            } else {
                Overshoot::Reverse
            },
        }
    }

    /// Plan from the current raw state towards `goal`. The velocity override, `max_velocity`
    /// and the hold input scale a jog's target velocity as they scale a move's cruise velocity
    /// (in `limits_for`). A zero velocity (override 0 %, hold speed 0, CPU 226H MAX_SPEED 0)
    /// plans a stop; the goal stays, and a later change of the limits re-plans towards it.
    fn plan(&mut self, tick: u64, goal: Goal, limits: Limits) -> Result<(), PlanError> {
        let mut options = self.options();
        let (goal, limits) = match goal {
            Goal::Position { target, .. } if limits.velocity > 0.0 => (
                Goal::Position {
                    target,
                    end_velocity: self.param(ParamId::EndVelocity).min(limits.velocity),
                },
                limits,
            ),
            Goal::Position { .. } => {
                options.start_velocity = 0.0;
                (
                    Goal::Velocity { target: 0.0 },
                    Limits {
                        velocity: unbinding_velocity(0.0, self.raw.v),
                        ..limits
                    },
                )
            }
            Goal::Velocity { target } => {
                options.start_velocity = 0.0;
                let v = self.scale_velocity(target);
                (
                    Goal::Velocity { target: v },
                    Limits {
                        velocity: unbinding_velocity(v, self.raw.v),
                        ..limits
                    },
                )
            }
        };
        let profile = Profile::plan(self.raw, goal, &limits, &options)?;
        self.source = Source::Profile {
            profile,
            origin: tick,
            shift: 0.0,
            segment: 0,
        };
        Ok(())
    }

    /// A jog velocity after the override (`vel_scale`), the cap (`max_velocity`) and the hold.
    fn scale_velocity(&self, v: f64) -> f64 {
        let p = &self.params;
        let mut m = v.abs() * p.get(ParamId::VelScale) / 100.0;
        let cap = p.get(ParamId::MaxVelocity);
        if cap > 0.0 {
            m = m.min(cap);
        }
        if self.inputs.hold {
            m = m.min(p.get(ParamId::HoldSpeed));
        }
        v.signum() * m
    }

    /// The jerk limit of the axis's own profiles: `jerk` in S-curve mode, none (trapezoid)
    /// otherwise (HMC JerkMode).
    fn profile_jerk(&self) -> f64 {
        if self.flag(ParamId::JerkMode) {
            self.param(ParamId::Jerk)
        } else {
            f64::INFINITY
        }
    }

    /// Plan a ramp to rest with deceleration `decel`.
    fn plan_stop(&mut self, tick: u64, decel: f64) {
        if self.raw.v == 0.0 && self.raw.a == 0.0 {
            self.source = Source::Hold;
            return;
        }
        let jerk = self.profile_jerk();
        let limits = Limits {
            velocity: unbinding_velocity(0.0, self.raw.v),
            acceleration: decel,
            deceleration: decel,
            jerk,
        };
        let options = Options::default();
        self.source =
            match Profile::plan(self.raw, Goal::Velocity { target: 0.0 }, &limits, &options) {
                Ok(profile) => Source::Profile {
                    profile,
                    origin: tick,
                    shift: 0.0,
                    segment: 0,
                },
                // Limits come from validated parameters; if planning still fails, stop dead rather
                // than leave the axis without a setpoint (Reflexxes-style fallback).
                Err(_) => Source::Hold,
            };
    }

    /// Stop at once: velocity jumps to zero.
    fn stop_immediately(&mut self) {
        self.raw.v = 0.0;
        self.raw.a = 0.0;
        self.source = Source::Hold;
    }

    fn limit_decel(&self) -> f64 {
        let fast = self.param(ParamId::FastDecel);
        if self.param(ParamId::LimitDecelMode) == 1.0 {
            // HMC §3.3.5: Max(FastDecel, Decel).
            fast.max(self.param(ParamId::Decel))
        } else {
            fast
        }
    }

    /// The goal of `run` as a planner goal, given the current state.
    fn run_goal(run: &Run) -> Option<Goal> {
        match run.goal {
            RunGoal::Position { target } => Some(Goal::Position {
                target,
                end_velocity: 0.0,
            }),
            RunGoal::Velocity { velocity } => Some(Goal::Velocity { target: velocity }),
            RunGoal::Homing | RunGoal::Stream => None,
        }
    }

    /// A live parameter change (speed, accel, …, override, hold) re-plans the running command
    /// from where it is (HMC §2.4: "takes effect immediately").
    fn replan_for_new_limits(&mut self, tick: u64) {
        if self.halted {
            return;
        }
        let Activity::Running(run) = &self.activity else {
            return;
        };
        let Some(goal) = Self::run_goal(run) else {
            return;
        };
        let limits = self.limits_for(&run.overrides);
        if self.planned_limits == Some(limits) {
            return;
        }
        if matches!(self.source, Source::Hold)
            && matches!(goal, Goal::Position { target, .. } if target == self.raw.p)
        {
            return;
        }
        self.planned_limits = Some(limits);
        let _ = self.plan(tick, goal, limits);
    }

    /// A new speed for the running move (NMC PTP compare, `crate::guard`): a position move
    /// keeps its target, a velocity move its direction, both their accelerations; re-planned
    /// from where the axis is. False when no such move runs (or it is halted).
    pub(crate) fn change_running_speed(&mut self, tick: u64, speed: f64) -> bool {
        if self.halted || !(speed.is_finite() && speed > 0.0) {
            return false;
        }
        let Activity::Running(run) = &mut self.activity else {
            return false;
        };
        match &mut run.goal {
            RunGoal::Position { .. } => {}
            RunGoal::Velocity { velocity } => *velocity = speed.copysign(*velocity),
            RunGoal::Homing | RunGoal::Stream => return false,
        }
        run.overrides.velocity = Some(speed);
        let overrides = run.overrides;
        let Some(goal) = Self::run_goal(run) else {
            return false;
        };
        let limits = self.limits_for(&overrides);
        self.planned_limits = Some(limits);
        self.plan(tick, goal, limits).is_ok()
    }

    // ------------------------------------------------------------------ status

    /// The commanded position is changing (HIMC IsMoving: "PG still outputting new positions").
    fn moving(&self) -> bool {
        self.cmd.v != 0.0 || self.raw.v != 0.0 || self.raw.a != 0.0
    }

    fn source_at_rest(&self) -> bool {
        self.raw.v == 0.0 && self.raw.a == 0.0
    }

    fn update_in_position(&mut self) {
        let fe = (self.cmd.p - self.act_pos).abs();
        if fe <= self.setup.in_position_window {
            self.in_window_for += self.period;
        } else {
            self.in_window_for = 0.0;
        }
    }

    /// HIMC IsInPos: motion done (or halted) and |FE| within the window for the window time.
    fn in_position(&self) -> bool {
        let running = matches!(self.activity, Activity::Running(_) | Activity::Streaming);
        self.enabled
            && (!running || self.halted)
            && !self.moving()
            && self.in_window_for >= self.params.get(ParamId::InPositionTime)
    }

    /// The drive's torque as a fraction of rated torque: the setpoint in torque mode, else
    /// what the commanded acceleration takes, rated torque accelerating at `max_accel` (or
    /// `accel`) as the torque setpoint does (`advance_source`).
    pub(crate) fn torque(&self) -> f64 {
        if let Source::External(Setpoint::Torque { torque }) = self.source {
            return torque;
        }
        let rated = nonzero_or(self.param(ParamId::MaxAccel), self.param(ParamId::Accel));
        if self.enabled && rated > 0.0 {
            self.cmd.a / rated
        } else {
            0.0
        }
    }

    /// Whole turns of a rollover (cyclic) axis's actual position past the range's start; 0 on
    /// a finite axis.
    fn rollover_turns(&self) -> i64 {
        match self.setup.cyclic {
            // `as` saturates: a position of ±1e300 reads as i64::MAX/MIN turns, never panics.
            Some(c) if c.length > 0.0 => ((self.act_pos - c.low) / c.length).floor() as i64,
            _ => 0,
        }
    }

    pub fn state(&self) -> AxisState {
        if !self.blocking.is_empty() {
            return AxisState::ErrorStop;
        }
        if !self.enabled {
            return AxisState::Disabled;
        }
        match &self.activity {
            Activity::Idle => AxisState::Standstill,
            Activity::Running(run) => match run.goal {
                RunGoal::Homing => AxisState::Homing,
                RunGoal::Velocity { .. } => AxisState::ContinuousMotion,
                RunGoal::Position { .. } | RunGoal::Stream => AxisState::DiscreteMotion,
            },
            Activity::Ramping(_) => AxisState::Stopping,
            Activity::Streaming => AxisState::SynchronizedMotion,
        }
    }

    /// Wrap a user-frame position into the cyclic range (HMC §2.3 RepMode).
    #[inline]
    fn wrap(&self, p: f64) -> f64 {
        match self.setup.cyclic {
            Some(c) => c.wrap(p),
            None => p,
        }
    }

    /// Everything a front-end may want to know about the axis, as of the last tick.
    pub fn status(&self) -> AxisStatus {
        let mut status = AxisStatus::default();
        self.status_into(&mut status);
        status
    }

    /// [`Axis::status`] written in place (snapshots refresh their records every tick).
    pub fn status_into(&self, out: &mut AxisStatus) {
        let moving = self.moving();
        let current = match &self.activity {
            Activity::Running(r) => Some(CommandRef {
                id: r.id,
                kind: r.kind,
            }),
            _ => None,
        };
        let in_position = self.in_position();
        let mut flags = self.flags | self.latched;
        flags.put(AxisFlags::ENABLED, self.enabled);
        flags.put(AxisFlags::MOVING, moving);
        flags.put(AxisFlags::IN_POSITION, in_position);
        flags.put(AxisFlags::HOME_SWITCH, self.inputs.home);
        flags.put(AxisFlags::INDEX, self.inputs.index);
        flags.put(AxisFlags::HALTED, self.halted);
        flags.put(AxisFlags::QUEUE_FULL, self.fifo.is_full());
        flags.put(AxisFlags::ACCELERATING, self.cmd.v * self.cmd.a > 0.0);
        flags.put(AxisFlags::IN_GROUP, self.group.is_some());
        flags.put(AxisFlags::COUPLED, self.coupled.is_some());
        flags.put(AxisFlags::IN_SYNC, self.in_sync);
        flags.put(AxisFlags::HANDWHEEL, self.handwheel);
        if self.gantry_fault_shown {
            flags |= AxisFlags::GANTRY_FAULT;
        }
        flags.put(AxisFlags::CAPTURE_TRIGGERED, self.triggers.captures > 0);
        let mut inputs = AxisFlags::empty();
        inputs.put(AxisFlags::HW_LIMIT_POS, self.inputs.limit_pos);
        inputs.put(AxisFlags::HW_LIMIT_NEG, self.inputs.limit_neg);
        inputs.put(AxisFlags::HOME_SWITCH, self.inputs.home);
        inputs.put(AxisFlags::INDEX, self.inputs.index);
        inputs.put(AxisFlags::DRIVE_ALARM, self.inputs.drive_alarm);
        let next = self
            .fifo
            .get(usize::from(current.is_some()))
            .map(|q| CommandRef {
                id: q.id,
                kind: q.kind,
            });
        let (pulses, last, freq, dir) = if self.class == AxisClass::Stepper {
            (
                self.pulse.count(),
                self.pulse.last_tick(),
                self.pulse.frequency(),
                self.pulse.direction(),
            )
        } else {
            (0, 0, 0.0, self.direction >= 0.0)
        };
        let (cmd_pos, act_pos, target_pos) = match self.setup.cyclic {
            None => (self.cmd.p, self.act_pos, self.target_pos),
            Some(c) => (
                c.wrap(self.cmd.p),
                c.wrap(self.act_pos),
                c.wrap(self.target_pos),
            ),
        };
        let (compensation_offset, compensation_offset_moving) = self
            .compensation
            .as_deref()
            .map_or((0.0, false), |c| c.offset());
        *out = AxisStatus {
            state: self.state(),
            flags,
            latched: self.latched,
            cmd_pos,
            cmd_vel: self.cmd.v,
            cmd_acc: self.cmd.a,
            act_pos,
            act_vel: self.act_vel,
            following_error: self.cmd.p - self.act_pos,
            target_pos,
            remaining: self.target_pos - self.cmd.p,
            motion_direction: if self.direction < 0.0 { -1 } else { 1 },
            pulses,
            pulses_last_tick: last,
            pulse_frequency: freq,
            direction: dir,
            encoder_counts: self.encoder.counts(),
            quadrature: self.encoder.quadrature(),
            dac_out: self.plant.dac_out(),
            fifo_len: self.fifo.len() as u16,
            current_command: current,
            next_command: next,
            homing_phase: self.homing_phase,
            last_error: self.last_error,
            captures: self.triggers.captures,
            capture_position: self.triggers.capture_position,
            compare_outputs: self.triggers.compare_outputs,
            stream: self.stream.status(),
            output_pos: cmd_pos + self.correction,
            compensation: self.correction,
            coupling: self.coupling_kind,
            gantry_deviation: self.gantry_deviation,
            position_offset: self.cmd_offset,
            rollover_turns: self.rollover_turns(),
            move_time: self.timing.move_time(),
            settling_time: self.timing.settling_time(),
            torque: self.torque(),
            input_edges: self.input_edges,
            z_output: self.triggers.z_output,
            compensation_offset,
            compensation_offset_moving,
            command_filter: self.filter_status(),
            inputs,
            homing_failure: self.homing_record.failure,
            home_error: self.homing_record.home_error,
            add_axis: self.add_axis,
            encoder_offset: self.encoder.counts_of(self.act_offset),
        };
    }
}

/// A velocity limit that does not constrain a ramp from `current` to the velocity `target`: the
/// goal itself bounds it. Never zero, and of the problem's own magnitude so that the planner's
/// normalisation stays well-conditioned.
pub(crate) fn unbinding_velocity(target: f64, current: f64) -> f64 {
    let v = target.abs().max(current.abs());
    if v > 0.0 {
        v
    } else {
        1.0
    }
}

fn nonzero_or(value: f64, fallback: f64) -> f64 {
    if value > 0.0 {
        value
    } else {
        fallback
    }
}

/// Pulses per user unit: units × Ks (HMC §4.7.6).
pub(crate) fn pulses_per_unit(p: &ParamSet) -> f64 {
    p.get(ParamId::Units) * p.get(ParamId::KsNumerator) / p.get(ParamId::KsDenominator)
}

/// Counts per user unit: units / Ke, following the HMC examples (digest 000 §9 item 9).
pub(crate) fn counts_per_unit(p: &ParamSet) -> f64 {
    p.get(ParamId::Units) * p.get(ParamId::KeDenominator) / p.get(ParamId::KeNumerator)
}

/// Moving-average window in ticks for a smoothing time, `None` when off.
fn smoothing_window(seconds: f64, period: f64) -> Option<usize> {
    let n = (seconds / period).round() as usize;
    (n > 1).then_some(n)
}

/// HIMC SetRollover: > 0 = cyclic [0, rollover); 0 = finite.
pub(crate) fn apply_rollover(params: &mut ParamSet, rollover: f64) {
    params.set_unchecked(ParamId::Rollover, rollover);
    if rollover > 0.0 {
        params.set_unchecked(ParamId::RepMode, 1.0);
        params.set_unchecked(ParamId::RepDist, rollover);
    } else {
        params.set_unchecked(ParamId::RepMode, 0.0);
    }
}

impl std::fmt::Debug for Axis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Axis")
            .field("index", &self.index)
            .field("name", &self.name)
            .field("status", &self.status())
            .finish_non_exhaustive()
    }
}
