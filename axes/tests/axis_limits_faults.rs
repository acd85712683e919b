//! Limits, following error, drive alarm, encoder loss, and the simulated hardware seen through
//! the engine (ARCHITECTURE §3.3 steps 2–8).

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    AxisInput, Command, CommandState, Direction, Enable, EngineError, ErrorKind, ForceDigitalInput,
    InjectFollowingError, Reset, ResetFaults, SetParameter, Setpoint, Stop, StopMode,
    StreamSetpoint,
};
use axes::config::{AxisConfig, AxisSignal, EngineConfig, InputBinding, PlantModel};
use axes::{AxisFlags, AxisState, Engine, ParamId};
use common::*;

#[test]
fn hard_limit_stops_the_axis_latches_and_allows_motion_out() {
    let mut e = enabled(stepper_mm());
    set(&mut e, ParamId::LimitLatch, 1.0);
    let id = id_of(ok(&mut e, jog(100.0)));
    let hit = run_until(&mut e, 10.0, |s| s.flags.contains(AxisFlags::HW_LIMIT_POS)).unwrap();
    assert!(hit > 4000);
    assert!(run_until(&mut e, 1.0, |s| s.state == AxisState::Standstill).is_some());
    let s = status(&e);
    // max(fast_decel 10 000, decel 1000) from 100 mm/s: 0.5 mm of overtravel (+1 tick latency).
    assert!(s.act_pos > 500.0 && s.act_pos < 500.7, "{}", s.act_pos);
    assert_eq!(
        state_of(&mut e, id),
        CommandState::Error(ErrorKind::LimitReached)
    );
    assert!(s.latched.contains(AxisFlags::MOTION_ERROR));
    // Further into the limit: refused. Out of it: fine.
    assert!(matches!(
        refused(&mut e, move_abs(600.0)),
        EngineError::LimitActive {
            axis: 0,
            direction: Direction::Positive
        }
    ));
    ok(&mut e, move_abs(400.0));
    assert!(run_until(&mut e, 10.0, |s| s.state == AxisState::Standstill).is_some());
    let s = status(&e);
    assert!(
        !s.flags.contains(AxisFlags::HW_LIMIT_POS) || s.latched.contains(AxisFlags::HW_LIMIT_POS)
    );
    // limit_latch = 1 (NMC): the flag stays until a reset once the input is clear.
    assert!(s.latched.contains(AxisFlags::HW_LIMIT_POS));
    ok(&mut e, Command::from(Reset { axis: 0 }));
    assert!(!status(&e).flags.contains(AxisFlags::HW_LIMIT_POS));
}

#[test]
fn masked_reset_clears_only_the_named_latches() {
    // NMC_MtClrStsByBits (TV26): a latched + limit (input released) and an E-stop.
    let mut e = enabled(stepper_mm());
    set(&mut e, ParamId::LimitLatch, 1.0);
    force(&mut e, AxisInput::LimitPos, Some(true));
    run(&mut e, 0.001);
    assert!(status(&e).inputs.contains(AxisFlags::HW_LIMIT_POS));
    force(&mut e, AxisInput::LimitPos, None);
    run(&mut e, 0.001);
    ok(
        &mut e,
        Command::from(Stop {
            axis: 0,
            mode: StopMode::Emergency,
            deceleration: None,
        }),
    );
    let s = status(&e);
    // The input's live level is gone; its latch is not.
    assert!(!s.inputs.contains(AxisFlags::HW_LIMIT_POS));
    assert!(s
        .latched
        .contains(AxisFlags::HW_LIMIT_POS | AxisFlags::ESTOP));
    ok(
        &mut e,
        Command::from(ResetFaults {
            axis: 0,
            faults: AxisFlags::ESTOP,
        }),
    );
    let s = status(&e);
    assert!(!s.latched.contains(AxisFlags::ESTOP));
    assert!(s.latched.contains(AxisFlags::HW_LIMIT_POS));
    // A named latch whose cause remains stays, and is reported.
    force(&mut e, AxisInput::LimitPos, Some(true));
    run(&mut e, 0.001);
    match refused(
        &mut e,
        Command::from(ResetFaults {
            axis: 0,
            faults: AxisFlags::HW_LIMIT_POS,
        }),
    ) {
        EngineError::CauseStillPresent { faults, .. } => {
            assert_eq!(faults, AxisFlags::HW_LIMIT_POS)
        }
        other => panic!("{other}"),
    }
    force(&mut e, AxisInput::LimitPos, None);
    run(&mut e, 0.001);
    ok(
        &mut e,
        Command::from(ResetFaults {
            axis: 0,
            faults: AxisFlags::HW_LIMIT_POS,
        }),
    );
    assert!(!status(&e).latched.contains(AxisFlags::HW_LIMIT_POS));
}

