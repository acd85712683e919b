//! NMC's polar machine (`group_set_polar_transform`, digest 001 C3§10.5 "极坐标转换"): the group's
//! Cartesian path fed to a rotary member (θ) and a feed member (r) each tick. The members'
//! (r cos θ, r sin θ) stays on the programmed line or arc, θ is continuous across the ±π cut
//! and keeps the rotary axis's whole turns, a path through the pole is refused, the members
//! stay within their own limits near the pole, and two runs are bit-identical.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use std::f64::consts::{PI, TAU};

use axes::command::{
    ArcDirection, Command, ErrorKind, GroupJog, MoveLinearAbsolute, PositionFrame, SetPosition,
};
use axes::status::{GroupState, GroupStatus};
use axes::{Engine, EngineConfig, EngineError};
use common::{cmd, ok, refused, stepper_mm};

/// Rotary axis units (mm of the stepper) per radian: 10 rad/s at its 100 mm/s.
const UPR: f64 = 10.0;
const ROTARY_SPEED: f64 = 100.0;
const ROTARY_ACCEL: f64 = 1000.0;

/// Axis 0 turns, axis 1 feeds, group 1 of both (X, Y), enabled; the rotary axis at `theta`
/// (rad) and the feed axis at `r` before the polar transform is set.
fn machine(theta: f64, r: f64) -> Engine {
    let e = Engine::new(&EngineConfig {
        axes: (0..2).map(|_| stepper_mm()).collect(),
        ..EngineConfig::default()
    })
    .unwrap();
    let mut e = common::with_group(e, &[0, 1]);
    for (axis, position) in [(0, theta * UPR), (1, r)] {
        ok(
            &mut e,
            Command::from(SetPosition {
                axis,
                position,
                frame: PositionFrame::Both,
            }),
        );
    }
    ok(&mut e, polar_on());
    e
}

