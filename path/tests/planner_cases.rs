//! The planner's fixed cases (issue 11 tests): exact stops, markers, halt/resume/stop/abort,
//! override, corner blends, LinuxCNC #3773, a 5-turn helix.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use path::geometry::{Arc, Segment, Turn};
use path::planner::{Join, MarkerKind, PathEvent, PathPlanner, PlannerConfig, Transition};

fn square_config() -> PlannerConfig {
    PlannerConfig::uniform(2, axis(100.0, 1000.0, f64::INFINITY), 1e-3)
}

#[test]
fn a_buffered_square_stops_at_each_corner_and_ends_exactly() {
    let cfg = square_config();
    let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0, 0.0])).unwrap();
    let corners = [
        p(&[10.0, 0.0]),
        p(&[10.0, 10.0]),
        p(&[0.0, 10.0]),
        p(&[0.0, 0.3]),
    ];
    let mut from = p(&[0.0, 0.0]);
    for (i, c) in corners.iter().enumerate() {
        let m = motion(
            line(from, *c, 2),
            limits(50.0, 500.0, f64::INFINITY),
            Join::Buffered,
            Transition::None,
            i as u64,
        );
        pl.push_motion(m).unwrap();
        from = *c;
    }
    assert_eq!(pl.queued(), 4);
    let (states, events) = run(&mut pl, 100_000);
    let last = states.last().unwrap();
    assert_eq!(last.position, p(&[0.0, 0.3]));
    assert_eq!(last.completed, 4);
    assert!(pl.is_idle());
    let pk = peaks(&states, &cfg);
    assert!(pk.v_fd <= 1.0 && pk.a_fd <= 1.0, "{} {}", pk.v_fd, pk.a_fd);
    let started = events
        .iter()
        .filter(|e| matches!(e, PathEvent::Started { .. }))
        .count();
    let done = events
        .iter()
        .filter(|e| matches!(e, PathEvent::Done { .. }))
        .count();
    assert_eq!((started, done), (4, 4));
    // Every corner is passed at rest: a tick within one period of it, slower than one
    // period's acceleration (the next motion starts in the tick the previous one ends).
    for c in &corners[..3] {
        assert!(states.iter().any(|s| {
            let d = (s.position[0] - c[0]).hypot(s.position[1] - c[1]);
            d <= 0.5 * 500.0 * 1e-6 && s.path_velocity <= 500.0 * 1e-3
        }));
    }
}

fn three_lines(pl: &mut PathPlanner, join: Join) {
    let pts = [
        p(&[0.0, 0.0]),
        p(&[20.0, 0.0]),
        p(&[20.0, 20.0]),
        p(&[40.0, 20.0]),
    ];
    for i in 0..3 {
        let m = motion(
            line(pts[i], pts[i + 1], 2),
            limits(50.0, 500.0, f64::INFINITY),
            join,
            Transition::None,
            i as u64,
        );
        pl.push_motion(m).unwrap();
    }
}

#[test]
fn markers_pass_through_and_hold_until_released() {
    let cfg = square_config();
    let mut pl = PathPlanner::new(cfg, p(&[0.0, 0.0])).unwrap();
    let m = |a, b, tag| {
        motion(
            line(p(a), p(b), 2),
            limits(50.0, 500.0, f64::INFINITY),
            Join::BlendingLow,
            Transition::None,
            tag,
        )
    };
    pl.push_motion(m(&[0.0, 0.0], &[10.0, 0.0], 1)).unwrap();
    pl.push_marker(100, MarkerKind::PassThrough).unwrap();
    pl.push_motion(m(&[10.0, 0.0], &[20.0, 0.0], 2)).unwrap();
    pl.push_marker(200, MarkerKind::Hold).unwrap();
    pl.push_motion(m(&[20.0, 0.0], &[30.0, 0.0], 3)).unwrap();
    assert_eq!(pl.queued(), 5);
    let mut events = Vec::new();
    let mut min_v_at_pass = f64::INFINITY;
    for _ in 0..5000 {
        let before = events.len();
        let st = *pl.step(&mut events);
        if events[before..].contains(&PathEvent::Marker {
            tag: 100,
            kind: MarkerKind::PassThrough,
        }) {
            min_v_at_pass = st.path_velocity;
        }
        if st.holding.is_some() {
            break;
        }
    }
    // The pass-through marker does not slow the path (collinear, blended: full speed).
    assert_eq!(min_v_at_pass, 50.0);
    let st = *pl.state();
    assert_eq!(st.holding, Some(200));
    assert_eq!(st.position, p(&[20.0, 0.0]));
    assert_eq!(st.path_velocity, 0.0);
    // It waits.
    for _ in 0..100 {
        assert_eq!(pl.step(&mut events).position, p(&[20.0, 0.0]));
    }
    pl.release_hold();
    let (states, ev) = run(&mut pl, 10_000);
    assert_eq!(states.last().unwrap().position, p(&[30.0, 0.0]));
    events.extend(ev);
    let order: Vec<_> = events
        .iter()
        .filter(|e| !matches!(e, PathEvent::Started { .. }))
        .copied()
        .collect();
    assert_eq!(
        order,
        vec![
            PathEvent::Done { tag: 1 },
            PathEvent::Marker {
                tag: 100,
                kind: MarkerKind::PassThrough
            },
            PathEvent::Done { tag: 2 },
            PathEvent::Marker {
                tag: 200,
                kind: MarkerKind::Hold
            },
            PathEvent::Done { tag: 3 },
        ]
    );
}

