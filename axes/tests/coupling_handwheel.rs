//! Handwheel (MPG) at the engine level (issue 12 item 7): NMC S-HANDWHEEL (digest 001 §5:
//! SetHandWheelInput(256), SetHandWheel(axis 0, ratio 5, acc 1, vel 10)), the velocity and
//! acceleration limits, catching up or dropping excess counts, an axis encoder as input, the
//! axis refusing its own motion, and bad input.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, Disable, EngineError, ErrorKind, HandwheelExcess, HandwheelIn, HandwheelOut,
    HandwheelTurn,
};
use axes::{AxisFlags, Engine};
use common::{gear_in_of, move_abs_of, ok, refused, run};

fn machine(n: usize) -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), n)
}

fn wheel(axis: u16, input: u16, ratio: f64, velocity: f64, acceleration: f64) -> HandwheelIn {
    HandwheelIn {
        axis,
        input,
        numerator: ratio,
        denominator: 1.0,
        velocity,
        acceleration,
        excess: HandwheelExcess::CatchUp,
    }
}

fn turn(input: u16, counts: i64) -> Command {
    Command::from(HandwheelTurn { input, counts })
}

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

#[test]
fn s_handwheel_the_axis_follows_five_units_per_count_within_its_limits() {
    // S-HANDWHEEL: axis 0 follows the first external encoder × 5, acc 1, vel 10 (per ms in
    // NMC units; here units/s² and units/s).
    let mut e = machine(1);
    ok(&mut e, Command::from(wheel(0, 256, 5.0, 10.0, 1.0)));
    assert!(e
        .axis_status(0)
        .unwrap()
        .flags
        .contains(AxisFlags::HANDWHEEL));
    ok(&mut e, turn(256, 4));
    let (mut last_v, mut top_v) = (0.0f64, 0.0f64);
    let mut done = false;
    for _ in 0..30_000 {
        e.step();
        let s = e.axis_status(0).unwrap();
        assert!(s.cmd_vel.abs() <= 10.0 + 1e-9, "{}", s.cmd_vel);
        assert!((s.cmd_vel - last_v).abs() <= 1.0 * e.period() + 1e-9);
        last_v = s.cmd_vel;
        top_v = top_v.max(s.cmd_vel);
        if s.cmd_pos == 20.0 && s.cmd_vel == 0.0 {
            done = true;
            break;
        }
    }
    assert!(done, "did not arrive: {}", cmd(&e, 0));
    // 20 units at 1 units/s²: a triangle that peaks near √20.
    assert!(top_v > 4.0 && top_v < 4.5, "{top_v}");
    let h = e.snapshot().handwheels[0];
    assert_eq!((h.axis, h.input, h.counts, h.ratio), (0, 256, 4, 5.0));
    assert_eq!((h.target, h.lag, h.dropped), (20.0, 0.0, 0.0));
}

#[test]
fn with_drop_the_counts_the_velocity_cannot_follow_are_lost() {
    let mut e = machine(1);
    ok(
        &mut e,
        Command::from(HandwheelIn {
            excess: HandwheelExcess::Drop,
            ..wheel(0, 257, 0.01, 10.0, 1e6)
        }),
    );
    // 1000 counts in one tick = 10 units: 1 ms at 10 units/s keeps 0.01 of them.
    ok(&mut e, turn(257, 1000));
    run(&mut e, 0.1);
    assert!((cmd(&e, 0) - 0.01).abs() < 1e-9, "{}", cmd(&e, 0));
    let h = e.snapshot().handwheels[0];
    assert!((h.dropped - 9.99).abs() < 1e-9, "{h:?}");
    // Turned slowly, nothing is dropped: 1 count per tick = 10 units/s.
    for _ in 0..100 {
        ok(&mut e, turn(257, 1));
        e.step();
    }
    run(&mut e, 0.1);
    assert!((cmd(&e, 0) - 1.01).abs() < 1e-9, "{}", cmd(&e, 0));
}

