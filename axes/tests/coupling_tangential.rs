//! The tangential axis at the engine level (issue 12 item 9): HMC MoveTang (digest 000 §4.4,
//! TV 62): an axis that tracks the tangent angle of a group's path, exactly while the tangent
//! turns within the axis's limits, turning the shortest way within them at a corner, holding
//! while the path stands; bad input.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

/// What a refusal must match.
type Expected = fn(&EngineError) -> bool;

use axes::command::{
    ArcDirection, Command, EngineError, GroupBufferMode, GroupCreate, GroupDwell,
    MoveCircularAbsolute, MoveLinearAbsolute, SafeZMode, TangentialCornerContinue,
    TangentialCornerFollowNext, TangentialCornerMode, TangentialCornerModeKind, TangentialIn,
    TangentialOut, TransitionMode,
};
use axes::status::{CouplingKind, CouplingPhase, CouplingStatus, GroupState};
use axes::{AxisFlags, AxisState, Engine, ParamId};
use common::{fast_mm_axis, free_linear_axis, group_arc, group_line, ok, refused, run_path};

/// X, Y (group 1) and the tangential axis 2 with `speed` and `accel` of its own.
fn machine(speed: f64, accel: f64) -> Engine {
    let xy = fast_mm_axis(1e5, 1e7);
    let c = free_linear_axis(
        1000.0,
        &[
            (ParamId::Speed, speed),
            (ParamId::Accel, accel),
            (ParamId::Decel, accel),
        ],
    );
    common::with_group(common::engine_with(vec![xy.clone(), xy, c]), &[0, 1])
}

fn tangential(units_per_turn: f64, offset: f64) -> Command {
    Command::from(TangentialIn {
        axis: 2,
        group: 1,
        coordinates: [0, 1],
        offset,
        units_per_turn,
    })
}

fn coupling(e: &Engine) -> CouplingStatus {
    e.couplings().status_of(2).expect("axis 2 is tangential")
}

fn line(to: [f64; 2], transition: TransitionMode) -> Command {
    Command::from(MoveLinearAbsolute {
        velocity: Some(100.0),
        acceleration: Some(1000.0),
        deceleration: Some(1000.0),
        transition,
        ..group_line(1, &to)
    })
}

#[test]
fn a_circle_turns_the_axis_at_speed_over_radius_tv62() {
    // TV 62: C range [−10000, 10000) ↔ [−π, π): 20000 units a turn. XY circle radius 1000 at
    // Speed 1000, Accel 2000 → 3183.09886 units/s (1 rad/s), 6366.19772 units/s² (2 rad/s²).
    let mut e = machine(1e5, 1e8);
    ok(&mut e, tangential(20_000.0, 0.0));
    let arc = |center: [f64; 2], end: [f64; 2]| {
        Command::from(MoveCircularAbsolute {
            velocity: Some(1000.0),
            acceleration: Some(2000.0),
            deceleration: Some(2000.0),
            transition: TransitionMode::CornerDistance(1.0),
            ..group_arc(1, &center, &end, ArcDirection::Ccw)
        })
    };
    // A full circle from (0, 0) about (1000, 0), counter-clockwise: the tangent starts at
    // −90° (−5000 units) and turns a full turn.
    ok(&mut e, arc([1000.0, 0.0], [2000.0, 0.0]));
    ok(&mut e, arc([1000.0, 0.0], [0.0, 0.0]));
    let (mut cruise, mut accelerating) = (0, 0);
    let mut last_angle = None;
    run_path(&mut e, 20.0, |e, g| {
        let c = e.axis_status(2).unwrap();
        let k = coupling(e);
        if k.phase != CouplingPhase::InSync {
            return;
        }
        assert_eq!(k.deviation, 0.0);
        // The angle is the direction of the XY velocity, unwrapped.
        let (x, y) = (e.axis_status(0).unwrap(), e.axis_status(1).unwrap());
        if x.cmd_vel.hypot(y.cmd_vel) > 1e-6 {
            let raw = y.cmd_vel.atan2(x.cmd_vel) * 20_000.0 / std::f64::consts::TAU;
            let turns = (c.cmd_pos - raw) / 20_000.0;
            assert!(
                (turns - turns.round()).abs() < 1e-9,
                "{} vs {raw}",
                c.cmd_pos
            );
        }
        if let Some(previous) = last_angle {
            assert!(
                c.cmd_pos >= previous,
                "counter-clockwise: the angle only grows"
            );
        }
        last_angle = Some(c.cmd_pos);
        if (g.path_velocity - 1000.0).abs() < 1e-9 {
            assert!((c.cmd_vel - 3183.09886).abs() < 1e-5, "{}", c.cmd_vel);
            cruise += 1;
        } else if g.path_velocity > 1.0 && g.path_velocity < 999.0 && c.cmd_vel > 0.0 {
            // Speeding up at 2000 units/s² on radius 1000: 2 rad/s².
            if (c.cmd_acc - 6366.19772).abs() < 1e-3 {
                accelerating += 1;
            }
        }
    });
    assert!(cruise > 5000, "{cruise} ticks at cruise");
    assert!(accelerating > 300, "{accelerating} ticks speeding up");
    // A full turn from −90°: −5000 + 20000.
    assert!(
        (e.axis_status(2).unwrap().cmd_pos - 15_000.0).abs() < 1e-6,
        "{}",
        e.axis_status(2).unwrap().cmd_pos
    );
}

