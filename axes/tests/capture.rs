//! Capture channels (issue 12 item 4): NMC capture, repeat and advanced capture (digest 001
//! §2.18, §4.6, S-CAPT, S-ADVCAPT, TV 60–62), the HMC window and states (digest 000 §4.4, §8
//! vector 31), the HIMC touch probe (digest 004 §2.12) and the latch's precision: the position at
//! the moment of the edge, inside the tick.
// Tests: failing loudly is the point.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    CaptureArm, CaptureClear, CaptureEdge, CaptureSource, CaptureWindow, Command,
    ForceDigitalInput, MoveTogether, MoveVelocity, TogetherMove,
};
use axes::config::{AxisConfig, AxisSignal, HomeSwitchConfig, InputBinding};
use axes::status::{CaptureState, CaptureStatus};
use axes::{AxisFlags, Engine, EngineConfig, EngineError, ParamId};
use common::{free_linear_axis, ok, refused, refused_code, run, run_until};
use proptest::prelude::*;

/// An NMC-style axis in pulses (1 count per unit at `units` 1) at `speed` units/s, reached
/// within microseconds.
fn pulse_axis(units: f64, speed: f64) -> AxisConfig {
    free_linear_axis(
        units,
        &[
            (ParamId::Speed, speed),
            (ParamId::Accel, 1e9),
            (ParamId::Decel, 1e9),
        ],
    )
}

/// A [`pulse_axis`] with a home cam on `[low, high]` (active low when `active_low`), its sensor
/// wired to DI 0.
fn machine(speed: f64, low: f64, high: f64, active_low: bool) -> Engine {
    let mut axis = pulse_axis(1.0, speed);
    axis.switches.home = Some(HomeSwitchConfig {
        low,
        high,
        active_low,
        filter: 0,
    });
    engine(vec![axis], true)
}

fn engine(axes: Vec<AxisConfig>, wire_home_to_di0: bool) -> Engine {
    let mut config = EngineConfig {
        axes,
        ..EngineConfig::default()
    };
    if wire_home_to_di0 {
        config.io.bindings.push(InputBinding {
            channel: 0,
            axis: 0,
            signal: AxisSignal::Home,
        });
    }
    let mut e = Engine::new(&config).expect("valid machine");
    for axis in 0..e.axis_count() as u16 {
        ok(&mut e, Command::from(axes::command::Enable { axis }));
    }
    e
}

fn arm(source: CaptureSource, edge: CaptureEdge) -> CaptureArm {
    CaptureArm {
        axis: 0,
        channel: 0,
        source,
        input: (source == CaptureSource::Di).then_some(0),
        source_axis: None,
        edge,
        repeat: 1,
        continuous: false,
        window: None,
    }
}

fn capture(e: &Engine) -> CaptureStatus {
    e.triggers().capture(0, 0).expect("channel 0 armed").clone()
}

fn captset(e: &Engine) -> bool {
    common::status(e)
        .flags
        .contains(AxisFlags::CAPTURE_TRIGGERED)
}

fn jog(e: &mut Engine, velocity: f64) {
    ok(e, common::jog(velocity));
}

fn move_to(e: &mut Engine, position: f64) {
    ok(e, common::move_abs(position));
    run_until(e, 60.0, |s| {
        s.cmd_pos == position && !s.flags.contains(AxisFlags::MOVING)
    })
    .expect("move done");
}

