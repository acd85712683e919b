//! Z-phase compare outputs (HMC SwitchTZ, manual §4.4.3.4–4.4.3.8, digest 000 §4.4; HMC Switch
//! ucOutputMode 1, §8 vector 32 with the Z-phase output): an axis's positions drive another
//! axis's Z-phase output, toggled, or pulsed for an exact time from the crossing; positions
//! reached while a pulse is on are missed (manual note 5, "S1 − S0 > V·T").
// Tests: failing loudly is the point.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, CompareOutputMode, Enable, PositionSource, ZCompareStart, ZCompareStop,
};
use axes::config::AxisConfig;
use axes::status::{CompareState, ZCompareStatus};
use axes::{Engine, ParamId};
use common::{engine_with, free_linear_axis, jog, move_abs, ok, refused_code};

fn axis() -> AxisConfig {
    free_linear_axis(
        1.0,
        &[
            (ParamId::Speed, 1000.0),
            (ParamId::Accel, 1e9),
            (ParamId::Decel, 1e9),
        ],
    )
}

/// Two axes, enabled; 1 ms ticks, so a jog at 1000 moves 1 unit per tick.
fn machine() -> Engine {
    let mut e = engine_with(vec![axis(), axis()]);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    ok(&mut e, Command::from(Enable { axis: 1 }));
    e
}

fn tz(positions: &[f64], mode: CompareOutputMode, pulse_width: f64) -> ZCompareStart {
    ZCompareStart {
        channel: 0,
        axis: 0,
        source: PositionSource::Actual,
        positions: positions.to_vec(),
        output_axis: 1,
        mode,
        level: true,
        pulse_width,
    }
}

fn channel(e: &Engine) -> ZCompareStatus {
    e.snapshot().z_compares[0].clone()
}

/// Step `ticks` ticks, recording (actual position of axis 0, Z output of axis 1).
fn watch(e: &mut Engine, ticks: usize) -> Vec<(f64, bool)> {
    (0..ticks)
        .map(|_| {
            e.step();
            let s = e.snapshot();
            assert!(!s.axes[0].z_output, "only the output axis's Z moves");
            (s.axes[0].act_pos, s.axes[1].z_output)
        })
        .collect()
}

#[test]
fn toggle_mode_is_hmc_vector_32_on_another_axis_z_phase() {
    // SwitchTZ ucTimeMode 0 = Switch: targets 100 … 1000, on at 100, off at 200 …
    let targets: Vec<f64> = (1..=10).map(|k| 100.0 * f64::from(k)).collect();
    let mut e = machine();
    ok(
        &mut e,
        Command::from(tz(&targets, CompareOutputMode::Toggle, 0.0)),
    );
    assert_eq!(channel(&e).state, CompareState::Running, "state 0");
    ok(&mut e, move_abs(1050.0));
    let seen = watch(&mut e, 1200);
    for k in 1..=10 {
        let target = 100.0 * f64::from(k);
        let i = seen.iter().position(|(p, _)| *p >= target).unwrap();
        assert_eq!(seen[i].1, k % 2 == 1, "level after {target}");
        assert_eq!(seen[i - 1].1, k % 2 == 0, "level before {target}");
    }
    let c = channel(&e);
    assert_eq!((c.count, c.missed, c.remaining), (10, 0, 0));
    assert_eq!(c.state, CompareState::Done, "state 3");
}

#[test]
fn a_pulse_far_shorter_than_a_period_shows_in_the_tick_of_its_crossing_only() {
    let mut e = machine();
    // 20 µs (HMC dTime 20), 1 unit per tick.
    ok(
        &mut e,
        Command::from(tz(&[10.5, 30.5], CompareOutputMode::Pulse, 20e-6)),
    );
    ok(&mut e, jog(1000.0));
    let seen = watch(&mut e, 60);
    let high: Vec<usize> = (0..seen.len()).filter(|&i| seen[i].1).collect();
    assert_eq!(high.len(), 2, "{seen:?}");
    for (&i, target) in high.iter().zip([10.5, 30.5]) {
        assert!(seen[i].0 >= target && seen[i - 1].0 < target, "{seen:?}");
    }
    let c = channel(&e);
    assert_eq!((c.count, c.missed, c.state), (2, 0, CompareState::Done));
}

