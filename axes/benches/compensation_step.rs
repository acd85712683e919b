//! `Engine::step()` of an axis with a lead-screw compensation table (128 points, both
//! directions) and a backlash setting, beside a plain axis measured in the same run (issue 12
//! item 8: the table lookup carries its segment, so the cost should be a few ns).
//!
//! `cargo bench -p axes --bench compensation_step`

// A benchmark that cannot build its machine should stop loudly.
#![allow(clippy::expect_used, clippy::panic)]

use std::hint::black_box;

use axes::command::{BacklashDirection, CompensationBacklash, CompensationLeadScrew};
use axes::{Command, Engine};
use criterion::{criterion_group, criterion_main, Criterion};

mod common;

const POINTS: usize = 128;

fn moving(compensated: bool) -> Engine {
    let mut e = common::moving_engine(1);
    if compensated {
        // 128 points over the whole 1e8 mm move, so that every tick interpolates (a benchmark
        // run covers hours of virtual time; a short table would be left behind).
        let spacing = 1e8 / (POINTS - 1) as f64;
        let positions: Vec<f64> = (0..POINTS).map(|i| i as f64 * spacing).collect();
        let positive: Vec<f64> = (0..POINTS)
            .map(|i| ((i as f64) * 0.3).sin() * 0.01)
            .collect();
        let negative: Vec<f64> = positive.iter().map(|v| v * 0.5).collect();
        e.apply(Command::from(CompensationLeadScrew {
            axis: 0,
            positions,
            positive,
            negative: Some(negative),
            enable: true,
        }))
        .expect("lead screw");
        e.apply(Command::from(CompensationBacklash {
            axis: 0,
            amount: 0.01,
            step: 0.002,
            direction: BacklashDirection::Negative,
            enable: true,
        }))
        .expect("backlash");
    }
    for _ in 0..200 {
        e.step();
    }
    e
}

fn step_cost(c: &mut Criterion) {
    let mut bench = c.benchmark_group("step_compensation");
    let mut plain = moving(false);
    bench.bench_function("plain_axis_moving", |b| {
        b.iter(|| {
            plain.step();
            black_box(&mut plain);
        })
    });
    let mut compensated = moving(true);
    bench.bench_function("lead_screw_and_backlash_axis_moving", |b| {
        b.iter(|| {
            compensated.step();
            black_box(&mut compensated);
        })
    });
    let c = compensated.axis_status(0).expect("axis 0").compensation;
    assert!(c != 0.0, "the compensation should be active");
    bench.finish();
}

criterion_group!(benches, step_cost);
criterion_main!(benches);