#[test]
fn tv60_di0_falls_at_1234_latches_1234_and_clear_resets_captset() {
    // S-CAPT: MtSetCaptSns(ax, CAPT_MODE_IO, CAPT_IO_SRC_DI0, 0 = falling); MtSetCapt. DI0 is a
    // sensor that goes low when the axis leaves [−∞, 1234], passed at 7777 pulses/s (7.8 per
    // tick): the latch holds the encoder count of the edge, not of the tick after it.
    let mut e = machine(7777.0, f64::NEG_INFINITY, 1234.0, false);
    ok(
        &mut e,
        Command::from(arm(CaptureSource::Di, CaptureEdge::Falling)),
    );
    assert!(!captset(&e));
    jog(&mut e, 7777.0);
    run_until(&mut e, 1.0, |s| {
        s.flags.contains(AxisFlags::CAPTURE_TRIGGERED)
    })
    .expect("captured");
    let c = capture(&e);
    assert_eq!(c.state, CaptureState::Done);
    assert_eq!(c.count, 1);
    let latch = c.latches[0];
    assert_eq!(latch.encoder_counts, 1234, "MtGetCaptPos");
    assert_eq!(latch.act_pos, 1234.0);
    assert!(!latch.rising);
    let status = common::status(&e);
    assert!(status.encoder_counts > 1234);
    assert_eq!((status.captures, status.capture_position), (1, 1234.0));
    // One shot: later edges do not latch.
    run(&mut e, 0.1);
    assert_eq!(capture(&e).count, 1);
    // MtClrCaptSts.
    ok(
        &mut e,
        Command::from(CaptureClear {
            axis: 0,
            channel: 0,
        }),
    );
    assert!(!captset(&e));
    assert!(e.triggers().capture(0, 0).is_none());
    assert!(e.snapshot().captures.is_empty());
}

#[test]
fn tv60_a_di_forced_by_command_latches_where_the_axis_stands() {
    let mut e = machine(5000.0, 1e9, 2e9, false);
    let force = |value| {
        Command::from(ForceDigitalInput {
            channel: 0,
            value: Some(value),
        })
    };
    ok(&mut e, force(true));
    ok(
        &mut e,
        Command::from(arm(CaptureSource::Di, CaptureEdge::Falling)),
    );
    move_to(&mut e, 1234.0);
    assert!(!captset(&e), "no edge yet");
    ok(&mut e, force(false));
    assert!(captset(&e), "BIT_AXIS_CAPTSET at once");
    let latch = capture(&e).latches[0];
    assert_eq!(latch.encoder_counts, 1234);
    assert_eq!(latch.cmd_pos, 1234.0);
    assert_eq!(latch.tick, e.tick());
    assert!(e.snapshot().axes[0]
        .flags
        .contains(AxisFlags::CAPTURE_TRIGGERED));
}

#[test]
fn tv61_advanced_capture_latches_the_leading_and_the_trailing_edge() {
    // S-ADVCAPT: trigSrc GPI DI0, trigValue 0 (active low); DI0 is low while the axis is in
    // [500, 1500]. Both edges, two latches: pos[0] = 500 (leading), pos[1] = 1500 (trailing).
    let mut e = machine(3333.0, 500.0, 1500.0, true);
    let mut c = arm(CaptureSource::Di, CaptureEdge::Both);
    c.repeat = 2;
    ok(&mut e, Command::from(c));
    jog(&mut e, 3333.0);
    run_until(&mut e, 2.0, |s| s.act_pos > 1600.0).expect("past the pulse");
    let c = capture(&e);
    assert_eq!(c.state, CaptureState::Done, "captSts = 0x3");
    let latches: Vec<(bool, i64)> = c
        .latches
        .iter()
        .map(|l| (l.rising, l.encoder_counts))
        .collect();
    assert_eq!(latches, vec![(false, 500), (true, 1500)]);
}

#[test]
fn tv62_repeat_above_64_is_refused_and_nothing_is_armed() {
    let mut e = machine(1000.0, 0.0, 1.0, false);
    for repeat in [65, 0] {
        let mut c = arm(CaptureSource::Home, CaptureEdge::Rising);
        c.repeat = repeat;
        let err = refused(&mut e, Command::from(c));
        assert!(
            matches!(err, EngineError::InvalidArgument { name: "repeat", .. }),
            "{err}"
        );
    }
    assert!(e.snapshot().captures.is_empty());
    let mut c = arm(CaptureSource::Home, CaptureEdge::Rising);
    c.repeat = 64;
    ok(&mut e, Command::from(c));
}

