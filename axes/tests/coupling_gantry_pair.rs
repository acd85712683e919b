//! HIMC gantry pair at the engine level (issue 12 item 6; digest 004 §2.6, §6.3 TV 38–39):
//! `EnableGantryPair` needs both axes disabled, and enabling the RHS (the master) then enables
//! both; disabling it disables both.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, Disable, Enable, EngineError, GantryEnable};
use axes::status::CouplingKind;
use axes::{AxisFlags, Engine};
use common::{move_abs_of, ok, refused, run};

fn pair(require_disabled: bool) -> Command {
    Command::from(GantryEnable {
        master: 0,
        slaves: vec![1],
        warning_limit: 0.0,
        fault_limit: 1.0,
        require_disabled,
        closed_loop: false,
    })
}

fn disabled_machine() -> Engine {
    common::engine_with(vec![common::virtual_pulse_axis(); 3])
}

fn enabled(e: &Engine, axis: usize) -> bool {
    e.axis_status(axis)
        .unwrap()
        .flags
        .contains(AxisFlags::ENABLED)
}

#[test]
fn tv38_a_pair_of_enabled_axes_is_refused_and_nothing_changes() {
    let mut e = common::enabled_machine(common::virtual_pulse_axis(), 2);
    let err = refused(&mut e, pair(true));
    assert!(
        matches!(err, EngineError::InvalidGantry { master: 0, .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("disabled"), "{err}");
    assert!(e.snapshot().couplings.is_empty());
    // One side enabled is refused too.
    let mut e = disabled_machine();
    ok(&mut e, Command::from(Enable { axis: 1 }));
    assert!(matches!(
        refused(&mut e, pair(true)),
        EngineError::InvalidGantry { master: 0, .. }
    ));
    assert!(e.snapshot().couplings.is_empty());
}

#[test]
fn tv39_enabling_the_rhs_enables_both_and_the_pair_moves_together() {
    let mut e = disabled_machine();
    ok(&mut e, pair(true));
    // At rest, both off: no gantry fault although the slave takes no setpoint.
    run(&mut e, 0.05);
    let s = e.snapshot();
    assert!(!s.axes[0].latched.contains(AxisFlags::GANTRY_FAULT));
    let c = s.couplings[0];
    assert_eq!((c.slave, c.master, c.kind), (1, 0, CouplingKind::Gantry));
    ok(&mut e, Command::from(Enable { axis: 0 }));
    // IsEnabled(0) = IsEnabled(1) = 1; IsGantry on both (the slave's coupling names the master).
    assert!(enabled(&e, 0) && enabled(&e, 1));
    assert!(!enabled(&e, 2));
    run(&mut e, 0.01);
    ok(&mut e, move_abs_of(0, 25.0));
    run(&mut e, 1.0);
    let s = e.snapshot();
    assert_eq!(s.axes[0].cmd_pos, 25.0);
    assert_eq!(s.axes[1].cmd_pos, 25.0);
    assert!(!s.axes[0].latched.contains(AxisFlags::GANTRY_FAULT));
    assert_eq!(s.couplings[0].kind, CouplingKind::Gantry);
    // Disabling the RHS switches both off, and the pair stays made.
    ok(&mut e, Command::from(Disable { axis: 0 }));
    assert!(!enabled(&e, 0) && !enabled(&e, 1));
    run(&mut e, 0.05);
    let s = e.snapshot();
    assert!(!s.axes[0].latched.contains(AxisFlags::GANTRY_FAULT));
    assert_eq!(s.couplings.len(), 1);
}

#[test]
fn a_pair_made_at_rest_still_refuses_bad_axes() {
    let mut e = disabled_machine();
    ok(&mut e, pair(true));
    // Axis 1 is already ganged; axis 0 cannot follow its own slave.
    let again = Command::from(GantryEnable {
        master: 2,
        slaves: vec![1],
        warning_limit: 0.0,
        fault_limit: 0.0,
        require_disabled: true,
        closed_loop: false,
    });
    assert_eq!(
        refused(&mut e, again),
        EngineError::AlreadyCoupled { axis: 1, master: 0 }
    );
    let own = Command::from(GantryEnable {
        master: 2,
        slaves: vec![2],
        warning_limit: 0.0,
        fault_limit: 0.0,
        require_disabled: true,
        closed_loop: false,
    });
    assert_eq!(
        refused(&mut e, own),
        EngineError::CoupledToItself { axis: 2 }
    );
    assert_eq!(e.snapshot().couplings.len(), 1);
}
