//! Machine-wide commands and atomic batches (issue 11 item 6): several axes started, stopped,
//! enabled, disabled, emergency-stopped and reset between the same two ticks, all or none.
//! Cases from NMC TV27–28 (digest 001), CPU 226H TV-39 (digest 003), HIMC §6.1 TV4–5
//! (digest 004), HMC DriveEnable/ClearAllErr (digest 000 §4.1, §4.9).

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::cia402::State;
use axes::command::ForceDigitalInput;
use axes::command::{
    AxisInput, BufferMode, Command, CommandState, DisableAll, EmergencyStopAll, Enable, EnableAll,
    EngineError, ErrorKind, ForceInput, GetCommandState, MoveAbsolute, MoveRelative, MoveTogether,
    MoveVelocity, Reply, ResetAll, SetEstopInput, SetParameter, StopAll, StopAxes, StopMode,
    TogetherMove,
};
use axes::config::AxisConfig;
use axes::engine::MAX_ATOMIC_COMMANDS;
use axes::{AxisFlags, AxisState, Engine, ParamId};
use common::*;

/// A stepper axis in mm with no switches: travel is free, so NMC's 1000/2000 targets fit.
fn free_axis() -> AxisConfig {
    let mut a = stepper_mm();
    a.switches.limit_pos = None;
    a.switches.limit_neg = None;
    a.switches.home = None;
    a
}

fn machine(n: usize) -> Engine {
    engine_with(vec![free_axis(); n])
}

fn enable(e: &mut Engine, axis: u16) {
    ok(e, Command::from(Enable { axis }));
}

fn abs(axis: u16, position: f64) -> TogetherMove {
    TogetherMove::MoveAbsolute(MoveAbsolute {
        axis,
        position,
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: BufferMode::Aborting,
    })
}

fn rel(axis: u16, distance: f64) -> TogetherMove {
    TogetherMove::MoveRelative(MoveRelative {
        axis,
        distance,
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: BufferMode::Aborting,
    })
}

fn jog_move(axis: u16, velocity: f64) -> MoveVelocity {
    MoveVelocity {
        axis,
        velocity,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: BufferMode::Aborting,
    }
}

fn vel(axis: u16, velocity: f64) -> TogetherMove {
    TogetherMove::MoveVelocity(jog_move(axis, velocity))
}

fn jog_axis(axis: u16, velocity: f64) -> Command {
    Command::from(jog_move(axis, velocity))
}

fn together(moves: Vec<TogetherMove>) -> Command {
    Command::from(MoveTogether { moves })
}

fn st(e: &Engine, axis: usize) -> axes::AxisStatus {
    e.axis_status(axis).expect("axis")
}

/// Step until every axis in `axes` has moved, and return the tick each first had a non-zero
/// commanded velocity.
fn first_moving_ticks(e: &mut Engine, axes: &[usize], max_ticks: u64) -> Vec<Option<u64>> {
    let mut first = vec![None; axes.len()];
    for _ in 0..max_ticks {
        e.step();
        for (slot, &axis) in first.iter_mut().zip(axes) {
            if slot.is_none() && st(e, axis).cmd_vel != 0.0 {
                *slot = Some(e.tick());
            }
        }
        if first.iter().all(Option::is_some) {
            break;
        }
    }
    first
}

/// The engine is exactly as a twin that never saw the refused command: same snapshot now, and
/// the same snapshot after every one of the next `ticks` ticks.
fn assert_same_as_twin(e: &mut Engine, twin: &mut Engine, ticks: u64) {
    assert_eq!(e.snapshot(), twin.snapshot(), "right after the refusal");
    for _ in 0..ticks {
        e.step();
        twin.step();
        assert_eq!(e.snapshot(), twin.snapshot(), "tick {}", e.tick());
    }
}

fn item(err: &EngineError) -> (&'static str, u32, &EngineError) {
    match err {
        EngineError::Item { list, index, error } => (list, *index, error),
        other => panic!("expected an item error, got {other:?}"),
    }
}

// ------------------------------------------------------------------ move_together