#[test]
fn forced_limit_and_auto_clearing_flags() {
    let mut e = enabled(stepper_mm());
    force(&mut e, AxisInput::LimitNeg, Some(true));
    run(&mut e, 0.001);
    assert!(status(&e).flags.contains(AxisFlags::HW_LIMIT_NEG));
    assert_eq!(param(&mut e, ParamId::LimitState), 2.0);
    assert!(matches!(
        refused(&mut e, jog(-1.0)),
        EngineError::LimitActive { .. }
    ));
    force(&mut e, AxisInput::LimitNeg, None);
    run(&mut e, 0.001);
    // limit_latch = 0 (HMC): the flag follows the input.
    assert!(!status(&e).flags.contains(AxisFlags::HW_LIMIT_NEG));
    ok(&mut e, jog(-1.0));
}

#[test]
fn inverted_limit_wiring_reads_active_until_fixed() {
    let mut cfg = stepper_mm();
    cfg.params.insert(ParamId::LimitPosInvert, 1.0);
    let mut e = enabled(cfg);
    run(&mut e, 0.001);
    assert!(
        status(&e).flags.contains(AxisFlags::HW_LIMIT_POS),
        "NO switch read as NC"
    );
    set(&mut e, ParamId::LimitPosInvert, 0.0);
    run(&mut e, 0.001);
    assert!(!status(&e).flags.contains(AxisFlags::HW_LIMIT_POS));
}

#[test]
fn soft_limits_stop_and_optionally_refuse_targets() {
    let mut cfg = stepper_mm();
    cfg.params.insert(ParamId::FsLimit, 50.0);
    cfg.params.insert(ParamId::RsLimit, -50.0);
    let mut e = enabled(cfg);
    let id = id_of(ok(&mut e, move_abs(100.0)));
    assert!(run_until(&mut e, 10.0, |s| s.state == AxisState::Standstill).is_some());
    let s = status(&e);
    assert!(s.cmd_pos >= 50.0 && s.cmd_pos < 51.0, "{}", s.cmd_pos);
    assert!(s.flags.contains(AxisFlags::SW_LIMIT_POS));
    assert_eq!(
        state_of(&mut e, id),
        CommandState::Error(ErrorKind::LimitReached)
    );
    ok(&mut e, move_abs(0.0));
    assert!(run_until(&mut e, 10.0, |s| s.state == AxisState::Standstill).is_some());
    set(&mut e, ParamId::SwLimitRejectTargets, 1.0);
    assert!(matches!(
        refused(&mut e, move_abs(60.0)),
        EngineError::InvalidArgument { .. }
    ));
    // Inconsistent soft limits are flagged (HMC LimitState bit 4) and not applied.
    set(&mut e, ParamId::FsLimit, -60.0);
    run(&mut e, 0.001);
    assert_eq!(param(&mut e, ParamId::LimitState) as u32 & 16, 16);
}

