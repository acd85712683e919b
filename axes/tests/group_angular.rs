//! HIMC's angular TCP profile (SetGrpAngMotionProfile, digest 004 §8.3.7; TV 49): a group's
//! orientation coordinates (A, B, C) change under the angular profile while X, Y, Z keep the
//! linear one, the move lasting as long as the slower of the two (closed forms below); a move
//! that only turns runs on the angular profile; the defaults [360, 1800, 1800, 50 ms]; and the
//! refusals.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, CoordinateSet, Enable, ErrorKind, GroupCreate, GroupEnable, GroupParameter,
    GroupSetParameter,
};
use axes::config::AxisConfig;
use axes::status::{GroupState, GroupStatus};
use axes::{Engine, EngineConfig, EngineError};
use common::{ok, refused};

/// A fast mm (or degree) axis: its own limits never bind here.
fn fast_axis() -> AxisConfig {
    common::fast_mm_axis(1e5, 1e7)
}

/// Six enabled axes, group 1 of them all with orientation coordinates 3, 4, 5 (HIMC's A, B,
/// C), enabled; the linear and angular profiles are trapezoids unless `s_curve`.
fn machine(s_curve: bool) -> Engine {
    let mut e = Engine::new(&EngineConfig {
        axes: vec![fast_axis(); 6],
        ..EngineConfig::default()
    })
    .unwrap();
    for axis in 0..6 {
        ok(&mut e, Command::from(Enable { axis }));
    }
    ok(
        &mut e,
        Command::from(GroupCreate {
            group: 1,
            axes: vec![0, 1, 2, 3, 4, 5],
            queue_capacity: None,
            lookahead: None,
            result_axis: None,
            orientation: CoordinateSet::from_indices(&[3, 4, 5]).unwrap(),
        }),
    );
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    if !s_curve {
        set(&mut e, GroupParameter::Jerk, 0.0);
        set(&mut e, GroupParameter::AngularJerk, 0.0);
    }
    e
}

