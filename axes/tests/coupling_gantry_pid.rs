//! HMC gantry closed loop and group redefinition (digest 000 §4.4 "Gantry"; manual §4.4.11.1
//! ucMode 1 "cross-coupling sync", §4.4.11.3 HMC_SetGantryAxisPID with defaults Kp 1, Ki 0,
//! Kd 0, §4.4.11.5 HMC_GantryGroupDefPos).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, EngineError, GantryEnable, GantrySetPid, GantrySetPosition, InjectFollowingError,
};
use axes::status::GantryStatus;
use axes::Engine;
use common::{move_abs_of, ok, refused, refused_code, run};

fn machine(n: usize) -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), n)
}

fn gantry(slaves: &[u16], closed_loop: bool) -> Command {
    Command::from(GantryEnable {
        master: 0,
        slaves: slaves.to_vec(),
        warning_limit: 0.0,
        fault_limit: 0.0,
        require_disabled: false,
        closed_loop,
    })
}

fn slave(e: &Engine, k: usize) -> GantryStatus {
    e.snapshot().couplings[k].gantry.unwrap()
}

/// The slave's actual position reads 3 behind its command from now on.
fn lag_slave(e: &mut Engine, axis: u16) {
    ok(
        e,
        Command::from(InjectFollowingError {
            axis,
            amount: Some(3.0),
        }),
    );
}

#[test]
fn open_loop_keeps_the_deviation_and_closed_loop_removes_it_at_rate_kp() {
    let mut open = machine(2);
    ok(&mut open, gantry(&[1], false));
    lag_slave(&mut open, 1);
    run(&mut open, 1.0);
    assert_eq!(
        slave(&open, 0).deviation,
        -3.0,
        "open loop: nothing corrects"
    );
    assert_eq!(slave(&open, 0).correction, 0.0);

    let mut closed = machine(2);
    ok(&mut closed, gantry(&[1], true));
    let g = slave(&closed, 0);
    assert_eq!((g.kp, g.ki, g.kd), (1.0, 0.0, 0.0), "HMC defaults");
    lag_slave(&mut closed, 1);
    // 1000 measurements of 1 ms: e_n = −3·(1 − kp·dt)^(n−1), the correction 3 + e_n.
    let ticks = 1000;
    for _ in 0..ticks {
        closed.step();
    }
    let expected = -3.0 * (1.0 - 1e-3f64).powi(ticks - 1);
    let g = slave(&closed, 0);
    assert!((g.deviation - expected).abs() < 1e-9, "{g:?} vs {expected}");
    let next = -3.0 * (1.0 - 1e-3f64).powi(ticks);
    assert!((g.correction - (3.0 + next)).abs() < 1e-9, "{g:?}");
    // This tick's command carried the correction before the last update: 3 + e_n.
    let s = closed.snapshot();
    let carried = s.axes[1].cmd_pos - s.axes[0].cmd_pos;
    assert!((carried - (3.0 + g.deviation)).abs() < 1e-9, "{carried}");
}

#[test]
fn a_larger_kp_squares_the_gantry_within_a_fraction_of_a_second_while_it_moves() {
    let mut e = machine(3);
    ok(&mut e, gantry(&[1, 2], true));
    ok(
        &mut e,
        Command::from(GantrySetPid {
            axis: 1,
            kp: 100.0,
            ki: 0.0,
            kd: 0.0,
        }),
    );
    lag_slave(&mut e, 1);
    ok(&mut e, move_abs_of(0, 500.0));
    run(&mut e, 0.2);
    let s = e.snapshot();
    let g1 = s.couplings[0].gantry.unwrap();
    assert_eq!(g1.kp, 100.0);
    // 0.9^199 of 3.
    assert!(g1.deviation.abs() < 1e-8, "{g1:?}");
    assert!((s.axes[1].act_pos - s.axes[0].act_pos).abs() < 1e-8);
    assert!((s.axes[1].cmd_pos - s.axes[0].cmd_pos - 3.0).abs() < 1e-8);
    // Slave 2 had nothing to correct and keeps its own gains.
    let g2 = s.couplings[1].gantry.unwrap();
    assert_eq!((g2.kp, g2.correction, g2.deviation), (1.0, 0.0, 0.0));
}

