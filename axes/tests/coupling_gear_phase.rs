//! HMC gear phase offset (HMC_SetGearPhaseOffset, digest 000 §4.3: "delays the slave trajectory
//! by 0~128 servo cycles"; §8 vector 46: 129 is refused).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, EngineError, GearIn, MasterSource};
use axes::Engine;
use common::{move_abs_of, ok, refused};

fn gear(phase_offset: u32) -> Command {
    Command::from(GearIn {
        master: 0,
        slave: 1,
        numerator: 3.0,
        denominator: 2.0,
        master_source: MasterSource::Commanded,
        clutch_distance: None,
        acceleration: None,
        direction: None,
        phase_offset,
        transition: false,
    })
}

fn machine() -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), 2)
}

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

#[test]
fn the_slave_runs_the_gear_five_servo_periods_late() {
    let mut e = machine();
    ok(&mut e, gear(5));
    assert_eq!(e.snapshot().couplings[0].phase_offset, 5);
    ok(&mut e, move_abs_of(0, 200.0));
    let mut master = Vec::new();
    for t in 0..400 {
        e.step();
        master.push(cmd(&e, 0));
        let expected = if t >= 5 { 1.5 * master[t - 5] } else { 0.0 };
        assert!(
            (cmd(&e, 1) - expected).abs() < 1e-9,
            "tick {t}: {} vs {expected}",
            cmd(&e, 1)
        );
    }
    assert_eq!(cmd(&e, 1), 300.0);
}

#[test]
fn hmc_vector_46_an_offset_over_128_is_refused() {
    let mut e = machine();
    let err = refused(&mut e, gear(129));
    assert!(
        matches!(
            err,
            EngineError::InvalidArgument {
                name: "phase_offset",
                ..
            }
        ),
        "{err:?}"
    );
    assert!(e.snapshot().couplings.is_empty());
    ok(&mut e, gear(128));
}
