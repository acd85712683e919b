//! PT streams through the runtime (issue 12, performance): 8 axes each run a refresh-mode PT
//! stream of 1 ms points (1 kHz) for 60 s of virtual time, the host refilling 32 points at a
//! time through the `EngineHandle` whenever a FIFO half has run out. It must never underrun;
//! the figure is the virtual clock's speed as a multiple of real time, beside a baseline run
//! in the same process: the same 8 axes on plain long moves, advanced and read the same way.
//!
//! `cargo bench -p axes --bench stream_runtime`; `STREAM_RUNTIME_SECONDS=5` shortens the
//! simulated time (for callgrind). Beside each wall time it prints the voluntary context
//! switches per look at the buffers (Linux): the thread hand-offs, which cost little on a
//! loaded host and ~20 µs each on an idle VM, so they are the load-independent figure.

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::time::{Duration, Instant};

use axes::command::{Command, PtKind, PtPoint, PtPush, StreamConfig, StreamMode, StreamStart};
use axes::runtime::{ClockMode, EngineHandle, Runtime, RuntimeOptions};
use axes::{AxisState, Engine};

const AXES: usize = 8;
const SIM_SECONDS: u64 = 60;
/// Ticks advanced between two looks at the buffers, as a host refilling a refresh-mode FIFO
/// does: it holds 2 × 32 points (digest 001 TV57), so after 32 ms one half has run out and is
/// refilled while the other still holds 32 ms (`STREAM_RUNTIME_CHUNK` overrides, ≤ 32).
const CHUNK: u64 = 32;
const RUNS: usize = 3;
const POINTS_PER_PUSH: usize = 32;

/// The points of one axis: velocity V·sin(2πt / 1 s) (V a little different per axis), cut at
/// every millisecond with positions from the trapezoid rule, so that NMC's NORMAL rule
/// (v_end = 2·Δp/Δt − v_start) gives back the sine's velocities; a STOP point at the end.
struct SineStream {
    axis: u16,
    k: u64,
    last: u64,
    pos: f64,
    vel: f64,
    amplitude: f64,
}

impl SineStream {
    fn new(axis: u16, ms: u64) -> SineStream {
        SineStream {
            axis,
            k: 0,
            last: ms,
            pos: 0.0,
            vel: 0.0,
            // mm/ms: 50–85 mm/s.
            amplitude: 0.05 + 0.005 * f64::from(axis),
        }
    }

    fn next_push(&mut self) -> Option<Command> {
        if self.k >= self.last {
            return None;
        }
        let mut points = Vec::with_capacity(POINTS_PER_PUSH);
        while points.len() < POINTS_PER_PUSH && self.k < self.last {
            self.k += 1;
            let t = self.k as f64;
            if self.k == self.last {
                points.push(PtPoint {
                    position: 0.0,
                    time_ms: t,
                    kind: PtKind::Stop,
                });
                break;
            }
            let v = self.amplitude * (2.0 * std::f64::consts::PI * t / 1000.0).sin();
            self.pos += (v + self.vel) / 2.0;
            self.vel = v;
            points.push(PtPoint {
                position: self.pos,
                time_ms: t,
                kind: PtKind::Normal,
            });
        }
        Some(Command::from(PtPush {
            axis: self.axis,
            points,
        }))
    }
}

fn virtual_runtime(engine: Engine) -> (EngineHandle, axes::runtime::RuntimeGuard) {
    Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap()
}

/// How the host sends the refills of one look at the buffers.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Refill {
    /// `call` each push, waiting for its reply. On the virtual clock a blocking call serves the
    /// queue on the calling thread: no hand-off at all.
    Call,
    /// `submit` every push of the look and go on to the next advance without waiting: the
    /// virtual runtime's queue applies them in order before it, so their replies are in when
    /// the advance returns. The submits wake the servo thread, which may take the queue before
    /// the advance does (then the host waits for it).
    Pipelined,
    /// One atomic `call_batch` of the look's pushes (served on the calling thread, as `Call`).
    Batch,
    /// One `submit_batch` of the look's pushes, not waited on: one servo-thread wake-up a look.
    PipelinedBatch,
    /// One `call_each` of the look's pushes: one request and one publication, each push on its
    /// own (no rollback to prepare, unlike an atomic batch), served on the calling thread.
    Each,
}

/// Voluntary context switches of this process's live threads so far (Linux `/proc`; `None`
/// elsewhere): each is a thread blocking for another, the hand-offs that wall time on a loaded
/// host hides. Read before the runtime stops, while its servo thread is still alive.
fn voluntary_switches() -> Option<u64> {
    let mut total = 0;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let status = std::fs::read_to_string(task.ok()?.path().join("status")).ok()?;
        let line = status
            .lines()
            .find_map(|l| l.strip_prefix("voluntary_ctxt_switches:"))?;
        total += line.trim().parse::<u64>().ok()?;
    }
    Some(total)
}

