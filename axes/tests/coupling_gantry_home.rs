//! HMC_GantryInit (manual §4.4.11.2, digest 000 §4.4 "Gantry"): `gantry_home` homes the
//! gantry's axes one after the other, the others following, returns, redefines them all at
//! once and moves each onto its own reference switch; HMC_GetGantryInitState's states.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, EngineError, GantryHome};
use axes::config::HomeSwitchConfig;
use axes::homing::vendor::HmcInstruction;
use axes::param::ParamId;
use axes::status::{GantryHomePhase, GantryHomeStatus};
use axes::Engine;
use common::{ok, refused};

/// Two stepper axes in mm, standing at 0, whose home switches (active from `switch` up)
/// are 3 mm apart: the gantry is skewed by 3 mm.
fn machine(switches: [f64; 2]) -> Engine {
    let axes = switches
        .iter()
        .map(|&low| {
            let mut a = common::stepper_mm();
            a.params.insert(ParamId::CreepSpeed, 5.0);
            a.switches.home = Some(HomeSwitchConfig {
                low,
                high: f64::INFINITY,
                filter: 0,
                active_low: false,
            });
            a
        })
        .collect();
    let mut e = common::engine_with(axes);
    for axis in 0..2 {
        ok(&mut e, Command::from(axes::command::Enable { axis }));
    }
    e
}

fn gantry_home(position_error: f64) -> GantryHome {
    GantryHome {
        axes: vec![0, 1],
        // HMC_HomeEx: the falling edge is latched exactly.
        instruction: HmcInstruction::HomeEx,
        home_mode: 0,
        reference_position: -1000.0,
        position_error,
    }
}

fn run(e: &mut Engine) -> (GantryHomeStatus, Vec<GantryHomePhase>) {
    let mut seen = vec![e.snapshot().gantry_homes[0].phase];
    for _ in 0..(60.0 / e.period()) as usize {
        e.step();
        let s = e.snapshot().gantry_homes[0].clone();
        if seen.last() != Some(&s.phase) {
            seen.push(s.phase);
        }
        if matches!(s.phase, GantryHomePhase::Finish | GantryHomePhase::Failed) {
            return (s, seen);
        }
        // While one axis homes, the other follows it exactly (commanded, motor frames).
        if s.phase == GantryHomePhase::Homing {
            let gap = e.axis(1).unwrap().motor_position() - e.axis(0).unwrap().motor_position();
            assert!(gap.abs() < 1e-6, "the follower lags by {gap}");
        }
    }
    panic!("gantry_home did not end: {:?}", e.snapshot().gantry_homes);
}

#[test]
fn the_gantry_homes_axis_by_axis_and_ends_aligned_on_its_switches() {
    let mut e = machine([100.0, 103.0]);
    ok(&mut e, Command::from(gantry_home(10.0)));
    let s = &e.snapshot().gantry_homes[0];
    assert_eq!(s.phase, GantryHomePhase::Homing);
    assert_eq!(s.homing_axis, Some(0));
    let (s, seen) = run(&mut e);
    assert_eq!(s.error, None);
    assert_eq!(
        seen,
        [
            GantryHomePhase::Homing,
            GantryHomePhase::ReturnBack,
            GantryHomePhase::DefPos,
            GantryHomePhase::Compensate,
            GantryHomePhase::Finish
        ]
    );
    assert_eq!(
        seen.iter().map(|p| p.hmc_state()).collect::<Vec<_>>(),
        [1, 2, 3, 4, 5]
    );
    // The skew: the first axis stood 3 mm further when the second found its switch.
    assert_eq!(s.deviations.len(), 2);
    assert_eq!(s.deviations[0], 0.0);
    assert!((s.deviations[1] - 3.0).abs() < 1e-6, "{:?}", s.deviations);
    // Each axis on its own switch, both reading the reference position.
    for (axis, switch) in [(0, 100.0), (1, 103.0)] {
        let st = e.axis_status(axis).unwrap();
        assert!(
            (st.cmd_pos + 1000.0).abs() < 1e-6,
            "axis {axis}: {}",
            st.cmd_pos
        );
        let m = e.axis(axis).unwrap().motor_position();
        assert!((m - switch).abs() < 1e-6, "axis {axis} at {m}");
    }
    // Nothing is left coupled: the gantry is made afterwards with gantry_enable.
    assert!(e.snapshot().couplings.is_empty());
}

#[test]
fn a_deviation_over_the_limit_ends_it_after_the_redefinition() {
    let mut e = machine([100.0, 103.0]);
    ok(&mut e, Command::from(gantry_home(2.0)));
    let (s, seen) = run(&mut e);
    assert_eq!(s.phase, GantryHomePhase::Failed);
    assert_eq!(s.phase.hmc_state(), u32::MAX);
    assert!(
        s.error.as_deref().unwrap().contains("over the limit"),
        "{s:?}"
    );
    assert!(!seen.contains(&GantryHomePhase::Compensate));
    // Redefined together (step 2), not compensated: the second reads the skew.
    let p0 = e.axis_status(0).unwrap().cmd_pos;
    let p1 = e.axis_status(1).unwrap().cmd_pos;
    assert!(
        (p0 + 1000.0).abs() < 1e-6 && (p1 + 1003.0).abs() < 1e-6,
        "{p0} {p1}"
    );
    assert!(e.snapshot().couplings.is_empty());
}

#[test]
fn a_stop_during_the_homing_fails_it_and_frees_the_axes() {
    let mut e = machine([100.0, 103.0]);
    ok(&mut e, Command::from(gantry_home(0.0)));
    for _ in 0..100 {
        e.step();
    }
    ok(
        &mut e,
        Command::from(axes::command::Stop {
            axis: 0,
            mode: Default::default(),
            deceleration: None,
        }),
    );
    let (s, _) = run(&mut e);
    assert_eq!(s.phase, GantryHomePhase::Failed);
    assert!(e.snapshot().couplings.is_empty());
}

#[test]
fn bad_gantry_homes_are_refused_and_leave_nothing_behind() {
    let mut e = machine([100.0, 103.0]);
    for (c, name) in [
        (
            GantryHome {
                axes: vec![0],
                ..gantry_home(0.0)
            },
            "gantry_home",
        ),
        (
            GantryHome {
                axes: vec![0, 0],
                ..gantry_home(0.0)
            },
            "gantry_home",
        ),
        (
            GantryHome {
                home_mode: 6,
                ..gantry_home(0.0)
            },
            "home_mode",
        ),
        (gantry_home(-1.0), "position_error"),
        (gantry_home(f64::NAN), "position_error"),
        (
            GantryHome {
                reference_position: f64::INFINITY,
                ..gantry_home(0.0)
            },
            "reference_position",
        ),
    ] {
        let err = refused(&mut e, Command::from(c));
        assert!(
            matches!(err, EngineError::InvalidArgument { name: n, .. } if n == name),
            "{err:?}"
        );
    }
    let err = refused(
        &mut e,
        Command::from(GantryHome {
            axes: vec![0, 7],
            ..gantry_home(0.0)
        }),
    );
    assert!(matches!(err, EngineError::InvalidAxis { .. }), "{err:?}");
    // A disabled axis refuses its gantry: nothing is left coupled or running.
    ok(&mut e, Command::from(axes::command::Disable { axis: 1 }));
    refused(&mut e, Command::from(gantry_home(0.0)));
    let snap = e.snapshot();
    assert!(snap.gantry_homes.is_empty() && snap.couplings.is_empty());
    assert_eq!(e.axis_status(0).unwrap().current_command, None);
}
