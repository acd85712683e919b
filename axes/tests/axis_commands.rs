//! Single-axis behaviour through `Command` → `Result<Reply, EngineError>` (ARCHITECTURE §3.4–§3.5):
//! the state machine, the FIFO, stops, halts, parameters, bad input.

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    BufferMode, Cancel, CancelScope, Command, CommandKind, CommandState, Disable, Enable,
    EngineError, ErrorKind, ForceAnalogInput, ForceDigitalInput, ForceInput, GetCommandState, Halt,
    ModifyTarget, MoveAbsolute, PositionFrame, Reply, Reset, Resume, SetParameter, SetPosition,
    Stop, StopMode, WriteAnalogOutput, WriteDigitalOutput,
};
use axes::{AxisFlags, AxisState, ParamId};
use common::*;

#[test]
fn enable_disable_and_motion_needs_power() {
    let mut e = one_axis();
    assert_eq!(status(&e).state, AxisState::Disabled);
    let err = refused(&mut e, move_abs(10.0));
    assert!(
        matches!(err, EngineError::AxisDisabled { axis: 0 }),
        "{err}"
    );
    ok(&mut e, Command::from(Enable { axis: 0 }));
    assert_eq!(status(&e).state, AxisState::Standstill);
    assert!(status(&e).flags.contains(AxisFlags::ENABLED));
    ok(&mut e, Command::from(Disable { axis: 0 }));
    assert_eq!(status(&e).state, AxisState::Disabled);
}

#[test]
fn bad_input_is_a_typed_error_and_the_engine_keeps_running() {
    let mut e = enabled(stepper_mm());
    let bad = [
        Command::from(Enable { axis: 7 }),
        move_abs(f64::NAN),
        move_abs(f64::INFINITY),
        jog(f64::NEG_INFINITY),
        Command::from(MoveAbsolute {
            axis: 0,
            position: 1.0,
            velocity: Some(0.0),
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: BufferMode::Aborting,
        }),
        Command::from(MoveAbsolute {
            axis: 0,
            position: 1.0,
            velocity: None,
            acceleration: Some(-3.0),
            deceleration: None,
            jerk: None,
            buffer_mode: BufferMode::Aborting,
        }),
        Command::from(MoveAbsolute {
            axis: 0,
            position: 1.0,
            velocity: None,
            acceleration: None,
            deceleration: Some(f64::NAN),
            jerk: None,
            buffer_mode: BufferMode::Aborting,
        }),
        Command::from(SetParameter {
            axis: 0,
            name: ParamId::Accel,
            value: 0.0,
            lenient: false,
        }),
        Command::from(SetParameter {
            axis: 0,
            name: ParamId::ActualPosition,
            value: 1.0,
            lenient: false,
        }),
        Command::from(Stop {
            axis: 0,
            mode: StopMode::Smooth,
            deceleration: Some(-1.0),
        }),
        Command::from(SetPosition {
            axis: 0,
            position: f64::NAN,
            frame: PositionFrame::Both,
        }),
        Command::from(GetCommandState { id: 999 }),
        Command::from(WriteDigitalOutput {
            channel: 9999,
            value: true,
        }),
    ];
    for c in bad {
        let err = refused(&mut e, c);
        // Every refusal says why.
        assert!(!err.to_string().is_empty());
    }
    assert!(matches!(
        refused(&mut e, Command::from(Enable { axis: 7 })),
        EngineError::InvalidAxis { axis: 7, count: 1 }
    ));
    // Still alive and correct after all that.
    ok(&mut e, move_abs(5.0));
    run(&mut e, 1.0);
    assert_eq!(status(&e).cmd_pos, 5.0);
    assert_eq!(status(&e).state, AxisState::Standstill);
}

#[test]
fn a_move_reaches_its_target_exactly_and_emits_the_pulses() {
    let mut e = enabled(stepper_mm());
    let id = id_of(ok(&mut e, move_abs(50.0)));
    assert_eq!(state_of(&mut e, id), CommandState::Running);
    assert_eq!(status(&e).state, AxisState::DiscreteMotion);
    assert!(run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill).is_some());
    let s = status(&e);
    assert_eq!(s.cmd_pos, 50.0);
    assert_eq!(s.act_pos, 50.0);
    assert_eq!(s.pulses, 50_000, "HMC §4.7.3: 1000 lines/mm × 50 mm");
    assert_eq!(s.encoder_counts, 50_000);
    assert_eq!(s.following_error, 0.0);
    assert!(s.flags.contains(AxisFlags::IN_POSITION));
    assert_eq!(state_of(&mut e, id), CommandState::Done);
}

