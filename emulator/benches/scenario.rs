//! `mcemu scenario` speed, end to end through the real binary (issue: 8 axes moving for one
//! simulated hour at 1 ms without a trace in under 3.6 s of wall time; with a trace, the rate).
//!
//! Baselines in the same run: the same ticks as a bare `Engine::step` loop in this process, and
//! for the trace the same scenario without `--trace`, plus row formatting alone against the
//! standard library's float formatting.
//!
//! `cargo bench -p mcemu --bench scenario`

// A benchmark that cannot set itself up should stop loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use axes::command::{BufferMode, Enable, MoveRelative};
use axes::{AxisStatus, Engine};
use mcemu::config::Config;
use mcemu::scenario::Scenario;

const AXES: usize = 8;
const RUNS: usize = 3;
/// The hour of the requirement, and the shorter run the trace is measured on (an hour of trace
/// for 8 axes would be ~2.3 GB).
const HOUR: f64 = 3600.0;
const TRACE_SECONDS: f64 = 60.0;

/// The machine of `axes/benches/common`: steppers in mm with pulse output, encoder with index,
/// a lag plant, debounced limits and a home cam far away (so the axes keep moving all hour),
/// S-curve profiles and following-error supervision.
fn machine() -> String {
    let mut text = String::from("[machine]\nname = \"bench\"\nperiod = 0.001\n");
    for _ in 0..AXES {
        text.push_str(
            r#"
[[axes]]
[axes.params]
axis_type = "stepper"
units = 1000
rep_mode = "finite"
speed = 100
accel = 1000
decel = 1000
jerk_mode = 1
jerk = 20000
fe_limit = 1e6
in_position_window = 0.01
[axes.plant]
model = "lag"
time_constant = 0.002
[axes.switches.limit_pos]
position = 1e9
filter = 2
[axes.switches.limit_neg]
position = -1e9
filter = 2
[axes.switches.home]
low = 5e8
high = 500000010.0
"#,
        );
    }
    text
}

/// Enable every axis and start a move longer than an hour at 100 mm/s.
fn commands() -> Vec<axes::Command> {
    (0..AXES as u16)
        .flat_map(|axis| {
            [
                axes::Command::from(Enable { axis }),
                axes::Command::from(MoveRelative {
                    axis,
                    distance: 1e8,
                    velocity: None,
                    acceleration: None,
                    deceleration: None,
                    jerk: None,
                    buffer_mode: BufferMode::Aborting,
                }),
            ]
        })
        .collect()
}

/// The scenario: the same machine inline, the same commands as steps at 0.
fn scenario(end: f64) -> String {
    let mut text = format!("end = {end}\n");
    for axis in 0..AXES {
        let _ = write!(
            text,
            "[[step]]\nat = 0\ncommand = {{ type = \"enable\", axis = {axis} }}\n\
             [[step]]\nat = 0\ncommand = {{ type = \"move_relative\", axis = {axis}, distance = 1e8 }}\n"
        );
    }
    for axis in 0..AXES {
        // Still moving at the end: the hour was all motion.
        let _ = write!(
            text,
            "[[step]]\nat = {end}\nexpect = {{ axis = {axis}, state = \"discrete_motion\" }}\n"
        );
    }
    text + &machine()
}

fn median(mut xs: Vec<Duration>) -> Duration {
    xs.sort();
    xs[xs.len() / 2]
}

fn bare_steps(ticks: u64) -> Duration {
    let config = Config::parse(&machine(), "bench machine").unwrap();
    let mut engine = Engine::new(&config.engine_config()).unwrap();
    for c in commands() {
        engine.apply(c).unwrap();
    }
    let start = Instant::now();
    for _ in 0..ticks {
        engine.step();
    }
    let elapsed = start.elapsed();
    std::hint::black_box(engine.axis(0).map(|a| a.motor_position()));
    elapsed
}

fn in_process(path: &Path) -> Duration {
    let start = Instant::now();
    let s = Scenario::load(path).unwrap();
    let report = s.run(None).unwrap();
    let elapsed = start.elapsed();
    assert!(report.passed(), "{:?}", report.failures);
    elapsed
}

/// Wall time of `mcemu scenario FILE [--trace OUT]`, process start to exit.
fn binary(path: &Path, trace: Option<&Path>) -> Duration {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_mcemu"));
    cmd.arg("scenario").arg(path);
    if let Some(t) = trace {
        cmd.arg("--trace").arg(t);
    }
    let start = Instant::now();
    let out = cmd.output().unwrap();
    let elapsed = start.elapsed();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    elapsed
}

fn secs(d: Duration) -> String {
    format!("{:.3} s", d.as_secs_f64())
}

