//! What the axis status measures for HIMC's last getters (issue 14; digest 004 §2.4
//! 5.3.17–5.3.40, §3.7–3.10): the last move's time and settling time on the virtual clock, the
//! origin offset `set_position` moves, a rollover axis's turns, and the drive's torque.

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, PositionFrame, SetPosition, Setpoint, Stop, StopMode, StreamSetpoint,
};
use axes::{AxisFlags, ParamId};
use common::*;

fn near(got: f64, want: f64, tolerance: f64) -> bool {
    (got - want).abs() <= tolerance
}

#[test]
fn move_time_is_the_profile_and_settling_time_the_wait_for_in_position() {
    // 100 mm at 100 mm/s, 1000 mm/s²: 0.1 s up, 0.9 s cruise, 0.1 s down = 1.1 s.
    // A drive that lags 5 ms behind its command: 0.5 mm behind at 100 mm/s, so the window
    // (0.01 mm) is left while moving and reached again shortly after the profile ends.
    let mut axis = stepper_mm();
    axis.plant.model = axes::hw::plant::PlantModel::Lag;
    axis.plant.time_constant = 0.005;
    axis.params.insert(ParamId::InPositionWindow, 0.01);
    axis.params.insert(ParamId::InPositionTime, 0.05);
    let mut e = enabled(axis);
    run(&mut e, 0.1);
    assert_eq!((status(&e).move_time, status(&e).settling_time), (0.0, 0.0));
    ok(&mut e, move_abs(100.0));
    run(&mut e, 0.5);
    assert_eq!(status(&e).move_time, 0.0, "the move has not ended yet");
    run(&mut e, 1.0);
    let period = e.period();
    let s = status(&e);
    assert!(near(s.move_time, 1.1, 2.0 * period), "{}", s.move_time);
    // In position once the lag has closed to the window and the window time (50 ms) has run.
    assert!(
        s.settling_time > 0.05 && s.settling_time < 0.2,
        "{}",
        s.settling_time
    );
    // The next move replaces both; until it settles, settling reads 0.
    // 10 mm: 0.1 s up, 0.1 s down.
    ok(&mut e, move_abs(90.0));
    run(&mut e, 0.01);
    run_until(&mut e, 2.0, |s| !s.flags.contains(AxisFlags::MOVING)).unwrap();
    let s = status(&e);
    assert!(near(s.move_time, 0.2, 2.0 * period), "{}", s.move_time);
    assert_eq!(s.settling_time, 0.0);
}

#[test]
fn set_position_moves_the_origin_offset() {
    // Digest 004 TV 32: at 100, redefining the position as 0 makes the offset −100.
    let mut e = enabled(stepper_mm());
    ok(&mut e, move_abs(100.0));
    run(&mut e, 2.0);
    assert_eq!(status(&e).position_offset, 0.0);
    ok(
        &mut e,
        Command::from(SetPosition {
            axis: 0,
            position: 0.0,
            frame: PositionFrame::Both,
        }),
    );
    let s = status(&e);
    assert!(
        near(s.position_offset, -100.0, 1e-9),
        "{}",
        s.position_offset
    );
    assert!(near(s.cmd_pos, 0.0, 1e-9));
}

#[test]
fn a_rollover_axis_counts_whole_turns_below_zero_too() {
    let axis = free_linear_axis(
        1000.0,
        &[
            (ParamId::Rollover, 360.0),
            (ParamId::Speed, 3600.0),
            (ParamId::Accel, 36_000.0),
            (ParamId::Decel, 36_000.0),
        ],
    );
    let mut e = enabled(axis);
    assert_eq!(status(&e).rollover_turns, 0);
    ok(&mut e, move_rel_of(0, 800.0));
    run(&mut e, 2.0);
    let s = status(&e);
    assert_eq!(s.rollover_turns, 2);
    assert!(near(s.act_pos, 80.0, 1e-6), "{}", s.act_pos);
    ok(&mut e, move_rel_of(0, -1000.0));
    run(&mut e, 2.0);
    let s = status(&e);
    assert_eq!(s.rollover_turns, -1, "−200° is one turn below 0 and 160°");
    assert!(near(s.act_pos, 160.0, 1e-6), "{}", s.act_pos);
    // A finite axis has no turns.
    let mut e = enabled(stepper_mm());
    ok(&mut e, move_abs(400.0));
    run(&mut e, 5.0);
    assert_eq!(status(&e).rollover_turns, 0);
}

#[test]
fn torque_is_the_setpoint_in_torque_mode_else_the_acceleration_over_the_rated() {
    let mut e = enabled(stepper_mm());
    assert_eq!(status(&e).torque, 0.0);
    // Accelerating at `accel` (no `max_accel`): rated torque; cruising: none.
    ok(&mut e, move_abs(100.0));
    run(&mut e, 0.05);
    assert!(near(status(&e).torque, 1.0, 1e-9), "{}", status(&e).torque);
    run(&mut e, 0.3);
    assert_eq!(status(&e).torque, 0.0);
    run(&mut e, 2.0);
    ok(
        &mut e,
        Command::from(StreamSetpoint {
            axis: 0,
            setpoint: Some(Setpoint::Torque { torque: 0.25 }),
        }),
    );
    run(&mut e, 0.01);
    assert_eq!(status(&e).torque, 0.25);
    ok(
        &mut e,
        Command::from(Stop {
            axis: 0,
            mode: StopMode::default(),
            deceleration: None,
        }),
    );
    run(&mut e, 2.0);
    assert_eq!(status(&e).torque, 0.0, "stopped: torque mode has ended");
}

#[test]
fn the_rated_torque_and_current_are_axis_parameters() {
    let mut e = one_axis();
    assert_eq!(param(&mut e, ParamId::RatedTorque), 1.27);
    assert_eq!(param(&mut e, ParamId::RatedCurrent), 2.6);
    set(&mut e, ParamId::RatedCurrent, 4.2);
    assert_eq!(param(&mut e, ParamId::RatedCurrent), 4.2);
}
