//! Start-up to listening (issue: under 100 ms): the real binary, spawned until it prints
//! `listening: control …`, then stopped with SIGTERM. Baseline in the same run: spawning the
//! same binary for `--version` (process creation, loading, exit).
//!
//! `cargo bench -p mcemu --bench startup`

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const RUNS: usize = 30;

fn stats(mut xs: Vec<Duration>) -> (Duration, Duration, Duration) {
    xs.sort();
    (xs[xs.len() / 2], xs[xs.len() * 9 / 10], xs[xs.len() - 1])
}

fn main() {
    let mcemu = std::path::PathBuf::from(env!("CARGO_BIN_EXE_mcemu"));
    let config = std::env::temp_dir().join("mcemu-startup-bench.toml");
    std::fs::write(
        &config,
        concat!(
            include_str!("../../fixtures/default.toml"),
            "\n# bench: any free port\n"
        )
        .replace("bind = \"127.0.0.1:8700\"", "bind = \"127.0.0.1:0\""),
    )
    .unwrap();
    let mut baseline = Vec::new();
    let mut startup = Vec::new();
    for _ in 0..RUNS {
        let t = Instant::now();
        let status = Command::new(&mcemu)
            .arg("--version")
            .stdout(Stdio::null())
            .status()
            .unwrap();
        assert!(status.success());
        baseline.push(t.elapsed());

        let t = Instant::now();
        let mut child = Command::new(&mcemu)
            .args(["run", "--config", config.to_str().unwrap()])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let stdout = child.stdout.take().unwrap();
        let mut lines = BufReader::new(stdout).lines();
        loop {
            let line = lines.next().expect("mcemu exited").unwrap();
            if line.starts_with("listening: control") {
                break;
            }
        }
        startup.push(t.elapsed());
        let _ = Command::new("kill")
            .args(["-TERM", &child.id().to_string()])
            .status();
        let _ = child.wait();
    }
    let (b50, b90, bmax) = stats(baseline);
    let (s50, s90, smax) = stats(startup);
    println!("startup: {RUNS} runs of {}", mcemu.display());
    println!("  baseline (spawn `mcemu --version`): p50 {b50:?}, p90 {b90:?}, max {bmax:?}");
    println!("  spawn → `listening: control`:      p50 {s50:?}, p90 {s90:?}, max {smax:?}  (requirement: < 100 ms)");
}
