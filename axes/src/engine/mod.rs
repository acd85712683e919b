//! The engine: axes, machine I/O and the command ledger, advanced one servo period per
//! [`Engine::step`] (ARCHITECTURE §3). Same config + same commands at the same ticks ⇒
//! bit-identical state: nothing here reads a clock, iterates a hash map or uses a thread.

use crate::axis::{Axis, Context, Ledger, MotionAction, MotionSubmission, Overrides};
use crate::cia402::{controlword_for, obj, Cia402Drive, DriveMaster, PowerTarget, State};
use crate::command::{
    AxisCommand, AxisIndex, Cancel, Command, CommandKind, CouplingCommand, Disable, Enable,
    EngineError, ForceAnalogInput, ForceDigitalInput, ForceInput, GetParameter, GroupCommand, Halt,
    Home, InjectFollowingError, IoCommand, ModifyTarget, MoveAbsolute, MoveRelative, MoveVelocity,
    ReadObject, Reply, Reset, ResetFaults, SetParameter, SetPosition, SlaveCommand, Stop,
    StreamSetpoint, WriteAnalogOutput, WriteDigitalOutput, WriteObject,
};
use crate::config::{ConfigError, EngineConfig, InputBinding};
use crate::coupling::{Couplings, Env as CouplingEnv};
use crate::group::{Env as GroupEnv, Groups, IoRequest as GroupIoRequest};
use crate::guard::Guards;
use crate::homing::HomingSpec;
use crate::od::Value;
use crate::param::ParamId;
use crate::rng::Rng;
use crate::sampling::Samplers;
use crate::status::{AxisFlags, AxisStatus, DriveStatus, IoImage, Snapshot};
use crate::trigger::{Env as TriggerEnv, Triggers};
use std::sync::Arc;

mod ao_bindings;
mod compensation;
mod do_pulses;
mod estimate;
mod estop_input;
mod gantry_home;
mod guards;
mod machine;
mod planner;
mod sampling;
mod stream_inputs;
mod streams;
pub use crate::axis::Feed;
pub use estimate::MAX_DRY_RUN_TICKS;
pub use machine::MAX_ATOMIC_COMMANDS;
pub use planner::{Feeds, MachinePlanner};

/// The machine's digital and analog I/O.
#[derive(Clone, Debug)]
struct Io {
    image: IoImage,
    /// Bumped on every change of `image`; starts at 1 so a fresh snapshot (0) always copies.
    version: u64,
    di_forced: Vec<Option<bool>>,
    ai_forced: Vec<Option<f64>>,
    bindings: Vec<InputBinding>,
    /// Outputs toggling themselves on the virtual clock.
    pulses: do_pulses::DoPulses,
    /// Analog outputs following an axis variable (`bind_analog_output`).
    ao_bindings: ao_bindings::AoBindings,
}

/// One channel of an I/O image, or the error that names the image and its size.
fn channel<'a, T>(
    values: &'a mut [T],
    channel: u16,
    kind: &'static str,
) -> Result<&'a mut T, EngineError> {
    let count = values.len() as u16;
    values
        .get_mut(channel as usize)
        .ok_or(EngineError::InvalidChannel {
            kind,
            channel,
            count,
        })
}

impl Io {
    /// Force a digital input, or release it (`None`). A forced level shows at once; a released
    /// unwired input reads low (a bound one follows its signal from the next tick).
    fn force_digital_input(&mut self, ch: u16, value: Option<bool>) -> Result<(), EngineError> {
        *channel(&mut self.di_forced, ch, "digital inputs")? = value;
        let di = channel(&mut self.image.di, ch, "digital inputs")?;
        let level = value.unwrap_or(false);
        if *di != level {
            *di = level;
            self.count_edge(ch);
        }
        self.version += 1;
        Ok(())
    }

    fn force_analog_input(&mut self, ch: u16, value: Option<f64>) -> Result<(), EngineError> {
        if let Some(v) = value {
            crate::command::finite("value", v)?;
        }
        *channel(&mut self.ai_forced, ch, "analog inputs")? = value;
        *channel(&mut self.image.ai, ch, "analog inputs")? = value.unwrap_or(0.0);
        self.version += 1;
        Ok(())
    }

    fn write_digital_output(&mut self, ch: u16, value: bool) -> Result<(), EngineError> {
        *channel(&mut self.image.do_, ch, "digital outputs")? = value;
        self.version += 1;
        Ok(())
    }

    /// One more change of digital input `ch` (NMC GetDiReverseCount).
    fn count_edge(&mut self, ch: u16) {
        if let Some(n) = self.image.di_edges.get_mut(usize::from(ch)) {
            *n = n.wrapping_add(1);
        }
    }

    fn write_analog_output(&mut self, ch: u16, value: f64) -> Result<(), EngineError> {
        crate::command::finite("value", value)?;
        *channel(&mut self.image.ao, ch, "analog outputs")? = value;
        self.version += 1;
        Ok(())
    }
}

