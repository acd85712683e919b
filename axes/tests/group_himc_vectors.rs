//! HIWIN HIMC group test vectors (digest 004 §6.4, TV 40–57) at the engine level, in mm. The
//! axes' own limits are far above the path's, so the group's profile governs, as in the
//! manual. HIMC's call ↦ engine command: SetGrpMotionProfile ↦ `group_set_parameter`
//! (velocity, acceleration, deceleration; the smoothing time T read as jerk = A / T),
//! SetupGroup ↦ `group_create` + `group_enable`, LineAbs2D/LineRel2D ↦ `move_linear_*`, Arc2D
//! ↦ a circular move by a point on the arc (`border`), ArcCW2D/ArcCCW2D/Circle2D/CircleAbs ↦ by
//! centre, Circle2D's signed `turns` ↦ a direction and extra turns, SetGrpQueueSize(n) ↦
//! `queue_capacity` 2^n. Vectors the engine has no capability for are named in the
//! module's last comment.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    ArcDirection, CircleMode, Command, ErrorKind, GroupBufferMode, GroupCreate, GroupEnable,
    GroupParameter, GroupSetParameter, MoveCircularAbsolute, MoveCircularAngle, MoveLinearAbsolute,
};
use axes::config::AxisConfig;
use axes::status::{GroupState, GroupStatus};
use axes::{AxisFlags, Engine, EngineConfig, EngineError};
use common::{id_of, nearest, ok, refused, run_path, swept_degrees};

fn mm_axis() -> AxisConfig {
    common::fast_mm_axis(1e4, 1e6)
}

/// `n` mm axes, enabled, no group.
fn axes_enabled(n: usize) -> Engine {
    let mut e = Engine::new(&EngineConfig {
        axes: vec![mm_axis(); n],
        ..EngineConfig::default()
    })
    .unwrap();
    for axis in 0..n as u16 {
        ok(&mut e, Command::from(axes::command::Enable { axis }));
    }
    e
}

