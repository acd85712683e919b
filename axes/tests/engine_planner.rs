//! Engine stage 2: a machine-level planner feeds an axis its setpoints tick by tick (the slot
//! groups and couplings fill). The planner here is a test double: a ramp at a constant speed.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use std::sync::{Arc, Mutex};

use axes::command::{AxisIndex, Command, EngineError, ErrorKind, StreamSetpoint};
use axes::engine::{Feeds, MachinePlanner};
use axes::profile::MotionState;
use axes::{AxisFlags, AxisState, ParamId};
use common::{enabled, jog, move_abs, ok, refused, run_until, status, stepper_mm};

/// What the test reads back from the planner once the engine owns it.
type Refusals = Arc<Mutex<Vec<(AxisIndex, ErrorKind)>>>;

/// Feeds axis 0 `start + speed·(tick − first)` from tick `first` until tick `last`, then
/// releases it once.
#[derive(Debug)]
struct Ramp {
    first: u64,
    last: u64,
    start: f64,
    /// Units per tick.
    step: f64,
    period: f64,
    refusals: Refusals,
}

impl Ramp {
    fn position(&self, tick: u64) -> f64 {
        self.start + self.step * (tick - self.first) as f64
    }
}

impl MachinePlanner for Ramp {
    fn plan(&mut self, tick: u64, _axes: &[axes::axis::Axis], feeds: &mut Feeds) {
        if tick >= self.first && tick <= self.last {
            feeds.follow(
                0,
                MotionState {
                    p: self.position(tick),
                    v: self.step / self.period,
                    a: 0.0,
                },
            );
        } else if tick == self.last + 1 {
            feeds.release(0);
        }
    }

    fn refused(&mut self, axis: AxisIndex, error: &EngineError) {
        self.refusals.lock().unwrap().push((axis, error.kind()));
    }
}

fn ramp(e: &axes::Engine, last: u64, step: f64) -> (Ramp, Refusals) {
    let refusals = Refusals::default();
    let first = e.tick() + 1;
    let planner = Ramp {
        first,
        last: first + last,
        start: status(e).cmd_pos + step,
        step,
        period: e.period(),
        refusals: refusals.clone(),
    };
    (planner, refusals)
}

#[test]
fn a_fed_axis_follows_its_setpoints_tick_by_tick_and_refuses_single_axis_motion() {
    let mut e = enabled(stepper_mm());
    let (planner, refusals) = ramp(&e, 299, 0.002);
    let first = e.tick() + 1;
    let expected: Vec<f64> = (0..300).map(|k| planner.position(first + k)).collect();
    e.add_planner(Box::new(planner));
    for (k, p) in expected.iter().enumerate() {
        e.step();
        let s = status(&e);
        assert_eq!(s.cmd_pos, *p, "tick {k}");
        assert_eq!(s.cmd_vel, 0.002 / e.period(), "tick {k}");
        assert_eq!(s.state, AxisState::SynchronizedMotion, "tick {k}");
        if k == 100 {
            // The planner owns the axis: single-axis motion and streams are refused.
            for c in [
                move_abs(0.0),
                jog(-5.0),
                Command::from(StreamSetpoint {
                    axis: 0,
                    setpoint: None,
                }),
            ] {
                assert!(matches!(
                    refused(&mut e, c),
                    EngineError::InvalidState {
                        state: AxisState::SynchronizedMotion,
                        ..
                    }
                ));
            }
        }
    }
    assert!(refusals.lock().unwrap().is_empty());
    // The plant follows the commanded position (stepper: within a pulse, a few ticks late).
    assert!((status(&e).act_pos - expected[299]).abs() < 0.05);
    // Released: it ramps down with `decel` and is free again.
    assert!(run_until(&mut e, 1.0, |s| s.state == AxisState::Standstill).is_some());
    let stop = status(&e).cmd_pos;
    assert!(
        stop > expected[299] && stop < expected[299] + 0.01,
        "{stop}"
    );
    ok(&mut e, move_abs(0.0));
}

#[test]
fn soft_limits_still_stop_a_fed_axis_and_the_planner_hears_the_refusals() {
    let mut cfg = stepper_mm();
    cfg.params.insert(ParamId::FsLimit, 0.5);
    cfg.params.insert(ParamId::RsLimit, -0.5);
    let mut e = enabled(cfg);
    let (planner, refusals) = ramp(&e, 1000, 0.01);
    e.add_planner(Box::new(planner));
    for _ in 0..1000 {
        e.step();
    }
    let s = status(&e);
    assert!(s.flags.contains(AxisFlags::SW_LIMIT_POS), "{:?}", s.flags);
    assert!(s.cmd_pos >= 0.5 && s.cmd_pos < 0.52, "{}", s.cmd_pos);
    assert_eq!(s.cmd_vel, 0.0);
    assert_eq!(s.state, AxisState::Standstill);
    let refusals = refusals.lock().unwrap();
    // Every tick after the limit stop refuses the setpoint that goes further in.
    assert!(refusals.len() > 900, "{}", refusals.len());
    assert!(refusals.iter().all(|r| *r == (0, ErrorKind::LimitActive)));
}