#[test]
fn halt_keeps_the_path_and_resume_finishes_it() {
    let cfg = square_config();
    let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0, 0.0])).unwrap();
    three_lines(&mut pl, Join::BlendingLow);
    let mut events = Vec::new();
    let mut states = vec![*pl.state()];
    for _ in 0..300 {
        states.push(*pl.step(&mut events));
    }
    pl.halt(Some(200.0));
    let mut rest_at = None;
    for i in 0..2000 {
        let st = *pl.step(&mut events);
        states.push(st);
        if events.contains(&PathEvent::AtRest) && rest_at.is_none() {
            rest_at = Some(i);
            assert_eq!(st.path_velocity, 0.0);
            assert!(st.halted);
        }
    }
    assert!(rest_at.is_some());
    let held = pl.state().position;
    // On the programmed path (the first two lines), not at the end.
    assert!(
        held[1].abs() < 1e-12 || (held[0] - 20.0).abs() < 1e-12,
        "{held:?}"
    );
    assert_eq!(pl.queued(), 3 - pl.state().completed as usize);
    pl.resume();
    let (more, ev) = run(&mut pl, 100_000);
    states.extend(more);
    events.extend(ev);
    assert_eq!(states.last().unwrap().position, p(&[40.0, 20.0]));
    assert_eq!(states.last().unwrap().completed, 3);
    let pk = peaks(&states, &cfg);
    assert!(pk.v_fd <= 1.0 + 1e-9, "{}", pk.v_fd);
}

#[test]
fn stop_drops_the_queue_once_at_rest_and_abort_drops_it_at_once() {
    let cfg = square_config();
    let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0, 0.0])).unwrap();
    three_lines(&mut pl, Join::BlendingLow);
    let mut events = Vec::new();
    for _ in 0..300 {
        pl.step(&mut events);
    }
    pl.stop(500.0);
    let (states, ev) = run(&mut pl, 10_000);
    assert!(pl.is_idle());
    let at_rest = ev.iter().position(|e| *e == PathEvent::AtRest).unwrap();
    let dropped: Vec<_> = ev[at_rest..]
        .iter()
        .filter(|e| matches!(e, PathEvent::Dropped { .. }))
        .collect();
    assert!(!dropped.is_empty());
    let end = states.last().unwrap();
    assert_eq!(end.path_velocity, 0.0);
    // A new motion starts where the path stopped.
    let here = pl.queue_end();
    assert_eq!(here, end.position);
    pl.push_motion(motion(
        line(here, p(&[0.0, 0.0]), 2),
        limits(50.0, 500.0, f64::INFINITY),
        Join::Buffered,
        Transition::None,
        9,
    ))
    .unwrap();
    for _ in 0..10 {
        pl.step(&mut events);
    }
    assert!(pl.state().path_velocity > 0.0);
    let mut ev = Vec::new();
    pl.abort(&mut ev);
    assert_eq!(ev, vec![PathEvent::Dropped { tag: 9 }]);
    assert!(pl.is_idle());
    assert_eq!(pl.state().path_velocity, 0.0);
    let still = pl.state().position;
    assert_eq!(pl.step(&mut ev).position, still);
}

#[test]
fn an_arc_keeps_every_axis_within_its_acceleration() {
    let cfg = PlannerConfig::uniform(2, axis(200.0, 1000.0, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg.clone(), p(&[10.0, 0.0])).unwrap();
    let a = arc(
        p(&[10.0, 0.0]),
        p(&[10.0, 0.0]),
        p(&[0.0, 0.0]),
        Turn::Ccw,
        2,
    );
    pl.push_motion(motion(
        a,
        limits(500.0, 5000.0, f64::INFINITY),
        Join::Buffered,
        Transition::None,
        1,
    ))
    .unwrap();
    let (states, _) = run(&mut pl, 100_000);
    assert_eq!(states.last().unwrap().position, p(&[10.0, 0.0]));
    let pk = peaks(&states, &cfg);
    assert!(
        pk.a_fd <= 1.0 && pk.a_reported <= 1.0 + 1e-12,
        "{} {}",
        pk.a_fd,
        pk.a_reported
    );
    // Full circle speed: √(A/√2 · r) = √(707.1·10) ≈ 84 mm/s.
    let top = states.iter().map(|s| s.path_velocity).fold(0.0, f64::max);
    assert!(
        (top - (1000.0 * std::f64::consts::FRAC_1_SQRT_2 * 10.0f64).sqrt()).abs() < 1e-6,
        "{top}"
    );
    let _ = (Arc::from_center, Segment::length);
}
