//! Shared by the runtime benches: the machine under test and the commands that make it move.

use axes::command::BufferMode;
use axes::config::{AxisConfig, EngineConfig};
use axes::{Command, Engine};

/// `n` axes with default configuration, 1 ms period.
pub fn machine(n: usize) -> EngineConfig {
    EngineConfig {
        axes: vec![AxisConfig::default(); n],
        ..EngineConfig::default()
    }
}

pub fn engine(n: usize) -> Engine {
    match Engine::new(&machine(n)) {
        Ok(engine) => engine,
        Err(e) => {
            eprintln!("bench machine config is invalid: {e}");
            std::process::exit(2);
        }
    }
}

/// Enable every axis and jog it; errors are ignored (the engine may not support motion yet).
pub fn motion_commands(n: usize) -> Vec<Command> {
    (0..n as u16)
        .flat_map(|axis| {
            [
                Command::Enable { axis },
                Command::MoveVelocity {
                    axis,
                    velocity: 100.0 * f64::from(axis + 1),
                    acceleration: None,
                    deceleration: None,
                    jerk: None,
                    buffer_mode: BufferMode::Aborting,
                },
            ]
        })
        .collect()
}

pub fn fmt_duration(d: std::time::Duration) -> String {
    let s = d.as_secs_f64();
    if s >= 1.0 {
        format!("{s:.3} s")
    } else if s >= 1e-3 {
        format!("{:.3} ms", s * 1e3)
    } else if s >= 1e-6 {
        format!("{:.1} µs", s * 1e6)
    } else {
        format!("{:.0} ns", s * 1e9)
    }
}
