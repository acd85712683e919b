//! A long spline is constructed over several ticks (issue 11 item 4: the planning work per
//! tick bounded; docs/decisions.md, "Group tick and spline acceptance cost"): the motion is
//! the one a construction in one tick gives, started later; the commands after it wait
//! behind it; a stop drops them; a cusp found late ends the spline with an error.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{Command, CommandState, GroupStop, MoveSpline};
use axes::config::GroupsConfig;
use axes::status::{GroupState, GroupStatus};
use axes::{AxisState, Engine, EngineConfig};
use common::{id_of, ok, state_of, stepper_mm};

/// Two stepper axes in group 1, the group constructing `spans` spline spans per tick.
fn machine(spans: u32) -> Engine {
    let e = Engine::new(&EngineConfig {
        axes: (0..2).map(|_| stepper_mm()).collect(),
        groups: GroupsConfig {
            spline_spans_per_tick: spans,
            ..GroupsConfig::default()
        },
        ..EngineConfig::default()
    })
    .unwrap();
    common::with_group(e, &[0, 1])
}

/// `n` points of a zigzag after `(x0, 0)`: x by 1 mm, y alternating 1 and 0 mm.
fn zigzag(x0: f64, n: usize) -> Vec<Vec<f64>> {
    (1..=n)
        .map(|i| vec![x0 + i as f64, if i % 2 == 0 { 0.0 } else { 1.0 }])
        .collect()
}

fn spline(points: Vec<Vec<f64>>) -> MoveSpline {
    MoveSpline {
        velocity: Some(50.0),
        ..common::group_spline(1, points)
    }
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

fn send(e: &mut Engine, c: impl Into<Command>) -> u32 {
    id_of(ok(e, c.into()))
}

/// The members' commanded position and velocity each tick until the group is back in
/// Standby, without the leading ticks at rest, and how many those were (each checked: the
/// group Moving, its members standing still).
fn trace(e: &mut Engine) -> (usize, Vec<[f64; 4]>) {
    let mut out = Vec::new();
    let mut at_rest = 0;
    for _ in 0..200_000 {
        e.step();
        let (a, b) = (e.axis_status(0).unwrap(), e.axis_status(1).unwrap());
        let row = [a.cmd_pos, b.cmd_pos, a.cmd_vel, b.cmd_vel];
        if out.is_empty() && row == [0.0; 4] {
            at_rest += 1;
            assert_eq!(group(e).state, GroupState::Moving);
            assert_eq!(a.state, AxisState::Standstill);
            continue;
        }
        out.push(row);
        if group(e).state == GroupState::Standby {
            return (at_rest, out);
        }
    }
    panic!("the path did not end");
}

#[test]
fn a_long_spline_moves_as_when_built_in_one_tick_only_later() {
    let commands = || vec![Command::from(spline(zigzag(0.0, 120)))];
    let mut at_once = machine(1000);
    let mut stepped = machine(8);
    for c in commands() {
        ok(&mut at_once, c.clone());
        ok(&mut stepped, c);
    }
    // Built in the applying tick: queued in the planner at once.
    assert!(group(&at_once).remaining_length > 0.0);
    // 120 spans at 8 per tick: 8 when applied, the rest over 14 ticks; meanwhile nothing
    // moves, and the spline waits in the queue.
    let waiting = group(&stepped);
    assert_eq!((waiting.state, waiting.queue_used), (GroupState::Moving, 1));
    assert_eq!(waiting.remaining_length, 0.0);
    let ((rest_a, a), (rest_b, b)) = (trace(&mut at_once), trace(&mut stepped));
    assert_eq!((rest_a, rest_b), (0, 13));
    assert!(a.len() > 1000, "{}", a.len());
    // The same motion, bit for bit, tick for tick.
    assert_eq!(a.len(), b.len());
    assert!(a == b, "the motions differ");
    assert_eq!(a.last().unwrap()[..2], [120.0, 0.0]);
}

#[test]
fn commands_after_a_spline_under_construction_follow_it_in_order() {
    let commands = || {
        vec![
            Command::from(spline(zigzag(0.0, 60))),
            Command::from(common::group_line(1, &[70.0, 5.0])),
            Command::from(spline(zigzag(70.0, 30))),
            Command::from(common::group_line(1, &[110.0, 0.0])),
        ]
    };
    let mut at_once = machine(1000);
    let mut stepped = machine(8);
    let mut ids = Vec::new();
    for c in commands() {
        ok(&mut at_once, c.clone());
        ids.push(send(&mut stepped, c));
    }
    assert_eq!(group(&stepped).queue_used, 4);
    for &id in &ids {
        assert_eq!(state_of(&mut stepped, id), CommandState::Waiting);
    }
    let ((_, a), (_, b)) = (trace(&mut at_once), trace(&mut stepped));
    assert_eq!(a.len(), b.len());
    // The second spline reaches the planner while the path runs the first: the running
    // motion is planned again then, which may move a bit of the last place.
    let worst = a
        .iter()
        .zip(&b)
        .flat_map(|(x, y)| x.iter().zip(y).map(|(p, q)| (p - q).abs()))
        .fold(0.0, f64::max);
    assert!(worst < 1e-9, "off by {worst}");
    assert_eq!(b.last().unwrap()[..2], [110.0, 0.0]);
    for id in ids {
        assert_eq!(state_of(&mut stepped, id), CommandState::Done);
    }
}

#[test]
fn a_stop_drops_a_spline_under_construction_and_the_commands_after_it() {
    let mut e = machine(8);
    let s = send(&mut e, spline(zigzag(0.0, 200)));
    let l = send(&mut e, common::group_line(1, &[0.0, 10.0]));
    e.step();
    ok(
        &mut e,
        Command::from(GroupStop {
            group: 1,
            deceleration: None,
        }),
    );
    for _ in 0..50 {
        e.step();
    }
    assert_eq!(state_of(&mut e, s), CommandState::Aborted);
    assert_eq!(state_of(&mut e, l), CommandState::Aborted);
    let g = group(&e);
    assert_eq!((g.state, g.queue_used), (GroupState::Standby, 0));
    assert_eq!(g.position()[..2], [0.0, 0.0]);
}

#[test]
fn a_cusp_found_while_building_ends_the_spline_with_an_error() {
    // Along x to 50, then back to 45: the spline turns back on itself (no tangent there),
    // which only the construction of its spans finds.
    let mut e = machine(8);
    let mut points: Vec<Vec<f64>> = (1..=50).map(|i| vec![f64::from(i), 0.0]).collect();
    points.push(vec![45.0, 0.0]);
    let s = send(&mut e, spline(points));
    let l = send(&mut e, common::group_line(1, &[0.0, 10.0]));
    for _ in 0..20 {
        e.step();
    }
    assert!(
        matches!(state_of(&mut e, s), CommandState::Error(_)),
        "{:?}",
        state_of(&mut e, s)
    );
    assert_eq!(state_of(&mut e, l), CommandState::Aborted);
    let g = group(&e);
    assert_eq!((g.state, g.queue_used), (GroupState::Standby, 0));
    assert!(g.last_error.is_some());
    assert_eq!(g.position()[..2], [0.0, 0.0]);
}
