//! Guards (NMC watchdog TV71, E-stop inputs, PTP compare; `axes::guard`): judged in the tick,
//! so they act at the same tick however the clock is paced.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, Enable};
use axes::config::IoConfig;
use axes::{AxisFlags, Engine, EngineConfig, EngineError};
use common::{cmd, ok, refused, stepper_mm};

/// Two enabled mm steppers, 4 DI and 4 DO, 1 ms period.
fn machine() -> Engine {
    let mut e = Engine::new(&EngineConfig {
        axes: vec![stepper_mm(), stepper_mm()],
        io: IoConfig {
            digital_inputs: 4,
            digital_outputs: 4,
            ..IoConfig::default()
        },
        ..EngineConfig::default()
    })
    .unwrap();
    for axis in 0..2 {
        ok(&mut e, Command::from(Enable { axis }));
    }
    e
}

fn jog(e: &mut Engine, axis: u16) {
    ok(
        e,
        cmd(&format!(
            r#"{{"type":"move_velocity","axis":{axis},"velocity":50}}"#
        )),
    );
}

fn estopped(e: &Engine, axis: usize) -> bool {
    e.axis_status(axis)
        .unwrap()
        .latched
        .contains(AxisFlags::ESTOP)
}

/// DI1 high with a 3-tick filter: the E-stop comes on the 4th tick that reads it high, and
/// only the watched axis stops.
#[test]
fn an_input_stop_fires_on_the_tick_its_filter_ends() {
    let mut e = machine();
    jog(&mut e, 0);
    jog(&mut e, 1);
    common::run(&mut e, 0.1);
    ok(
        &mut e,
        cmd(
            r#"{"type":"input_stop_set","slot":0,"level":true,"filter":3,"axes":[0],
                "input":{"kind":"digital","channel":1}}"#,
        ),
    );
    ok(
        &mut e,
        cmd(r#"{"type":"force_digital_input","channel":1,"value":true}"#),
    );
    let mut ticks = 0;
    while !estopped(&e, 0) {
        e.step();
        ticks += 1;
        assert!(ticks < 100, "never stopped");
    }
    assert_eq!(ticks, 4);
    assert!(!estopped(&e, 1));
    common::run(&mut e, 0.1);
    assert_eq!(e.axis_status(0).unwrap().cmd_vel, 0.0);
    assert!(e.axis_status(1).unwrap().cmd_vel > 49.0);
    // An input out of range, or no axis, is refused.
    let err = refused(
        &mut e,
        cmd(
            r#"{"type":"input_stop_set","slot":0,"level":true,"axes":[0],
                "input":{"kind":"digital","channel":9}}"#,
        ),
    );
    assert!(matches!(err, EngineError::InvalidChannel { .. }), "{err:?}");
    let err = refused(
        &mut e,
        cmd(r#"{"type":"input_stop_set","slot":0,"level":true,"axes":[],
                "input":{"kind":"home","axis":1}}"#),
    );
    assert!(
        matches!(err, EngineError::InvalidArgument { .. }),
        "{err:?}"
    );
}

/// The watchdog fires at its deadline tick (every axis stops, DO2 is written), once; a kick
/// moves the deadline.
#[test]
fn the_watchdog_fires_at_its_deadline_tick() {
    let mut e = machine();
    jog(&mut e, 1);
    let deadline = e.tick() + 100;
    ok(
        &mut e,
        cmd(&format!(
            r#"{{"type":"watchdog_set","deadline":{deadline},"mode":"abrupt",
                 "outputs":[{{"channel":2,"value":true}}]}}"#
        )),
    );
    common::run(&mut e, 0.05);
    ok(
        &mut e,
        cmd(&format!(
            r#"{{"type":"watchdog_kick","deadline":{}}}"#,
            deadline + 50
        )),
    );
    while !e.snapshot().io.do_[2] {
        e.step();
        assert!(e.tick() <= deadline + 50, "not fired by its deadline");
    }
    assert_eq!(e.tick(), deadline + 50);
    assert!(!estopped(&e, 1), "an abrupt stop latches nothing");
    common::run(&mut e, 0.1);
    assert_eq!(e.axis_status(1).unwrap().cmd_vel, 0.0);
    // Once: a new jog runs on.
    jog(&mut e, 1);
    common::run(&mut e, 0.5);
    assert!(e.axis_status(1).unwrap().cmd_vel > 49.0);
}

/// A position watch re-plans the running move at its speed from the tick the planned position
/// passes it; the move keeps its target and ends there.
#[test]
fn a_position_watch_changes_the_speed_where_the_position_is_passed() {
    let mut e = machine();
    ok(
        &mut e,
        cmd(r#"{"type":"move_absolute","axis":0,"position":60,"velocity":50}"#),
    );
    ok(
        &mut e,
        cmd(r#"{"type":"position_watch_set","axis":0,"position":20,"positive":true,"speed":10}"#),
    );
    let passed = |e: &Engine| e.snapshot().position_watches[0].passed;
    while !passed(&e) {
        e.step();
        assert!(e.tick() < 5000, "never passed");
    }
    let s = e.axis_status(0).unwrap();
    assert!(
        s.cmd_pos >= 20.0 && s.cmd_pos < 20.0 + 50.0 * e.period(),
        "{}",
        s.cmd_pos
    );
    assert!(!e.snapshot().position_watches[0].armed);
    common::run(&mut e, 0.2);
    let v = e.axis_status(0).unwrap().cmd_vel;
    assert!((v - 10.0).abs() < 1e-9, "v {v}");
    common::run(&mut e, 5.0);
    assert_eq!(e.axis_status(0).unwrap().cmd_pos, 60.0);
    let err = refused(
        &mut e,
        cmd(r#"{"type":"position_watch_set","axis":0,"position":20,"positive":true,"speed":0}"#),
    );
    assert!(
        matches!(err, EngineError::InvalidArgument { .. }),
        "{err:?}"
    );
}
