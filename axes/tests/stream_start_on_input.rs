//! PT streams started by a digital input edge (issue 12 item 3; NMC `MtPtStartMtnEx(axis,
//! diIndex, diSns)`, digest 001 §2.8 and §4.7, the DI form of S-PT-STATIC's start): the stream
//! starts before the first tick that sees the edge of the chosen polarity, not on the other
//! edge, and several axes armed on one input start in the same tick.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    CaptureEdge, Command, EngineError, ForceDigitalInput, PtKind, PtPoint, PtPush, StreamClear,
    StreamStartOnInput,
};
use axes::config::{EngineConfig, IoConfig};
use axes::status::StreamInputStart;
use axes::Engine;
use common::{ok, refused};

fn machine() -> Engine {
    let mut e = Engine::new(&EngineConfig {
        axes: vec![common::virtual_pulse_axis(); 2],
        io: IoConfig {
            digital_inputs: 4,
            digital_outputs: 4,
            ..IoConfig::default()
        },
        ..EngineConfig::default()
    })
    .unwrap();
    for axis in 0..2 {
        ok(&mut e, Command::from(axes::command::Enable { axis }));
    }
    e
}

/// S-PT-STATIC's points (TV 55): 40000 pulses in 300 ms.
fn push(e: &mut Engine, axis: u16) {
    let points = [
        (10_000.0, 100.0, PtKind::Normal),
        (30_000.0, 200.0, PtKind::Normal),
        (40_000.0, 300.0, PtKind::Stop),
    ]
    .iter()
    .map(|&(position, time_ms, kind)| PtPoint {
        position,
        time_ms,
        kind,
    })
    .collect();
    ok(e, Command::from(PtPush { axis, points }));
}

fn di(e: &mut Engine, channel: u16, value: bool) {
    ok(
        e,
        Command::from(ForceDigitalInput {
            channel,
            value: Some(value),
        }),
    );
}

fn arm(e: &mut Engine, axis: u16, edge: CaptureEdge) {
    ok(
        e,
        Command::from(StreamStartOnInput {
            axis,
            input: 2,
            edge,
        }),
    );
}

#[test]
fn the_streams_start_together_on_the_rising_edge_only() {
    let mut e = machine();
    push(&mut e, 0);
    push(&mut e, 1);
    di(&mut e, 2, true);
    arm(&mut e, 0, CaptureEdge::Rising);
    arm(&mut e, 1, CaptureEdge::Rising);
    assert_eq!(
        e.snapshot().stream_input_starts,
        vec![
            StreamInputStart {
                axis: 0,
                input: 2,
                edge: CaptureEdge::Rising
            },
            StreamInputStart {
                axis: 1,
                input: 2,
                edge: CaptureEdge::Rising
            },
        ]
    );
    // A falling edge does not start a rising arm.
    di(&mut e, 2, false);
    for _ in 0..10 {
        e.step();
    }
    let s = e.snapshot();
    assert!(!s.axes[0].stream.running && !s.axes[1].stream.running);
    assert_eq!(s.axes[0].cmd_pos, 0.0);
    di(&mut e, 2, true);
    e.step();
    let s = e.snapshot();
    assert!(s.axes[0].stream.running && s.axes[1].stream.running);
    assert!(s.stream_input_starts.is_empty(), "an arm fires once");
    // Both take their first sample in this tick, as after a `stream_start` between ticks; at
    // 300 ms (TV 55) both stand at 40000.
    assert_eq!(s.axes[0].cmd_pos, s.axes[1].cmd_pos);
    assert!(s.axes[0].cmd_pos > 0.0);
    for _ in 0..299 {
        e.step();
    }
    let s = e.snapshot();
    assert_eq!((s.axes[0].cmd_pos, s.axes[1].cmd_pos), (40_000.0, 40_000.0));
}

#[test]
fn falling_edge_arm_and_disarm_by_stream_clear() {
    let mut e = machine();
    push(&mut e, 0);
    push(&mut e, 1);
    di(&mut e, 2, true);
    arm(&mut e, 0, CaptureEdge::Falling);
    arm(&mut e, 1, CaptureEdge::Falling);
    ok(&mut e, Command::from(StreamClear { axis: 1 }));
    assert_eq!(e.snapshot().stream_input_starts.len(), 1);
    di(&mut e, 2, false);
    e.step();
    let s = e.snapshot();
    assert!(s.axes[0].stream.running);
    assert!(!s.axes[1].stream.running);
}

#[test]
fn an_arm_on_a_missing_input_or_axis_is_refused() {
    let mut e = machine();
    let r = refused(
        &mut e,
        Command::from(StreamStartOnInput {
            axis: 0,
            input: 4,
            edge: CaptureEdge::Rising,
        }),
    );
    assert!(
        matches!(r, EngineError::InvalidChannel { channel: 4, .. }),
        "{r}"
    );
    let r = refused(
        &mut e,
        Command::from(StreamStartOnInput {
            axis: 7,
            input: 0,
            edge: CaptureEdge::Rising,
        }),
    );
    assert!(matches!(r, EngineError::InvalidAxis { axis: 7, .. }), "{r}");
    assert!(e.snapshot().stream_input_starts.is_empty());
}
