//! `Engine::step()` with gear and cam slaves (issue 12: aim ≤ 1.5× a plain moving axis).
//! Three machines of the same 64 busy steppers, measured in the same run: all 64 moving on
//! their own profiles (the baseline); 32 moving masters each with a geared slave (ratio 3/7,
//! commanded master, clutch over 5 mm); 32 masters each with a periodic cubic cam slave (a
//! 33-point table). A slave costs 2·t(coupled) / t(plain) − 1 plain axes; the bench prints
//! that figure after criterion's own.
//!
//! `cargo bench -p axes --bench coupling_step`

#![allow(clippy::expect_used)]

use std::hint::black_box;
use std::time::Instant;

use axes::command::MasterSource;
use axes::command::{CamIn, CamInterpolation, CamPoint, CamTableDefine, FollowSegment, GearIn};
use axes::{Command, Engine};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

mod common;

const AXES: usize = 64;

#[derive(Clone, Copy, Debug)]
enum Kind {
    Plain,
    Gear,
    Cam,
}

fn machine(kind: Kind) -> Engine {
    let mut e = common::engine(AXES);
    let half = (AXES / 2) as u16;
    let commands = common::motion_commands(AXES);
    // Enable everything; only the masters (and, for the plain machine, every axis) move.
    for (i, c) in commands.into_iter().enumerate() {
        let axis = (i / 2) as u16;
        let is_move = i % 2 == 1;
        if is_move && axis >= half && !matches!(kind, Kind::Plain) {
            continue;
        }
        e.apply(c).expect("bench command");
    }
    if matches!(kind, Kind::Cam) {
        let points = (0..=32)
            .map(|k| {
                let x = k as f64 * 10.0;
                CamPoint {
                    master: x,
                    slave: 20.0 * (x / 320.0 * std::f64::consts::TAU).sin() + x / 4.0,
                    segment: FollowSegment::Normal,
                }
            })
            .collect();
        e.apply(Command::from(CamTableDefine {
            table: 0,
            points,
            interpolation: CamInterpolation::Cubic,
        }))
        .expect("table");
    }
    for m in 0..half {
        let slave = m + half;
        let c = match kind {
            Kind::Plain => continue,
            Kind::Gear => Command::from(GearIn {
                master: m,
                slave,
                numerator: 3.0,
                denominator: 7.0,
                master_source: MasterSource::Commanded,
                clutch_distance: Some(5.0),
                acceleration: None,
                direction: None,
            }),
            Kind::Cam => Command::from(CamIn {
                master: m,
                slave,
                table: 0,
                master_source: MasterSource::Commanded,
                periodic: true,
                loop_count: 0,
                master_absolute: false,
                slave_absolute: false,
                master_offset: 0.0,
                slave_offset: 0.0,
                master_scaling: 1.0,
                slave_scaling: 1.0,
                start_position: None,
                start_direction: None,
                start_input: None,
            }),
        };
        e.apply(c).expect("coupling");
    }
    // Past the acceleration and the clutch.
    for _ in 0..500 {
        e.step();
    }
    e
}

fn step_cost(c: &mut Criterion) {
    let mut group = c.benchmark_group("coupled_step_per_axis");
    group.throughput(Throughput::Elements(AXES as u64));
    for kind in [Kind::Plain, Kind::Gear, Kind::Cam] {
        let mut engine = machine(kind);
        group.bench_with_input(
            BenchmarkId::new(format!("{kind:?}").to_lowercase(), AXES),
            &kind,
            |b, _| {
                b.iter(|| {
                    engine.step();
                    black_box(&mut engine);
                })
            },
        );
    }
    group.finish();
    // The figure the issue asks for, from one more interleaved measurement: each machine is
    // timed in turns, so drift of the host hits all three alike.
    let mut engines = [Kind::Plain, Kind::Gear, Kind::Cam].map(machine);
    let mut ns = [0.0f64; 3];
    const ROUNDS: usize = 20;
    const STEPS: usize = 2000;
    for _ in 0..ROUNDS {
        for (e, t) in engines.iter_mut().zip(ns.iter_mut()) {
            let start = Instant::now();
            for _ in 0..STEPS {
                e.step();
            }
            *t += start.elapsed().as_nanos() as f64;
            black_box(&mut *e);
        }
    }
    let per_axis = ns.map(|t| t / (ROUNDS * STEPS * AXES) as f64);
    let [plain, gear, cam] = per_axis;
    println!(
        "coupling_step: plain moving axis {plain:.1} ns; gear slave {:.1} ns = {:.2}× plain; \
         cam slave {:.1} ns = {:.2}× plain (aim ≤ 1.5×)",
        2.0 * gear - plain,
        (2.0 * gear - plain) / plain,
        2.0 * cam - plain,
        (2.0 * cam - plain) / plain,
    );
}

criterion_group!(benches, step_cost);
criterion_main!(benches);
