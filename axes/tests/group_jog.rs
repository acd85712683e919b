//! Group jogs (HIMC JogGroup and JogGroupAxis, digest 004 §8.2.7–8.2.8; TV 54): the ramp up
//! to the jog velocity with the group's acceleration, a velocity change while jogging, the
//! stop and halt with deceleration, a soft limit that stops the group, jogs in a rotated
//! frame, and the refusals.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, CommandState, CoordinateSystem, ErrorKind, GroupDisable, GroupHalt, GroupJog,
    GroupJogAxis, GroupParameter, GroupSetCoordinateSystem, GroupSetCoordinateTransform,
    GroupSetOverride, GroupStop,
};
use axes::status::{GroupFault, GroupState, GroupStatus};
use axes::{AxisState, Engine, EngineError, ParamId};
use common::{engine_with, id_of, ok, refused, state_of, stepper_mm};

/// The group's jog limits in these tests (below the members' 1000 mm/s²): a trapezoid.
const ACC: f64 = 500.0;
const DEC: f64 = 250.0;

/// Group 1 of `n` stepper axes (100 mm/s, 1000 mm/s² each), enabled, with acceleration
/// [`ACC`], deceleration [`DEC`] and no jerk limit along the path.
fn machine(n: u16) -> Engine {
    let members: Vec<u16> = (0..n).collect();
    let mut e = common::with_group(
        engine_with((0..n).map(|_| stepper_mm()).collect()),
        &members,
    );
    for (name, value) in [
        (GroupParameter::Acceleration, ACC),
        (GroupParameter::Deceleration, DEC),
        (GroupParameter::Jerk, 0.0),
    ] {
        common::group_parameter(&mut e, name, value);
    }
    e
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

fn jog_axis(member: usize, velocity: f64) -> Command {
    Command::from(GroupJogAxis {
        group: 1,
        member,
        velocity,
    })
}

fn jog(coordinate: usize, velocity: f64, system: Option<&str>) -> Command {
    Command::from(GroupJog {
        group: 1,
        coordinate,
        velocity,
        coordinate_system: system.map(|s| s.parse::<CoordinateSystem>().unwrap()),
    })
}

fn steps(e: &mut Engine, seconds: f64) {
    for _ in 0..(seconds / e.period()).round() as u64 {
        e.step();
    }
}

/// Step until the group is in Standby (at most `max_s`).
fn run_to_standby(e: &mut Engine, max_s: f64) {
    for _ in 0..(max_s / e.period()).round() as u64 {
        e.step();
        if group(e).state == GroupState::Standby {
            return;
        }
    }
    panic!("still {:?} after {max_s} s", group(e));
}

#[test]
fn a_jog_ramps_up_with_the_group_acceleration_and_holds_its_velocity() {
    let mut e = machine(3);
    let id = id_of(ok(&mut e, jog_axis(1, 20.0)));
    assert_eq!(group(&e).state, GroupState::Moving);
    let mut last = 0.0;
    let period = e.period();
    for _ in 0..(1.0 / period).round() as u64 {
        e.step();
        let v = e.axis_status(1).unwrap().cmd_vel;
        // Never faster than the jog velocity, never more than the group's acceleration.
        assert!(v <= 20.0 + 1e-9, "{v}");
        assert!(v - last <= ACC * period + 1e-9, "{last} → {v}");
        last = v;
    }
    // Ramp 20/500 = 0.04 s: after 1 s, 20·1 − 20²/(2·500) = 19.6 mm.
    let p = e.axis_status(1).unwrap().cmd_pos;
    assert!((p - 19.6).abs() < 1e-6, "{p}");
    assert!((last - 20.0).abs() < 1e-9);
    for other in [0, 2] {
        assert_eq!(e.axis_status(other).unwrap().cmd_pos, 0.0);
    }
    let g = group(&e);
    assert_eq!(g.state, GroupState::Moving);
    assert_eq!(g.current_command, Some(id));
    assert!((g.path_velocity - 20.0).abs() < 1e-9);
    assert_eq!(state_of(&mut e, id), CommandState::Running);
    assert_eq!(
        e.axis_status(1).unwrap().state,
        AxisState::SynchronizedMotion
    );
}

/// Jog `member` at `velocity` for 0.5 s, send `stop`, run to Standby: the distance travelled
/// after the stop, and the jog's id.
fn travel_after(e: &mut Engine, member: usize, velocity: f64, stop: Command) -> (f64, u32) {
    let id = id_of(ok(e, jog_axis(member, velocity)));
    steps(e, 0.5);
    let at_stop = e.axis_status(member).unwrap().cmd_pos;
    ok(e, stop);
    assert_eq!(group(e).state, GroupState::Stopping);
    run_to_standby(e, 1.0);
    (e.axis_status(member).unwrap().cmd_pos - at_stop, id)
}

fn stop(deceleration: Option<f64>) -> Command {
    Command::from(GroupStop {
        group: 1,
        deceleration,
    })
}

#[test]
fn group_stop_ends_a_jog_with_the_deceleration() {
    let mut e = machine(2);
    let (travel, id) = travel_after(&mut e, 0, 20.0, stop(None));
    // 20 mm/s to rest at 250 mm/s²: 20² / (2·250) = 0.8 mm.
    assert!((travel - 0.8).abs() < 1e-6, "{travel}");
    assert_eq!(state_of(&mut e, id), CommandState::Aborted);
    steps(&mut e, 0.01);
    assert_eq!(e.axis_status(0).unwrap().state, AxisState::Standstill);
    assert_eq!(group(&e).current_command, None);
}

#[test]
fn group_stop_with_a_deceleration_and_a_halt_end_a_jog() {
    let mut e = machine(2);
    // 20² / (2·100) = 2 mm.
    let (travel, _) = travel_after(&mut e, 0, 20.0, stop(Some(100.0)));
    assert!((travel - 2.0).abs() < 1e-6, "{travel}");
    // A stop faster than the member allows is cut to its own 1000 mm/s²: 20² / 2000 = 0.2 mm.
    let (travel, _) = travel_after(&mut e, 0, 20.0, stop(Some(1e6)));
    assert!((travel - 0.2).abs() < 1e-6, "{travel}");
    // A halt has no path to keep: it stops the jog (the group's deceleration).
    let halt = Command::from(GroupHalt {
        group: 1,
        deceleration: None,
    });
    let (travel, id) = travel_after(&mut e, 1, -20.0, halt);
    assert!((travel + 0.8).abs() < 1e-6, "{travel}");
    assert_eq!(state_of(&mut e, id), CommandState::Aborted);
}

#[test]
fn a_new_jog_changes_the_velocity_by_a_ramp_and_velocity_zero_stops() {
    let mut e = machine(2);
    let first = id_of(ok(&mut e, jog_axis(0, 20.0)));
    steps(&mut e, 0.2);
    let second = id_of(ok(&mut e, jog_axis(0, -10.0)));
    assert_eq!(state_of(&mut e, first), CommandState::Aborted);
    assert_eq!(state_of(&mut e, second), CommandState::Running);
    // +20 → 0 at the deceleration (0.08 s), 0 → −10 at the acceleration (0.02 s).
    let period = e.period();
    let mut last = e.axis_status(0).unwrap().cmd_vel;
    assert!((last - 20.0).abs() < 1e-9);
    for _ in 0..(0.2 / period).round() as u64 {
        e.step();
        let v = e.axis_status(0).unwrap().cmd_vel;
        assert!(v <= last + 1e-9, "the velocity only falls: {last} → {v}");
        let limit = if v >= 0.0 { DEC } else { ACC };
        assert!(last - v <= limit * period + 1e-9, "{last} → {v}");
        last = v;
    }
    assert!((last + 10.0).abs() < 1e-9, "{last}");
    assert!((group(&e).path_velocity + 10.0).abs() < 1e-9);

    // The override scales a jog too.
    ok(
        &mut e,
        Command::from(GroupSetOverride {
            group: 1,
            factor: 0.5,
        }),
    );
    steps(&mut e, 0.1);
    assert!((e.axis_status(0).unwrap().cmd_vel + 5.0).abs() < 1e-9);

    // Velocity 0: a ramp to rest, then the command is done and the group in Standby.
    let zero = id_of(ok(&mut e, jog_axis(0, 0.0)));
    assert_eq!(state_of(&mut e, second), CommandState::Aborted);
    assert_eq!(group(&e).state, GroupState::Moving);
    run_to_standby(&mut e, 1.0);
    assert_eq!(state_of(&mut e, zero), CommandState::Done);
    // From rest, velocity 0 is done at once.
    let idle = id_of(ok(&mut e, jog_axis(1, 0.0)));
    assert_eq!(state_of(&mut e, idle), CommandState::Done);
    assert_eq!(group(&e).state, GroupState::Standby);
}

#[test]
fn a_jog_is_held_to_the_members_own_velocity() {
    let mut e = machine(2);
    ok(&mut e, jog_axis(1, 1000.0));
    steps(&mut e, 1.0);
    // The member's speed is 100 mm/s.
    assert!((e.axis_status(1).unwrap().cmd_vel - 100.0).abs() < 1e-9);
}

#[test]
fn a_soft_limit_stops_the_jogging_group_in_error_stop() {
    let mut cfg = stepper_mm();
    cfg.params.insert(ParamId::FsLimit, 5.0);
    let mut e = common::with_group(engine_with(vec![cfg, stepper_mm()]), &[0, 1]);
    let id = id_of(ok(&mut e, jog_axis(0, 20.0)));
    steps(&mut e, 1.0);
    let g = group(&e);
    assert_eq!(g.state, GroupState::ErrorStop);
    assert_eq!(
        g.fault,
        Some(GroupFault::Member {
            axis: 0,
            error: ErrorKind::LimitReached
        })
    );
    assert!(matches!(state_of(&mut e, id), CommandState::Error(_)));
    let p = e.axis_status(0).unwrap().cmd_pos;
    // The axis stops at its soft limit as it would on its own (one tick's travel past it at
    // most, then its own ramp).
    assert!(p > 4.9 && p < 5.5, "{p}");
    // The group takes no jog until it is reset.
    assert!(matches!(
        refused(&mut e, jog_axis(0, -5.0)),
        EngineError::GroupState {
            state: GroupState::ErrorStop,
            ..
        }
    ));
}

#[test]
fn a_jog_in_a_rotated_wcs_moves_the_machine_along_that_direction() {
    let mut e = machine(3);
    // WCS1 turned 90° about Z: its X is the machine's Y.
    ok(
        &mut e,
        Command::from(GroupSetCoordinateTransform {
            group: 1,
            frame: "wcs1".parse().unwrap(),
            pose: [10.0, 0.0, 0.0, 0.0, 0.0, 90.0],
        }),
    );
    ok(
        &mut e,
        Command::from(GroupSetCoordinateSystem {
            group: 1,
            coordinate_system: "wcs1".parse().unwrap(),
        }),
    );
    ok(&mut e, jog(0, 10.0, None));
    steps(&mut e, 0.5);
    let (x, y) = (
        e.axis_status(0).unwrap().cmd_pos,
        e.axis_status(1).unwrap().cmd_pos,
    );
    assert!(x.abs() < 1e-9, "{x}");
    // 10·0.5 − 10²/(2·500) = 4.9 mm.
    assert!((y - 4.9).abs() < 1e-6, "{y}");
    ok(&mut e, stop(None));
    run_to_standby(&mut e, 1.0);
    // The same coordinate in the MCS (HIMC JogGroup's system) moves machine X.
    ok(&mut e, jog(0, -10.0, Some("mcs")));
    steps(&mut e, 0.5);
    assert!((e.axis_status(0).unwrap().cmd_pos + 4.9).abs() < 1e-6);
}

#[test]
fn bad_jogs_are_refused_with_the_reason() {
    let mut e = machine(6);
    // Digest 004 TV 54: JogGroup(0, 6, 10) → error (carte_dir 0~5 on a six-axis group).
    assert!(matches!(
        refused(&mut e, jog(6, 10.0, None)),
        EngineError::InvalidArgument {
            name: "coordinate",
            ..
        }
    ));
    assert!(matches!(
        refused(&mut e, jog_axis(9, 10.0)),
        EngineError::InvalidArgument { name: "member", .. }
    ));
    for v in [f64::NAN, f64::INFINITY] {
        assert!(matches!(
            refused(&mut e, jog_axis(0, v)),
            EngineError::InvalidArgument {
                name: "velocity",
                ..
            }
        ));
    }
    assert!(matches!(
        refused(
            &mut e,
            Command::from(GroupJogAxis {
                group: 7,
                member: 0,
                velocity: 1.0
            })
        ),
        EngineError::UnknownGroup { group: 7 }
    ));
    assert_eq!(group(&e).state, GroupState::Standby);

    // While a path runs a jog is refused; while a jog runs a path is refused.
    ok(
        &mut e,
        Command::from(common::group_line(1, &[10.0, 0.0, 0.0, 0.0, 0.0, 0.0])),
    );
    assert!(matches!(
        refused(&mut e, jog_axis(0, 10.0)),
        EngineError::GroupState {
            state: GroupState::Moving,
            ..
        }
    ));
    run_to_standby(&mut e, 2.0);
    ok(&mut e, jog_axis(0, 10.0));
    assert!(matches!(
        refused(&mut e, Command::from(common::group_line(1, &[0.0; 6]))),
        EngineError::GroupState { .. }
    ));
    // Another coordinate while a jog runs: refused, the jog goes on.
    assert!(matches!(
        refused(&mut e, jog_axis(1, 10.0)),
        EngineError::GroupState { .. }
    ));
    steps(&mut e, 0.1);
    assert!((e.axis_status(0).unwrap().cmd_vel - 10.0).abs() < 1e-9);

    // A disabled group takes no jog.
    ok(&mut e, Command::from(GroupDisable { group: 1 }));
    assert!(matches!(
        refused(&mut e, jog_axis(0, 10.0)),
        EngineError::GroupState {
            state: GroupState::Disabled,
            ..
        }
    ));
}