#[test]
fn moves_started_together_leave_on_the_same_tick() {
    let mut e = machine(3);
    for a in 0..3 {
        enable(&mut e, a);
    }
    // Axis 2 already jogs: the aborting move replaces its jog in the same tick.
    ok(&mut e, jog_axis(2, 5.0));
    run(&mut e, 0.1);
    let reply = ok(
        &mut e,
        together(vec![abs(0, 100.0), rel(1, -50.0), vel(2, -20.0)]),
    );
    let Reply::AcceptedAll { ids } = reply else {
        panic!("{reply:?}");
    };
    assert_eq!(ids.len(), 3);
    for &id in &ids {
        assert_eq!(state_of(&mut e, id), CommandState::Running);
    }
    let first = first_moving_ticks(&mut e, &[0, 1], 10);
    assert_eq!(
        first,
        vec![Some(e.tick()); 2],
        "first moving ticks {first:?}"
    );
    // Axis 2 reverses from the same tick on: its velocity drops on that very tick.
    let v2 = st(&e, 2).cmd_vel;
    assert!(v2 < 5.0, "axis 2 velocity {v2}");
    assert_eq!(st(&e, 0).state, AxisState::DiscreteMotion);
    assert_eq!(st(&e, 2).state, AxisState::ContinuousMotion);
}

#[test]
fn nmc_tv27_update_multi_starts_both_axes_in_the_same_cycle() {
    // Digest 001 TV27: axes 0 and 1 in PTP with targets 1000 and 2000; MtUpdateMulti(ax0, 0x3).
    let mut e = machine(2);
    enable(&mut e, 0);
    enable(&mut e, 1);
    ok(&mut e, together(vec![abs(0, 1000.0), abs(1, 2000.0)]));
    let first = first_moving_ticks(&mut e, &[0, 1], 10);
    assert_eq!(first, vec![Some(1), Some(1)]);
    run(&mut e, 30.0);
    assert_eq!(st(&e, 0).cmd_pos, 1000.0);
    assert_eq!(st(&e, 1).cmd_pos, 2000.0);
    assert_eq!(st(&e, 0).state, AxisState::Standstill);
}

#[test]
fn nmc_tv28_pack8_moves_the_masked_axes_and_leaves_the_others() {
    // Digest 001 TV28: MovePtpAbsPack8(ax0, {axisMask 0x5, tgtPos[0]=1000, tgtPos[2]=2000}).
    let mut e = machine(3);
    for a in 0..3 {
        enable(&mut e, a);
    }
    ok(&mut e, together(vec![abs(0, 1000.0), abs(2, 2000.0)]));
    let first = first_moving_ticks(&mut e, &[0, 2], 10);
    assert_eq!(first, vec![Some(1), Some(1)]);
    run(&mut e, 30.0);
    assert_eq!(st(&e, 0).cmd_pos, 1000.0);
    assert_eq!(st(&e, 1).cmd_pos, 0.0);
    assert_eq!(st(&e, 1).state, AxisState::Standstill);
    assert_eq!(st(&e, 2).cmd_pos, 2000.0);
}

#[test]
fn cpu226h_two_instructions_on_one_axis_refuse_the_second_and_start_nothing() {
    // Digest 003 TV-39: two instructions commanding the same axis at once: the second is busy.
    // Two PTP instructions on two axes in one scan start together.
    let mut e = machine(2);
    enable(&mut e, 0);
    enable(&mut e, 1);
    let mut twin = machine(2);
    enable(&mut twin, 0);
    enable(&mut twin, 1);
    let err = refused(
        &mut e,
        together(vec![rel(1, 10.0), rel(0, 5.0), rel(1, 20.0)]),
    );
    let (list, index, inner) = item(&err);
    assert_eq!((list, index), ("moves", 2));
    assert!(
        matches!(inner, EngineError::InvalidArgument { name: "axis", .. }),
        "{inner}"
    );
    assert_eq!(
        err.to_string(),
        "moves[2]: axis = 1: appears earlier in the list: one entry per axis"
    );
    assert_same_as_twin(&mut e, &mut twin, 5);
    ok(&mut e, together(vec![rel(1, 10.0), rel(0, 5.0)]));
    let next = e.tick() + 1;
    assert_eq!(first_moving_ticks(&mut e, &[0, 1], 10), vec![Some(next); 2]);
}