/// Wall time and hand-offs (voluntary context switches) of one run.
struct RunCost {
    wall: Duration,
    switches: Option<u64>,
}

/// The PT run: returns its cost and the pushes made.
fn pt_run(ticks: u64, chunk: u64, refill: Refill) -> (RunCost, u64) {
    let (handle, guard) = virtual_runtime(common::engine(AXES));
    let mut streams: Vec<_> = (0..AXES as u16)
        .map(|axis| SineStream::new(axis, ticks))
        .collect();
    for axis in 0..AXES as u16 {
        handle
            .call(Command::from(axes::command::Enable { axis }))
            .unwrap();
        handle
            .call(Command::from(StreamConfig {
                axis,
                mode: StreamMode::Refresh,
                loop_count: 0,
                stop_deceleration: None,
            }))
            .unwrap();
    }
    let switches_before = voluntary_switches();
    let start = Instant::now();
    let mut pushes = 0;
    // Fill both FIFO halves, then start every axis in the same tick.
    for s in &mut streams {
        for _ in 0..2 {
            handle.call(s.next_push().unwrap()).unwrap();
            pushes += 1;
        }
    }
    handle
        .call(Command::from(StreamStart {
            axes: (0..AXES as u16).collect(),
        }))
        .unwrap();
    let mut done = 0;
    let mut pending: Vec<axes::runtime::PendingReply> = Vec::with_capacity(AXES);
    let mut pending_batch: Option<axes::runtime::Pending<Vec<axes::command::Reply>, _>> = None;
    while done < ticks + chunk {
        handle.advance(chunk).unwrap();
        done += chunk;
        for reply in pending.drain(..) {
            reply.wait().unwrap();
        }
        if let Some(reply) = pending_batch.take() {
            reply.wait().unwrap();
        }
        let snapshot = handle.snapshot();
        let mut refills = Vec::with_capacity(AXES);
        for (s, status) in streams.iter_mut().zip(&snapshot.axes) {
            assert_eq!(status.stream.underruns, 0, "axis {} ran dry", s.axis);
            if status.stream.space >= POINTS_PER_PUSH as u16 {
                refills.extend(s.next_push());
            }
        }
        pushes += refills.len() as u64;
        match refill {
            Refill::Call => {
                for push in refills {
                    handle.call(push).unwrap();
                }
            }
            Refill::Pipelined => {
                for push in refills {
                    pending.push(handle.submit(push).unwrap());
                }
            }
            Refill::Batch if refills.is_empty() => {}
            Refill::Batch => {
                handle.call_batch(refills).unwrap();
            }
            Refill::PipelinedBatch if refills.is_empty() => {}
            Refill::PipelinedBatch => {
                pending_batch = Some(handle.submit_batch(refills).unwrap());
            }
            Refill::Each if refills.is_empty() => {}
            Refill::Each => {
                for reply in handle.call_each(refills).unwrap() {
                    reply.unwrap();
                }
            }
        }
    }
    if let Some(reply) = pending_batch.take() {
        reply.wait().unwrap();
    }
    for reply in pending.drain(..) {
        reply.wait().unwrap();
    }
    let elapsed = start.elapsed();
    let switches = voluntary_switches()
        .zip(switches_before)
        .map(|(after, before)| after - before);
    let snapshot = handle.snapshot();
    for (axis, status) in snapshot.axes.iter().enumerate() {
        assert_eq!(status.stream.underruns, 0, "axis {axis} ran dry");
        assert_eq!(status.state, AxisState::Standstill, "axis {axis} finished");
        assert!(status.cmd_pos.abs() < 1e-6, "axis {axis} back at its start");
    }
    guard.stop().unwrap();
    let cost = RunCost {
        wall: elapsed,
        switches,
    };
    (cost, pushes)
}

/// The baseline: the same axes on plain long moves, advanced and read in the same chunks.
fn plain_run(ticks: u64, chunk: u64) -> RunCost {
    let (handle, guard) = virtual_runtime(common::engine(AXES));
    for command in common::motion_commands(AXES) {
        handle.call(command).unwrap();
    }
    let switches_before = voluntary_switches();
    let start = Instant::now();
    let mut done = 0;
    while done < ticks + chunk {
        handle.advance(chunk).unwrap();
        done += chunk;
        std::hint::black_box(handle.snapshot());
    }
    let elapsed = start.elapsed();
    let switches = voluntary_switches()
        .zip(switches_before)
        .map(|(after, before)| after - before);
    guard.stop().unwrap();
    RunCost {
        wall: elapsed,
        switches,
    }
}

