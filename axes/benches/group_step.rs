//! `Engine::step()` cost per axis of a moving 4-axis group with blending (issue 11: aim ≤ 100 ns
//! per axis, as single axes are), beside 4 free axes each running its own move in the same run.
//! The group runs an endless polygon of 100 mm lines in 4-D, blended (`blending_low`, 5 mm
//! corner distance), topped up every 1024 ticks when fewer than 32 entries are queued (a refill
//! runs the look-ahead; its cost is in the figure, spread over the ticks it serves, as on a
//! machine streaming a program).
//!
//! `cargo bench -p axes --bench group_step`

// A benchmark that cannot build its machine should stop loudly.
#![allow(clippy::expect_used, clippy::panic)]

use std::hint::black_box;

use axes::Engine;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

mod common;

const AXES: usize = 4;

struct Group {
    engine: Engine,
    next: u64,
}

impl Group {
    fn new() -> Group {
        let engine = common::grouped_engine(AXES);
        let mut g = Group { engine, next: 1 };
        g.refill();
        // Past the first acceleration.
        for _ in 0..500 {
            g.engine.step();
        }
        let moving = g
            .engine
            .group_status(1)
            .is_some_and(|s| s.path_velocity > 0.0);
        assert!(moving, "the group should be moving");
        g
    }

    fn refill(&mut self) {
        let queued = self.engine.groups().get(1).map_or(0, |g| g.queued());
        if queued >= 32 {
            return;
        }
        for _ in 0..64 {
            self.engine
                .apply(common::hypercube_corner_move(AXES, self.next))
                .expect("move_linear_absolute");
            self.next += 1;
        }
    }
}

fn step_cost(c: &mut Criterion) {
    let mut bench = c.benchmark_group("step_per_axis_group");
    bench.throughput(Throughput::Elements(AXES as u64));
    let mut free = common::moving_engine(AXES);
    for _ in 0..200 {
        free.step();
    }
    bench.bench_with_input(BenchmarkId::new("free_axes_moving", AXES), &AXES, |b, _| {
        b.iter(|| {
            free.step();
            black_box(&mut free);
        })
    });
    let mut group = Group::new();
    bench.bench_with_input(
        BenchmarkId::new("group_blending_moving", AXES),
        &AXES,
        |b, _| {
            b.iter(|| {
                group.engine.step();
                if group.engine.tick().is_multiple_of(1024) {
                    group.refill();
                }
                black_box(&mut group.engine);
            });
        },
    );
    bench.finish();
}

criterion_group!(benches, step_cost);
criterion_main!(benches);
