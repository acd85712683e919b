//! Homing through the engine: the real switches, index pulse, profile generator and frames
//! (ARCHITECTURE §3.7).

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, CommandState, EngineError, ErrorKind, PositionFrame, SetPosition, Stop,
};
use axes::config::HomeSwitchConfig;
use axes::homing::vendor::{hmc, HmcInstruction};
use axes::homing::{HomingError, HomingFailure, HomingQuirks, HomingSpec};
use axes::{AxisFlags, AxisState, Engine};
use common::*;

fn home(spec: &HomingSpec) -> Command {
    home_of(0, spec)
}

fn cia(method: i16, offset: f64) -> HomingSpec {
    HomingSpec {
        method,
        switch_velocity: 40.0,
        zero_velocity: 4.0,
        acceleration: 800.0,
        offset,
        timeout: 60.0,
        quirks: HomingQuirks::default(),
    }
}

/// Index pulses at 5, 15, …, 95, 105 mm (physical).
fn homing_axis() -> Engine {
    let mut cfg = stepper_mm();
    cfg.encoder.index_offset = 5000;
    enabled(cfg)
}

fn motor(e: &Engine) -> f64 {
    e.axis(0).unwrap().motor_position()
}

#[test]
fn method_7_finds_the_index_left_of_the_cam_and_redefines_the_frame() {
    let mut e = homing_axis();
    let id = id_of(ok(&mut e, home(&cia(7, 12.5))));
    assert_eq!(status(&e).state, AxisState::Homing);
    assert!(run_until(&mut e, 30.0, |s| s.current_command.is_none()).is_some());
    let s = status(&e);
    assert_eq!(state_of(&mut e, id), CommandState::Done);
    assert!(s.flags.contains(AxisFlags::HOMED));
    assert_eq!(s.state, AxisState::Standstill);
    // The home point is the index at 95 mm (physical) and now reads 12.5; the axis decelerated
    // past it in the negative direction (CiA 402: no return).
    let home_reading = s.act_pos - (motor(&e) - 95.0);
    assert!((home_reading - 12.5).abs() < 1e-6, "{home_reading}");
    assert!(motor(&e) < 95.0 && motor(&e) > 94.9);
    assert!((s.cmd_pos - s.act_pos).abs() < 1e-9);
}

#[test]
fn hmc_mode_0_returns_to_the_origin() {
    // HMC_Home(axis, 0, DI): + at Speed to the rising edge, creep back to the falling edge,
    // origin there, return to it (digest 000 §5). The polled latch is up to one tick late.
    let mut cfg = stepper_mm();
    cfg.switches.home = Some(HomeSwitchConfig {
        low: 100.0,
        high: f64::INFINITY,
        filter: 0,
        active_low: false,
    });
    let mut e = enabled(cfg);
    let spec = hmc(HmcInstruction::Home, 0, 50.0, 5.0, 500.0).unwrap();
    ok(&mut e, home(&spec));
    assert!(run_until(&mut e, 30.0, |s| s.current_command.is_none()).is_some());
    let s = status(&e);
    assert!(s.flags.contains(AxisFlags::HOMED));
    assert_eq!(s.cmd_pos, 0.0, "ends exactly at the origin");
    let m = motor(&e);
    assert!(
        (99.994..=100.0).contains(&m),
        "origin within one creep tick of the edge: {m}"
    );
}

#[test]
fn method_37_and_missing_inputs() {
    let mut e = homing_axis();
    ok(&mut e, move_abs(3.0));
    run(&mut e, 1.0);
    ok(&mut e, home(&cia(37, -4.0)));
    run(&mut e, 0.002);
    assert_eq!(status(&e).act_pos, -4.0);
    assert!(status(&e).flags.contains(AxisFlags::HOMED));

    let mut bare = stepper_mm();
    bare.switches.limit_neg = None;
    let mut e = enabled(bare);
    match refused(&mut e, home(&cia(1, 0.0))) {
        EngineError::Homing(HomingError::MissingInput { method: 1, .. }) => {}
        other => panic!("{other}"),
    }
    match refused(&mut e, home(&cia(15, 0.0))) {
        EngineError::Homing(HomingError::UnsupportedMethod { method: 15 }) => {}
        other => panic!("{other}"),
    }
}

#[test]
fn homing_timeout_fails_the_command_and_the_axis_stops() {
    let mut e = homing_axis();
    let mut spec = cia(34, 0.0);
    spec.zero_velocity = 0.001; // too slow to reach the index at 5 mm
    spec.timeout = 0.5;
    let id = id_of(ok(&mut e, home(&spec)));
    assert!(run_until(&mut e, 5.0, |s| s.current_command.is_none()).is_some());
    assert_eq!(state_of(&mut e, id), CommandState::Error(ErrorKind::Homing));
    let s = status(&e);
    assert!(s.latched.contains(AxisFlags::HOMING_FAILED));
    assert_eq!(s.homing_failure, Some(HomingFailure::Timeout));
    assert!(!s.flags.contains(AxisFlags::HOMED));
    assert_eq!(s.state, AxisState::Standstill);
    assert_eq!(s.cmd_vel, 0.0);
}