/// `n` mm axes, enabled; group 1 of `members`, enabled (HIMC SetupGroup).
fn machine(n: usize, members: &[u16]) -> Engine {
    common::with_group(axes_enabled(n), members)
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

fn send(e: &mut Engine, c: impl Into<Command>) -> u32 {
    id_of(ok(e, c.into()))
}

fn set(e: &mut Engine, name: GroupParameter, value: f64) {
    ok(
        e,
        Command::from(GroupSetParameter {
            group: 1,
            name,
            value,
        }),
    );
}

fn line(position: &[f64]) -> MoveLinearAbsolute {
    common::group_line(1, position)
}

/// A circular move of group 1 by centre (`mode` center) or by a point on the arc (`border`).
fn circular(mode: CircleMode, aux: &[f64], end: &[f64], dir: ArcDirection) -> MoveCircularAbsolute {
    MoveCircularAbsolute {
        mode,
        ..common::group_arc(1, aux, end, dir)
    }
}

/// Every (x, y) the path passes until it is done.
fn trace_xy(e: &mut Engine, max_s: f64) -> Vec<(f64, f64)> {
    let mut seen = Vec::new();
    run_path(e, max_s, |_, g| {
        seen.push((g.position()[0], g.position()[1]))
    });
    seen
}

/// Within one servo period's travel at 100 mm/s of a point the arc passes.
const PASSES: f64 = 0.1;

#[test]
fn tv40_setup_group_and_a_line_to_100_100_with_the_motion_profile() {
    // SetGrpMotionProfile(0, 100, 5000, 5000, 200): smoothing 200 ms ↦ jerk 5000 / 0.2.
    let mut e = machine(2, &[0, 1]);
    set(&mut e, GroupParameter::Velocity, 100.0);
    set(&mut e, GroupParameter::Acceleration, 5000.0);
    set(&mut e, GroupParameter::Deceleration, 5000.0);
    set(&mut e, GroupParameter::Jerk, 5000.0 / 0.2);
    send(&mut e, line(&[100.0, 100.0]));
    let mut fastest: f64 = 0.0;
    run_path(&mut e, 5.0, |_, g| fastest = fastest.max(g.path_velocity));
    let g = group(&e);
    assert!(g.in_position, "IsGrpInPos");
    assert_eq!(g.state, GroupState::Standby, "IsGrpEnabled");
    for axis in 0..2 {
        assert_eq!(e.axis_status(axis).unwrap().cmd_pos, 100.0, "axis {axis}");
    }
    assert!((fastest - 100.0).abs() < 1e-9, "{fastest}");
}

#[test]
fn tv41_line_rel_2d_from_100_200_ends_at_200_300() {
    let mut e = machine(2, &[0, 1]);
    send(&mut e, line(&[100.0, 200.0]));
    run_path(&mut e, 10.0, |_, _| {});
    let rel: Command =
        serde_json::from_str(r#"{"type":"move_linear_relative","group":1,"distance":[100,100]}"#)
            .unwrap();
    send(&mut e, rel);
    run_path(&mut e, 10.0, |_, _| {});
    assert_eq!(group(&e).position(), &[200.0, 300.0]);
}

#[test]
fn tv42_arc_2d_through_100_100_ends_at_200_0_on_the_circle_about_100_0() {
    let mut e = machine(2, &[0, 1]);
    send(
        &mut e,
        circular(
            CircleMode::Border,
            &[100.0, 100.0],
            &[200.0, 0.0],
            ArcDirection::Ccw,
        ),
    );
    let seen = trace_xy(&mut e, 10.0);
    assert_eq!(group(&e).position(), &[200.0, 0.0]);
    assert!(nearest(&seen, (100.0, 100.0)) < PASSES);
    for (x, y) in &seen {
        assert!(((x - 100.0).hypot(*y) - 100.0).abs() < 1e-6, "({x}, {y})");
    }
}

#[test]
fn tv43_arc_cw_2d_passes_100_100_and_arc_ccw_2d_passes_100_minus_100() {
    for (dir, through, away) in [
        (ArcDirection::Cw, (100.0, 100.0), (100.0, -100.0)),
        (ArcDirection::Ccw, (100.0, -100.0), (100.0, 100.0)),
    ] {
        let mut e = machine(2, &[0, 1]);
        send(
            &mut e,
            circular(CircleMode::Center, &[100.0, 0.0], &[200.0, 0.0], dir),
        );
        let seen = trace_xy(&mut e, 10.0);
        assert_eq!(group(&e).position(), &[200.0, 0.0]);
        assert!(nearest(&seen, through) < PASSES, "{dir:?}");
        assert!(nearest(&seen, away) > 100.0, "{dir:?}");
    }
}

#[test]
fn tv45_circle_2d_one_turn_is_half_a_circle_ccw_through_100_minus_100() {
    // Circle2D(0, 100, 0, 200, 0, 1): turns 1 sweeps θ itself (as turns 0).
    let mut e = machine(2, &[0, 1]);
    send(
        &mut e,
        circular(
            CircleMode::Center,
            &[100.0, 0.0],
            &[200.0, 0.0],
            ArcDirection::Ccw,
        ),
    );
    let seen = trace_xy(&mut e, 10.0);
    assert_eq!(group(&e).position(), &[200.0, 0.0]);
    assert!(nearest(&seen, (100.0, -100.0)) < PASSES);
    assert!((swept_degrees(&seen, (100.0, 0.0), (0.0, 0.0)) - 180.0).abs() < 1e-6);
}

/// Circle2D's signed `turns` (digest 004 §8.2.17) as the engine's direction and extra turns:
/// n ≥ 2 sweeps θ + (n − 1)·360° counter-clockwise, 0 and 1 sweep θ, n ≤ −1 sweeps
/// (360° − θ) + (−n − 1)·360° clockwise.
fn circle_2d_turns(turns: i32) -> (ArcDirection, u32) {
    if turns < 0 {
        (ArcDirection::Cw, turns.unsigned_abs() - 1)
    } else {
        (ArcDirection::Ccw, turns.max(1) as u32 - 1)
    }
}

#[test]
fn tv46_circle_2d_turn_table_for_210_degrees() {
    // θ = 210°: start (10, 0) about the origin, end at 210°.
    let end = [
        10.0 * 210f64.to_radians().cos(),
        10.0 * 210f64.to_radians().sin(),
    ];
    for (turns, degrees) in [
        (-2, -510.0),
        (-1, -150.0),
        (0, 210.0),
        (1, 210.0),
        (2, 570.0),
    ] {
        let mut e = machine(2, &[0, 1]);
        send(&mut e, line(&[10.0, 0.0]));
        run_path(&mut e, 5.0, |_, _| {});
        let (direction, extra) = circle_2d_turns(turns);
        send(
            &mut e,
            MoveCircularAbsolute {
                turns: extra,
                ..circular(CircleMode::Center, &[0.0, 0.0], &end, direction)
            },
        );
        let seen = trace_xy(&mut e, 20.0);
        let swept = swept_degrees(&seen, (0.0, 0.0), (10.0, 0.0));
        assert!((swept - degrees).abs() < 1e-6, "turns {turns}: {swept}°");
        assert_eq!(group(&e).position(), &end);
    }
}

#[test]
fn tv47_a_motion_profile_with_acceleration_0_is_refused() {
    // SetGrpMotionProfile(0, 100, 0, 5000, 50): acceleration must be > 0.
    let mut e = machine(2, &[0, 1]);
    let err = refused(
        &mut e,
        Command::from(GroupSetParameter {
            group: 1,
            name: GroupParameter::Acceleration,
            value: 0.0,
        }),
    );
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
}

#[test]
fn tv48_a_fresh_group_moves_with_100_mm_s_5000_mm_s2_and_50_ms_smoothing() {
    // The defaults [100, 5000, 5000, 50 ms]: 100 mm/s at most; jerk 5000 / 0.05 = 100 000, so
    // on the way to 100 mm/s the acceleration peaks at √(jerk · v) = √(100 000 · 100).
    let mut e = machine(2, &[0, 1]);
    send(&mut e, line(&[300.0, 400.0]));
    let (mut fastest, mut hardest): (f64, f64) = (0.0, 0.0);
    run_path(&mut e, 10.0, |_, g| {
        fastest = fastest.max(g.path_velocity);
        hardest = hardest.max(g.path_acceleration.abs());
    });
    assert!((fastest - 100.0).abs() < 1e-9, "{fastest}");
    let peak = (100_000.0f64 * 100.0).sqrt();
    assert!((hardest - peak).abs() < 0.02 * peak, "{hardest}");
    // With room to reach it, the acceleration is 5000.
    set(&mut e, GroupParameter::Velocity, 1000.0);
    send(&mut e, line(&[0.0, 0.0]));
    let mut hardest: f64 = 0.0;
    run_path(&mut e, 10.0, |_, g| {
        hardest = hardest.max(g.path_acceleration.abs())
    });
    assert!((hardest - 5000.0).abs() < 1e-3, "{hardest}");
}

fn create(group: u16, axes: &[u16], queue_capacity: Option<u32>) -> Command {
    Command::from(GroupCreate {
        group,
        axes: axes.to_vec(),
        queue_capacity,
        lookahead: None,
        result_axis: None,
        orientation: Default::default(),
    })
}

#[test]
fn tv50_a_tenth_axis_is_refused() {
    let mut e = axes_enabled(10);
    let err = refused(&mut e, create(1, &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9], None));
    assert_eq!(err.kind(), ErrorKind::InvalidGroup);
    ok(&mut e, create(1, &[0, 1, 2, 3, 4, 5, 6, 7, 8], None));
}

#[test]
fn tv51_the_same_axis_twice_is_refused() {
    let mut e = axes_enabled(3);
    let err = refused(&mut e, create(1, &[0, 1, 1], None));
    assert_eq!(
        err,
        EngineError::InvalidGroup {
            group: 1,
            reason: "axis 1 is listed twice".into()
        }
    );
    ok(&mut e, create(1, &[0, 1], None));
    let err = refused(&mut e, create(2, &[1], None));
    assert_eq!(err.kind(), ErrorKind::InvalidGroup);
}

#[test]
fn tv52_an_ungrouped_axis_belongs_to_no_group() {
    let e = machine(3, &[0, 1]);
    let s = e.snapshot();
    assert!(!s.axes[2].flags.contains(AxisFlags::IN_GROUP));
    assert!(s.groups.iter().all(|g| !g.axes().contains(&2)));
    assert!(s.axes[0].flags.contains(AxisFlags::IN_GROUP));
}

#[test]
fn tv53_a_queue_of_2_to_the_9_takes_512_commands_and_2_to_the_11_is_refused() {
    let mut e = axes_enabled(4);
    let err = refused(&mut e, create(2, &[2, 3], Some(1 << 11)));
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    ok(&mut e, create(1, &[0, 1], Some(1 << 9)));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    for k in 0..512 {
        let x = if k % 2 == 0 { 1.0 } else { 0.0 };
        send(&mut e, line(&[x, 0.0]));
    }
    let err = refused(&mut e, Command::from(line(&[2.0, 0.0])));
    assert_eq!(
        err,
        EngineError::GroupQueueFull {
            group: 1,
            capacity: 512
        }
    );
}

#[test]
fn tv55_a_stadium_blends_at_p1_and_p2_and_stops_at_p3_after_waiting_in_position() {
    // CircleAbs about a centre with normal {0, 0, 1}: a 3-axis group, z = 0.
    let mut e = machine(3, &[0, 1, 2]);
    let about = |center: [f64; 3], end: [f64; 3], mode: GroupBufferMode| MoveCircularAbsolute {
        normal: Some(vec![0.0, 0.0, 1.0]),
        buffer_mode: mode,
        ..circular(CircleMode::Center, &center, &end, ArcDirection::Ccw)
    };
    send(
        &mut e,
        MoveLinearAbsolute {
            buffer_mode: GroupBufferMode::BlendingPrevious,
            ..line(&[100.0, 0.0, 0.0])
        },
    );
    send(
        &mut e,
        about(
            [100.0, 50.0, 0.0],
            [100.0, 100.0, 0.0],
            GroupBufferMode::BlendingNext,
        ),
    );
    send(
        &mut e,
        MoveLinearAbsolute {
            buffer_mode: GroupBufferMode::BlendingLow,
            ..line(&[0.0, 100.0, 0.0])
        },
    );
    let mut seen = Vec::new();
    let slowest_at = |seen: &[(f64, f64, f64)], p: (f64, f64)| {
        seen.iter()
            .filter(|(x, y, _)| (x - p.0).hypot(y - p.1) < 1.0)
            .map(|(_, _, v)| *v)
            .fold(f64::INFINITY, f64::min)
    };
    run_path(&mut e, 20.0, |_, g| {
        seen.push((g.position()[0], g.position()[1], g.path_velocity))
    });
    assert!(group(&e).in_position);
    assert_eq!(group(&e).position(), &[0.0, 100.0, 0.0]);
    let first: Vec<(f64, f64)> = seen.iter().map(|(x, y, _)| (*x, *y)).collect();
    assert!(nearest(&first, (150.0, 50.0)) < PASSES);
    // At p1 and p2 the tangent junctions keep the speed (100 mm/s).
    assert!(slowest_at(&seen, (100.0, 0.0)) > 90.0);
    assert!(slowest_at(&seen, (100.0, 100.0)) > 90.0);
    // The group was in position at p3: the last motion starts from rest, its mode ignored.
    send(
        &mut e,
        about([0.0, 50.0, 0.0], [0.0, 0.0, 0.0], GroupBufferMode::Buffered),
    );
    let mut second = Vec::new();
    let mut slowest_start = f64::INFINITY;
    run_path(&mut e, 20.0, |_, g| {
        second.push((g.position()[0], g.position()[1]));
        if second.len() == 1 {
            slowest_start = g.path_velocity;
        }
    });
    assert!(slowest_start < 1.0, "starts from rest: {slowest_start}");
    assert!(nearest(&second, (-50.0, 50.0)) < PASSES);
    assert_eq!(group(&e).position(), &[0.0, 0.0, 0.0]);
}

/// ArcAngle2D (`move_circular_angle`).
fn arc_angle(center: [f64; 2], degrees: f64) -> MoveCircularAngle {
    MoveCircularAngle {
        group: 1,
        center: center.to_vec(),
        angle: degrees,
        plane: None,
        relative: false,
        velocity: Some(100.0),
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: GroupBufferMode::Buffered,
        transition: Default::default(),
        user_segment: None,
        coordinate_system: None,
    }
}

#[test]
fn tv44_arc_angle_2d_45_degrees_ends_at_10_minus_4_142136() {
    // ArcAngle2D(0, 10, 10, 45) from (0, 0): radius 10√2, counter-clockwise (> 0) by 45°.
    let mut e = machine(2, &[0, 1]);
    send(&mut e, arc_angle([10.0, 10.0], 45.0));
    let seen = trace_xy(&mut e, 10.0);
    let end = group(&e).position().to_vec();
    let expected = [10.0, 10.0 - 10.0 * 2f64.sqrt()];
    assert!(
        (end[0] - expected[0]).abs() < 1e-9 && (end[1] - expected[1]).abs() < 1e-9,
        "{end:?}"
    );
    // On the circle all the way, and counter-clockwise: through the point 22.5° along.
    let r = 10.0 * 2f64.sqrt();
    assert!(seen
        .iter()
        .all(|(x, y)| ((x - 10.0).hypot(y - 10.0) - r).abs() < 1e-6));
    let a = (-135.0f64 + 22.5).to_radians();
    assert!(nearest(&seen, (10.0 + r * a.cos(), 10.0 + r * a.sin())) < PASSES);
    // Negative: clockwise, from −135° to −180°; beyond 360°: more than a turn.
    let mut e = machine(2, &[0, 1]);
    send(&mut e, arc_angle([10.0, 10.0], -45.0));
    trace_xy(&mut e, 10.0);
    let end = group(&e).position().to_vec();
    assert!(
        (end[0] - (10.0 - r)).abs() < 1e-9 && (end[1] - 10.0).abs() < 1e-9,
        "{end:?}"
    );
    let mut e = machine(2, &[0, 1]);
    send(&mut e, arc_angle([10.0, 10.0], 405.0));
    let mut swept = Vec::new();
    run_path(&mut e, 20.0, |_, g| {
        swept.push((g.position()[0], g.position()[1]))
    });
    assert!((swept_degrees(&swept, (10.0, 10.0), (0.0, 0.0)) - 405.0).abs() < 0.5);
    // An angle of 0, or not a number: refused with the reason, nothing queued.
    let mut e = machine(2, &[0, 1]);
    for bad in [0.0, f64::NAN, 2e6] {
        let err = refused(&mut e, Command::from(arc_angle([10.0, 10.0], bad)));
        assert_eq!(err.kind(), ErrorKind::InvalidArgument, "{bad}: {err}");
        assert!(err.to_string().contains("angle"), "{bad}: {err}");
    }
    assert_eq!(group(&e).queue_used, 0);
}

// Not at the engine level (no capability; see the session's report):
// - TV 47's bounds velocity ≤ 5000 mm/s and smoothing ≤ 500 ms, TV 49 SetGrpAngMotionProfile
//   (no orientation profile), TV 54 JogGroup (no group jog).
// - TV 56–57 SetGrpCoordTrans: in `axes/tests/group_frames.rs`.
