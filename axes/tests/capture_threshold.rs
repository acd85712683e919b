//! Capture on a position threshold (issue 12 item 4; NMC advanced capture sources
//! `CAPT_EX_SRC_PRFPOS` 5 and `CAPT_EX_SRC_ENCPOS` 6, digest 001 §2.18, §3.15, S-ADVCAPT): the
//! latch is taken where the source axis's position crosses the threshold, inside the tick, with
//! the polarity of the crossing, on the capture axis (`capPosIndex`) or the source axis itself.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    CaptureArm, CaptureArmThreshold, CaptureEdge, CaptureSource, Command, PositionSource,
};
use axes::status::CaptureState;
use axes::{Engine, EngineError};
use common::{jog_of, move_abs_of, ok, refused, run};

fn machine() -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), 2)
}

fn arm(axis: u16, source_axis: u16, source: PositionSource, threshold: f64) -> Command {
    Command::from(CaptureArmThreshold {
        axis,
        channel: 1,
        source,
        source_axis: Some(source_axis),
        threshold,
        edge: CaptureEdge::Both,
        repeat: 2,
        continuous: false,
    })
}

#[test]
fn a_planned_position_crossing_latches_inside_the_tick_s_advcapt() {
    let mut e = machine();
    // 10 000 units/s: 10 per 1 ms tick; the crossing of 1234.5 falls inside a tick.
    ok(&mut e, arm(0, 0, PositionSource::Commanded, 1234.5));
    ok(&mut e, jog_of(0, 10_000.0));
    run(&mut e, 0.3);
    let c = e.triggers().capture(0, 1).unwrap().clone();
    assert_eq!(c.source, CaptureSource::CommandedPosition);
    assert_eq!(c.count, 1);
    let l = c.latches[0];
    assert!(l.rising);
    assert!((l.cmd_pos - 1234.5).abs() < 1e-6, "{}", l.cmd_pos);
    assert!((l.act_pos - 1234.5).abs() <= 1.0, "{}", l.act_pos);
    // Back down through it: the falling crossing is the second latch, and the channel is done.
    ok(&mut e, move_abs_of(0, 0.0));
    run(&mut e, 1.0);
    let c = e.triggers().capture(0, 1).unwrap().clone();
    assert_eq!((c.count, c.state), (2, CaptureState::Done));
    assert!(!c.latches[1].rising);
    assert!((c.latches[1].cmd_pos - 1234.5).abs() < 1e-6);
    assert!(e.axis_status(0).unwrap().captures >= 2);
}

#[test]
fn another_axis_encoder_crossing_latches_the_capture_axis() {
    let mut e = machine();
    // capPosIndex = axis 1, trigSrc ENCPOS of axis 0 at 500.
    ok(&mut e, arm(1, 0, PositionSource::Actual, 500.0));
    ok(&mut e, jog_of(1, 2_000.0));
    ok(&mut e, jog_of(0, 1_000.0));
    run(&mut e, 0.7);
    let c = e.triggers().capture(1, 1).unwrap().clone();
    assert_eq!(
        (c.source, c.source_axis, c.count),
        (CaptureSource::ActualPosition, 0, 1)
    );
    // Axis 0 reached 500 at t ≈ 0.5 s; axis 1 moves twice as fast: ≈ 1000 there.
    let l = c.latches[0];
    assert!((l.cmd_pos - 1000.0).abs() < 5.0, "{}", l.cmd_pos);
}

#[test]
fn a_position_source_needs_a_finite_threshold() {
    let mut e = machine();
    let r = refused(
        &mut e,
        Command::from(CaptureArm {
            axis: 0,
            channel: 0,
            source: CaptureSource::CommandedPosition,
            input: None,
            source_axis: None,
            edge: CaptureEdge::Rising,
            repeat: 1,
            continuous: false,
            window: None,
        }),
    );
    assert!(r.to_string().contains("capture_arm_threshold"), "{r}");
    let r = refused(&mut e, arm(0, 0, PositionSource::Commanded, f64::NAN));
    assert!(
        matches!(
            r,
            EngineError::InvalidArgument {
                name: "threshold",
                ..
            }
        ),
        "{r}"
    );
    let r = refused(&mut e, arm(0, 5, PositionSource::Commanded, 1.0));
    assert!(matches!(r, EngineError::InvalidAxis { axis: 5, .. }), "{r}");
    assert!(e.triggers().capture(0, 1).is_none());
}
