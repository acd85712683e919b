//! Group frames and move protection (issue 11 item 1): HIMC's coordinate transforms and
//! selection (digest 004 §2.7, TV 56–57), arcs in a rotated workpiece frame, NMC's rotary and
//! XYZA transforms (digest 001 S-TRANS-ROTATE, S-TRANS-XYZA), NMC's interference protection
//! between two groups (`SetMvProtect` modes 0 and 1), and the bad inputs.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    ArcDirection, Command, CoordinateSystem, GroupAxisMove, GroupBufferMode, GroupCreate,
    GroupDeleteTransform, GroupEnable, GroupJog, GroupSetCoordinateSystem,
    GroupSetCoordinateTransform, GroupSetRotaryTransform, GroupSetXyzaTransform, GroupWaitPosition,
    MoveCircularAbsolute, MoveLinearAbsolute, MoveProtectionDisable, MoveProtectionEnable,
    ProtectionMode, TransitionMode,
};
use axes::status::{GroupState, GroupStatus, InterferenceStatus};
use axes::{Engine, EngineError};
use common::{engine_with, ok, refused, stepper_mm};

fn machine(axes: usize, members: &[u16]) -> Engine {
    common::with_group(
        engine_with((0..axes).map(|_| stepper_mm()).collect()),
        members,
    )
}

fn cs(s: &str) -> CoordinateSystem {
    s.parse().unwrap()
}

fn set_pose(e: &mut Engine, frame: &str, pose: [f64; 6]) {
    ok(
        e,
        Command::from(GroupSetCoordinateTransform {
            group: 1,
            frame: cs(frame),
            pose,
        }),
    );
}

fn select(e: &mut Engine, system: &str) {
    ok(
        e,
        Command::from(GroupSetCoordinateSystem {
            group: 1,
            coordinate_system: cs(system),
        }),
    );
}

fn line_in(group: u16, position: &[f64], system: Option<&str>) -> MoveLinearAbsolute {
    MoveLinearAbsolute {
        coordinate_system: system.map(cs),
        ..common::group_line(group, position)
    }
}

fn relative(distance: &[f64]) -> axes::command::MoveLinearRelative {
    axes::command::MoveLinearRelative {
        group: 1,
        distance: distance.to_vec(),
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: Default::default(),
        transition: Default::default(),
        user_segment: None,
        independent: Default::default(),
        coordinate_system: None,
    }
}

fn group(e: &Engine, id: u16) -> GroupStatus {
    e.group_status(id).unwrap()
}

