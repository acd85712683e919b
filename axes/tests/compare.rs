//! Position-compare outputs (issue 12 item 5): 1-D lists (HMC Switch / NormalSwitch1D, digest
//! 000 §4.4 and §8 vector 32), grids (HIMC PT trigger, digest 004 §2.11), 2-D closest approach
//! (NMC §2.11, §4.6, S-CMP-2D, TV 63; HMC NormalSwitch2D); outputs in the I/O image at the tick
//! they fire.
// Tests: failing loudly is the point.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, CompareOutputMode, CompareStart, CompareStop, PositionSource};
use axes::config::AxisConfig;
use axes::status::{CompareState, CompareStatus};
use axes::{Engine, EngineError, ParamId};
use common::{
    engine_with, free_linear_axis, group_line, move_abs, ok, refused, refused_code, run, with_group,
};
use proptest::prelude::*;

fn axis(speed: f64) -> AxisConfig {
    free_linear_axis(
        1.0,
        &[
            (ParamId::Speed, speed),
            (ParamId::Accel, 1e6),
            (ParamId::Decel, 1e6),
        ],
    )
}

fn machine(speed: f64) -> Engine {
    let mut e = engine_with(vec![axis(speed)]);
    ok(&mut e, Command::from(axes::command::Enable { axis: 0 }));
    e
}

fn list(positions: &[f64]) -> CompareStart {
    CompareStart {
        channel: 0,
        axis: 0,
        axis_y: None,
        source: PositionSource::Commanded,
        positions: positions.to_vec(),
        start: None,
        interval: None,
        end: None,
        points: vec![],
        error_zone: 0.0,
        disturbance: 0.0,
        output: 0,
        mode: CompareOutputMode::Pulse,
        level: true,
        pulse_width: 0.0,
        min_interval: 0.0,
    }
}

fn compare(e: &Engine) -> CompareStatus {
    e.triggers().compare(0).expect("channel 0").clone()
}

/// Step `ticks` ticks, recording (commanded position of axis 0, outputs fired so far, DO 0).
fn watch(e: &mut Engine, ticks: usize) -> Vec<(f64, u32, bool)> {
    (0..ticks)
        .map(|_| {
            e.step();
            let s = e.snapshot();
            (s.axes[0].cmd_pos, s.compares[0].count, s.io.do_[0])
        })
        .collect()
}

#[test]
fn hmc_vector_32_toggles_at_every_hundred_and_goes_idle_after_the_tenth() {
    // HMC_SwitchConfig(0, …, targets 100, 200 … 1000): laser on at 100, off at 200 …
    let mut e = machine(5000.0);
    let targets: Vec<f64> = (1..=10).map(|k| 100.0 * f64::from(k)).collect();
    let mut c = list(&targets);
    c.mode = CompareOutputMode::Toggle;
    ok(&mut e, Command::from(c));
    assert_eq!(compare(&e).state, CompareState::Running, "state 0");
    ok(&mut e, move_abs(1050.0));
    let seen = watch(&mut e, 400);
    for k in 1..=10u32 {
        let (pos, _, level) = seen.iter().find(|(_, n, _)| *n == k).copied().unwrap();
        assert!(pos >= 100.0 * f64::from(k), "fired at {pos}");
        assert_eq!(level, k % 2 == 1, "on at odd targets, off at even");
    }
    let c = compare(&e);
    assert_eq!((c.count, c.remaining, c.state), (10, 0, CompareState::Done));
    assert_eq!(common::status(&e).compare_outputs, 10);
}

#[test]
fn a_pulse_shows_in_the_io_image_for_its_width_and_in_the_tick_it_fires() {
    let mut e = machine(1000.0); // 1 unit per tick
    let mut c = list(&[10.5]);
    c.pulse_width = 0.003;
    ok(&mut e, Command::from(c));
    ok(&mut e, common::jog(1000.0));
    let seen = watch(&mut e, 30);
    let high: Vec<usize> = (0..seen.len()).filter(|&i| seen[i].2).collect();
    assert_eq!(high.len(), 3, "3 ms = 3 ticks");
    let first = high[0];
    assert_eq!(high, vec![first, first + 1, first + 2]);
    assert!(
        seen[first].0 >= 10.5 && seen[first - 1].0 < 10.5,
        "{seen:?}"
    );
    assert_eq!(seen[first].1, 1);
}