#[test]
fn one_refused_move_starts_none_and_leaves_the_machine_as_it_was() {
    // Axis 0 jogs, axis 1 is disabled, axis 2 stands on its positive limit.
    let build = || {
        let mut axes = vec![free_axis(); 3];
        axes[2] = stepper_mm();
        let mut e = engine_with(axes);
        enable(&mut e, 0);
        enable(&mut e, 2);
        ok(&mut e, jog_axis(0, 10.0));
        ok(
            &mut e,
            Command::from(ForceInput {
                axis: 2,
                input: AxisInput::LimitPos,
                value: Some(true),
            }),
        );
        run(&mut e, 0.05);
        e
    };
    let cases: Vec<(Vec<TogetherMove>, u32, ErrorKind)> = vec![
        (vec![abs(0, 50.0), abs(1, 50.0)], 1, ErrorKind::AxisDisabled),
        (vec![abs(0, 50.0), rel(2, 5.0)], 1, ErrorKind::LimitActive),
        (vec![abs(0, f64::NAN)], 0, ErrorKind::InvalidArgument),
        (
            vec![vel(0, 1.0), abs(2, f64::INFINITY)],
            1,
            ErrorKind::InvalidArgument,
        ),
        (vec![rel(0, 1e13)], 0, ErrorKind::InvalidArgument),
        (vec![abs(0, 1.0), abs(7, 1.0)], 1, ErrorKind::InvalidAxis),
    ];
    for (moves, index, kind) in cases {
        let mut e = build();
        let mut twin = build();
        let err = refused(&mut e, together(moves.clone()));
        let (list, at, _) = item(&err);
        assert_eq!(
            (list, at, err.kind()),
            ("moves", index, kind),
            "{moves:?}: {err}"
        );
        // No MOTION_ERROR latched, no last error, axis 0 still jogging, ids not used up.
        assert_same_as_twin(&mut e, &mut twin, 20);
        let id = id_of(ok(&mut e, move_abs(1.0)));
        assert_eq!(id, id_of(ok(&mut twin, move_abs(1.0))));
    }
    let mut e = build();
    let err = refused(&mut e, together(vec![]));
    assert!(
        matches!(err, EngineError::InvalidArgument { name: "moves", .. }),
        "{err}"
    );
    let mut buffered = abs(0, 1.0);
    if let TogetherMove::MoveAbsolute(m) = &mut buffered {
        m.buffer_mode = BufferMode::Buffered;
    }
    let err = refused(&mut e, together(vec![buffered]));
    assert_eq!(err.kind(), ErrorKind::Unsupported, "{err}");
}

// ------------------------------------------------------------------ stops

fn jogging(n: usize, velocity: f64) -> Engine {
    let mut e = machine(n);
    for a in 0..n as u16 {
        enable(&mut e, a);
        ok(&mut e, jog_axis(a, velocity));
    }
    run(&mut e, 0.5);
    e
}

/// Ticks until axis `axis` stands still (commanded velocity 0).
fn ticks_to_rest(e: &mut Engine, axis: usize, max: u64) -> Option<u64> {
    (1..=max).find(|_| {
        e.step();
        st(e, axis).cmd_vel == 0.0
    })
}

