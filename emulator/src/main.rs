//! `mcemu`: runs the motion engine on a machine config and serves its front-ends
//! (ARCHITECTURE §6). The config loader, the front-ends and the control API arrive with the
//! next issues; today `mcemu run` runs the embedded default machine on the realtime servo clock.

use std::process::ExitCode;
use std::time::Duration;

use axes::config::{AxisConfig, EngineConfig, HomeSwitchConfig, SwitchConfig};
use axes::runtime::{ClockMode, Runtime, RuntimeOptions};
use axes::{Engine, ParamId};

/// The embedded default machine: 4 stepper axes in mm (1000 pulses/mm, 10 000 counts/rev at
/// 1000 counts/mm), ±500 mm travel with limit switches, a home cam at 100–120 mm, 1 ms period.
fn default_machine() -> EngineConfig {
    let axis = |i: usize| {
        let mut a = AxisConfig {
            name: Some(format!("axis{i}")),
            ..AxisConfig::default()
        };
        for (p, v) in [
            (ParamId::AxisType, 10.0),
            (ParamId::Units, 1000.0),
            (ParamId::RepMode, 0.0),
            (ParamId::Speed, 100.0),
            (ParamId::Accel, 1000.0),
            (ParamId::Decel, 1000.0),
            (ParamId::FastDecel, 10_000.0),
        ] {
            a.params.insert(p, v);
        }
        a.switches.limit_pos = Some(SwitchConfig {
            position: 500.0,
            filter: 0,
            active_low: false,
        });
        a.switches.limit_neg = Some(SwitchConfig {
            position: -500.0,
            filter: 0,
            active_low: false,
        });
        a.switches.home = Some(HomeSwitchConfig {
            low: 100.0,
            high: 120.0,
            filter: 0,
            active_low: false,
        });
        a
    };
    EngineConfig {
        axes: (0..4).map(axis).collect(),
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
        Some("run") if args.len() == 1 => run(default_machine()),
        _ => usage(),
    }
}

fn run(config: EngineConfig) -> ExitCode {
    let engine = match Engine::new(&config) {
        Ok(e) => e,
        Err(e) => {
            eprintln!("mcemu: config: {e}");
            return ExitCode::FAILURE;
        }
    };
    let axes = engine.axis_count();
    let period_ms = engine.period() * 1e3;
    let (handle, _guard) =
        match Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Realtime)) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("mcemu: cannot start the servo runtime: {e}");
                return ExitCode::FAILURE;
            }
        };
    println!("mcemu: {axes} axes, servo period {period_ms} ms, realtime clock");
    println!("mcemu: no front-end listens yet (the control API and protocols are being built)");
    while handle.is_running() {
        std::thread::sleep(Duration::from_millis(200));
    }
    eprintln!("mcemu: the servo runtime stopped");
    ExitCode::FAILURE
}
