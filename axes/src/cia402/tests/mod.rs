//! Tests of the CiA 402 drive against a tiny fake axis that applies the drive's commands to an
//! `AxisStatus` (no profiles: moves run at constant speed, stops are immediate).

mod modes;
mod objects;
mod power;

use std::collections::VecDeque;

use super::*;
use crate::command::{
    AxisCommand, CommandId, Direction, Disable, Enable, Halt, Home, MoveAbsolute, MoveRelative,
    MoveVelocity, Reset, Resume, SetPosition, Stop, StreamSetpoint,
};
use crate::status::CommandRef;

/// Increments per mm in the tests: bus values are 1000 × axis values.
const IPU: f64 = 1000.0;
const DT: f64 = 0.001;

#[derive(Clone, Copy, Debug, PartialEq)]
struct Move {
    id: CommandId,
    target: f64,
    speed: f64,
}

/// An axis that does what the drive asks, one tick at a time.
#[derive(Debug, Default)]
struct FakeAxis {
    status: AxisStatus,
    queue: VecDeque<Move>,
    velocity: Option<f64>,
    halted: bool,
    /// (id, ticks left, offset)
    homing: Option<(CommandId, u32, f64)>,
    homing_ticks: u32,
    fail_homing: bool,
    /// The drive alarm's cause is present: Reset cannot clear it.
    alarm_forced: bool,
    stream: Option<Setpoint>,
    next_id: CommandId,
    /// Every command applied, in order.
    log: Vec<Command>,
}

const FAULTS: AxisFlags = AxisFlags::ERROR_STOP_FAULTS;

impl FakeAxis {
    fn id(&mut self) -> CommandId {
        self.next_id += 1;
        self.next_id
    }

    fn enabled(&self) -> bool {
        self.status.flags.contains(AxisFlags::ENABLED)
    }

    fn last_target(&self) -> f64 {
        self.queue.back().map_or(self.status.cmd_pos, |m| m.target)
    }

    fn apply(&mut self, command: &Command) -> Result<Reply, EngineError> {
        self.log.push(command.clone());
        let axis = 0;
        let f = &mut self.status.flags;
        match *command {
            Command::Axis(AxisCommand::Enable(Enable { .. })) => {
                if f.intersects(FAULTS) {
                    return Err(EngineError::AxisInError {
                        axis,
                        faults: *f & FAULTS,
                    });
                }
                f.insert(AxisFlags::ENABLED);
                self.status.state = AxisState::Standstill;
            }
            Command::Axis(AxisCommand::Disable(Disable { .. })) => {
                f.remove(AxisFlags::ENABLED | AxisFlags::MOVING);
                self.queue.clear();
                self.velocity = None;
                self.homing = None;
                self.stream = None;
                self.halted = false;
                self.status.state = if f.intersects(FAULTS) {
                    AxisState::ErrorStop
                } else {
                    AxisState::Disabled
                };
            }
            Command::Axis(AxisCommand::Reset(Reset { .. })) => {
                if self.alarm_forced {
                    return Err(EngineError::CauseStillPresent {
                        axis,
                        faults: AxisFlags::DRIVE_ALARM,
                    });
                }
                f.remove(FAULTS);
                self.status.state = if f.contains(AxisFlags::ENABLED) {
                    AxisState::Standstill
                } else {
                    AxisState::Disabled
                };
            }
            Command::Axis(AxisCommand::MoveAbsolute(MoveAbsolute {
                position,
                velocity,
                buffer_mode,
                ..
            })) => {
                return self.post(position, velocity, buffer_mode);
            }
            Command::Axis(AxisCommand::MoveRelative(MoveRelative {
                distance,
                velocity,
                buffer_mode,
                ..
            })) => {
                let target = self.last_target() + distance;
                return self.post(target, velocity, buffer_mode);
            }
            Command::Axis(AxisCommand::MoveVelocity(MoveVelocity { velocity, .. })) => {
                if !self.enabled() {
                    return Err(EngineError::AxisDisabled { axis });
                }
                self.queue.clear();
                self.velocity = Some(velocity);
                let id = self.id();
                return Ok(Reply::Accepted { id });
            }
            Command::Axis(AxisCommand::Stop(Stop { .. })) => {
                self.queue.clear();
                self.velocity = None;
                self.homing = None;
                self.halted = false;
            }
            Command::Axis(AxisCommand::Halt(Halt { .. })) => self.halted = true,
            Command::Axis(AxisCommand::Resume(Resume { .. })) => self.halted = false,
            Command::Axis(AxisCommand::Home(Home { method, offset, .. })) => {
                if !self.enabled() {
                    return Err(EngineError::AxisDisabled { axis });
                }
                let id = self.id();
                let ticks = if method == Some(37) {
                    0
                } else {
                    self.homing_ticks
                };
                self.queue.clear();
                self.velocity = None;
                self.homing = Some((id, ticks, offset.unwrap_or(0.0)));
                self.status.flags.remove(AxisFlags::HOMED);
                self.status.state = AxisState::Homing;
                self.status.current_command = Some(CommandRef {
                    id,
                    kind: CommandKind::Home,
                });
                return Ok(Reply::Accepted { id });
            }
            Command::Axis(AxisCommand::SetPosition(SetPosition { position, .. })) => {
                self.status.cmd_pos = position;
                self.status.act_pos = position;
            }
            Command::Axis(AxisCommand::Setpoint(StreamSetpoint { setpoint, .. })) => {
                if setpoint.is_some() && !self.enabled() {
                    return Err(EngineError::AxisDisabled { axis });
                }
                self.stream = setpoint;
                if let Some(Setpoint::Position { position }) = setpoint {
                    self.status.cmd_pos = position;
                }
            }
            _ => {}
        }
        Ok(Reply::Done)
    }

