//! Planning cost of the path planner (issue 11, Performance).
//!
//! `cargo bench -p path --bench planner`. Two parts, each with a summary printed beside its
//! reference in the same run:
//! - (a) planning cost per motion with look-ahead 64 on a fixed (seeded) random 3-axis path
//!   of lines, beside rsruckig's 3-DoF time-synchronized plan between the same end points.
//!   A motion's planning is its push (path limits, junction, look-ahead pass) plus the profile
//!   planned when it starts, inside a step: the latter is measured as the mean extra time of
//!   steps that start a motion over steps that do not.
//! - (b) the dense G-code case: 100 000 lines of 0.05 mm with small random direction changes
//!   at 1 kHz, fed as the queue has room: the longest step() and the most motions started in
//!   one step, beside the servo period.

#![allow(clippy::panic, clippy::unwrap_used, clippy::expect_used)]

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::Criterion;
use path::geometry::{Line, Segment};
use path::planner::{AxisLimits, Join, Motion, PathLimits, PathPlanner, PlannerConfig, Transition};
use path::{Point, MAX_AXES};
use rsruckig::prelude::{InputParameter, Ruckig, ThrowErrorHandler, Trajectory};

const MOTIONS: usize = 1000;

/// xorshift64*: a reproducible stream without another dependency.
struct Rng(u64);

impl Rng {
    fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

fn axis() -> AxisLimits {
    AxisLimits {
        velocity: 200.0,
        acceleration: 2000.0,
        jerk: f64::INFINITY,
    }
}

fn config(period: f64) -> PlannerConfig {
    PlannerConfig {
        capacity: PlannerConfig::MAX_CAPACITY,
        ..PlannerConfig::uniform(3, axis(), period)
    }
}

fn path_limits() -> PathLimits {
    PathLimits {
        velocity: 150.0,
        acceleration: 3000.0,
        deceleration: 3000.0,
        jerk: f64::INFINITY,
    }
}

/// Random 3-axis lines of 1–20 mm, blended (BlendingLow, corner rule).
fn random_lines() -> Vec<(Point, Point)> {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut at = [0.0; MAX_AXES];
    (0..MOTIONS)
        .map(|_| {
            let mut to = at;
            for c in to.iter_mut().take(3) {
                *c += rng.uniform(-10.0, 10.0);
            }
            let seg = (at, to);
            at = to;
            seg
        })
        .collect()
}

fn motion(seg: (Point, Point), tag: u64) -> Motion {
    let line = Line::new(seg.0, seg.1, 3).unwrap_or_else(|e| panic!("line: {e}"));
    Motion {
        segment: Segment::Line(line),
        limits: path_limits(),
        join: Join::BlendingLow,
        transition: Transition::None,
        tag,
    }
}

fn ruckig_input(seg: &(Point, Point)) -> InputParameter<3> {
    let mut input = InputParameter::new(None);
    for k in 0..3 {
        input.current_position[k] = seg.0[k];
        input.target_position[k] = seg.1[k];
        input.max_velocity[k] = axis().velocity;
        input.max_acceleration[k] = axis().acceleration;
        input.max_jerk[k] = 1e6;
    }
    input
}

/// A planner with the first `queued` lines of `lines` pushed.
fn planner_with(lines: &[(Point, Point)], queued: usize) -> PathPlanner {
    let mut pl = PathPlanner::new(config(1e-3), lines[0].0).unwrap_or_else(|e| panic!("{e}"));
    for (i, seg) in lines.iter().take(queued).enumerate() {
        pl.push_motion(motion(*seg, i as u64))
            .unwrap_or_else(|e| panic!("push: {e}"));
    }
    pl
}

fn bench_plan_per_motion(c: &mut Criterion) {
    let lines = random_lines();
    let inputs: Vec<InputParameter<3>> = lines.iter().map(ruckig_input).collect();
    let mut otg = Ruckig::<3, ThrowErrorHandler>::new(None, 0.001);
    let mut traj = Trajectory::new(None);
    let mut group = c.benchmark_group("plan_per_motion");
    group.bench_function("mcemu_push_lookahead64", |b| {
        // Steady state: 128 queued, one pushed per iteration; the steps that make room are
        // not timed.
        b.iter_custom(|iters| {
            let mut pl = planner_with(&lines, 128);
            let mut events = Vec::new();
            let mut next = 128;
            let mut timed = Duration::ZERO;
            for _ in 0..iters {
                while pl.queued() >= 128 {
                    pl.step(&mut events);
                    events.clear();
                }
                if next == MOTIONS {
                    pl = planner_with(&lines, 128);
                    next = 128;
                }
                let m = motion(lines[next], next as u64);
                let t0 = Instant::now();
                let _ = black_box(pl.push_motion(m));
                timed += t0.elapsed();
                next += 1;
            }
            timed
        })
    });
    group.bench_function("rsruckig_3dof_sync", |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) % MOTIONS;
            let result = otg.calculate(black_box(&inputs[i]), &mut traj);
            black_box((result.is_ok(), traj.get_duration()))
        })
    });
    group.finish();
    summary_plan_per_motion(&lines, &inputs);
}