#[test]
fn repeated_capture_keeps_every_index_in_order() {
    // NMC MtSetCaptRepeat(ax, 3): three index pulses, one every 10 000 counts.
    let mut e = machine(50_000.0, 1e9, 2e9, false);
    let mut c = arm(CaptureSource::Index, CaptureEdge::Rising);
    c.repeat = 3;
    ok(&mut e, Command::from(c));
    jog(&mut e, 50_000.0);
    run(&mut e, 1.0);
    let c = capture(&e);
    let counts: Vec<i64> = c.latches.iter().map(|l| l.encoder_counts).collect();
    assert_eq!(counts, vec![10_000, 20_000, 30_000]);
    assert_eq!(c.state, CaptureState::Done);
}

#[test]
fn hmc_vector_31_window_states_and_an_edge_outside_the_window() {
    // HMC_CaptureConfig(0, rising, Z, axis 0, capture axis 0, inside, −100, 1000); Z every 500
    // counts from `offset`.
    let z_axis = |offset| {
        let mut a = pulse_axis(1.0, 2000.0);
        a.encoder.counts_per_rev = 500;
        a.encoder.index_offset = offset;
        a
    };
    // Armed at −300: the Z at −250 is outside the window, the one at 250 inside.
    let mut e = engine(vec![z_axis(250)], false);
    move_to(&mut e, -300.0);
    let mut c = arm(CaptureSource::Index, CaptureEdge::Rising);
    c.window = Some(CaptureWindow {
        low: -100.0,
        high: 1000.0,
        outside: false,
    });
    ok(&mut e, Command::from(c.clone()));
    assert_eq!(capture(&e).state, CaptureState::OutsideWindow, "state 1");
    jog(&mut e, 2000.0);
    run_until(&mut e, 1.0, |s| s.act_pos >= -90.0).expect("inside");
    assert_eq!(capture(&e).state, CaptureState::Waiting, "state 2");
    assert_eq!(capture(&e).count, 0, "the Z at −250 was outside");
    run_until(&mut e, 1.0, |s| s.act_pos >= 300.0).expect("past Z at 250");
    let done = capture(&e);
    assert_eq!(done.state, CaptureState::Done, "state 3");
    assert_eq!(done.latches[0].act_pos, 250.0, "HMC_CaptureGetMpos");

    // A Z edge at MPos 1500 does not capture.
    let mut e = engine(vec![z_axis(0)], false);
    move_to(&mut e, 1200.0);
    ok(&mut e, Command::from(c));
    jog(&mut e, 2000.0);
    run_until(&mut e, 1.0, |s| s.act_pos >= 1700.0).expect("past Z at 1500");
    let c = capture(&e);
    assert_eq!(c.count, 0);
    assert_eq!(c.state, CaptureState::OutsideWindow);
    assert!(!captset(&e));
}

#[test]
fn himc_touch_probe_single_and_continuous() {
    // SetTouchProbe1Func(axis, Z, single, rising) + EnableTouchProbe1: enabled, then triggered
    // after the first index (HMC vector 57: 0x60B9 = enabled + rising captured).
    let mut e = machine(50_000.0, 1e9, 2e9, false);
    ok(
        &mut e,
        Command::from(arm(CaptureSource::Index, CaptureEdge::Rising)),
    );
    assert_eq!(capture(&e).count, 0, "enabled, not triggered");
    let mut cont = arm(CaptureSource::Index, CaptureEdge::Rising);
    cont.channel = 1;
    cont.continuous = true;
    ok(&mut e, Command::from(cont));
    jog(&mut e, 50_000.0);
    run(&mut e, 1.0);
    let single = capture(&e);
    assert_eq!((single.count, single.state), (1, CaptureState::Done));
    assert_eq!(single.latches[0].encoder_counts, 10_000);
    let cont = e.triggers().capture(0, 1).expect("channel 1").clone();
    assert_eq!(
        cont.state,
        CaptureState::Waiting,
        "continuous never completes"
    );
    assert_eq!(
        cont.count, 4,
        "indices at 10 000 … 40 000 in 1 s at 50 000/s"
    );
    assert_eq!(cont.latches.len(), 1, "keeps the newest");
    assert_eq!(cont.latches[0].encoder_counts, 40_000);
}