#[test]
fn stop_axes_stops_the_named_axes_in_one_tick_and_leaves_the_others() {
    let mut e = jogging(3, 20.0);
    ok(
        &mut e,
        Command::from(StopAxes {
            axes: vec![2, 0],
            mode: StopMode::Abrupt,
            deceleration: None,
        }),
    );
    assert_eq!(st(&e, 0).state, AxisState::Stopping);
    assert_eq!(st(&e, 2).state, AxisState::Stopping);
    assert_eq!(st(&e, 1).state, AxisState::ContinuousMotion);
    // fast_decel 10 000 mm/s² from 20 mm/s: 2 ms, two ticks of 1 ms (decel 1000 would take 20).
    let t0 = ticks_to_rest(&mut e, 0, 100).unwrap();
    assert!(t0 <= 3, "axis 0 took {t0} ticks");
    assert_eq!(st(&e, 2).cmd_vel, 0.0);
    assert_eq!(st(&e, 1).cmd_vel, 20.0);
    // Bad input: nothing stops.
    let mut e = jogging(3, 20.0);
    for (c, kind) in [
        (
            StopAxes {
                axes: vec![],
                mode: StopMode::Smooth,
                deceleration: None,
            },
            ErrorKind::InvalidArgument,
        ),
        (
            StopAxes {
                axes: vec![0, 9],
                mode: StopMode::Smooth,
                deceleration: None,
            },
            ErrorKind::InvalidAxis,
        ),
        (
            StopAxes {
                axes: vec![0, 1, 0],
                mode: StopMode::Smooth,
                deceleration: None,
            },
            ErrorKind::InvalidArgument,
        ),
        (
            StopAxes {
                axes: vec![0],
                mode: StopMode::Smooth,
                deceleration: Some(f64::NAN),
            },
            ErrorKind::InvalidArgument,
        ),
        (
            StopAxes {
                axes: vec![0],
                mode: StopMode::Smooth,
                deceleration: Some(-1.0),
            },
            ErrorKind::InvalidArgument,
        ),
    ] {
        let before = e.snapshot();
        let err = refused(&mut e, Command::from(c.clone()));
        assert_eq!(err.kind(), kind, "{c:?}: {err}");
        assert_eq!(e.snapshot(), before, "{c:?}");
    }
    let err = refused(
        &mut e,
        Command::from(StopAxes {
            axes: vec![0, 9],
            mode: StopMode::Smooth,
            deceleration: None,
        }),
    );
    assert_eq!(
        err.to_string(),
        "axes[1]: axis 9 does not exist (the machine has 3 axes)"
    );
}

#[test]
fn himc_stop_all_uses_the_kill_deceleration_and_keeps_the_axes_enabled() {
    // Digest 004 §6.1 TV4: StopAll → all decelerate with the kill deceleration; afterwards
    // enabled, not moving, queues cleared.
    let mut e = jogging(3, 20.0);
    let queued = id_of(ok(&mut e, move_rel_buffered(5.0)));
    assert_eq!(st(&e, 0).fifo_len, 2);
    ok(&mut e, Command::from(StopAll::default()));
    assert_eq!(state_of(&mut e, queued), CommandState::Aborted);
    for a in 0..3 {
        assert_eq!(st(&e, a).state, AxisState::Stopping, "axis {a}");
        assert_eq!(st(&e, a).fifo_len, 0);
    }
    let ticks = ticks_to_rest(&mut e, 1, 100).unwrap();
    assert!(
        ticks <= 3,
        "{ticks} ticks: the kill deceleration, not decel"
    );
    run(&mut e, 0.01);
    for a in 0..3 {
        let s = st(&e, a);
        assert_eq!(s.state, AxisState::Standstill, "axis {a}");
        assert!(s.flags.contains(AxisFlags::ENABLED));
        assert!(!s.latched.contains(AxisFlags::ESTOP));
        assert_eq!(s.cmd_vel, 0.0);
    }
    // The mode and deceleration can be chosen: smooth with the axis `decel` takes 20 ticks.
    let mut e = jogging(1, 20.0);
    ok(
        &mut e,
        Command::from(StopAll {
            mode: StopMode::Smooth,
            deceleration: None,
        }),
    );
    let ticks = ticks_to_rest(&mut e, 0, 100).unwrap();
    assert!((19..=21).contains(&ticks), "{ticks}");
    let err = refused(
        &mut e,
        Command::from(StopAll {
            mode: StopMode::Smooth,
            deceleration: Some(0.0),
        }),
    );
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
}

// ------------------------------------------------------------------ power

#[test]
fn himc_disable_all_disables_every_axis_and_clears_the_queues() {
    // Digest 004 §6.1 TV5.
    let mut e = jogging(3, 20.0);
    let queued = id_of(ok(&mut e, move_rel_buffered(5.0)));
    ok(&mut e, Command::from(DisableAll {}));
    assert_eq!(state_of(&mut e, queued), CommandState::Aborted);
    for a in 0..3 {
        let s = st(&e, a);
        assert_eq!(s.state, AxisState::Disabled, "axis {a}");
        assert_eq!(s.fifo_len, 0);
        assert!(!s.flags.contains(AxisFlags::ENABLED));
    }
}

