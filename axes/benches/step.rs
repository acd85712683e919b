//! `Engine::step()` cost per axis (issue: ≤ 100 ns per moving axis with pulse output, encoder,
//! switches and plant). Baseline in the same run: the same machine with the axes enabled and
//! standing still.
//!
//! `cargo bench -p axes --bench step`

// A benchmark that cannot build its machine should stop loudly.
#![allow(clippy::expect_used)]

use std::hint::black_box;

use axes::command::{Command, Enable};
use axes::Engine;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

mod common;

fn machine(n: usize, moving: bool) -> Engine {
    let mut e = if moving {
        common::moving_engine(n)
    } else {
        let mut e = common::engine(n);
        for axis in 0..n as u16 {
            e.apply(Command::from(Enable { axis })).expect("enable");
        }
        e
    };
    // Past the acceleration phase.
    for _ in 0..200 {
        e.step();
    }
    e
}

fn step_cost(c: &mut Criterion) {
    let mut group = c.benchmark_group("step_per_axis");
    for n in [1usize, 8, 64, 512] {
        group.throughput(Throughput::Elements(n as u64));
        for (label, moving) in [("idle", false), ("moving", true)] {
            let mut engine = machine(n, moving);
            group.bench_with_input(BenchmarkId::new(label, n), &n, |b, _| {
                b.iter(|| {
                    engine.step();
                    black_box(&mut engine);
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, step_cost);
criterion_main!(benches);
