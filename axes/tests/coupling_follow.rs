//! NMC Follow FIFOs at the engine level (issue 12 item 2; digest 001 §2.17, §4.7): S-FOLLOW /
//! TV 59 through `follow_config`/`follow_push`/`follow_start`, loop counts and the switch to
//! the other FIFO (automatic and by `follow_switch`), `follow_out`, and bad input.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    CamPoint, Command, Direction, EngineError, FollowClear, FollowConfig, FollowEvent, FollowOut,
    FollowPush, FollowSegment, FollowStart, FollowSwitch, MasterSource,
};
use axes::status::{CouplingKind, CouplingPhase, FollowState};
use axes::{AxisFlags, Engine};
use common::{jog_of, move_rel_of, ok, refused};

fn machine(n: usize) -> Engine {
    common::enabled_machine(common::virtual_pulse_axis(), n)
}

fn config(axis: u16) -> FollowConfig {
    FollowConfig {
        axis,
        master: None,
        master_source: None,
        loop_count: None,
        event: None,
        start_position: None,
        start_direction: None,
        direction: None,
    }
}

fn push(e: &mut Engine, axis: u16, fifo: u8, p: &[(f64, f64)]) {
    let points = p
        .iter()
        .map(|&(master, slave)| CamPoint {
            master,
            slave,
            segment: FollowSegment::Normal,
        })
        .collect();
    ok(e, Command::from(FollowPush { axis, fifo, points }));
}

fn cmd(e: &Engine, axis: usize) -> f64 {
    e.axis_status(axis).unwrap().cmd_pos
}

/// S-FOLLOW's FIFO: ratio 0 → 1 → 1 → 0 over 60000 of master, 40000 of slave.
const S_FOLLOW: [(f64, f64); 3] = [
    (20_000.0, 10_000.0),
    (40_000.0, 30_000.0),
    (60_000.0, 40_000.0),
];

/// Axis 1 follows axis 0 by commanded position, with `loop_count`.
fn follower(e: &mut Engine, loop_count: u32) {
    ok(
        e,
        Command::from(FollowConfig {
            master: Some(0),
            master_source: Some(MasterSource::Commanded),
            loop_count: Some(loop_count),
            ..config(1)
        }),
    );
}

fn master_by(e: &mut Engine, d: f64) {
    ok(e, move_rel_of(0, d));
    for _ in 0..20_000 {
        e.step();
        if !e.axis_status(0).unwrap().flags.contains(AxisFlags::MOVING) {
            e.step();
            return;
        }
    }
    panic!("master still moving");
}

#[test]
fn s_follow_through_the_fifo_starts_at_master_50000_and_repeats_every_60000_tv59() {
    // S-FOLLOW (digest 001 §5): FollowClear(0), SetMaster(0, AXIS_PRF), push the three points
    // into FIFO 0, SetLoopCount(0), SetEvent(2, 1, 50000), FollowStart; master jogs at 50/ms.
    let mut e = machine(2);
    ok(&mut e, Command::from(FollowClear { axis: 1, fifo: 0 }));
    push(&mut e, 1, 0, &S_FOLLOW);
    ok(
        &mut e,
        Command::from(FollowConfig {
            master: Some(0),
            master_source: Some(MasterSource::Commanded),
            loop_count: Some(0),
            event: Some(FollowEvent::MasterCrossing),
            start_position: Some(50_000.0),
            start_direction: Some(Direction::Positive),
            ..config(1)
        }),
    );
    assert_eq!(e.snapshot().follows[0].space, [29, 32]);
    ok(&mut e, Command::from(FollowStart { axes: vec![1] }));
    let f = e.snapshot().follows[0];
    assert_eq!((f.state, f.active_fifo), (FollowState::Waiting, 0));
    assert_eq!(e.snapshot().couplings[0].phase, CouplingPhase::Waiting);
    ok(&mut e, jog_of(0, 50_000.0));
    let mut k = 1;
    for _ in 0..10_000 {
        e.step();
        let (m, s) = (cmd(&e, 0), cmd(&e, 1));
        if m < 50_000.0 {
            assert_eq!(s, 0.0, "slave moved before the start at master {m}");
            continue;
        }
        let at = 50_000.0 + 60_000.0 * k as f64;
        if m >= at {
            // TV 59: slave = 40000·k, plus the next pass's quadratic start (≤ 0.5/20000 · 50²).
            assert!((s - 40_000.0 * k as f64).abs() < 0.07, "k {k}: slave {s}");
            k += 1;
        }
    }
    assert!(k > 5, "{k}");
    let snap = e.snapshot();
    let f = snap.follows[0];
    assert_eq!(f.state, FollowState::Running);
    assert!(f.loops_done >= 5, "{}", f.loops_done);
    let c = snap.couplings[0];
    assert_eq!(
        (c.kind, c.phase),
        (CouplingKind::Follow, CouplingPhase::InSync)
    );
    assert_eq!(c.cycle, i64::from(f.loops_done));
}

