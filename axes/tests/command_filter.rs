//! Command filters after the planner (issue 14; digest 004 §2.14, HIMC chapter 15): an input
//! shaper or VSF on the commanded position. The move is done only once the filtered output has
//! arrived, exactly at the target; filters change only at rest; bad parameters are typed errors.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, CommandState, Enable};
use axes::filter::{FilterSlot, FilterStatus, ShaperType};
use axes::status::AxisFlags;
use axes::{Engine, ParamId};
use common::{cmd, engine_with, free_linear_axis, id_of, ok, refused_code, state_of, status};

fn machine() -> Engine {
    let axis = free_linear_axis(
        1.0,
        &[
            (ParamId::Speed, 1000.0),
            (ParamId::Accel, 10_000.0),
            (ParamId::Decel, 10_000.0),
        ],
    );
    let mut e = engine_with(vec![axis]);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    e
}

/// Ticks until the move to 100 is done, and the commanded position each tick; the axis is
/// moving and not in position on every tick before.
fn move_until_done(e: &mut Engine) -> (u64, Vec<f64>) {
    let id = id_of(ok(
        e,
        cmd(r#"{"type":"move_absolute","axis":0,"position":100}"#),
    ));
    let mut seen = Vec::new();
    for k in 1..=5000 {
        e.step();
        seen.push(status(e).cmd_pos);
        if state_of(e, id) == CommandState::Done {
            return (k, seen);
        }
        // Until the filtered output arrives the axis moves and is not in position (HIMC
        // IsMoving / IsInPos).
        let flags = status(e).flags;
        assert!(!flags.contains(AxisFlags::IN_POSITION), "tick {k}");
        assert!(flags.contains(AxisFlags::MOVING) || k == 1, "tick {k}");
    }
    panic!("the move never finished");
}

#[test]
fn shaped_move_is_done_when_the_filtered_output_arrives() {
    let (plain_ticks, plain) = move_until_done(&mut machine());
    let mut e = machine();
    // ζ = 0, 10 Hz: the ZV shaper's second impulse comes 50 ms (50 ticks at 1 ms) later.
    ok(
        &mut e,
        cmd(r#"{"type":"filter_input_shaping","axis":0,"shaper":"zv","frequency":10,"damping":0}"#),
    );
    let (ticks, shaped) = move_until_done(&mut e);
    let delay = (0.05 / e.period()).round() as u64;
    assert_eq!(ticks, plain_ticks + delay, "done one shaper length later");
    assert_eq!(*shaped.last().unwrap(), 100.0, "ends exactly at the target");
    // Before the second impulse the output is half the plan; after it, the mean of the plan
    // now and 50 ms ago.
    let d = delay as usize;
    for (k, p) in shaped.iter().enumerate().take(plain.len()) {
        let late = if k >= d { plain[k - d] } else { 0.0 };
        let expected = 0.5 * plain[k] + 0.5 * late;
        assert!((p - expected).abs() < 1e-9, "tick {k}: {p} vs {expected}");
    }
    match status(&e).command_filter {
        Some(FilterStatus::InputShaping {
            shaper: ShaperType::Zv,
            slot: FilterSlot::Axis,
            delay,
            ..
        }) => assert!((delay - 0.05).abs() < 1e-12),
        other => panic!("status shows {other:?}"),
    }
    let snapshot = serde_json::to_value(e.snapshot()).unwrap();
    let text = snapshot.to_string();
    assert!(text.contains(r#""kind":"input_shaping""#), "{text}");
}

#[test]
fn vsf_move_ends_exactly_at_the_target() {
    let mut e = machine();
    ok(
        &mut e,
        cmd(r#"{"type":"filter_vsf","axis":0,"frequency":40,"damping":1.0}"#),
    );
    let (_, seen) = move_until_done(&mut e);
    assert_eq!(*seen.last().unwrap(), 100.0);
    assert!(matches!(
        status(&e).command_filter,
        Some(FilterStatus::Vsf { .. })
    ));
}

#[test]
fn filters_change_only_at_rest() {
    let mut e = machine();
    ok(
        &mut e,
        cmd(r#"{"type":"move_absolute","axis":0,"position":100}"#),
    );
    e.step();
    let c = refused_code(
        &mut e,
        cmd(r#"{"type":"filter_vsf","axis":0,"frequency":40}"#),
    );
    assert_eq!(c, "invalid_state");
    let c = refused_code(&mut e, cmd(r#"{"type":"filter_disable","axis":0}"#));
    assert_eq!(c, "invalid_state");
}

#[test]
fn bad_parameters_are_typed_errors() {
    let mut e = machine();
    for json in [
        r#"{"type":"filter_input_shaping","axis":0,"frequency":0}"#,
        r#"{"type":"filter_input_shaping","axis":0,"frequency":-3}"#,
        r#"{"type":"filter_input_shaping","axis":0,"frequency":5,"damping":1}"#,
        r#"{"type":"filter_input_shaping","axis":0,"frequency":5,"damping":-0.1}"#,
        r#"{"type":"filter_vsf","axis":0,"frequency":5,"damping":0}"#,
        r#"{"type":"filter_vsf","axis":0,"frequency":900}"#,
    ] {
        assert_eq!(
            refused_code(&mut e, cmd(json)),
            "invalid_argument",
            "{json}"
        );
    }
    let unknown = serde_json::from_str::<Command>(
        r#"{"type":"filter_input_shaping","axis":0,"shaper":"zvdd","frequency":5}"#,
    );
    assert!(unknown.is_err());
    assert_eq!(status(&e).command_filter, None);
}

#[test]
fn disable_removes_the_filter() {
    let mut e = machine();
    ok(
        &mut e,
        cmd(r#"{"type":"filter_input_shaping","axis":0,"frequency":10}"#),
    );
    ok(
        &mut e,
        cmd(r#"{"type":"filter_disable","axis":0,"slot":"axis"}"#),
    );
    assert_eq!(status(&e).command_filter, None);
    let (ticks, _) = move_until_done(&mut e);
    let (plain_ticks, _) = move_until_done(&mut machine());
    assert_eq!(ticks, plain_ticks);
}

#[test]
fn shaped_moves_are_bit_identical() {
    let run = || {
        let mut e = machine();
        ok(
            &mut e,
            cmd(
                r#"{"type":"filter_input_shaping","axis":0,"shaper":"ei","frequency":13.7,"damping":0.2}"#,
            ),
        );
        let (_, seen) = move_until_done(&mut e);
        seen.iter().map(|p| p.to_bits()).collect::<Vec<_>>()
    };
    assert_eq!(run(), run());
}

/// Axis 0's commanded position each tick of a group line to (50, 0), with `filter` on it first.
fn group_run(filter: Option<&str>) -> Vec<f64> {
    let axis = common::fast_mm_axis(100.0, 1000.0);
    let mut e = common::with_group(engine_with(vec![axis.clone(), axis]), &[0, 1]);
    if let Some(f) = filter {
        ok(&mut e, cmd(f));
    }
    ok(&mut e, Command::from(common::group_line(1, &[50.0, 0.0])));
    (0..2000)
        .map(|_| {
            e.step();
            status(&e).cmd_pos
        })
        .collect()
}

/// Digest 004 §2.14: "Axis InShape has no effect on coordinated (group) motion; use Group
/// InShape there": the axis slot is idle while the axis is grouped, the group slot shapes.
#[test]
fn group_motion_uses_the_group_slot_only() {
    let plain = group_run(None);
    let axis_slot = group_run(Some(
        r#"{"type":"filter_input_shaping","axis":0,"frequency":10,"slot":"axis"}"#,
    ));
    let group_slot = group_run(Some(
        r#"{"type":"filter_input_shaping","axis":0,"frequency":10,"slot":"group"}"#,
    ));
    assert_eq!(axis_slot, plain);
    assert_ne!(group_slot, plain);
    assert_eq!(*group_slot.last().unwrap(), 50.0);
    let d = 50;
    for k in d..plain.len() {
        let expected = 0.5 * plain[k] + 0.5 * plain[k - d];
        assert!((group_slot[k] - expected).abs() < 1e-9, "tick {k}");
    }
}

/// Group 1 of two fast axes, axis 0 with a 10 Hz group shaper (50 ticks long), and the id of a
/// line moving axis 0 to 50 just queued.
fn shaped_group_line() -> (Engine, u32) {
    let axis = common::fast_mm_axis(100.0, 1000.0);
    let mut e = common::with_group(engine_with(vec![axis.clone(), axis]), &[0, 1]);
    ok(
        &mut e,
        cmd(r#"{"type":"filter_input_shaping","axis":0,"frequency":10,"slot":"group"}"#),
    );
    let line = id_of(ok(
        &mut e,
        Command::from(common::group_line(1, &[50.0, 0.0])),
    ));
    (e, line)
}

/// A halt while only the shaped members are still arriving has no path to halt: the group
/// stays Moving and goes to Standby when they arrive, not Halted for ever.
#[test]
fn a_halt_after_the_path_leaves_the_group_to_settle() {
    let (mut e, _) = shaped_group_line();
    let state = |e: &Engine| e.group_status(1).unwrap().state;
    // Until the path is done (nothing queued), then halt in the shaper's tail.
    for _ in 0..3000 {
        e.step();
        if e.group_status(1).unwrap().queue_used == 0 {
            break;
        }
    }
    assert_eq!(state(&e), axes::status::GroupState::Moving);
    assert_ne!(status(&e).cmd_pos, 50.0, "still arriving");
    ok(&mut e, cmd(r#"{"type":"group_halt","group":1}"#));
    assert_eq!(state(&e), axes::status::GroupState::Moving);
    for _ in 0..100 {
        e.step();
    }
    assert_eq!(status(&e).cmd_pos, 50.0);
    assert_eq!(state(&e), axes::status::GroupState::Standby);
}

/// The group stays Moving, its line not done and its members moving and not in position,
/// until every member's shaped output has arrived (decisions.md, "Command filters after
/// smoothing"): the group's state follows the members' commands, not the planner.
#[test]
fn group_is_standby_only_when_the_shaped_members_arrive() {
    let (mut e, line) = shaped_group_line();
    let (mut standby, mut arrived, mut done) = (None, None, None);
    for k in 0..3000u32 {
        e.step();
        let g = e.group_status(1).unwrap();
        let member = status(&e).flags;
        if standby.is_none() && g.state == axes::status::GroupState::Standby {
            standby = Some(k);
        }
        if done.is_none() && state_of(&mut e, line) == CommandState::Done {
            done = Some(k);
        }
        if arrived.is_none() && status(&e).cmd_pos == 50.0 {
            arrived = Some(k);
        }
        if arrived.is_none() {
            assert_eq!(g.state, axes::status::GroupState::Moving, "tick {k}");
            assert!(
                !g.in_position,
                "tick {k}: group in position before arriving"
            );
            assert!(member.contains(AxisFlags::MOVING), "tick {k}");
            assert!(!member.contains(AxisFlags::IN_POSITION), "tick {k}");
            assert_ne!(state_of(&mut e, line), CommandState::Done, "tick {k}");
        }
    }
    let (standby, arrived, done) = (standby.unwrap(), arrived.unwrap(), done.unwrap());
    // The member's output settles on the tick it arrives; the group sees that on its next tick.
    assert_eq!(standby, arrived + 1, "standby {standby}, arrived {arrived}");
    assert_eq!(done, standby, "the line is done with the group's standby");
}