/// A CiA 402 drive on the engine's fieldbus.
#[derive(Clone, Debug)]
struct Slave {
    drive: Cia402Drive,
    master: DriveMaster,
    /// Engine-mastered drives: the power state the engine is walking the drive to.
    power: Option<PowerTarget>,
    /// The controlword the engine wrote last.
    controlword: u16,
}

/// Which stages one servo period runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stages {
    All,
    /// Everything a [`machine::Checkpoint`] saves and puts back (`estimate.rs`).
    DryRun,
}

#[derive(Debug)]
pub struct Engine {
    period: f64,
    tick: u64,
    axes: Vec<Axis>,
    io: Io,
    ledger: Ledger,
    slaves: Vec<Slave>,
    /// The slave bound to each axis, if any.
    axis_slave: Vec<Option<usize>>,
    /// Commands the drives emitted this tick (reused; no allocation per tick).
    drive_commands: Vec<Command>,
    /// The axis groups (issue 11): stage 2 runs them before the other planners.
    groups: Groups,
    /// `enable_all` left engine-mastered drives walking to Operation enabled: once no drive
    /// walks there any more, the groups are enabled as `enable_all` enables them.
    groups_await_power: bool,
    /// Gears and cams (issue 12): stage 3 steps masters before their slaves.
    couplings: Couplings,
    /// Stage 2's planners, in the order they were added.
    planners: Vec<Box<dyn MachinePlanner>>,
    /// The setpoints of the planner being run (reused; no allocation per tick).
    feeds: Feeds,
    /// Capture channels and position-compare outputs (issue 12 items 4–5).
    triggers: Triggers,
    /// Data sampling (issue 12 item 9): stage 5 records after the axes and drives.
    samplers: Samplers,
    /// Streams armed to start on a digital input edge (`stream_inputs.rs`).
    input_starts: Vec<stream_inputs::InputStart>,
    /// `gantry_home` runs, running or ended (`gantry_home.rs`).
    gantry_homes: Vec<gantry_home::GantryHoming>,
    /// The E-stop input (`estop_input.rs`), watched in stage 1b.
    estop_input: estop_input::EstopInput,
    /// The watchdog and input stops (`guards.rs`), judged after the axes each tick.
    guards: Guards,
}

impl Engine {
    /// Build the machine a config describes. The config is validated first.
    pub fn new(config: &EngineConfig) -> Result<Engine, ConfigError> {
        config.validate()?;
        let rng = Rng::new(config.seed);
        let axes = config
            .axes
            .iter()
            .enumerate()
            .map(|(i, a)| Axis::new(i as AxisIndex, a, config.period, &rng))
            .collect();
        let mut slaves = Vec::with_capacity(config.drives.len());
        let mut axis_slave = vec![None; config.axes.len()];
        for (i, d) in config.drives.iter().enumerate() {
            let drive = Cia402Drive::new(d.clone())
                .map_err(|e| ConfigError::new(format!("drives[{i}]"), e.to_string()))?;
            if let Some(slot) = axis_slave.get_mut(d.axis as usize) {
                *slot = Some(i);
            }
            slaves.push(Slave {
                drive,
                master: d.master,
                power: None,
                controlword: 0,
            });
        }
        let mut couplings = Couplings::default();
        for (i, table) in config.cam_tables.iter().enumerate() {
            if config
                .cam_tables
                .iter()
                .take(i)
                .any(|t| t.table == table.table)
            {
                return Err(ConfigError::new(
                    format!("cam_tables[{i}].table"),
                    format!("table {} is defined twice", table.table),
                ));
            }
            couplings
                .define_table(table.clone())
                .map_err(|e| ConfigError::new(format!("cam_tables[{i}]"), e.to_string()))?;
        }
        let io = &config.io;
        Ok(Engine {
            period: config.period,
            tick: 0,
            axes,
            io: Io {
                version: 1,
                image: IoImage {
                    di: vec![false; io.digital_inputs as usize],
                    do_: vec![false; io.digital_outputs as usize],
                    ai: vec![0.0; io.analog_inputs as usize],
                    ao: vec![0.0; io.analog_outputs as usize],
                    di_edges: vec![0; io.digital_inputs as usize],
                    do_pulses: vec![0; io.digital_outputs as usize],
                },
                di_forced: vec![None; io.digital_inputs as usize],
                ai_forced: vec![None; io.analog_inputs as usize],
                bindings: io.bindings.clone(),
                pulses: Default::default(),
                ao_bindings: Default::default(),
            },
            ledger: Ledger::default(),
            slaves,
            axis_slave,
            drive_commands: Vec::new(),
            groups: Groups::new(config.groups.clone()),
            groups_await_power: false,
            couplings,
            planners: Vec::new(),
            feeds: Feeds::default(),
            triggers: Triggers::default(),
            samplers: Samplers::default(),
            input_starts: Vec::new(),
            gantry_homes: Vec::new(),
            estop_input: Default::default(),
            guards: Guards::default(),
        })
    }