#[test]
fn enable_all_enables_every_axis_that_can_move_or_none() {
    let mut axes = vec![free_axis(); 3];
    axes[1].params.insert(ParamId::AxisType, 30.0); // encoder only: skipped
    let build = || engine_with(axes.clone());
    let mut e = build();
    ok(&mut e, Command::from(EnableAll {}));
    assert_eq!(st(&e, 0).state, AxisState::Standstill);
    assert!(!st(&e, 1).flags.contains(AxisFlags::ENABLED));
    assert_eq!(st(&e, 2).state, AxisState::Standstill);
    // A drive alarm on axis 2: refused, and axis 0 stays disabled too.
    let mut e = build();
    let alarm = Command::from(ForceInput {
        axis: 2,
        input: AxisInput::DriveAlarm,
        value: Some(true),
    });
    ok(&mut e, alarm.clone());
    run(&mut e, 0.01);
    let mut twin = build();
    ok(&mut twin, alarm);
    run(&mut twin, 0.01);
    let err = refused(&mut e, Command::from(EnableAll {}));
    let (list, index, inner) = item(&err);
    assert_eq!((list, index), ("axes", 2));
    assert!(
        matches!(inner, EngineError::AxisInError { axis: 2, .. }),
        "{inner}"
    );
    assert_eq!(err.kind(), ErrorKind::AxisInError);
    assert_same_as_twin(&mut e, &mut twin, 5);
    assert_eq!(st(&e, 0).state, AxisState::Disabled);
}

#[test]
fn emergency_stop_all_latches_estop_until_reset_all() {
    let mut e = jogging(2, 20.0);
    ok(&mut e, Command::from(EmergencyStopAll {}));
    e.step();
    for a in 0..2 {
        let s = st(&e, a);
        assert_eq!(s.state, AxisState::ErrorStop, "axis {a}");
        assert!(s.latched.contains(AxisFlags::ESTOP));
        assert!(!s.flags.contains(AxisFlags::ENABLED));
        assert_eq!(s.cmd_vel, 0.0);
    }
    // Held: enabling and moving are refused until the latch is cleared.
    let err = refused(&mut e, Command::from(EnableAll {}));
    assert_eq!(err.kind(), ErrorKind::AxisInError);
    let err = refused(&mut e, Command::from(Enable { axis: 1 }));
    assert_eq!(err.kind(), ErrorKind::AxisInError);
    run(&mut e, 0.01);
    ok(&mut e, Command::from(ResetAll {}));
    ok(&mut e, Command::from(EnableAll {}));
    ok(&mut e, together(vec![rel(0, 1.0), rel(1, 1.0)]));
    assert_eq!(
        first_moving_ticks(&mut e, &[0, 1], 5),
        vec![Some(e.tick()); 2]
    );
}

fn force(e: &mut Engine, channel: u16, value: bool) {
    ok(
        e,
        Command::from(ForceDigitalInput {
            channel,
            value: Some(value),
        }),
    );
}

fn estop_input(channel: Option<u16>, level: bool) -> Command {
    Command::from(SetEstopInput { channel, level })
}

fn estopped(e: &Engine, axis: usize) -> bool {
    let s = st(e, axis);
    s.state == AxisState::ErrorStop && s.latched.contains(AxisFlags::ESTOP)
}

#[test]
fn the_estop_input_stops_every_axis_in_the_tick_that_reads_its_edge() {
    // HIMC BindEMO (digest 004 §1.10, §9.2.6): GPI 8 is DI 7.
    let mut e = jogging(2, 20.0);
    // The twin is e-stopped by command just before the same tick.
    let mut twin = jogging(2, 20.0);
    ok(&mut e, estop_input(Some(7), true));
    force(&mut e, 7, true);
    force(&mut twin, 7, true);
    ok(&mut twin, Command::from(EmergencyStopAll {}));
    e.step();
    twin.step();
    assert_eq!(e.estop_input_trips(), 1);
    for a in 0..2 {
        assert!(estopped(&e, a), "axis {a} in the tick that read the edge");
        assert_eq!(st(&e, a), st(&twin, a), "axis {a}");
    }
    // Held high: no new edge. Falling and rising again fires again.
    run(&mut e, 0.01);
    assert_eq!(e.estop_input_trips(), 1);
    force(&mut e, 7, false);
    e.step();
    force(&mut e, 7, true);
    e.step();
    assert_eq!(e.estop_input_trips(), 2);
}

