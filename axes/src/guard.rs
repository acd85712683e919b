//! Guards: watches the engine carries out on the tick (NMC `NMC_SetWatchDog` TV71,
//! `NMC_MtSetEstopDI`, `NMC_SetEstopDIEx`; digest 001 §2.3, §2.20). A front-end arms them;
//! [`Guards::step`] judges them after the axes have stepped (engine stage 3c) and returns the
//! commands they call for, which the engine applies before the next tick. Acting in the tick
//! rather than from a front-end's timer is what makes a scaled or virtual clock give what real
//! time gives.
//!
//! The watchdog fires once at its deadline tick (a kick moves the deadline and re-arms it):
//! every axis stops with its mode, the outputs are written. An input stop fires once its input
//! has held the level for `filter` ticks more: its axes get an emergency stop, moving or not;
//! while the level stays, an axis of it that moves again (and is not already in an E-stop) is
//! stopped again; the level going away re-arms it.
//!
//! The machine's E-stop input (`set_estop_input`, HIMC BindEMO, `engine/estop_input.rs`) is
//! not an input stop: it acts before the axes step, on every group and axis (powering them
//! off), on the edge only, and counts trips (docs/decisions.md, "`set_estop_input` stays
//! beside the guards' input stops").

use serde::{Deserialize, Serialize};

use crate::command::{
    AxisIndex, Command, EngineError, GuardInput, InputStopSet, OutputLevel, PositionWatchSet, Stop,
    StopMode, WatchdogSet, WriteDigitalOutput, MAX_INPUT_STOPS,
};

/// A position watch as the snapshot shows it (NMC `MtGetPtpCompareSts`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PositionWatchStatus {
    pub axis: AxisIndex,
    /// Waiting for the position.
    pub armed: bool,
    /// The position was passed and the speed changed.
    pub passed: bool,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct PositionWatch {
    set: PositionWatchSet,
    passed: bool,
}

#[derive(Clone, Debug, PartialEq)]
struct Watchdog {
    deadline: u64,
    mode: StopMode,
    outputs: Vec<OutputLevel>,
    fired: bool,
}

#[derive(Clone, Debug, PartialEq)]
struct InputStop {
    set: InputStopSet,
    /// The tick the input came to its level (None: not at it).
    since: Option<u64>,
    /// Fired since the level came.
    fired: bool,
}

/// The machine's guards. `Clone` for the checkpoints.
#[derive(Clone, Debug, Default)]
pub struct Guards {
    watchdog: Option<Watchdog>,
    /// Sorted by slot (deterministic order).
    stops: Vec<InputStop>,
    /// Sorted by axis.
    watches: Vec<PositionWatch>,
}

impl Guards {
    /// Whether any guard is armed (the engine skips the stage otherwise).
    pub fn active(&self) -> bool {
        self.watchdog.as_ref().is_some_and(|w| !w.fired)
            || !self.stops.is_empty()
            || self.watches.iter().any(|w| !w.passed)
    }

    /// Arm `c.axis`'s watch (the caller checked the axis and numbers).
    pub fn set_position_watch(&mut self, c: PositionWatchSet) {
        let watch = PositionWatch {
            set: c,
            passed: false,
        };
        match self.watches.binary_search_by_key(&c.axis, |w| w.set.axis) {
            Ok(i) => {
                if let Some(w) = self.watches.get_mut(i) {
                    *w = watch;
                }
            }
            Err(i) => self.watches.insert(i, watch),
        }
    }

    pub fn clear_position_watch(&mut self, axis: AxisIndex) {
        self.watches.retain(|w| w.set.axis != axis);
    }

    /// The position watches, for the snapshot (`out` is reused).
    pub fn position_watches_into(&self, out: &mut Vec<PositionWatchStatus>) {
        out.clear();
        out.extend(self.watches.iter().map(|w| PositionWatchStatus {
            axis: w.set.axis,
            armed: !w.passed,
            passed: w.passed,
        }));
    }

    /// The armed watches `at(axis)` (the axis's planned position and velocity) says are passed
    /// this tick: each is marked passed and returned as (axis, speed).
    pub fn passed_watches(
        &mut self,
        at: impl Fn(AxisIndex) -> Option<(f64, f64)>,
        out: &mut Vec<(AxisIndex, f64)>,
    ) {
        for w in self.watches.iter_mut().filter(|w| !w.passed) {
            let Some((position, velocity)) = at(w.set.axis) else {
                continue;
            };
            let passed = if w.set.positive {
                velocity > 0.0 && position >= w.set.position
            } else {
                velocity < 0.0 && position <= w.set.position
            };
            if passed {
                w.passed = true;
                out.push((w.set.axis, w.set.speed));
            }
        }
    }

    pub fn set_watchdog(&mut self, c: WatchdogSet) {
        self.watchdog = c.deadline.map(|deadline| Watchdog {
            deadline,
            mode: c.mode,
            outputs: c.outputs,
            fired: false,
        });
    }

    pub fn kick_watchdog(&mut self, deadline: u64) {
        if let Some(w) = &mut self.watchdog {
            (w.deadline, w.fired) = (deadline, false);
        }
    }

    /// The watchdog's deadline and whether it fired, if one is armed.
    pub fn watchdog(&self) -> Option<(u64, bool)> {
        self.watchdog.as_ref().map(|w| (w.deadline, w.fired))
    }