#[test]
fn buffered_commands_run_in_order_and_the_fifo_is_bounded() {
    let mut axis = stepper_mm();
    axis.fifo_depth = Some(3);
    let mut e = enabled(axis);
    let a = id_of(ok(&mut e, move_rel_buffered(10.0)));
    let b = id_of(ok(&mut e, move_rel_buffered(20.0)));
    let c = id_of(ok(&mut e, move_rel_buffered(-5.0)));
    assert!(a < b && b < c);
    assert_eq!(state_of(&mut e, a), CommandState::Running);
    assert_eq!(state_of(&mut e, b), CommandState::Waiting);
    assert!(status(&e).flags.contains(AxisFlags::QUEUE_FULL));
    assert!(matches!(
        refused(&mut e, move_rel_buffered(1.0)),
        EngineError::QueueFull { axis: 0, depth: 3 }
    ));
    let st = status(&e);
    assert_eq!(st.current_command.map(|c| c.id), Some(a));
    assert_eq!(
        st.next_command.map(|c| c.kind),
        Some(CommandKind::MoveRelative)
    );
    assert!(run_until(&mut e, 10.0, |s| s.fifo_len == 0
        && s.state == AxisState::Standstill)
    .is_some());
    assert_eq!(status(&e).cmd_pos, 25.0);
    for id in [a, b, c] {
        assert_eq!(state_of(&mut e, id), CommandState::Done);
    }
}

#[test]
fn an_aborting_command_aborts_the_running_and_queued_ones() {
    let mut e = enabled(stepper_mm());
    let a = id_of(ok(&mut e, move_rel_buffered(100.0)));
    let b = id_of(ok(&mut e, move_rel_buffered(100.0)));
    run(&mut e, 0.2);
    let c = id_of(ok(&mut e, move_abs(-10.0)));
    assert_eq!(state_of(&mut e, a), CommandState::Aborted);
    assert_eq!(state_of(&mut e, b), CommandState::Aborted);
    assert!(run_until(&mut e, 10.0, |s| s.state == AxisState::Standstill).is_some());
    assert_eq!(status(&e).cmd_pos, -10.0);
    assert_eq!(state_of(&mut e, c), CommandState::Done);
}

#[test]
fn consecutive_zero_length_buffered_moves_share_an_id() {
    // HMC §10.7 (digest 000 TV47).
    let mut e = enabled(stepper_mm());
    ok(&mut e, move_rel_buffered(100.0));
    let z1 = id_of(ok(&mut e, move_rel_buffered(0.0)));
    let z2 = id_of(ok(&mut e, move_rel_buffered(0.0)));
    assert_eq!(z1, z2);
    let n = id_of(ok(&mut e, move_rel_buffered(1.0)));
    assert_ne!(n, z2);
}

#[test]
fn jog_both_ways_then_smooth_stop() {
    let mut e = enabled(stepper_mm());
    ok(&mut e, jog(20.0));
    assert_eq!(status(&e).state, AxisState::ContinuousMotion);
    run(&mut e, 1.0);
    assert!((status(&e).cmd_vel - 20.0).abs() < 1e-9);
    ok(&mut e, jog(-20.0));
    run(&mut e, 1.0);
    assert!((status(&e).cmd_vel + 20.0).abs() < 1e-9);
    ok(
        &mut e,
        Command::from(Stop {
            axis: 0,
            mode: StopMode::Smooth,
            deceleration: Some(200.0),
        }),
    );
    assert_eq!(status(&e).state, AxisState::Stopping);
    // Motion is refused until the stop is done (PLCopen MC_Stop).
    assert!(matches!(
        refused(&mut e, move_abs(0.0)),
        EngineError::InvalidState { .. }
    ));
    // 20 mm/s at 200 mm/s² stops in 0.1 s.
    let ticks = run_until(&mut e, 1.0, |s| s.state == AxisState::Standstill).unwrap();
    assert!((99..=101).contains(&ticks), "{ticks}");
    assert_eq!(status(&e).cmd_vel, 0.0);
    ok(&mut e, move_abs(0.0));
}

