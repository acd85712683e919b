//! `Engine::step()` of an axis whose command goes through an input shaper (ZVD, 3 interpolated
//! ring-buffer samples) or the VSF notch (one biquad step), beside a plain axis measured in
//! the same run (issue 14: the filter's work per tick is bounded and closed-form).
//!
//! `cargo bench -p axes --bench filter_step`

// A benchmark that cannot build its machine should stop loudly.
#![allow(clippy::expect_used, clippy::panic)]

use std::hint::black_box;

use axes::command::{FilterInputShaping, FilterVsf};
use axes::filter::{FilterSlot, ShaperType};
use axes::{Command, Engine};
use criterion::{criterion_group, criterion_main, Criterion};

mod common;

fn moving(filter: Option<Command>) -> Engine {
    let mut e = common::engine(1);
    if let Some(f) = filter {
        e.apply(f).expect("filter");
    }
    for c in common::motion_commands(1) {
        e.apply(c).expect("motion");
    }
    for _ in 0..200 {
        e.step();
    }
    e
}

fn step_cost(c: &mut Criterion) {
    let mut bench = c.benchmark_group("step_filter");
    let cases = [
        ("plain_axis_moving", None),
        (
            "zvd_shaped_axis_moving",
            Some(Command::from(FilterInputShaping {
                axis: 0,
                shaper: ShaperType::Zvd,
                frequency: 5.5,
                damping: 0.03,
                slot: FilterSlot::Axis,
            })),
        ),
        (
            "vsf_axis_moving",
            Some(Command::from(FilterVsf {
                axis: 0,
                frequency: 40.0,
                damping: 1.0,
            })),
        ),
    ];
    for (name, filter) in cases {
        let filtered = filter.is_some();
        let mut e = moving(filter);
        bench.bench_function(name, |b| {
            b.iter(|| {
                e.step();
                black_box(&mut e);
            })
        });
        let s = e.axis_status(0).expect("axis 0");
        assert_eq!(s.command_filter.is_some(), filtered, "{name}: filter state");
    }
    bench.finish();
}

criterion_group!(benches, step_cost);
criterion_main!(benches);
