//! Gantry at the engine level (issue 12 item 6): slaves receive the master's command with
//! their offset (NMC S-GANTRY, digest 001 §5), the deviation warning and fault (HMC AxisStatus
//! bits 5–6, digest 000 §4.4), HIMC's pair view (digest 004 §6.3 TV 36), homing the master
//! moves and redefines the slaves, slaves refuse single-axis motion, and bad input.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, EngineError, ErrorKind, GantryDisable, GantryEnable, InjectFollowingError, Reset,
    SetPosition,
};
use axes::config::{AxisConfig, PlantModel};
use axes::homing::{HomingQuirks, HomingSpec};
use axes::param::ParamId;
use axes::status::{CouplingKind, CouplingPhase};
use axes::{AxisFlags, AxisState, Engine};
use common::{gear_in_of, home_of, move_abs_of, ok, refused, run, stepper_mm};

fn machine(n: usize) -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), n)
}

fn gantry(master: u16, slaves: &[u16], warning_limit: f64, fault_limit: f64) -> Command {
    Command::from(GantryEnable {
        master,
        slaves: slaves.to_vec(),
        warning_limit,
        fault_limit,
        require_disabled: false,
        closed_loop: false,
    })
}

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

#[test]
fn s_gantry_the_slave_copies_the_master_with_its_offset() {
    // S-GANTRY: SetGantryMaster(ax0, 0); SetGantrySlave(ax1, 0, 2000): the slave copies the
    // master (open loop: identical pulses, so the offset at engagement stays).
    let mut e = machine(3);
    ok(&mut e, move_abs_of(1, 7.0));
    run(&mut e, 0.1);
    ok(&mut e, gantry(0, &[1, 2], 0.0, 2000.0));
    let s = e.snapshot();
    assert_eq!(s.couplings.len(), 2);
    let c = s.couplings[0];
    assert_eq!((c.slave, c.master, c.kind), (1, 0, CouplingKind::Gantry));
    assert_eq!(c.phase, CouplingPhase::InSync);
    assert_eq!(c.gantry.unwrap().offset, 7.0);
    ok(&mut e, move_abs_of(0, 1000.0));
    let mut max_gap: f64 = 0.0;
    for _ in 0..1000 {
        e.step();
        // Zero lag: each tick the slave's command is the master's of the same tick.
        max_gap = max_gap.max((cmd(&e, 1) - cmd(&e, 0) - 7.0).abs());
        assert_eq!(cmd(&e, 2), cmd(&e, 0));
    }
    assert!(max_gap < 1e-9, "{max_gap}");
    assert_eq!(cmd(&e, 0), 1000.0);
    assert_eq!(cmd(&e, 1), 1007.0);
    let slave = e.axis_status(1).unwrap();
    assert!(slave
        .flags
        .contains(AxisFlags::COUPLED | AxisFlags::IN_SYNC));
    assert!(!slave.flags.contains(AxisFlags::GANTRY_WARNING));
}

#[test]
fn a_slave_refuses_its_own_motion_while_ganged_and_takes_it_after_disable() {
    let mut e = machine(2);
    ok(&mut e, gantry(0, &[1], 0.0, 0.0));
    let err = refused(&mut e, move_abs_of(1, 5.0));
    assert_eq!(err, EngineError::AxisCoupled { axis: 1, master: 0 });
    assert_eq!(
        refused(&mut e, gear_in_of(0, 1)),
        EngineError::AlreadyCoupled { axis: 1, master: 0 }
    );
    ok(&mut e, Command::from(GantryDisable { master: 0 }));
    assert!(e.snapshot().couplings.is_empty());
    ok(&mut e, move_abs_of(1, 5.0));
    run(&mut e, 0.1);
    assert_eq!(cmd(&e, 1), 5.0);
    assert_eq!(cmd(&e, 0), 0.0);
    assert_eq!(
        refused(&mut e, Command::from(GantryDisable { master: 0 })),
        EngineError::NotCoupled {
            axis: 0,
            what: "the master of a gantry"
        }
    );
}