#[test]
fn emergency_stop_latches_and_needs_a_reset_abrupt_does_not() {
    let mut e = enabled(stepper_mm());
    ok(&mut e, jog(50.0));
    run(&mut e, 0.5);
    ok(
        &mut e,
        Command::from(Stop {
            axis: 0,
            mode: StopMode::Abrupt,
            deceleration: None,
        }),
    );
    run(&mut e, 0.1);
    assert_eq!(status(&e).state, AxisState::Standstill);
    ok(&mut e, jog(50.0));
    run(&mut e, 0.5);
    ok(
        &mut e,
        Command::from(Stop {
            axis: 0,
            mode: StopMode::Emergency,
            deceleration: None,
        }),
    );
    run(&mut e, 0.1);
    let s = status(&e);
    assert_eq!(s.state, AxisState::ErrorStop);
    assert!(s.latched.contains(AxisFlags::ESTOP));
    assert_eq!(s.cmd_vel, 0.0);
    assert!(matches!(
        refused(&mut e, jog(1.0)),
        EngineError::AxisInError { .. }
    ));
    ok(&mut e, Command::from(Reset { axis: 0 }));
    assert_eq!(status(&e).state, AxisState::Standstill);
    ok(&mut e, jog(1.0));
}

#[test]
fn immediate_stop_jumps_to_zero() {
    let mut e = enabled(stepper_mm());
    ok(&mut e, jog(50.0));
    run(&mut e, 0.5);
    let before = status(&e).cmd_pos;
    ok(
        &mut e,
        Command::from(Stop {
            axis: 0,
            mode: StopMode::Immediate,
            deceleration: None,
        }),
    );
    run(&mut e, 0.01);
    assert_eq!(status(&e).cmd_pos, before);
    assert_eq!(status(&e).state, AxisState::Standstill);
}

#[test]
fn halt_pauses_and_resume_finishes_the_same_move() {
    let mut e = enabled(stepper_mm());
    let id = id_of(ok(&mut e, move_abs(80.0)));
    run(&mut e, 0.3);
    ok(
        &mut e,
        Command::from(Halt {
            axis: 0,
            deceleration: None,
        }),
    );
    run(&mut e, 0.5);
    let s = status(&e);
    assert_eq!(s.cmd_vel, 0.0);
    assert!(s.flags.contains(AxisFlags::HALTED));
    assert!(s.cmd_pos < 80.0);
    assert_eq!(state_of(&mut e, id), CommandState::Running);
    ok(&mut e, Command::from(Resume { axis: 0 }));
    assert!(run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill).is_some());
    assert_eq!(status(&e).cmd_pos, 80.0);
    assert_eq!(state_of(&mut e, id), CommandState::Done);
}

#[test]
fn modify_target_during_motion() {
    // HMC_MoveModify: cases "continue onto the new target" and "stop and reverse".
    let mut e = enabled(stepper_mm());
    let id = id_of(ok(&mut e, move_abs(100.0)));
    run(&mut e, 0.3);
    assert_eq!(
        id_of(ok(
            &mut e,
            Command::from(ModifyTarget {
                axis: 0,
                position: 150.0,
                relative: false
            })
        )),
        id
    );
    assert!(run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill).is_some());
    assert_eq!(status(&e).cmd_pos, 150.0);
    ok(&mut e, move_abs(300.0));
    run(&mut e, 0.5);
    let here = status(&e).cmd_pos;
    ok(
        &mut e,
        Command::from(ModifyTarget {
            axis: 0,
            position: here - 50.0,
            relative: false,
        }),
    );
    let trace = record(&mut e, 5.0);
    assert!(trace.iter().any(|s| s.cmd_vel < 0.0), "reversed");
    assert_eq!(status(&e).cmd_pos, here - 50.0);
    // With an empty FIFO it posts a move (HMC); on a jog it is refused.
    let posted = id_of(ok(
        &mut e,
        Command::from(ModifyTarget {
            axis: 0,
            position: 5.0,
            relative: true,
        }),
    ));
    assert!(run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill).is_some());
    assert_eq!(status(&e).cmd_pos, here - 45.0);
    assert_eq!(state_of(&mut e, posted), CommandState::Done);
    ok(&mut e, jog(1.0));
    assert!(matches!(
        refused(
            &mut e,
            Command::from(ModifyTarget {
                axis: 0,
                position: 1.0,
                relative: false
            })
        ),
        EngineError::Unsupported { .. }
    ));
}

