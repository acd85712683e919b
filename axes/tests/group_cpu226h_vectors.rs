//! Co-Trust CPU 226H interpolation test vectors (digest 003 §8: TV-15, TV-31–33) at the engine
//! level, in pulses (user unit = 1 pulse), Hz = pulses/s and Hz/ms = 1000 pulses/s². The CPU's
//! instructions ↦ engine commands: MC_LINE_R ↦ `move_linear_relative` of a 2-axis group of
//! A_AXIS and B_AXIS, MC_CIRCLE_R ↦ a circular move by signed radius with CW, MC_3P_CIRCLE_R ↦
//! a circular move by a point on the arc. The CPU's speeds are the long axis's (digest 003
//! §4.3): its front-end gives the engine the path speed MAX_SPEED · L / |long-axis distance|.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    ArcDirection, CircleMode, Command, GroupBufferMode, GroupParameter, GroupSetParameter,
    MoveCircularRelative, MoveLinearRelative, TransitionMode,
};
use axes::config::AxisConfig;
use axes::status::GroupStatus;
use axes::{Engine, EngineConfig, ParamId};
use common::{id_of, nearest, ok, run_path, swept_degrees};

/// Hz/ms in pulses/s².
const HZ_PER_MS: f64 = 1e3;

/// A pulse axis ≤ 200 kHz (digest 003 §2.0) whose `max_accel` (MC_SET_MAX_ACCELE) is
/// `max_accel` Hz/ms.
fn pulse_axis(max_accel: f64) -> AxisConfig {
    common::free_linear_axis(
        1.0,
        &[
            (ParamId::Speed, 200_000.0),
            (ParamId::Accel, 1e9),
            (ParamId::Decel, 1e9),
            (ParamId::MaxAccel, max_accel * HZ_PER_MS),
        ],
    )
}

