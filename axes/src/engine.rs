//! The engine: axes, machine I/O and the command ledger, advanced one servo period per
//! [`Engine::step`] (ARCHITECTURE §3). Same config + same commands at the same ticks ⇒
//! bit-identical state: nothing here reads a clock, iterates a hash map or uses a thread.

use crate::axis::{Action, Axis, Context, Ledger, MotionRequest, Overrides};
use crate::command::{AxisIndex, Command, CommandKind, EngineError, Reply};
use crate::config::{AxisSignal, ConfigError, EngineConfig, InputBinding};
use crate::homing::HomingSpec;
use crate::param::ParamId;
use crate::rng::Rng;
use crate::status::{AxisFlags, AxisStatus, IoImage, Snapshot};

/// The machine's digital and analog I/O.
#[derive(Clone, Debug)]
struct Io {
    image: IoImage,
    di_forced: Vec<Option<bool>>,
    ai_forced: Vec<Option<f64>>,
    bindings: Vec<InputBinding>,
}

#[derive(Debug)]
pub struct Engine {
    period: f64,
    tick: u64,
    axes: Vec<Axis>,
    io: Io,
    ledger: Ledger,
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
        let io = &config.io;
        Ok(Engine {
            period: config.period,
            tick: 0,
            axes,
            io: Io {
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

    pub fn axis_status(&self, axis: usize) -> Option<&AxisStatus> {
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
        let Engine {
            axes,
            io,
            ledger,
            tick,
            ..
        } = self;
        let mut ctx = Context {
            tick: *tick,
            di: &io.image.di,
            ledger,
        };
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
                let slot =
                    io.di_forced
                        .get_mut(channel as usize)
                        .ok_or(EngineError::InvalidChannel {
                            kind: "digital inputs",
                            channel,
                            count: io.image.di.len() as u16,
                        })?;
                *slot = value;
                Ok(Reply::Done)
            }
            Command::ForceAnalogInput { channel, value } => {
                if let Some(v) = value {
                    crate::command::finite("value", v)?;
                }
                let slot =
                    io.ai_forced
                        .get_mut(channel as usize)
                        .ok_or(EngineError::InvalidChannel {
                            kind: "analog inputs",
                            channel,
                            count: io.image.ai.len() as u16,
                        })?;
                *slot = value;
                Ok(Reply::Done)
            }
            Command::WriteDigitalOutput { channel, value } => {
                let count = io.image.do_.len() as u16;
                let slot =
                    io.image
                        .do_
                        .get_mut(channel as usize)
                        .ok_or(EngineError::InvalidChannel {
                            kind: "digital outputs",
                            channel,
                            count,
                        })?;
                *slot = value;
                Ok(Reply::Done)
            }
            Command::WriteAnalogOutput { channel, value } => {
                crate::command::finite("value", value)?;
                let count = io.image.ao.len() as u16;
                let slot =
                    io.image
                        .ao
                        .get_mut(channel as usize)
                        .ok_or(EngineError::InvalidChannel {
                            kind: "analog outputs",
                            channel,
                            count,
                        })?;
                *slot = value;
                Ok(Reply::Done)
            }
            Command::ReadObject { slave, .. } | Command::WriteObject { slave, .. } => {
                Err(EngineError::InvalidSlave { slave, count: 0 })
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
    }

    /// The input images: forced values win, then wiring from axis signals (last tick's), else
    /// the input stays low.
    fn update_inputs(&mut self) {
        let io = &mut self.io;
        for (di, forced) in io.image.di.iter_mut().zip(&io.di_forced) {
            *di = forced.unwrap_or(false);
        }
        for b in &io.bindings {
            if io
                .di_forced
                .get(b.channel as usize)
                .copied()
                .flatten()
                .is_some()
            {
                continue;
            }
            let Some(axis) = self.axes.get(b.axis as usize) else {
                continue;
            };
            let f = axis.status().flags;
            let level = match b.signal {
                AxisSignal::LimitPos => f.contains(AxisFlags::HW_LIMIT_POS),
                AxisSignal::LimitNeg => f.contains(AxisFlags::HW_LIMIT_NEG),
                AxisSignal::Home => f.contains(AxisFlags::HOME_SWITCH),
                AxisSignal::Index => f.contains(AxisFlags::INDEX),
                AxisSignal::DriveAlarm => f.contains(AxisFlags::DRIVE_ALARM),
            };
            if let Some(di) = io.image.di.get_mut(b.channel as usize) {
                *di = level;
            }
        }
        for (ai, forced) in io.image.ai.iter_mut().zip(&io.ai_forced) {
            *ai = forced.unwrap_or(0.0);
        }
    }

    /// Copy the machine's state into `snapshot`, reusing its allocations.
    pub fn snapshot_into(&self, snapshot: &mut Snapshot) {
        snapshot.tick = self.tick;
        snapshot.period = self.period;
        snapshot.axes.clear();
        snapshot.axes.extend(self.axes.iter().map(|a| *a.status()));
        snapshot.io.clone_from(&self.io.image);
    }

    pub fn snapshot(&self) -> Snapshot {
        let mut s = Snapshot::default();
        self.snapshot_into(&mut s);
        s
    }
}