#[test]
fn cancel_next_current_all() {
    let mut e = enabled(stepper_mm());
    let a = id_of(ok(&mut e, move_rel_buffered(10.0)));
    let b = id_of(ok(&mut e, move_rel_buffered(10.0)));
    let c = id_of(ok(&mut e, move_rel_buffered(10.0)));
    ok(
        &mut e,
        Command::from(Cancel {
            axis: 0,
            scope: CancelScope::Next,
        }),
    );
    assert_eq!(state_of(&mut e, b), CommandState::Aborted);
    run(&mut e, 0.05);
    ok(
        &mut e,
        Command::from(Cancel {
            axis: 0,
            scope: CancelScope::Current,
        }),
    );
    assert_eq!(state_of(&mut e, a), CommandState::Aborted);
    assert!(run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill
        && s.fifo_len == 0)
    .is_some());
    assert_eq!(state_of(&mut e, c), CommandState::Done);
    let after_c = status(&e).cmd_pos;
    assert!(
        after_c > 10.0 && after_c < 20.0,
        "a was cut short, c ran: {after_c}"
    );
    let d = id_of(ok(&mut e, move_rel_buffered(10.0)));
    let f = id_of(ok(&mut e, move_rel_buffered(10.0)));
    ok(
        &mut e,
        Command::from(Cancel {
            axis: 0,
            scope: CancelScope::All,
        }),
    );
    assert_eq!(state_of(&mut e, d), CommandState::Aborted);
    assert_eq!(state_of(&mut e, f), CommandState::Aborted);
    assert!(run_until(&mut e, 2.0, |s| s.state == AxisState::Standstill).is_some());
}

#[test]
fn parameters_validate_and_the_hmc_lenient_rule() {
    let mut e = enabled(stepper_mm());
    match refused(
        &mut e,
        Command::from(SetParameter {
            axis: 0,
            name: ParamId::Speed,
            value: -5.0,
            lenient: false,
        }),
    ) {
        EngineError::InvalidParameter {
            name,
            value,
            reason,
        } => {
            assert_eq!(name, "speed");
            assert_eq!(value, -5.0);
            assert!(reason.contains("at least 0"), "{reason}");
        }
        other => panic!("{other}"),
    }
    ok(
        &mut e,
        Command::from(SetParameter {
            axis: 0,
            name: ParamId::Speed,
            value: -500.0,
            lenient: true,
        }),
    );
    assert_eq!(param(&mut e, ParamId::Speed), 500.0);
    assert!(status(&e).latched.contains(AxisFlags::PARAMETER_ERROR));
    assert_eq!(param(&mut e, ParamId::AxisStatusWord) as u32 & 4, 4);
    ok(
        &mut e,
        Command::from(SetParameter {
            axis: 0,
            name: ParamId::Accel,
            value: 0.0,
            lenient: true,
        }),
    );
    assert_eq!(param(&mut e, ParamId::Accel), 200_000.0);
    // Idle-only parameters refuse while commands are queued.
    ok(&mut e, move_abs(10.0));
    assert!(matches!(
        refused(
            &mut e,
            Command::from(SetParameter {
                axis: 0,
                name: ParamId::Units,
                value: 5.0,
                lenient: false
            })
        ),
        EngineError::InvalidState { .. }
    ));
    assert!(matches!(
        refused(
            &mut e,
            Command::from(SetParameter {
                axis: 0,
                name: ParamId::Remain,
                value: 5.0,
                lenient: false
            })
        ),
        EngineError::ReadOnlyParameter { name: "remain" }
    ));
}