#[test]
fn a_capture_on_another_axis_signal_interpolates_the_capture_axis() {
    // HMC captures one axis on another's Z: axis 1 moves at half axis 0's speed, so its
    // position at axis 0's index is half of it, interpolated inside the tick.
    let speed = 7_000.0;
    let mut fast = pulse_axis(1.0, speed);
    fast.params.insert(ParamId::AxisType, 0.0);
    let mut slow = fast.clone();
    slow.params.insert(ParamId::Speed, speed / 2.0);
    let mut e = engine(vec![fast, slow], false);
    let mut c = arm(CaptureSource::Index, CaptureEdge::Rising);
    c.axis = 1;
    c.source_axis = Some(0);
    ok(&mut e, Command::from(c));
    ok(
        &mut e,
        Command::from(MoveTogether {
            moves: [(0, speed), (1, speed / 2.0)]
                .map(|(axis, velocity)| {
                    TogetherMove::MoveVelocity(MoveVelocity {
                        axis,
                        velocity,
                        acceleration: None,
                        deceleration: None,
                        jerk: None,
                        buffer_mode: Default::default(),
                    })
                })
                .to_vec(),
        }),
    );
    run(&mut e, 2.0);
    let c = e.triggers().capture(1, 0).expect("armed").clone();
    assert_eq!(c.count, 1);
    assert!(
        // 5000 less what the two 1e9/s² ramps differ by (3500 · 1.75 µs ≈ 0.006); the tick's
        // end would be up to 3.5 away.
        (c.latches[0].cmd_pos - 5000.0).abs() < 0.01,
        "{:?}",
        c.latches[0]
    );
    assert!(e.snapshot().axes[1]
        .flags
        .contains(AxisFlags::CAPTURE_TRIGGERED));
    assert!(!e.snapshot().axes[0]
        .flags
        .contains(AxisFlags::CAPTURE_TRIGGERED));
}

