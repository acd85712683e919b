//! The engine: axes, machine I/O and the command ledger, advanced one servo period per
//! [`Engine::step`] (ARCHITECTURE §3). Same config + same commands at the same ticks ⇒
//! bit-identical state: nothing here reads a clock, iterates a hash map or uses a thread.

use crate::axis::{Action, Axis, Context, Ledger, MotionRequest, Overrides};
use crate::cia402::{controlword_for, obj, Cia402Drive, DriveMaster, PowerTarget, State};
use crate::command::{AxisIndex, Command, CommandKind, EngineError, Reply};
use crate::config::{ConfigError, EngineConfig, InputBinding};
use crate::homing::HomingSpec;
use crate::od::Value;
use crate::param::ParamId;
use crate::rng::Rng;
use crate::status::{AxisStatus, DriveStatus, IoImage, Snapshot};
use std::sync::Arc;

/// The machine's digital and analog I/O.
#[derive(Clone, Debug)]
struct Io {
    image: IoImage,
    /// Bumped on every change of `image`; starts at 1 so a fresh snapshot (0) always copies.
    version: u64,
    di_forced: Vec<Option<bool>>,
    ai_forced: Vec<Option<f64>>,
    bindings: Vec<InputBinding>,
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
        *channel(&mut self.image.di, ch, "digital inputs")? = value.unwrap_or(false);
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

    fn write_analog_output(&mut self, ch: u16, value: f64) -> Result<(), EngineError> {
        crate::command::finite("value", value)?;
        *channel(&mut self.image.ao, ch, "analog outputs")? = value;
        self.version += 1;
        Ok(())
    }
}