    fn post(
        &mut self,
        target: f64,
        speed: Option<f64>,
        mode: BufferMode,
    ) -> Result<Reply, EngineError> {
        let axis = 0;
        if !self.enabled() {
            return Err(EngineError::AxisDisabled { axis });
        }
        let up = target > self.status.cmd_pos;
        let f = self.status.flags;
        if up && f.contains(AxisFlags::HW_LIMIT_POS) {
            return Err(EngineError::LimitActive {
                axis,
                direction: Direction::Positive,
            });
        }
        if !up && f.contains(AxisFlags::HW_LIMIT_NEG) {
            return Err(EngineError::LimitActive {
                axis,
                direction: Direction::Negative,
            });
        }
        if mode == BufferMode::Aborting {
            self.queue.clear();
            self.velocity = None;
        }
        let id = self.id();
        self.queue.push_back(Move {
            id,
            target,
            speed: speed.unwrap_or(1.0),
        });
        self.status.fifo_len = self.queue.len() as u16;
        Ok(Reply::Accepted { id })
    }

    fn advance(&mut self, dt: f64) {
        let before = self.status.cmd_pos;
        let s = &mut self.status;
        s.current_command = None;
        if let Some(setpoint) = self.stream {
            s.state = AxisState::SynchronizedMotion;
            if let Setpoint::Velocity { velocity } = setpoint {
                s.cmd_pos += velocity * dt;
            }
        } else if let Some((id, left, offset)) = self.homing {
            if left == 0 {
                self.homing = None;
                if self.fail_homing {
                    s.flags.insert(AxisFlags::HOMING_FAILED);
                    s.latched.insert(AxisFlags::HOMING_FAILED);
                    s.state = AxisState::ErrorStop;
                } else {
                    s.cmd_pos = offset;
                    s.act_pos = offset;
                    s.flags.insert(AxisFlags::HOMED);
                    s.state = AxisState::Standstill;
                }
            } else {
                self.homing = Some((id, left - 1, offset));
                s.cmd_pos += 0.001;
                s.current_command = Some(CommandRef {
                    id,
                    kind: CommandKind::Home,
                });
            }
        } else if self.halted {
        } else if let Some(v) = self.velocity {
            s.cmd_pos += v * dt;
            s.state = AxisState::ContinuousMotion;
        } else if let Some(m) = self.queue.front().copied() {
            let step = m.speed * dt;
            let gap = m.target - s.cmd_pos;
            s.current_command = Some(CommandRef {
                id: m.id,
                kind: CommandKind::MoveAbsolute,
            });
            if gap.abs() <= step {
                s.cmd_pos = m.target;
                self.queue.pop_front();
            } else {
                s.cmd_pos += step * gap.signum();
            }
            s.state = AxisState::DiscreteMotion;
        } else if s.flags.contains(AxisFlags::ENABLED) && !s.flags.intersects(FAULTS) {
            s.state = AxisState::Standstill;
        }
        let moved = s.cmd_pos != before;
        s.flags.set(AxisFlags::MOVING, moved);
        s.cmd_vel = (s.cmd_pos - before) / dt;
        s.act_pos = s.cmd_pos - s.following_error;
        s.act_vel = s.cmd_vel;
        s.fifo_len = self.queue.len() as u16
            + u16::from(self.homing.is_some())
            + u16::from(self.velocity.is_some());
    }
}