#[test]
fn the_integral_and_derivative_terms_follow_their_closed_forms() {
    // One tick with kp 0, ki 1000, kd 0.5 after the lag appears: integral −3·dt, derivative
    // (−3 − 0)/dt is not taken on the first measurement (no previous one).
    let mut e = machine(2);
    ok(&mut e, gantry(&[1], true));
    ok(
        &mut e,
        Command::from(GantrySetPid {
            axis: 1,
            kp: 0.0,
            ki: 1000.0,
            kd: 0.5,
        }),
    );
    lag_slave(&mut e, 1);
    e.step();
    // rate = −(1000 · (−3 · 0.001)) = 3/s, correction 3 · 0.001.
    let c1 = slave(&e, 0).correction;
    assert!((c1 - 0.003).abs() < 1e-12, "{c1}");
    e.step();
    // e2 = −3 + 0.003; integral = 0.001·(−3 + e2); derivative (e2 − (−3))/dt = 3.
    let e2 = -3.0 + 0.003;
    let integral = 0.001 * (-3.0 + e2);
    let rate = -(1000.0 * integral + 0.5 * (e2 + 3.0) / 0.001);
    let c2 = slave(&e, 0).correction;
    assert!((c2 - (0.003 + rate * 0.001)).abs() < 1e-12, "{c2}");
}

#[test]
fn gantry_set_position_redefines_every_axis_and_zeroes_the_offsets() {
    let mut e = machine(3);
    ok(&mut e, move_abs_of(1, 7.0));
    run(&mut e, 0.1);
    ok(&mut e, gantry(&[1, 2], false));
    ok(&mut e, move_abs_of(0, 100.0));
    run(&mut e, 1.0);
    let before = e.snapshot();
    assert_eq!(
        [before.axes[0].cmd_pos, before.axes[1].cmd_pos],
        [100.0, 107.0]
    );
    ok(
        &mut e,
        Command::from(GantrySetPosition {
            master: 0,
            position: -20.0,
        }),
    );
    let s = e.snapshot();
    for a in &s.axes {
        assert_eq!((a.cmd_pos, a.act_pos), (-20.0, -20.0));
    }
    assert_eq!(slave(&e, 0).offset, 0.0);
    // Nothing moved, and the gantry still follows its master with the new frames.
    e.step();
    assert_eq!(
        e.snapshot().axes[1].cmd_pos,
        -20.0,
        "no shift passed on twice"
    );
    ok(&mut e, move_abs_of(0, 30.0));
    run(&mut e, 1.0);
    let s = e.snapshot();
    assert_eq!(
        [s.axes[0].cmd_pos, s.axes[1].cmd_pos, s.axes[2].cmd_pos],
        [30.0, 30.0, 30.0]
    );
    assert_eq!(slave(&e, 0).deviation, 0.0);
    assert_eq!(
        s.axes[1].pulses - before.axes[1].pulses,
        s.axes[0].pulses - before.axes[0].pulses
    );
}

#[test]
fn bad_gantry_pid_and_set_position_are_refused_and_disturb_nothing() {
    let mut e = machine(3);
    ok(&mut e, gantry(&[1], true));
    let before = e.snapshot();
    let err = refused(
        &mut e,
        Command::from(GantrySetPosition {
            master: 1,
            position: 0.0,
        }),
    );
    assert!(
        matches!(err, EngineError::NotCoupled { axis: 1, .. }),
        "{err}"
    );
    let err = refused(
        &mut e,
        Command::from(GantrySetPid {
            axis: 2,
            kp: 1.0,
            ki: 0.0,
            kd: 0.0,
        }),
    );
    assert!(
        matches!(err, EngineError::NotCoupled { axis: 2, .. }),
        "{err}"
    );
    for (kp, ki, kd) in [
        (-1.0, 0.0, 0.0),
        (f64::NAN, 0.0, 0.0),
        (1.0, f64::INFINITY, 0.0),
    ] {
        let code = refused_code(
            &mut e,
            Command::from(GantrySetPid {
                axis: 1,
                kp,
                ki,
                kd,
            }),
        );
        assert_eq!(code, "invalid_argument");
    }
    let code = refused_code(
        &mut e,
        Command::from(GantrySetPosition {
            master: 0,
            position: f64::NAN,
        }),
    );
    assert_eq!(code, "invalid_argument");
    assert_eq!(e.snapshot(), before);
}

#[test]
fn closed_loop_gantries_are_deterministic() {
    let once = || {
        let mut e = machine(2);
        ok(&mut e, gantry(&[1], true));
        ok(
            &mut e,
            Command::from(GantrySetPid {
                axis: 1,
                kp: 40.0,
                ki: 300.0,
                kd: 0.01,
            }),
        );
        lag_slave(&mut e, 1);
        ok(&mut e, move_abs_of(0, 50.0));
        (0..1500)
            .map(|_| {
                e.step();
                let g = slave(&e, 0);
                (g.correction.to_bits(), g.deviation.to_bits())
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(once(), once());
}
