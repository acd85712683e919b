//! Superimposed motion at the engine level (issue 12 item 9): HMC SuperimposeEx and
//! SetSuperimposeRatio (digest 000 §4.4, TV 22–24), zero lag, disengaging, bad input, and the
//! property that the slave's travel is the combination of the masters' travels.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

/// What a refusal must match.
type Expected = fn(&EngineError) -> bool;

use axes::command::{
    Command, EngineError, GearIn, MasterSource, SuperimposeIn, SuperimposeOut, SuperimposeSetRatios,
};
use axes::status::{CouplingKind, CouplingPhase};
use axes::{AxisFlags, AxisState, Engine};
use common::{move_rel_of, ok, refused, run};
use proptest::prelude::*;

fn machine(n: usize) -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), n)
}

fn superimpose(slave: u16, masters: [u16; 2], ratios: [f64; 2]) -> Command {
    Command::from(SuperimposeIn {
        slave,
        masters,
        ratios,
        // HMC follows the masters' MPos (digest 000 §4.4); the virtual axes' MPos = DPos.
        master_source: MasterSource::Actual,
    })
}

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

/// Move `axis` by `distance` and run until it is done.
fn travel(e: &mut Engine, axis: u16, distance: f64) {
    ok(e, move_rel_of(axis, distance));
    run(e, 2.0);
}

#[test]
fn a_live_ratio_change_applies_to_travel_from_then_on_tv22() {
    // SuperimposeEx(3, 0, 1, 1, 1, 1, 1); Move(0, 1000); Move(1, 2000) → axis 3 = 3000.
    let mut e = machine(4);
    ok(&mut e, superimpose(3, [0, 1], [1.0, 1.0]));
    travel(&mut e, 0, 1000.0);
    travel(&mut e, 1, 2000.0);
    assert_eq!(cmd(&e, 3), 3000.0);
    let c = e.snapshot().couplings[0];
    assert_eq!(
        (c.slave, c.master, c.master2, c.kind, c.phase),
        (
            3,
            0,
            Some(1),
            CouplingKind::Superimpose,
            CouplingPhase::InSync
        )
    );
    // SetSuperimposeRatio(3, 1, 1, −1, 1): no jump; Move(0, 1000); Move(1, −1000) → 5000.
    ok(
        &mut e,
        Command::from(SuperimposeSetRatios {
            slave: 3,
            ratios: [1.0, -1.0],
        }),
    );
    e.step();
    assert_eq!(cmd(&e, 3), 3000.0, "a ratio change moves nothing");
    travel(&mut e, 0, 1000.0);
    travel(&mut e, 1, -1000.0);
    assert_eq!(cmd(&e, 3), 5000.0);
    let c = e.snapshot().couplings[0];
    assert_eq!((c.ratio, c.ratio2), (1.0, -1.0));
}

#[test]
fn cross_belt_kinematics_tv23() {
    // u = x + y, v = x − y: master X += 100, Y += 50 → u += 150, v += 50.
    let mut e = machine(4);
    ok(&mut e, superimpose(2, [0, 1], [1.0, 1.0]));
    ok(&mut e, superimpose(3, [0, 1], [1.0, -1.0]));
    ok(&mut e, move_rel_of(0, 100.0));
    ok(&mut e, move_rel_of(1, 50.0));
    run(&mut e, 1.0);
    assert_eq!((cmd(&e, 2), cmd(&e, 3)), (150.0, 50.0));
}

#[test]
fn a_45_degree_rotation_tv24() {
    // SuperImposeEx(2, 0, 1, 707/1000, −707/1000), (3, 0, 1, 707/1000, 707/1000); masters at
    // (2000, 0) → axes 2 and 3 at 1414.
    let mut e = machine(4);
    ok(&mut e, superimpose(2, [0, 1], [0.707, -0.707]));
    ok(&mut e, superimpose(3, [0, 1], [0.707, 0.707]));
    travel(&mut e, 0, 2000.0);
    assert!((cmd(&e, 2) - 1414.0).abs() < 1e-9, "{}", cmd(&e, 2));
    assert!((cmd(&e, 3) - 1414.0).abs() < 1e-9, "{}", cmd(&e, 3));
}

#[test]
fn the_slave_has_no_lag_and_is_synchronized() {
    let mut e = machine(3);
    ok(
        &mut e,
        Command::from(SuperimposeIn {
            slave: 2,
            masters: [0, 1],
            ratios: [2.0, -0.5],
            master_source: MasterSource::Commanded,
        }),
    );
    ok(&mut e, move_rel_of(0, 500.0));
    ok(&mut e, move_rel_of(1, 300.0));
    for _ in 0..40 {
        e.step();
        let want = 2.0 * cmd(&e, 0) - 0.5 * cmd(&e, 1);
        assert!((cmd(&e, 2) - want).abs() < 1e-9);
        let s = e.axis_status(2).unwrap();
        let v = 2.0 * e.axis_status(0).unwrap().cmd_vel - 0.5 * e.axis_status(1).unwrap().cmd_vel;
        assert!((s.cmd_vel - v).abs() < 1e-6, "{} {v}", s.cmd_vel);
        assert_eq!(s.state, AxisState::SynchronizedMotion);
        assert!(s.flags.contains(AxisFlags::COUPLED | AxisFlags::IN_SYNC));
    }
}