#[test]
fn after_its_loops_the_follow_switches_to_the_other_fifo_and_empties_the_first() {
    let mut e = machine(2);
    follower(&mut e, 2);
    push(&mut e, 1, 0, &S_FOLLOW);
    // FIFO 1: 30000 of master → 10000 of slave, from rest to rest.
    push(&mut e, 1, 1, &[(15_000.0, 5_000.0), (30_000.0, 10_000.0)]);
    ok(&mut e, Command::from(FollowStart { axes: vec![1] }));
    // Two passes of FIFO 0 (120000), then FIFO 1 runs.
    master_by(&mut e, 130_000.0);
    let f = e.snapshot().follows[0];
    assert_eq!(
        (f.state, f.active_fifo, f.loops_done),
        (FollowState::Running, 1, 0)
    );
    assert_eq!(
        f.space,
        [32, 30],
        "the finished FIFO is emptied for refilling"
    );
    // 10000 into FIFO 1's first NORMAL segment (ratio 0 → 2/3 over 15000): 10000²/2 · 2/45000.
    assert!(
        (cmd(&e, 1) - (80_000.0 + 2_222.222_222)).abs() < 1e-3,
        "{}",
        cmd(&e, 1)
    );
    // The host refills FIFO 0 while FIFO 1 runs; pushing into the running FIFO is refused.
    push(&mut e, 1, 0, &[(5_000.0, 500.0), (10_000.0, 1_000.0)]);
    let r = refused(
        &mut e,
        Command::from(FollowPush {
            axis: 1,
            fifo: 1,
            points: vec![CamPoint {
                master: 40_000.0,
                slave: 0.0,
                segment: FollowSegment::Normal,
            }],
        }),
    );
    assert!(
        matches!(r, EngineError::InvalidFollow { axis: 1, .. }),
        "{r}"
    );
    // FIFO 1's two passes (60000 from 120000), then FIFO 0's refill twice (20000): then
    // nothing is left to switch to and the Follow ends at its last point.
    master_by(&mut e, 80_000.0);
    assert!(
        (cmd(&e, 1) - (80_000.0 + 20_000.0 + 2_000.0)).abs() < 1e-6,
        "{}",
        cmd(&e, 1)
    );
    let snap = e.snapshot();
    assert!(snap.couplings.is_empty());
    assert_eq!(snap.follows[0].state, FollowState::Idle);
    assert!(!e.axis_status(1).unwrap().flags.contains(AxisFlags::COUPLED));
}

#[test]
fn follow_switch_changes_fifo_at_the_end_of_the_pass() {
    let mut e = machine(2);
    follower(&mut e, 0);
    push(&mut e, 1, 0, &S_FOLLOW);
    ok(&mut e, Command::from(FollowStart { axes: vec![1] }));
    // Nothing in FIFO 1 yet: no switch.
    let r = refused(&mut e, Command::from(FollowSwitch { axes: vec![1] }));
    assert!(
        matches!(r, EngineError::InvalidFollow { axis: 1, .. }),
        "{r}"
    );
    push(&mut e, 1, 1, &[(30_000.0, -10_000.0)]);
    master_by(&mut e, 30_000.0);
    ok(&mut e, Command::from(FollowSwitch { axes: vec![1] }));
    assert!(e.snapshot().follows[0].switch_pending);
    // Still in FIFO 0 until its pass ends at 60000.
    master_by(&mut e, 20_000.0);
    assert_eq!(e.snapshot().follows[0].active_fifo, 0);
    master_by(&mut e, 25_000.0);
    let f = e.snapshot().follows[0];
    assert_eq!(
        (f.active_fifo, f.switch_pending, f.space[0]),
        (1, false, 32)
    );
    // 40000 from FIFO 0's pass, then 15000 of FIFO 1's NORMAL segment from rest: ratio
    // −2/3 · (15000/30000) · … = −10000 · (1/2)² = −2500.
    assert!(
        (cmd(&e, 1) - (40_000.0 - 2_500.0)).abs() < 1e-6,
        "{}",
        cmd(&e, 1)
    );
}

