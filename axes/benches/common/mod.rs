//! Shared by the runtime benches: the machine under test and the commands that make it move.
// Shared by several benches; each uses a part.
#![allow(dead_code)]

use axes::command::{
    BufferMode, Enable, GroupBufferMode, GroupCreate, GroupEnable, MoveLinearAbsolute,
    MoveRelative, TransitionMode,
};
use axes::config::{AxisConfig, EngineConfig, HomeSwitchConfig, PlantModel, SwitchConfig};
use axes::{Command, Engine, ParamId};

/// A stepper in mm with the whole per-tick pipeline: pulse output, encoder with index, lag
/// plant, both limits (debounced) and a home cam — far away, so the axes keep moving for the
/// whole measurement — S-curve profiles and following-error supervision.
pub fn busy_axis() -> AxisConfig {
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
    a
}

/// `n` busy axes, 1 ms period.
pub fn machine(n: usize) -> EngineConfig {
    EngineConfig {
        axes: vec![busy_axis(); n],
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

/// Enable every axis and start a long S-curve move (it runs for more than a simulated hour).
pub fn motion_commands(n: usize) -> Vec<Command> {
    (0..n as u16)
        .flat_map(|axis| {
            [
                Command::from(Enable { axis }),
                Command::from(MoveRelative {
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

/// A machine of `n` busy axes, enabled and moving.
pub fn moving_engine(n: usize) -> Engine {
    let mut e = engine(n);
    for command in motion_commands(n) {
        if let Err(err) = e.apply(command) {
            eprintln!("bench command refused: {err}");
            std::process::exit(2);
        }
    }
    e
}

/// A machine of `n` busy axes, enabled, at rest, all in group 1, enabled (Standby).
pub fn grouped_engine(n: usize) -> Engine {
    grouped_engine_of(machine(n))
}

/// [`grouped_engine`] of the machine `config` (every axis in group 1).
pub fn grouped_engine_of(config: EngineConfig) -> Engine {
    let n = config.axes.len();
    let mut e = match Engine::new(&config) {
        Ok(engine) => engine,
        Err(e) => {
            eprintln!("bench machine refused: {e}");
            std::process::exit(2);
        }
    };
    let setup = (0..n as u16)
        .map(|axis| Command::from(Enable { axis }))
        .chain([
            Command::from(GroupCreate {
                group: 1,
                axes: (0..n as u16).collect(),
                queue_capacity: None,
                lookahead: None,
                result_axis: None,
                orientation: Default::default(),
            }),
            Command::from(GroupEnable { group: 1 }),
        ]);
    for command in setup {
        if let Err(err) = e.apply(command) {
            eprintln!("bench command refused: {err}");
            std::process::exit(2);
        }
    }
    e
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

/// The line to corner `k` of an `n`-D hypercube of side 100 mm in Gray-code order, blended
/// (BlendingLow, corner distance 5 mm) at 50 mm/s: consecutive corners differ in one
/// coordinate, so every segment is a 100 mm line and every junction a right angle.
pub fn hypercube_corner_move(n: usize, k: u64) -> Command {
    let gray = k ^ (k >> 1);
    let position = (0..n as u64)
        .map(|bit| if (gray >> bit) & 1 == 1 { 100.0 } else { 0.0 })
        .collect();
    Command::from(MoveLinearAbsolute {
        group: 1,
        position,
        velocity: Some(50.0),
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: GroupBufferMode::BlendingLow,
        transition: TransitionMode::CornerDistance(5.0),
        user_segment: None,
        independent: Default::default(),
        coordinate_system: None,
    })
}