#[test]
fn a_live_speed_change_replans_the_running_move() {
    // HMC §2.4: Speed edits take effect immediately.
    let mut fast = enabled(stepper_mm());
    ok(&mut fast, move_abs(200.0));
    let t_fast = run_until(&mut fast, 20.0, |s| s.state == AxisState::Standstill).unwrap();
    let mut slow = enabled(stepper_mm());
    ok(&mut slow, move_abs(200.0));
    run(&mut slow, 0.5);
    set(&mut slow, ParamId::Speed, 20.0);
    let trace = record(&mut slow, 2.0);
    assert!(trace.iter().all(|s| s.cmd_vel <= 100.0 + 1e-9));
    assert!((trace.last().unwrap().cmd_vel - 20.0).abs() < 1e-9);
    let rest = run_until(&mut slow, 20.0, |s| s.state == AxisState::Standstill).unwrap();
    assert!(500 + 2000 + rest > t_fast + 1000);
    assert_eq!(status(&slow).cmd_pos, 200.0);
}

#[test]
fn set_position_frames() {
    let mut e = enabled(stepper_mm());
    ok(&mut e, move_abs(10.0));
    run(&mut e, 1.0);
    let pulses = status(&e).pulses;
    ok(
        &mut e,
        Command::from(SetPosition {
            axis: 0,
            position: 100.0,
            frame: PositionFrame::Both,
        }),
    );
    let s = status(&e);
    assert_eq!((s.cmd_pos, s.act_pos), (100.0, 100.0));
    // The raw counter stays; the user frame's counter (NMC encPos) reads the new position.
    assert_eq!(
        (s.encoder_counts, s.encoder_counts + s.encoder_offset),
        (10_000, 100_000)
    );
    run(&mut e, 0.1);
    assert_eq!(
        status(&e).pulses,
        pulses,
        "redefining never moves the motor"
    );
    ok(
        &mut e,
        Command::from(SetPosition {
            axis: 0,
            position: 0.0,
            frame: PositionFrame::Actual,
        }),
    );
    run(&mut e, 0.001);
    let s = status(&e);
    assert_eq!(s.act_pos, 0.0);
    assert_eq!(s.cmd_pos, 100.0);
    assert_eq!(s.following_error, 100.0);
    assert_eq!(s.encoder_counts + s.encoder_offset, 0);
    ok(
        &mut e,
        Command::from(SetPosition {
            axis: 0,
            position: 0.0,
            frame: PositionFrame::Commanded,
        }),
    );
    run(&mut e, 0.001);
    let s = status(&e);
    assert_eq!(s.following_error, 0.0);
    assert_eq!(
        s.encoder_counts + s.encoder_offset,
        0,
        "the plan's frame only"
    );
}

#[test]
fn command_state_of_unknown_and_finished_ids() {
    let mut e = enabled(stepper_mm());
    assert!(matches!(
        refused(&mut e, Command::from(GetCommandState { id: 0 })),
        EngineError::UnknownCommand { id: 0 }
    ));
    let id = id_of(ok(&mut e, move_abs(1.0)));
    run(&mut e, 1.0);
    assert_eq!(
        ok(&mut e, Command::from(GetCommandState { id })),
        Reply::CommandState {
            id,
            state: CommandState::Done
        }
    );
}

#[test]
fn velocity_override_and_hold() {
    let mut e = enabled(stepper_mm());
    set(&mut e, ParamId::VelScale, 50.0);
    ok(&mut e, jog(40.0));
    run(&mut e, 1.0);
    assert!((status(&e).cmd_vel - 20.0).abs() < 1e-9);
    // 0 % pauses, 100 % resumes.
    set(&mut e, ParamId::VelScale, 0.0);
    run(&mut e, 1.0);
    assert_eq!(status(&e).cmd_vel, 0.0);
    assert_eq!(status(&e).state, AxisState::ContinuousMotion);
    set(&mut e, ParamId::VelScale, 100.0);
    run(&mut e, 1.0);
    assert!((status(&e).cmd_vel - 40.0).abs() < 1e-9);
    // HMC_HoldConfig: DI 3 high → HoldSpeed.
    set(&mut e, ParamId::HoldIn, 3.0);
    set(&mut e, ParamId::HoldSpeed, 5.0);
    ok(
        &mut e,
        Command::from(ForceDigitalInput {
            channel: 3,
            value: Some(true),
        }),
    );
    run(&mut e, 1.0);
    assert!((status(&e).cmd_vel - 5.0).abs() < 1e-9);
    ok(
        &mut e,
        Command::from(ForceDigitalInput {
            channel: 3,
            value: None,
        }),
    );
    run(&mut e, 1.0);
    assert!((status(&e).cmd_vel - 40.0).abs() < 1e-9);
}

