//! The 2-D compare's anti-jitter threshold (HMC NormalSwitch2D `dDisturbValue`, manual
//! §4.4.4.2, digest 000 §4.4; NMC `vibrateRange`, digest 001 §3.16): on a noisy actual position
//! the approach/recede test must not take jitter for receding.
// Tests: failing loudly is the point.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, CompareOutputMode, CompareStart, Enable, PositionSource};
use axes::config::AxisConfig;
use axes::status::CompareState;
use axes::{Engine, ParamId};
use common::{engine_with, free_linear_axis, jog, ok};

/// 1000 pulses and counts per unit, the encoder reading ±`noise` counts off.
fn noisy_axis(noise: f64) -> AxisConfig {
    let mut a = free_linear_axis(
        1000.0,
        &[
            (ParamId::Speed, 10.0),
            (ParamId::Accel, 1e6),
            (ParamId::Decel, 1e6),
        ],
    );
    a.encoder.noise = noise;
    a
}

fn machine(noise: f64) -> Engine {
    let mut e = engine_with(vec![noisy_axis(noise), noisy_axis(noise)]);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    ok(&mut e, Command::from(Enable { axis: 1 }));
    e
}

fn two_d(source: PositionSource, disturbance: f64) -> CompareStart {
    CompareStart {
        channel: 0,
        axis: 0,
        axis_y: Some(1),
        source,
        positions: vec![],
        start: None,
        interval: None,
        end: None,
        // 1 away from the path y = 0, a zone of 3: entered at x ≈ 47.2.
        points: vec![[50.0, 1.0]],
        error_zone: 3.0,
        disturbance,
        output: 0,
        mode: CompareOutputMode::Pulse,
        level: true,
        pulse_width: 0.001,
        min_interval: 0.0,
    }
}

/// Jog X at 10 units/s (0.01 per tick) past the point; where (commanded X) it fired.
fn fired_at(noise: f64, c: CompareStart) -> f64 {
    let mut e = machine(noise);
    ok(&mut e, Command::from(c));
    ok(&mut e, jog(10.0));
    for _ in 0..7000 {
        e.step();
        let s = e.snapshot();
        if s.compares[0].count == 1 {
            assert_eq!(s.compares[0].state, CompareState::Done);
            return s.axes[0].cmd_pos;
        }
    }
    panic!("never fired")
}

#[test]
fn jitter_fires_a_2d_point_early_without_the_threshold_and_near_the_approach_with_it() {
    // ±0.05 units of noise on each axis against 0.01 units of travel per tick.
    let early = fired_at(50.0, two_d(PositionSource::Actual, 0.0));
    assert!(early < 48.5, "jitter looks like receding at once: {early}");
    let settled = fired_at(50.0, two_d(PositionSource::Actual, 0.2));
    assert!(
        (50.0..51.5).contains(&settled),
        "receding by more than 0.2 starts past x = 50: {settled}"
    );
}

#[test]
fn without_noise_the_threshold_fires_once_the_distance_grew_by_it() {
    // Distance sqrt(1 + (x − 50)²) − 1 > 0.2 from x ≈ 50.66 on.
    let x = fired_at(0.0, two_d(PositionSource::Actual, 0.2));
    assert!((50.6..50.7).contains(&x), "{x}");
    // On the commanded position the threshold is ignored (manual: "valid only on MPos").
    let exact = fired_at(0.0, two_d(PositionSource::Commanded, 0.2));
    assert!((50.0..50.02).contains(&exact), "{exact}");
}

#[test]
fn a_path_that_grazes_the_zone_fires_once_it_is_the_threshold_beyond_the_least_distance() {
    // 2.9 from the path, zone 3: inside only for |x − 50| < 0.77. It fires when the distance
    // passes 2.9 + 0.5 ("once the zone was entered the output always fires"): x ≈ 51.775.
    let mut c = two_d(PositionSource::Actual, 0.5);
    c.points = vec![[50.0, 2.9]];
    let x = fired_at(0.0, c);
    assert!((51.77..51.79).contains(&x), "{x}");
}

#[test]
fn a_negative_threshold_is_refused() {
    let mut e = machine(0.0);
    let err = common::refused_code(&mut e, Command::from(two_d(PositionSource::Actual, -1.0)));
    assert_eq!(err, "invalid_argument");
    assert!(e.snapshot().compares.is_empty());
}