/// A drive and its fake axis, stepped together.
struct Rig {
    drive: Cia402Drive,
    axis: FakeAxis,
    now: f64,
    /// Commands of the last tick.
    last: Vec<Command>,
}

impl Rig {
    fn new() -> Rig {
        let config = DriveConfig {
            increments_per_unit: IPU,
            ..DriveConfig::default()
        };
        let mut rig = Rig {
            drive: Cia402Drive::new(config).unwrap(),
            axis: FakeAxis {
                homing_ticks: 5,
                ..FakeAxis::default()
            },
            now: 0.0,
            last: Vec::new(),
        };
        rig.tick(); // transition 1
        rig
    }

    fn tick(&mut self) {
        self.last.clear();
        self.drive.step(&self.axis.status, self.now, &mut self.last);
        for command in &self.last {
            let result = self.axis.apply(command);
            self.drive.on_reply(command, &result);
        }
        self.axis.advance(DT);
        self.now += DT;
    }

    fn ticks(&mut self, n: usize) {
        for _ in 0..n {
            self.tick();
        }
    }

    /// Tick until `done` holds (at most `limit` ticks); whether it did.
    fn until(&mut self, limit: usize, done: impl Fn(&Rig) -> bool) -> bool {
        for _ in 0..limit {
            if done(self) {
                return true;
            }
            self.tick();
        }
        done(self)
    }

    fn set(&mut self, index: u16, subindex: u8, value: Value) {
        self.drive.write(index, subindex, value).unwrap();
    }

    /// Write the controlword and tick once.
    fn cw(&mut self, controlword: u16) {
        self.set(obj::CONTROLWORD, 0, Value::U16(controlword));
        self.tick();
    }

    fn sw(&self) -> u16 {
        self.drive.statusword()
    }

    fn state(&self) -> State {
        self.drive.state()
    }

    fn get(&self, index: u16, subindex: u8) -> Value {
        self.drive.read(index, subindex).unwrap()
    }

    fn int(&self, index: u16) -> i64 {
        self.get(index, 0).as_i64().unwrap()
    }

    fn mode(&mut self, mode: OperationMode) {
        self.set(obj::MODES_OF_OPERATION, 0, Value::I8(mode.code()));
    }

    /// Walk to `target` with the master-side helper, as the engine would.
    fn walk(&mut self, target: PowerTarget) {
        let mut controlword = self.int(obj::CONTROLWORD) as u16;
        for _ in 0..10 {
            controlword = controlword_for(target, self.sw(), controlword);
            self.cw(controlword);
        }
    }

    fn operation_enabled(&mut self) {
        self.cw(cw::SHUTDOWN);
        self.cw(cw::SWITCH_ON_COMMAND);
        self.cw(cw::ENABLE_OPERATION_COMMAND);
        assert_eq!(self.state(), State::OperationEnabled);
    }

    /// Put the drive into `state` from a fresh rig.
    fn goto(&mut self, state: State) {
        match state {
            State::NotReadyToSwitchOn | State::SwitchOnDisabled => {}
            State::ReadyToSwitchOn => self.cw(cw::SHUTDOWN),
            State::SwitchedOn => {
                self.cw(cw::SHUTDOWN);
                self.cw(cw::SWITCH_ON_COMMAND);
            }
            State::OperationEnabled => self.operation_enabled(),
            State::QuickStopActive => {
                self.set(obj::QUICK_STOP_OPTION, 0, Value::I16(6));
                self.operation_enabled();
                self.cw(cw::QUICK_STOP_COMMAND);
            }
            State::FaultReactionActive | State::Fault => {
                self.operation_enabled();
                self.axis.status.flags.insert(AxisFlags::DRIVE_ALARM);
                self.tick();
                if state == State::Fault {
                    self.tick();
                }
            }
        }
        assert_eq!(self.state(), state);
    }

    /// Commands of the last tick that match.
    fn sent(&self, f: impl Fn(&Command) -> bool) -> Vec<Command> {
        self.last.iter().filter(|c| f(c)).cloned().collect()
    }
}

fn is_enable(c: &Command) -> bool {
    matches!(c, Command::Axis(AxisCommand::Enable(Enable { .. })))
}

fn is_disable(c: &Command) -> bool {
    matches!(c, Command::Axis(AxisCommand::Disable(Disable { .. })))
}

fn is_stop(c: &Command) -> bool {
    matches!(c, Command::Axis(AxisCommand::Stop(Stop { .. })))
}

fn approx(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}
