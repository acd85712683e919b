//! The tangential axis's auto lift (HMC_MoveTangConfigCornerMode mode 2, digest 000 §4.4
//! "Tangential tracking"; HMC_GetMoveTangCornerState 3 auto running, 4 auto lifting): at a
//! corner sharper than the limit the XY path pauses, Z lifts to the safe position, C turns to
//! the next direction, Z comes back, and the path continues — with no command from outside.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, EngineError, GroupBufferMode, MoveLinearAbsolute, SafeZMode, TangentialCornerMode,
    TangentialCornerModeKind, TangentialIn,
};
use axes::{Engine, ParamId};
use common::{fast_mm_axis, free_linear_axis, group_line, ok, refused, run_path};

/// X, Y (group 1), the tangential axis C = 2 and the lifting axis Z = 3.
fn machine() -> Engine {
    let xy = fast_mm_axis(1e5, 1e7);
    let own = |speed: f64, accel: f64| {
        free_linear_axis(
            1000.0,
            &[
                (ParamId::Speed, speed),
                (ParamId::Accel, accel),
                (ParamId::Decel, accel),
            ],
        )
    };
    let mut e = common::with_group(
        common::engine_with(vec![xy.clone(), xy, own(90.0, 1000.0), own(50.0, 500.0)]),
        &[0, 1],
    );
    ok(
        &mut e,
        Command::from(TangentialIn {
            axis: 2,
            group: 1,
            coordinates: [0, 1],
            offset: 0.0,
            units_per_turn: 360.0,
        }),
    );
    e
}

fn auto(z_axis: Option<u16>, safe_z: f64, safe_z_mode: SafeZMode) -> Command {
    Command::from(TangentialCornerMode {
        axis: 2,
        mode: TangentialCornerModeKind::Auto,
        angle_limit: std::f64::consts::FRAC_PI_4,
        z_axis,
        safe_z,
        safe_z_mode,
    })
}

fn blended(to: [f64; 2]) -> Command {
    Command::from(MoveLinearAbsolute {
        buffer_mode: GroupBufferMode::BlendingLow,
        ..group_line(1, &to)
    })
}

fn corner_state(e: &Engine) -> u8 {
    e.couplings().status_of(2).unwrap().corner_state
}

/// What each tick of the run showed: corner state, X, Y, C, Z.
type Tick = (u8, f64, f64, f64, f64);

fn run(e: &mut Engine) -> Vec<Tick> {
    let mut seen = Vec::new();
    run_path(e, 30.0, |e, g| {
        let c = e.axis_status(2).unwrap().cmd_pos;
        let z = e.axis_status(3).unwrap().cmd_pos;
        seen.push((corner_state(e), g.coordinates[0], g.coordinates[1], c, z));
    });
    seen
}

#[test]
fn at_a_sharp_corner_z_lifts_c_turns_z_returns_and_the_path_goes_on() {
    let mut e = machine();
    ok(&mut e, common::move_abs_of(3, 5.0));
    common::run(&mut e, 1.0);
    ok(&mut e, auto(Some(3), 20.0, SafeZMode::Incremental));
    assert_eq!(corner_state(&e), 3);
    ok(&mut e, blended([100.0, 0.0]));
    ok(&mut e, blended([100.0, 100.0]));
    ok(&mut e, blended([110.0, 200.0]));
    let seen = run(&mut e);
    // The lifting ticks: one stretch (the 5.7° junction is below the limit).
    let lifting: Vec<&Tick> = seen.iter().filter(|t| t.0 == 4).collect();
    assert!(!lifting.is_empty());
    let first = seen.iter().position(|t| t.0 == 4).unwrap();
    let last = seen.iter().rposition(|t| t.0 == 4).unwrap();
    assert_eq!(lifting.len(), last - first + 1, "one lift");
    for t in &seen[first..=last] {
        // XY pauses at the corner for the whole lift.
        assert_eq!((t.1, t.2), (100.0, 0.0));
    }
    // Z: up to 5 + 20, then back to 5, within the lift; C turns only while Z is up.
    let top = seen[first..=last]
        .iter()
        .map(|t| t.4)
        .fold(f64::MIN, f64::max);
    assert_eq!(top, 25.0);
    for t in &seen[first..=last] {
        if t.3 != seen[first].3 && t.3 != 90.0 {
            assert_eq!(t.4, 25.0, "C turns with Z up: {t:?}");
        }
    }
    let end = seen[last];
    assert_eq!((end.3, end.4), (90.0, 5.0), "C turned, Z back");
    // Before the lift the path ran with C at 0; after it, state 3 again and the path done.
    assert!(seen[..first].iter().all(|t| t.0 == 3 && t.4 == 5.0));
    assert!(seen[last + 1..].iter().all(|t| t.0 == 3 && t.4 == 5.0));
    let g = e.snapshot().groups[0];
    assert_eq!((g.coordinates[0], g.coordinates[1]), (110.0, 200.0));
    assert_eq!(corner_state(&e), 3);
}

#[test]
fn an_absolute_safe_position_is_where_z_lifts_to() {
    let mut e = machine();
    ok(&mut e, auto(Some(3), 12.5, SafeZMode::Absolute));
    ok(&mut e, blended([100.0, 0.0]));
    ok(&mut e, blended([100.0, 100.0]));
    let seen = run(&mut e);
    let top = seen.iter().map(|t| t.4).fold(f64::MIN, f64::max);
    assert_eq!(top, 12.5);
    assert_eq!(seen.last().unwrap().4, 0.0);
    assert_eq!(seen.last().unwrap().3, 90.0);
}

#[test]
fn a_z_that_cannot_move_leaves_the_path_at_the_corner_with_state_255() {
    let mut e = machine();
    ok(&mut e, auto(Some(3), 20.0, SafeZMode::Incremental));
    ok(&mut e, Command::from(axes::command::Disable { axis: 3 }));
    ok(&mut e, blended([100.0, 0.0]));
    ok(&mut e, blended([100.0, 100.0]));
    for _ in 0..5000 {
        e.step();
    }
    assert_eq!(corner_state(&e), 255);
    let g = e.snapshot().groups[0];
    assert_eq!((g.coordinates[0], g.coordinates[1]), (100.0, 0.0));
}

#[test]
fn a_bad_lifting_axis_is_refused() {
    let mut e = machine();
    for (z, why) in [
        (None, "no axis"),
        (Some(0), "a member of the group"),
        (Some(2), "the tangential axis"),
        (Some(9), "no such axis"),
    ] {
        let err = refused(&mut e, auto(z, 10.0, SafeZMode::Incremental));
        assert!(
            matches!(
                err,
                EngineError::InvalidArgument { name: "z_axis", .. }
                    | EngineError::InvalidAxis { axis: 9, .. }
            ),
            "{why}: {err}"
        );
    }
    let err = refused(&mut e, auto(Some(3), f64::NAN, SafeZMode::Incremental));
    assert!(matches!(err, EngineError::InvalidArgument { .. }), "{err}");
    assert_eq!(corner_state(&e), 0, "nothing changed");
}