    /// Servo period, seconds.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// Ticks since start.
    pub fn tick(&self) -> u64 {
        self.tick
    }

    /// Engine time, seconds.
    pub fn time(&self) -> f64 {
        self.tick as f64 * self.period
    }

    pub fn axis_count(&self) -> usize {
        self.axes.len()
    }

    /// The status record of `axis`, assembled now (see `Axis::status`).
    pub fn axis_status(&self, axis: usize) -> Option<AxisStatus> {
        self.axes.get(axis).map(Axis::status)
    }

    pub fn axis(&self, axis: usize) -> Option<&Axis> {
        self.axes.get(axis)
    }

    pub fn io(&self) -> &IoImage {
        &self.io.image
    }

    /// Apply one command at the current tick. Each family goes to its own function: the axis
    /// family to the axis (through its drive first, for power commands on an engine-mastered
    /// drive), I/O to the I/O image, slave commands to a drive's dictionary, machine commands
    /// to the whole machine, group commands to the group registry (issue 11), coupling
    /// commands to the coupling registry (issue 12).
    pub fn apply(&mut self, command: Command) -> Result<Reply, EngineError> {
        match command {
            Command::Axis(c) => self.apply_axis_command(c),
            Command::Group(c) => self.apply_group_command(c),
            Command::Coupling(c) => self.apply_coupling_command(c),
            Command::Compensation(c) => self.apply_compensation_command(c),
            Command::Sampling(c) => self.apply_sampling_command(c),
            Command::Io(c) => self.apply_io_command(c),
            Command::Trigger(c) => self.with_triggers(|t, env| t.apply(env, c)),
            Command::Slave(c) => self.apply_slave_command(c),
            Command::Machine(c) => self.apply_machine_command(c),
            Command::Stream(c) => self.apply_stream_command(c),
        }
    }

    /// A command for one axis, from a front-end.
    fn apply_axis_command(&mut self, command: AxisCommand) -> Result<Reply, EngineError> {
        let (gang, disable) = match &command {
            AxisCommand::Enable(Enable { axis }) => {
                (self.couplings.gantry_power_gang(*axis), false)
            }
            AxisCommand::Disable(Disable { axis }) => {
                (self.couplings.gantry_power_gang(*axis), true)
            }
            _ => (Vec::new(), false),
        };
        let reply = self.apply_power_or_other(command)?;
        // A gantry master's power goes to its slaves too (HIMC §7.1.1, digest 004 TV 39).
        for axis in gang {
            self.apply_power_or_other(if disable {
                AxisCommand::Disable(Disable { axis })
            } else {
                AxisCommand::Enable(Enable { axis })
            })?;
        }
        Ok(reply)
    }

    /// One axis command, through its drive first for power commands on an engine-mastered
    /// drive.
    fn apply_power_or_other(&mut self, command: AxisCommand) -> Result<Reply, EngineError> {
        if let Some(reply) = self.route_power(&command) {
            return reply;
        }
        self.apply_to_axis(command)
    }

    /// A command on an axis group (issue 11), applied to the group registry with the axes,
    /// the ledger and the I/O image it may need.
    fn apply_group_command(&mut self, command: GroupCommand) -> Result<Reply, EngineError> {
        self.with_groups(|groups, env| groups.apply(env, command))
    }

    /// Lend the group registry what a group command or tick may touch (the axes, the ledger,
    /// the digital inputs and outputs), and bump the I/O version if an output changed.
    fn with_groups<R>(&mut self, f: impl FnOnce(&mut Groups, &mut GroupEnv) -> R) -> R {
        let Engine {
            axes,
            io,
            ledger,
            tick,
            period,
            groups,
            ..
        } = self;
        let mut env = GroupEnv {
            tick: *tick,
            period: *period,
            axes,
            ledger,
            di: &io.image.di,
            outputs: &mut io.image.do_,
            outputs_changed: false,
            analog_outputs: io.image.ao.len(),
            io_requests: Vec::new(),
            halts: Vec::new(),
        };
        let result = f(groups, &mut env);
        if env.outputs_changed {
            io.version += 1;
        }
        // The groups checked the channels and times when the commands were queued.
        for request in std::mem::take(&mut env.io_requests) {
            let _ = match request {
                GroupIoRequest::Pulse(c) => io.pulses.start(&c, &mut io.image.do_, *period),
                GroupIoRequest::Analog { channel, value } => io.write_analog_output(channel, value),
            };
            io.version += 1;
        }
        result
    }

