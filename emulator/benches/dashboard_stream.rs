//! The dashboard's cost: mcemu's CPU while 0, 1 and 4 dashboard pages stream 8 axes × 4
//! channels at 1 kHz (the page's default: cmd_pos, act_pos, cmd_vel, following_error of axes
//! 0–7), the pages' frame rate (requestAnimationFrame in headless chromium), their JS heap and
//! mcemu's resident memory after each run. The run with no page is the baseline, measured in
//! the same run on the same mcemu.
//!
//! ```sh
//! cargo bench -p mcemu --bench dashboard_stream
//! # memory over 10 minutes of streaming to one page:
//! MCEMU_DASHBOARD_SECONDS=600 MCEMU_DASHBOARD_PAGES=0,1 cargo bench -p mcemu --bench dashboard_stream
//! ```
//!
//! The page's JS heap and mcemu's RSS are printed at the start and at the end of each window:
//! bounded memory shows as an end no larger than the start plus noise.
//!
//! mcemu runs an 8-axis machine on the realtime clock (1 ms), every axis jogging so every value
//! changes each tick. The pages are tabs of one chromium driven by `tests/web/bench.mjs`
//! (playwright-core and chromium from `scripts/setup`). CPU = utime + stime of mcemu from
//! `/proc/PID/stat` over the measured window (`MCEMU_DASHBOARD_SECONDS`, default 20), as % of
//! one core.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use mcemu_tests::{require_tool, spawn_until_line, workspace_root, READY_TIMEOUT};
use serde_json::{json, Value};

/// Pages per run, unless `MCEMU_DASHBOARD_PAGES` lists others (`0,1`); 0 is the baseline.
const PAGES: [usize; 3] = [0, 1, 4];

fn main() {
    let pages_list: Vec<usize> = std::env::var("MCEMU_DASHBOARD_PAGES")
        .ok()
        .map(|s| {
            s.split(',')
                .map(|p| {
                    p.trim()
                        .parse()
                        .expect("MCEMU_DASHBOARD_PAGES: numbers, `0,1`")
                })
                .collect()
        })
        .unwrap_or_else(|| PAGES.to_vec());
    let seconds: f64 = std::env::var("MCEMU_DASHBOARD_SECONDS")
        .ok()
        .map(|s| s.parse().expect("MCEMU_DASHBOARD_SECONDS: a number"))
        .unwrap_or(20.0);
    let dir = std::env::temp_dir().join(format!("mcemu-dashboard-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut config = String::from("[machine]\nname = \"bench8\"\nclock = \"realtime\"\n");
    for n in 0..8 {
        config.push_str(&format!("\n[[axes]]\nname = \"a{n}\"\n"));
    }
    let path = dir.join("bench8.toml");
    std::fs::write(&path, config).unwrap();
    let mut command = Command::new(env!("CARGO_BIN_EXE_mcemu"));
    command
        .args(["run", "--config"])
        .arg(&path)
        .arg("--state-dir")
        .arg(&dir)
        .args(["--set", "frontends.control.bind=127.0.0.1:0"]);
    let (mut mcemu, address) = spawn_until_line(command, "listening: control ", READY_TIMEOUT);
    let base = format!("http://{}", address.trim());
    let pid = mcemu.id();
    let agent: ureq::Agent = ureq::Agent::config_builder()
        .timeout_global(Some(Duration::from_secs(30)))
        .build()
        .into();
    for axis in 0..8 {
        for command in [
            json!({"type": "enable", "axis": axis}),
            json!({"type": "move_velocity", "axis": axis, "velocity": 1.0 + axis as f64}),
        ] {
            agent
                .post(format!("{base}/api/v1/commands"))
                .header("content-type", "application/json")
                .send(command.to_string())
                .unwrap();
        }
    }
    println!(
        "dashboard_stream: 8 axes × 4 channels at 1 kHz (realtime clock), {seconds} s per run; \
         pages are tabs of one headless chromium"
    );
    println!(
        "{:>6} {:>14} {:>16} {:>22} {:>20} {:>20} {:>6}",
        "pages",
        "mcemu CPU %",
        "Δ per page %",
        "page fps min/mean",
        "page heap MB start→end",
        "mcemu RSS MB start→end",
        "lost"
    );
    let mut baseline = None;
    for pages in pages_list {
        let (cpu, rss_start, result) = if pages == 0 {
            let before = cpu_seconds(pid);
            let rss = rss_bytes(pid);
            let start = Instant::now();
            std::thread::sleep(Duration::from_secs_f64(seconds));
            (
                (cpu_seconds(pid) - before) / start.elapsed().as_secs_f64(),
                rss,
                json!({"fps": [], "heap_start": [], "heap": [], "lost": []}),
            )
        } else {
            run_pages(&base, pid, pages, seconds)
        };
        let base_cpu = *baseline.get_or_insert(cpu);
        let per_page = if pages == 0 {
            "-".to_string()
        } else {
            format!("{:.2}", (cpu - base_cpu) * 100.0 / pages as f64)
        };
        let floats = |key: &str| -> Vec<f64> {
            result[key]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap_or(0.0))
                .collect()
        };
        let fps = floats("fps");
        let heap = floats("heap");
        let heap_start = floats("heap_start");
        let lost: f64 = floats("lost").iter().sum();
        let fps_text = if fps.is_empty() {
            "-".to_string()
        } else {
            format!(
                "{:.1}/{:.1}",
                fps.iter().copied().fold(f64::INFINITY, f64::min),
                fps.iter().sum::<f64>() / fps.len() as f64
            )
        };
        let largest = |v: &[f64]| v.iter().copied().fold(0.0, f64::max) / 1e6;
        let heap_text = if heap.is_empty() {
            "-".to_string()
        } else {
            format!("{:.1}→{:.1}", largest(&heap_start), largest(&heap))
        };
        let rss_text = format!("{:.1}→{:.1}", rss_start / 1e6, rss_bytes(pid) / 1e6);
        println!(
            "{pages:>6} {:>14.2} {per_page:>16} {fps_text:>22} {heap_text:>20} {rss_text:>20} {lost:>6}",
            cpu * 100.0,
        );
    }
    mcemu.kill();
    let _ = std::fs::remove_dir_all(&dir);
}