/// The row format before `zmij`/`itoa`: `write!` with `Display`, as a same-run baseline.
fn std_row(out: &mut Vec<u8>, time: f64, axis: usize, s: &AxisStatus) {
    let flag = |f: axes::AxisFlags| u8::from(s.flags.contains(f));
    let _ = writeln!(
        out,
        "{time},{axis},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
        s.state.name(),
        s.cmd_pos,
        s.cmd_vel,
        s.cmd_acc,
        s.act_pos,
        s.act_vel,
        s.following_error,
        s.pulses,
        s.encoder_counts,
        flag(axes::AxisFlags::HW_LIMIT_POS),
        flag(axes::AxisFlags::HW_LIMIT_NEG),
        flag(axes::AxisFlags::HOME_SWITCH),
        flag(axes::AxisFlags::HOMED),
        s.last_error.map_or("", |e| e.name()),
    );
}

/// Rows per second of formatting alone (no I/O), over recorded statuses of the moving machine.
fn formatting_rates() -> (f64, f64) {
    let config = Config::parse(&machine(), "bench machine").unwrap();
    let mut engine = Engine::new(&config.engine_config()).unwrap();
    for c in commands() {
        engine.apply(c).unwrap();
    }
    // Small enough to stay in cache, as one tick's statuses are when a trace is written.
    let ticks = 1_000u64;
    let mut statuses = Vec::with_capacity(ticks as usize * AXES);
    for _ in 0..ticks {
        engine.step();
        statuses.extend((0..AXES).filter_map(|i| engine.axis_status(i)));
    }
    const REPEAT: usize = 50;
    let rate = |format: fn(&mut Vec<u8>, f64, usize, &AxisStatus)| {
        let mut buf = Vec::with_capacity(statuses.len() * 200);
        let runs = (0..RUNS)
            .map(|_| {
                let start = Instant::now();
                for _ in 0..REPEAT {
                    buf.clear();
                    for (k, s) in statuses.iter().enumerate() {
                        format(&mut buf, (k / AXES) as f64 / 1000.0, k % AXES, s);
                    }
                }
                let elapsed = start.elapsed();
                std::hint::black_box(&buf);
                elapsed
            })
            .collect();
        (statuses.len() * REPEAT) as f64 / median(runs).as_secs_f64()
    };
    (rate(mcemu::trace::format_row), rate(std_row))
}

fn main() {
    let dir: PathBuf = Path::new(env!("CARGO_TARGET_TMPDIR")).join("scenario-bench");
    std::fs::create_dir_all(&dir).unwrap();
    let hour = dir.join("hour.toml");
    let minute = dir.join("minute.toml");
    let trace = dir.join("minute.csv");
    std::fs::write(&hour, scenario(HOUR)).unwrap();
    std::fs::write(&minute, scenario(TRACE_SECONDS)).unwrap();
    let ticks = |seconds: f64| (seconds / 1e-3).round() as u64;

    println!(
        "scenario: {AXES} moving S-curve stepper axes (encoder, lag plant, switches), 1 ms; \
         median of {RUNS} runs"
    );
    let base = median((0..RUNS).map(|_| bare_steps(ticks(HOUR))).collect());
    let inproc = median((0..RUNS).map(|_| in_process(&hour)).collect());
    let bin = median((0..RUNS).map(|_| binary(&hour, None)).collect());
    println!("one simulated hour ({} ticks), no trace:", ticks(HOUR));
    println!("  baseline: bare Engine::step loop      {:>10}", secs(base));
    println!(
        "  Scenario::load + run, in process      {:>10}  ({:.3}x baseline)",
        secs(inproc),
        inproc.as_secs_f64() / base.as_secs_f64()
    );
    println!(
        "  mcemu scenario (the binary, wall)     {:>10}  ({:.3}x baseline; requirement < 3.6 s: {})",
        secs(bin),
        bin.as_secs_f64() / base.as_secs_f64(),
        if bin.as_secs_f64() < 3.6 { "met" } else { "NOT MET" }
    );

    let plain = median((0..RUNS).map(|_| binary(&minute, None)).collect());
    let traced = median((0..RUNS).map(|_| binary(&minute, Some(&trace))).collect());
    let bytes = std::fs::metadata(&trace).unwrap().len() as f64;
    let rows = (ticks(TRACE_SECONDS) + 1) as f64 * AXES as f64;
    let _ = std::fs::remove_file(&trace);
    println!(
        "{TRACE_SECONDS} simulated s ({rows} rows, {:.1} MB of trace):",
        bytes / 1e6
    );
    println!(
        "  baseline: mcemu scenario, no trace    {:>10}",
        secs(plain)
    );
    println!(
        "  mcemu scenario --trace (wall)         {:>10}  = {:.2} M rows/s, {:.0} MB/s \
         (tracing alone: {:.2} M rows/s)",
        secs(traced),
        rows / traced.as_secs_f64() / 1e6,
        bytes / traced.as_secs_f64() / 1e6,
        rows / (traced.as_secs_f64() - plain.as_secs_f64()).max(1e-9) / 1e6,
    );
    let (fast, std) = formatting_rates();
    println!(
        "row formatting alone: zmij/itoa {:.2} M rows/s; baseline std `Display` {:.2} M rows/s \
         ({:.1}x)",
        fast / 1e6,
        std / 1e6,
        fast / std
    );
    let _ = std::fs::remove_dir_all(&dir);
}
