//! The worst servo tick while the engine accepts the largest spline it takes (issue 11: the
//! planning work per tick bounded): `move_spline` with 1000 points of a tight zigzag (1 mm
//! pitch, 1 mm amplitude: the curve table's worst case) on a 2-axis group, applied between
//! two steps as the servo thread does. For each run a fresh machine accepts the spline
//! (`apply` + `step`) and then runs 3000 ticks along it; the bench prints the worst single
//! tick (and which tick it was) beside the mean tick of the same runs, for the default
//! `[groups] spline_spans_per_tick` (8: the construction spread over 125 ticks) and, as the
//! baseline in the same run, for 1000 (the whole spline constructed in the accepting tick,
//! as before the construction was spread); then criterion's figure for the accepting tick
//! of each.
//!
//! `cargo bench -p axes --bench group_spline_accept`

// A benchmark that cannot build its machine should stop loudly.
#![allow(clippy::expect_used, clippy::panic)]

use std::time::{Duration, Instant};

use axes::command::{Command, GroupBufferMode, MoveSpline, TransitionMode};
use axes::config::GroupsConfig;
use axes::Engine;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion};

mod common;

/// The most points one `move_spline` carries (HMC: 1000 nodes after the start).
const POINTS: usize = 1000;
/// Ticks run along the spline after the accepting one, per run.
const TICKS_AFTER: usize = 3000;
const RUNS: usize = 5;

/// The construction spread over ticks (the default), and all of it in the accepting tick.
const SPREAD: u32 = 8;
const AT_ONCE: u32 = 1000;

/// An enabled 2-axis group at rest, constructing `spans` spline spans per tick.
fn machine(spans: u32) -> Engine {
    let mut config = common::machine(2);
    config.groups = GroupsConfig {
        spline_spans_per_tick: spans,
        ..GroupsConfig::default()
    };
    let mut engine = common::grouped_engine_of(config);
    engine.step();
    engine
}

/// 1000 points of a zigzag from the origin: x by 1 mm, y alternating 0 and 1 mm.
fn zigzag() -> Command {
    let points = (1..=POINTS)
        .map(|i| vec![i as f64, if i % 2 == 0 { 0.0 } else { 1.0 }])
        .collect();
    Command::from(MoveSpline {
        group: 1,
        points,
        independent: Default::default(),
        relative: false,
        velocity: Some(50.0),
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: GroupBufferMode::Aborting,
        transition: TransitionMode::None,
        user_segment: None,
        coordinate_system: None,
    })
}

/// The accepting tick: the command applied, then the step.
fn accept(engine: &mut Engine, command: Command) {
    engine.apply(command).expect("move_spline");
    engine.step();
}

/// The worst tick over the runs, which tick it was, the worst accepting tick, the mean tick.
fn ticks(spans: u32) -> (Duration, usize, Duration, Duration) {
    let mut worst = (Duration::ZERO, 0usize);
    let mut total = Duration::ZERO;
    let mut ticks = 0u32;
    let mut accepting = Duration::ZERO;
    for _ in 0..RUNS {
        let mut engine = machine(spans);
        let command = zigzag();
        let t0 = Instant::now();
        accept(&mut engine, command);
        let d = t0.elapsed();
        accepting = accepting.max(d);
        let mut record = |d: Duration, k: usize| {
            total += d;
            ticks += 1;
            if d > worst.0 {
                worst = (d, k);
            }
        };
        record(d, 0);
        for k in 1..=TICKS_AFTER {
            let t0 = Instant::now();
            engine.step();
            record(t0.elapsed(), k);
        }
        let moving = engine
            .group_status(1)
            .is_some_and(|s| s.path_velocity > 0.0);
        assert!(moving, "the group should still be moving along the spline");
    }
    (worst.0, worst.1, accepting, total / ticks.max(1))
}

fn worst_tick(c: &mut Criterion) {
    for (spans, what) in [
        (SPREAD, "spread over ticks"),
        (AT_ONCE, "baseline, all in the accepting tick"),
    ] {
        let (worst, at, accepting, mean) = ticks(spans);
        println!(
            "move_spline {POINTS}-point zigzag, spline_spans_per_tick {spans} ({what}), {RUNS} \
             runs of 1 + {TICKS_AFTER} ticks: worst tick {} (tick {at} after the accepting \
             one), accepting tick {} at worst, mean tick {}",
            common::fmt_duration(worst),
            common::fmt_duration(accepting),
            common::fmt_duration(mean),
        );
    }

    let mut bench = c.benchmark_group("group_spline_accept");
    bench.sample_size(10);
    for (spans, name) in [
        (SPREAD, "accepting_tick"),
        (AT_ONCE, "accepting_tick_at_once"),
    ] {
        bench.bench_function(name, |b| {
            b.iter_batched(
                || (machine(spans), zigzag()),
                |(mut engine, command)| {
                    accept(&mut engine, command);
                    engine
                },
                BatchSize::PerIteration,
            )
        });
    }
    bench.finish();
}

criterion_group!(benches, worst_tick);
criterion_main!(benches);