/// A closed-loop servo axis whose position loop gain is `kp`: a lower gain lags more.
fn servo(kp: f64) -> AxisConfig {
    let mut a = stepper_mm();
    a.params.insert(ParamId::AxisType, 20.0);
    a.params.insert(ParamId::ServoLoop, 1.0);
    a.params.insert(ParamId::Kp, kp);
    a.params.insert(ParamId::FeLimit, 0.0);
    a.params.insert(ParamId::Speed, 100.0);
    a.params.insert(ParamId::Accel, 2000.0);
    a.params.insert(ParamId::Decel, 2000.0);
    a.plant.model = PlantModel::PositionLoop;
    a.plant.full_scale_velocity = 200.0;
    a
}

fn lagging_gantry() -> Engine {
    // The master's loop is stiff, the slave's soft: the slave lags behind while moving.
    let mut e = common::engine_with(vec![servo(3000.0), servo(300.0)]);
    for axis in 0..2 {
        ok(&mut e, Command::from(axes::command::Enable { axis }));
    }
    e
}

#[test]
fn a_lagging_slave_raises_the_warning_which_clears_when_it_catches_up() {
    let mut e = lagging_gantry();
    ok(&mut e, gantry(0, &[1], 0.3, 0.0));
    ok(&mut e, move_abs_of(0, 50.0));
    let mut worst: f64 = 0.0;
    let mut warned = false;
    for _ in 0..600 {
        e.step();
        let s = e.snapshot();
        let g = s.couplings[0].gantry.unwrap();
        worst = worst.max(g.deviation.abs());
        // The deviation is the slave's actual position less the master's (offset 0).
        assert!((g.deviation - (s.axes[1].act_pos - s.axes[0].act_pos)).abs() < 1e-9);
        assert_eq!(s.axes[1].gantry_deviation, g.deviation);
        assert_eq!(s.axes[0].gantry_deviation, g.deviation);
        if g.deviation.abs() > 0.3 {
            warned = true;
            assert!(s.axes[1].flags.contains(AxisFlags::GANTRY_WARNING));
            assert!(s.axes[0].flags.contains(AxisFlags::GANTRY_WARNING));
        }
    }
    assert!(warned, "the slave never lagged by 0.3: worst {worst}");
    run(&mut e, 3.0);
    let s = e.snapshot();
    let g = s.couplings[0].gantry.unwrap();
    assert!(
        g.deviation.abs() < 0.3,
        "{g:?} {:?} {:?}",
        s.axes[0],
        s.axes[1]
    );
    assert!(!s.axes[1].flags.contains(AxisFlags::GANTRY_WARNING));
    assert!(!s.axes[0].latched.contains(AxisFlags::GANTRY_FAULT));
}

#[test]
fn a_deviation_over_the_fault_limit_stops_master_and_slaves_together() {
    let mut e = machine(3);
    ok(&mut e, gantry(0, &[1, 2], 1.0, 2.0));
    ok(&mut e, move_abs_of(0, 5000.0));
    run(&mut e, 0.05);
    // Forced: slave 2's feedback reads 3 units behind.
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 2,
            amount: Some(3.0),
        }),
    );
    e.step();
    let s = e.snapshot();
    assert!(s.axes[0].latched.contains(AxisFlags::GANTRY_FAULT));
    assert_eq!(s.axes[0].state, AxisState::ErrorStop);
    // The slaves show the fault and follow the master's stop ramp.
    for slave in [1, 2] {
        assert!(s.axes[slave].flags.contains(AxisFlags::GANTRY_FAULT));
        assert!(s.axes[slave].flags.contains(AxisFlags::COUPLED));
    }
    assert!(s.couplings[1].gantry.unwrap().deviation.abs() > 2.0);
    run(&mut e, 1.0);
    let s = e.snapshot();
    assert!(s.axes.iter().all(|a| !a.flags.contains(AxisFlags::MOVING)));
    assert!(s.axes[0].cmd_pos < 5000.0);
    assert_eq!(s.axes[1].cmd_pos, s.axes[0].cmd_pos);
    assert_eq!(s.axes[2].cmd_pos, s.axes[0].cmd_pos);
    // Motion is refused until the cause is gone and the master is reset.
    assert_eq!(
        refused(&mut e, move_abs_of(0, 0.0)).kind(),
        ErrorKind::AxisInError
    );
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 2,
            amount: None,
        }),
    );
    run(&mut e, 0.01);
    ok(&mut e, Command::from(Reset { axis: 0 }));
    run(&mut e, 0.01);
    let s = e.snapshot();
    assert!(!s.axes[2].flags.contains(AxisFlags::GANTRY_FAULT));
    assert_eq!(s.axes[0].state, AxisState::Standstill);
    ok(&mut e, move_abs_of(0, 0.0));
    run(&mut e, 2.0);
    assert_eq!(cmd(&e, 2), 0.0);
}

