//! Electronic gear at the engine level (issue 12 item 1): NMC S-GEAR / TV 58 (digest 001 §2.16,
//! §4.7), HMC gear inversion (digest 000 §8.3 TV 21), HIMC GearIn and EnableGear (digest 004
//! §6.3 TV 34–35), the clutches, ratio changes, the direction filter, zero lag along master
//! chains, bad input, and the exact-ratio and determinism properties.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, Direction, Disable, EngineError, GearIn, GearOut, GearSetRatio, MasterSource,
};
use axes::status::{CouplingKind, CouplingPhase};
use axes::{AxisFlags, AxisState, Engine};
use common::{move_abs_of, move_rel_of, ok, refused, run};
use proptest::prelude::*;

fn machine(n: usize) -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), n)
}

fn gear(master: u16, slave: u16, numerator: f64, denominator: f64) -> GearIn {
    GearIn {
        master,
        slave,
        numerator,
        denominator,
        master_source: MasterSource::Commanded,
        clutch_distance: None,
        acceleration: None,
        direction: None,
        phase_offset: 0,
        transition: false,
    }
}

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

/// Step until every axis is at rest (at most `seconds`).
fn settle(e: &mut Engine, seconds: f64) {
    let n = (seconds / e.period()).round() as u64;
    for _ in 0..n {
        e.step();
        let s = e.snapshot();
        if s.axes.iter().all(|a| !a.flags.contains(AxisFlags::MOVING)) {
            return;
        }
    }
    panic!("not at rest after {seconds} s");
}

#[test]
fn s_gear_the_slave_makes_four_fifths_less_half_the_clutch_tv58() {
    // S-GEAR: slave axis 0 follows axis 1's planned position, MtGearSetRatio(5, 4, 2000): slave
    // : master = 4 : 5, clutch over 2000 master pulses; the master moves +10000.
    let mut e = machine(2);
    ok(
        &mut e,
        Command::from(GearIn {
            clutch_distance: Some(2000.0),
            ..gear(1, 0, 4.0, 5.0)
        }),
    );
    let c = e.snapshot().couplings[0];
    assert_eq!((c.slave, c.master, c.kind), (0, 1, CouplingKind::Gear));
    assert_eq!(c.phase, CouplingPhase::Engaging);
    ok(&mut e, move_rel_of(1, 10_000.0));
    e.step();
    assert_eq!(
        e.axis_status(0).unwrap().state,
        AxisState::SynchronizedMotion
    );
    settle(&mut e, 10.0);
    // 0.8 × 10000 − 0.8 × 2000 / 2 (the ratio ramps linearly over the clutch).
    assert!((cmd(&e, 0) - 7200.0).abs() < 1e-6, "{}", cmd(&e, 0));
    let s = e.snapshot();
    assert_eq!(s.couplings[0].phase, CouplingPhase::InSync);
    assert_eq!(s.couplings[0].ratio, 0.8);
    assert!(s.axes[0]
        .flags
        .contains(AxisFlags::COUPLED | AxisFlags::IN_SYNC));
    assert!(!s.axes[1].flags.contains(AxisFlags::COUPLED));
}

#[test]
fn the_slave_follows_the_master_of_the_same_tick_down_a_chain() {
    // Axis 2 is the master, 1 follows it, 0 follows 1: the slaves have lower indices, so only
    // the coupling order puts each after its master. No tick of lag anywhere.
    let mut e = machine(3);
    ok(&mut e, Command::from(gear(2, 1, 3.0, 2.0)));
    ok(&mut e, Command::from(gear(1, 0, -1.0, 4.0)));
    ok(&mut e, move_rel_of(2, 500.0));
    for _ in 0..400 {
        e.step();
        let m = cmd(&e, 2);
        assert_eq!(cmd(&e, 1), 1.5 * m);
        assert_eq!(cmd(&e, 0), -0.25 * (1.5 * m));
    }
}

#[test]
fn himc_gear_in_with_four_ratios_tv34() {
    // Digest 004 TV 34: master 0, slaves 1–4 at 0, GearIn ratios 1, 2, 4, −1; MoveAbs(0, 100).
    let mut e = machine(5);
    for (slave, ratio) in [(1, 1.0), (2, 2.0), (3, 4.0), (4, -1.0)] {
        ok(&mut e, Command::from(gear(0, slave, ratio, 1.0)));
    }
    ok(&mut e, move_abs_of(0, 100.0));
    settle(&mut e, 5.0);
    for (axis, want) in [(1, 100.0), (2, 200.0), (3, 400.0), (4, -100.0)] {
        assert!((cmd(&e, axis) - want).abs() < 1e-9, "axis {axis}");
    }
}

#[test]
fn himc_a_disabled_slave_cannot_be_geared_tv35() {
    let mut e = machine(2);
    ok(&mut e, Command::from(Disable { axis: 1 }));
    let err = refused(&mut e, Command::from(gear(0, 1, 1.0, 1.0)));
    assert_eq!(err, EngineError::AxisDisabled { axis: 1 });
    assert!(e.snapshot().couplings.is_empty());
}

