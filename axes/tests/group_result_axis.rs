//! HMC's result axis (合轴, digest 000 §4.3) and independent coordinates: the manual's
//! interpolation cases TV 13–19 (digest 000 §8.2) on the engine's virtual clock, the result
//! axis's limits as the path profile, and the refusals and faults around it.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use std::f64::consts::TAU;

use axes::command::{
    ArcDirection, Command, CommandState, CoordinateSet, Enable, ErrorKind, GroupBufferMode,
    GroupCreate, GroupDelete, GroupEnable, MoveAbsolute, MoveCircularAbsolute, MoveLinearRelative,
    MoveSpline, SetParameter, TransitionMode,
};
use axes::config::AxisConfig;
use axes::status::{GroupFault, GroupState, GroupStatus};
use axes::{AxisState, Engine, EngineConfig, EngineError, ParamId};
use common::{id_of, ok, refused, state_of};

/// The result axis's path limits in the tests (HMC-like units: pulses, pulses/s …).
const SPEED: f64 = 10_000.0;
const ACCEL: f64 = 100_000.0;

/// A virtual axis on finite travel with `speed`, `accel` and `decel`.
fn virtual_axis(speed: f64, accel: f64) -> AxisConfig {
    let mut a = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 0.0),
        (ParamId::RepMode, 0.0),
        (ParamId::Speed, speed),
        (ParamId::Accel, accel),
        (ParamId::Decel, accel),
    ] {
        a.params.insert(p, v);
    }
    a
}

/// `n` virtual axes, all enabled: the components are fast (their own limits never bind), axis
/// `result` has the path limits [`SPEED`], [`ACCEL`]. Group 1 of `members` with `result` as
/// its result axis, enabled.
fn machine(n: usize, members: &[u16], result: u16) -> Engine {
    let axes = (0..n)
        .map(|a| {
            if a == usize::from(result) {
                virtual_axis(SPEED, ACCEL)
            } else {
                virtual_axis(1e7, 1e9)
            }
        })
        .collect();
    let mut e = Engine::new(&EngineConfig {
        axes,
        ..EngineConfig::default()
    })
    .unwrap();
    for axis in 0..n as u16 {
        ok(&mut e, Command::from(Enable { axis }));
    }
    ok(&mut e, Command::from(create(1, members, Some(result))));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    e
}

fn create(group: u16, members: &[u16], result_axis: Option<u16>) -> GroupCreate {
    GroupCreate {
        group,
        axes: members.to_vec(),
        queue_capacity: None,
        lookahead: None,
        result_axis,
        orientation: Default::default(),
    }
}

/// HMC_Move2D/3D/ND: a relative line, the result axis's limits.
fn line(distance: &[f64]) -> MoveLinearRelative {
    MoveLinearRelative {
        group: 1,
        distance: distance.to_vec(),
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: GroupBufferMode::Buffered,
        transition: TransitionMode::None,
        user_segment: None,
        independent: Default::default(),
        coordinate_system: None,
    }
}

/// HMC_MoveCircle modes 1/3 (and HMC_MoveHelical 1/3/5/7) by centre and end, absolute here
/// (HMC's are relative to the start).
fn arc(center: &[f64], end: &[f64], direction: ArcDirection) -> MoveCircularAbsolute {
    common::group_arc(1, center, end, direction)
}

fn coords(indices: &[usize]) -> CoordinateSet {
    CoordinateSet::from_indices(indices).unwrap()
}