#[test]
fn himc_pair_view_tv36() {
    // Digest 004 TV 36: RHS (the master) at 10, LHS (the slave) at 6 → Linear 8, Yaw 2.
    let mut e = machine(2);
    ok(&mut e, move_abs_of(0, 10.0));
    ok(&mut e, move_abs_of(1, 6.0));
    run(&mut e, 0.1);
    ok(&mut e, gantry(0, &[1], 0.0, 0.0));
    e.step();
    let g = e.snapshot().couplings[0].gantry.unwrap();
    assert_eq!((g.linear, g.yaw), (8.0, 2.0));
    assert_eq!(g.offset, -4.0);
}

#[test]
fn homing_the_master_moves_the_slave_along_and_redefines_it() {
    // Index pulses at 5, 15, … mm; the slave stands 3 mm from the master.
    let mut cfg = stepper_mm();
    cfg.encoder.index_offset = 5000;
    let mut e = common::engine_with(vec![cfg.clone(), cfg]);
    for axis in 0..2 {
        ok(&mut e, Command::from(axes::command::Enable { axis }));
    }
    ok(&mut e, move_abs_of(1, 3.0));
    run(&mut e, 1.0);
    ok(&mut e, gantry(0, &[1], 0.0, 0.0));
    let spec = HomingSpec {
        method: 7,
        switch_velocity: 40.0,
        zero_velocity: 4.0,
        acceleration: 800.0,
        offset: 12.5,
        timeout: 60.0,
        quirks: HomingQuirks::default(),
    };
    assert_eq!(
        refused(&mut e, home_of(1, &spec)),
        EngineError::AxisCoupled { axis: 1, master: 0 }
    );
    ok(&mut e, home_of(0, &spec));
    let mut moved = false;
    for _ in 0..30_000 {
        e.step();
        let m = e.axis(0).unwrap().motor_position();
        let s = e.axis(1).unwrap().motor_position();
        // The slave's motor stays 3 mm from the master's the whole way.
        assert!((s - m - 3.0).abs() < 1e-6, "{s} {m}");
        moved |= m > 10.0;
        if e.axis_status(0).unwrap().current_command.is_none() {
            break;
        }
    }
    assert!(moved);
    let s = e.snapshot();
    assert!(s.axes[0].flags.contains(AxisFlags::HOMED));
    // Redefined with the master: it still reads 3 mm from it, and is homed.
    assert!(s.axes[1].flags.contains(AxisFlags::HOMED));
    assert!((s.axes[1].cmd_pos - s.axes[0].cmd_pos - 3.0).abs() < 1e-6);
    assert!((s.axes[1].act_pos - s.axes[0].act_pos - 3.0).abs() < 1e-6);
    // set_position on the master moves no slave and shifts its frame the same.
    ok(
        &mut e,
        Command::from(SetPosition {
            axis: 0,
            position: 100.0,
            frame: Default::default(),
        }),
    );
    let m0 = e.axis(1).unwrap().motor_position();
    run(&mut e, 0.1);
    assert!((e.axis(1).unwrap().motor_position() - m0).abs() < 1e-9);
    assert!((cmd(&e, 1) - 103.0).abs() < 1e-6, "{}", cmd(&e, 1));
}

