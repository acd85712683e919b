//! Planning and sampling cost of `axes::profile` against rsruckig on the same problems.
//!
//! `cargo bench -p axes --bench profile`. The problem set is fixed (seeded): 1000 random 1-DoF
//! position problems inside Ruckig's input conditions (|v0| ≤ vmax, |a0| ≤ amax,
//! |a0| ≤ sqrt(2 j (vmax − |v0|)), equal acceleration and deceleration, rest at the target),
//! S-curve and trapezoid (infinite jerk). Each criterion iteration plans the next problem of
//! the set, so "time" is the mean per plan. A side-by-side summary is printed at the end.

use std::hint::black_box;
use std::time::Instant;

use axes::profile::{Goal, Limits, MotionState, Options, PlanError, Profile};
use criterion::Criterion;
use rsruckig::prelude::{InputParameter, Ruckig, ThrowErrorHandler, Trajectory};

const PROBLEMS: usize = 1000;

/// xorshift64*: a reproducible stream without another dependency.
struct Rng(u64);

impl Rng {
    fn next_f64(&mut self) -> f64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        (x.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.uniform(lo.ln(), hi.ln()).exp()
    }
}

#[derive(Clone, Copy)]
struct Problem {
    start: MotionState,
    target: f64,
    limits: Limits,
}

fn problems(jerk_limited: bool) -> Vec<Problem> {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    (0..PROBLEMS)
        .map(|i| {
            let vmax = rng.log_uniform(0.1, 10.0);
            let amax = rng.log_uniform(0.1, 10.0);
            let jerk = if jerk_limited {
                rng.log_uniform(0.1, 100.0)
            } else {
                f64::INFINITY
            };
            // A quarter of the problems start at rest, as most engine moves do.
            let at_rest = i % 4 == 0;
            let v0 = if at_rest {
                0.0
            } else {
                rng.uniform(-1.0, 1.0) * vmax
            };
            let a_cap = amax.min((2.0 * jerk * (vmax - v0.abs())).sqrt());
            let a0 = if at_rest || !jerk_limited {
                0.0
            } else {
                rng.uniform(-1.0, 1.0) * a_cap
            };
            let dist = rng.log_uniform(1e-3, 100.0);
            let target = if rng.next_f64() < 0.5 { -dist } else { dist };
            Problem {
                start: MotionState {
                    p: 0.0,
                    v: v0,
                    a: a0,
                },
                target,
                limits: Limits {
                    velocity: vmax,
                    acceleration: amax,
                    deceleration: amax,
                    jerk,
                },
            }
        })
        .collect()
}

fn plan_result(p: &Problem) -> Result<Profile, PlanError> {
    Profile::plan(
        p.start,
        Goal::Position {
            target: p.target,
            end_velocity: 0.0,
        },
        &p.limits,
        &Options::default(),
    )
}

fn plan(p: &Problem) -> Option<Profile> {
    plan_result(p).ok()
}

fn ruckig_input(p: &Problem) -> InputParameter<1> {
    let mut input = InputParameter::new(None);
    input.current_position[0] = p.start.p;
    input.current_velocity[0] = p.start.v;
    input.current_acceleration[0] = p.start.a;
    input.target_position[0] = p.target;
    input.max_velocity[0] = p.limits.velocity;
    input.max_acceleration[0] = p.limits.acceleration;
    input.max_jerk[0] = p.limits.jerk;
    input
}

fn bench_plan(c: &mut Criterion, name: &str, jerk_limited: bool) {
    let set = problems(jerk_limited);
    let inputs: Vec<InputParameter<1>> = set.iter().map(ruckig_input).collect();
    // Both planners accept every problem, so neither bails out early.
    let mut otg = Ruckig::<1, ThrowErrorHandler>::new(None, 0.001);
    let mut traj = Trajectory::new(None);
    assert!(set.iter().all(|p| plan(p).is_some()));
    assert!(inputs.iter().all(|i| otg.calculate(i, &mut traj).is_ok()));
    let mut group = c.benchmark_group(name);
    group.bench_function("mcemu", |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) % PROBLEMS;
            black_box(plan_result(black_box(&set[i])))
        })
    });
    group.bench_function("rsruckig", |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) % PROBLEMS;
            let result = otg.calculate(black_box(&inputs[i]), &mut traj);
            black_box((result.is_ok(), traj.get_duration()))
        })
    });
    group.finish();
}