/// The side-by-side figures, timed over the whole path (pushes as the queue has room).
fn summary_plan_per_motion(lines: &[(Point, Point)], inputs: &[InputParameter<3>]) {
    let mut pl = planner_with(lines, 0);
    let mut events = Vec::new();
    let (mut push_time, mut pushes) = (Duration::ZERO, 0u32);
    let (mut start_steps, mut start_time) = (0u32, Duration::ZERO);
    let (mut plain_steps, mut plain_time) = (0u32, Duration::ZERO);
    let mut next = 0;
    while next < lines.len() || !pl.is_idle() {
        while next < lines.len() && pl.queued() < 128 {
            let m = motion(lines[next], next as u64);
            let t0 = Instant::now();
            let r = pl.push_motion(m);
            push_time += t0.elapsed();
            pushes += 1;
            black_box(r).unwrap_or_else(|e| panic!("push: {e}"));
            next += 1;
        }
        let t0 = Instant::now();
        black_box(pl.step(&mut events));
        let dt = t0.elapsed();
        events.clear();
        if pl.starts_last_step() > 0 {
            start_steps += 1;
            start_time += dt;
        } else {
            plain_steps += 1;
            plain_time += dt;
        }
    }
    let mut otg = Ruckig::<3, ThrowErrorHandler>::new(None, 0.001);
    let mut traj = Trajectory::new(None);
    let t0 = Instant::now();
    for input in inputs {
        let r = otg.calculate(black_box(input), &mut traj);
        black_box((r.is_ok(), traj.get_duration()));
    }
    let ruckig = t0.elapsed().as_secs_f64() / inputs.len() as f64;
    let push = push_time.as_secs_f64() / f64::from(pushes.max(1));
    let with_start = start_time.as_secs_f64() / f64::from(start_steps.max(1));
    let plain = plain_time.as_secs_f64() / f64::from(plain_steps.max(1));
    let start = (with_start - plain).max(0.0);
    println!("\n(a) planning per motion, look-ahead 64, {MOTIONS} random 3-axis lines:");
    println!(
        "    mcemu push (limits, junction, look-ahead)  {:8.3} µs",
        push * 1e6
    );
    println!("    mcemu profile plan at the motion's start   {:8.3} µs  (step with a start {:.3} µs, without {:.3} µs)", start * 1e6, with_start * 1e6, plain * 1e6);
    println!(
        "    mcemu total per motion                     {:8.3} µs",
        (push + start) * 1e6
    );
    println!(
        "    rsruckig 3-DoF time-synchronized plan      {:8.3} µs\n",
        ruckig * 1e6
    );
}

/// 100 000 lines of 0.05 mm turning by up to ±3° each, at 1 kHz.
fn dense_gcode() {
    let period = 1e-3;
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let mut pl =
        PathPlanner::new(config(period), [0.0; MAX_AXES]).unwrap_or_else(|e| panic!("{e}"));
    let mut events = Vec::new();
    let (mut at, mut heading) = ([0.0; MAX_AXES], 0.0f64);
    let (mut max_step, mut max_push) = (Duration::ZERO, Duration::ZERO);
    let (mut max_starts, mut steps, mut total) = (0usize, 0u64, Duration::ZERO);
    let mut over_100us = 0u32;
    let mut max_visits = 0usize;
    let mut pushed = 0;
    const SEGMENTS: usize = 100_000;
    while pushed < SEGMENTS || !pl.is_idle() {
        while pushed < SEGMENTS && pl.queued() < PlannerConfig::MAX_CAPACITY {
            heading += rng.uniform(-3.0, 3.0).to_radians();
            let mut to = at;
            to[0] += 0.05 * heading.cos();
            to[1] += 0.05 * heading.sin();
            to[2] += rng.uniform(-1e-3, 1e-3);
            let t0 = Instant::now();
            let r = pl.push_motion(motion((at, to), pushed as u64));
            max_push = max_push.max(t0.elapsed());
            r.unwrap_or_else(|e| panic!("push: {e}"));
            at = to;
            pushed += 1;
        }
        let t0 = Instant::now();
        black_box(pl.step(&mut events));
        let dt = t0.elapsed();
        events.clear();
        max_visits = max_visits.max(pl.lookahead_visits());
        max_step = max_step.max(dt);
        if dt > Duration::from_micros(100) {
            over_100us += 1;
        }
        total += dt;
        steps += 1;
        max_starts = max_starts.max(pl.starts_last_step());
    }
    println!("(b) dense G-code: {SEGMENTS} lines of 0.05 mm at 1 kHz, {steps} steps:");
    println!(
        "    longest step()            {:10.3} µs   (servo period {:.0} µs)",
        max_step.as_secs_f64() * 1e6,
        period * 1e6
    );
    println!(
        "    mean step()               {:10.3} µs",
        total.as_secs_f64() * 1e6 / steps as f64
    );
    println!("    steps over 100 µs         {over_100us:10}     (preemption on a shared machine shows here)");
    println!(
        "    longest push_motion()     {:10.3} µs",
        max_push.as_secs_f64() * 1e6
    );
    println!("    most motions started in one step: {max_starts}");
    println!("    most look-ahead visits in one step: {max_visits} (queue entries; window 64)\n");
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_plan_per_motion(&mut c);
    dense_gcode();
    c.final_summary();
}