fn polar_on() -> Command {
    cmd(
        r#"{"type":"group_set_polar_transform","group":1,"rotary":0,"feed":1,"rotary_units_per_radian":10}"#,
    )
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

fn line(x: f64, y: f64) -> MoveLinearAbsolute {
    common::group_line(1, &[x, y])
}

/// The members' point: (r cos θ, r sin θ).
fn members_point(e: &Engine) -> (f64, f64, f64) {
    let theta = e.axis_status(0).unwrap().cmd_pos / UPR;
    let r = e.axis_status(1).unwrap().cmd_pos;
    (r * theta.cos(), r * theta.sin(), theta)
}

/// Step to Standby, calling `each` after every tick.
fn run(e: &mut Engine, mut each: impl FnMut(&Engine)) {
    for _ in 0..200_000 {
        e.step();
        each(e);
        if group(e).state == GroupState::Standby {
            return;
        }
    }
    panic!("still {:?}", group(e));
}

/// Both members within their own limits (100 mm/s, 1000 mm/s²).
fn within_limits(e: &Engine) {
    for a in 0..2 {
        let s = e.axis_status(a).unwrap();
        assert!(
            s.cmd_vel.abs() <= ROTARY_SPEED * (1.0 + 1e-9),
            "axis {a}: v {}",
            s.cmd_vel
        );
        assert!(
            s.cmd_acc.abs() <= ROTARY_ACCEL * (1.0 + 1e-6),
            "axis {a}: a {}",
            s.cmd_acc
        );
    }
}

#[test]
fn a_line_and_an_arc_keep_the_members_on_the_programmed_geometry() {
    let mut e = machine(0.0, 10.0);
    // The program point of θ = 0, r = 10.
    let start = group(&e).coordinates;
    assert!((start[0] - 10.0).abs() < 1e-12 && start[1].abs() < 1e-12);
    assert!(group(&e).polar);
    ok(&mut e, line(30.0, 40.0).into());
    let mut worst: f64 = 0.0;
    run(&mut e, |e| {
        within_limits(e);
        let (x, y, _) = members_point(e);
        // Distance from the line (10, 0) → (30, 40).
        let (dx, dy) = (20.0, 40.0);
        worst = worst.max(((x - 10.0) * dy - y * dx).abs() / dx.hypot(dy));
        let g = group(e);
        assert!((g.coordinates[0] - x).abs() < 1e-9 && (g.coordinates[1] - y).abs() < 1e-9);
    });
    assert!(worst < 1e-9, "off the line by {worst}");
    let (x, y, theta) = members_point(&e);
    assert!(
        (x - 30.0).abs() < 1e-9 && (y - 40.0).abs() < 1e-9,
        "({x}, {y})"
    );
    assert!((theta - 40f64.atan2(30.0)).abs() < 1e-12);
    assert!((e.axis_status(1).unwrap().cmd_pos - 50.0).abs() < 1e-9);

    // An arc about (20, 20) from (30, 40), counter-clockwise to (0, 30): the pole is outside.
    let radius = 10f64.hypot(20.0);
    ok(
        &mut e,
        common::group_arc(1, &[20.0, 20.0], &[0.0, 30.0], ArcDirection::Ccw).into(),
    );
    let mut worst: f64 = 0.0;
    run(&mut e, |e| {
        within_limits(e);
        let (x, y, _) = members_point(e);
        worst = worst.max(((x - 20.0).hypot(y - 20.0) - radius).abs());
    });
    assert!(worst < 1e-9, "off the arc by {worst}");
    let (x, y, _) = members_point(&e);
    assert!(x.abs() < 1e-9 && (y - 30.0).abs() < 1e-9, "({x}, {y})");
}

#[test]
fn theta_crosses_the_cut_continuously_and_keeps_the_whole_turns() {
    // Just below π, 3 turns up: the line to (−10, −1) crosses the negative X axis.
    let turns = 3.0 * TAU;
    let mut e = machine(turns + PI - 0.1, 10.0);
    ok(&mut e, line(-10.0, -1.0).into());
    let mut last = turns + PI - 0.1;
    run(&mut e, |e| {
        let (_, _, theta) = members_point(e);
        assert!((theta - last).abs() < 0.01, "θ jumped {last} → {theta}");
        last = theta;
    });
    let end = turns + PI + 1f64.atan2(10.0);
    assert!((last - end).abs() < 1e-12, "{last} vs {end}");

    // On the X axis at 2 turns: a radial line does not turn the rotary axis at all.
    let mut e = machine(2.0 * TAU, 10.0);
    ok(&mut e, line(20.0, 0.0).into());
    let rotary = e.axis_status(0).unwrap().cmd_pos;
    run(&mut e, |e| {
        assert_eq!(e.axis_status(0).unwrap().cmd_pos, rotary)
    });
    assert!((e.axis_status(1).unwrap().cmd_pos - 20.0).abs() < 1e-9);
}

#[test]
fn a_path_through_the_pole_is_refused_and_one_to_it_holds_the_angle() {
    let mut e = machine(0.5, 10.0);
    let through = line(-10.0 * 0.5f64.cos(), -10.0 * 0.5f64.sin());
    let err = refused(&mut e, through.into());
    assert!(matches!(err, EngineError::InvalidPath { .. }), "{err}");
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    assert_eq!(group(&e).state, GroupState::Standby);

    // Along the radius into the pole: θ stays, r goes to 0, nothing is NaN.
    ok(&mut e, line(0.0, 0.0).into());
    run(&mut e, |e| {
        let s = e.axis_status(0).unwrap();
        assert!((s.cmd_pos - 0.5 * UPR).abs() < 1e-9, "{}", s.cmd_pos);
        assert!(e.axis_status(1).unwrap().cmd_pos.is_finite());
    });
    assert_eq!(e.axis_status(1).unwrap().cmd_pos, 0.0);
    // Out of the pole: only where the rotary axis points.
    let err = refused(&mut e, line(0.0, 10.0).into());
    assert!(matches!(err, EngineError::InvalidPath { .. }), "{err}");
    ok(
        &mut e,
        line(10.0 * 0.5f64.cos(), 10.0 * 0.5f64.sin()).into(),
    );
    run(&mut e, |e| {
        assert!((e.axis_status(0).unwrap().cmd_pos - 0.5 * UPR).abs() < 1e-9);
    });
    assert!((e.axis_status(1).unwrap().cmd_pos - 10.0).abs() < 1e-9);
}

#[test]
fn near_the_pole_the_path_slows_so_the_rotary_axis_keeps_its_limits() {
    // y = 1 from x = −30 to 30: dθ/ds reaches 1 rad/mm, so at most 10 mm/s there.
    let mut e = machine(PI - 1f64.atan2(30.0), 30f64.hypot(1.0));
    ok(&mut e, line(30.0, 1.0).into());
    let mut peak: f64 = 0.0;
    run(&mut e, |e| {
        within_limits(e);
        peak = peak.max(group(e).path_velocity);
    });
    assert!(peak <= ROTARY_SPEED / UPR + 1e-9, "path speed {peak}");
    let (x, y, _) = members_point(&e);
    assert!((x - 30.0).abs() < 1e-9 && (y - 1.0).abs() < 1e-9);
}

#[test]
fn the_transform_changes_only_at_rest_and_needs_the_plane_members() {
    let mut e = machine(0.0, 10.0);
    ok(&mut e, line(20.0, 5.0).into());
    e.step();
    assert!(matches!(
        refused(&mut e, polar_on()),
        EngineError::GroupState { .. }
    ));
    let off = cmd(r#"{"type":"group_delete_polar_transform","group":1}"#);
    assert!(matches!(
        refused(&mut e, off.clone()),
        EngineError::GroupState { .. }
    ));
    let jog = GroupJog {
        group: 1,
        coordinate: 0,
        velocity: 1.0,
        coordinate_system: None,
    };
    assert!(matches!(
        refused(&mut e, jog.into()),
        EngineError::GroupState { .. }
    ));
    run(&mut e, |_| {});
    ok(&mut e, off);
    assert!(!group(&e).polar);
    // Cartesian again: the members read θ and r as coordinates.
    let c = group(&e).coordinates;
    assert_eq!(c[0], e.axis_status(0).unwrap().cmd_pos);
    assert!((c[1] - 20f64.hypot(5.0)).abs() < 1e-9);
    let other = cmd(
        r#"{"type":"group_set_polar_transform","group":1,"rotary":0,"feed":2,"rotary_units_per_radian":10}"#,
    );
    assert!(matches!(
        refused(&mut e, other),
        EngineError::InvalidGroup { .. }
    ));
    let zero = cmd(
        r#"{"type":"group_set_polar_transform","group":1,"rotary":0,"feed":1,"rotary_units_per_radian":0}"#,
    );
    assert!(matches!(
        refused(&mut e, zero),
        EngineError::InvalidPath { .. }
    ));
}

#[test]
fn two_runs_are_bit_identical() {
    let trace = || {
        let mut e = machine(PI - 0.2, 12.0);
        ok(&mut e, line(-5.0, -3.0).into());
        ok(
            &mut e,
            common::group_arc(1, &[-5.0, 0.0], &[-8.0, 0.0], ArcDirection::Cw).into(),
        );
        let mut out = Vec::new();
        run(&mut e, |e| {
            out.push((
                e.axis_status(0).unwrap().cmd_pos.to_bits(),
                e.axis_status(1).unwrap().cmd_pos.to_bits(),
            ));
        });
        out
    };
    let first = trace();
    assert!(first.len() > 10);
    assert_eq!(first, trace());
}