/// A CiA 402 drive on the engine's fieldbus.
#[derive(Debug)]
struct Slave {
    drive: Cia402Drive,
    master: DriveMaster,
    /// Engine-mastered drives: the power state the engine is walking the drive to.
    power: Option<PowerTarget>,
    /// The controlword the engine wrote last.
    controlword: u16,
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
                },
                di_forced: vec![None; io.digital_inputs as usize],
                ai_forced: vec![None; io.analog_inputs as usize],
                bindings: io.bindings.clone(),
            },
            ledger: Ledger::default(),
            slaves,
            axis_slave,
            drive_commands: Vec::new(),
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

    /// Apply one command at the current tick.
    pub fn apply(&mut self, command: Command) -> Result<Reply, EngineError> {
        if let Some(reply) = self.route_power(&command) {
            return reply;
        }
        self.apply_to_axes(command)
    }

    /// Power commands on an axis whose drive the engine masters go through the drive's state
    /// machine: the engine writes the controlword sequence over the next ticks and the drive
    /// powers the axis when it reaches Operation enabled (HIMC Enable/Disable/Reset, digest 004
    /// §3.2). The reply says the request was taken; the state follows in the status.
    fn route_power(&mut self, command: &Command) -> Option<Result<Reply, EngineError>> {
        let (axis, target) = match command {
            Command::Enable { axis } => (*axis, PowerTarget::OperationEnabled),
            Command::Disable { axis } => (*axis, PowerTarget::SwitchOnDisabled),
            Command::Reset { axis } => (*axis, PowerTarget::SwitchOnDisabled),
            _ => return None,
        };
        let slave = self.axis_slave.get(axis as usize).copied().flatten()?;
        let s = self.slaves.get_mut(slave)?;
        if s.master != DriveMaster::Engine {
            return None;
        }
        if let Command::Reset { .. } = command {
            // A fault reset walks Fault → Switch on disabled; the axis's own latches are
            // cleared directly.
            if s.drive.state() == State::Fault {
                s.power = Some(target);
            }
            return Some(self.apply_to_axes(command.clone()));
        }
        s.power = Some(target);
        Some(Ok(Reply::Done))
    }

    fn apply_to_axes(&mut self, command: Command) -> Result<Reply, EngineError> {
        let Engine {
            axes,
            io,
            ledger,
            tick,
            slaves,
            ..
        } = self;
        let mut ctx = Context {
            tick: *tick,
            di: &io.image.di,
            ledger,
        };
        fn slave_of(slaves: &mut [Slave], slave: u16) -> Result<&mut Slave, EngineError> {
            let count = slaves.len() as u16;
            slaves
                .get_mut(slave as usize)
                .ok_or(EngineError::InvalidSlave { slave, count })
        }
        fn axis_mut(axes: &mut [Axis], axis: AxisIndex) -> Result<&mut Axis, EngineError> {
            let count = axes.len() as u32;
            axes.get_mut(axis as usize).ok_or(EngineError::InvalidAxis {
                axis: axis as u32,
                count,
            })
        }
        match command {
            Command::Enable { axis } => axis_mut(axes, axis)?.enable(&mut ctx),
            Command::Disable { axis } => axis_mut(axes, axis)?.disable(&mut ctx),
            Command::Reset { axis } => axis_mut(axes, axis)?.reset(&mut ctx),
            Command::MoveAbsolute {
                axis,
                position,
                velocity,
                acceleration,
                deceleration,
                jerk,
                buffer_mode,
            } => axis_mut(axes, axis)?.submit(
                &mut ctx,
                MotionRequest {
                    kind: CommandKind::MoveAbsolute,
                    action: Action::MoveAbsolute { position },
                    overrides: Overrides {
                        velocity,
                        acceleration,
                        deceleration,
                        jerk,
                    },
                    buffer_mode,
                },
            ),
            Command::MoveRelative {
                axis,
                distance,
                velocity,
                acceleration,
                deceleration,
                jerk,
                buffer_mode,
            } => axis_mut(axes, axis)?.submit(
                &mut ctx,
                MotionRequest {
                    kind: CommandKind::MoveRelative,
                    action: Action::MoveRelative { distance },
                    overrides: Overrides {
                        velocity,
                        acceleration,
                        deceleration,
                        jerk,
                    },
                    buffer_mode,
                },
            ),
            Command::MoveVelocity {
                axis,
                velocity,
                acceleration,
                deceleration,
                jerk,
                buffer_mode,
            } => axis_mut(axes, axis)?.submit(
                &mut ctx,
                MotionRequest {
                    kind: CommandKind::MoveVelocity,
                    action: Action::MoveVelocity { velocity },
                    overrides: Overrides {
                        velocity: None,
                        acceleration,
                        deceleration,
                        jerk,
                    },
                    buffer_mode,
                },
            ),
            Command::Stop {
                axis,
                mode,
                deceleration,
            } => axis_mut(axes, axis)?.stop(&mut ctx, mode, deceleration),
            Command::Halt { axis, deceleration } => {
                axis_mut(axes, axis)?.halt(&mut ctx, deceleration)
            }
            Command::Resume { axis } => axis_mut(axes, axis)?.resume(&mut ctx),
            Command::Home {
                axis,
                method,
                switch_velocity,
                zero_velocity,
                acceleration,
                offset,
                timeout,
                quirks,
                buffer_mode,
            } => {
                let a = axis_mut(axes, axis)?;
                for (name, v) in [
                    ("switch_velocity", switch_velocity),
                    ("zero_velocity", zero_velocity),
                    ("offset", offset),
                ] {
                    if let Some(v) = v {
                        crate::command::bounded(name, v)?;
                    }
                }
                let p = a.params();
                let spec = HomingSpec {
                    method: method.unwrap_or(p.get(ParamId::HomeMethod) as i16),
                    switch_velocity: switch_velocity.unwrap_or(p.get(ParamId::HomeSwitchVelocity)),
                    zero_velocity: zero_velocity.unwrap_or(p.get(ParamId::HomeZeroVelocity)),
                    acceleration: acceleration.unwrap_or(p.get(ParamId::HomeAcceleration)),
                    offset: offset.unwrap_or(p.get(ParamId::HomeOffset)),
                    timeout: timeout.unwrap_or(p.get(ParamId::HomeTimeout)),
                    quirks,
                };
                a.submit(
                    &mut ctx,
                    MotionRequest {
                        kind: CommandKind::Home,
                        action: Action::Home(spec),
                        overrides: Overrides::default(),
                        buffer_mode,
                    },
                )
            }
            Command::SetPosition {
                axis,
                position,
                frame,
            } => axis_mut(axes, axis)?.set_position(position, frame),
            Command::SetParameter {
                axis,
                name,
                value,
                lenient,
            } => axis_mut(axes, axis)?.set_parameter(name, value, lenient),
            Command::GetParameter { axis, name } => Ok(Reply::Value {
                value: axis_mut(axes, axis)?.get_parameter(name),
            }),
            Command::ModifyTarget {
                axis,
                position,
                relative,
            } => axis_mut(axes, axis)?.modify_target(&mut ctx, position, relative),
            Command::Cancel { axis, scope } => axis_mut(axes, axis)?.cancel(&mut ctx, scope),
            Command::CommandState { id } => {
                let state = axes
                    .iter()
                    .find_map(|a| a.queued_state(id))
                    .or_else(|| ctx.ledger.lookup(id))
                    .ok_or(EngineError::UnknownCommand { id })?;
                Ok(Reply::CommandState { id, state })
            }
            Command::ForceInput { axis, input, value } => {
                axis_mut(axes, axis)?.force_input(input, value)
            }
            Command::InjectFollowingError { axis, amount } => {
                axis_mut(axes, axis)?.inject_following_error(amount)
            }
            Command::Setpoint { axis, setpoint } => {
                axis_mut(axes, axis)?.setpoint(&mut ctx, setpoint)
            }
            Command::ForceDigitalInput { channel, value } => {
                io.force_digital_input(channel, value).map(|()| Reply::Done)
            }
            Command::ForceAnalogInput { channel, value } => {
                io.force_analog_input(channel, value).map(|()| Reply::Done)
            }
            Command::WriteDigitalOutput { channel, value } => io
                .write_digital_output(channel, value)
                .map(|()| Reply::Done),
            Command::WriteAnalogOutput { channel, value } => {
                io.write_analog_output(channel, value).map(|()| Reply::Done)
            }
            Command::ReadObject {
                slave,
                index,
                subindex,
            } => {
                let s = slave_of(slaves, slave)?;
                let value = s
                    .drive
                    .read(index, subindex)
                    .map_err(|error| EngineError::Object { slave, error })?;
                Ok(Reply::Object { value })
            }
            Command::WriteObject {
                slave,
                index,
                subindex,
                value,
            } => {
                let s = slave_of(slaves, slave)?;
                s.drive
                    .write(index, subindex, value)
                    .map_err(|error| EngineError::Object { slave, error })?;
                Ok(Reply::Done)
            }
        }
    }

    /// Advance one servo period.
    pub fn step(&mut self) {
        self.tick += 1;
        self.update_inputs();
        let mut ctx = Context {
            tick: self.tick,
            di: &self.io.image.di,
            ledger: &mut self.ledger,
        };
        for axis in &mut self.axes {
            axis.step(&mut ctx);
        }
        self.step_drives();
    }

    /// Each drive sees its axis after the tick and emits the commands that take effect from the
    /// next one; refusals go back to the drive (ARCHITECTURE §3.8).
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
                let result = self.apply_to_axes(command.clone());
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

    /// Digital inputs wired to axis signals follow them (last tick's levels), unless forced.
    /// Forced and unwired channels change only by command, so nothing else runs per tick.
    fn update_inputs(&mut self) {
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
                }
            }
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

fn reached(target: PowerTarget, state: State) -> bool {
    matches!(
        (target, state),
        (PowerTarget::OperationEnabled, State::OperationEnabled)
            | (PowerTarget::SwitchedOn, State::SwitchedOn)
            | (PowerTarget::ReadyToSwitchOn, State::ReadyToSwitchOn)
            | (PowerTarget::SwitchOnDisabled, State::SwitchOnDisabled)
    )
}