fn set(e: &mut Engine, name: GroupParameter, value: f64) {
    common::group_parameter(e, name, value);
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

/// What a path did: its duration (ticks with the path moving × period) and each member's
/// largest |velocity| and |acceleration|.
struct Run {
    seconds: f64,
    velocity: [f64; 6],
    acceleration: [f64; 6],
}

/// Run a line to `position` to its end.
fn run_line(e: &mut Engine, position: &[f64]) -> Run {
    ok(e, Command::from(common::group_line(1, position)));
    let mut run = Run {
        seconds: 0.0,
        velocity: [0.0; 6],
        acceleration: [0.0; 6],
    };
    let period = e.period();
    for _ in 0..(20.0 / period) as u64 {
        e.step();
        let g = group(e);
        if g.state == GroupState::Standby {
            return run;
        }
        if g.path_velocity > 0.0 {
            run.seconds += period;
        }
        for k in 0..6 {
            let s = e.axis_status(k).unwrap();
            run.velocity[k] = run.velocity[k].max(s.cmd_vel.abs());
            run.acceleration[k] = run.acceleration[k].max(s.cmd_acc.abs());
        }
    }
    panic!("the line is not done: {:?}", group(e));
}

/// A trapezoid's duration over `d` with cruise `v`, acceleration and deceleration `a` (the
/// cruise reached).
fn trapezoid(d: f64, v: f64, a: f64) -> f64 {
    d / v + v / a
}

#[test]
fn an_orientation_only_move_runs_on_the_angular_profile_tv49_defaults() {
    // HIMC TV 49 (digest 004 §8.3.7): the defaults are [360 deg/s, 1800, 1800, 50 ms].
    let mut e = machine(true);
    let mut fastest: f64 = 0.0;
    let mut hardest: f64 = 0.0;
    ok(
        &mut e,
        Command::from(common::group_line(1, &[0.0, 0.0, 0.0, 720.0, 0.0, 0.0])),
    );
    common::run_path(&mut e, 10.0, |_, g| {
        fastest = fastest.max(g.path_velocity);
        hardest = hardest.max(g.path_acceleration.abs());
    });
    assert!((fastest - 360.0).abs() < 1e-6, "{fastest}");
    assert!((hardest - 1800.0).abs() < 1e-3, "{hardest}");
    assert!((e.axis_status(3).unwrap().cmd_pos - 720.0).abs() < 1e-9);

    // The same turn as a trapezoid: 720/360 + 360/1800 = 2.2 s.
    let mut e = machine(false);
    let run = run_line(&mut e, &[0.0, 0.0, 0.0, 720.0, 0.0, 0.0]);
    let period = e.period();
    assert!(
        (run.seconds - trapezoid(720.0, 360.0, 1800.0)).abs() <= 2.0 * period,
        "{}",
        run.seconds
    );
    assert!((run.velocity[3] - 360.0).abs() < 1e-6);
}

#[test]
fn a_move_that_turns_slowly_lasts_as_long_as_its_angular_profile() {
    let mut e = machine(false);
    set(&mut e, GroupParameter::AngularVelocity, 30.0);
    // 100 mm at [100 mm/s, 5000 mm/s²]: 1.02 s. 90° at [30 deg/s, 1800 deg/s²]: 3.0167 s, and
    // the angular profile binds both velocity and acceleration, so the move takes that.
    let run = run_line(&mut e, &[60.0, 80.0, 0.0, 90.0, 0.0, 0.0]);
    let linear = trapezoid(100.0, 100.0, 5000.0);
    let angular = trapezoid(90.0, 30.0, 1800.0);
    let period = e.period();
    assert!(
        (run.seconds - linear.max(angular)).abs() <= 2.0 * period,
        "{} against {}",
        run.seconds,
        linear.max(angular)
    );
    // The orientation turns at its profile; X and Y move in proportion (100 mm in the time
    // of 90°: 33.3 mm/s along the line).
    assert!((run.velocity[3] - 30.0).abs() < 1e-6, "{}", run.velocity[3]);
    assert!((run.acceleration[3] - 1800.0).abs() < 1e-3);
    let along = run.velocity[0].hypot(run.velocity[1]);
    assert!((along - 100.0 / 3.0).abs() < 1e-6, "{along}");
}

#[test]
fn a_move_that_turns_quickly_lasts_as_long_as_its_linear_profile() {
    let mut e = machine(false);
    set(&mut e, GroupParameter::AngularAcceleration, 72_000.0);
    set(&mut e, GroupParameter::AngularDeceleration, 72_000.0);
    // 90° at [360, 72 000]: 0.255 s; 100 mm at [100, 5000]: 1.02 s, which binds both limits.
    let run = run_line(&mut e, &[60.0, 80.0, 0.0, 90.0, 0.0, 0.0]);
    let linear = trapezoid(100.0, 100.0, 5000.0);
    let angular = trapezoid(90.0, 360.0, 72_000.0);
    let period = e.period();
    assert!(
        (run.seconds - linear.max(angular)).abs() <= 2.0 * period,
        "{}",
        run.seconds
    );
    let along = run.velocity[0].hypot(run.velocity[1]);
    assert!((along - 100.0).abs() < 1e-6, "{along}");
    assert!((run.velocity[3] - 90.0).abs() < 1e-6, "{}", run.velocity[3]);
}

#[test]
fn where_each_profile_binds_one_limit_neither_is_exceeded() {
    let mut e = machine(false);
    // Linear binds the velocity (100 mm/s against 360 deg/s for 90° over 100 mm), angular the
    // acceleration (1800 deg/s² against 5000 mm/s²): each holds, so the move is a little
    // longer than either alone.
    let run = run_line(&mut e, &[60.0, 80.0, 0.0, 90.0, 0.0, 0.0]);
    let along = run.velocity[0].hypot(run.velocity[1]);
    assert!(along <= 100.0 + 1e-6, "{along}");
    assert!(run.velocity[3] <= 360.0 + 1e-6);
    assert!(
        run.acceleration[3] <= 1800.0 + 1e-3,
        "{}",
        run.acceleration[3]
    );
    let linear = trapezoid(100.0, 100.0, 5000.0);
    let angular = trapezoid(90.0, 360.0, 1800.0);
    assert!(run.seconds >= linear.max(angular) - 2.0 * e.period());
    // v_path = 100 / (100/L) along, a_path = 1800 / (90/L): 1 s + 100/(1800·100/90) s.
    let expected = 1.0 + 100.0 / (1800.0 * 100.0 / 90.0);
    assert!(
        (run.seconds - expected).abs() <= 2.0 * e.period(),
        "{}",
        run.seconds
    );
}

#[test]
fn without_orientation_coordinates_every_coordinate_is_linear() {
    // The default group: the 90° count as 90 mm of a 134.5 mm line at 100 mm/s.
    let mut e = Engine::new(&EngineConfig {
        axes: vec![fast_axis(); 6],
        ..EngineConfig::default()
    })
    .unwrap();
    e = common::with_group(e, &[0, 1, 2, 3, 4, 5]);
    set(&mut e, GroupParameter::Jerk, 0.0);
    let run = run_line(&mut e, &[60.0, 80.0, 0.0, 90.0, 0.0, 0.0]);
    let length = 100.0f64.hypot(90.0);
    assert!((run.seconds - trapezoid(length, 100.0, 5000.0)).abs() <= 2.0 * e.period());
}

#[test]
fn bad_orientation_coordinates_and_angular_parameters_are_refused() {
    let mut e = Engine::new(&EngineConfig {
        axes: vec![fast_axis(); 3],
        ..EngineConfig::default()
    })
    .unwrap();
    let err = refused(
        &mut e,
        Command::from(GroupCreate {
            group: 1,
            axes: vec![0, 1, 2],
            queue_capacity: None,
            lookahead: None,
            result_axis: None,
            orientation: CoordinateSet::from_indices(&[2, 3]).unwrap(),
        }),
    );
    assert_eq!(err.kind(), ErrorKind::InvalidGroup);
    assert!(
        err.to_string().contains("orientation coordinate 3"),
        "{err}"
    );

    let mut e = machine(false);
    for (name, value) in [
        (GroupParameter::AngularVelocity, 0.0),
        (GroupParameter::AngularVelocity, f64::NAN),
        (GroupParameter::AngularAcceleration, 0.0),
        (GroupParameter::AngularDeceleration, -1.0),
        (GroupParameter::AngularJerk, -1.0),
    ] {
        let err = refused(
            &mut e,
            Command::from(GroupSetParameter {
                group: 1,
                name,
                value,
            }),
        );
        assert!(
            matches!(err, EngineError::InvalidArgument { .. }),
            "{name:?} {value}: {err:?}"
        );
    }
    // A line that moves nothing is still refused as before.
    let err = refused(
        &mut e,
        Command::from(axes::command::MoveLinearAbsolute {
            independent: CoordinateSet::from_indices(&[0, 1, 2]).unwrap(),
            ..common::group_line(1, &[1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
        }),
    );
    assert!(err.to_string().contains("do not move"), "{err}");
}

#[test]
fn a_jog_of_an_orientation_coordinate_ramps_with_the_angular_acceleration() {
    let mut e = machine(false);
    ok(
        &mut e,
        Command::from(axes::command::GroupJogAxis {
            group: 1,
            member: 4,
            velocity: 90.0,
        }),
    );
    // 90 deg/s at 1800 deg/s²: 0.05 s of ramp, then 90·(1 − 0.05/2) after 1 s.
    for _ in 0..(1.0 / e.period()).round() as u64 {
        e.step();
    }
    let b = e.axis_status(4).unwrap();
    assert!((b.cmd_vel - 90.0).abs() < 1e-9);
    assert!(
        (b.cmd_pos - (90.0 - 90.0 * 0.05 / 2.0)).abs() < 1e-6,
        "{}",
        b.cmd_pos
    );
}
