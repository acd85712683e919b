//! `mcemu`: runs the motion engine on a machine config and serves its front-ends
//! (ARCHITECTURE §6). The config loader, front-ends and control API arrive with later issues.

use std::process::ExitCode;
use std::time::{Duration, Instant};

use axes::config::{AxisConfig, EngineConfig};
use axes::Engine;

fn default_machine() -> EngineConfig {
    EngineConfig {
        axes: (0..4)
            .map(|i| AxisConfig {
                name: Some(format!("axis{i}")),
                ..AxisConfig::default()
            })
            .collect(),
        ..EngineConfig::default()
    }
}

fn usage() -> ExitCode {
    eprintln!("usage: mcemu run");
    ExitCode::from(2)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("run") => run(default_machine()),
        _ => usage(),
    }
}

fn run(config: EngineConfig) -> ExitCode {
    let mut engine = match Engine::new(&config) {
        Ok(e) => e,
        Err(e) => {
            eprintln!("mcemu: config: {e}");
            return ExitCode::FAILURE;
        }
    };
    println!(
        "mcemu: {} axes, servo period {} ms, realtime clock; no front-end listens yet",
        engine.axis_count(),
        engine.period() * 1e3
    );
    let period = Duration::from_secs_f64(engine.period());
    let start = Instant::now();
    loop {
        engine.step();
        let deadline = start + period.mul_f64(engine.tick() as f64);
        if let Some(wait) = deadline.checked_duration_since(Instant::now()) {
            std::thread::sleep(wait);
        }
    }
}
