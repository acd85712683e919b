//! Machine-level planners: stage 2 of [`super::Engine::step`], the slot where groups (issue 11)
//! and other planners feed their axes. Gears and cams (issue 12) are not planners: they run
//! inside stage 3 so that a slave follows its master without lag (`crate::coupling`).
//!
//! A planner owns no axis. Each tick, before the axes step, it reads the axes as the previous
//! tick left them and writes a setpoint (position, velocity, acceleration in the axis's user
//! units) for each axis it drives. The axis takes a fed setpoint as its command source for that
//! one tick and runs it through its own smoothing, output stage, plant and supervision like any
//! other source: soft and hard limits, following error and faults still stop it.
//!
//! Timing: a planner sees every axis's state *of the previous tick* (stage 2 runs
//! before stage 3), so a slave geared to a master's actual or commanded position follows it one
//! servo period late, whatever the axis order. A planner that drives both master and slave (a
//! group, a cam whose master is a virtual axis it feeds itself) computes both setpoints of the
//! same tick and has no such lag.

use std::fmt;

use crate::axis::{Axis, Feed};
use crate::command::{AxisIndex, EngineError};
use crate::profile::MotionState;

/// A machine-level planner (a group's path interpolator, a gear, a cam …).
///
/// Inputs: the tick number and the axes as the previous tick left them ([`Axis::status`]).
/// Outputs: setpoints written into [`Feeds`]. Order per tick: [`MachinePlanner::plan`], then
/// [`MachinePlanner::refused`] for each setpoint an axis did not take, before any axis steps.
pub trait MachinePlanner: Send + fmt::Debug {
    /// Write this tick's setpoints for the axes this planner drives. `tick` is the tick being
    /// computed (the engine's tick after this step).
    fn plan(&mut self, tick: u64, axes: &[Axis], feeds: &mut Feeds);

    /// An axis refused a setpoint: it is disabled, in error, stopping, or the setpoint moves
    /// further into an active limit. The axis keeps whatever it was doing (a limit stop goes
    /// on). Planners that coordinate several axes stop the others here.
    fn refused(&mut self, axis: AxisIndex, error: &EngineError) {
        let _ = (axis, error);
    }
}

/// One planner's setpoints of one tick. Reused from tick to tick (no allocation once its
/// capacity has grown to the number of axes fed).
#[derive(Debug, Default)]
pub struct Feeds {
    entries: Vec<(AxisIndex, Feed)>,
}

impl Feeds {
    /// Feed `axis` this commanded state this tick.
    pub fn follow(&mut self, axis: AxisIndex, setpoint: MotionState) {
        self.entries.push((axis, Feed::Follow(setpoint)));
    }

    /// Let go of `axis`.
    pub fn release(&mut self, axis: AxisIndex) {
        self.entries.push((axis, Feed::Release));
    }

    pub(super) fn clear(&mut self) {
        self.entries.clear();
    }

    pub(super) fn entries(&self) -> &[(AxisIndex, Feed)] {
        &self.entries
    }
}