/// The same PT streams on the engine alone, stepped on this thread (no runtime, no snapshots):
/// the per-tick cost of sampling the streams, refills included.
fn pt_bare(ticks: u64, chunk: u64) -> Duration {
    let mut e = common::engine(AXES);
    let mut streams: Vec<_> = (0..AXES as u16)
        .map(|axis| SineStream::new(axis, ticks))
        .collect();
    for axis in 0..AXES as u16 {
        e.apply(Command::from(axes::command::Enable { axis }))
            .unwrap();
    }
    for s in &mut streams {
        for _ in 0..2 {
            e.apply(s.next_push().unwrap()).unwrap();
        }
    }
    e.apply(Command::from(StreamStart {
        axes: (0..AXES as u16).collect(),
    }))
    .unwrap();
    let start = Instant::now();
    for tick in 1..=ticks + chunk {
        e.step();
        if tick % chunk == 0 {
            for s in &mut streams {
                let space = e.axis(usize::from(s.axis)).unwrap().status().stream.space;
                if space >= POINTS_PER_PUSH as u16 {
                    if let Some(push) = s.next_push() {
                        e.apply(push).unwrap();
                    }
                }
            }
        }
    }
    let elapsed = start.elapsed();
    assert!((0..AXES).all(|a| e.axis_status(a).unwrap().stream.underruns == 0));
    elapsed
}

/// The baseline of [`pt_bare`]: plain moves stepped on this thread.
fn plain_bare(ticks: u64, chunk: u64) -> Duration {
    let mut e = common::moving_engine(AXES);
    let start = Instant::now();
    for _ in 0..ticks + chunk {
        e.step();
    }
    let elapsed = start.elapsed();
    std::hint::black_box(&e);
    elapsed
}

fn median<T: Ord + Copy>(mut xs: Vec<T>) -> T {
    xs.sort();
    xs[xs.len() / 2]
}

/// The median wall time and the median hand-offs of `runs`.
fn median_cost(runs: Vec<RunCost>) -> (Duration, Option<u64>) {
    let switches: Option<Vec<u64>> = runs.iter().map(|r| r.switches).collect();
    let wall = median(runs.iter().map(|r| r.wall).collect());
    (wall, switches.map(median))
}

fn main() {
    let period = common::machine(1).period;
    let sim_seconds: u64 = std::env::var("STREAM_RUNTIME_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(SIM_SECONDS);
    let ticks = (sim_seconds as f64 / period).round() as u64;
    let chunk: u64 = std::env::var("STREAM_RUNTIME_CHUNK")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(CHUNK)
        .clamp(1, CHUNK);
    println!(
        "stream_runtime: {AXES} axes, {SIM_SECONDS} simulated s at {} ms through the runtime \
         (virtual clock), advanced {chunk} ticks at a time; median of {RUNS} runs",
        period * 1e3,
        SIM_SECONDS = sim_seconds
    );
    let mut pushes = 0;
    let mut pt_runs = Vec::new();
    for refill in [
        Refill::Call,
        Refill::Pipelined,
        Refill::Batch,
        Refill::PipelinedBatch,
        Refill::Each,
    ] {
        let cost = median_cost(
            (0..RUNS)
                .map(|_| {
                    let (cost, n) = pt_run(ticks, chunk, refill);
                    pushes = n;
                    cost
                })
                .collect(),
        );
        pt_runs.push((refill, cost));
    }
    let (plain, plain_switches) = median_cost((0..RUNS).map(|_| plain_run(ticks, chunk)).collect());
    let pt_engine = median((0..RUNS).map(|_| pt_bare(ticks, chunk)).collect());
    let plain_engine = median((0..RUNS).map(|_| plain_bare(ticks, chunk)).collect());
    let speed = |d: Duration| sim_seconds as f64 / d.as_secs_f64();
    // Hand-offs per look at the buffers: the part of the wall time a loaded host hides and an
    // idle one shows (each is a thread wake-up).
    let looks = (ticks + chunk).div_ceil(chunk) as f64;
    let per_look =
        |s: Option<u64>| s.map_or("-".to_owned(), |s| format!("{:.2}", s as f64 / looks));
    println!(
        "{:<44} {:>12} {:>14} {:>16}",
        "", "wall", "× real time", "switches / look"
    );
    println!(
        "{:<44} {:>12} {:>13.0}x {:>16}",
        "baseline: 8 axes on plain moves",
        common::fmt_duration(plain),
        speed(plain),
        per_look(plain_switches)
    );
    for (refill, (pt, switches)) in pt_runs {
        println!(
            "{:<44} {:>12} {:>13.0}x {:>16}  ({:.2} × the baseline's wall time)",
            format!("PT streams, refills by {refill:?}"),
            common::fmt_duration(pt),
            speed(pt),
            per_look(switches),
            pt.as_secs_f64() / plain.as_secs_f64()
        );
    }
    println!(
        "{pushes} pushes of 32 points per run, 1 kHz points, no underrun (requirement: ≥ 1000x real time)"
    );
    println!(
        "engine alone (step() on this thread): plain {} = {:.0}x, PT {} = {:.0}x; PT / plain {:.2}",
        common::fmt_duration(plain_engine),
        speed(plain_engine),
        common::fmt_duration(pt_engine),
        speed(pt_engine),
        pt_engine.as_secs_f64() / plain_engine.as_secs_f64()
    );
}