#[test]
fn an_axis_encoder_drives_another_axis_and_handwheel_out_frees_it() {
    let mut e = machine(2);
    ok(&mut e, Command::from(wheel(1, 0, -0.5, 1e4, 1e6)));
    ok(&mut e, move_abs_of(0, 100.0));
    run(&mut e, 1.0);
    assert!((cmd(&e, 1) + 50.0).abs() < 1e-6, "{}", cmd(&e, 1));
    // Own motion is refused while on the wheel, and so is a coupling.
    assert_eq!(
        refused(&mut e, move_abs_of(1, 0.0)),
        EngineError::AxisOnHandwheel { axis: 1 }
    );
    assert_eq!(
        refused(&mut e, gear_in_of(0, 1)),
        EngineError::AxisOnHandwheel { axis: 1 }
    );
    ok(&mut e, Command::from(HandwheelOut { axis: 1 }));
    assert!(e.snapshot().handwheels.is_empty());
    ok(&mut e, move_abs_of(1, 0.0));
    run(&mut e, 1.0);
    assert_eq!(cmd(&e, 1), 0.0);
}

#[test]
fn a_disabled_axis_leaves_its_handwheel() {
    let mut e = machine(1);
    ok(&mut e, Command::from(wheel(0, 256, 1.0, 10.0, 100.0)));
    ok(&mut e, Command::from(Disable { axis: 0 }));
    e.step();
    assert!(e.snapshot().handwheels.is_empty());
    assert!(!e
        .axis_status(0)
        .unwrap()
        .flags
        .contains(AxisFlags::HANDWHEEL));
}

#[test]
fn bad_handwheels_are_refused_and_disturb_nothing() {
    let mut e = machine(3);
    ok(&mut e, move_abs_of(2, 100.0));
    let bad = [
        HandwheelIn {
            denominator: 0.0,
            ..wheel(0, 256, 1.0, 1.0, 1.0)
        },
        wheel(0, 256, 0.0, 1.0, 1.0),
        wheel(0, 256, f64::NAN, 1.0, 1.0),
        wheel(0, 256, 1.0, 0.0, 1.0),
        wheel(0, 256, 1.0, 1.0, f64::INFINITY),
        wheel(0, 256, 1.0, -1.0, 1.0),
        wheel(0, 0, 1.0, 1.0, 1.0),
    ];
    for c in bad {
        assert_eq!(
            refused(&mut e, Command::from(c.clone())).kind(),
            ErrorKind::InvalidArgument,
            "{c:?}"
        );
    }
    for input in [3, 255, 258, u16::MAX] {
        assert!(matches!(
            refused(&mut e, Command::from(wheel(0, input, 1.0, 1.0, 1.0))),
            EngineError::UnknownHandwheelInput { .. }
        ));
    }
    assert!(matches!(
        refused(&mut e, turn(3, 1)),
        EngineError::UnknownHandwheelInput { input: 3, .. }
    ));
    assert_eq!(
        refused(&mut e, Command::from(wheel(9, 256, 1.0, 1.0, 1.0))).kind(),
        ErrorKind::InvalidAxis
    );
    ok(&mut e, Command::from(wheel(0, 256, 1.0, 1.0, 1.0)));
    assert_eq!(
        refused(&mut e, Command::from(wheel(0, 257, 1.0, 1.0, 1.0))),
        EngineError::AxisOnHandwheel { axis: 0 }
    );
    assert_eq!(
        refused(&mut e, Command::from(HandwheelOut { axis: 1 })),
        EngineError::NotCoupled {
            axis: 1,
            what: "driven by a handwheel"
        }
    );
    // Huge turns wrap instead of overflowing.
    ok(&mut e, turn(257, i64::MAX));
    ok(&mut e, turn(257, i64::MAX));
    run(&mut e, 1.0);
    assert_eq!(cmd(&e, 2), 100.0);
}