#[test]
fn a_position_reached_while_the_pulse_is_on_is_missed_and_the_next_is_answered() {
    let mut e = machine();
    // 1 ms pulses at 1 unit/ms: 11.2 comes 0.7 ms after 10.5 (S1 − S0 < V·T), 20.5 long after.
    ok(
        &mut e,
        Command::from(tz(&[10.5, 11.2, 20.5], CompareOutputMode::Pulse, 0.001)),
    );
    ok(&mut e, jog(1000.0));
    let seen = watch(&mut e, 40);
    let high: Vec<usize> = (0..seen.len()).filter(|&i| seen[i].1).collect();
    // Each 1 ms pulse starts mid-tick, so it overlaps two ticks.
    assert_eq!(high.len(), 4, "{seen:?}");
    assert_eq!(high[1], high[0] + 1);
    assert_eq!(high[3], high[2] + 1);
    assert!(seen[high[2]].0 >= 20.5 && seen[high[2] - 1].0 < 20.5);
    let c = channel(&e);
    assert_eq!((c.count, c.missed, c.remaining), (2, 1, 0));
}

#[test]
fn a_pulse_channel_idles_its_output_and_stopping_ends_a_pulse() {
    let mut e = machine();
    let mut c = tz(&[5.5], CompareOutputMode::Pulse, 0.05);
    c.level = false;
    ok(&mut e, Command::from(c));
    assert!(e.snapshot().axes[1].z_output, "idle is the opposite level");
    ok(&mut e, jog(1000.0));
    let seen = watch(&mut e, 10);
    assert!(seen.iter().any(|(_, z)| !z), "the pulse is low");
    assert!(!seen.last().unwrap().1, "50 ms pulse still on");
    ok(&mut e, Command::from(ZCompareStop { channel: 0 }));
    assert!(e.snapshot().axes[1].z_output, "back to idle");
    assert!(e.snapshot().z_compares.is_empty());
}

#[test]
fn bad_z_compares_are_refused_and_leave_the_running_channel_alone() {
    let mut e = machine();
    ok(
        &mut e,
        Command::from(tz(&[5.0], CompareOutputMode::Toggle, 0.0)),
    );
    let mut again = tz(&[6.0], CompareOutputMode::Toggle, 0.0);
    again.channel = 1;
    assert_eq!(
        refused_code(&mut e, Command::from(again.clone())),
        "invalid_trigger",
        "one channel per Z output"
    );
    again.output_axis = 0;
    ok(&mut e, Command::from(again.clone()));
    // Each replaces channel 1, whose own Z output (axis 0) it may take again.
    let toggle = |p: &[f64]| ZCompareStart {
        channel: 1,
        output_axis: 0,
        ..tz(p, CompareOutputMode::Toggle, 0.0)
    };
    let pulse = |width| ZCompareStart {
        channel: 1,
        output_axis: 0,
        ..tz(&[1.0], CompareOutputMode::Pulse, width)
    };
    let cases = [
        (toggle(&[]), "invalid_trigger"),
        (toggle(&[f64::NAN]), "invalid_argument"),
        (pulse(0.0), "invalid_argument"),
        (pulse(f64::INFINITY), "invalid_argument"),
        (
            ZCompareStart {
                channel: 8,
                ..toggle(&[1.0])
            },
            "invalid_trigger",
        ),
        (
            ZCompareStart {
                output_axis: 9,
                ..toggle(&[1.0])
            },
            "invalid_axis",
        ),
    ];
    let before = e.snapshot();
    for (c, code) in cases {
        assert_eq!(
            refused_code(&mut e, Command::from(c.clone())),
            code,
            "{c:?}"
        );
    }
    assert_eq!(e.snapshot(), before, "nothing else disturbed");
    let s = e.snapshot();
    assert_eq!(s.z_compares.len(), 2);
    assert_eq!(s.z_compares[0].total, 1);
    assert_eq!(
        refused_code(&mut e, Command::from(ZCompareStop { channel: 8 })),
        "invalid_trigger"
    );
}
