//! A group's buffered I/O and stops (NMC CrdBufDoBitPulseEnable, CrdBufOut, CrdAdvBufIoOnAfterLen
//! / OffBeforeLen, CrdBufSetEstopDI, CrdBufStopMtn; digest 001 §2.7): an output at a path
//! distance switches at the tick the path crosses it, pulse trains and analog writes start where
//! the path reaches them, a watched input e-stops the group only once armed, a buffered halt
//! halts where the path reaches it and `group_continue` goes on.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, CommandState, ForceDigitalInput, GroupBufferedHalt, GroupContinue, GroupPulseOutput,
    GroupReset, GroupSetAnalogOutput, GroupStopInput, MoveLinearAbsolute,
};
use axes::status::{GroupFault, GroupState};
use axes::{Engine, EngineConfig, EngineError};
use common::{id_of, ok, refused, state_of, stepper_mm};

fn machine() -> Engine {
    let e = Engine::new(&EngineConfig {
        axes: (0..2).map(|_| stepper_mm()).collect(),
        ..EngineConfig::default()
    })
    .unwrap();
    common::with_group(e, &[0, 1])
}

fn line(position: &[f64]) -> MoveLinearAbsolute {
    common::group_line(1, position)
}

fn send(e: &mut Engine, c: impl Into<Command>) -> u32 {
    id_of(ok(e, c.into()))
}

fn output(channel: u16, level: bool) -> GroupPulseOutput {
    GroupPulseOutput {
        group: 1,
        channel,
        level: Some(level),
        level_time: 0.0,
        other_time: 0.0,
        toggles: 0,
        after_length: None,
        before_end: None,
    }
}

fn position(e: &Engine) -> Vec<f64> {
    e.snapshot().groups[0].position().to_vec()
}

/// Step until `done(engine)` (at most 20 s of ticks); the positions of the tick before and the
/// tick of it.
fn step_until(e: &mut Engine, done: impl Fn(&Engine) -> bool) -> (Vec<f64>, Vec<f64>) {
    let mut before = position(e);
    for _ in 0..20_000 {
        e.step();
        if done(e) {
            return (before, position(e));
        }
        before = position(e);
    }
    panic!("never happened");
}

#[test]
fn an_output_after_a_length_switches_at_the_tick_the_path_crosses_it() {
    let mut e = machine();
    let id = send(
        &mut e,
        GroupPulseOutput {
            after_length: Some(30.0),
            ..output(4, true)
        },
    );
    send(&mut e, line(&[100.0, 0.0]));
    let (before, at) = step_until(&mut e, |e| e.snapshot().io.do_[4]);
    assert!(before[0] < 30.0 && at[0] >= 30.0, "{before:?} {at:?}");
    assert_eq!(state_of(&mut e, id), CommandState::Done);
}

#[test]
fn an_output_before_the_end_switches_that_far_before_the_end_of_the_queued_motion() {
    let mut e = machine();
    ok(&mut e, output(6, true).into());
    let id = send(
        &mut e,
        GroupPulseOutput {
            before_end: Some(20.0),
            ..output(6, false)
        },
    );
    // Two segments: the point is on the second, 20 before the end of both.
    send(&mut e, line(&[50.0, 0.0]));
    send(&mut e, line(&[50.0, 50.0]));
    // The marker's "on" acts at once; the "off" waits for its distance.
    e.step();
    assert!(e.snapshot().io.do_[6]);
    assert!(!matches!(state_of(&mut e, id), CommandState::Done));
    let (before, at) = step_until(&mut e, |e| !e.snapshot().io.do_[6]);
    assert!(before[1] < 30.0 && at[1] >= 30.0, "{before:?} {at:?}");
    step_until(&mut e, |e| {
        e.snapshot().groups[0].state == GroupState::Standby
    });
    // Longer than what is queued behind it: at once.
    let late = send(
        &mut e,
        GroupPulseOutput {
            before_end: Some(1000.0),
            ..output(7, true)
        },
    );
    send(&mut e, line(&[0.0, 50.0]));
    e.step();
    assert!(e.snapshot().io.do_[7]);
    assert_eq!(state_of(&mut e, late), CommandState::Done);
}