#[test]
fn bad_capture_commands_are_typed_and_disturb_nothing() {
    let mut e = machine(1000.0, 0.0, 1.0, false);
    let base = arm(CaptureSource::Home, CaptureEdge::Rising);
    ok(&mut e, Command::from(base.clone()));
    let before = e.snapshot();
    let cases: Vec<(CaptureArm, &str)> = vec![
        (
            CaptureArm {
                axis: 9,
                ..base.clone()
            },
            "invalid_axis",
        ),
        (
            CaptureArm {
                source_axis: Some(9),
                ..base.clone()
            },
            "invalid_axis",
        ),
        (
            CaptureArm {
                channel: 8,
                ..base.clone()
            },
            "invalid_trigger",
        ),
        (
            CaptureArm {
                source: CaptureSource::Di,
                input: None,
                ..base.clone()
            },
            "invalid_trigger",
        ),
        (
            CaptureArm {
                source: CaptureSource::Di,
                input: Some(64),
                ..base.clone()
            },
            "invalid_channel",
        ),
        (
            CaptureArm {
                input: Some(1),
                ..base.clone()
            },
            "invalid_trigger",
        ),
        (
            CaptureArm {
                window: Some(CaptureWindow {
                    low: 5.0,
                    high: 1.0,
                    outside: false,
                }),
                ..base.clone()
            },
            "invalid_trigger",
        ),
        (
            CaptureArm {
                window: Some(CaptureWindow {
                    low: f64::NAN,
                    high: 1.0,
                    outside: false,
                }),
                ..base.clone()
            },
            "invalid_argument",
        ),
    ];
    for (c, code) in cases {
        assert_eq!(refused_code(&mut e, Command::from(c)), code);
    }
    assert_eq!(e.snapshot(), before);
    // An unknown source is refused by the JSON itself.
    let err =
        serde_json::from_str::<Command>(r#"{"type":"capture_arm","axis":0,"source":"probe"}"#)
            .expect_err("unknown source");
    assert!(err.to_string().contains("unknown variant `probe`"), "{err}");
}

#[test]
fn captures_are_deterministic() {
    let run_once = || {
        let mut e = machine(4321.0, 700.0, 900.0, false);
        let mut c = arm(CaptureSource::Home, CaptureEdge::Both);
        c.repeat = 2;
        ok(&mut e, Command::from(c));
        jog(&mut e, 4321.0);
        run(&mut e, 0.5);
        e.snapshot()
    };
    let a = run_once();
    assert_eq!(a.captures[0].count, 2);
    assert_eq!(a, run_once());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A capture latches within one encoder count of the true crossing, whatever the speed
    /// (up to many counts per tick) and wherever the switch is.
    #[test]
    fn a_capture_latches_within_one_count_of_the_crossing(
        speed in 10.0f64..200_000.0,
        edge in 5.0f64..2_000.0,
        counts_per_unit in prop_oneof![Just(1.0), Just(1000.0)],
        virtual_axis in any::<bool>(),
    ) {
        let mut axis = pulse_axis(counts_per_unit, speed / counts_per_unit);
        if virtual_axis {
            axis.params.insert(ParamId::AxisType, 0.0);
        }
        let edge = edge / counts_per_unit;
        axis.switches.home = Some(HomeSwitchConfig {
            low: edge,
            high: f64::INFINITY,
            active_low: false,
            filter: 0,
        });
        let mut e = engine(vec![axis], false);
        ok(&mut e, Command::from(arm(CaptureSource::Home, CaptureEdge::Rising)));
        jog(&mut e, speed / counts_per_unit);
        let mut before = common::status(&e);
        let mut found = None;
        for _ in 0..100_000 {
            e.step();
            if captset(&e) {
                found = Some((before, common::status(&e)));
                break;
            }
            before = common::status(&e);
        }
        let (before, after) = found.expect("captured");
        let latch = capture(&e).latches[0];
        let count = 1.0 / counts_per_unit;
        prop_assert!((latch.act_pos - edge).abs() <= count, "{latch:?} vs {edge}");
        prop_assert!(
            (latch.encoder_counts as f64 - edge * counts_per_unit).abs() <= 1.0,
            "{latch:?}"
        );
        // Not the tick's end (unless the edge was there): the commanded position lies inside
        // the tick's travel.
        prop_assert!(before.cmd_pos <= latch.cmd_pos && latch.cmd_pos <= after.cmd_pos);
        prop_assert!(latch.tick == e.tick());
    }
}

#[test]
fn a_limit_switch_latches_where_the_motor_crosses_it() {
    // NMC CAPT_IO_SRC_LMTP: the positive limit at 300.5, passed at 3.3 pulses a tick.
    let mut axis = pulse_axis(1.0, 3333.0);
    axis.switches.limit_pos = Some(axes::config::SwitchConfig {
        position: 300.5,
        active_low: false,
        filter: 0,
    });
    let mut e = engine(vec![axis], false);
    ok(
        &mut e,
        Command::from(arm(CaptureSource::LimitPos, CaptureEdge::Rising)),
    );
    jog(&mut e, 3333.0);
    run(&mut e, 0.2);
    let c = capture(&e);
    assert_eq!(c.count, 1);
    let latch = c.latches[0];
    assert!(latch.rising);
    assert!(
        (latch.encoder_counts as f64 - 300.5).abs() <= 1.0,
        "{latch:?}"
    );
    assert!(common::status(&e).flags.contains(AxisFlags::HW_LIMIT_POS));
}

#[test]
fn a_forced_home_switch_edges_at_the_tick_boundary() {
    let mut e = machine(1000.0, 1e9, 2e9, false);
    ok(
        &mut e,
        Command::from(arm(CaptureSource::Home, CaptureEdge::Rising)),
    );
    jog(&mut e, 1000.0);
    run(&mut e, 0.05);
    let before = common::status(&e);
    common::force(&mut e, axes::command::AxisInput::Home, Some(true));
    e.step();
    let latch = capture(&e).latches[0];
    assert_eq!(latch.tick, e.tick());
    assert_eq!(
        latch.cmd_pos, before.cmd_pos,
        "where the command found the axis"
    );
    assert!(common::status(&e).cmd_pos > before.cmd_pos);
}