    /// Lend the capture and compare channels what they may touch (the axes, the I/O image),
    /// and bump the I/O version if an output changed.
    fn with_triggers<R>(&mut self, f: impl FnOnce(&mut Triggers, &mut TriggerEnv) -> R) -> R {
        let Engine {
            axes,
            io,
            tick,
            period,
            triggers,
            ..
        } = self;
        let mut env = TriggerEnv {
            tick: *tick,
            period: *period,
            axes,
            di_forced: &io.di_forced,
            bindings: &io.bindings,
            outputs: &mut io.image.do_,
            outputs_changed: false,
        };
        let result = f(triggers, &mut env);
        if env.outputs_changed {
            io.version += 1;
        }
        result
    }

    /// The capture and compare channels.
    pub fn triggers(&self) -> &Triggers {
        &self.triggers
    }

    /// The axis groups.
    pub fn groups(&self) -> &Groups {
        &self.groups
    }

    /// The status record of group `id`, assembled now.
    pub fn group_status(&self, id: crate::command::GroupId) -> Option<crate::status::GroupStatus> {
        self.groups.get(id).map(|g| g.status(&self.axes))
    }

    /// A gear or cam command (issue 12), applied to the coupling registry with the axes and
    /// the inputs it may need.
    fn apply_coupling_command(&mut self, command: CouplingCommand) -> Result<Reply, EngineError> {
        let reply = self.with_couplings(|couplings, env| couplings.apply(env, command));
        if self.couplings.waits_for_captures() {
            // A cam waiting for a capture takes the latches it finds now as old.
            self.couplings.offer_captures(&self.triggers);
        }
        reply
    }

    /// Lend the coupling registry what a coupling command or stage 3 touches: the axes, the
    /// digital inputs and the ledger.
    fn with_couplings<R>(&mut self, f: impl FnOnce(&mut Couplings, &mut CouplingEnv) -> R) -> R {
        let Engine {
            axes,
            io,
            ledger,
            tick,
            period,
            couplings,
            groups,
            ..
        } = self;
        let mut ctx = Context {
            tick: *tick,
            di: &io.image.di,
            ledger,
        };
        let mut env = CouplingEnv {
            axes,
            groups,
            ctx: &mut ctx,
            period: *period,
        };
        f(couplings, &mut env)
    }

    /// The gears and cams.
    pub fn couplings(&self) -> &Couplings {
        &self.couplings
    }

    /// Power commands on an axis whose drive the engine masters go through the drive's state
    /// machine: the engine writes the controlword sequence over the next ticks and the drive
    /// powers the axis when it reaches Operation enabled (HIMC Enable/Disable/Reset, digest 004
    /// §3.2). The reply says the request was taken; the state follows in the status.
    fn route_power(&mut self, command: &AxisCommand) -> Option<Result<Reply, EngineError>> {
        let (axis, target) = match command {
            AxisCommand::Enable(Enable { axis }) => (*axis, PowerTarget::OperationEnabled),
            AxisCommand::Disable(Disable { axis }) => (*axis, PowerTarget::SwitchOnDisabled),
            AxisCommand::Reset(Reset { axis }) => (*axis, PowerTarget::SwitchOnDisabled),
            AxisCommand::ResetFaults(ResetFaults { axis, faults })
                if faults.contains(AxisFlags::DRIVE_ALARM) =>
            {
                (*axis, PowerTarget::SwitchOnDisabled)
            }
            _ => return None,
        };
        let slave = self.axis_slave.get(axis as usize).copied().flatten()?;
        let s = self.slaves.get_mut(slave)?;
        if s.master != DriveMaster::Engine {
            return None;
        }
        if let AxisCommand::Reset(_) | AxisCommand::ResetFaults(_) = command {
            // A fault reset walks Fault → Switch on disabled; the axis's own latches are
            // cleared directly.
            if s.drive.state() == State::Fault {
                s.power = Some(target);
            }
            return Some(self.apply_to_axis(command.clone()));
        }
        s.power = Some(target);
        Some(Ok(Reply::Done))
    }