#[test]
fn hmc_gear_inversion_follows_the_masters_actual_position_tv21() {
    // Digest 000 TV 21: HMC_Gear(10, 0, −1, 1); master 0 moves +1000 → slave DPos −1000.
    let mut e = machine(11);
    ok(
        &mut e,
        Command::from(GearIn {
            master_source: MasterSource::Actual,
            ..gear(0, 10, -1.0, 1.0)
        }),
    );
    ok(&mut e, move_rel_of(0, 1000.0));
    settle(&mut e, 5.0);
    assert!((cmd(&e, 10) + 1000.0).abs() < 1e-9, "{}", cmd(&e, 10));
}

#[test]
fn an_acceleration_clutch_catches_up_then_locks_the_ratio() {
    // PLCopen MC_GearIn: the slave accelerates to ratio × master velocity, InGear once the
    // velocities match; from there slave travel = ratio × master travel.
    let mut e = machine(2);
    ok(&mut e, common::jog_of(0, 1000.0));
    run(&mut e, 0.1);
    ok(
        &mut e,
        Command::from(GearIn {
            acceleration: Some(5000.0),
            ..gear(0, 1, 2.0, 1.0)
        }),
    );
    e.step();
    assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::Engaging);
    let mut peak: f64 = 0.0;
    let mut ticks = 0;
    while e.snapshot().couplings[0].phase == CouplingPhase::Engaging {
        e.step();
        peak = peak.max(e.axis_status(1).unwrap().cmd_acc.abs());
        ticks += 1;
        assert!(ticks < 2000, "never in gear");
    }
    assert!(peak <= 5000.0 + 1e-9, "{peak}");
    // 2000 units/s at 5000 units/s² takes 0.4 s.
    assert!((ticks as f64 * e.period() - 0.4).abs() < 0.01, "{ticks}");
    let (m0, s0) = (cmd(&e, 0), cmd(&e, 1));
    run(&mut e, 0.5);
    assert!(((cmd(&e, 1) - s0) - 2.0 * (cmd(&e, 0) - m0)).abs() < 1e-9);
}

#[test]
fn a_ratio_change_applies_from_where_the_slave_is() {
    // HMC_SetGearRatio: the new ratio acts on the master travel from now on.
    let mut e = machine(2);
    ok(&mut e, Command::from(gear(0, 1, 1.0, 1.0)));
    ok(&mut e, move_rel_of(0, 100.0));
    settle(&mut e, 5.0);
    ok(
        &mut e,
        Command::from(GearSetRatio {
            slave: 1,
            numerator: -3.0,
            denominator: 2.0,
        }),
    );
    assert_eq!(e.snapshot().couplings[0].ratio, -1.5);
    ok(&mut e, move_rel_of(0, 100.0));
    settle(&mut e, 5.0);
    assert!(
        (cmd(&e, 1) - (100.0 - 150.0)).abs() < 1e-9,
        "{}",
        cmd(&e, 1)
    );
}

#[test]
fn the_direction_filter_follows_one_direction_of_the_master_only() {
    // NMC MtGearSetDir(>0): only positive master motion moves the slave.
    let mut e = machine(2);
    ok(
        &mut e,
        Command::from(GearIn {
            direction: Some(Direction::Positive),
            ..gear(0, 1, 1.0, 1.0)
        }),
    );
    for d in [100.0, -50.0, 50.0] {
        ok(&mut e, move_rel_of(0, d));
        settle(&mut e, 5.0);
    }
    assert!((cmd(&e, 1) - 150.0).abs() < 1e-9, "{}", cmd(&e, 1));
}

#[test]
fn gear_out_lets_the_slave_run_down_with_its_own_deceleration() {
    let mut e = machine(2);
    ok(&mut e, Command::from(gear(0, 1, 1.0, 1.0)));
    ok(&mut e, common::jog_of(0, 1000.0));
    run(&mut e, 0.1);
    ok(&mut e, Command::from(GearOut { slave: 1 }));
    let s = e.snapshot();
    assert!(s.couplings.is_empty());
    assert!(!s.axes[1].flags.contains(AxisFlags::COUPLED));
    // It ramps down from the master's velocity, which it still has.
    let slave = e.axis_status(1).unwrap();
    assert_eq!(slave.state, AxisState::Stopping);
    assert_eq!(slave.cmd_vel, 1000.0);
    // 1000 units/s at decel 1e6 units/s²: 1 ms, a tick or two.
    run(&mut e, 0.01);
    assert_eq!(e.axis_status(1).unwrap().state, AxisState::Standstill);
    // Free again: single-axis motion is taken.
    ok(&mut e, move_rel_of(1, 10.0));
}

#[test]
fn a_coupled_slave_refuses_single_axis_motion_and_a_disabled_one_is_decoupled() {
    let mut e = machine(2);
    ok(&mut e, Command::from(gear(0, 1, 1.0, 1.0)));
    let err = refused(&mut e, move_rel_of(1, 10.0));
    assert_eq!(err, EngineError::AxisCoupled { axis: 1, master: 0 });
    e.step();
    ok(&mut e, Command::from(Disable { axis: 1 }));
    ok(&mut e, move_rel_of(0, 10.0));
    e.step();
    let s = e.snapshot();
    assert!(s.couplings.is_empty(), "{:?}", s.couplings);
    assert!(!s.axes[1].flags.contains(AxisFlags::COUPLED));
    assert_eq!(cmd(&e, 0), e.axis_status(0).unwrap().cmd_pos);
}