fn pos(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

/// Step until every group is in Standby, calling `each` after every tick.
fn run_all(e: &mut Engine, max_s: f64, mut each: impl FnMut(&Engine)) {
    let n = (max_s / e.period()).round() as u64;
    for _ in 0..n {
        e.step();
        each(e);
        if e.snapshot()
            .groups
            .iter()
            .all(|g| g.state == GroupState::Standby)
        {
            return;
        }
    }
    panic!("not at rest after {max_s} s: {:?}", e.snapshot().groups);
}

#[test]
fn tv56_a_line_in_the_pcs_lands_on_the_rotated_and_shifted_machine_point() {
    // Digest 004 TV 56: SetGrpCoordTrans(0, CS_PCS, {400, 200, 0, 0, 0, 45});
    // SetGrpCoordSys(0, CS_PCS); LineAbs2D(0, 10, 10) → MCS (400, 214.142136).
    let mut e = machine(2, &[0, 1]);
    set_pose(&mut e, "pcs", [400.0, 200.0, 0.0, 0.0, 0.0, 45.0]);
    select(&mut e, "pcs");
    ok(&mut e, Command::from(line_in(1, &[10.0, 10.0], None)));
    run_all(&mut e, 10.0, |_| {});
    assert!((pos(&e, 0) - 400.0).abs() < 1e-6, "x {}", pos(&e, 0));
    assert!((pos(&e, 1) - 214.142136).abs() < 1e-6, "y {}", pos(&e, 1));
    let g = group(&e, 1);
    assert_eq!(g.coordinate_system, cs("pcs"));
    assert!((g.frame_position()[0] - 10.0).abs() < 1e-9);
    assert!((g.frame_position()[1] - 10.0).abs() < 1e-9);
    assert!((g.position()[0] - 400.0).abs() < 1e-6);
    // TV 57: GetGrpCoordTrans(0, CS_PCS) returns the pose exactly as set.
    assert_eq!(
        e.groups().get(1).unwrap().coordinate_transform(cs("pcs")),
        Some([400.0, 200.0, 0.0, 0.0, 0.0, 45.0])
    );
}

#[test]
fn a_move_names_its_own_system_and_the_default_stays_machine_coordinates() {
    let mut e = machine(2, &[0, 1]);
    set_pose(&mut e, "wcs3", [5.0, -5.0, 0.0, 0.0, 0.0, 90.0]);
    // No selection: machine coordinates, as before frames existed.
    ok(&mut e, Command::from(line_in(1, &[10.0, 20.0], None)));
    run_all(&mut e, 5.0, |_| {});
    assert!((pos(&e, 0) - 10.0).abs() < 1e-9 && (pos(&e, 1) - 20.0).abs() < 1e-9);
    // WCS3 rotated 90° about Z, shifted (5, −5): (10, 0) → (5, 5).
    ok(
        &mut e,
        Command::from(line_in(1, &[10.0, 0.0], Some("wcs3"))),
    );
    run_all(&mut e, 5.0, |_| {});
    assert!((pos(&e, 0) - 5.0).abs() < 1e-9, "x {}", pos(&e, 0));
    assert!((pos(&e, 1) - 5.0).abs() < 1e-9, "y {}", pos(&e, 1));
    assert_eq!(group(&e, 1).coordinate_system, CoordinateSystem::MCS);
    // A relative move's distance is turned with the frame: (10, 0) in WCS3 is (0, 10).
    ok(
        &mut e,
        Command::from(axes::command::MoveLinearRelative {
            coordinate_system: Some(cs("wcs3")),
            ..relative(&[10.0, 0.0])
        }),
    );
    run_all(&mut e, 5.0, |_| {});
    assert!((pos(&e, 0) - 5.0).abs() < 1e-9, "x {}", pos(&e, 0));
    assert!((pos(&e, 1) - 15.0).abs() < 1e-9, "y {}", pos(&e, 1));
    // The chain: OFFSET ∘ WCS3 ∘ PCS.
    set_pose(&mut e, "offset", [1.0, 2.0, 0.0, 0.0, 0.0, 0.0]);
    set_pose(&mut e, "pcs", [10.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    ok(
        &mut e,
        Command::from(line_in(1, &[0.0, 0.0], Some("offset|wcs3|pcs"))),
    );
    run_all(&mut e, 5.0, |_| {});
    // PCS (0,0) → WCS3 (10, 0) → OFFSET (5, 5) → MCS (6, 7).
    assert!((pos(&e, 0) - 6.0).abs() < 1e-9, "x {}", pos(&e, 0));
    assert!((pos(&e, 1) - 7.0).abs() < 1e-9, "y {}", pos(&e, 1));
}

#[test]
fn an_arc_in_a_wcs_rolled_about_x_runs_in_the_machine_xz_plane() {
    let mut e = machine(3, &[0, 1, 2]);
    // Roll 90° about X: (x, y, z) ↦ (x, −z, y), then + (10, 20, 5).
    set_pose(&mut e, "wcs1", [10.0, 20.0, 5.0, 90.0, 0.0, 0.0]);
    select(&mut e, "wcs1");
    ok(&mut e, Command::from(line_in(1, &[20.0, 0.0, 0.0], None)));
    run_all(&mut e, 5.0, |_| {});
    assert!((pos(&e, 0) - 30.0).abs() < 1e-9);
    assert!((pos(&e, 1) - 20.0).abs() < 1e-9);
    assert!((pos(&e, 2) - 5.0).abs() < 1e-9);
    let arc = MoveCircularAbsolute {
        coordinate_system: None,
        ..common::group_arc(1, &[0.0, 0.0, 0.0], &[0.0, 20.0, 0.0], ArcDirection::Ccw)
    };
    ok(&mut e, Command::from(arc));
    let mut ticks = 0;
    run_all(&mut e, 5.0, |e| {
        ticks += 1;
        let (x, y, z) = (pos(e, 0), pos(e, 1), pos(e, 2));
        // On the machine circle about (10, 20, 5) of radius 20 in the plane y = 20.
        assert!((y - 20.0).abs() < 1e-9, "y {y}");
        let r = ((x - 10.0).powi(2) + (z - 5.0).powi(2)).sqrt();
        assert!((r - 20.0).abs() < 1e-6, "r {r}");
        assert!(
            z >= 5.0 - 1e-9 && x >= 10.0 - 1e-9,
            "({x}, {z}) left the quarter"
        );
    });
    assert!(ticks > 100);
    assert!((pos(&e, 0) - 10.0).abs() < 1e-9, "x {}", pos(&e, 0));
    assert!((pos(&e, 1) - 20.0).abs() < 1e-9);
    assert!((pos(&e, 2) - 25.0).abs() < 1e-9, "z {}", pos(&e, 2));
    let g = group(&e, 1);
    for (got, want) in g.frame_position().iter().zip([0.0, 20.0, 0.0]) {
        assert!((got - want).abs() < 1e-9, "{:?}", g.frame_position());
    }
}

#[test]
fn s_trans_rotate_the_table_turns_between_segments_and_later_points_follow_it() {
    // Digest 001 S-TRANS-ROTATE: CrdSetTransRotate(crd, 3, 2π/10000, 0, 15000) with
    // −90° table moves between segments; here 10 units per turn and the centre (0, 15) mm.
    let mut e = machine(4, &[0, 1]);
    ok(
        &mut e,
        Command::from(GroupSetRotaryTransform {
            group: 1,
            rotary_axis: 3,
            rad_per_unit: std::f64::consts::TAU / 10.0,
            center: [0.0, 15.0],
            plane: None,
        }),
    );
    select(&mut e, "rotary");
    ok(&mut e, Command::from(line_in(1, &[50.0, 0.0], None)));
    ok(
        &mut e,
        Command::from(GroupAxisMove {
            group: 1,
            axis: 3,
            position: -2.5,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
        }),
    );
    ok(
        &mut e,
        Command::from(GroupWaitPosition {
            group: 1,
            axis: 3,
            position: -2.5,
            tolerance: Some(1e-9),
            timeout: None,
            condition: Default::default(),
            source: Default::default(),
        }),
    );
    ok(&mut e, Command::from(line_in(1, &[50.0, 30.0], None)));
    let mut first_end = None;
    run_all(&mut e, 20.0, |e| {
        if first_end.is_none() && (pos(e, 3) + 1e-9) < 0.0 {
            first_end = Some((pos(e, 0), pos(e, 1)));
        }
    });
    // Table at 0: the first point is where it is programmed.
    let (x0, y0) = first_end.unwrap();
    assert!((x0 - 50.0).abs() < 1e-9 && y0.abs() < 1e-9, "({x0}, {y0})");
    // Table at −90°: (50, 30) − c = (50, 15) turns to (15, −50); + c = (15, −35).
    assert!((pos(&e, 3) + 2.5).abs() < 1e-9);
    assert!((pos(&e, 0) - 15.0).abs() < 1e-9, "x {}", pos(&e, 0));
    assert!((pos(&e, 1) + 35.0).abs() < 1e-9, "y {}", pos(&e, 1));
    // The status shows the point in the workpiece frame at the table's angle.
    let g = group(&e, 1);
    assert!((g.frame_position()[0] - 50.0).abs() < 1e-9);
    assert!((g.frame_position()[1] - 30.0).abs() < 1e-9);
    ok(&mut e, Command::from(GroupDeleteTransform { group: 1 }));
    assert_eq!(group(&e, 1).coordinate_system, CoordinateSystem::MCS);
}

#[test]
fn s_trans_xyza_keeps_the_tool_tip_on_the_programmed_point_when_a_turns() {
    // Digest 001 S-TRANS-XYZA: pulse2Rad = 2π/288000 and the tool offset from
    // CrdSetXYZAToolCalc(crd, π/3, −3687, −9494); here in mm with 288 units per turn.
    let mut e = machine(4, &[0, 1, 2, 3]);
    let (tx, ty) =
        path::frames::xyza_tool_offset(std::f64::consts::FRAC_PI_3, -3.687, -9.494).unwrap();
    let rad = std::f64::consts::TAU / 288.0;
    ok(
        &mut e,
        Command::from(GroupSetXyzaTransform {
            group: 1,
            rad_per_unit: rad,
            tool: [tx, ty],
        }),
    );
    // A = 48 units = 60°, the measured turn: the tip moved by (−3.687, −9.494), so the
    // machine XY goes the other way.
    ok(
        &mut e,
        Command::from(line_in(1, &[10.0, 20.0, 3.0, 48.0], Some("xyza"))),
    );
    select(&mut e, "xyza");
    run_all(&mut e, 10.0, |_| {});
    assert!(
        (pos(&e, 0) - (10.0 + 3.687)).abs() < 1e-9,
        "x {}",
        pos(&e, 0)
    );
    assert!(
        (pos(&e, 1) - (20.0 + 9.494)).abs() < 1e-9,
        "y {}",
        pos(&e, 1)
    );
    assert!((pos(&e, 2) - 3.0).abs() < 1e-9);
    assert!((pos(&e, 3) - 48.0).abs() < 1e-9);
    let g = group(&e, 1);
    assert!((g.frame_position()[0] - 10.0).abs() < 1e-9);
    assert!((g.frame_position()[1] - 20.0).abs() < 1e-9);
    // An arc with A constant is moved whole; one that turns A is refused.
    let flat = MoveCircularAbsolute {
        coordinate_system: Some(cs("xyza")),
        ..common::group_arc(
            1,
            &[0.0, 20.0, 3.0, 48.0],
            &[-10.0, 20.0, 3.0, 48.0],
            ArcDirection::Ccw,
        )
    };
    ok(&mut e, Command::from(flat));
    run_all(&mut e, 10.0, |_| {});
    assert!(
        (pos(&e, 0) - (-10.0 + 3.687)).abs() < 1e-9,
        "x {}",
        pos(&e, 0)
    );
    let turning = MoveCircularAbsolute {
        coordinate_system: Some(cs("xyza")),
        ..common::group_arc(
            1,
            &[0.0, 20.0, 3.0, 48.0],
            &[10.0, 20.0, 3.0, 0.0],
            ArcDirection::Ccw,
        )
    };
    let err = refused(&mut e, Command::from(turning));
    assert!(err.to_string().contains("keeps A constant"), "{err}");
}

/// Two one-axis groups on a common rail: group 1 is axis 0, group 2 is axis 1; the distance is
/// 100 − x0 + x1 (group 1 closes moving +, group 2 moving −).
fn rail() -> Engine {
    with_group_2(machine(2, &[0]), 1)
}

/// `e` with group 2 made of axis `axis`, enabled.
fn with_group_2(mut e: Engine, axis: u16) -> Engine {
    ok(
        &mut e,
        Command::from(GroupCreate {
            group: 2,
            axes: vec![axis],
            queue_capacity: None,
            lookahead: None,
            result_axis: None,
            orientation: Default::default(),
        }),
    );
    ok(&mut e, Command::from(GroupEnable { group: 2 }));
    e
}

fn protection(mode: ProtectionMode) -> MoveProtectionEnable {
    MoveProtectionEnable {
        protection: 0,
        groups: [1, 2],
        axes: [0, 0],
        move_direction: [1, -1],
        origin_distance: 100.0,
        protection_distance: 20.0,
        mode,
        stop_group: None,
        safe_wait_position: None,
        retreat_velocity: None,
        retreat_acceleration: None,
    }
}

fn distance(e: &Engine) -> f64 {
    100.0 - pos(e, 0) + pos(e, 1)
}

#[test]
fn mode_0_both_groups_stop_before_closing_below_the_protection_distance() {
    let mut e = rail();
    assert_eq!(group(&e, 1).interference, InterferenceStatus::NotEnabled);
    ok(&mut e, Command::from(protection(ProtectionMode::BothStop)));
    e.step();
    assert_eq!(group(&e, 1).interference, InterferenceStatus::Clear);
    assert!((group(&e, 2).interference_distance - 100.0).abs() < 1e-9);
    ok(&mut e, Command::from(line_in(1, &[200.0], None)));
    ok(&mut e, Command::from(line_in(2, &[-200.0], None)));
    let mut closest = f64::INFINITY;
    let mut saw_interference = false;
    run_all(&mut e, 10.0, |e| {
        closest = closest.min(distance(e));
        saw_interference |= group(e, 1).interference == InterferenceStatus::Interference;
    });
    assert!(saw_interference);
    assert!(closest >= 20.0, "closed to {closest}");
    // They stopped because of each other, not far away: within a few braking distances.
    assert!(closest < 35.0, "stopped at {closest}");
    assert!(pos(&e, 0) < 200.0 && pos(&e, 1) > -200.0);
    // A move away is free; a move toward is stopped again.
    ok(&mut e, Command::from(line_in(2, &[30.0], None)));
    run_all(&mut e, 10.0, |_| {});
    assert!((pos(&e, 1) - 30.0).abs() < 1e-9);
    assert_eq!(group(&e, 1).interference, InterferenceStatus::Clear);
    ok(
        &mut e,
        Command::from(MoveProtectionDisable { protection: 0 }),
    );
    e.step();
    assert_eq!(group(&e, 1).interference, InterferenceStatus::NotEnabled);
}

#[test]
fn mode_1_the_stop_group_retreats_and_the_other_finishes_its_move() {
    let mut e = rail();
    ok(
        &mut e,
        Command::from(MoveProtectionEnable {
            stop_group: Some(2),
            safe_wait_position: Some(80.0),
            retreat_velocity: Some(50.0),
            retreat_acceleration: Some(500.0),
            ..protection(ProtectionMode::Retreat)
        }),
    );
    ok(&mut e, Command::from(line_in(1, &[150.0], None)));
    ok(&mut e, Command::from(line_in(2, &[-200.0], None)));
    let mut closest = f64::INFINITY;
    let mut retreated = false;
    run_all(&mut e, 20.0, |e| {
        closest = closest.min(distance(e));
        retreated |= e.axis_status(1).unwrap().cmd_vel > 0.0;
    });
    assert!(retreated, "group 2 never moved back");
    assert!(closest >= 20.0, "closed to {closest}");
    assert!(
        (pos(&e, 0) - 150.0).abs() < 1e-9,
        "group 1 at {}",
        pos(&e, 0)
    );
    assert!(
        (pos(&e, 1) - 80.0).abs() < 1e-9,
        "group 2 at {}",
        pos(&e, 1)
    );
    assert_eq!(group(&e, 2).interference, InterferenceStatus::Clear);
    // With group 2 already waiting at its safe position, group 1 halts short of it and stays
    // halted (its queue kept) rather than creeping on.
    ok(&mut e, Command::from(line_in(1, &[200.0], None)));
    for _ in 0..3000 {
        e.step();
        assert!(distance(&e) >= 20.0, "closed to {}", distance(&e));
    }
    let g = group(&e, 1);
    assert_eq!(g.state, GroupState::Halted);
    assert_eq!(g.queue_used, 1);
    assert_eq!(g.interference, InterferenceStatus::Interference);
    assert!((pos(&e, 1) - 80.0).abs() < 1e-9);
}

/// Group 1 is (x, y) on axes 0 and 1, guarded on x; group 2 is axis 2: the distance is
/// 100 − x + z.
fn turning_rail() -> Engine {
    with_group_2(machine(3, &[0, 1]), 2)
}

/// Issue 11 item 1 defect: a path moving across (not toward) the other group, whose queued
/// path turns toward it within its braking distance, counted no reserve until it turned,
/// and then came closer than the protection distance by most of a braking distance. The
/// guard now measures the reserve along the queued path itself.
#[test]
fn a_path_that_turns_toward_the_other_group_stops_before_coming_too_close() {
    let mut e = turning_rail();
    // x to 79 first: the distance is 21, 1 above the protection distance.
    ok(&mut e, Command::from(line_in(1, &[79.0, 0.0], None)));
    run_all(&mut e, 10.0, |_| {});
    ok(&mut e, Command::from(protection(ProtectionMode::BothStop)));
    // Across at full speed, then a rounded corner toward +x.
    ok(
        &mut e,
        Command::from(MoveLinearAbsolute {
            velocity: Some(100.0),
            buffer_mode: GroupBufferMode::BlendingLow,
            transition: TransitionMode::CornerDistance(5.0),
            ..line_in(1, &[79.0, 60.0], None)
        }),
    );
    ok(
        &mut e,
        Command::from(MoveLinearAbsolute {
            velocity: Some(100.0),
            buffer_mode: GroupBufferMode::BlendingLow,
            ..line_in(1, &[150.0, 60.0], None)
        }),
    );
    let mut closest = f64::INFINITY;
    let mut saw_interference = false;
    run_all(&mut e, 10.0, |e| {
        closest = closest.min(100.0 - pos(e, 0) + pos(e, 2));
        saw_interference |= group(e, 1).interference == InterferenceStatus::Interference;
    });
    assert!(saw_interference);
    assert!(closest >= 20.0, "closed to {closest}");
    // Stopped by the protection near its corner, not at the end of its path.
    assert!(
        pos(&e, 0) < 80.0 && pos(&e, 1) > 50.0,
        "at {} {}",
        pos(&e, 0),
        pos(&e, 1)
    );
}

/// Issue 11 item 1 defect: protections did not watch group jogs. A jog toward the other
/// group now stops at the protection distance, and a jog away is free.
#[test]
fn a_jog_toward_the_other_group_stops_before_the_protection_distance() {
    let mut e = rail();
    ok(&mut e, Command::from(protection(ProtectionMode::BothStop)));
    ok(
        &mut e,
        Command::from(GroupJog {
            group: 1,
            coordinate: 0,
            velocity: 80.0,
            coordinate_system: None,
        }),
    );
    let mut closest = f64::INFINITY;
    let mut saw_interference = false;
    for _ in 0..5000 {
        e.step();
        closest = closest.min(distance(&e));
        saw_interference |= group(&e, 1).interference == InterferenceStatus::Interference;
    }
    assert!(saw_interference);
    assert!(closest >= 20.0, "closed to {closest}");
    assert!(closest < 25.0, "stopped at {closest}");
    assert_eq!(group(&e, 1).state, GroupState::Standby);
    assert_eq!(e.axis_status(0).unwrap().cmd_vel, 0.0);
    // Away is free: the jog runs.
    ok(
        &mut e,
        Command::from(GroupJog {
            group: 1,
            coordinate: 0,
            velocity: -80.0,
            coordinate_system: None,
        }),
    );
    for _ in 0..200 {
        e.step();
    }
    assert_eq!(group(&e, 1).state, GroupState::Moving);
    assert!(e.axis_status(0).unwrap().cmd_vel < 0.0);
}

#[test]
fn bad_frames_and_protections_are_typed_errors_and_change_nothing() {
    let mut e = machine(3, &[0, 1]);
    let pose = |p: [f64; 6]| {
        Command::from(GroupSetCoordinateTransform {
            group: 1,
            frame: cs("pcs"),
            pose: p,
        })
    };
    for bad in [f64::NAN, f64::INFINITY] {
        match refused(&mut e, pose([0.0, bad, 0.0, 0.0, 0.0, 0.0])) {
            EngineError::InvalidArgument { name: "pose", .. } => {}
            other => panic!("{other:?}"),
        }
    }
    let undefined = |e: &mut Engine, c: Command| match refused(e, c) {
        EngineError::UndefinedCoordinateSystem { group: 1, .. } => {}
        other => panic!("{other:?}"),
    };
    for system in ["wcs16", "wcs0", "rotary", "xyza"] {
        undefined(
            &mut e,
            Command::from(GroupSetCoordinateSystem {
                group: 1,
                coordinate_system: cs(system),
            }),
        );
        undefined(&mut e, Command::from(line_in(1, &[1.0, 1.0], Some(system))));
    }
    undefined(
        &mut e,
        Command::from(GroupSetCoordinateTransform {
            group: 1,
            frame: cs("wcs1|pcs"),
            pose: [0.0; 6],
        }),
    );
    for frame in ["wcs16", "mcs", "rotary"] {
        undefined(
            &mut e,
            Command::from(GroupSetCoordinateTransform {
                group: 1,
                frame: cs(frame),
                pose: [0.0; 6],
            }),
        );
    }
    // A pitch on a 2-axis group would move the path into Z.
    ok(&mut e, pose([0.0, 0.0, 0.0, 0.0, 30.0, 0.0]));
    undefined(&mut e, Command::from(line_in(1, &[1.0, 1.0], Some("pcs"))));
    assert!("wcs1|wcs2".parse::<CoordinateSystem>().is_err());
    assert!("pcs|pcs".parse::<CoordinateSystem>().is_err());
    assert!("world".parse::<CoordinateSystem>().is_err());
    match refused(
        &mut e,
        Command::from(GroupSetXyzaTransform {
            group: 1,
            rad_per_unit: 1.0,
            tool: [0.0, 0.0],
        }),
    ) {
        EngineError::InvalidGroup { .. } => {}
        other => panic!("{other:?}"),
    }
    match refused(
        &mut e,
        Command::from(GroupSetRotaryTransform {
            group: 1,
            rotary_axis: 1,
            rad_per_unit: 1.0,
            center: [0.0, 0.0],
            plane: None,
        }),
    ) {
        EngineError::InvalidGroup { .. } => {}
        other => panic!("{other:?}"),
    }
    assert_eq!(group(&e, 1).coordinate_system, CoordinateSystem::MCS);
    assert_eq!(group(&e, 1).queue_used, 0);

    let mut e = rail();
    let invalid = |e: &mut Engine, c: MoveProtectionEnable| match refused(e, Command::from(c)) {
        EngineError::InvalidProtection { protection: 0, .. } => {}
        other => panic!("{other:?}"),
    };
    invalid(
        &mut e,
        MoveProtectionEnable {
            groups: [1, 1],
            ..protection(ProtectionMode::BothStop)
        },
    );
    invalid(
        &mut e,
        MoveProtectionEnable {
            axes: [0, 1],
            ..protection(ProtectionMode::BothStop)
        },
    );
    invalid(
        &mut e,
        MoveProtectionEnable {
            move_direction: [1, 0],
            ..protection(ProtectionMode::BothStop)
        },
    );
    invalid(&mut e, protection(ProtectionMode::Retreat));
    invalid(
        &mut e,
        MoveProtectionEnable {
            stop_group: Some(3),
            safe_wait_position: Some(0.0),
            ..protection(ProtectionMode::Retreat)
        },
    );
    match refused(
        &mut e,
        Command::from(MoveProtectionEnable {
            groups: [1, 7],
            ..protection(ProtectionMode::BothStop)
        }),
    ) {
        EngineError::UnknownGroup { group: 7 } => {}
        other => panic!("{other:?}"),
    }
    match refused(
        &mut e,
        Command::from(MoveProtectionEnable {
            protection_distance: f64::NAN,
            ..protection(ProtectionMode::BothStop)
        }),
    ) {
        EngineError::InvalidArgument { .. } => {}
        other => panic!("{other:?}"),
    }
    match refused(
        &mut e,
        Command::from(MoveProtectionDisable { protection: 0 }),
    ) {
        EngineError::InvalidProtection { .. } => {}
        other => panic!("{other:?}"),
    }
    e.step();
    assert_eq!(group(&e, 1).interference, InterferenceStatus::NotEnabled);
}

/// Issue 13 defect (NMC mv_protect.c): the reserve counted one period at the speed of the last
/// tick, not the speed the path could reach by the next check. A line accelerating at
/// 500 000 units/s² toward a stop braking at the group's 5000 units/s² gains 2000 units of
/// braking length a tick, so the guard decided one tick late and the path stopped 400 units
/// (that tick's growth less its travel) past the protection distance.
#[test]
fn a_path_accelerating_hard_toward_a_gentle_stop_stops_before_the_protection_distance() {
    use axes::param::ParamId;
    let mut a = stepper_mm();
    for (p, v) in [
        (ParamId::Units, 1.0),
        (ParamId::Speed, 100_000.0),
        (ParamId::Accel, 1e6),
        (ParamId::Decel, 1e6),
        (ParamId::FastDecel, 1e7),
    ] {
        a.params.insert(p, v);
    }
    a.switches.limit_pos = None;
    a.switches.limit_neg = None;
    let mut e = with_group_2(common::with_group(engine_with(vec![a.clone(), a]), &[0]), 1);
    ok(
        &mut e,
        Command::from(MoveProtectionEnable {
            origin_distance: 50_000.0,
            protection_distance: 10_000.0,
            ..protection(ProtectionMode::BothStop)
        }),
    );
    ok(
        &mut e,
        Command::from(MoveLinearAbsolute {
            velocity: Some(20_000.0),
            acceleration: Some(500_000.0),
            deceleration: Some(500_000.0),
            jerk: Some(0.0),
            ..line_in(1, &[100_000.0], None)
        }),
    );
    let mut closest = f64::INFINITY;
    run_all(&mut e, 100.0, |e| {
        closest = closest.min(50_000.0 - pos(e, 0) + pos(e, 1));
    });
    assert!(closest >= 10_000.0, "closed to {closest}");
    // Stopped for the protection, in the last tick whose stop still ends before the distance:
    // within one tick's growth of the braking length (≤ 2000 + 20 here) of it.
    assert!(closest < 12_020.0, "stopped at {closest}");
}