/// Run a square (0,0) → (100,0) → (100,100) → (0,100) → (0,0) with `transition` at the corners
/// and the tangential axis in degrees; the largest deviation and the ticks out of sync.
fn square(e: &mut Engine, transition: TransitionMode) -> (f64, u32) {
    ok(e, tangential(360.0, 0.0));
    for to in [[100.0, 0.0], [100.0, 100.0], [0.0, 100.0], [0.0, 0.0]] {
        ok(e, line(to, transition));
    }
    let (mut deviation, mut turning) = (0.0f64, 0u32);
    let limit = e.axis(2).unwrap().params().get(ParamId::Speed);
    run_path(e, 30.0, |e, _| {
        let k = coupling(e);
        deviation = deviation.max(k.deviation.abs());
        if k.phase == CouplingPhase::Engaging {
            turning += 1;
        }
        let c = e.axis_status(2).unwrap();
        assert!(c.cmd_vel.abs() <= limit * (1.0 + 1e-9), "{}", c.cmd_vel);
        assert_eq!(c.state, AxisState::SynchronizedMotion);
    });
    (deviation, turning)
}

#[test]
fn at_a_sharp_corner_where_the_path_stops_the_axis_turns_within_its_limits() {
    // The path stops at each corner; the tangent jumps by 90° when the next side starts, and
    // the axis (90°/s, 3600°/s²) turns there the shortest way while XY already moves on.
    let mut e = machine(90.0, 3600.0);
    let (deviation, turning) = square(&mut e, TransitionMode::None);
    // The full jump at the start of each side, less the first tick's turn.
    assert!((deviation - 90.0).abs() < 0.01, "{deviation}");
    // Three turns of 90° at 90°/s: about a second each.
    assert!(
        turning > 3 * 900 && turning < 3 * 1200,
        "{turning} ticks turning"
    );
    let c = coupling(&e);
    assert_eq!(c.phase, CouplingPhase::InSync);
    assert_eq!((c.angle, e.axis_status(2).unwrap().cmd_pos), (270.0, 270.0));
    assert_eq!(c.kind, CouplingKind::Tangential);
}

#[test]
fn a_blended_corner_is_tracked_exactly_when_the_axis_can_turn_that_fast() {
    let mut e = machine(1e5, 1e8);
    let (deviation, turning) = square(&mut e, TransitionMode::CornerDistance(5.0));
    assert_eq!((deviation, turning), (0.0, 0));
    let c = e.axis_status(2).unwrap();
    assert!((c.cmd_pos - 270.0).abs() < 1e-9, "{}", c.cmd_pos);
}

#[test]
fn the_angle_holds_while_the_path_stands_and_takes_the_offset() {
    let mut e = machine(1e5, 1e8);
    ok(&mut e, tangential(360.0, 45.0));
    common::run(&mut e, 0.1);
    assert_eq!(coupling(&e).phase, CouplingPhase::Waiting);
    assert_eq!(
        e.axis_status(2).unwrap().cmd_pos,
        0.0,
        "no path yet: it holds"
    );
    // Along −Y: −90° + 45° = −45°.
    ok(&mut e, line([0.0, -50.0], TransitionMode::None));
    run_path(&mut e, 10.0, |_, _| {});
    common::run(&mut e, 0.5);
    assert_eq!(e.axis_status(2).unwrap().cmd_pos, -45.0);
    let s = e.axis_status(2).unwrap();
    assert!(s.flags.contains(AxisFlags::COUPLED));
    ok(&mut e, Command::from(TangentialOut { axis: 2 }));
    common::run(&mut e, 0.1);
    assert_eq!(e.axis_status(2).unwrap().state, AxisState::Standstill);
    assert!(e.snapshot().couplings.is_empty());
}