    /// A command for one axis, applied to the axis itself (no drive routing): the front-ends'
    /// commands after `route_power`, and the commands a drive emits.
    fn apply_to_axis(&mut self, command: AxisCommand) -> Result<Reply, EngineError> {
        let (axis, mut ctx) = self.axis_with_context(command.axis())?;
        match command {
            AxisCommand::Enable(_) => axis.enable(&mut ctx),
            AxisCommand::Disable(_) => axis.disable(&mut ctx),
            AxisCommand::Reset(_) => axis.reset(&mut ctx),
            AxisCommand::ResetFaults(ResetFaults { axis: _, faults }) => axis.reset_faults(faults),
            AxisCommand::MoveAbsolute(MoveAbsolute {
                axis: _,
                position,
                velocity,
                acceleration,
                deceleration,
                jerk,
                buffer_mode,
            }) => axis.submit(
                &mut ctx,
                MotionSubmission {
                    kind: CommandKind::MoveAbsolute,
                    action: MotionAction::MoveAbsolute { position },
                    overrides: Overrides {
                        velocity,
                        acceleration,
                        deceleration,
                        jerk,
                    },
                    buffer_mode,
                },
            ),
            AxisCommand::MoveRelative(MoveRelative {
                axis: _,
                distance,
                velocity,
                acceleration,
                deceleration,
                jerk,
                buffer_mode,
            }) => axis.submit(
                &mut ctx,
                MotionSubmission {
                    kind: CommandKind::MoveRelative,
                    action: MotionAction::MoveRelative { distance },
                    overrides: Overrides {
                        velocity,
                        acceleration,
                        deceleration,
                        jerk,
                    },
                    buffer_mode,
                },
            ),
            AxisCommand::MoveVelocity(MoveVelocity {
                axis: _,
                velocity,
                acceleration,
                deceleration,
                jerk,
                buffer_mode,
            }) => axis.submit(
                &mut ctx,
                MotionSubmission {
                    kind: CommandKind::MoveVelocity,
                    action: MotionAction::MoveVelocity { velocity },
                    overrides: Overrides {
                        velocity: None,
                        acceleration,
                        deceleration,
                        jerk,
                    },
                    buffer_mode,
                },
            ),
            AxisCommand::Stop(Stop {
                axis: _,
                mode,
                deceleration,
            }) => axis.stop(&mut ctx, mode, deceleration),
            AxisCommand::Halt(Halt {
                axis: _,
                deceleration,
            }) => axis.halt(&mut ctx, deceleration),
            AxisCommand::Resume(_) => axis.resume(&mut ctx),
            AxisCommand::Home(home) => {
                let spec = homing_spec(axis, &home)?;
                axis.submit(
                    &mut ctx,
                    MotionSubmission {
                        kind: CommandKind::Home,
                        action: MotionAction::Home(spec),
                        overrides: Overrides::default(),
                        buffer_mode: home.buffer_mode,
                    },
                )
            }
            AxisCommand::SetPosition(SetPosition {
                axis: _,
                position,
                frame,
            }) => axis.set_position(position, frame),
            AxisCommand::SetParameter(SetParameter {
                axis: _,
                name,
                value,
                lenient,
            }) => axis.set_parameter(name, value, lenient),
            AxisCommand::GetParameter(GetParameter { axis: _, name }) => Ok(Reply::Value {
                value: axis.get_parameter(name),
            }),
            AxisCommand::ModifyTarget(ModifyTarget {
                axis: _,
                position,
                relative,
            }) => axis.modify_target(&mut ctx, position, relative),
            AxisCommand::Cancel(Cancel { axis: _, scope }) => axis.cancel(&mut ctx, scope),
            AxisCommand::ForceInput(ForceInput {
                axis: _,
                input,
                value,
            }) => axis.force_input(input, value),
            AxisCommand::InjectFollowingError(InjectFollowingError { axis: _, amount }) => {
                axis.inject_following_error(amount)
            }
            AxisCommand::Setpoint(StreamSetpoint { axis: _, setpoint }) => {
                axis.setpoint(&mut ctx, setpoint)
            }
        }
    }

    /// One axis and the context a command for it needs (the tick, the digital inputs, the
    /// ledger).
    pub(super) fn axis_with_context(
        &mut self,
        index: AxisIndex,
    ) -> Result<(&mut Axis, Context<'_>), EngineError> {
        let Engine {
            axes,
            io,
            ledger,
            tick,
            ..
        } = self;
        let count = axes.len() as u32;
        let axis = axes
            .get_mut(index as usize)
            .ok_or(EngineError::InvalidAxis {
                axis: u32::from(index),
                count,
            })?;
        let ctx = Context {
            tick: *tick,
            di: &io.image.di,
            ledger,
        };
        Ok((axis, ctx))
    }

    /// A command on the I/O image; it shows in the next snapshot. A digital input changed by
    /// command is an edge at the tick boundary for the captures watching it.
    fn apply_io_command(&mut self, command: IoCommand) -> Result<Reply, EngineError> {
        let io = &mut self.io;
        match command {
            IoCommand::ForceDigitalInput(ForceDigitalInput { channel, value }) => {
                let before = io.image.di.get(channel as usize).copied();
                io.force_digital_input(channel, value)?;
                let after = value.unwrap_or(false);
                if before.is_some_and(|b| b != after) && self.triggers.watches_inputs() {
                    self.with_triggers(|t, env| t.input_changed(env, channel, after));
                }
                Ok(())
            }
            IoCommand::ForceAnalogInput(ForceAnalogInput { channel, value }) => {
                io.force_analog_input(channel, value)
            }
            IoCommand::WriteDigitalOutput(WriteDigitalOutput { channel, value }) => {
                io.write_digital_output(channel, value)
            }
            IoCommand::WriteAnalogOutput(WriteAnalogOutput { channel, value }) => {
                io.write_analog_output(channel, value)
            }
            IoCommand::PulseDigitalOutput(c) => {
                let started = io.pulses.start(&c, &mut io.image.do_, self.period);
                io.version += 1;
                started
            }
            IoCommand::BindAnalogOutput(c) => {
                io.ao_bindings.bind(&c, io.image.ao.len(), &self.axes)
            }
        }
        .map(|()| Reply::Done)
    }