#[test]
fn himc_pt_trigger_grid_fires_every_interval_up_to_end_in_either_direction() {
    // SetPT_StartPos 10, SetPT_EndPos 50, SetPT_Interval 10: outputs at 10, 20 … 50.
    let mut e = machine(2000.0);
    let grid = |start, end| CompareStart {
        start: Some(start),
        interval: Some(10.0),
        end: Some(end),
        ..list(&[])
    };
    ok(&mut e, Command::from(grid(10.0, 50.0)));
    assert_eq!(compare(&e).total, 5);
    ok(&mut e, move_abs(100.0));
    let up = watch(&mut e, 200);
    let c = compare(&e);
    assert_eq!((c.count, c.state), (5, CompareState::Done));
    for k in 1..=5u32 {
        let (pos, _, _) = up.iter().find(|(_, n, _)| *n == k).copied().unwrap();
        let target = 10.0 * f64::from(k);
        assert!(pos >= target && pos < target + 2.5, "{target}: {pos}");
    }
    // Reverse: start 50 > end 10 (SetPT_EndIndex reverse), moving down from 100.
    ok(&mut e, Command::from(grid(50.0, 10.0)));
    ok(&mut e, move_abs(0.0));
    let down = watch(&mut e, 200);
    let (pos, _, _) = down.iter().find(|(_, n, _)| *n == 1).copied().unwrap();
    assert!(pos <= 50.0 && pos > 47.5, "{pos}");
    assert_eq!(compare(&e).count, 5);
}

#[test]
fn positions_passed_in_one_tick_all_fire_and_the_minimum_interval_spaces_them() {
    let mut e = machine(10_000.0); // 10 units per tick
    let mut c = list(&[100.5, 101.0, 101.5]);
    c.mode = CompareOutputMode::Toggle;
    ok(&mut e, Command::from(c.clone()));
    ok(&mut e, move_abs(200.0));
    let seen = watch(&mut e, 40);
    let first = seen.iter().position(|s| s.1 > 0).unwrap();
    assert_eq!(seen[first].1, 3, "all three in the tick that passes them");

    let mut e = machine(10_000.0);
    c.min_interval = 0.002;
    ok(&mut e, Command::from(c));
    ok(&mut e, move_abs(200.0));
    let seen = watch(&mut e, 40);
    let ticks: Vec<usize> = (1..=3)
        .map(|k| seen.iter().position(|s| s.1 >= k).unwrap())
        .collect();
    assert_eq!(ticks, vec![ticks[0], ticks[0] + 2, ticks[0] + 4]);
}

#[test]
fn tv63_s_cmp_2d_fires_100_pulses_along_the_diagonal() {
    // S-CMP-2D: dir1No 0, dir2No 1, pulse, errZone 10, gateTime 10 µs, posSrc 1 (encoder);
    // points (100i+100, 100i+100), i < 100; then a line (0,0) → (10000,10000).
    let axes = vec![axis(10_000.0), axis(10_000.0)];
    let mut e = with_group(engine_with(axes), &[0, 1]);
    let points: Vec<[f64; 2]> = (0..100)
        .map(|i| [100.0 * f64::from(i) + 100.0; 2])
        .collect();
    ok(
        &mut e,
        Command::from(CompareStart {
            axis_y: Some(1),
            source: PositionSource::Actual,
            points: points.clone(),
            error_zone: 10.0,
            disturbance: 0.0,
            pulse_width: 10e-6,
            ..list(&[])
        }),
    );
    assert_eq!(compare(&e).remaining, 100, "usedSpace");
    ok(&mut e, Command::from(group_line(1, &[10_000.0, 10_000.0])));
    let mut rises = 0;
    let mut last = false;
    let mut fired_at = vec![];
    // Until the path is done and a tick after (the last point is where the path stops).
    for _ in 0..200_000 {
        let before = e.snapshot();
        if before.compares[0].state == CompareState::Done {
            break;
        }
        e.step();
        let s = e.snapshot();
        let level = s.io.do_[0];
        if level && !last {
            rises += 1;
        }
        last = level;
        if s.compares[0].count > before.compares[0].count {
            // The point fired lies within the zone of this tick's travel.
            let k = before.compares[0].count as usize;
            let p = points[k];
            let (a, b) = (
                [before.axes[0].act_pos, before.axes[1].act_pos],
                [s.axes[0].act_pos, s.axes[1].act_pos],
            );
            fired_at.push(segment_distance(p, a, b));
        }
    }
    let c = compare(&e);
    assert_eq!(c.count, 100, "outCount");
    assert_eq!(c.remaining, 0, "usedSpace");
    assert_eq!(c.state, CompareState::Done, "sts back to 0");
    assert_eq!(rises, 100, "one pulse each");
    assert!(fired_at.iter().all(|d| *d <= 10.0), "{fired_at:?}");
}

fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1]];
    let uu = u[0] * u[0] + u[1] * u[1];
    let t = if uu > 0.0 {
        (((p[0] - a[0]) * u[0] + (p[1] - a[1]) * u[1]) / uu).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * u[0]).hypot(p[1] - a[1] - t * u[1])
}

#[test]
fn a_2d_point_off_the_path_fires_at_the_closest_approach_and_one_outside_the_zone_waits() {
    let axes = vec![axis(1000.0), axis(1000.0)];
    let mut e = with_group(engine_with(axes), &[0, 1]);
    ok(
        &mut e,
        Command::from(CompareStart {
            axis_y: Some(1),
            points: vec![[50.0, 3.0], [80.0, 20.0]],
            error_zone: 5.0,
            disturbance: 0.0,
            ..list(&[])
        }),
    );
    ok(&mut e, Command::from(group_line(1, &[100.0, 0.0])));
    let mut fired = None;
    for _ in 0..1000 {
        e.step();
        let s = e.snapshot();
        if fired.is_none() && s.compares[0].count == 1 {
            fired = Some(s.axes[0].cmd_pos);
        }
    }
    let x = fired.expect("fired");
    assert!(
        (50.0..51.5).contains(&x),
        "the tick whose travel holds x = 50: {x}"
    );
    let c = compare(&e);
    assert_eq!(
        (c.count, c.remaining),
        (1, 1),
        "(80, 20) is 20 away: never within 5"
    );
    assert_eq!(c.state, CompareState::Running);
}

#[test]
fn compare_stop_ends_a_pulse_and_drops_the_channel() {
    let mut e = machine(1000.0);
    let mut c = list(&[5.5]);
    c.pulse_width = 1.0;
    ok(&mut e, Command::from(c));
    ok(&mut e, move_abs(20.0));
    run(&mut e, 0.05);
    assert!(e.snapshot().io.do_[0]);
    ok(&mut e, Command::from(CompareStop { channel: 0 }));
    let s = e.snapshot();
    assert!(!s.io.do_[0]);
    assert!(s.compares.is_empty());
}

#[test]
fn bad_compare_commands_are_typed_and_disturb_nothing() {
    let mut e = machine(1000.0);
    ok(&mut e, Command::from(list(&[1.0])));
    let before = e.snapshot();
    let base = list(&[1.0]);
    let cases: Vec<(CompareStart, &str)> = vec![
        (
            CompareStart {
                output: 64,
                ..base.clone()
            },
            "invalid_channel",
        ),
        (
            CompareStart {
                channel: 8,
                ..base.clone()
            },
            "invalid_trigger",
        ),
        (
            CompareStart {
                axis: 3,
                ..base.clone()
            },
            "invalid_axis",
        ),
        (list(&[]), "invalid_trigger"),
        (list(&[1.0, f64::NAN]), "invalid_argument"),
        (list(&[f64::INFINITY]), "invalid_argument"),
        (
            CompareStart {
                points: vec![[1.0, 1.0]],
                ..base.clone()
            },
            "invalid_trigger",
        ),
        (
            CompareStart {
                axis_y: Some(0),
                points: vec![[1.0, 1.0]],
                positions: vec![],
                ..base.clone()
            },
            "invalid_trigger",
        ),
        (
            CompareStart {
                positions: vec![],
                start: Some(0.0),
                interval: Some(1.0),
                ..base.clone()
            },
            "invalid_trigger",
        ),
        (
            CompareStart {
                positions: vec![],
                start: Some(0.0),
                interval: Some(0.0),
                end: Some(10.0),
                ..base.clone()
            },
            "invalid_argument",
        ),
        (
            CompareStart {
                positions: vec![],
                start: Some(0.0),
                interval: Some(1e-9),
                end: Some(1e9),
                ..base.clone()
            },
            "invalid_trigger",
        ),
        (
            CompareStart {
                pulse_width: -1.0,
                ..base.clone()
            },
            "invalid_argument",
        ),
        (
            CompareStart {
                min_interval: f64::NAN,
                ..base.clone()
            },
            "invalid_argument",
        ),
        (
            CompareStart {
                positions: vec![0.0; 65_537],
                ..base.clone()
            },
            "invalid_trigger",
        ),
    ];
    for (c, code) in cases {
        assert_eq!(refused_code(&mut e, Command::from(c)), code);
    }
    assert_eq!(e.snapshot(), before);
    let err = refused(&mut e, Command::from(CompareStop { channel: 9 }));
    assert!(matches!(err, EngineError::InvalidTrigger { .. }), "{err}");
}