#[test]
fn bad_input_is_refused() {
    let mut e = machine(1e5, 1e8);
    let with = |f: fn(&mut TangentialIn)| {
        let mut c = TangentialIn {
            axis: 2,
            group: 1,
            coordinates: [0, 1],
            offset: 0.0,
            units_per_turn: 360.0,
        };
        f(&mut c);
        Command::from(c)
    };
    let cases: Vec<(Command, Expected)> = vec![
        (with(|c| c.group = 7), |e| {
            matches!(e, EngineError::UnknownGroup { group: 7 })
        }),
        (with(|c| c.coordinates = [0, 2]), |e| {
            matches!(e, EngineError::InvalidGroup { group: 1, .. })
        }),
        (with(|c| c.coordinates = [1, 1]), |e| {
            matches!(
                e,
                EngineError::InvalidArgument {
                    name: "coordinates",
                    ..
                }
            )
        }),
        (with(|c| c.offset = f64::NAN), |e| {
            matches!(e, EngineError::InvalidArgument { name: "offset", .. })
        }),
        (with(|c| c.units_per_turn = 0.0), |e| {
            matches!(
                e,
                EngineError::InvalidArgument {
                    name: "units_per_turn",
                    ..
                }
            )
        }),
        (with(|c| c.axis = 0), |e| {
            matches!(e, EngineError::CoupledToItself { axis: 0 })
        }),
        (Command::from(TangentialOut { axis: 2 }), |e| {
            matches!(e, EngineError::NotCoupled { axis: 2, .. })
        }),
    ];
    for (command, expected) in cases {
        let error = refused(&mut e, command.clone());
        assert!(expected(&error), "{command:?}: {error:?}");
    }
    // A member of another group cannot be the tangential axis.
    ok(
        &mut e,
        Command::from(GroupCreate {
            group: 2,
            axes: vec![2],
            queue_capacity: None,
            lookahead: None,
            result_axis: None,
            orientation: Default::default(),
        }),
    );
    let error = refused(&mut e, tangential(360.0, 0.0));
    assert!(
        matches!(error, EngineError::AxisInGroup { axis: 2, group: 2 }),
        "{error:?}"
    );
    assert!(e.snapshot().couplings.is_empty());
    assert_eq!(e.snapshot().groups[0].state, GroupState::Standby);
}

fn corner_mode(mode: TangentialCornerModeKind, angle_limit: f64) -> Command {
    Command::from(TangentialCornerMode {
        axis: 2,
        mode,
        angle_limit,
        z_axis: None,
        safe_z: 0.0,
        safe_z_mode: SafeZMode::Incremental,
    })
}

/// A line blended into the one before (HMC merge): without a corner stop the path would not
/// stop at a junction below the corner rule.
fn blended(to: [f64; 2]) -> Command {
    Command::from(MoveLinearAbsolute {
        buffer_mode: GroupBufferMode::BlendingLow,
        ..group_line(1, &to)
    })
}

/// Step until the path stands at a corner stop (corner state 2); the ticks it took.
fn until_corner_stop(e: &mut Engine) -> u32 {
    for tick in 0..100_000 {
        e.step();
        if coupling(e).corner_state == 2 {
            return tick;
        }
    }
    panic!("no corner stop: {:?}", e.snapshot().groups[0]);
}