    /// A read or write of a drive's object dictionary, as a fieldbus master's SDO would.
    fn apply_slave_command(&mut self, command: SlaveCommand) -> Result<Reply, EngineError> {
        match command {
            SlaveCommand::ReadObject(ReadObject {
                slave,
                index,
                subindex,
            }) => {
                let value = self
                    .slave_drive(slave)?
                    .read(index, subindex)
                    .map_err(|error| EngineError::Object { slave, error })?;
                Ok(Reply::Object { value })
            }
            SlaveCommand::WriteObject(WriteObject {
                slave,
                index,
                subindex,
                value,
            }) => {
                self.slave_drive(slave)?
                    .write(index, subindex, value)
                    .map_err(|error| EngineError::Object { slave, error })?;
                Ok(Reply::Done)
            }
        }
    }

    fn slave_drive(&mut self, slave: u16) -> Result<&mut Cia402Drive, EngineError> {
        let count = self.slaves.len() as u16;
        self.slaves
            .get_mut(slave as usize)
            .map(|s| &mut s.drive)
            .ok_or(EngineError::InvalidSlave { slave, count })
    }

    /// Advance one servo period, in stages (the order of operations inside a tick is fixed:
    /// traces compare bit for bit):
    ///
    /// 1. `read_inputs`: the I/O image's inputs from last tick's sensors, and the timed
    ///    outputs (`pulse_digital_output`) that toggle this tick; 1b. the E-stop input
    ///    (`set_estop_input`): reaching its active level e-stops the machine in this tick;
    /// 2. `run_planners`: the axis groups (issue 11), in group-number order, then the other
    ///    machine-level planners, feed their axes this tick's setpoints;
    /// 3. `step_axes`: every axis, in index order, or with couplings (issue 12) masters before
    ///    their slaves, each slave fed from its master's state of this tick (compensation tables
    ///    first read their reference axes as the previous tick left them:
    ///    `gather_compensation_inputs`); 3b. analog outputs bound to an axis variable take its
    ///    value of this tick (`bind_analog_output`); then the capture channels latch this
    ///    tick's edges and the compare channels fire their outputs (issue 12 items 4–5);
    /// 4. `step_drives`: the CiA 402 drives see their axes and answer with commands;
    /// 5. `sample`: armed and recording data samplers read the machine as the tick left it;
    /// 6. outputs and status: no per-tick work. Outputs change only by command (or a timed
    ///    output's train, stage 1, or a bound analog output, stage 3b), and status is
    ///    assembled when it is read ([`Engine::snapshot_into`], [`Engine::axis_status`]).
    ///
    /// Commands ([`Engine::apply`]) arrive between steps and act on the state the last step
    /// left.
    pub fn step(&mut self) {
        self.advance(Stages::All);
    }

    /// One servo period; a dry run ([`Stages::DryRun`], `estimate.rs`) leaves out the
    /// registered planners and the samplers, whose state a checkpoint does not save.
    fn advance(&mut self, stages: Stages) {
        self.start_streams_on_inputs();
        self.step_gantry_homes();
        self.tick += 1;
        self.read_inputs();
        self.watch_estop_input();
        self.with_groups(|groups, env| groups.step(env));
        if stages == Stages::All {
            self.run_planners();
        }
        self.gather_compensation_inputs();
        self.step_axes();
        self.drive_bound_outputs();
        self.with_triggers(|t, env| t.step(env));
        self.step_guards();
        self.step_drives();
        if self.groups_await_power {
            self.enable_groups_once_powered();
        }
        if stages == Stages::All {
            self.sample();
        }
    }

    /// Add a machine-level planner to stage 2 (see [`MachinePlanner`]). Planners run in the
    /// order they were added; the one added last has the last word on an axis two of them feed.
    pub fn add_planner(&mut self, planner: Box<dyn MachinePlanner>) {
        self.planners.push(planner);
    }

