//! `estimate_group_time` (the NMC execution-time dry run) against running the same program for
//! real, in the same run: both step the machine through the whole path; the dry run adds the
//! whole-machine checkpoint and its rollback. The program is 8 blended 100 mm lines of a 4-axis
//! group at 50 mm/s (about 16 000 ticks at 1 ms); the figure per iteration is one whole path.
//!
//! `cargo bench -p axes --bench group_estimate`

// A benchmark that cannot build its machine should stop loudly.
#![allow(clippy::expect_used, clippy::panic)]

use std::hint::black_box;

use axes::command::{Command, EstimateGroupTime, Reply};
use axes::status::GroupState;
use axes::Engine;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion};

mod common;

const AXES: usize = 4;

fn program() -> Vec<Command> {
    (1..=8)
        .map(|k| common::hypercube_corner_move(AXES, k))
        .collect()
}

fn estimate(e: &mut Engine) -> u64 {
    match e.apply(Command::from(EstimateGroupTime {
        group: 1,
        commands: program(),
    })) {
        Ok(Reply::Value { value }) => value as u64,
        other => panic!("{other:?}"),
    }
}

fn run(e: &mut Engine) -> u64 {
    for c in program() {
        e.apply(c).expect("move");
    }
    let mut ticks = 0;
    while e.groups().get(1).map(|g| g.state()) != Some(GroupState::Standby) {
        e.step();
        ticks += 1;
    }
    ticks
}

fn estimate_cost(c: &mut Criterion) {
    let ticks = estimate(&mut common::grouped_engine(AXES));
    assert_eq!(ticks, run(&mut common::grouped_engine(AXES)));
    println!("path: {ticks} ticks");
    let mut bench = c.benchmark_group("group_path_8_lines");
    bench.sample_size(10);
    bench.bench_function("estimate_group_time", |b| {
        b.iter_batched_ref(
            || common::grouped_engine(AXES),
            |e| black_box(estimate(e)),
            BatchSize::LargeInput,
        )
    });
    bench.bench_function("run_for_real", |b| {
        b.iter_batched_ref(
            || common::grouped_engine(AXES),
            |e| black_box(run(e)),
            BatchSize::LargeInput,
        )
    });
    bench.finish();
}

criterion_group!(benches, estimate_cost);
criterion_main!(benches);