#[test]
fn bad_gears_are_refused_naming_what_is_wrong_and_disturb_nothing() {
    let mut e = machine(3);
    ok(&mut e, Command::from(gear(0, 1, 1.0, 1.0)));
    let before = e.snapshot();
    let cases: Vec<(GearIn, EngineError)> = vec![
        (
            gear(2, 2, 1.0, 1.0),
            EngineError::CoupledToItself { axis: 2 },
        ),
        (
            gear(2, 1, 1.0, 1.0),
            EngineError::AlreadyCoupled { axis: 1, master: 0 },
        ),
        (
            gear(1, 0, 1.0, 1.0),
            EngineError::CouplingLoop {
                slave: 0,
                master: 1,
            },
        ),
        (
            gear(0, 2, 1.0, 0.0),
            EngineError::InvalidArgument {
                name: "denominator",
                value: 0.0,
                reason: "must not be zero",
            },
        ),
        (
            gear(7, 2, 1.0, 1.0),
            EngineError::InvalidAxis { axis: 7, count: 3 },
        ),
    ];
    for (g, want) in cases {
        assert_eq!(refused(&mut e, Command::from(g)), want);
    }
    assert!(matches!(
        refused(&mut e, Command::from(gear(0, 2, f64::NAN, 1.0))),
        EngineError::InvalidArgument {
            name: "numerator",
            ..
        }
    ));
    assert!(matches!(
        refused(
            &mut e,
            Command::from(GearIn {
                clutch_distance: Some(1.0),
                acceleration: Some(1.0),
                ..gear(0, 2, 1.0, 1.0)
            })
        ),
        EngineError::InvalidArgument { .. }
    ));
    assert_eq!(
        refused(&mut e, Command::from(GearOut { slave: 2 })),
        EngineError::NotCoupled {
            axis: 2,
            what: "the slave of a gear"
        }
    );
    // A longer loop: 2 follows 1 (which follows 0); 0 following 2 closes it.
    ok(&mut e, Command::from(gear(1, 2, 1.0, 1.0)));
    assert_eq!(
        refused(&mut e, Command::from(gear(2, 0, 1.0, 1.0))),
        EngineError::CouplingLoop {
            slave: 0,
            master: 2
        }
    );
    ok(&mut e, Command::from(GearOut { slave: 2 }));
    assert_eq!(e.snapshot(), before);
}

/// Run a geared pair through `moves` of the master and record (master, slave) commanded
/// positions every tick.
fn geared_run(
    numerator: f64,
    denominator: f64,
    clutch: Option<f64>,
    moves: &[f64],
) -> (Engine, Vec<(f64, f64)>) {
    let mut e = machine(2);
    ok(
        &mut e,
        Command::from(GearIn {
            clutch_distance: clutch,
            ..gear(0, 1, numerator, denominator)
        }),
    );
    let mut seen = Vec::new();
    for &d in moves {
        ok(&mut e, move_rel_of(0, d));
        for _ in 0..3000 {
            e.step();
            seen.push((cmd(&e, 0), cmd(&e, 1)));
            if !e.axis_status(0).unwrap().flags.contains(AxisFlags::MOVING) {
                break;
            }
        }
    }
    (e, seen)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn after_the_clutch_slave_travel_is_ratio_times_master_travel(
        numerator in -50i32..50,
        denominator in prop_oneof![-20i32..-1, 1i32..20],
        clutch in 0.0f64..300.0,
        moves in prop::collection::vec(-2000.0f64..2000.0, 1..4),
    ) {
        let mut moves = moves;
        // A first move long enough to get through the clutch.
        moves.insert(0, clutch + 100.0);
        let (e, seen) = geared_run(numerator as f64, denominator as f64, Some(clutch), &moves);
        let ratio = numerator as f64 / denominator as f64;
        prop_assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::InSync);
        // From the first tick in sync to the end.
        let start = seen.iter().position(|&(m, _)| m >= clutch).unwrap();
        let (m0, s0) = seen[start];
        for &(m, s) in &seen[start..] {
            let want = ratio * (m - m0);
            prop_assert!(((s - s0) - want).abs() <= 1e-9 * (1.0 + want.abs()), "{} vs {}", s - s0, want);
        }
    }
}

#[test]
fn the_same_commands_give_bit_identical_states() {
    let (a, sa) = geared_run(7.0, 3.0, Some(123.0), &[500.0, -250.0, 1000.0]);
    let (b, sb) = geared_run(7.0, 3.0, Some(123.0), &[500.0, -250.0, 1000.0]);
    assert_eq!(a.snapshot(), b.snapshot());
    let bits = |v: &[(f64, f64)]| -> Vec<(u64, u64)> {
        v.iter().map(|(m, s)| (m.to_bits(), s.to_bits())).collect()
    };
    assert_eq!(bits(&sa), bits(&sb));
}