#[test]
fn superimpose_out_lets_the_slave_ramp_down_and_go() {
    let mut e = machine(3);
    ok(&mut e, superimpose(2, [0, 1], [1.0, 1.0]));
    ok(&mut e, common::jog_of(0, 1000.0));
    run(&mut e, 0.2);
    ok(&mut e, Command::from(SuperimposeOut { slave: 2 }));
    assert!(e.snapshot().couplings.is_empty());
    run(&mut e, 1.0);
    let s = e.axis_status(2).unwrap();
    assert_eq!(s.state, AxisState::Standstill);
    assert!(!s.flags.contains(AxisFlags::COUPLED));
    // Free again: it takes a move of its own.
    ok(&mut e, move_rel_of(2, 10.0));
}

#[test]
fn bad_input_is_refused_and_disturbs_nothing() {
    let mut e = machine(5);
    ok(&mut e, superimpose(2, [0, 1], [1.0, 1.0]));
    let before = e.snapshot().couplings.clone();
    let cases: Vec<(Command, Expected)> = vec![
        (superimpose(3, [3, 1], [1.0, 1.0]), |e| {
            matches!(e, EngineError::CoupledToItself { axis: 3 })
        }),
        (superimpose(3, [0, 3], [1.0, 1.0]), |e| {
            matches!(e, EngineError::CoupledToItself { axis: 3 })
        }),
        (superimpose(3, [0, 0], [1.0, 1.0]), |e| {
            matches!(
                e,
                EngineError::InvalidArgument {
                    name: "masters",
                    ..
                }
            )
        }),
        (superimpose(3, [0, 1], [f64::NAN, 1.0]), |e| {
            matches!(
                e,
                EngineError::InvalidArgument {
                    name: "ratios[0]",
                    ..
                }
            )
        }),
        (superimpose(3, [0, 1], [1.0, f64::INFINITY]), |e| {
            matches!(
                e,
                EngineError::InvalidArgument {
                    name: "ratios[1]",
                    ..
                }
            )
        }),
        // Axis 0 would follow axis 2, which follows axis 0 (through its first master) …
        (superimpose(0, [2, 4], [1.0, 1.0]), |e| {
            matches!(
                e,
                EngineError::CouplingLoop {
                    slave: 0,
                    master: 2
                }
            )
        }),
        // … or through its second master, down a gear.
        (
            Command::from(GearIn {
                master: 2,
                slave: 1,
                numerator: 1.0,
                denominator: 1.0,
                master_source: MasterSource::Commanded,
                clutch_distance: None,
                acceleration: None,
                direction: None,
                phase_offset: 0,
                transition: false,
            }),
            |e| {
                matches!(
                    e,
                    EngineError::CouplingLoop {
                        slave: 1,
                        master: 2
                    }
                )
            },
        ),
        (superimpose(2, [3, 4], [1.0, 1.0]), |e| {
            matches!(e, EngineError::AlreadyCoupled { axis: 2, .. })
        }),
        (superimpose(9, [0, 1], [1.0, 1.0]), |e| {
            matches!(e, EngineError::InvalidAxis { axis: 9, .. })
        }),
        (
            Command::from(SuperimposeSetRatios {
                slave: 3,
                ratios: [1.0, 1.0],
            }),
            |e| matches!(e, EngineError::NotCoupled { axis: 3, .. }),
        ),
        (
            Command::from(SuperimposeSetRatios {
                slave: 2,
                ratios: [f64::NAN, 1.0],
            }),
            |e| matches!(e, EngineError::InvalidArgument { .. }),
        ),
        (Command::from(SuperimposeOut { slave: 4 }), |e| {
            matches!(e, EngineError::NotCoupled { axis: 4, .. })
        }),
    ];
    for (command, expected) in cases {
        let error = refused(&mut e, command.clone());
        assert!(expected(&error), "{command:?}: {error:?}");
    }
    assert_eq!(e.snapshot().couplings, before);
    travel(&mut e, 0, 10.0);
    assert_eq!(cmd(&e, 2), 10.0, "the coupling still runs");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Slave travel = k1 · master 1 travel + k2 · master 2 travel, exactly to rounding, across
    /// random moves and a live ratio change.
    #[test]
    fn the_slave_travel_is_the_combination_of_the_masters(
        k in prop::array::uniform2(-4.0f64..4.0),
        k_later in prop::array::uniform2(-4.0f64..4.0),
        moves in prop::collection::vec((0u16..2, -3000.0f64..3000.0), 1..5),
    ) {
        let mut e = machine(3);
        ok(&mut e, superimpose(2, [0, 1], k));
        let mut expected = 0.0;
        let (half, rest) = moves.split_at(moves.len() / 2);
        for (ratios, part) in [(k, half), (k_later, rest)] {
            if ratios != k {
                ok(&mut e, Command::from(SuperimposeSetRatios { slave: 2, ratios }));
            }
            for &(axis, d) in part {
                let before = cmd(&e, axis as usize);
                ok(&mut e, move_rel_of(axis, d));
                run(&mut e, 1.5);
                expected += ratios[axis as usize] * (cmd(&e, axis as usize) - before);
            }
        }
        prop_assert!((cmd(&e, 2) - expected).abs() < 1e-7, "{} vs {expected}", cmd(&e, 2));
    }
}
