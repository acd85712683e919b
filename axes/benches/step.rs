//! `Engine::step()` cost per axis (issue: ≤ 100 ns per moving axis with pulse output, encoder,
//! switches and plant). Baseline in the same run: the same machine with the axes enabled and
//! standing still.
//!
//! `cargo bench -p axes --bench step`

// A benchmark that cannot build its machine should stop loudly.
#![allow(clippy::expect_used)]

use std::hint::black_box;

use axes::command::Command;
use axes::config::{AxisConfig, HomeSwitchConfig, PlantModel, SwitchConfig};
use axes::{Engine, EngineConfig, ParamId};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

/// A stepper in mm with the whole per-tick pipeline: pulse output, encoder with index
/// (no noise: optional, +~5 ns), lag plant, both limits and a home cam (far away, so the axes
/// keep moving for the whole measurement), following-error supervision.
fn busy_axis() -> AxisConfig {
    let mut a = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 10.0),
        (ParamId::Units, 1000.0),
        (ParamId::RepMode, 0.0),
        (ParamId::Speed, 100.0),
        (ParamId::Accel, 1000.0),
        (ParamId::Decel, 1000.0),
        (ParamId::JerkMode, 1.0),
        (ParamId::Jerk, 20_000.0),
        (ParamId::FeLimit, 1e6),
        (ParamId::InPositionWindow, 0.01),
    ] {
        a.params.insert(p, v);
    }
    a.plant.model = PlantModel::Lag;
    a.plant.time_constant = 0.002;
    a.switches.limit_pos = Some(SwitchConfig {
        position: 1e9,
        filter: 2,
        active_low: false,
    });
    a.switches.limit_neg = Some(SwitchConfig {
        position: -1e9,
        filter: 2,
        active_low: false,
    });
    a.switches.home = Some(HomeSwitchConfig {
        low: 5e8,
        high: 5e8 + 10.0,
        filter: 0,
        active_low: false,
    });
    a
}

fn machine(n: usize, moving: bool) -> Engine {
    let config = EngineConfig {
        axes: vec![busy_axis(); n],
        ..EngineConfig::default()
    };
    let mut e = Engine::new(&config).expect("bench machine");
    for axis in 0..n as u16 {
        e.apply(Command::Enable { axis }).expect("enable");
        if moving {
            // A long S-curve move: the axes stay in motion for the whole measurement.
            e.apply(Command::MoveRelative {
                axis,
                distance: 1e8,
                velocity: None,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode: Default::default(),
            })
            .expect("move");
        }
    }
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
                    black_box(engine.axis_status(0));
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, step_cost);
criterion_main!(benches);
