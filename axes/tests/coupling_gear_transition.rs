//! HMC gear transition switch (HMC_SetGearTransationSwitch, digest 000 §4.3: "1 = insert a
//! smoothing transition using the axis's own Accel/Decel at gear start and on ratio changes"):
//! `gear_in` with `transition`.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, EngineError, GearIn, GearSetRatio, MasterSource};
use axes::param::ParamId;
use axes::status::CouplingPhase;
use axes::Engine;
use common::{jog_of, ok, refused};

const ACCEL: f64 = 10_000.0;
const DECEL: f64 = 5_000.0;

fn gear(transition: bool, acceleration: Option<f64>) -> Command {
    Command::from(GearIn {
        master: 0,
        slave: 1,
        numerator: 2.0,
        denominator: 1.0,
        master_source: MasterSource::Commanded,
        clutch_distance: None,
        acceleration,
        direction: None,
        phase_offset: 0,
        transition,
    })
}

fn machine() -> Engine {
    let master = common::virtual_pulse_axis();
    let slave = common::free_linear_axis(
        1.0,
        &[
            (ParamId::AxisType, 0.0),
            (ParamId::Speed, 10_000.0),
            (ParamId::Accel, ACCEL),
            (ParamId::Decel, DECEL),
            (ParamId::FastDecel, 1e7),
        ],
    );
    let mut e = common::engine_with(vec![master, slave]);
    for axis in 0..2 {
        ok(&mut e, Command::from(axes::command::Enable { axis }));
    }
    e
}

fn phase(e: &Engine) -> CouplingPhase {
    e.snapshot().couplings[0].phase
}

/// Steps until the gear is in sync, checking each tick's velocity change against `limit`;
/// returns the ticks taken.
fn ramp(e: &mut Engine, limit: f64) -> usize {
    let dt = e.period();
    for tick in 1..=10_000 {
        let before = e.axis_status(1).unwrap().cmd_vel;
        e.step();
        let after = e.axis_status(1).unwrap().cmd_vel;
        assert!(
            (after - before).abs() <= limit * dt * (1.0 + 1e-9),
            "tick {tick}: {before} → {after}"
        );
        if phase(e) == CouplingPhase::InSync {
            return tick;
        }
    }
    panic!("never in sync");
}

#[test]
fn the_slave_engages_with_its_accel_and_changes_ratio_with_its_decel() {
    let mut e = machine();
    ok(&mut e, jog_of(0, 1000.0));
    for _ in 0..10 {
        e.step();
    }
    ok(&mut e, gear(true, None));
    assert_eq!(phase(&e), CouplingPhase::Engaging);
    // 0 → 2 × 1000 at 10 000/s²: 0.2 s.
    let ticks = ramp(&mut e, ACCEL);
    let expected = (2000.0 / ACCEL / e.period()).round() as usize;
    assert!((expected..=expected + 1).contains(&ticks), "{ticks}");
    // Locked: from here the slave's travel is exactly twice the master's.
    let (m0, s0) = (
        e.axis_status(0).unwrap().cmd_pos,
        e.axis_status(1).unwrap().cmd_pos,
    );
    for _ in 0..100 {
        e.step();
        let m = e.axis_status(0).unwrap().cmd_pos - m0;
        let s = e.axis_status(1).unwrap().cmd_pos - s0;
        assert!((s - 2.0 * m).abs() < 1e-9, "{s} vs 2 × {m}");
    }
    // Ratio 1: 2000 → 1000 at the slave's decel, 0.2 s.
    ok(
        &mut e,
        Command::from(GearSetRatio {
            slave: 1,
            numerator: 1.0,
            denominator: 1.0,
        }),
    );
    assert_eq!(phase(&e), CouplingPhase::Engaging);
    let ticks = ramp(&mut e, DECEL);
    let expected = (1000.0 / DECEL / e.period()).round() as usize;
    assert!((expected..=expected + 1).contains(&ticks), "{ticks}");
    assert!((e.axis_status(1).unwrap().cmd_vel - 1000.0).abs() < 1e-9);
}

#[test]
fn a_transition_with_its_own_clutch_is_refused() {
    let mut e = machine();
    let err = refused(&mut e, gear(true, Some(100.0)));
    assert!(
        matches!(
            err,
            EngineError::InvalidArgument {
                name: "transition",
                ..
            }
        ),
        "{err:?}"
    );
    assert!(e.snapshot().couplings.is_empty());
}