    /// Arm `c.slot` (the caller checked the input and axes against the machine).
    pub fn set_input_stop(&mut self, c: InputStopSet) -> Result<(), EngineError> {
        if c.slot >= MAX_INPUT_STOPS {
            return Err(EngineError::InvalidArgument {
                name: "slot",
                value: f64::from(c.slot),
                reason: "input-stop slots are 0 to 255",
            });
        }
        let stop = InputStop {
            set: c,
            since: None,
            fired: false,
        };
        match self
            .stops
            .binary_search_by_key(&stop.set.slot, |s| s.set.slot)
        {
            Ok(i) => {
                if let Some(s) = self.stops.get_mut(i) {
                    *s = stop;
                }
            }
            Err(i) => self.stops.insert(i, stop),
        }
        Ok(())
    }

    pub fn clear_input_stop(&mut self, slot: u16) {
        self.stops.retain(|s| s.set.slot != slot);
    }

    /// One tick at `tick`: `level` reads an input as the tick left it (None: no such input),
    /// `moving` whether an axis moves and is not already in an E-stop. The commands to apply
    /// are appended to `out`, at most one stop per axis.
    pub fn step(
        &mut self,
        tick: u64,
        axes: usize,
        level: impl Fn(&GuardInput) -> Option<bool>,
        moving: impl Fn(AxisIndex) -> bool,
        out: &mut Vec<Command>,
    ) {
        let first = out.len();
        for s in &mut self.stops {
            if level(&s.set.input) != Some(s.set.level) {
                (s.since, s.fired) = (None, false);
                continue;
            }
            let since = *s.since.get_or_insert(tick);
            if tick - since < u64::from(s.set.filter) {
                continue;
            }
            let edge = !s.fired;
            s.fired = true;
            for &axis in &s.set.axes {
                if usize::from(axis) < axes && (edge || moving(axis)) {
                    push_stop(out, first, axis, StopMode::Emergency);
                }
            }
        }
        if let Some(w) = &mut self.watchdog {
            if !w.fired && tick >= w.deadline {
                w.fired = true;
                for axis in 0..axes {
                    push_stop(out, first, axis as AxisIndex, w.mode);
                }
                out.extend(w.outputs.iter().map(|o| {
                    Command::from(WriteDigitalOutput {
                        channel: o.channel,
                        value: o.value,
                    })
                }));
            }
        }
    }
}

/// A stop of `axis` unless one was pushed since `first` (an E-stop wins: it comes first).
fn push_stop(out: &mut Vec<Command>, first: usize, axis: AxisIndex, mode: StopMode) {
    let already = out
        .get(first..)
        .unwrap_or(&[])
        .iter()
        .any(|c| c.axis() == Some(axis));
    if !already {
        out.push(
            Stop {
                axis,
                mode,
                deceleration: None,
            }
            .into(),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::InputStopSet;

    fn stop_on_di2(filter: u32) -> Guards {
        let mut g = Guards::default();
        g.set_input_stop(InputStopSet {
            slot: 3,
            input: GuardInput::Digital { channel: 2 },
            level: true,
            filter,
            axes: vec![1],
        })
        .unwrap();
        g
    }

    fn run(g: &mut Guards, tick: u64, di2: bool, moving: bool) -> usize {
        let mut out = Vec::new();
        g.step(tick, 2, |_| Some(di2), |_| moving, &mut out);
        out.len()
    }

    /// DI2 high for the filter's 5 ticks stops axis 1 (still or not, once at the edge); while
    /// it stays high only a moving axis is stopped again; low re-arms.
    #[test]
    fn an_input_stop_fires_after_its_filter() {
        let mut g = stop_on_di2(5);
        assert!(g.active());
        assert_eq!(run(&mut g, 10, true, false), 0);
        assert_eq!(run(&mut g, 14, true, false), 0);
        assert_eq!(run(&mut g, 15, true, false), 1);
        assert_eq!(run(&mut g, 16, true, false), 0);
        assert_eq!(run(&mut g, 17, true, true), 1);
        assert_eq!(run(&mut g, 18, false, true), 0);
        assert_eq!(run(&mut g, 19, true, false), 0);
        assert_eq!(run(&mut g, 24, true, false), 1);
    }

    /// Fires once at its deadline; a kick moves the deadline and re-arms it.
    #[test]
    fn the_watchdog_fires_once_at_its_deadline() {
        let mut g = Guards::default();
        g.set_watchdog(WatchdogSet {
            deadline: Some(600),
            mode: StopMode::Abrupt,
            outputs: vec![OutputLevel {
                channel: 0,
                value: true,
            }],
        });
        assert_eq!(run(&mut g, 599, false, true), 0);
        assert_eq!(run(&mut g, 600, false, true), 3, "2 stops and an output");
        assert_eq!(run(&mut g, 601, false, true), 0);
        assert!(!g.active());
        g.kick_watchdog(2500);
        assert_eq!(run(&mut g, 2499, false, true), 0);
        assert_eq!(run(&mut g, 2500, false, true), 3);
        g.set_watchdog(WatchdogSet {
            deadline: None,
            mode: StopMode::Smooth,
            outputs: Vec::new(),
        });
        g.kick_watchdog(3000);
        assert_eq!(g.watchdog(), None);
    }
}
