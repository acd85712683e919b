//! A fixed workload for profilers (perf, callgrind): 8 moving axes, 200 000 ticks.
#![allow(clippy::expect_used)]
use axes::command::Command;
use axes::config::{AxisConfig, HomeSwitchConfig, PlantModel, SwitchConfig};
use axes::{Engine, EngineConfig, ParamId};

fn main() {
    let mut a = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 10.0),
        (ParamId::Units, 1000.0),
        (ParamId::RepMode, 0.0),
        (ParamId::Speed, 100.0),
        (ParamId::Accel, 1000.0),
        (ParamId::Decel, 1000.0),
        (ParamId::JerkMode, 1.0),
        (ParamId::Jerk, 20_000.0),
        (ParamId::FeLimit, 1e6),
        (ParamId::InPositionWindow, 0.01),
    ] {
        a.params.insert(p, v);
    }
    a.plant.model = PlantModel::Lag;
    a.plant.time_constant = 0.002;
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
    let n = 8;
    let mut e = Engine::new(&EngineConfig {
        axes: vec![a; n],
        ..EngineConfig::default()
    })
    .expect("machine");
    for axis in 0..n as u16 {
        e.apply(Command::Enable { axis }).expect("enable");
        e.apply(Command::MoveRelative {
            axis,
            distance: 1e8,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: Default::default(),
        })
        .expect("move");
    }
    let ticks: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(200_000);
    for _ in 0..ticks {
        e.step();
    }
    println!("{:?}", e.axis_status(0).map(|s| s.cmd_pos));
}