fn send(e: &mut Engine, c: impl Into<Command>) -> u32 {
    id_of(ok(e, c.into()))
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

fn pos(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

fn vel(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_vel
}

/// Step until the group is back in Standby, calling `each` after every tick; returns the
/// ticks taken.
fn run_path(e: &mut Engine, max_s: f64, mut each: impl FnMut(&Engine)) -> u64 {
    let n = (max_s / e.period()).round() as u64;
    for k in 1..=n {
        e.step();
        each(e);
        if group(e).state == GroupState::Standby {
            return k;
        }
    }
    panic!("still {:?} after {max_s} s", group(e));
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn tv13_move2d_result_axis_travels_the_hypotenuse_at_its_own_speed() {
    // HMC_Move2D(0, 1, 2, 30000, 40000) from 0: EndPos axis 0 = 50000, axes 1, 2 = 30000, 40000.
    let mut e = machine(3, &[1, 2], 0);
    let id = send(&mut e, line(&[30000.0, 40000.0]));
    let mut peak: f64 = 0.0;
    run_path(&mut e, 20.0, |e| {
        // On a line from the origin, the result axis is the distance from it, every tick.
        let (x, y) = (pos(e, 1), pos(e, 2));
        assert!(
            close(pos(e, 0), x.hypot(y), 1e-6),
            "{} vs {x}, {y}",
            pos(e, 0)
        );
        // The components move at L(i)/D of the result axis's speed.
        assert!(close(vel(e, 1), 0.6 * vel(e, 0), 1e-6));
        assert!(close(vel(e, 2), 0.8 * vel(e, 0), 1e-6));
        if group(e).state == GroupState::Moving {
            assert_eq!(
                e.axis_status(0).unwrap().state,
                AxisState::SynchronizedMotion
            );
        }
        peak = peak.max(vel(e, 0));
    });
    assert!(close(pos(&e, 0), 50000.0, 1e-6), "{}", pos(&e, 0));
    assert_eq!((pos(&e, 1), pos(&e, 2)), (30000.0, 40000.0));
    // The path cruised at the result axis's Speed, not the components' 1e7.
    assert!(close(peak, SPEED, 1e-6), "peak {peak}");
    assert_eq!(state_of(&mut e, id), CommandState::Done);
    assert_eq!(group(&e).result_axis, Some(0));
    // Back in Standby, the result axis is free of the feed but still bound to the group.
    assert_eq!(e.axis_status(0).unwrap().state, AxisState::Standstill);
}

#[test]
fn tv14_full_circle_result_axis_ends_at_two_pi_r() {
    // HMC_MoveCircle(0, 1, 2, 3, 0, 0, 10000, 0): clockwise full circle about (10000, 0).
    let mut e = machine(3, &[1, 2], 0);
    send(&mut e, arc(&[10000.0, 0.0], &[0.0, 0.0], ArcDirection::Cw));
    let mut min_y: f64 = 0.0;
    run_path(&mut e, 30.0, |e| min_y = min_y.min(pos(e, 2)));
    assert!(close(pos(&e, 0), TAU * 10000.0, 1e-6), "{}", pos(&e, 0));
    assert!(close(pos(&e, 0), 62831.853, 1e-3));
    assert_eq!((pos(&e, 1), pos(&e, 2)), (0.0, 0.0));
    // Clockwise from the left of the centre: through y = +r first, so y never went negative
    // before the top; it reached −r on the way back.
    assert!(close(min_y, -10000.0, 1e-3), "{min_y}");
}

/// Peak path velocity of a clockwise full circle of radius `r` (from the origin about
/// (r, 0)) whose result axis has `speed` and S-curve `jerk` (JerkMode 1), acceleration far
/// above what the jerk lets the path reach.
fn circle_peak_with_result_jerk(r: f64, speed: f64, jerk: f64) -> (f64, Engine) {
    let mut result = virtual_axis(speed, 1e9);
    result.params.insert(ParamId::JerkMode, 1.0);
    result.params.insert(ParamId::Jerk, jerk);
    let mut e = Engine::new(&EngineConfig {
        axes: vec![result, virtual_axis(1e7, 1e9), virtual_axis(1e7, 1e9)],
        ..EngineConfig::default()
    })
    .unwrap();
    for axis in 0..3 {
        ok(&mut e, Command::from(Enable { axis }));
    }
    ok(&mut e, Command::from(create(1, &[1, 2], Some(0))));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    send(&mut e, arc(&[r, 0.0], &[0.0, 0.0], ArcDirection::Cw));
    let mut peak: f64 = 0.0;
    run_path(&mut e, 60.0, |e| peak = peak.max(group(e).path_velocity));
    (peak, e)
}

#[test]
fn tv37_a_circle_s_speed_is_capped_at_the_cube_root_of_jerk_over_curvature_squared() {
    // Digest 000 TV 37 (§4.4.7 (2)): an arc at Speed 20000 with Jerk 5000 reaches at most
    // 7937.01 (radius 10000: (5000 · 10000²)^(1/3) = 7937.005); with Jerk 5e9 it reaches 20000.
    let (peak, e) = circle_peak_with_result_jerk(10_000.0, 20_000.0, 5_000.0);
    assert!(close(peak, 7937.005, 0.01), "peak path velocity {peak}");
    assert!(close(pos(&e, 0), TAU * 10_000.0, 1e-6), "{}", pos(&e, 0));
    let (peak, _) = circle_peak_with_result_jerk(10_000.0, 20_000.0, 5e9);
    assert!(close(peak, 20_000.0, 1e-6), "peak path velocity {peak}");
    // TV 36's small circle (curvature 1/(50·√2)) with Jerk := 100000 at Speed 1000: ≈ 793.7.
    let (peak, _) = circle_peak_with_result_jerk(50.0 * 2f64.sqrt(), 1000.0, 100_000.0);
    assert!(close(peak, 793.700_5, 1e-3), "peak path velocity {peak}");
}

#[test]
fn tv15_triangle_contour_result_axis_300_700_1200_then_the_absolute_version() {
    // HMC_Move2D(10, 0, 1, …) ×3, then the same path with HMC_MoveAbs2D.
    let mut e = machine(11, &[0, 1], 10);
    for (d, expected) in [
        ([300.0, 0.0], 300.0),
        ([0.0, 400.0], 700.0),
        ([-300.0, -400.0], 1200.0),
    ] {
        send(&mut e, line(&d));
        run_path(&mut e, 10.0, |_| {});
        assert!(close(pos(&e, 10), expected, 1e-6), "{}", pos(&e, 10));
    }
    assert_eq!((pos(&e, 0), pos(&e, 1)), (0.0, 0.0));
    // The absolute version: the result axis keeps growing (EndPos += length).
    for (p, expected) in [
        ([300.0, 0.0], 1500.0),
        ([300.0, 400.0], 1900.0),
        ([0.0, 0.0], 2400.0),
    ] {
        let id = send(&mut e, common::group_line(1, &p));
        run_path(&mut e, 10.0, |_| {});
        assert_eq!(state_of(&mut e, id), CommandState::Done);
        assert!(close(pos(&e, 10), expected, 1e-6), "{}", pos(&e, 10));
    }
    assert_eq!((pos(&e, 0), pos(&e, 1)), (0.0, 0.0));
}

#[test]
fn tv16_cube_sixteen_edges_result_axis_16000() {
    // Src §4.3.1.5: HMC_Move3D(5, 0, 1, 2, …) over the 16 edges.
    let edges = [
        [1000.0, 0.0, 0.0],
        [0.0, 1000.0, 0.0],
        [-1000.0, 0.0, 0.0],
        [0.0, -1000.0, 0.0],
        [0.0, 0.0, 1000.0],
        [0.0, 1000.0, 0.0],
        [0.0, 0.0, -1000.0],
        [1000.0, 0.0, 0.0],
        [0.0, 0.0, 1000.0],
        [-1000.0, 0.0, 0.0],
        [0.0, -1000.0, 0.0],
        [1000.0, 0.0, 0.0],
        [0.0, 1000.0, 0.0],
        [0.0, 0.0, -1000.0],
        [0.0, -1000.0, 0.0],
        [0.0, 0.0, 1000.0],
    ];
    let mut e = machine(6, &[0, 1, 2], 5);
    for d in &edges {
        send(&mut e, line(d));
    }
    run_path(&mut e, 30.0, |_| {});
    assert!(close(pos(&e, 5), 16000.0, 1e-6), "{}", pos(&e, 5));
    assert_eq!([pos(&e, 0), pos(&e, 1), pos(&e, 2)], [1000.0, 0.0, 1000.0]);
}

#[test]
fn tv17_move_nd_independent_axes_ride_in_proportion_and_do_not_count() {
    // HMC_MoveND(15, [0,1,2,3,4], [10000,20000,30000,180,120], 3, 2): the result axis is
    // axis 5 here.
    let mut e = machine(6, &[0, 1, 2, 3, 4], 5);
    let d = (10000.0f64.powi(2) + 20000.0f64.powi(2) + 30000.0f64.powi(2)).sqrt();
    assert!(close(d, 37416.574, 1e-3));
    send(
        &mut e,
        MoveLinearRelative {
            independent: coords(&[3, 4]),
            ..line(&[10000.0, 20000.0, 30000.0, 180.0, 120.0])
        },
    );
    let mut peak: f64 = 0.0;
    let mut finished = [None; 5];
    let mut tick = 0u64;
    let end = [10000.0, 20000.0, 30000.0, 180.0, 120.0];
    run_path(&mut e, 20.0, |e| {
        tick += 1;
        let v = vel(e, 5);
        peak = peak.max(v);
        // SpeedL(i) = L(i)/D · Speed, SpeedS(j) = S(j)/D · Speed.
        for (k, l) in end.iter().enumerate() {
            assert!(close(vel(e, k), l / d * v, 1e-6 * (1.0 + v)), "axis {k}");
            if finished[k].is_none() && pos(e, k) == *l {
                finished[k] = Some(tick);
            }
        }
        // Every axis is the same fraction of its way.
        let progress = pos(e, 0) / 10000.0;
        assert!(close(pos(e, 3), 180.0 * progress, 1e-6));
        assert!(close(pos(e, 5), d * progress, 1e-6));
    });
    assert!(close(pos(&e, 5), d, 1e-6), "{}", pos(&e, 5));
    // The path speed is the result axis's Speed over the path axes: the full 5-D speed is
    // above it by |(L, S)| / D (1 + 1.6e-5), so a profile over all five would peak lower.
    assert!(close(peak, SPEED, 1e-9 * SPEED), "peak {peak}");
    // All finish together.
    assert!(
        finished.iter().all(|t| t.is_some() && *t == finished[0]),
        "{finished:?}"
    );
}

/// A spline of group 1 through `points` (absolute) with `independent` coordinates.
fn spline<const N: usize>(points: &[[f64; N]], independent: &[usize]) -> MoveSpline {
    MoveSpline {
        independent: coords(independent),
        ..common::group_spline(1, points.iter().map(|p| p.to_vec()).collect())
    }
}

/// Issue 11 item 2: splines take independent coordinates as lines and arcs do (HMC
/// MoveSplineND with independent axes, NMC D8): the spline goes through the points' counted
/// coordinates, the independent ones ride from the start to the last point's values in
/// proportion to the counted length, and only the counted length counts (the result axis).
#[test]
fn a_spline_s_independent_coordinates_ride_in_proportion_and_do_not_count() {
    let mut e = machine(4, &[0, 1, 2], 3);
    let points = [
        [1000.0, 500.0, 7.0],
        [2000.0, -500.0, -3.0],
        [3000.0, 0.0, 40.0],
    ];
    // The counted length: the same spline in (x, y) alone.
    let flat: Vec<path::Point> = std::iter::once([0.0, 0.0])
        .chain(points.iter().map(|p| [p[0], p[1]]))
        .map(|q| {
            let mut out = [0.0; path::MAX_AXES];
            out[..2].copy_from_slice(&q);
            out
        })
        .collect();
    let counted = path::geometry::Curve::spline(&flat, 2).unwrap().length();
    send(&mut e, spline(&points, &[2]));
    run_path(&mut e, 30.0, |e| {
        // z is the same fraction of its way as the result axis of the counted length.
        let progress = pos(e, 3) / counted;
        assert!(
            close(pos(e, 2), 40.0 * progress, 1e-6),
            "z {} at {progress}",
            pos(e, 2)
        );
    });
    assert_eq!([pos(&e, 0), pos(&e, 1), pos(&e, 2)], [3000.0, 0.0, 40.0]);
    assert!(
        close(pos(&e, 3), counted, 1e-6),
        "{} vs {counted}",
        pos(&e, 3)
    );
    // Without independent coordinates, z is part of the shape and the length counts it.
    let mut e = machine(4, &[0, 1, 2], 3);
    send(&mut e, spline(&points, &[]));
    run_path(&mut e, 30.0, |_| {});
    assert_eq!([pos(&e, 0), pos(&e, 1), pos(&e, 2)], [3000.0, 0.0, 40.0]);
    assert!(pos(&e, 3) > counted + 0.5, "{} vs {counted}", pos(&e, 3));
}

#[test]
fn tv18_slot_contour_result_axis_4000_plus_two_pi_1000() {
    // HMC_Move2D(6,0,1,2000,0); HMC_MoveCircle(6,0,1,3,0,−2000,0,−1000);
    // HMC_Move2D(6,0,1,−2000,0); HMC_MoveCircle(6,0,1,3,0,2000,0,1000).
    let mut e = machine(7, &[0, 1], 6);
    send(&mut e, line(&[2000.0, 0.0]));
    send(
        &mut e,
        arc(&[2000.0, -1000.0], &[2000.0, -2000.0], ArcDirection::Cw),
    );
    send(&mut e, line(&[-2000.0, 0.0]));
    send(&mut e, arc(&[0.0, -1000.0], &[0.0, 0.0], ArcDirection::Cw));
    let mut max_x: f64 = 0.0;
    run_path(&mut e, 30.0, |e| max_x = max_x.max(pos(e, 0)));
    let expected = 4000.0 + TAU * 1000.0;
    assert!(close(expected, 10283.19, 1e-2));
    assert!(close(pos(&e, 6), expected, 1e-6), "{}", pos(&e, 6));
    // Clockwise half circles: out to x = 3000 on the right, back to (0, 0).
    assert!(close(max_x, 3000.0, 1e-3), "{max_x}");
    assert!(close(pos(&e, 0), 0.0, 1e-9) && close(pos(&e, 1), 0.0, 1e-9));
}

/// HMC_MoveHelical(0, 1, 2, 3, mode, 0, 0, 50, 0, 500): a clockwise full circle of radius 50
/// about (50, 0) while Z climbs 500 (to 500 × `call`); `plane_only` is modes 4/5/7 (the result
/// axis counts the XY arc), else modes 0/1/3 (the XYZ length).
fn helix(plane_only: bool, call: u32) -> MoveCircularAbsolute {
    let z = 500.0 * f64::from(call);
    MoveCircularAbsolute {
        independent: if plane_only {
            coords(&[2])
        } else {
            coords(&[])
        },
        ..arc(&[50.0, 0.0, z - 500.0], &[0.0, 0.0, z], ArcDirection::Cw)
    }
}

#[test]
fn tv19_helix_mode_7_counts_the_arc_only_314_159_per_call() {
    let mut e = machine(4, &[1, 2, 3], 0);
    // A result Speed the path reaches on a 314-unit arc; read when the motion is queued.
    ok(
        &mut e,
        Command::from(SetParameter {
            axis: 0,
            name: ParamId::Speed,
            value: 1000.0,
            lenient: false,
        }),
    );
    let circle = TAU * 50.0;
    let mut peak: f64 = 0.0;
    let mut peak_z: f64 = 0.0;
    for call in 1..=2 {
        send(&mut e, helix(true, call));
        run_path(&mut e, 10.0, |e| {
            peak = peak.max(vel(e, 0));
            peak_z = peak_z.max(vel(e, 3));
            // The result axis is the counted share of the way: Z / 500 of a circle per call.
            let turns = (call - 1) as f64 + (pos(e, 3) - 500.0 * (call - 1) as f64) / 500.0;
            assert!(
                close(pos(e, 0), circle * turns, 1e-6),
                "{} at {turns}",
                pos(e, 0)
            );
        });
        assert!(
            close(pos(&e, 0), circle * call as f64, 1e-6),
            "{}",
            pos(&e, 0)
        );
    }
    assert!(close(pos(&e, 0), 628.318, 1e-3));
    assert_eq!([pos(&e, 1), pos(&e, 2), pos(&e, 3)], [0.0, 0.0, 1000.0]);
    // The result axis's Speed is the XY speed (over the full XYZ length it would peak at
    // 314/590 of it); Z rides at 500/314.159 of it.
    assert!(close(peak, 1000.0, 1e-9), "{peak}");
    assert!(close(peak_z, 500.0 / circle * 1000.0, 1e-6), "{peak_z}");
}

#[test]
fn helix_modes_0_1_3_count_the_xyz_length() {
    let mut e = machine(4, &[1, 2, 3], 0);
    send(&mut e, helix(false, 1));
    run_path(&mut e, 10.0, |_| {});
    let length = (TAU * 50.0).hypot(500.0);
    assert!(
        close(pos(&e, 0), length, 1e-6),
        "{} vs {length}",
        pos(&e, 0)
    );
    assert_eq!(pos(&e, 3), 500.0);
}

#[test]
fn the_result_axis_speed_is_the_path_speed_and_the_components_own_limits_still_hold() {
    // The result axis asks 10 000/s; axis 2 may only do 3000/s: the path slows so that it
    // never exceeds it (issue 11 item 3), along a line where axis 2 has 0.8 of the length.
    let mut e = machine(3, &[1, 2], 0);
    ok(
        &mut e,
        Command::from(SetParameter {
            axis: 2,
            name: ParamId::MaxVelocity,
            value: 3000.0,
            lenient: false,
        }),
    );
    send(&mut e, line(&[30000.0, 40000.0]));
    let mut peak: f64 = 0.0;
    run_path(&mut e, 30.0, |e| {
        assert!(vel(e, 2) <= 3000.0 * (1.0 + 1e-9), "{}", vel(e, 2));
        peak = peak.max(vel(e, 0));
    });
    assert!(close(peak, 3000.0 / 0.8, 1e-6), "{peak}");
    assert!(close(pos(&e, 0), 50000.0, 1e-6));
    // A motion's own velocity is the result axis's speed too, as HMC_Move2DEx's dSpeed.
    send(
        &mut e,
        MoveLinearRelative {
            velocity: Some(1000.0),
            ..line(&[-30000.0, -40000.0])
        },
    );
    let mut peak: f64 = 0.0;
    run_path(&mut e, 80.0, |e| peak = peak.max(vel(e, 0)));
    assert!(close(peak, 1000.0, 1e-6), "{peak}");
    assert!(close(pos(&e, 0), 100000.0, 1e-6));
}

#[test]
fn a_group_without_result_axis_uses_its_group_parameters_as_before() {
    let mut e = machine(3, &[1, 2], 0);
    ok(&mut e, Command::from(GroupDelete { group: 1 }));
    // The former result axis is free again: it takes single-axis motion.
    send(
        &mut e,
        MoveAbsolute {
            axis: 0,
            position: 5.0,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: Default::default(),
        },
    );
    ok(&mut e, Command::from(create(1, &[1, 2], None)));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    send(&mut e, line(&[300.0, 400.0]));
    let mut peak: f64 = 0.0;
    run_path(&mut e, 30.0, |e| peak = peak.max(group(e).path_velocity));
    // The group's default path velocity (HIMC: 100).
    assert!(close(peak, 100.0, 1e-6), "{peak}");
    assert_eq!(group(&e).result_axis, None);
    assert!(close(pos(&e, 0), 5.0, 1e-9));
}

#[test]
fn the_result_axis_is_bound_like_a_member() {
    let mut e = machine(3, &[1, 2], 0);
    // IN_GROUP, and no single-axis motion: the typed error members give.
    let err = refused(
        &mut e,
        Command::from(MoveAbsolute {
            axis: 0,
            position: 5.0,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: Default::default(),
        }),
    );
    assert_eq!(err, EngineError::AxisInGroup { axis: 0, group: 1 });
    assert!(e
        .axis_status(0)
        .unwrap()
        .flags
        .contains(axes::status::AxisFlags::IN_GROUP));
    // A disabled result axis keeps the group from being enabled (as a member would).
    ok(
        &mut e,
        Command::from(axes::command::GroupDisable { group: 1 }),
    );
    ok(&mut e, Command::from(axes::command::Disable { axis: 0 }));
    let err = refused(&mut e, Command::from(GroupEnable { group: 1 }));
    assert!(
        matches!(err, EngineError::GroupMember { axis: 0, .. }),
        "{err:?}"
    );
}

#[test]
fn a_result_axis_that_is_a_member_in_another_group_or_unknown_is_refused() {
    let mut e = machine(6, &[1, 2], 0);
    // A member of the same group.
    let err = refused(&mut e, Command::from(create(2, &[3, 4], Some(3))));
    assert!(
        matches!(&err, EngineError::InvalidGroup { group: 2, reason } if reason.contains("member")),
        "{err:?}"
    );
    // A member of another group, and another group's result axis.
    for taken in [1, 0] {
        let err = refused(&mut e, Command::from(create(2, &[3, 4], Some(taken))));
        assert!(
            matches!(&err, EngineError::InvalidGroup { group: 2, reason } if reason.contains("group 1")),
            "{err:?}"
        );
    }
    // No such axis.
    let err = refused(&mut e, Command::from(create(2, &[3, 4], Some(60))));
    assert_eq!(err, EngineError::InvalidAxis { axis: 60, count: 6 });
    // Nothing was made by the refusals; a good one works.
    assert_eq!(e.snapshot().groups.len(), 1);
    ok(&mut e, Command::from(create(2, &[3, 4], Some(5))));
    assert_eq!(e.snapshot().groups[1].result_axis, Some(5));
}

#[test]
fn bad_independent_coordinates_are_refused_with_the_reason() {
    let mut e = machine(4, &[1, 2, 3], 0);
    let lines: [(&[f64], &[usize], &str); 3] = [
        (&[1.0, 2.0, 3.0], &[3], "not one of the group's 3"),
        (
            &[1.0, 2.0, 3.0],
            &[0, 1, 2],
            "every coordinate is independent",
        ),
        (&[5.0, 0.0, 0.0], &[0], "do not move"),
    ];
    let mut cases: Vec<(Command, &str)> = lines
        .iter()
        .map(|&(distance, independent, why)| {
            let c = MoveLinearRelative {
                independent: coords(independent),
                ..line(distance)
            };
            (c.into(), why)
        })
        .collect();
    cases.push((
        MoveCircularAbsolute {
            independent: coords(&[1]),
            ..arc(&[50.0, 0.0, 0.0], &[100.0, 0.0, 10.0], ArcDirection::Cw)
        }
        .into(),
        "plane has counted and independent",
    ));
    for (c, why) in cases {
        let err = refused(&mut e, c.clone());
        assert!(
            matches!(&err, EngineError::InvalidPath { group: 1, reason } if reason.contains(why)),
            "{c:?}: {err:?}"
        );
    }
    // Nothing was queued and no id used: the next motion runs alone.
    assert_eq!(group(&e).queue_used, 0);
    // A spline whose counted coordinates do not move has no shape to measure by.
    let err = refused(
        &mut e,
        spline(&[[0.0, 0.0, 5.0], [0.0, 0.0, 9.0]], &[2]).into(),
    );
    assert!(
        matches!(&err, EngineError::InvalidPath { group: 1, .. }),
        "{err:?}"
    );
    assert_eq!(group(&e).queue_used, 0);
    // A group has at most 9 coordinates: index 9 is refused when the command is read.
    let err = serde_json::from_str::<Command>(
        r#"{"type":"move_linear_relative","group":1,"distance":[1,2,3],"independent":[2,9]}"#,
    )
    .unwrap_err();
    assert!(
        err.to_string()
            .contains("group coordinates are indices 0 to 8 into the group's axes, not [2, 9]"),
        "{err}"
    );
}

#[test]
fn a_result_axis_at_its_soft_limit_stops_the_whole_group_in_error_stop() {
    // Digest 000 §6.1 (b): the result axis over a limit cancels the whole interpolation.
    let mut e = machine(3, &[1, 2], 0);
    ok(
        &mut e,
        Command::from(SetParameter {
            axis: 0,
            name: ParamId::FsLimit,
            value: 2000.0,
            lenient: false,
        }),
    );
    let id = send(&mut e, line(&[30000.0, 40000.0]));
    let n = (2.0 / e.period()).round() as u64;
    for _ in 0..n {
        e.step();
        if group(&e).state == GroupState::ErrorStop {
            break;
        }
    }
    let g = group(&e);
    assert_eq!(g.state, GroupState::ErrorStop, "{g:?}");
    assert_eq!(
        g.fault,
        Some(GroupFault::Member {
            axis: 0,
            error: ErrorKind::LimitReached
        })
    );
    assert_eq!(
        state_of(&mut e, id),
        CommandState::Error(ErrorKind::LimitReached)
    );
    // The components stopped short of their targets and come to rest.
    common::run(&mut e, 2.0);
    assert!(pos(&e, 1) < 30000.0 && pos(&e, 2) < 40000.0);
    assert_eq!((vel(&e, 1), vel(&e, 2)), (0.0, 0.0));
    assert!(
        pos(&e, 0) >= 2000.0 - 1e-6 && pos(&e, 0) < 2100.0,
        "{}",
        pos(&e, 0)
    );
}

/// HMC's result axis Speed is editable live (digest 000 §4.3; the single-axis case is TV 3):
/// Speed 1000, Accel = Decel = 1000, a 3000-unit line; at t = 2 s (position 1500) Speed := 500.
/// The path decelerates to 500 (0.5 s, 375 units), cruises (2 s, 1000 units) and stops (0.5 s,
/// 125 units): done at t = 5 s at 3000.
#[test]
fn a_live_speed_change_of_the_result_axis_changes_the_path_speed() {
    let axes = vec![
        virtual_axis(1e7, 1e9),
        virtual_axis(1e7, 1e9),
        virtual_axis(1000.0, 1000.0),
    ];
    let mut e = Engine::new(&EngineConfig {
        axes,
        ..EngineConfig::default()
    })
    .unwrap();
    for axis in 0..3 {
        ok(&mut e, Command::from(Enable { axis }));
    }
    ok(&mut e, Command::from(create(1, &[0, 1], Some(2))));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    let id = send(&mut e, line(&[3000.0, 0.0]));
    let period = e.period();
    for _ in 0..(2.0 / period).round() as u64 {
        e.step();
    }
    assert!(close(pos(&e, 0), 1500.0, 1e-6), "{}", pos(&e, 0));
    assert!(close(group(&e).path_velocity, 1000.0, 1e-9));
    ok(
        &mut e,
        Command::from(SetParameter {
            axis: 2,
            name: ParamId::Speed,
            value: 500.0,
            lenient: false,
        }),
    );
    let mut cruise = 0;
    let ticks = run_path(&mut e, 10.0, |e| {
        if close(group(e).path_velocity, 500.0, 1e-9) {
            cruise += 1;
        }
    });
    // About 2 s at the new speed.
    assert!(close(cruise as f64 * period, 2.0, 3.0 * period), "{cruise}");
    let t = 2.0 + ticks as f64 * period;
    assert!(close(t, 5.0, 3.0 * period), "{t}");
    assert!(close(pos(&e, 0), 3000.0, 1e-9));
    assert!(close(pos(&e, 2), 3000.0, 1e-6), "{}", pos(&e, 2));
    assert_eq!(state_of(&mut e, id), CommandState::Done);
    // A motion that gives its own velocity keeps it.
    let own = MoveLinearRelative {
        velocity: Some(800.0),
        ..line(&[-800.0, 0.0])
    };
    send(&mut e, own);
    let mut fastest: f64 = 0.0;
    run_path(&mut e, 10.0, |e| {
        fastest = fastest.max(group(e).path_velocity)
    });
    assert!(close(fastest, 800.0, 1e-9), "{fastest}");
}
