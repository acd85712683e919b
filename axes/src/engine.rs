//! The engine: axes, machine I/O and slaves, advanced one servo period per [`Engine::step`]
//! (ARCHITECTURE §3). Same config + same commands at the same ticks ⇒ bit-identical state.

use crate::command::{Command, EngineError, Reply};
use crate::config::{ConfigError, EngineConfig};
use crate::status::{AxisFlags, AxisState, AxisStatus, IoImage, Snapshot};

pub struct Engine {
    period: f64,
    tick: u64,
    axes: Vec<AxisStatus>,
    io: IoImage,
}

impl Engine {
    /// Build the machine a config describes. The config is validated first.
    pub fn new(config: &EngineConfig) -> Result<Engine, ConfigError> {
        config.validate()?;
        Ok(Engine {
            period: config.period,
            tick: 0,
            axes: vec![AxisStatus::default(); config.axes.len()],
            io: IoImage {
                di: vec![false; config.io.digital_inputs as usize],
                do_: vec![false; config.io.digital_outputs as usize],
                ai: vec![0.0; config.io.analog_inputs as usize],
                ao: vec![0.0; config.io.analog_outputs as usize],
            },
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

    pub fn axis_count(&self) -> usize {
        self.axes.len()
    }

    pub fn axis_status(&self, axis: usize) -> Option<&AxisStatus> {
        self.axes.get(axis)
    }

    /// Apply one command at the current tick.
    pub fn apply(&mut self, command: Command) -> Result<Reply, EngineError> {
        if let Some(axis) = command.axis() {
            let count = self.axes.len() as u32;
            let status = self
                .axes
                .get_mut(axis as usize)
                .ok_or(EngineError::InvalidAxis {
                    axis: axis as u32,
                    count,
                })?;
            if let Command::Enable { .. } = command {
                status.flags |= AxisFlags::ENABLED;
                status.state = AxisState::Standstill;
            }
        }
        Ok(Reply::Done)
    }

    /// Advance one servo period.
    pub fn step(&mut self) {
        self.tick += 1;
    }

    /// Copy the machine's state into `snapshot`, reusing its allocations.
    pub fn snapshot_into(&self, snapshot: &mut Snapshot) {
        snapshot.tick = self.tick;
        snapshot.period = self.period;
        snapshot.axes.clone_from(&self.axes);
        snapshot.io.clone_from(&self.io);
    }

    pub fn snapshot(&self) -> Snapshot {
        let mut s = Snapshot::default();
        self.snapshot_into(&mut s);
        s
    }
}
