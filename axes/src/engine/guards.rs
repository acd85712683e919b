//! The engine's side of the guards (`crate::guard`): arming them against the machine, and
//! stage 3c, which judges them after the axes and triggers have stepped and applies what they
//! call for before the drives read the axes (the stops act from the next tick, as any command
//! between two ticks does).

use super::Engine;
use crate::command::{
    bounded, positive, EngineError, GuardInput, InputStopSet, PositionWatchSet, Reply, WatchdogSet,
};
use crate::status::AxisFlags;

impl Engine {
    pub(super) fn set_watchdog(&mut self, c: WatchdogSet) -> Result<Reply, EngineError> {
        let count = self.io.image.do_.len() as u16;
        for o in &c.outputs {
            if o.channel >= count {
                return Err(EngineError::InvalidChannel {
                    kind: "digital outputs",
                    channel: o.channel,
                    count,
                });
            }
        }
        self.guards.set_watchdog(c);
        Ok(Reply::Done)
    }

    pub(super) fn set_input_stop(&mut self, c: InputStopSet) -> Result<Reply, EngineError> {
        let count = self.axes.len() as u32;
        let axis_ok = |axis: u16| {
            if u32::from(axis) < count {
                Ok(())
            } else {
                Err(EngineError::InvalidAxis {
                    axis: u32::from(axis),
                    count,
                })
            }
        };
        match c.input {
            GuardInput::Digital { channel } => {
                let inputs = self.io.image.di.len() as u16;
                if channel >= inputs {
                    return Err(EngineError::InvalidChannel {
                        kind: "digital inputs",
                        channel,
                        count: inputs,
                    });
                }
            }
            GuardInput::NegativeLimit { axis }
            | GuardInput::PositiveLimit { axis }
            | GuardInput::Home { axis }
            | GuardInput::Index { axis } => axis_ok(axis)?,
        }
        if c.axes.is_empty() {
            return Err(EngineError::InvalidArgument {
                name: "axes",
                value: 0.0,
                reason: "an input stop stops at least one axis",
            });
        }
        for &axis in &c.axes {
            axis_ok(axis)?;
        }
        self.guards.set_input_stop(c)?;
        Ok(Reply::Done)
    }

    pub(super) fn set_position_watch(&mut self, c: PositionWatchSet) -> Result<Reply, EngineError> {
        let count = self.axes.len() as u32;
        if u32::from(c.axis) >= count {
            return Err(EngineError::InvalidAxis {
                axis: u32::from(c.axis),
                count,
            });
        }
        bounded("position", c.position)?;
        positive("speed", c.speed)?;
        self.guards.set_position_watch(c);
        Ok(Reply::Done)
    }

    /// Stage 3c. Reads the digital inputs and the axes' flags as this tick left them; applies
    /// the guards' stops and outputs (a refusal, e.g. of a disabled axis, changes nothing).
    pub(super) fn step_guards(&mut self) {
        if !self.guards.active() {
            return;
        }
        let mut commands = Vec::new();
        {
            let Engine {
                axes,
                io,
                guards,
                tick,
                ..
            } = &mut *self;
            let flag = |axis: u16, f: AxisFlags| {
                axes.get(usize::from(axis))
                    .map(|a| a.status().flags.contains(f))
            };
            guards.step(
                *tick,
                axes.len(),
                |input| match *input {
                    GuardInput::Digital { channel } => {
                        io.image.di.get(usize::from(channel)).copied()
                    }
                    GuardInput::NegativeLimit { axis } => flag(axis, AxisFlags::HW_LIMIT_NEG),
                    GuardInput::PositiveLimit { axis } => flag(axis, AxisFlags::HW_LIMIT_POS),
                    GuardInput::Home { axis } => flag(axis, AxisFlags::HOME_SWITCH),
                    GuardInput::Index { axis } => flag(axis, AxisFlags::INDEX),
                },
                |axis| {
                    axes.get(usize::from(axis)).is_some_and(|a| {
                        let s = a.status();
                        s.flags.contains(AxisFlags::MOVING) && !s.latched.contains(AxisFlags::ESTOP)
                    })
                },
                &mut commands,
            );
        }
        for command in commands {
            let _ = self.apply(command);
        }
        let mut passed = Vec::new();
        let axes = &self.axes;
        self.guards.passed_watches(
            |axis| {
                axes.get(usize::from(axis)).map(|a| {
                    let c = a.commanded();
                    (c.p, c.v)
                })
            },
            &mut passed,
        );
        for (axis, speed) in passed {
            if let Some(a) = self.axes.get_mut(usize::from(axis)) {
                a.change_running_speed(self.tick, speed);
            }
        }
    }
}