#[test]
fn cyclic_axes_ignore_limits_and_wrap() {
    // HMC §3.5.13 example (digest 000 TV63): RepMode 2, RepDist 1000, targets 900, −200, 700.
    let expect = |mode: f64, deltas: [f64; 3]| {
        let mut cfg = stepper_mm();
        cfg.params.insert(ParamId::RepMode, 2.0);
        cfg.params.insert(ParamId::RepDist, 1000.0);
        cfg.params.insert(ParamId::MoveAbsMode, mode);
        cfg.params.insert(ParamId::Speed, 2000.0);
        cfg.params.insert(ParamId::Accel, 1e5);
        cfg.params.insert(ParamId::Decel, 1e5);
        let mut e = enabled(cfg);
        for (target, delta) in [900.0, -200.0, 700.0].into_iter().zip(deltas) {
            let before = e.axis(0).unwrap().motor_position();
            ok(&mut e, move_abs(target));
            assert!(run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill).is_some());
            let moved = e.axis(0).unwrap().motor_position() - before;
            assert!(
                (moved - delta).abs() < 1e-6,
                "mode {mode}: {target} moved {moved}, want {delta}"
            );
            assert!((status(&e).cmd_pos - target).abs() < 1e-9);
        }
    };
    expect(0.0, [900.0, -1100.0, 900.0]);
    expect(1.0, [900.0, 900.0, 900.0]);
    expect(2.0, [900.0, 900.0, 900.0]);
    expect(3.0, [-1100.0, -1100.0, -1100.0]);
}

#[test]
fn following_error_warns_then_faults_and_reset_needs_the_cause_gone() {
    // HMC §3.3.3 (digest 000 TV43): one tick over → warning; 10 consecutive → fault; the default
    // AxisErrMask = 1 switches the drive off.
    let mut e = enabled(stepper_mm());
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: Some(2.0),
        }),
    );
    run(&mut e, 0.001);
    let s = status(&e);
    assert!(s.flags.contains(AxisFlags::FE_WARNING));
    assert!(!s.latched.contains(AxisFlags::FE_FAULT));
    assert_eq!(param(&mut e, ParamId::AxisStatusWord), 2.0);
    run(&mut e, 0.009);
    let s = status(&e);
    assert!(s.latched.contains(AxisFlags::FE_FAULT));
    assert_eq!(s.state, AxisState::ErrorStop);
    assert!(!s.flags.contains(AxisFlags::ENABLED));
    assert!(matches!(
        refused(&mut e, Command::from(Enable { axis: 0 })),
        EngineError::AxisInError { .. }
    ));
    // Disabled: the command tracks the actual position, so the error is gone and reset works;
    // but while the injected offset persists on an enabled axis it would come back.
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: None,
        }),
    );
    run(&mut e, 0.001);
    ok(&mut e, Command::from(Reset { axis: 0 }));
    assert_eq!(status(&e).state, AxisState::Disabled);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    // The warning clears itself after 1000 good ticks.
    run(&mut e, 0.999);
    assert!(!status(&e).flags.contains(AxisFlags::FE_WARNING));
}

#[test]
fn fe_fault_with_flag_only_reaction_keeps_moving() {
    // NMC default: posErrAction 0 = flag only (with AxisErrMask 0).
    let mut cfg = stepper_mm();
    cfg.params.insert(ParamId::AxisErrMask, 0.0);
    let mut e = enabled(cfg);
    ok(&mut e, jog(10.0));
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: Some(5.0),
        }),
    );
    run(&mut e, 0.1);
    let s = status(&e);
    assert!(s.latched.contains(AxisFlags::FE_FAULT));
    assert_eq!(s.state, AxisState::ContinuousMotion);
    // With the stop reaction the axis stops and sits in ErrorStop, still powered.
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: None,
        }),
    );
    run(&mut e, 0.001);
    ok(&mut e, Command::from(Reset { axis: 0 }));
    set(&mut e, ParamId::FeAction, 2.0);
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: Some(5.0),
        }),
    );
    run(&mut e, 0.1);
    let s = status(&e);
    assert_eq!(s.state, AxisState::ErrorStop);
    assert!(s.flags.contains(AxisFlags::ENABLED));
    assert_eq!(s.cmd_vel, 0.0);
    match refused(&mut e, Command::from(Reset { axis: 0 })) {
        EngineError::CauseStillPresent { faults, .. } => {
            assert!(faults.contains(AxisFlags::FE_FAULT))
        }
        other => panic!("{other}"),
    }
}

