//! A group e-stop that keeps the path (issue 13, NMC `CrdEstopMtn` / `CrdGotoBreak`): the
//! members ramp down off the path, the reset returns to Halted with the queue kept, a line
//! back to the break goes in front of the remainder, and `group_continue` finishes the
//! program exactly as programmed from the break on.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    ArcDirection, Command, CommandState, Disable, ErrorKind, GroupBufferMode, GroupContinue,
    GroupEmergencyStop, GroupReset, Reset, TransitionMode,
};
use axes::status::{GroupFault, GroupState};
use axes::{AxisState, Engine, EngineConfig};
use common::{group_arc, group_line, id_of, ok, refused, run, run_path, state_of, stepper_mm};

fn machine() -> Engine {
    let e = Engine::new(&EngineConfig {
        axes: vec![stepper_mm(), stepper_mm()],
        ..EngineConfig::default()
    })
    .unwrap();
    common::with_group(e, &[0, 1])
}

/// The program: a diagonal line, a line, a half circle; user segments 1, 2, 3.
fn program(e: &mut Engine) -> Vec<u32> {
    let mut first = group_line(1, &[30.0, 10.0]);
    first.user_segment = Some(1);
    let mut second = group_line(1, &[30.0, 30.0]);
    second.user_segment = Some(2);
    let mut third = group_arc(1, &[15.0, 30.0], &[0.0, 30.0], ArcDirection::Ccw);
    third.user_segment = Some(3);
    vec![
        id_of(ok(e, Command::from(first))),
        id_of(ok(e, Command::from(second))),
        id_of(ok(e, Command::from(third))),
    ]
}