#[test]
fn manual_corner_mode_stops_the_path_at_a_sharp_corner_until_continued() {
    // HMC_MoveTangConfigCornerMode(C, 1, π/4, …), manual §4.4.9.2: the path stops at a 90°
    // junction and waits (state 2); HMC_MoveTangCornerFollowNextCmd turns C to the next
    // motion's start direction; HMC_MoveTangCornerContinue lets the path go on (state 1). The
    // 5.7° junction after it is below the limit: no stop.
    let mut e = machine(90.0, 1000.0);
    ok(&mut e, tangential(360.0, 0.0));
    ok(
        &mut e,
        corner_mode(
            TangentialCornerModeKind::Manual,
            std::f64::consts::FRAC_PI_4,
        ),
    );
    assert_eq!(coupling(&e).corner_state, 1);
    ok(&mut e, blended([100.0, 0.0]));
    ok(&mut e, blended([100.0, 100.0]));
    ok(&mut e, blended([110.0, 200.0]));
    until_corner_stop(&mut e);
    for _ in 0..2000 {
        e.step();
        let g = e.snapshot().groups[0];
        assert_eq!((g.coordinates[0], g.coordinates[1]), (100.0, 0.0));
        assert_eq!(g.path_velocity, 0.0);
        assert_eq!(coupling(&e).corner_state, 2);
    }
    assert_eq!(
        e.axis_status(2).unwrap().cmd_pos,
        0.0,
        "C holds at the corner"
    );
    ok(
        &mut e,
        Command::from(TangentialCornerFollowNext { axis: 2 }),
    );
    // 90° at 90 units/s within 1000 units/s²: about a second; C ends on the new direction
    // exactly while the path still stands.
    let mut top_speed: f64 = 0.0;
    for _ in 0..3000 {
        e.step();
        let c = e.axis_status(2).unwrap();
        top_speed = top_speed.max(c.cmd_vel.abs());
        assert_eq!(e.snapshot().groups[0].coordinates[1], 0.0);
    }
    assert_eq!(e.axis_status(2).unwrap().cmd_pos, 90.0);
    assert!(top_speed <= 90.0 * (1.0 + 1e-9), "{top_speed}");
    ok(&mut e, Command::from(TangentialCornerContinue { axis: 2 }));
    let mut stops = 0;
    let mut was = 2;
    run_path(&mut e, 20.0, |e, _| {
        let state = coupling(e).corner_state;
        stops += u32::from(state == 2 && was != 2);
        was = state;
    });
    assert_eq!(stops, 0, "the 5.7° junction does not stop");
    assert_eq!(coupling(&e).corner_state, 1);
    let g = e.snapshot().groups[0];
    assert_eq!((g.coordinates[0], g.coordinates[1]), (110.0, 200.0));
}

#[test]
fn no_corner_stop_across_a_buffered_command_or_without_the_mode() {
    // Manual §4.4.9.2: a non-interpolation command between two motions — its start tangent
    // cannot be judged in advance — is a junction without a lift.
    let mut e = machine(1e4, 1e6);
    ok(&mut e, tangential(360.0, 0.0));
    ok(
        &mut e,
        corner_mode(
            TangentialCornerModeKind::Manual,
            std::f64::consts::FRAC_PI_4,
        ),
    );
    ok(&mut e, blended([100.0, 0.0]));
    ok(
        &mut e,
        Command::from(GroupDwell {
            group: 1,
            seconds: 0.01,
        }),
    );
    ok(&mut e, blended([100.0, 100.0]));
    run_path(&mut e, 20.0, |e, _| assert_ne!(coupling(e).corner_state, 2));
    // Mode none (0): state 0, no stop.
    ok(&mut e, corner_mode(TangentialCornerModeKind::None, 0.0));
    assert_eq!(coupling(&e).corner_state, 0);
    ok(&mut e, blended([0.0, 100.0]));
    ok(&mut e, blended([0.0, 0.0]));
    run_path(&mut e, 20.0, |e, _| assert_eq!(coupling(e).corner_state, 0));
    // Decoupling clears the group's corner stops.
    ok(
        &mut e,
        corner_mode(
            TangentialCornerModeKind::Manual,
            std::f64::consts::FRAC_PI_4,
        ),
    );
    ok(&mut e, Command::from(TangentialOut { axis: 2 }));
    ok(&mut e, blended([100.0, 0.0]));
    ok(&mut e, blended([100.0, 100.0]));
    run_path(&mut e, 20.0, |_, _| {});
}

#[test]
fn corner_commands_out_of_place_are_refused() {
    let mut e = machine(1e4, 1e6);
    // Not a tangential axis yet.
    let err = refused(&mut e, corner_mode(TangentialCornerModeKind::Manual, 0.5));
    assert!(
        matches!(err, EngineError::NotCoupled { axis: 2, .. }),
        "{err}"
    );
    ok(&mut e, tangential(360.0, 0.0));
    for limit in [f64::NAN, -0.1, 4.0] {
        let err = refused(&mut e, corner_mode(TangentialCornerModeKind::Manual, limit));
        assert!(matches!(err, EngineError::InvalidArgument { .. }), "{err}");
    }
    // Mode none: the manual commands are refused.
    let err = refused(&mut e, Command::from(TangentialCornerContinue { axis: 2 }));
    assert!(matches!(err, EngineError::InvalidArgument { .. }), "{err}");
    // Manual, but the path does not stand at a corner.
    ok(&mut e, corner_mode(TangentialCornerModeKind::Manual, 0.5));
    for c in [
        Command::from(TangentialCornerFollowNext { axis: 2 }),
        Command::from(TangentialCornerContinue { axis: 2 }),
    ] {
        let err = refused(&mut e, c);
        assert!(
            matches!(err, EngineError::InvalidGroup { group: 1, .. }),
            "{err}"
        );
    }
}