#[test]
fn drive_alarm_removes_power_until_cleared() {
    let mut e = enabled(stepper_mm());
    ok(&mut e, jog(10.0));
    run(&mut e, 0.1);
    force(&mut e, AxisInput::DriveAlarm, Some(true));
    run(&mut e, 0.001);
    let s = status(&e);
    assert_eq!(s.state, AxisState::ErrorStop);
    assert!(s.latched.contains(AxisFlags::DRIVE_ALARM));
    assert!(matches!(
        refused(&mut e, Command::from(Reset { axis: 0 })),
        EngineError::CauseStillPresent { .. }
    ));
    force(&mut e, AxisInput::DriveAlarm, Some(false));
    run(&mut e, 0.001);
    ok(&mut e, Command::from(Reset { axis: 0 }));
    ok(&mut e, Command::from(Enable { axis: 0 }));
    // Disabled alarm input (NMC default): no reaction.
    set(&mut e, ParamId::DriveAlarmEnable, 0.0);
    force(&mut e, AxisInput::DriveAlarm, Some(true));
    run(&mut e, 0.01);
    assert_eq!(status(&e).state, AxisState::Standstill);
}

#[test]
fn encoder_loss_faults_and_the_counts_it_missed_stay_missing() {
    let mut cfg = stepper_mm();
    cfg.params.insert(ParamId::AxisErrMask, 0.0);
    let mut e = enabled(cfg);
    ok(&mut e, jog(10.0));
    run(&mut e, 0.5);
    force(&mut e, AxisInput::EncoderLoss, Some(true));
    run(&mut e, 0.001);
    assert!(status(&e).latched.contains(AxisFlags::ENCODER_LOSS));
    assert_eq!(status(&e).state, AxisState::ErrorStop);
}

#[test]
fn index_pulse_and_home_switch_levels() {
    let mut e = enabled(stepper_mm());
    ok(&mut e, move_abs(110.0));
    let mut saw_index = 0;
    let mut home_from = None;
    for _ in 0..5000 {
        e.step();
        let s = status(&e);
        if s.flags.contains(AxisFlags::INDEX) {
            saw_index += 1;
        }
        if s.flags.contains(AxisFlags::HOME_SWITCH) && home_from.is_none() {
            home_from = Some(s.act_pos);
        }
    }
    // 10 000 counts/rev at 1000 counts/mm: an index every 10 mm; at 100 mm/s one tick covers
    // 100 counts so a 1-count index is seen only when a tick lands on it.
    let _ = saw_index;
    let h = home_from.unwrap();
    assert!((100.0..100.2).contains(&h), "{h}");
}

#[test]
fn di_bindings_and_di_routed_limits() {
    let mut cfg = EngineConfig {
        axes: vec![stepper_mm()],
        ..EngineConfig::default()
    };
    cfg.io.bindings.push(InputBinding {
        channel: 5,
        axis: 0,
        signal: AxisSignal::Home,
    });
    let mut e = Engine::new(&cfg).unwrap();
    ok(&mut e, Command::from(Enable { axis: 0 }));
    ok(&mut e, move_abs(110.0));
    run(&mut e, 3.0);
    assert!(e.io().di[5], "DI 5 follows the home switch");
    // HMC_HwLimitConfig(axis, 0, 7): the positive limit is DI 7.
    set(&mut e, ParamId::FhLimitIn, 7.0);
    ok(
        &mut e,
        Command::from(ForceDigitalInput {
            channel: 7,
            value: Some(true),
        }),
    );
    run(&mut e, 0.002);
    assert!(status(&e).flags.contains(AxisFlags::HW_LIMIT_POS));
    set(&mut e, ParamId::FhLimitIn, -1.0);
    run(&mut e, 0.001);
    assert!(!status(&e).flags.contains(AxisFlags::HW_LIMIT_POS));
}

fn servo_axis() -> AxisConfig {
    let mut a = stepper_mm();
    a.params.insert(ParamId::AxisType, 20.0);
    a.params.insert(ParamId::ServoLoop, 1.0);
    a.params.insert(ParamId::Kp, 3000.0);
    a.params.insert(ParamId::Kvff, 32767.0 / 200.0);
    a.params.insert(ParamId::FeLimit, 5.0);
    a.plant.model = PlantModel::PositionLoop;
    a.plant.full_scale_velocity = 200.0;
    a
}

