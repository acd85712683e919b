//! HMC axis position compensation (manual §4.4.12, digest 000 §4.4 "Axis position
//! compensation"): an offset after the planner moved by its own profile on
//! HMC_TrigAxisCompens, abandoned and restarted by a new trigger, stopped at once by
//! HMC_StopAxisCompens, its state HMC_GetAxisCompenState (0 done, 1 in progress).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, CompensationOffsetAmount, CompensationOffsetProfile, CompensationOffsetStop,
    CompensationOffsetTrigger, Enable,
};
use axes::{AxisStatus, Engine, ParamId};
use common::{engine_with, free_linear_axis, ok, refused_code};

fn machine() -> Engine {
    let axis = free_linear_axis(
        1.0,
        &[
            (ParamId::Speed, 1000.0),
            (ParamId::Accel, 1e5),
            (ParamId::Decel, 1e5),
        ],
    );
    let mut e = engine_with(vec![axis]);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    e
}

fn profile(s_curve: bool, velocity: f64) -> Command {
    Command::from(CompensationOffsetProfile {
        axis: 0,
        s_curve,
        velocity,
        acceleration: 100.0,
        deceleration: 100.0,
        jerk: if s_curve { 2000.0 } else { 0.0 },
    })
}

fn amount(amount: f64) -> Command {
    Command::from(CompensationOffsetAmount { axis: 0, amount })
}

fn trigger() -> Command {
    Command::from(CompensationOffsetTrigger { axis: 0 })
}

/// Step until the offset's move is done (at most 10 s); every tick's status.
fn until_done(e: &mut Engine) -> Vec<AxisStatus> {
    let mut seen = Vec::new();
    for _ in 0..10_000 {
        e.step();
        let s = e.axis_status(0).unwrap();
        let done = !s.compensation_offset_moving;
        seen.push(s);
        if done {
            return seen;
        }
    }
    panic!("the offset never arrived")
}

#[test]
fn a_trigger_moves_the_output_by_the_amount_on_a_trapezoid_and_the_plan_does_not_show_it() {
    let mut e = machine();
    ok(&mut e, profile(false, 10.0));
    ok(&mut e, amount(5.0));
    assert!(
        !e.axis_status(0).unwrap().compensation_offset_moving,
        "state 0"
    );
    ok(&mut e, trigger());
    let seen = until_done(&mut e);
    // 0.1 s accelerating (0.5), 0.4 s at 10 (4), 0.1 s braking (0.5): 600 ticks of 1 ms.
    assert_eq!(seen.len(), 600);
    assert!(
        seen[..599].iter().all(|s| s.compensation_offset_moving),
        "state 1"
    );
    let last = seen.last().unwrap();
    assert_eq!(last.compensation_offset, 5.0);
    assert_eq!(
        (last.cmd_pos, last.act_pos),
        (0.0, 0.0),
        "DPos and the load keep"
    );
    assert_eq!(last.output_pos, 5.0);
    assert_eq!(last.compensation, 5.0);
    let mut before = 0.0;
    for s in &seen {
        let step = s.compensation_offset - before;
        assert!(
            (0.0..=0.010 + 1e-12).contains(&step),
            "≤ 10 units/s: {step}"
        );
        assert_eq!(s.output_pos, s.compensation_offset);
        before = s.compensation_offset;
    }
    // A second trigger adds the amount again.
    ok(&mut e, trigger());
    until_done(&mut e);
    assert_eq!(e.axis_status(0).unwrap().compensation_offset, 10.0);
}

#[test]
fn a_trigger_during_a_move_abandons_the_rest_and_moves_by_the_amount_from_there() {
    let mut e = machine();
    ok(&mut e, profile(false, 10.0));
    ok(&mut e, amount(5.0));
    ok(&mut e, trigger());
    for _ in 0..300 {
        e.step();
    }
    let halfway = e.axis_status(0).unwrap().compensation_offset;
    assert!((2.0..3.0).contains(&halfway), "{halfway}");
    // The new amount applies to the next trigger only.
    ok(&mut e, amount(-1.0));
    ok(&mut e, trigger());
    let seen = until_done(&mut e);
    let last = seen.last().unwrap();
    assert_eq!(last.compensation_offset, halfway - 1.0);
    // It started moving at +10 and braked through: never past 10 units/s either way.
    let mut before = halfway;
    for s in &seen {
        assert!((s.compensation_offset - before).abs() <= 0.010 + 1e-12);
        before = s.compensation_offset;
    }
}

#[test]
fn stop_holds_the_offset_where_it_stands_and_reports_done() {
    let mut e = machine();
    ok(&mut e, profile(false, 10.0));
    ok(&mut e, amount(5.0));
    ok(&mut e, trigger());
    for _ in 0..200 {
        e.step();
    }
    ok(&mut e, Command::from(CompensationOffsetStop { axis: 0 }));
    let at = e.axis_status(0).unwrap().compensation_offset;
    for _ in 0..100 {
        e.step();
    }
    let s = e.axis_status(0).unwrap();
    assert_eq!(
        (s.compensation_offset, s.compensation_offset_moving),
        (at, false)
    );
    assert_eq!(s.output_pos, at);
}

#[test]
fn a_new_profile_takes_effect_on_the_move_in_progress_and_s_curves_take_longer() {
    let trapezoid = {
        let mut e = machine();
        ok(&mut e, profile(false, 10.0));
        ok(&mut e, amount(5.0));
        ok(&mut e, trigger());
        until_done(&mut e).len()
    };
    let s_curve = {
        let mut e = machine();
        ok(&mut e, profile(true, 10.0));
        ok(&mut e, amount(5.0));
        ok(&mut e, trigger());
        let seen = until_done(&mut e);
        assert_eq!(seen.last().unwrap().compensation_offset, 5.0);
        seen.len()
    };
    assert!(s_curve > trapezoid, "{s_curve} vs {trapezoid}");
    // Halfway, a slower profile: it still arrives, later, never faster than the new limit
    // once braked down to it.
    let mut e = machine();
    ok(&mut e, profile(false, 10.0));
    ok(&mut e, amount(5.0));
    ok(&mut e, trigger());
    for _ in 0..200 {
        e.step();
    }
    ok(&mut e, profile(false, 2.0));
    let seen = until_done(&mut e);
    assert_eq!(seen.last().unwrap().compensation_offset, 5.0);
    assert!(200 + seen.len() > trapezoid + 500, "{}", seen.len());
}

#[test]
fn bad_offset_commands_are_refused_and_change_nothing() {
    let mut e = machine();
    assert_eq!(
        refused_code(&mut e, trigger()),
        "invalid_compensation",
        "no profile"
    );
    ok(&mut e, profile(false, 10.0));
    let before = e.snapshot();
    for c in [
        amount(f64::NAN),
        amount(1e300),
        profile(false, 0.0),
        profile(false, -1.0),
        profile(false, f64::INFINITY),
        Command::from(CompensationOffsetProfile {
            axis: 0,
            s_curve: true,
            velocity: 1.0,
            acceleration: 1.0,
            deceleration: 1.0,
            jerk: 0.0,
        }),
    ] {
        assert_eq!(
            refused_code(&mut e, c.clone()),
            "invalid_compensation",
            "{c:?}"
        );
    }
    assert_eq!(
        refused_code(&mut e, Command::from(CompensationOffsetTrigger { axis: 3 })),
        "invalid_axis"
    );
    assert_eq!(e.snapshot(), before);
}
