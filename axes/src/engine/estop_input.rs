//! The machine's E-stop input (`set_estop_input`, HIMC `BindEMO`, digest 004 §1.10, §9.2.6):
//! watched in stage 1b of [`Engine::step`], right after the inputs are read, so the tick that
//! reads the input reaching its active level is the tick the axes stop.
//!
//! Not an input stop of [`crate::guard`], though both watch an input: this one acts in stage
//! 1b (the guards in 3c, a tick later), on every group and axis and powers them off (an input
//! stop e-stops its listed axes, which stay enabled), on the rising edge only (an input stop
//! fires when armed at its level and re-stops a moving axis while it holds), and counts trips.
//! Folding either into the other changes a front-end's observable tick or action
//! (docs/decisions.md, "`set_estop_input` stays beside the guards' input stops").

use super::Engine;
use crate::command::{EngineError, Reply, SetEstopInput};

/// The bound input and what it read last tick.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct EstopInput {
    /// (channel, active level), if an input is bound.
    bound: Option<(u16, bool)>,
    /// Whether the input was at its active level last tick.
    active: bool,
    /// How many times it fired since start.
    trips: u64,
}

impl Engine {
    pub(super) fn set_estop_input(&mut self, c: SetEstopInput) -> Result<Reply, EngineError> {
        let active = match c.channel {
            Some(ch) => *super::channel(&mut self.io.image.di, ch, "digital inputs")? == c.level,
            None => false,
        };
        let e = &mut self.estop_input;
        e.bound = c.channel.map(|ch| (ch, c.level));
        e.active = active;
        Ok(Reply::Done)
    }

    /// Stage 1b: the bound input reached its active level this tick → `emergency_stop_all` now.
    pub(super) fn watch_estop_input(&mut self) {
        let Some((channel, level)) = self.estop_input.bound else {
            return;
        };
        let active = self.io.image.di.get(usize::from(channel)) == Some(&level);
        let rose = active && !self.estop_input.active;
        self.estop_input.active = active;
        if rose {
            self.estop_input.trips += 1;
            self.emergency_stop_everything();
        }
    }

    /// How many times the E-stop input has fired since start (a front-end latches its error
    /// code when this changes).
    pub fn estop_input_trips(&self) -> u64 {
        self.estop_input.trips
    }
}