#[test]
fn closed_loop_servo_tracks_and_settles() {
    let mut e = enabled(servo_axis());
    ok(&mut e, move_abs(50.0));
    let trace = record(&mut e, 3.0);
    assert!(trace.iter().all(|s| s.following_error.abs() < 5.0));
    assert!(trace.iter().any(|s| s.dac_out != 0.0));
    let s = status(&e);
    assert_eq!(s.cmd_pos, 50.0);
    assert!((s.act_pos - 50.0).abs() < 0.01, "{}", s.act_pos);
    assert_eq!(s.state, AxisState::Standstill);
}

#[test]
fn cmd_stop_mode_1_waits_for_the_following_error() {
    // HMC §3.5.12 (digest 000 TV48): FE held above StopFETol ⇒ the command completes exactly
    // 500 ms after the commanded position arrives.
    let mut cfg = servo_axis();
    cfg.params.insert(ParamId::CmdStopMode, 1.0);
    cfg.params.insert(ParamId::StopFeTol, 0.001);
    cfg.params.insert(ParamId::AxisErrMask, 0.0);
    let mut e = enabled(cfg);
    let id = id_of(ok(&mut e, move_abs(10.0)));
    let arrive = run_until(&mut e, 5.0, |s| s.cmd_pos == 10.0).unwrap();
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: Some(0.5),
        }),
    );
    let done = run_until(&mut e, 5.0, |s| s.current_command.is_none()).unwrap();
    assert_eq!(state_of(&mut e, id), CommandState::Done);
    assert!((499..=501).contains(&done), "{arrive} then {done}");
}

#[test]
fn plant_type_mismatch_is_refused() {
    let mut cfg = stepper_mm();
    cfg.params.insert(ParamId::AxisType, 20.0);
    let err = Engine::new(&EngineConfig {
        axes: vec![cfg],
        ..EngineConfig::default()
    })
    .unwrap_err();
    assert_eq!(err.key, "axes[0].plant.model");
    let mut e = one_axis();
    assert!(matches!(
        refused(
            &mut e,
            Command::from(SetParameter {
                axis: 0,
                name: ParamId::AxisType,
                value: 20.0,
                lenient: false
            })
        ),
        EngineError::InvalidParameter { .. }
    ));
}

#[test]
fn virtual_axes_have_mpos_equal_dpos_and_encoder_axes_refuse_motion() {
    let mut v = AxisConfig::default();
    v.params.insert(ParamId::RepMode, 0.0);
    v.params.insert(ParamId::Speed, 7.0);
    let mut e = enabled(v);
    ok(&mut e, move_abs(1.0 / 3.0));
    for _ in 0..300 {
        e.step();
        let s = status(&e);
        assert_eq!(s.cmd_pos, s.act_pos);
    }
    let mut enc = AxisConfig::default();
    enc.params.insert(ParamId::AxisType, 30.0);
    let mut e = engine_with(vec![enc]);
    assert!(matches!(
        refused(&mut e, Command::from(Enable { axis: 0 })),
        EngineError::Unsupported { .. }
    ));
}

#[test]
fn external_setpoints_drive_the_axis() {
    let mut e = enabled(stepper_mm());
    for k in 1..=100 {
        ok(
            &mut e,
            Command::from(StreamSetpoint {
                axis: 0,
                setpoint: Some(Setpoint::Position {
                    position: k as f64 * 0.01,
                }),
            }),
        );
        e.step();
        assert_eq!(status(&e).state, AxisState::SynchronizedMotion);
    }
    assert!((status(&e).cmd_pos - 1.0).abs() < 1e-12);
    ok(
        &mut e,
        Command::from(StreamSetpoint {
            axis: 0,
            setpoint: Some(Setpoint::Velocity { velocity: 5.0 }),
        }),
    );
    run(&mut e, 1.0);
    assert!((status(&e).cmd_pos - 6.0).abs() < 1e-9);
    ok(
        &mut e,
        Command::from(StreamSetpoint {
            axis: 0,
            setpoint: None,
        }),
    );
    assert!(run_until(&mut e, 1.0, |s| s.state == AxisState::Standstill).is_some());
}