    /// Stage 2, machine-level planners, after the axis groups (`group::Groups::step`, run by
    /// [`Engine::advance`]: each reads its members as the previous tick left them, steps its
    /// path and feeds every member this tick's setpoint; a refusal or a member in trouble stops
    /// the whole group; they also write the buffered digital outputs, start buffered
    /// single-axis moves and finish their commands in the ledger). Every registered planner
    /// reads the axes as the previous tick left them and writes setpoints; each setpoint
    /// becomes its axis's command source for this tick, or goes back to the planner as a
    /// refusal.
    fn run_planners(&mut self) {
        let Engine {
            axes,
            io,
            ledger,
            tick,
            planners,
            feeds,
            ..
        } = self;
        let mut ctx = Context {
            tick: *tick,
            di: &io.image.di,
            ledger,
        };
        let count = axes.len() as u32;
        for planner in planners.iter_mut() {
            feeds.clear();
            planner.plan(*tick, axes, feeds);
            for &(index, feed) in feeds.entries() {
                let result = match axes.get_mut(index as usize) {
                    Some(axis) => axis.feed(&mut ctx, feed),
                    None => Err(EngineError::InvalidAxis {
                        axis: index as u32,
                        count,
                    }),
                };
                if let Err(e) = result {
                    planner.refused(index, &e);
                }
            }
        }
    }

    /// Stage 3, the axes. Reads the digital inputs (stage 1) and each axis's own state and
    /// source; writes each axis's command, output, plant, encoder, switches, supervision and
    /// command progress for this tick, and the ledger of finished commands.
    ///
    /// With couplings (issue 12) the axes step in the couplings' order instead, masters before
    /// their slaves, and each slave is fed from its master just before it steps: a slave
    /// follows its master's state of this same tick (`crate::coupling`).
    fn step_axes(&mut self) {
        if self.couplings.waits_for_captures() {
            // HMC cam event start: the latches of the last tick's stage 3b.
            self.couplings.offer_captures(&self.triggers);
        }
        self.with_couplings(|couplings, env| couplings.step_axes(env));
    }

    /// Stage 4, drives and fieldbus. Each drive reads its axis's status after stage 3 and the
    /// controlword the engine writes for an engine-mastered power request; it writes its
    /// statusword and the commands that take effect from the next tick (applied to the axis
    /// here, refusals going back to the drive: ARCHITECTURE §3.8).
    fn step_drives(&mut self) {
        let now = self.time();
        let mut commands = std::mem::take(&mut self.drive_commands);
        for i in 0..self.slaves.len() {
            let Some(slave) = self.slaves.get_mut(i) else {
                break;
            };
            let axis = slave.drive.config().axis as usize;
            let Some(status) = self.axes.get(axis).map(Axis::status) else {
                continue;
            };
            if let Some(target) = slave.power {
                let cw = controlword_for(target, slave.drive.statusword(), slave.controlword);
                if cw != slave.controlword {
                    // 0x6040 is writable and the value in range: this cannot fail.
                    let _ = slave.drive.write(obj::CONTROLWORD, 0, Value::U16(cw));
                    slave.controlword = cw;
                }
            }
            commands.clear();
            slave.drive.step(&status, now, &mut commands);
            if slave.power.is_some_and(|t| reached(t, slave.drive.state())) {
                // Reached: from here only a new enable/disable/reset moves the drive, so a
                // fault stays a fault until the user resets it.
                slave.power = None;
            }
            for command in commands.drain(..) {
                // A drive's commands reach its axis directly: routing them back through the
                // drive's power state machine would loop.
                let result = match command.clone() {
                    Command::Axis(c) => self.apply_to_axis(c),
                    other => self.apply(other),
                };
                if let Some(slave) = self.slaves.get_mut(i) {
                    slave.drive.on_reply(&command, &result);
                }
            }
        }
        self.drive_commands = commands;
    }

    /// The drive bound to `axis`, if any.
    pub fn drive_of(&self, axis: usize) -> Option<&Cia402Drive> {
        let slave = self.axis_slave.get(axis).copied().flatten()?;
        self.slaves.get(slave).map(|s| &s.drive)
    }

    pub fn drive(&self, slave: usize) -> Option<&Cia402Drive> {
        self.slaves.get(slave).map(|s| &s.drive)
    }

    /// A drive for its fieldbus ([`crate::runtime::Fieldbus`]): SDO and PDO access to its
    /// dictionary between steps.
    pub fn drive_mut(&mut self, slave: usize) -> Option<&mut Cia402Drive> {
        self.slaves.get_mut(slave).map(|s| &mut s.drive)
    }

    /// Number of CiA 402 drives (slave numbers 0 …).
    pub fn drive_count(&self) -> usize {
        self.slaves.len()
    }

