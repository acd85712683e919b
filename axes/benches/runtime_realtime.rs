//! Realtime clock at 1 ms: drift of simulated vs wall time at the end of the run, ticks,
//! caught-up and dropped ticks, overruns, and the wake-up lateness histogram; beside a bare
//! `thread::sleep`-until-deadline loop on the same deadlines (run first, no engine).
//!
//! `MCEMU_RT_SECONDS=60 cargo bench -p axes --bench runtime_realtime`
//! (`MCEMU_RT_SECONDS`: runtime duration, default 60; the baseline runs min(5, that) seconds;
//! `MCEMU_RT_AXES`: axes, default 8; `MCEMU_RT_SPIN_US`: the runtime's spin window in µs,
//! default the runtime's own choice, 0 = sleep only.)

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use axes::runtime::{ClockMode, LatenessHistogram, Runtime, RuntimeOptions};

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Absolute-deadline loop with plain sleeps: what the OS gives without the runtime.
fn baseline(period: Duration, seconds: f64) -> (LatenessHistogram, f64) {
    let mut histogram = LatenessHistogram::default();
    let ticks = (seconds / period.as_secs_f64()).round() as u32;
    let start = Instant::now();
    for n in 1..=ticks {
        let deadline = start + period * n;
        let now = Instant::now();
        if now < deadline {
            std::thread::sleep(deadline - now);
            histogram.record(Instant::now() - deadline);
        }
    }
    let drift = f64::from(ticks) * period.as_secs_f64() - start.elapsed().as_secs_f64();
    (histogram, drift)
}

/// CPU time (user + system) of this process so far, from /proc (Linux); None elsewhere.
fn process_cpu() -> Option<Duration> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let fields: Vec<&str> = stat
        .get(stat.rfind(')')? + 2..)?
        .split_whitespace()
        .collect();
    let ticks: u64 = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    Some(Duration::from_millis(ticks * 10)) // USER_HZ is 100 on Linux
}

fn cpu_percent(before: Option<Duration>, wall: Duration) -> String {
    match (before, process_cpu()) {
        (Some(a), Some(b)) => format!(
            "{:.1} %",
            (b - a).as_secs_f64() * 100.0 / wall.as_secs_f64()
        ),
        _ => "n/a".to_owned(),
    }
}

fn print_histogram(name: &str, h: &LatenessHistogram) {
    let f = common::fmt_duration;
    println!(
        "{name}: {} wake-ups, lateness p50 ≤ {}, p99 ≤ {}, max {}, mean {}",
        h.count(),
        f(h.p50()),
        f(h.p99()),
        f(h.max()),
        f(h.mean())
    );
    let total = h.count().max(1) as f64;
    let mut cumulative = 0;
    for (edge, count) in h.buckets() {
        cumulative += count;
        let edge = edge.map_or_else(|| "> 10 s".to_owned(), |e| format!("≤ {}", f(e)));
        println!(
            "    {edge:>12} {count:>9} {:>7.3} % {:>8.3} %",
            count as f64 * 100.0 / total,
            cumulative as f64 * 100.0 / total
        );
    }
}

fn main() {
    let seconds: f64 = env_or("MCEMU_RT_SECONDS", 60.0);
    let axes: usize = env_or("MCEMU_RT_AXES", 8);
    let baseline_seconds = seconds.min(5.0);
    let config = common::machine(axes);
    let period = Duration::from_secs_f64(config.period);
    println!(
        "runtime_realtime: period {}, {axes} axes; baseline {baseline_seconds} s, runtime {seconds} s",
        common::fmt_duration(period)
    );

    let (base, base_drift) = baseline(period, baseline_seconds);
    print_histogram("baseline (thread::sleep to deadline)", &base);
    println!("baseline drift at end: {:+.3} ms\n", base_drift * 1e3);

    let engine = common::engine(axes);
    let options = RuntimeOptions {
        spin_window: std::env::var("MCEMU_RT_SPIN_US")
            .ok()
            .and_then(|v| v.parse::<f64>().ok())
            .map(|us| us * 1e-6),
        ..RuntimeOptions::with_clock(ClockMode::Realtime)
    };
    let cpu = process_cpu();
    let started = Instant::now();
    let (handle, guard) = Runtime::start(engine, options).unwrap();
    for command in common::motion_commands(axes) {
        let _ = handle.call(command);
    }
    // A front-end-like reader: polls snapshots and stats every 10 ms.
    let reading = Arc::new(AtomicBool::new(true));
    let reader = {
        let (handle, reading) = (handle.clone(), Arc::clone(&reading));
        std::thread::spawn(move || {
            let mut reads = 0u64;
            while reading.load(Ordering::Relaxed) {
                std::hint::black_box(handle.snapshot());
                std::hint::black_box(handle.stats());
                reads += 1;
                std::thread::sleep(Duration::from_millis(10));
            }
            reads
        })
    };
    std::thread::sleep(Duration::from_secs_f64(seconds));
    let stats = handle.stats();
    let snapshot = handle.snapshot();
    let outside_elapsed = started.elapsed().as_secs_f64();
    let runtime_cpu = cpu_percent(cpu, started.elapsed());
    reading.store(false, Ordering::Relaxed);
    let reads = reader.join().unwrap();
    let engine = guard.stop().unwrap();

    print_histogram("runtime (servo thread)", &stats.lateness);
    let p = config.period;
    println!(
        "runtime: ticks {} (engine tick at stop {}), caught up {}, dropped {}, overruns {}, max tick time {}",
        stats.ticks_run,
        engine.tick(),
        stats.caught_up_ticks,
        stats.dropped_ticks,
        stats.overruns,
        common::fmt_duration(Duration::from_secs_f64(stats.max_tick_time)),
    );
    println!(
        "runtime: commands {}, snapshot allocations {} ({reads} reader polls); process CPU {runtime_cpu} of one core",
        stats.commands_applied, stats.snapshot_allocations
    );
    println!(
        "DRIFT at end (servo, last tick): simulated {:.6} s − wall {:.6} s = {:+.3} ms = {:+.3} periods (requirement: |drift| ≤ 1 period)",
        stats.ticks_run as f64 * p,
        stats.elapsed,
        stats.drift * 1e3,
        stats.drift / p
    );
    println!(
        "drift seen by a reader (latest snapshot vs wall since Runtime::start was called): {:+.3} ms",
        (snapshot.time() - outside_elapsed) * 1e3
    );
}