/// The CPU's 4 axes, enabled, `max_accel` Hz/ms each; group 1 of `members` (A, B).
fn machine(max_accel: [f64; 4], members: &[u16]) -> Engine {
    let e = Engine::new(&EngineConfig {
        axes: max_accel.iter().map(|&m| pulse_axis(m)).collect(),
        ..EngineConfig::default()
    })
    .unwrap();
    common::with_group(e, members)
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

fn send(e: &mut Engine, c: impl Into<Command>) -> u32 {
    id_of(ok(e, c.into()))
}

/// MC_LINE_R by (a, b) with the long axis at `max_speed` Hz; `acceleration` along the path
/// (None: the members' max_accel governs, TA = 0).
fn line_r(a: f64, b: f64, max_speed: f64, acceleration: Option<f64>) -> MoveLinearRelative {
    let long = a.abs().max(b.abs());
    let speed = max_speed * a.hypot(b) / long;
    MoveLinearRelative {
        group: 1,
        distance: vec![a, b],
        velocity: Some(speed),
        acceleration: Some(acceleration.unwrap_or(1e12)),
        deceleration: Some(acceleration.unwrap_or(1e12)),
        jerk: Some(0.0),
        buffer_mode: GroupBufferMode::Buffered,
        transition: TransitionMode::None,
        user_segment: None,
        independent: Default::default(),
        coordinate_system: None,
    }
}

/// Each member's largest |velocity| and |acceleration| over the path.
fn peaks(e: &mut Engine, members: &[usize]) -> Vec<(f64, f64)> {
    let mut peak = vec![(0.0f64, 0.0f64); members.len()];
    run_path(e, 60.0, |e, _| {
        for (out, &a) in peak.iter_mut().zip(members) {
            let s = e.axis_status(a).unwrap();
            out.0 = out.0.max(s.cmd_vel.abs());
            out.1 = out.1.max(s.cmd_acc.abs());
        }
    });
    peak
}

#[test]
fn tv15_two_axes_with_max_accel_100_and_50_hz_per_ms_accelerate_at_the_smaller() {
    // MC_LINE_R A_AXIS = 1, B_AXIS = 3, TA = 0: the system acceleration is the smaller max
    // accel, 50 Hz/ms, on the long axis — here A (axis 1, whose own limit is 100 Hz/ms).
    let mut e = machine([0.0, 100.0, 0.0, 50.0], &[1, 3]);
    ok(
        &mut e,
        Command::from(GroupSetParameter {
            group: 1,
            name: GroupParameter::SmallestAxisAcceleration,
            value: 1.0,
        }),
    );
    send(&mut e, line_r(20_000.0, 10_000.0, 8000.0, None));
    let p = peaks(&mut e, &[1, 3]);
    assert!((p[0].1 - 50.0 * HZ_PER_MS).abs() < 1e-6, "{p:?}");
    assert!((p[1].1 - 25.0 * HZ_PER_MS).abs() < 1e-6, "{p:?}");
    assert_eq!(group(&e).position(), &[20_000.0, 10_000.0]);
    // Without the rule each member has its own limit: A reaches its 100 Hz/ms.
    let mut e = machine([0.0, 100.0, 0.0, 50.0], &[1, 3]);
    send(&mut e, line_r(20_000.0, 10_000.0, 8000.0, None));
    let p = peaks(&mut e, &[1, 3]);
    assert!((p[0].1 - 100.0 * HZ_PER_MS).abs() < 1e-6, "{p:?}");
}

/// MC_CIRCLE_R from (0, 0) by signed radius and CW.
fn circle_r(end: [f64; 2], radius: f64, cw: bool) -> MoveCircularRelative {
    MoveCircularRelative {
        group: 1,
        mode: CircleMode::Radius,
        aux_point: Vec::new(),
        radius: Some(radius),
        end_point: end.to_vec(),
        direction: if cw {
            ArcDirection::Cw
        } else {
            ArcDirection::Ccw
        },
        plane: None,
        normal: None,
        turns: 0,
        velocity: Some(2000.0),
        acceleration: Some(50.0 * HZ_PER_MS),
        deceleration: Some(50.0 * HZ_PER_MS),
        jerk: Some(0.0),
        buffer_mode: GroupBufferMode::Buffered,
        transition: TransitionMode::None,
        user_segment: None,
        independent: Default::default(),
        coordinate_system: None,
    }
}

/// Every (x, y) the path passes.
fn trace(e: &mut Engine) -> Vec<(f64, f64)> {
    let mut seen = Vec::new();
    run_path(e, 60.0, |_, g| {
        seen.push((g.position()[0], g.position()[1]))
    });
    seen
}

/// At most one servo period's travel at 2000 Hz from a point the arc passes.
const PASSES: f64 = 2.0;

#[test]
fn tv31_circle_r_radius_plus_1000_is_a_90_degree_cw_arc_minus_1000_a_270_degree_one() {
    // End (1000, 1000), CW: +1000 → centre (1000, 0), 90°; −1000 → centre (0, 1000), 270°.
    for (radius, center, degrees) in [
        (1000.0, (1000.0, 0.0), -90.0),
        (-1000.0, (0.0, 1000.0), -270.0),
    ] {
        let mut e = machine([0.0; 4], &[0, 2]);
        send(&mut e, circle_r([1000.0, 1000.0], radius, true));
        let seen = trace(&mut e);
        assert_eq!(group(&e).position(), &[1000.0, 1000.0]);
        for (x, y) in &seen {
            let r = (x - center.0).hypot(y - center.1);
            assert!((r - 1000.0).abs() < 1e-6, "radius {radius}: ({x}, {y})");
        }
        let swept = swept_degrees(&seen, center, (0.0, 0.0));
        assert!((swept - degrees).abs() < 1e-6, "radius {radius}: {swept}°");
    }
}

#[test]
fn tv32_3p_circle_r_through_1000_1000_is_a_cw_semicircle_ending_at_2000_0() {
    let mut e = machine([0.0; 4], &[0, 2]);
    send(
        &mut e,
        MoveCircularRelative {
            mode: CircleMode::Border,
            aux_point: vec![1000.0, 1000.0],
            radius: None,
            end_point: vec![2000.0, 0.0],
            ..circle_r([0.0, 0.0], 0.0, false)
        },
    );
    let seen = trace(&mut e);
    assert_eq!(group(&e).position(), &[2000.0, 0.0], "ACT_A_POS, ACT_B_POS");
    assert!(nearest(&seen, (1000.0, 1000.0)) < PASSES);
    for (x, y) in &seen {
        assert!(((x - 1000.0).hypot(*y) - 1000.0).abs() < 1e-6, "({x}, {y})");
    }
    assert!((swept_degrees(&seen, (1000.0, 0.0), (0.0, 0.0)) + 180.0).abs() < 1e-6);
}

#[test]
fn tv33_line_r_3000_4000_runs_the_long_axis_b_at_8000_hz_and_a_at_6000() {
    let mut e = machine([0.0; 4], &[0, 2]);
    send(
        &mut e,
        line_r(3000.0, 4000.0, 8000.0, Some(50.0 * HZ_PER_MS)),
    );
    let p = peaks(&mut e, &[0, 2]);
    assert!((p[1].0 - 8000.0).abs() < 1e-6, "long axis B: {p:?}");
    assert!((p[0].0 - 6000.0).abs() < 1e-6, "A at 3/4: {p:?}");
    assert_eq!(group(&e).position(), &[3000.0, 4000.0]);
}