/// Distance from (x, y) to the programmed path.
fn off_program(x: f64, y: f64) -> f64 {
    let seg = |(ax, ay): (f64, f64), (bx, by): (f64, f64)| {
        let (dx, dy) = (bx - ax, by - ay);
        let t = (((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
        (x - ax - t * dx).hypot(y - ay - t * dy)
    };
    let arc = if y >= 30.0 - 1e-9 {
        ((x - 15.0).hypot(y - 30.0) - 15.0).abs()
    } else {
        f64::INFINITY
    };
    seg((0.0, 0.0), (30.0, 10.0))
        .min(seg((30.0, 10.0), (30.0, 30.0)))
        .min(arc)
}

fn estop_keeping_path() -> Command {
    Command::from(GroupEmergencyStop {
        group: 1,
        keep_path: true,
    })
}

#[test]
fn after_an_estop_that_keeps_the_path_a_return_and_continue_finish_it_from_the_break() {
    let mut e = machine();
    let ids = program(&mut e);
    run(&mut e, 0.15);
    let g = e.snapshot().groups[0];
    assert_eq!((g.state, g.user_segment), (GroupState::Moving, 1));
    assert!(g.path_velocity > 0.0);
    let at = (g.coordinates[0], g.coordinates[1]);
    ok(&mut e, estop_keeping_path());
    let g = e.snapshot().groups[0];
    assert_eq!(
        (g.state, g.fault),
        (GroupState::ErrorStop, Some(GroupFault::EmergencyStop))
    );
    // The members ramp down on their own (fast_decel), off the path; the commands stay.
    run(&mut e, 0.1);
    let g = e.snapshot().groups[0];
    let stood = (g.coordinates[0], g.coordinates[1]);
    assert!(
        off_program(stood.0, stood.1) > 1e-3,
        "{stood:?} is off the line"
    );
    assert_eq!(g.queue_used, 3);
    for id in &ids {
        let st = state_of(&mut e, *id);
        assert!(
            matches!(st, CommandState::Running | CommandState::Waiting),
            "{id}: {st:?}"
        );
    }
    for axis in 0..2u16 {
        assert_eq!(
            e.axis_status(axis as usize).unwrap().state,
            AxisState::ErrorStop
        );
        ok(&mut e, Command::from(Reset { axis }));
    }
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(e.snapshot().groups[0].state, GroupState::Halted);
    // Off the path: neither going on nor any other motion, and a line elsewhere is refused.
    let err = refused(&mut e, Command::from(GroupContinue { group: 1 }));
    assert_eq!(err.kind(), ErrorKind::GroupState);
    let err = refused(
        &mut e,
        Command::from(group_arc(1, &[0.0, 0.0], &[1.0, 1.0], ArcDirection::Cw)),
    );
    assert_eq!(err.kind(), ErrorKind::GroupState);
    run(&mut e, 0.05);
    assert_eq!(e.snapshot().groups[0].coordinates[..2], [stood.0, stood.1]);
    // The line back to the break (named a little off it: it goes to the break exactly), then
    // go on.
    let mut back = group_line(1, &[at.0 + 0.01, at.1]);
    back.user_segment = Some(9);
    let back = id_of(ok(&mut e, Command::from(back)));
    ok(&mut e, Command::from(GroupContinue { group: 1 }));
    let mut seen = Vec::new();
    let mut returned = false;
    run_path(&mut e, 10.0, |_, g| {
        let (x, y) = (g.coordinates[0], g.coordinates[1]);
        if g.user_segment != 9 && g.state == GroupState::Moving {
            returned = true;
        }
        if returned {
            assert!(off_program(x, y) < 1e-6, "({x}, {y}) is off the program");
        }
        if seen.last() != Some(&g.user_segment) {
            seen.push(g.user_segment);
        }
    });
    assert_eq!(
        seen,
        vec![9, 1, 2, 3],
        "every remaining segment runs, in order"
    );
    let g = e.snapshot().groups[0];
    assert!((g.coordinates[0]).abs() < 1e-9 && (g.coordinates[1] - 30.0).abs() < 1e-9);
    for id in ids.iter().chain([&back]) {
        assert_eq!(state_of(&mut e, *id), CommandState::Done, "{id}");
    }
}

#[test]
fn an_estop_that_keeps_the_path_on_an_idle_group_is_the_plain_one() {
    let mut e = machine();
    ok(&mut e, estop_keeping_path());
    run(&mut e, 0.01);
    for axis in 0..2u16 {
        ok(&mut e, Command::from(Reset { axis }));
    }
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(e.snapshot().groups[0].state, GroupState::Standby);
    ok(&mut e, Command::from(group_line(1, &[5.0, 5.0])));
}

#[test]
fn a_reset_to_disabled_drops_the_kept_path() {
    let mut e = machine();
    let ids = program(&mut e);
    run(&mut e, 0.15);
    ok(&mut e, estop_keeping_path());
    run(&mut e, 0.1);
    for axis in 0..2u16 {
        ok(&mut e, Command::from(Reset { axis }));
        ok(&mut e, Command::from(Disable { axis }));
    }
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    let g = e.snapshot().groups[0];
    assert_eq!((g.state, g.queue_used), (GroupState::Disabled, 0));
    for id in &ids {
        assert_eq!(state_of(&mut e, *id), CommandState::Aborted, "{id}");
    }
}

/// A keep-path e-stop, then the members' and the group's resets: where the members stand.
fn estop_and_reset(e: &mut Engine) -> (f64, f64) {
    ok(e, estop_keeping_path());
    run(e, 0.1);
    for axis in 0..2u16 {
        ok(e, Command::from(Reset { axis }));
    }
    ok(e, Command::from(GroupReset { group: 1 }));
    let g = e.snapshot().groups[0];
    assert_eq!(g.state, GroupState::Halted);
    (g.coordinates[0], g.coordinates[1])
}

/// Distance from (x, y) to the segment from `a` to `b`.
fn off_segment((x, y): (f64, f64), (ax, ay): (f64, f64), (bx, by): (f64, f64)) -> f64 {
    let (dx, dy) = (bx - ax, by - ay);
    let t = (((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    (x - ax - t * dx).hypot(y - ay - t * dy)
}

/// A second e-stop on the return line: the break is still where the program was interrupted,
/// so the next return goes straight there (not to the point on the first return line), the
/// first return ends aborted, and the program finishes as programmed.
#[test]
fn a_second_estop_on_the_return_line_returns_to_the_program_break() {
    let mut e = machine();
    let ids = program(&mut e);
    run(&mut e, 0.15);
    let g = e.snapshot().groups[0];
    let at = (g.coordinates[0], g.coordinates[1]);
    estop_and_reset(&mut e);
    let mut back = group_line(1, &[at.0, at.1]);
    back.user_segment = Some(9);
    let first_back = id_of(ok(&mut e, Command::from(back.clone())));
    ok(&mut e, Command::from(GroupContinue { group: 1 }));
    run(&mut e, 0.02);
    let g = e.snapshot().groups[0];
    assert_eq!(
        (g.state, g.user_segment),
        (GroupState::Moving, 9),
        "on the way back"
    );
    let stood = estop_and_reset(&mut e);
    assert!(
        off_segment(stood, (g.coordinates[0], g.coordinates[1]), at) > 1e-3,
        "{stood:?} is off the first return line"
    );
    let second_back = id_of(ok(&mut e, Command::from(back)));
    ok(&mut e, Command::from(GroupContinue { group: 1 }));
    let mut seen = Vec::new();
    run_path(&mut e, 10.0, |_, g| {
        let p = (g.coordinates[0], g.coordinates[1]);
        if g.user_segment == 9 {
            let off = off_segment(p, stood, at);
            assert!(off < 1e-6, "{p:?} is {off} off the line back to the break");
        } else {
            assert!(off_program(p.0, p.1) < 1e-6, "{p:?} is off the program");
        }
        if seen.last() != Some(&g.user_segment) {
            seen.push(g.user_segment);
        }
    });
    assert_eq!(seen, vec![9, 1, 2, 3]);
    for id in ids.iter().chain([&second_back]) {
        assert_eq!(state_of(&mut e, *id), CommandState::Done, "{id}");
    }
    assert_eq!(state_of(&mut e, first_back), CommandState::Aborted);
}

/// An e-stop in a blend arc (the corner between user segments 1 and 2 rounded by the
/// look-ahead, which reports the motion it begins): the user segment reads 2, a number the
/// user gave, after the e-stop, after the return is queued, on the way back (the return names
/// none: it is the way back into segment 2) and through the rest of 2; then 3.
#[test]
fn an_estop_in_a_blend_arc_reports_the_users_segment_throughout() {
    let mut e = machine();
    let mut first = group_line(1, &[30.0, 0.0]);
    first.user_segment = Some(1);
    let mut second = group_line(1, &[30.0, 30.0]);
    second.user_segment = Some(2);
    second.buffer_mode = GroupBufferMode::BlendingLow;
    second.transition = TransitionMode::CornerDistance(5.0);
    let mut third = group_line(1, &[0.0, 30.0]);
    third.user_segment = Some(3);
    for m in [first, second, third] {
        ok(&mut e, Command::from(m));
    }
    // Into the arc: past the corner's start, not yet on the second line.
    let mut ticks = 0;
    let g = loop {
        e.step();
        let g = e.snapshot().groups[0];
        if g.coordinates[0] > 26.0 && g.coordinates[1] > 0.2 {
            break g;
        }
        ticks += 1;
        assert!(ticks < 100_000 && g.state == GroupState::Moving, "{g:?}");
    };
    assert!(
        g.coordinates[0] < 30.0 - 1e-6 && g.coordinates[1] < 5.0,
        "{g:?} in the arc"
    );
    assert_eq!(g.user_segment, 2);
    let at = (g.coordinates[0], g.coordinates[1]);
    estop_and_reset(&mut e);
    assert_eq!(e.snapshot().groups[0].user_segment, 2, "after the e-stop");
    ok(&mut e, Command::from(group_line(1, &[at.0, at.1])));
    assert_eq!(e.snapshot().groups[0].user_segment, 2, "the return queued");
    ok(&mut e, Command::from(GroupContinue { group: 1 }));
    let mut seen = Vec::new();
    run_path(&mut e, 10.0, |_, g| {
        if seen.last() != Some(&g.user_segment) {
            seen.push(g.user_segment);
        }
    });
    assert_eq!(seen, vec![2, 3], "the way back is segment 2's");
}
