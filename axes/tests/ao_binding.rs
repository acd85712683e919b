//! Analog outputs bound to an axis variable (`bind_analog_output`; issue 14, HIMC
//! SetSlvAOParam `ao_en_bind` 1, digest 004 §10.4): every tick the output is the variable of
//! that tick × scale + offset, until released; bad channels, axes and factors are typed errors.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{AnalogSource, BindAnalogOutput, Command};
use common::{cmd, enabled, move_abs, ok, refused_code, status, stepper_mm};

#[test]
fn a_bound_output_follows_the_commanded_velocity_every_tick() {
    // Smoothed: the output follows the command after smoothing, as the status shows it.
    let mut e = enabled(stepper_mm());
    common::set(&mut e, axes::ParamId::SmoothTime, 0.02);
    ok(
        &mut e,
        cmd(
            r#"{"type":"bind_analog_output","channel":1,"axis":0,"source":"cmd_vel","scale":0.01,"offset":0.5}"#,
        ),
    );
    ok(&mut e, move_abs(20.0));
    let mut moving_ticks = 0;
    for _ in 0..5000 {
        e.step();
        let v = status(&e).cmd_vel;
        assert_eq!(e.snapshot().io.ao[1], v * 0.01 + 0.5);
        moving_ticks += usize::from(v != 0.0);
    }
    assert!(moving_ticks > 10, "the move never ran");
    // The position, then released: the output keeps its last value.
    ok(
        &mut e,
        cmd(r#"{"type":"bind_analog_output","channel":1,"axis":0,"source":"act_pos"}"#),
    );
    e.step();
    assert_eq!(e.snapshot().io.ao[1], status(&e).act_pos);
    ok(&mut e, cmd(r#"{"type":"bind_analog_output","channel":1}"#));
    ok(&mut e, move_abs(0.0));
    let held = e.snapshot().io.ao[1];
    for _ in 0..100 {
        e.step();
    }
    assert_eq!(e.snapshot().io.ao[1], held);
    assert_ne!(status(&e).act_pos, held);
}

#[test]
fn bad_bindings_are_typed_errors() {
    let mut e = enabled(stepper_mm());
    let bad = |e: &mut axes::Engine, json: &str| refused_code(e, cmd(json));
    assert_eq!(
        bad(
            &mut e,
            r#"{"type":"bind_analog_output","channel":99,"axis":0}"#
        ),
        "invalid_channel"
    );
    assert_eq!(
        bad(
            &mut e,
            r#"{"type":"bind_analog_output","channel":0,"axis":7}"#
        ),
        "invalid_axis"
    );
    let nan = Command::from(BindAnalogOutput {
        channel: 0,
        axis: Some(0),
        source: AnalogSource::CmdPos,
        scale: f64::NAN,
        offset: 0.0,
        min: None,
        max: None,
    });
    assert_eq!(refused_code(&mut e, nan), "invalid_argument");
    assert_eq!(
        bad(
            &mut e,
            r#"{"type":"bind_analog_output","channel":0,"axis":0,"min":2,"max":1}"#
        ),
        "invalid_argument"
    );
}

/// `min` … `max` hold the output within a converter's range.
#[test]
fn a_bound_output_is_held_within_its_range() {
    let mut e = enabled(stepper_mm());
    ok(
        &mut e,
        cmd(
            r#"{"type":"bind_analog_output","channel":0,"axis":0,"source":"cmd_pos","scale":1000,"min":-100,"max":5000}"#,
        ),
    );
    ok(&mut e, move_abs(20.0));
    let mut seen = Vec::new();
    for _ in 0..5000 {
        e.step();
        seen.push(e.snapshot().io.ao[0]);
        let expected = (status(&e).cmd_pos * 1000.0).min(5000.0);
        assert_eq!(*seen.last().unwrap(), expected);
    }
    assert_eq!(*seen.last().unwrap(), 5000.0);
}