#[test]
fn bad_gantries_are_refused_and_disturb_nothing() {
    let mut e = machine(10);
    ok(&mut e, move_abs_of(0, 100.0));
    let cases: Vec<(Command, EngineError)> = vec![
        (
            gantry(1, &[1], 0.0, 0.0),
            EngineError::CoupledToItself { axis: 1 },
        ),
        (
            gantry(1, &[], 0.0, 0.0),
            EngineError::InvalidGantry {
                master: 1,
                reason: "give at least one slave",
            },
        ),
        (
            gantry(1, &[2, 3, 4, 5, 6, 7, 8, 9], 0.0, 0.0),
            EngineError::InvalidGantry {
                master: 1,
                reason: "at most 7 slaves (HMC_GantrySynchro)",
            },
        ),
        (
            gantry(1, &[2, 3, 2], 0.0, 0.0),
            EngineError::InvalidGantry {
                master: 1,
                reason: "a slave is listed twice",
            },
        ),
        (
            gantry(1, &[2], 3.0, 2.0),
            EngineError::InvalidGantry {
                master: 1,
                reason: "the warning limit must not exceed the fault limit",
            },
        ),
        (
            gantry(1, &[12], 0.0, 0.0),
            EngineError::InvalidAxis {
                axis: 12,
                count: 10,
            },
        ),
    ];
    for (c, want) in cases {
        assert_eq!(refused(&mut e, c), want);
    }
    for (w, f) in [(f64::NAN, 0.0), (0.0, f64::INFINITY), (-1.0, 0.0)] {
        assert_eq!(
            refused(&mut e, gantry(1, &[2], w, f)).kind(),
            ErrorKind::InvalidArgument
        );
    }
    // Already coupled, a second gantry on one master, a loop.
    ok(&mut e, gantry(1, &[2], 0.0, 0.0));
    assert_eq!(
        refused(&mut e, gantry(3, &[2], 0.0, 0.0)),
        EngineError::AlreadyCoupled { axis: 2, master: 1 }
    );
    assert_eq!(
        refused(&mut e, gantry(1, &[3], 0.0, 0.0)),
        EngineError::GantryExists { master: 1 }
    );
    assert_eq!(
        refused(&mut e, gantry(2, &[1], 0.0, 0.0)),
        EngineError::CouplingLoop {
            slave: 1,
            master: 2
        }
    );
    // All or none: slave 4 is fine but 2 is taken, so 4 stays free.
    assert!(
        refused(&mut e, gantry(5, &[4, 2], 0.0, 0.0))
            == EngineError::AlreadyCoupled { axis: 2, master: 1 }
    );
    assert!(!e.axis_status(4).unwrap().flags.contains(AxisFlags::COUPLED));
    // A grouped axis.
    let mut g = common::with_group(machine(3), &[1, 2]);
    assert_eq!(
        refused(&mut g, gantry(0, &[1], 0.0, 0.0)).kind(),
        ErrorKind::InvalidState
    );
    // Nothing else was disturbed: axis 0's move went on.
    run(&mut e, 1.0);
    assert_eq!(cmd(&e, 0), 100.0);
}

#[test]
fn a_disabled_slave_faults_an_enabled_master_but_not_a_disabled_one() {
    use axes::command::{Disable, DisableAll, Enable, EnableAll};
    let mut e = machine(2);
    ok(&mut e, gantry(0, &[1], 0.0, 0.0));
    ok(&mut e, Command::from(DisableAll {}));
    run(&mut e, 0.01);
    ok(&mut e, Command::from(EnableAll {}));
    run(&mut e, 0.01);
    let s = e.snapshot();
    assert!(!s.axes[0].latched.contains(AxisFlags::GANTRY_FAULT));
    ok(&mut e, move_abs_of(0, 10.0));
    run(&mut e, 0.5);
    assert_eq!(cmd(&e, 1), 10.0);
    // One side switched off: the other stops with a gantry fault.
    ok(&mut e, Command::from(Disable { axis: 1 }));
    e.step();
    let s = e.snapshot();
    assert!(s.axes[0].latched.contains(AxisFlags::GANTRY_FAULT));
    assert_eq!(s.axes[0].state, AxisState::ErrorStop);
    ok(&mut e, Command::from(Enable { axis: 1 }));
    run(&mut e, 0.01);
    ok(&mut e, Command::from(Reset { axis: 0 }));
    run(&mut e, 0.01);
    ok(&mut e, move_abs_of(0, 20.0));
    run(&mut e, 0.5);
    assert_eq!(cmd(&e, 1), 20.0);
}