#[test]
fn a_waiting_output_is_dropped_by_a_stop_of_the_group() {
    let mut e = machine();
    let id = send(
        &mut e,
        GroupPulseOutput {
            after_length: Some(90.0),
            ..output(4, true)
        },
    );
    send(&mut e, line(&[100.0, 0.0]));
    for _ in 0..50 {
        e.step();
    }
    ok(
        &mut e,
        axes::command::GroupStop {
            group: 1,
            deceleration: None,
        }
        .into(),
    );
    for _ in 0..2000 {
        e.step();
    }
    assert!(!e.snapshot().io.do_[4]);
    assert_eq!(state_of(&mut e, id), CommandState::Aborted);
}

#[test]
fn a_pulse_train_starts_where_the_path_reaches_it_and_ends_at_its_first_level() {
    let mut e = machine();
    send(&mut e, line(&[10.0, 0.0]));
    send(
        &mut e,
        GroupPulseOutput {
            level_time: 0.005,
            other_time: 0.003,
            toggles: 6,
            ..output(9, true)
        },
    );
    send(&mut e, line(&[10.0, 10.0]));
    let (before, at) = step_until(&mut e, |e| e.snapshot().io.do_[9]);
    // The tick the path passes the corner (it may already be a little into the next line).
    assert!(
        before[0] < 10.0 && at[0] == 10.0 && at[1] < 1e-3,
        "{before:?} {at:?}"
    );
    let mut levels = vec![true];
    for _ in 0..40 {
        e.step();
        levels.push(e.snapshot().io.do_[9]);
    }
    let rising = levels.windows(2).filter(|w| !w[0] && w[1]).count();
    let high = levels.iter().filter(|l| **l).count();
    // 5 ticks high, 3 low, three times (6 toggles), then it stays at the level it started with.
    assert_eq!(rising, 3);
    assert_eq!(high, 15 + (41 - 24));
    assert!(levels[40]);
}

#[test]
fn an_analog_output_is_written_where_the_path_reaches_it() {
    let mut e = machine();
    send(&mut e, line(&[10.0, 0.0]));
    send(
        &mut e,
        GroupSetAnalogOutput {
            group: 1,
            channel: 2,
            value: 3.5,
        },
    );
    send(&mut e, line(&[10.0, 10.0]));
    let (before, at) = step_until(&mut e, |e| e.snapshot().io.ao[2] == 3.5);
    assert!(
        before[0] < 10.0 && at[0] == 10.0 && at[1] < 1e-3,
        "{before:?} {at:?}"
    );
}

#[test]
fn a_stop_input_e_stops_the_group_only_once_the_path_has_armed_it() {
    let mut e = machine();
    send(&mut e, line(&[20.0, 0.0]));
    send(
        &mut e,
        GroupStopInput {
            group: 1,
            slot: 0,
            channel: Some(3),
            level: true,
        },
    );
    send(&mut e, line(&[20.0, 20.0]));
    for _ in 0..20 {
        e.step();
    }
    ok(
        &mut e,
        ForceDigitalInput {
            channel: 3,
            value: Some(true),
        }
        .into(),
    );
    // Not armed yet: the path goes on to the marker, where the group e-stops.
    let (before, _) = step_until(&mut e, |e| {
        e.snapshot().groups[0].state == GroupState::ErrorStop
    });
    // Armed as the path passes the corner, it stops the group the next tick.
    assert!(before[0] == 20.0 && before[1] < 1e-3, "{before:?}");
    assert_eq!(
        e.snapshot().groups[0].fault,
        Some(GroupFault::EmergencyStop)
    );
    assert_eq!(e.groups().get(1).unwrap().stop_inputs().count(), 1);
    // Released and reset: the watch is gone with the program.
    ok(
        &mut e,
        ForceDigitalInput {
            channel: 3,
            value: None,
        }
        .into(),
    );
    for _ in 0..2000 {
        e.step();
    }
    for axis in 0..2 {
        ok(&mut e, axes::command::Reset { axis }.into());
    }
    ok(&mut e, GroupReset { group: 1 }.into());
    assert_eq!(e.groups().get(1).unwrap().stop_inputs().count(), 0);
}