#[test]
fn follow_out_releases_the_slave_and_keeps_the_fifos() {
    let mut e = machine(2);
    follower(&mut e, 0);
    push(&mut e, 1, 0, &S_FOLLOW);
    ok(&mut e, Command::from(FollowStart { axes: vec![1] }));
    ok(&mut e, jog_of(0, 50_000.0));
    common::run(&mut e, 0.5);
    ok(&mut e, Command::from(FollowOut { axis: 1 }));
    common::run(&mut e, 1.0);
    let snap = e.snapshot();
    assert!(snap.couplings.is_empty());
    assert_eq!(snap.follows[0].state, FollowState::Idle);
    assert_eq!(snap.follows[0].space, [29, 32]);
    assert!(!e.axis_status(1).unwrap().flags.contains(AxisFlags::MOVING));
}

#[test]
fn bad_follow_input_is_refused_naming_what_is_wrong_tv59() {
    let mut e = machine(3);
    let before = e.snapshot();
    // No master yet.
    push(&mut e, 1, 0, &S_FOLLOW);
    let r = refused(&mut e, Command::from(FollowStart { axes: vec![1] }));
    assert!(r.to_string().contains("no master"), "{r}");
    // Its own master; a FIFO that does not exist; masters not increasing; a full FIFO.
    let r = refused(
        &mut e,
        Command::from(FollowConfig {
            master: Some(1),
            ..config(1)
        }),
    );
    assert!(matches!(r, EngineError::CoupledToItself { axis: 1 }), "{r}");
    let r = refused(&mut e, Command::from(FollowClear { axis: 1, fifo: 2 }));
    assert!(r.to_string().contains("no FIFO 2"), "{r}");
    let back = CamPoint {
        master: 50_000.0,
        slave: 0.0,
        segment: FollowSegment::Normal,
    };
    let r = refused(
        &mut e,
        Command::from(FollowPush {
            axis: 1,
            fifo: 0,
            points: vec![back],
        }),
    );
    assert!(r.to_string().contains("is not after 60000"), "{r}");
    let many: Vec<CamPoint> = (1..=30)
        .map(|i| CamPoint {
            master: 100_000.0 + f64::from(i),
            slave: 0.0,
            segment: FollowSegment::Even,
        })
        .collect();
    let r = refused(
        &mut e,
        Command::from(FollowPush {
            axis: 1,
            fifo: 0,
            points: many,
        }),
    );
    assert!(
        matches!(
            r,
            EngineError::FollowFull {
                axis: 1,
                fifo: 0,
                space: 29,
                count: 30
            }
        ),
        "{r}"
    );
    let nan = CamPoint {
        master: f64::NAN,
        slave: 0.0,
        segment: FollowSegment::Normal,
    };
    refused(
        &mut e,
        Command::from(FollowPush {
            axis: 1,
            fifo: 1,
            points: vec![nan],
        }),
    );
    // A loop: 2 follows 1 and 1 follows 2, started together: none starts.
    follower(&mut e, 0);
    ok(
        &mut e,
        Command::from(FollowConfig {
            master: Some(2),
            ..config(1)
        }),
    );
    ok(
        &mut e,
        Command::from(FollowConfig {
            master: Some(1),
            ..config(2)
        }),
    );
    push(&mut e, 2, 1, &S_FOLLOW);
    let r = refused(&mut e, Command::from(FollowStart { axes: vec![1, 2] }));
    assert!(matches!(r, EngineError::CouplingLoop { .. }), "{r}");
    let snap = e.snapshot();
    assert!(snap.couplings.is_empty());
    assert!(snap.follows.iter().all(|f| f.state == FollowState::Idle));
    assert_eq!(snap.axes, before.axes);
}