    /// Stage 1, inputs. Reads each wired axis sensor's electrical level as the last tick left
    /// it, and the forced channels; writes the digital inputs wired to axis signals (unless
    /// forced) and bumps the I/O version when one changes. Forced and unwired channels change
    /// only by command, so nothing else runs per tick.
    fn read_inputs(&mut self) {
        let io = &mut self.io;
        for b in &io.bindings {
            let ch = b.channel as usize;
            if io.di_forced.get(ch).copied().flatten().is_some() {
                continue;
            }
            let Some(axis) = self.axes.get(b.axis as usize) else {
                continue;
            };
            // A wire from the sensor: its electrical level, not the controller's reading of it.
            let level = axis.sensor(b.signal);
            if let Some(di) = io.image.di.get_mut(ch) {
                if *di != level {
                    *di = level;
                    io.version += 1;
                    if let Some(n) = io.image.di_edges.get_mut(ch) {
                        *n = n.wrapping_add(1);
                    }
                }
            }
        }
        if io.pulses.step(&mut io.image.do_, &mut io.image.do_pulses) {
            io.version += 1;
        }
    }

    /// Stage 3b: analog outputs bound to an axis variable take this tick's value.
    fn drive_bound_outputs(&mut self) {
        let io = &mut self.io;
        if !io.ao_bindings.is_empty()
            && io
                .ao_bindings
                .step(&self.axes, self.period, &mut io.image.ao)
        {
            io.version += 1;
        }
    }

    /// Copy the machine's state into `snapshot`, reusing its allocations.
    pub fn snapshot_into(&self, snapshot: &mut Snapshot) {
        snapshot.tick = self.tick;
        snapshot.period = self.period;
        snapshot.axes.resize(self.axes.len(), AxisStatus::default());
        for (out, axis) in snapshot.axes.iter_mut().zip(&self.axes) {
            axis.status_into(out);
        }
        self.groups
            .status_into(&self.axes, &snapshot.axes, &mut snapshot.groups);
        self.couplings.status_into(&mut snapshot.couplings);
        self.couplings.handwheels_into(&mut snapshot.handwheels);
        snapshot.external_encoders = self.couplings.external_encoders();
        self.couplings.follows_into(&mut snapshot.follows);
        self.stream_input_starts_into(&mut snapshot.stream_input_starts);
        self.gantry_homes_into(&mut snapshot.gantry_homes);
        self.triggers.status_into(
            &mut snapshot.captures,
            &mut snapshot.compares,
            &mut snapshot.z_compares,
        );
        if snapshot.io_version != self.io.version {
            snapshot.io.clone_from(&self.io.image);
            snapshot.io_version = self.io.version;
        }
        // Parameters change rarely: share one copy until a version moves (versions only grow,
        // so their sum moves exactly when one does).
        let params_version = self.axes.iter().map(Axis::params_version).sum();
        if snapshot.params_version != params_version || snapshot.params.len() != self.axes.len() {
            snapshot.params = Arc::new(self.axes.iter().map(|a| a.params().clone()).collect());
            snapshot.params_version = params_version;
        }
        self.samplers.status_into(&mut snapshot.samplers);
        self.guards
            .position_watches_into(&mut snapshot.position_watches);
        snapshot.drives.clear();
        snapshot
            .drives
            .extend(self.slaves.iter().map(|s| DriveStatus {
                axis: s.drive.config().axis,
                statusword: s.drive.statusword(),
                mode: s.drive.mode().code(),
                error_code: s.drive.error_code(),
            }));
    }

    pub fn snapshot(&self) -> Snapshot {
        let mut s = Snapshot::default();
        self.snapshot_into(&mut s);
        s
    }
}

/// The homing run a `home` command asks for: absent values come from the axis's `home_*`
/// parameters.
fn homing_spec(axis: &Axis, home: &Home) -> Result<HomingSpec, EngineError> {
    for (name, v) in [
        ("switch_velocity", home.switch_velocity),
        ("zero_velocity", home.zero_velocity),
        ("offset", home.offset),
    ] {
        if let Some(v) = v {
            crate::command::bounded(name, v)?;
        }
    }
    let p = axis.params();
    Ok(HomingSpec {
        method: home.method.unwrap_or(p.get(ParamId::HomeMethod) as i16),
        switch_velocity: home
            .switch_velocity
            .unwrap_or(p.get(ParamId::HomeSwitchVelocity)),
        zero_velocity: home
            .zero_velocity
            .unwrap_or(p.get(ParamId::HomeZeroVelocity)),
        acceleration: home
            .acceleration
            .unwrap_or(p.get(ParamId::HomeAcceleration)),
        offset: home.offset.unwrap_or(p.get(ParamId::HomeOffset)),
        timeout: home.timeout.unwrap_or(p.get(ParamId::HomeTimeout)),
        quirks: home.quirks,
    })
}

fn reached(target: PowerTarget, state: State) -> bool {
    matches!(
        (target, state),
        (PowerTarget::OperationEnabled, State::OperationEnabled)
            | (PowerTarget::SwitchedOn, State::SwitchedOn)
            | (PowerTarget::ReadyToSwitchOn, State::ReadyToSwitchOn)
            | (PowerTarget::SwitchOnDisabled, State::SwitchOnDisabled)
    )
}