#[test]
fn an_estop_input_bound_at_its_active_level_waits_for_the_next_edge() {
    let mut e = jogging(1, 20.0);
    force(&mut e, 3, true);
    e.step();
    ok(&mut e, estop_input(Some(3), true));
    run(&mut e, 0.01);
    assert!(!estopped(&e, 0), "already on when bound: no edge");
    // Active low (an inverted input): the input falling is the edge.
    ok(&mut e, estop_input(Some(3), false));
    force(&mut e, 3, false);
    e.step();
    assert!(estopped(&e, 0));
    // Unbound: nothing fires.
    ok(&mut e, Command::from(ResetAll {}));
    enable(&mut e, 0);
    ok(&mut e, estop_input(None, true));
    force(&mut e, 3, true);
    run(&mut e, 0.01);
    force(&mut e, 3, false);
    run(&mut e, 0.01);
    assert!(!estopped(&e, 0));
    assert_eq!(e.estop_input_trips(), 1);
    let err = refused(&mut e, estop_input(Some(64), true));
    assert_eq!(err.kind(), ErrorKind::InvalidChannel, "{err}");
}

#[test]
fn hmc_clear_all_err_clears_what_it_can_and_names_the_axis_whose_cause_remains() {
    let mut e = jogging(3, 20.0);
    ok(&mut e, Command::from(EmergencyStopAll {}));
    ok(
        &mut e,
        Command::from(ForceInput {
            axis: 1,
            input: AxisInput::DriveAlarm,
            value: Some(true),
        }),
    );
    run(&mut e, 0.01);
    let err = refused(&mut e, Command::from(ResetAll {}));
    assert!(
        matches!(err, EngineError::CauseStillPresent { axis: 1, .. }),
        "{err}"
    );
    assert_eq!(st(&e, 0).state, AxisState::Disabled, "axis 0 cleared");
    assert_eq!(st(&e, 2).state, AxisState::Disabled, "axis 2 cleared");
    assert_eq!(st(&e, 1).state, AxisState::ErrorStop);
    ok(
        &mut e,
        Command::from(ForceInput {
            axis: 1,
            input: AxisInput::DriveAlarm,
            value: None,
        }),
    );
    run(&mut e, 0.01);
    ok(&mut e, Command::from(ResetAll {}));
    assert_eq!(st(&e, 1).state, AxisState::Disabled);
}

#[test]
fn power_commands_on_engine_mastered_drives_go_through_the_drive_state_machine() {
    let mut e = engine_with_mastered_drive(vec![free_axis(), free_axis()]);
    ok(&mut e, Command::from(EnableAll {}));
    // Axis 0 is powered at once; axis 1 when its drive reaches Operation enabled.
    assert_eq!(st(&e, 0).state, AxisState::Standstill);
    assert_eq!(st(&e, 1).state, AxisState::Disabled);
    let mut ticks = 0;
    while st(&e, 1).state != AxisState::Standstill && ticks < 100 {
        e.step();
        ticks += 1;
    }
    assert_eq!(e.drive(0).unwrap().state(), State::OperationEnabled);
    ok(&mut e, Command::from(DisableAll {}));
    assert_eq!(st(&e, 0).state, AxisState::Disabled);
    run(&mut e, 0.05);
    assert_eq!(st(&e, 1).state, AxisState::Disabled);
    assert_eq!(e.drive(0).unwrap().state(), State::SwitchOnDisabled);
    // The emergency stop latches on the axis at once; the drive's fault reaction powers it
    // off and leaves it in Fault (0x8000 range error code) until reset_all.
    ok(&mut e, Command::from(EnableAll {}));
    run(&mut e, 0.05);
    assert_eq!(st(&e, 1).state, AxisState::Standstill);
    ok(&mut e, Command::from(EmergencyStopAll {}));
    assert!(st(&e, 1).latched.contains(AxisFlags::ESTOP));
    run(&mut e, 0.05);
    assert_eq!(e.drive(0).unwrap().state(), State::Fault);
    assert_eq!(st(&e, 1).state, AxisState::ErrorStop);
    assert!(!st(&e, 1).flags.contains(AxisFlags::ENABLED));
    ok(&mut e, Command::from(ResetAll {}));
    run(&mut e, 0.05);
    assert_eq!(e.drive(0).unwrap().state(), State::SwitchOnDisabled);
    assert_eq!(st(&e, 1).state, AxisState::Disabled);
    ok(&mut e, Command::from(EnableAll {}));
    run(&mut e, 0.05);
    assert_eq!(e.drive(0).unwrap().state(), State::OperationEnabled);
}