/// Open `pages` pages and measure mcemu's CPU share while they stream; also mcemu's RSS when
/// the window starts.
fn run_pages(base: &str, pid: u32, pages: usize, seconds: f64) -> (f64, f64, Value) {
    let web = workspace_root().join("tests/web");
    assert!(
        web.join("node_modules/playwright-core").is_dir(),
        "tests/web/node_modules is missing: run scripts/setup"
    );
    let mut child = Command::new(require_tool("node"))
        .current_dir(&web)
        .args(["bench.mjs", base, &pages.to_string(), &seconds.to_string()])
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let mut measuring = None;
    let mut rss_start = 0.0;
    let mut result = None;
    for line in lines.by_ref() {
        let line = line.unwrap();
        if line == "measuring" {
            rss_start = rss_bytes(pid);
            measuring = Some((cpu_seconds(pid), Instant::now()));
        } else if line.starts_with('{') {
            let (before, start) = measuring.expect("`measuring` before the result");
            let cpu = (cpu_seconds(pid) - before) / start.elapsed().as_secs_f64();
            result = Some((cpu, rss_start, serde_json::from_str(&line).unwrap()));
            break;
        }
    }
    let status = child.wait().unwrap();
    assert!(status.success(), "bench.mjs failed: {status}");
    result.expect("bench.mjs printed no result")
}

/// utime + stime of `pid`, seconds.
fn cpu_seconds(pid: u32) -> f64 {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
    // Fields after the command name (which may hold spaces) in parentheses.
    let rest = stat.rsplit_once(')').unwrap().1;
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // utime and stime are fields 14 and 15 of the whole line: 12 and 13 after `)`.
    let ticks: f64 = fields[11].parse::<f64>().unwrap() + fields[12].parse::<f64>().unwrap();
    ticks / clock_ticks_per_second()
}

fn clock_ticks_per_second() -> f64 {
    let out = Command::new("getconf").arg("CLK_TCK").output().unwrap();
    String::from_utf8_lossy(&out.stdout)
        .trim()
        .parse()
        .unwrap_or(100.0)
}

fn rss_bytes(pid: u32) -> f64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(0.0, |kb| kb * 1024.0)
}