#[test]
fn identical_runs_are_bit_identical() {
    let script = |e: &mut axes::Engine| {
        ok(e, move_abs(37.5));
        run(e, 0.2);
        ok(e, jog(-12.0));
        run(e, 0.7);
        set(e, ParamId::Speed, 33.0);
        ok(e, move_rel_buffered(3.0));
        run(e, 2.0);
    };
    let mut cfg = stepper_mm();
    cfg.encoder.noise = 1.5;
    let mut a = enabled(cfg.clone());
    let mut b = enabled(cfg);
    script(&mut a);
    script(&mut b);
    assert_eq!(snapshot(&a), snapshot(&b));
}

#[test]
fn last_error_is_reported_in_status() {
    let mut e = enabled(stepper_mm());
    refused(&mut e, move_abs(f64::NAN));
    assert_eq!(status(&e).last_error, Some(ErrorKind::InvalidArgument));
}

#[test]
fn io_writes_and_forces_show_in_every_snapshot() {
    // Snapshots copy the I/O image only when its version changed; every kind of change must
    // bump it, including a bound input following its axis. Each change alone, checked in two
    // reused snapshot buffers (the runtime alternates two).
    let mut cfg = axes::EngineConfig {
        axes: vec![stepper_mm()],
        ..axes::EngineConfig::default()
    };
    cfg.io.bindings.push(axes::config::InputBinding {
        channel: 9,
        axis: 0,
        signal: axes::config::AxisSignal::LimitPos,
    });
    let mut e = axes::Engine::new(&cfg).unwrap();
    let mut bufs = [e.snapshot(), e.snapshot()];
    type Check = fn(&axes::status::IoImage) -> bool;
    let changes: Vec<(Command, Check)> = vec![
        (
            Command::from(WriteDigitalOutput {
                channel: 3,
                value: true,
            }),
            |io| io.do_[3],
        ),
        (
            Command::from(WriteAnalogOutput {
                channel: 1,
                value: 2.5,
            }),
            |io| io.ao[1] == 2.5,
        ),
        (
            Command::from(ForceDigitalInput {
                channel: 4,
                value: Some(true),
            }),
            |io| io.di[4],
        ),
        (
            Command::from(ForceAnalogInput {
                channel: 2,
                value: Some(-1.0),
            }),
            |io| io.ai[2] == -1.0,
        ),
        (
            Command::from(ForceInput {
                axis: 0,
                input: axes::command::AxisInput::LimitPos,
                value: Some(true),
            }),
            |io| io.di[9],
        ),
    ];
    for (command, visible) in changes {
        ok(&mut e, command.clone());
        e.step();
        e.step();
        for b in bufs.iter_mut() {
            e.snapshot_into(b);
            assert!(visible(&b.io), "{command:?} not in the snapshot");
        }
    }
}

/// Front-ends read parameters from snapshots: the shared copy follows every change, and
/// `parameter_value` on a snapshot gives exactly what `GetParameter` gives, live values included.
#[test]
fn snapshots_carry_the_parameters_and_read_them_as_get_parameter_does() {
    let mut e = enabled(stepper_mm());
    ok(&mut e, move_abs(25.0));
    run(&mut e, 0.05);
    set(&mut e, ParamId::Speed, 42.0);
    let before = snapshot(&e);
    assert_eq!(before.params[0].get(ParamId::Speed), 42.0);
    for id in ParamId::all() {
        let from_snapshot = axes::param::parameter_value(id, &before.axes[0], &before.params[0]);
        assert_eq!(from_snapshot.to_bits(), param(&mut e, id).to_bits(), "{id}");
    }
    // The version stays while parameters do, and moves with a change.
    run(&mut e, 0.01);
    let same = snapshot(&e);
    assert_eq!(same.params_version, before.params_version);
    set(&mut e, ParamId::Accel, 123.0);
    let after = snapshot(&e);
    assert_ne!(after.params_version, before.params_version);
    assert_eq!(after.params[0].get(ParamId::Accel), 123.0);
    assert_eq!(before.params[0].get(ParamId::Accel), 1000.0);
}
