//! A fixed runtime workload for profilers: 8 moving axes advanced 200 000 ticks in virtual time.
#![allow(clippy::expect_used, clippy::unwrap_used)]
use axes::command::{BufferMode, Command};
use axes::config::{AxisConfig, EngineConfig, HomeSwitchConfig, PlantModel, SwitchConfig};
use axes::runtime::{ClockMode, Runtime, RuntimeOptions};
use axes::{Engine, ParamId};

fn main() {
    let mut a = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 10.0),
        (ParamId::Units, 1000.0),
        (ParamId::RepMode, 0.0),
        (ParamId::Speed, 100.0),
        (ParamId::JerkMode, 1.0),
        (ParamId::Jerk, 20_000.0),
        (ParamId::Accel, 1000.0),
        (ParamId::Decel, 1000.0),
        (ParamId::FeLimit, 1e6),
    ] {
        a.params.insert(p, v);
    }
    a.plant.model = PlantModel::Lag;
    a.switches.limit_pos = Some(SwitchConfig {
        position: 1e9,
        filter: 2,
        active_low: false,
    });
    a.switches.limit_neg = Some(SwitchConfig {
        position: -1e9,
        filter: 2,
        active_low: false,
    });
    a.switches.home = Some(HomeSwitchConfig {
        low: 5e8,
        high: 5e8 + 10.0,
        filter: 0,
        active_low: false,
    });
    let engine = Engine::new(&EngineConfig {
        axes: vec![a; 8],
        ..EngineConfig::default()
    })
    .unwrap();
    let (h, g) = Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap();
    for axis in 0..8u16 {
        h.call(Command::Enable { axis }).unwrap();
        h.call(Command::MoveRelative {
            axis,
            distance: 1e8,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: BufferMode::Aborting,
        })
        .unwrap();
    }
    let ticks: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(200_000);
    let t = std::time::Instant::now();
    h.advance(ticks).unwrap();
    println!("{:?} per tick", t.elapsed() / ticks as u32);
    g.stop().unwrap();
}
