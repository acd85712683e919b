//! The compensation limit (digest 004 §2.13 and §3.6, HIMC `max_comp_lim`, TV 63): over
//! `compensation_limit` the axis latches COMPENSATION_LIMIT, stops, and outputs at most the
//! limit; tables whose value is already over it are refused when switched on.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, Enable};
use axes::{AxisFlags, AxisState, Engine, EngineError, ParamId};
use common::{cmd, engine_with, free_linear_axis, ok, refused, run};

/// Axis 0 compensated over axis 1's planned position: 0 at 0, `top` at 100 (linear).
fn machine(limit: f64, top: f64) -> Engine {
    let axis = free_linear_axis(
        1.0,
        &[
            (ParamId::Speed, 100.0),
            (ParamId::Accel, 1_000.0),
            (ParamId::Decel, 1_000.0),
            (ParamId::CompensationLimit, limit),
        ],
    );
    let mut e = engine_with(vec![axis; 2]);
    for i in 0..2 {
        ok(&mut e, Command::from(Enable { axis: i }));
    }
    ok(
        &mut e,
        cmd(&format!(
            r#"{{"type":"compensation_table","axis":0,"references":[{{"axis":1}}],
                "start":[0],"step":[100],"count":[2],"values":[0,{top}],"enable":true}}"#
        )),
    );
    e
}

fn move_to(e: &mut Engine, axis: u16, position: f64) {
    ok(
        e,
        cmd(&format!(
            r#"{{"type":"move_absolute","axis":{axis},"position":{position}}}"#
        )),
    );
}

/// A limit the tables stay under changes nothing, bit for bit, at any tick.
#[test]
fn under_the_limit_nothing_changes() {
    let mut unlimited = machine(0.0, 0.9);
    let mut limited = machine(1.0, 0.9);
    for e in [&mut unlimited, &mut limited] {
        move_to(e, 1, 150.0);
        move_to(e, 0, 20.0);
    }
    for tick in 0..3000 {
        unlimited.step();
        limited.step();
        for axis in 0..2 {
            assert_eq!(
                unlimited.axis_status(axis).unwrap(),
                limited.axis_status(axis).unwrap(),
                "axis {axis}, tick {tick}"
            );
        }
    }
    assert_eq!(limited.axis_status(0).unwrap().compensation, 0.9);
}

/// Over the limit: the fault at the tick the table's value crosses it, the output held at the
/// limit, the axis in ErrorStop; the reference axis goes on. Reset is refused until the value
/// is back under the limit.
#[test]
fn over_the_limit_faults_at_the_crossing_tick() {
    let mut e = machine(1.0, 2.0);
    move_to(&mut e, 1, 100.0);
    let mut crossed = None;
    for tick in 0..3000 {
        // The grid reads its reference as the previous tick left it.
        let reference = e.axis_status(1).unwrap().cmd_pos;
        e.step();
        let s = e.axis_status(0).unwrap();
        let value = reference * 2.0 / 100.0;
        let faulted = s.flags.contains(AxisFlags::COMPENSATION_LIMIT);
        if value > 1.0 && crossed.is_none() {
            crossed = Some(tick);
            assert!(faulted, "tick {tick}: value {value}");
            assert_eq!(s.state, AxisState::ErrorStop);
        }
        if crossed.is_none() {
            assert!(!faulted, "tick {tick}: value {value}");
            assert_eq!(s.compensation, value);
        } else {
            assert_eq!(s.compensation, 1.0, "held at the limit");
        }
        assert_eq!(s.output_pos, s.cmd_pos + s.compensation);
    }
    assert!(crossed.is_some());
    assert_eq!(e.axis_status(1).unwrap().cmd_pos, 100.0, "axis 1 went on");
    let err = refused(&mut e, cmd(r#"{"type":"reset","axis":0}"#));
    assert!(
        matches!(err, EngineError::CauseStillPresent { faults, .. } if faults == AxisFlags::COMPENSATION_LIMIT),
        "{err}"
    );
    move_to(&mut e, 1, 10.0);
    run(&mut e, 3.0);
    ok(&mut e, cmd(r#"{"type":"reset","axis":0}"#));
    let s = e.axis_status(0).unwrap();
    assert!(!s.flags.contains(AxisFlags::COMPENSATION_LIMIT));
    assert_ne!(s.state, AxisState::ErrorStop);
    assert!((s.compensation - 0.2).abs() < 1e-12, "{}", s.compensation);
}

/// TV 63: a table value of 1.5 at the reference's present position, limit 1, is refused when
/// switched on (`compensation_enable`, or a table sent enabled), naming the value and the
/// limit; the tables stay as they were.
#[test]
fn switching_on_over_the_limit_is_refused_tv63() {
    let mut e = machine(1.0, 0.5);
    ok(&mut e, cmd(r#"{"type":"compensation_disable","axis":0}"#));
    move_to(&mut e, 1, 100.0);
    run(&mut e, 3.0);
    let table = r#"{"type":"compensation_table","axis":0,"references":[{"axis":1}],
        "start":[0],"step":[100],"count":[2],"values":[0,1.5],"enable":false}"#;
    let enabled = table.replace("false", "true");
    let err = refused(&mut e, cmd(&enabled));
    assert_eq!(
        err,
        EngineError::CompensationLimit {
            axis: 0,
            value: 1.5,
            limit: 1.0
        }
    );
    ok(&mut e, cmd(table));
    let err = refused(&mut e, cmd(r#"{"type":"compensation_enable","axis":0}"#));
    assert!(
        matches!(err, EngineError::CompensationLimit { .. }),
        "{err}"
    );
    e.step();
    let s = e.axis_status(0).unwrap();
    assert!(!e.axis(0).unwrap().compensation_status().enabled);
    assert_eq!(s.compensation, 0.0);
    assert!(!s.flags.contains(AxisFlags::COMPENSATION_LIMIT));
    // The reference back where the table is under the limit: accepted.
    move_to(&mut e, 1, 50.0);
    run(&mut e, 3.0);
    ok(&mut e, cmd(r#"{"type":"compensation_enable","axis":0}"#));
    e.step();
    assert_eq!(e.axis_status(0).unwrap().compensation, 0.75);
}