// ------------------------------------------------------------------ atomic batches

#[test]
fn a_batch_applies_in_order_between_two_ticks() {
    let mut e = machine(2);
    let replies = e
        .apply_batch(vec![
            Command::from(Enable { axis: 0 }),
            Command::from(Enable { axis: 1 }),
            Command::from(SetParameter {
                axis: 1,
                name: ParamId::Speed,
                value: 50.0,
                lenient: false,
            }),
            together(vec![rel(0, 10.0), rel(1, 10.0)]),
            Command::from(GetCommandState { id: 2 }),
        ])
        .unwrap();
    assert_eq!(replies.len(), 5);
    assert_eq!(replies[0], Reply::Done);
    assert_eq!(replies[3], Reply::AcceptedAll { ids: vec![1, 2] });
    assert_eq!(
        replies[4],
        Reply::CommandState {
            id: 2,
            state: CommandState::Running
        }
    );
    assert_eq!(first_moving_ticks(&mut e, &[0, 1], 5), vec![Some(1); 2]);
}

#[test]
fn a_refused_batch_applies_nothing_and_names_the_command() {
    let build = || {
        let mut e = machine(2);
        enable(&mut e, 0);
        ok(&mut e, move_abs(100.0));
        run(&mut e, 0.05);
        e
    };
    let bad_batches: Vec<(Vec<Command>, u32, ErrorKind)> = vec![
        // Axis 1 is still disabled when its move comes: everything before it is undone,
        // the speed change, the output and the stop of axis 0 included.
        (
            vec![
                Command::from(SetParameter {
                    axis: 0,
                    name: ParamId::Speed,
                    value: 5.0,
                    lenient: false,
                }),
                Command::from(axes::command::WriteDigitalOutput {
                    channel: 0,
                    value: true,
                }),
                Command::from(StopAll::default()),
                together(vec![rel(1, 10.0)]),
            ],
            3,
            ErrorKind::AxisDisabled,
        ),
        (
            vec![Command::from(Enable { axis: 1 }), move_abs(f64::NAN)],
            1,
            ErrorKind::InvalidArgument,
        ),
        (
            vec![
                Command::from(DisableAll {}),
                Command::from(Enable { axis: 5 }),
            ],
            1,
            ErrorKind::InvalidAxis,
        ),
    ];
    for (batch, index, kind) in bad_batches {
        let mut e = build();
        let mut twin = build();
        let err = e.apply_batch(batch).unwrap_err();
        let (list, at, _) = item(&err);
        assert_eq!((list, at, err.kind()), ("commands", index, kind), "{err}");
        assert_same_as_twin(&mut e, &mut twin, 50);
    }
    let mut e = build();
    let before = e.snapshot();
    for batch in [
        vec![],
        vec![Command::from(DisableAll {}); MAX_ATOMIC_COMMANDS + 1],
    ] {
        let err = e.apply_batch(batch).unwrap_err();
        let is_commands = matches!(
            err,
            EngineError::InvalidArgument {
                name: "commands",
                ..
            }
        );
        assert!(is_commands, "{err}");
    }
    assert_eq!(e.snapshot(), before);
}
