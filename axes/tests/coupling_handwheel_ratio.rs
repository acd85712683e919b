//! NMC SetHandWheelRatio at the engine level (issue 12 item 7; digest 001 §2.9): the ratio of
//! a running handwheel changes without a jump, counts before the change keep the old ratio.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, EngineError, HandwheelExcess, HandwheelIn, HandwheelSetRatio, HandwheelTurn,
};
use axes::Engine;
use common::{ok, refused, run};

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

fn turn(counts: i64) -> Command {
    Command::from(HandwheelTurn { input: 256, counts })
}

#[test]
fn a_new_ratio_applies_to_counts_after_it_without_a_jump() {
    let mut e = common::enabled_machine(common::virtual_pulse_axis(), 2);
    ok(
        &mut e,
        Command::from(HandwheelIn {
            axis: 1,
            input: 256,
            numerator: 5.0,
            denominator: 1.0,
            velocity: 1_000.0,
            acceleration: 1e6,
            excess: HandwheelExcess::CatchUp,
        }),
    );
    ok(&mut e, turn(10));
    run(&mut e, 1.0);
    assert_eq!(cmd(&e, 1), 50.0);
    // Change the ratio at rest: nothing moves.
    ok(
        &mut e,
        Command::from(HandwheelSetRatio {
            axis: Some(1),
            numerator: 1.0,
            denominator: 2.0,
        }),
    );
    e.step();
    assert_eq!(cmd(&e, 1), 50.0);
    assert_eq!(e.snapshot().handwheels[0].ratio, 0.5);
    // Counts after the change: 0.5 each.
    ok(&mut e, turn(10));
    run(&mut e, 1.0);
    assert_eq!(cmd(&e, 1), 55.0);
    // While the axis still follows: the target stays where it is, without `axis` (every
    // handwheel, NMC's one per device).
    ok(&mut e, turn(100));
    e.step();
    let before = e.snapshot().handwheels[0].target;
    ok(
        &mut e,
        Command::from(HandwheelSetRatio {
            axis: None,
            numerator: 2.0,
            denominator: 1.0,
        }),
    );
    e.step();
    assert_eq!(e.snapshot().handwheels[0].target, before);
    ok(&mut e, turn(1));
    run(&mut e, 2.0);
    assert_eq!(cmd(&e, 1), 55.0 + 50.0 + 2.0);
}

#[test]
fn a_ratio_for_an_axis_without_a_handwheel_or_of_zero_is_refused() {
    let mut e = common::enabled_machine(common::virtual_pulse_axis(), 1);
    let r = refused(
        &mut e,
        Command::from(HandwheelSetRatio {
            axis: None,
            numerator: 1.0,
            denominator: 1.0,
        }),
    );
    assert!(matches!(r, EngineError::NotCoupled { .. }), "{r}");
    let r = refused(
        &mut e,
        Command::from(HandwheelSetRatio {
            axis: Some(0),
            numerator: 1.0,
            denominator: 0.0,
        }),
    );
    assert!(r.to_string().contains("denominator"), "{r}");
}
