//! HMC add axis at the engine level (digest 000 §4.4 HMC_SetAddAxis / HMC_GetAddAxis): the base
//! axis's displacement is its own command's plus the add axis's, DPos shows the sum, VpSpeed
//! only the own command's speed; 255 (no `add`) ends it where the base stands; a loop is
//! refused (mcemu's choice: HMC does not detect it).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{AddAxisSet, Command, EngineError, SetPosition};
use axes::param::parameter_value;
use axes::{Engine, ParamId};
use common::{gear_in_of, jog_of, move_abs_of, move_rel_of, ok, refused, run};

fn machine(n: usize) -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), n)
}

fn add(base: u16, add: Option<u16>) -> Command {
    Command::from(AddAxisSet { base, add })
}

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

#[test]
fn the_base_moves_by_its_own_command_plus_the_add_axis() {
    let mut e = machine(2);
    ok(&mut e, add(0, Some(1)));
    assert_eq!(e.axis_status(0).unwrap().add_axis, Some(1));
    ok(&mut e, move_rel_of(0, 300.0));
    ok(&mut e, move_rel_of(1, 200.0));
    let mut seen_own_speed = false;
    let mut cruised = false;
    for _ in 0..2000 {
        e.step();
        let (base, other) = (e.axis_status(0).unwrap(), e.axis_status(1).unwrap());
        // VpSpeed is the own command's speed; MpSpeed (the actual) the combined one. Compared
        // while both cruise (a tick's mean velocity is then its end velocity).
        let cruising = base.cmd_vel != 0.0
            && base.cmd_acc == 0.0
            && other.cmd_vel != 0.0
            && other.cmd_acc == 0.0;
        if cruising && cruised {
            seen_own_speed = true;
            let params = e.axis(0).unwrap().params();
            let vp = parameter_value(ParamId::CommandedSpeed, &base, params);
            let mp = parameter_value(ParamId::ActualVelocity, &base, params);
            assert_eq!(vp, base.cmd_vel.abs());
            assert!(
                (mp - (base.cmd_vel + other.cmd_vel)).abs() < 1e-6,
                "{mp} vs {} + {}",
                base.cmd_vel,
                other.cmd_vel
            );
        }
        cruised = cruising;
    }
    assert!(seen_own_speed);
    // DPos and MPos show the real position: 300 of its own and 200 of the add axis.
    let base = e.axis_status(0).unwrap();
    assert_eq!((base.cmd_pos, base.act_pos), (500.0, 500.0));
    assert_eq!(base.remaining, 0.0);
    assert_eq!(cmd(&e, 1), 200.0);
}

#[test]
fn an_absolute_move_ends_on_its_target_when_the_add_axis_stands() {
    let mut e = machine(2);
    ok(&mut e, add(0, Some(1)));
    ok(&mut e, move_rel_of(1, 50.0));
    run(&mut e, 1.0);
    assert_eq!(cmd(&e, 0), 50.0);
    // The own move's distance is from where the base stands (DPos): 100 − 50.
    ok(&mut e, move_abs_of(0, 100.0));
    run(&mut e, 1.0);
    assert_eq!(cmd(&e, 0), 100.0);
}

#[test]
fn the_add_axis_travel_has_no_lag_while_the_base_jogs() {
    let mut e = machine(2);
    ok(&mut e, add(0, Some(1)));
    ok(&mut e, jog_of(0, 100.0));
    run(&mut e, 0.5);
    let (b0, a0) = (cmd(&e, 0), cmd(&e, 1));
    ok(&mut e, move_rel_of(1, -40.0));
    let mut own = 0.0;
    for _ in 0..500 {
        e.step();
        own += e.axis_status(0).unwrap().cmd_vel * 1e-3;
        // The base's travel is its own plus the add axis's of the same tick.
        let want = b0 + own + (cmd(&e, 1) - a0);
        assert!((cmd(&e, 0) - want).abs() < 1e-6, "{} vs {want}", cmd(&e, 0));
    }
    assert_eq!(cmd(&e, 1), a0 - 40.0);
}

#[test]
fn cancelling_keeps_the_base_where_it_stands() {
    let mut e = machine(2);
    ok(&mut e, add(0, Some(1)));
    ok(&mut e, move_rel_of(1, 70.0));
    run(&mut e, 1.0);
    ok(&mut e, add(0, None));
    assert_eq!(e.axis_status(0).unwrap().add_axis, None);
    run(&mut e, 0.1);
    assert_eq!(cmd(&e, 0), 70.0);
    ok(&mut e, move_rel_of(1, 30.0));
    run(&mut e, 1.0);
    assert_eq!(cmd(&e, 0), 70.0, "no longer added");
    assert_eq!(cmd(&e, 1), 100.0);
    // Cancelling without an add axis is accepted (HMC returns 0).
    ok(&mut e, add(0, None));
}

#[test]
fn redefining_the_add_axis_position_does_not_move_the_base() {
    let mut e = machine(2);
    ok(&mut e, add(0, Some(1)));
    ok(
        &mut e,
        Command::from(SetPosition {
            axis: 1,
            position: 1000.0,
            frame: Default::default(),
        }),
    );
    run(&mut e, 0.1);
    assert_eq!(cmd(&e, 0), 0.0);
}

#[test]
fn a_chain_of_add_axes_adds_up_in_one_tick() {
    // 0 ← 1 ← 2: axis 0 gets 2's travel through 1, in the same tick.
    let mut e = machine(3);
    ok(&mut e, add(0, Some(1)));
    ok(&mut e, add(1, Some(2)));
    ok(&mut e, move_rel_of(2, 25.0));
    for _ in 0..300 {
        e.step();
        assert_eq!(cmd(&e, 0), cmd(&e, 2));
        assert_eq!(cmd(&e, 1), cmd(&e, 2));
    }
    assert_eq!(cmd(&e, 0), 25.0);
}

#[test]
fn loops_and_bad_axes_are_refused_and_nothing_changes() {
    let mut e = machine(4);
    ok(&mut e, add(0, Some(1)));
    ok(&mut e, add(1, Some(2)));
    let loop_back = refused(&mut e, add(2, Some(0)));
    assert!(
        matches!(
            loop_back,
            EngineError::CouplingLoop {
                slave: 2,
                master: 0
            }
        ),
        "{loop_back:?}"
    );
    assert!(matches!(
        refused(&mut e, add(3, Some(3))),
        EngineError::CoupledToItself { axis: 3 }
    ));
    assert!(matches!(
        refused(&mut e, add(0, Some(9))),
        EngineError::InvalidAxis { axis: 9, .. }
    ));
    assert!(matches!(
        refused(&mut e, add(9, None)),
        EngineError::InvalidAxis { axis: 9, .. }
    ));
    // A loop through a gear: 3 follows 0, so 0 may not add 3's travel.
    ok(&mut e, gear_in_of(0, 3));
    assert!(matches!(
        refused(&mut e, add(0, Some(3))),
        EngineError::CouplingLoop { .. }
    ));
    // Nor may a gear make 1 follow 0 (0 adds 1's travel).
    assert!(matches!(
        refused(&mut e, gear_in_of(0, 1)),
        EngineError::CouplingLoop { .. }
    ));
    // The refused replacement left the old link in place.
    assert_eq!(e.axis_status(0).unwrap().add_axis, Some(1));
    ok(&mut e, move_rel_of(2, 10.0));
    run(&mut e, 1.0);
    assert_eq!(cmd(&e, 0), 10.0);
}
