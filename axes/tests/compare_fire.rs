//! A manual compare output (NMC `Comp2DimensOnoff(…, 2, …)`, S-CMP-MANUAL, digest 001 §2.11):
//! one output now, as a position would fire it, without using up a position.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, CompareFire, CompareOutputMode, CompareStart, PositionSource};
use axes::status::CompareState;
use axes::{Engine, EngineError};
use common::{ok, refused};

fn machine() -> Engine {
    let mut e = common::enabled_machine(common::virtual_pulse_axis(), 2);
    let start = CompareStart {
        channel: 1,
        axis: 0,
        axis_y: Some(1),
        source: PositionSource::Actual,
        positions: vec![],
        start: None,
        interval: None,
        end: None,
        points: (0..100)
            .map(|i| [100.0 * f64::from(i) + 100.0; 2])
            .collect(),
        error_zone: 10.0,
        disturbance: 0.0,
        output: 2,
        mode: CompareOutputMode::Pulse,
        level: true,
        pulse_width: 0.003,
        min_interval: 0.0,
    };
    ok(&mut e, Command::from(start));
    e
}

#[test]
fn s_cmp_manual_fires_one_pulse_and_keeps_the_points() {
    // S-CMP-MANUAL: the S-CMP-2D set-up, then Onoff(…, 2, …): one manual output.
    let mut e = machine();
    assert!(!e.snapshot().io.do_[2]);
    ok(&mut e, Command::from(CompareFire { channel: 1 }));
    let s = e.snapshot();
    assert!(s.io.do_[2], "the pulse is on at once");
    let c = s.compares[0].clone();
    assert_eq!(
        (c.count, c.remaining, c.state),
        (1, 100, CompareState::Running)
    );
    assert_eq!(s.axes[0].compare_outputs, 1);
    // The pulse lasts its width (3 ticks), then the output goes back.
    for _ in 0..2 {
        e.step();
        assert!(e.snapshot().io.do_[2]);
    }
    e.step();
    assert!(!e.snapshot().io.do_[2]);
}

#[test]
fn a_channel_not_started_cannot_fire() {
    let mut e = machine();
    let err = refused(&mut e, Command::from(CompareFire { channel: 0 }));
    assert!(
        matches!(err, EngineError::InvalidTrigger { channel: 0, .. }),
        "{err:?}"
    );
    assert!(matches!(
        refused(&mut e, Command::from(CompareFire { channel: 8 })),
        EngineError::InvalidTrigger { channel: 8, .. }
    ));
    assert_eq!(e.snapshot().compares[0].count, 0);
}