#[test]
fn a_buffered_halt_halts_the_path_where_it_reaches_it_and_continue_goes_on() {
    let mut e = machine();
    send(&mut e, line(&[20.0, 0.0]));
    let halt = send(
        &mut e,
        GroupBufferedHalt {
            group: 1,
            target: 1,
            deceleration: None,
        },
    );
    send(&mut e, line(&[20.0, 20.0]));
    let (before, _) = step_until(&mut e, |e| {
        e.snapshot().groups[0].state == GroupState::Halted
    });
    assert!(before[0] >= 20.0 - 1e-9, "{before:?}");
    assert_eq!(state_of(&mut e, halt), CommandState::Done);
    for _ in 0..3000 {
        e.step();
    }
    let rest = position(&e);
    assert!(rest[1] < 20.0, "halted on the path: {rest:?}");
    ok(&mut e, GroupContinue { group: 1 }.into());
    step_until(&mut e, |e| {
        e.snapshot().groups[0].state == GroupState::Standby
    });
    assert_eq!(position(&e), [20.0, 20.0]);
}

#[test]
fn bad_buffered_io_commands_are_refused() {
    let mut e = machine();
    let bad_channel = refused(&mut e, output(64, true).into());
    assert!(matches!(bad_channel, EngineError::InvalidChannel { .. }));
    let both = GroupPulseOutput {
        after_length: Some(1.0),
        before_end: Some(1.0),
        ..output(1, true)
    };
    assert!(matches!(
        refused(&mut e, both.into()),
        EngineError::InvalidArgument { .. }
    ));
    let negative = GroupPulseOutput {
        after_length: Some(-1.0),
        ..output(1, true)
    };
    assert!(matches!(
        refused(&mut e, negative.into()),
        EngineError::InvalidArgument { .. }
    ));
    let no_level = GroupPulseOutput {
        level: None,
        toggles: 2,
        level_time: 0.01,
        other_time: 0.01,
        ..output(1, true)
    };
    assert!(matches!(
        refused(&mut e, no_level.into()),
        EngineError::InvalidArgument { .. }
    ));
    let nan = GroupSetAnalogOutput {
        group: 1,
        channel: 0,
        value: f64::NAN,
    };
    assert!(matches!(
        refused(&mut e, nan.into()),
        EngineError::InvalidArgument { .. }
    ));
    let slot = GroupStopInput {
        group: 1,
        slot: 64,
        channel: Some(0),
        level: true,
    };
    assert!(matches!(
        refused(&mut e, slot.into()),
        EngineError::InvalidArgument { .. }
    ));
    let other = GroupBufferedHalt {
        group: 1,
        target: 9,
        deceleration: None,
    };
    assert!(matches!(
        refused(&mut e, other.into()),
        EngineError::UnknownGroup { group: 9 }
    ));
}

#[test]
fn an_output_before_the_end_waits_for_motion_pushed_after_its_marker_was_reached() {
    let mut e = machine();
    ok(&mut e, output(6, true).into());
    let id = send(
        &mut e,
        GroupPulseOutput {
            before_end: Some(20.0),
            ..output(6, false)
        },
    );
    // Reached at rest with nothing behind it: it waits.
    for _ in 0..10 {
        e.step();
    }
    assert!(e.snapshot().io.do_[6]);
    assert!(!matches!(state_of(&mut e, id), CommandState::Done));
    send(&mut e, line(&[50.0, 0.0]));
    send(&mut e, line(&[50.0, 50.0]));
    let (before, at) = step_until(&mut e, |e| !e.snapshot().io.do_[6]);
    assert!(before[1] < 30.0 && at[1] >= 30.0, "{before:?} {at:?}");
}

#[test]
fn a_watch_armed_and_ended_at_the_same_place_stops_nothing() {
    let mut e = machine();
    ok(
        &mut e,
        ForceDigitalInput {
            channel: 4,
            value: Some(true),
        }
        .into(),
    );
    send(&mut e, line(&[20.0, 0.0]));
    for (id, channel) in [(0, Some(4)), (1, None)] {
        let _ = id;
        send(
            &mut e,
            GroupStopInput {
                group: 1,
                slot: 33,
                channel,
                level: true,
            },
        );
    }
    send(&mut e, line(&[20.0, 20.0]));
    step_until(&mut e, |e| {
        e.snapshot().groups[0].state != GroupState::Moving
    });
    assert_eq!(e.snapshot().groups[0].state, GroupState::Standby);
    assert_eq!(position(&e), [20.0, 20.0]);
}