#[test]
fn compares_are_deterministic() {
    let run_once = || {
        let axes = vec![axis(3000.0), axis(3000.0)];
        let mut e = with_group(engine_with(axes), &[0, 1]);
        let points: Vec<[f64; 2]> = (1..20).map(|i| [f64::from(i) * 7.0, 0.5]).collect();
        ok(
            &mut e,
            Command::from(CompareStart {
                axis_y: Some(1),
                points,
                error_zone: 1.0,
                disturbance: 0.0,
                pulse_width: 0.002,
                ..list(&[])
            }),
        );
        ok(&mut e, Command::from(group_line(1, &[150.0, 0.0])));
        (0..20_000)
            .map(|_| {
                e.step();
                let s = e.snapshot();
                (
                    s.io.do_[0],
                    s.compares[0].clone(),
                    s.axes[0].act_pos.to_bits(),
                )
            })
            .collect::<Vec<_>>()
    };
    let a = run_once();
    assert_eq!(a.last().unwrap().1.count, 19);
    assert_eq!(a, run_once());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Each position fires once, in order, at the tick whose travel passes it: the first tick
    /// at whose end the commanded position is at or past it.
    #[test]
    fn outputs_fire_once_per_position_in_order_at_the_tick_of_the_crossing(
        speed in 50.0f64..50_000.0,
        gaps in prop::collection::vec(0.0f64..40.0, 1..30),
        down in any::<bool>(),
    ) {
        let sign = if down { -1.0 } else { 1.0 };
        let mut p = 1.0;
        let positions: Vec<f64> = gaps.iter().map(|g| { p += g; sign * p }).collect();
        let end = sign * (p + 5.0);
        let mut e = machine(speed);
        let mut c = list(&positions);
        c.mode = CompareOutputMode::Toggle;
        ok(&mut e, Command::from(c));
        ok(&mut e, move_abs(end));
        let mut before = 0.0f64;
        let mut fired = 0u32;
        for _ in 0..200_000 {
            e.step();
            let s = e.snapshot();
            let now = s.axes[0].cmd_pos;
            let crossed = positions
                .iter()
                .take_while(|q| if down { now <= **q } else { now >= **q })
                .count() as u32;
            // Fired exactly the positions passed so far (a position equal to the one before
            // it is passed in the same tick and fires with it).
            prop_assert_eq!(s.compares[0].count, crossed, "at {} (from {})", now, before);
            prop_assert!(s.compares[0].count >= fired);
            fired = s.compares[0].count;
            before = now;
            if now == end {
                break;
            }
        }
        prop_assert_eq!(fired, positions.len() as u32);
    }
}

#[test]
fn an_atomic_batch_refused_late_leaves_no_channel_and_no_output() {
    let mut e = machine(1000.0);
    ok(
        &mut e,
        Command::from(axes::command::WriteDigitalOutput {
            channel: 0,
            value: true,
        }),
    );
    let before = e.snapshot();
    let err = e
        .apply_batch(vec![
            Command::from(list(&[1.0])),
            Command::from(CompareStart {
                output: 99,
                ..list(&[1.0])
            }),
        ])
        .unwrap_err();
    assert!(matches!(err, EngineError::Item { index: 1, .. }), "{err}");
    assert_eq!(
        e.snapshot(),
        before,
        "the pulse channel's idle level is rolled back too"
    );
}
