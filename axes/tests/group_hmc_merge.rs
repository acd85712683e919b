//! HMC merge from the result axis (digest 000 §3.4, §4.3, §6.7: "for interpolations the
//! result axis's Merge value applies"), HMC's merge angles (TV 38) and the spherical arc
//! (TV 20), on the engine's virtual clock.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use std::f64::consts::PI;

use axes::command::{
    ArcDirection, CircleMode, Command, Enable, ErrorKind, GroupBufferMode, GroupCreate,
    GroupEnable, GroupParameter, GroupSetParameter, MoveCircularAbsolute, MoveLinearRelative,
    MoveSpline, SetParameter, TransitionMode,
};
use axes::config::AxisConfig;
use axes::status::{GroupState, GroupStatus};
use axes::{Engine, EngineConfig, ParamId};
use common::{ok, refused};

/// The result axis's path limits.
const SPEED: f64 = 50.0;
const ACCEL: f64 = 1000.0;

/// A virtual axis on finite travel with `speed` and `accel` (= decel).
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

/// Group 1 of the first `members` axes (fast: their own limits never bind) with the next
/// axis as its result axis ([`SPEED`], [`ACCEL`]), its `merge` set to `merge`.
fn machine(members: u16, merge: f64) -> Engine {
    let axes = (0..=members)
        .map(|a| {
            if a == members {
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
    for axis in 0..=members {
        ok(&mut e, Command::from(Enable { axis }));
    }
    ok(
        &mut e,
        Command::from(GroupCreate {
            group: 1,
            axes: (0..members).collect(),
            queue_capacity: None,
            lookahead: None,
            result_axis: Some(members),
            orientation: Default::default(),
        }),
    );
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    ok(
        &mut e,
        Command::from(SetParameter {
            axis: members,
            name: ParamId::Merge,
            value: merge,
            lenient: false,
        }),
    );
    e
}

/// HMC_Move2D: a relative line on the result axis's limits, buffered (the default).
fn line(distance: &[f64]) -> Command {
    Command::from(MoveLinearRelative {
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
    })
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

/// Run the path to its end; the lowest path velocity between the first and the last tick at
/// [`SPEED`] (both lines cruise there): the velocity at the junction.
fn junction_velocity(e: &mut Engine) -> f64 {
    let mut seen = Vec::new();
    for _ in 0..100_000 {
        e.step();
        let g = group(e);
        seen.push(g.path_velocity);
        if g.state == GroupState::Standby {
            let cruise = |v: &f64| *v >= SPEED * (1.0 - 1e-9);
            let first = seen.iter().position(cruise).unwrap();
            let last = seen.iter().rposition(cruise).unwrap();
            return seen[first..=last]
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min);
        }
    }
    panic!("the path did not end");
}

/// Two lines, the second turned by `degrees` from the first, under `merge`.
fn corner(merge: f64, degrees: f64) -> f64 {
    let mut e = machine(2, merge);
    let (s, c) = degrees.to_radians().sin_cos();
    ok(&mut e, line(&[100.0, 0.0]));
    ok(&mut e, line(&[100.0 * c, 100.0 * s]));
    junction_velocity(&mut e)
}

/// One tick's change of the path velocity at [`ACCEL`]: how close the slowest tick comes to
/// the junction velocity.
const ONE_TICK: f64 = ACCEL * 1e-3;

#[test]
fn the_result_axis_merge_joins_buffered_lines_without_a_stop() {
    // Merge 0 (off): each block finishes on its own.
    assert!(corner(0.0, 16.7) < ONE_TICK);
    // Merge 1–4 with equal speeds: the junction at the blocks' speed. A 16.7° corner (atan 0.3)
    // is below the decel angle π/6: unrestricted (TV 38).
    for merge in [1.0, 2.0, 3.0, 4.0] {
        let v = corner(merge, 16.7);
        assert!((v - SPEED).abs() <= ONE_TICK, "merge {merge}: {v}");
    }
}

#[test]
fn tv38_the_default_merge_angles_scale_the_junction_velocity() {
    // k = (θ − stop)/(decel − stop) with π/6, π/2: 45° → 0.75, 63.43° → 0.443, 90° → 0.
    for (degrees, k) in [
        (45.0, 0.75),
        (63.43, (63.43 - 90.0) / (30.0 - 90.0)),
        (90.0, 0.0),
    ] {
        let v = corner(1.0, degrees);
        assert!((v - k * SPEED).abs() <= ONE_TICK, "{degrees}°: {v}, k {k}");
    }
}

#[test]
fn tv38_merge_angles_beyond_hmc_bounds_are_refused() {
    let mut e = machine(2, 1.0);
    let set = |name, value| {
        Command::from(GroupSetParameter {
            group: 1,
            name,
            value,
        })
    };
    // HMC_SetMergeAngle(7, 0.6, 1.0): 0.6 > π/6.
    let err = refused(&mut e, set(GroupParameter::CornerSlowAngle, 0.6));
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    let err = refused(
        &mut e,
        set(GroupParameter::CornerStopAngle, PI / 2.0 + 0.01),
    );
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    // (7, 0.5, 0.4): the decel angle above the stop angle.
    ok(&mut e, set(GroupParameter::CornerSlowAngle, 0.5));
    let err = refused(&mut e, set(GroupParameter::CornerStopAngle, 0.4));
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    // A group without a result axis is not HMC's: only the planner's 0 ≤ slow ≤ stop ≤ π.
    let mut free = common::with_group(
        Engine::new(&EngineConfig {
            axes: (0..2).map(|_| common::stepper_mm()).collect(),
            ..EngineConfig::default()
        })
        .unwrap(),
        &[0, 1],
    );
    ok(&mut free, set(GroupParameter::CornerSlowAngle, 0.6));
}

#[test]
fn a_spline_does_not_merge() {
    // Digest 000 §3.4: splines are not mergeable; the line before one ends at rest.
    let mut e = machine(2, 1.0);
    ok(&mut e, line(&[100.0, 0.0]));
    ok(
        &mut e,
        Command::from(MoveSpline {
            relative: true,
            ..common::group_spline(1, vec![vec![50.0, 5.0], vec![100.0, 0.0]])
        }),
    );
    assert!(junction_velocity(&mut e) < ONE_TICK);
}

#[test]
fn tv20_a_spherical_arc_through_three_points_ends_on_its_end_and_feeds_the_arc_length() {
    // HMC_MoveSpherical(0,1,2,3, 0,1000,−1000, 1000,0,−1000): (0,0,0) → via (0,1000,−1000) →
    // (1000,0,−1000). The three points are an equilateral triangle: the circle's centre is
    // its centroid, radius 1000·√2/√3, in the plane x + y + z = 0, and the arc through the
    // middle point sweeps 240°.
    let mut e = machine(3, 0.0);
    ok(
        &mut e,
        Command::from(MoveCircularAbsolute {
            mode: CircleMode::Border,
            velocity: Some(1000.0),
            ..common::group_arc(
                1,
                &[0.0, 1000.0, -1000.0],
                &[1000.0, 0.0, -1000.0],
                ArcDirection::Ccw,
            )
        }),
    );
    let center = [1000.0 / 3.0, 1000.0 / 3.0, -2000.0 / 3.0];
    let radius = 1000.0 * (2.0f64 / 3.0).sqrt();
    let (mut off_plane, mut off_circle) = (0.0f64, 0.0f64);
    let mut near_via = f64::INFINITY;
    for _ in 0..1_000_000 {
        e.step();
        let g = group(&e);
        let p = g.position();
        off_plane = off_plane.max((p[0] + p[1] + p[2]).abs());
        let r =
            ((p[0] - center[0]).powi(2) + (p[1] - center[1]).powi(2) + (p[2] - center[2]).powi(2))
                .sqrt();
        off_circle = off_circle.max((r - radius).abs());
        near_via =
            near_via.min((p[0].powi(2) + (p[1] - 1000.0).powi(2) + (p[2] + 1000.0).powi(2)).sqrt());
        if g.state == GroupState::Standby {
            break;
        }
    }
    assert_eq!(group(&e).position()[..3], [1000.0, 0.0, -1000.0]);
    assert!(
        off_plane < 1e-9 && off_circle < 1e-9,
        "{off_plane} {off_circle}"
    );
    // Within one tick's travel (1000 units/s × 1 ms) of the middle point.
    assert!(near_via <= 1.0, "{near_via}");
    let travelled = e.axis_status(3).unwrap().cmd_pos;
    let arc = radius * 4.0 * PI / 3.0;
    assert!((travelled - arc).abs() < 1e-6, "{travelled} vs {arc}");
}

fn set(name: GroupParameter, value: f64) -> Command {
    Command::from(GroupSetParameter {
        group: 1,
        name,
        value,
    })
}

/// Run the path to its end; the lowest path velocity while the first coordinate is within
/// half a unit of `x`.
fn velocity_near(e: &mut Engine, x: f64) -> f64 {
    let mut lowest = f64::INFINITY;
    for _ in 0..100_000 {
        e.step();
        let g = group(e);
        if (g.coordinates[0] - x).abs() < 0.5 {
            lowest = lowest.min(g.path_velocity);
        }
        if g.state == GroupState::Standby {
            return lowest;
        }
    }
    panic!("the path did not end");
}

#[test]
fn a_merge_the_next_tiny_move_cannot_take_is_a_normal_stop() {
    // Manual §10.6 (8): "如 Merge 的下条指令为 HMC_MoveEx(1) 时，Merge 无效，正常减速". From 50
    // the path needs 50²/(2·1000) = 1.25 to stop: a next move of 1 cannot take the merge
    // velocity, so the first line decelerates to rest at its end (not to √2000 ≈ 44.7).
    let mut e = machine(2, 1.0);
    ok(&mut e, line(&[100.0, 0.0]));
    ok(&mut e, line(&[1.0, 0.0]));
    let v = velocity_near(&mut e, 100.0);
    assert!(v < 1e-9, "{v}");
    // Deep look-ahead reaches it when a long move follows the tiny one: no stop.
    let mut e = machine(2, 1.0);
    for d in [100.0, 1.0, 100.0] {
        ok(&mut e, line(&[d, 0.0]));
    }
    let v = junction_velocity(&mut e);
    assert!((v - SPEED).abs() <= ONE_TICK, "{v}");
    // A next move long enough to stop in: the merge holds.
    let mut e = machine(2, 1.0);
    ok(&mut e, line(&[100.0, 0.0]));
    ok(&mut e, line(&[2.0, 0.0]));
    assert!(velocity_near(&mut e, 100.0) > SPEED - ONE_TICK);
}

#[test]
fn the_speed_tolerance_ratio_passes_a_corner_whose_factor_is_within_it_at_full_speed() {
    // HMC_SetMergeSpeedTolerRatio (manual §4.4.7.6): 45° with the default angles is k = 0.75
    // (TV 38). A ratio of 0.3 suppresses that dip; 0.2 does not; 63.43° (k 0.443) stays.
    for (ratio, degrees, k) in [
        (0.3, 45.0, 1.0),
        (0.2, 45.0, 0.75),
        (0.3, 63.43, (63.43 - 90.0) / (30.0 - 90.0)),
    ] {
        let mut e = machine(2, 1.0);
        ok(&mut e, set(GroupParameter::MergeSpeedTolerance, ratio));
        assert_eq!(group(&e).merge_speed_tolerance, ratio);
        let (s, c) = f64::to_radians(degrees).sin_cos();
        ok(&mut e, line(&[100.0, 0.0]));
        ok(&mut e, line(&[100.0 * c, 100.0 * s]));
        let v = junction_velocity(&mut e);
        assert!((v - k * SPEED).abs() <= ONE_TICK, "{ratio} {degrees}°: {v}");
    }
}

#[test]
fn move3d_lines_do_not_merge_at_either_end() {
    // HMC_Move3D (manual §4.3.1.5–4.3.1.8): "本指令目前暂不支持 merge 功能". A front-end marks
    // its lines `mergeable` 0; MoveND lines on the same axes (1) merge.
    let mut e = machine(3, 1.0);
    assert!(group(&e).mergeable);
    ok(&mut e, line(&[100.0, 0.0, 0.0]));
    ok(&mut e, line(&[100.0, 0.0, 0.0]));
    assert!((junction_velocity(&mut e) - SPEED).abs() <= ONE_TICK);
    let mut e = machine(3, 1.0);
    ok(&mut e, set(GroupParameter::Mergeable, 0.0));
    assert!(!group(&e).mergeable);
    ok(&mut e, line(&[100.0, 0.0, 0.0]));
    ok(&mut e, line(&[100.0, 0.0, 0.0]));
    // Back to MoveND: it does not merge into the Move3D line before it either.
    ok(&mut e, set(GroupParameter::Mergeable, 1.0));
    ok(&mut e, line(&[100.0, 0.0, 0.0]));
    // Each line cruises, then comes down to (almost) rest: three dips.
    let mut stops = 0;
    let mut cruised = false;
    for _ in 0..100_000 {
        e.step();
        let g = group(&e);
        if g.path_velocity >= SPEED * (1.0 - 1e-9) {
            cruised = true;
        } else if cruised && g.path_velocity < ONE_TICK {
            stops += 1;
            cruised = false;
        }
        if g.state == GroupState::Standby {
            break;
        }
    }
    assert_eq!(stops, 3, "each of the three lines ends at rest");
}

#[test]
fn merge_parameters_out_of_range_or_without_a_result_axis_are_refused() {
    let mut e = machine(2, 1.0);
    for (name, value) in [
        (GroupParameter::MergeSpeedTolerance, 1.5),
        (GroupParameter::MergeSpeedTolerance, -0.1),
        (GroupParameter::MergeSpeedTolerance, f64::NAN),
        (GroupParameter::Mergeable, 0.5),
    ] {
        let err = refused(&mut e, set(name, value));
        assert_eq!(err.kind(), ErrorKind::InvalidArgument, "{name:?} {value}");
    }
    assert_eq!(group(&e).merge_speed_tolerance, 0.0);
    let mut free = common::with_group(
        Engine::new(&EngineConfig {
            axes: (0..2).map(|_| common::stepper_mm()).collect(),
            ..EngineConfig::default()
        })
        .unwrap(),
        &[0, 1],
    );
    let err = refused(&mut free, set(GroupParameter::MergeSpeedTolerance, 0.1));
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    assert!(!group(&free).mergeable);
}