#[test]
fn smoothing_lengthens_the_move_and_still_ends_exactly() {
    // NMC smoothCoef / HIMC SMTime: a moving average of T_s lengthens the move by T_s.
    let plain = {
        let mut e = enabled(stepper_mm());
        ok(&mut e, move_abs(30.0));
        run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill).unwrap()
    };
    let mut cfg = stepper_mm();
    cfg.params.insert(ParamId::SmoothTime, 0.05);
    let mut e = enabled(cfg);
    ok(&mut e, move_abs(30.0));
    let smooth = run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill).unwrap();
    assert_eq!(status(&e).cmd_pos, 30.0);
    assert!(
        (smooth as i64 - plain as i64 - 50).abs() <= 1,
        "{plain} → {smooth}"
    );
}

#[test]
fn cpu226h_ramp_from_min_speed() {
    // CPU 226H tip 3 (digest 003 TV-11): MIN 500, MAX 10 500 Hz, TA 100 ms ⇒ 100 Hz/ms.
    let mut cfg = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 10.0),
        (ParamId::RepMode, 0.0),
        (ParamId::StartVelocity, 500.0),
        (ParamId::EndVelocity, 500.0),
        (ParamId::Speed, 10_500.0),
        (ParamId::AccelTime, 0.1),
        (ParamId::DecelTime, 0.1),
    ] {
        cfg.params.insert(p, v);
    }
    cfg.pulse.max_frequency = 200_000.0;
    let mut e = enabled(cfg);
    ok(&mut e, move_abs(20_000.0));
    e.step();
    let first = status(&e);
    assert!(
        (first.cmd_vel - 500.0 - 100.0).abs() < 1.0,
        "jump-start at MIN_SPEED: {}",
        first.cmd_vel
    );
    let t = run_until(&mut e, 10.0, |s| s.state == AxisState::Standstill).unwrap();
    assert_eq!(status(&e).pulses, 20_000);
    // Ramps of 100 ms each, cruise (20 000 − 1100)/10 500 s.
    let expected = 0.2 + (20_000.0 - 1100.0) / 10_500.0;
    assert!((t as f64 / 1000.0 - expected).abs() < 0.003, "{t}");
}

#[test]
fn rollover_makes_the_axis_cyclic_at_run_time() {
    // HIMC SetRollover (only while disabled): positions wrap into [0, rollover).
    let mut e = one_axis();
    set(&mut e, ParamId::Rollover, 360.0);
    assert_eq!(param(&mut e, ParamId::RepMode), 1.0);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    assert!(matches!(
        refused(
            &mut e,
            Command::from(SetParameter {
                axis: 0,
                name: ParamId::Rollover,
                value: 90.0,
                lenient: false
            })
        ),
        EngineError::InvalidState { .. }
    ));
    ok(&mut e, jog(100.0));
    run(&mut e, 5.0);
    let s = status(&e);
    assert!((0.0..360.0).contains(&s.cmd_pos), "{}", s.cmd_pos);
    assert!(
        !s.flags.contains(AxisFlags::HW_LIMIT_POS),
        "cyclic axes ignore limits"
    );
}

#[test]
fn hmc_style_wiring_a_switch_to_a_di_and_the_limit_to_that_di() {
    // HMC_HwLimitConfig(axis, 0, 5): the positive limit is DI 5, and DI 5 is wired to the axis's
    // own limit switch. The binding carries the sensor's level, so the limit works through it.
    let mut cfg = EngineConfig {
        axes: vec![stepper_mm()],
        ..EngineConfig::default()
    };
    cfg.axes[0].params.insert(ParamId::FhLimitIn, 5.0);
    cfg.io.bindings.push(InputBinding {
        channel: 5,
        axis: 0,
        signal: AxisSignal::LimitPos,
    });
    let mut e = Engine::new(&cfg).unwrap();
    ok(&mut e, Command::from(Enable { axis: 0 }));
    ok(&mut e, jog(100.0));
    assert!(run_until(&mut e, 10.0, |s| s.flags.contains(AxisFlags::HW_LIMIT_POS)).is_some());
    assert!(e.io().di[5]);
    assert!(run_until(&mut e, 1.0, |s| s.state == AxisState::Standstill).is_some());
    let s = status(&e);
    assert!(s.act_pos > 500.0 && s.act_pos < 501.0, "{}", s.act_pos);
    assert!(matches!(
        refused(&mut e, jog(1.0)),
        EngineError::LimitActive { .. }
    ));
}