#[test]
fn home_error_is_the_home_found_minus_the_home_defined() {
    // Method 17: the negative limit releases at −500 mm (physical); NMC_MtGetHomeError.
    let mut e = homing_axis();
    ok(&mut e, home(&cia(17, 0.0)));
    assert!(run_until(&mut e, 60.0, |s| s.current_command.is_none()).is_some());
    // No home defined before: the power-on origin stands for it.
    let first = status(&e).home_error;
    assert!((first + 500.0).abs() < 1e-3, "{first}");
    // A trial run in the frame the homing made finds home where it put it.
    let mut trial = cia(17, 0.0);
    trial.quirks.trial = true;
    ok(&mut e, home(&trial));
    assert!(run_until(&mut e, 60.0, |s| s.current_command.is_none()).is_some());
    let again = status(&e).home_error;
    assert!(again.abs() < 1e-3, "{again}");
    // The recorded home is a number: redefining the position by +10 reads as 10 of error.
    let here = status(&e).cmd_pos;
    ok(
        &mut e,
        Command::from(SetPosition {
            axis: 0,
            position: here + 10.0,
            frame: PositionFrame::default(),
        }),
    );
    ok(&mut e, home(&trial));
    assert!(run_until(&mut e, 60.0, |s| s.current_command.is_none()).is_some());
    let shifted = status(&e).home_error;
    assert!((shifted - 10.0).abs() < 1e-3, "{shifted}");
    assert_eq!(status(&e).homing_failure, None);
}

#[test]
fn homing_on_the_limit_switch_does_not_fault_the_axis() {
    // Method 17: negative limit, home where it releases (−500 mm).
    let mut e = homing_axis();
    ok(&mut e, home(&cia(17, 0.0)));
    assert!(run_until(&mut e, 60.0, |s| s.current_command.is_none()).is_some());
    let s = status(&e);
    assert!(s.flags.contains(AxisFlags::HOMED), "{s:?}");
    let home_reading = s.act_pos - (motor(&e) - (-500.0));
    assert!(home_reading.abs() < 1e-6, "{home_reading}");
    assert_eq!(s.state, AxisState::Standstill);
}

#[test]
fn a_homing_run_that_fails_on_a_limit_ends_at_rest() {
    // Method 3 searches positive for a home switch that lies beyond the positive limit: the
    // limit ends the run with an error, and the axis must end stopped, not merely "standstill".
    let mut cfg = stepper_mm();
    cfg.switches.home = Some(HomeSwitchConfig {
        low: 600.0,
        high: 700.0,
        filter: 0,
        active_low: false,
    });
    let mut e = enabled(cfg);
    let id = id_of(ok(&mut e, home(&cia(3, 0.0))));
    assert!(run_until(&mut e, 60.0, |s| s.current_command.is_none()).is_some());
    assert_eq!(state_of(&mut e, id), CommandState::Error(ErrorKind::Homing));
    run(&mut e, 0.01);
    let s = status(&e);
    assert_eq!(s.state, AxisState::Standstill);
    assert_eq!(s.cmd_vel, 0.0, "{s:?}");
    assert!(!s.flags.contains(AxisFlags::MOVING), "{s:?}");
    assert!(s.latched.contains(AxisFlags::HOMING_FAILED));
    assert_eq!(s.homing_failure, Some(HomingFailure::LimitHit));
}

#[test]
fn homing_and_stops_end_only_when_the_smoothed_command_has_settled() {
    // HIMC SMTime: the command keeps moving one window after the profile stops; homing and stop
    // ramps must not report rest before that.
    let mut cfg = stepper_mm();
    cfg.params.insert(axes::ParamId::SmoothTime, 0.05);
    cfg.switches.home = Some(HomeSwitchConfig {
        low: 600.0,
        high: 700.0,
        filter: 0,
        active_low: false,
    });
    let mut e = enabled(cfg);
    ok(&mut e, home(&cia(3, 0.0)));
    assert!(run_until(&mut e, 60.0, |s| s.current_command.is_none()).is_some());
    let s = status(&e);
    assert_eq!(s.cmd_vel, 0.0, "{s:?}");
    assert!(!s.flags.contains(AxisFlags::MOVING));
    ok(&mut e, jog(-50.0));
    run(&mut e, 1.0);
    ok(
        &mut e,
        Command::from(Stop {
            axis: 0,
            mode: axes::command::StopMode::Smooth,
            deceleration: None,
        }),
    );
    while status(&e).state == AxisState::Stopping {
        e.step();
    }
    assert_eq!(status(&e).cmd_vel, 0.0);
}