/// (profile, time) pairs across whole profiles, past their ends too.
fn sample_points() -> (Vec<Profile>, Vec<(usize, f64)>) {
    let profiles: Vec<Profile> = problems(true).iter().filter_map(plan).collect();
    let points = (0..PROBLEMS * 8)
        .map(|k| {
            let i = k % profiles.len();
            (i, profiles[i].duration() * ((k * 37) % 101) as f64 / 100.0)
        })
        .collect();
    (profiles, points)
}

fn bench_sample(c: &mut Criterion) {
    let (profiles, points) = sample_points();
    let mut group = c.benchmark_group("sample_scurve");
    group.bench_function("mcemu", |b| {
        let mut k = 0;
        b.iter(|| {
            k += 1;
            if k == points.len() {
                k = 0;
            }
            let (i, t) = points[k];
            black_box(profiles[i].sample(black_box(t)))
        })
    });
    // One profile, as the servo tick sees it: hot in cache, time advancing. The one with the
    // most segments, the longest search.
    let p = profiles
        .iter()
        .max_by_key(|p| p.segment_count())
        .copied()
        .unwrap_or(Profile::hold(0.0));
    let ticks: Vec<f64> = (0..1000)
        .map(|k| p.duration() * f64::from(k) / 999.0)
        .collect();
    group.bench_function("mcemu_one_profile", |b| {
        let mut k = 0;
        b.iter(|| {
            k += 1;
            if k == ticks.len() {
                k = 0;
            }
            black_box(p.sample(black_box(ticks[k])))
        })
    });
    // What the loop around `sample` costs by itself.
    group.bench_function("harness_only", |b| {
        let mut k = 0;
        b.iter(|| {
            k += 1;
            if k == ticks.len() {
                k = 0;
            }
            black_box(black_box(ticks[k]))
        })
    });
    group.finish();
}

/// Mean nanoseconds per call of `f` over the set, best of a few rounds.
fn mean_ns(rounds: usize, mut f: impl FnMut(usize)) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..rounds {
        let start = Instant::now();
        for _ in 0..20 {
            for i in 0..PROBLEMS {
                f(i);
            }
        }
        let ns = start.elapsed().as_nanos() as f64 / (20 * PROBLEMS) as f64;
        best = best.min(ns);
    }
    best
}

fn summary() {
    println!();
    println!("side by side, same {PROBLEMS} problems (best of 5 rounds of 20 passes):");
    println!(
        "{:<22} {:>12} {:>12} {:>8}",
        "", "mcemu", "rsruckig", "ratio"
    );
    for (name, jerk_limited) in [("plan S-curve", true), ("plan trapezoid", false)] {
        let set = problems(jerk_limited);
        let inputs: Vec<InputParameter<1>> = set.iter().map(ruckig_input).collect();
        let ours = mean_ns(5, |i| {
            let _ = black_box(plan_result(black_box(&set[i])));
        });
        let mut otg = Ruckig::<1, ThrowErrorHandler>::new(None, 0.001);
        let mut traj = Trajectory::new(None);
        let theirs = mean_ns(5, |i| {
            let _ = black_box(otg.calculate(black_box(&inputs[i]), &mut traj));
        });
        println!(
            "{name:<22} {:>9.1} ns {:>9.1} ns {:>7.2}x",
            ours,
            theirs,
            theirs / ours
        );
    }
    let (profiles, points) = sample_points();
    let sample = mean_ns(5, |k| {
        let (i, t) = points[k];
        black_box(profiles[i].sample(black_box(t)));
    });
    println!("{:<22} {:>9.1} ns", "sample S-curve", sample);
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_plan(&mut c, "plan_scurve", true);
    bench_plan(&mut c, "plan_trapezoid", false);
    bench_sample(&mut c);
    c.final_summary();
    let quick = std::env::args().any(|a| a == "--test" || a == "--list");
    if !quick {
        summary();
    }
}
