//! The planner's fixed cases (issue 11 tests): exact stops, markers, halt/resume/stop/abort,
//! override, corner blends, LinuxCNC #3773, a 5-turn helix.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use path::geometry::{norm, sub, Arc, Segment, Turn};
use path::planner::{
    Join, MarkerKind, PathEvent, PathPlanner, PathState, PlannerConfig, Transition,
};

fn square_config() -> PlannerConfig {
    PlannerConfig::uniform(2, axis(100.0, 1000.0, f64::INFINITY), 1e-3)
}

/// The lowest path speed among `states`.
fn slowest(states: &[&PathState]) -> f64 {
    states
        .iter()
        .map(|s| s.path_velocity)
        .fold(f64::INFINITY, f64::min)
}

/// Every axis within its velocity and acceleration limits (finite differences and reported).
fn assert_within_limits(states: &[PathState], cfg: &PlannerConfig) {
    let pk = peaks(states, cfg);
    assert!(pk.a_fd <= 1.0 && pk.v_fd <= 1.0, "{} {}", pk.a_fd, pk.v_fd);
    assert!(pk.a_reported <= 1.0 + 1e-12);
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

#[test]
fn a_square_with_corner_distance_stays_within_it_and_never_stops_at_a_corner() {
    for (d, deviation) in [(2.0, false), (0.5, true), (12.0, false)] {
        let cfg = square_config();
        let pts = [
            p(&[0.0, 0.0]),
            p(&[20.0, 0.0]),
            p(&[20.0, 20.0]),
            p(&[0.0, 20.0]),
            p(&[0.0, 0.0]),
        ];
        let mut pl = PathPlanner::new(cfg.clone(), pts[0]).unwrap();
        let tr = if deviation {
            Transition::CornerDeviation(d)
        } else {
            Transition::CornerDistance(d)
        };
        for i in 0..4 {
            let m = motion(
                line(pts[i], pts[i + 1], 2),
                limits(80.0, 800.0, f64::INFINITY),
                Join::BlendingLow,
                tr,
                i as u64,
            );
            pl.push_motion(m).unwrap();
        }
        assert_eq!(pl.queued(), 4);
        let (states, events) = run(&mut pl, 100_000);
        assert_eq!(states.last().unwrap().position, pts[4]);
        let done: Vec<_> = events
            .iter()
            .filter_map(|e| match e {
                PathEvent::Done { tag } => Some(*tag),
                _ => None,
            })
            .collect();
        assert_eq!(done, vec![0, 1, 2, 3]);
        // Within d of the programmed square (deviation e: within e).
        let worst = states
            .iter()
            .map(|s| distance_to_polyline(&s.position, &pts))
            .fold(0.0, f64::max);
        assert!(worst <= d + 1e-9, "d = {d}: {worst}");
        // The speed does not drop to 0 at the three inner corners.
        for c in &pts[1..4] {
            let near: Vec<_> = states
                .iter()
                .filter(|s| (s.position[0] - c[0]).hypot(s.position[1] - c[1]) < d.min(10.0) + 0.5)
                .collect();
            let slowest = slowest(&near);
            assert!(slowest > 1.0, "corner {c:?}: {slowest}");
        }
        assert_within_limits(&states, &cfg);
    }
}

/// LinuxCNC issue #3773: many small arcs (R ≈ 4 mm) joined tangentially, 1 kHz, 1750 mm/s²
/// per axis, a commanded speed far above what the arcs allow. LinuxCNC measured peak axis
/// accelerations of 1.9–8× the limit; here the finite-difference peak stays ≤ 1.00×.
#[test]
fn linuxcnc_3773_small_tangent_arcs_keep_the_acceleration_within_the_limit() {
    let cfg = PlannerConfig::uniform(3, axis(400.0, 1750.0, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0, 0.0, 0.0])).unwrap();
    for (i, seg) in linuxcnc_3773_arcs().into_iter().enumerate() {
        let m = motion(
            seg,
            limits(2000.0, 20_000.0, f64::INFINITY),
            Join::BlendingHigh,
            Transition::None,
            i as u64,
        );
        pl.push_motion(m).unwrap();
    }
    let end = pl.queue_end();
    let (states, _) = run(&mut pl, 1_000_000);
    assert_eq!(states.last().unwrap().position, end);
    let pk = peaks(&states, &cfg);
    assert!(
        pk.a_fd <= 1.0,
        "peak FD acceleration {}× the limit",
        pk.a_fd
    );
    assert!(pk.a_reported <= 1.0 + 1e-12 && pk.v_fd <= 1.0);
    // It does not crawl either: the arcs run at their curvature speed, √(A/√2·r) ≈ 70 mm/s.
    let top = states.iter().map(|s| s.path_velocity).fold(0.0, f64::max);
    assert!(top > 60.0, "{top}");
}

#[test]
fn a_five_turn_helix_ends_exactly_within_the_limits() {
    let cfg = PlannerConfig::uniform(3, axis(100.0, 1000.0, f64::INFINITY), 1e-3);
    let start = p(&[10.0, 0.0, 0.0]);
    let mut pl = PathPlanner::new(cfg.clone(), start).unwrap();
    let helix = Arc::from_center(
        start,
        p(&[10.0, 0.0, 25.0]),
        p(&[0.0, 0.0, 0.0]),
        (0, 1),
        Turn::Ccw,
        4,
        3,
    )
    .unwrap();
    assert!((helix.sweep() - 5.0 * std::f64::consts::TAU).abs() < 1e-12);
    pl.push_motion(motion(
        Segment::Arc(helix),
        limits(200.0, 2000.0, f64::INFINITY),
        Join::Buffered,
        Transition::None,
        5,
    ))
    .unwrap();
    let (states, events) = run(&mut pl, 1_000_000);
    assert_eq!(states.last().unwrap().position, p(&[10.0, 0.0, 25.0]));
    assert_eq!(
        events,
        vec![PathEvent::Started { tag: 5 }, PathEvent::Done { tag: 5 }]
    );
    let pk = peaks(&states, &cfg);
    assert!(pk.a_fd <= 1.0 && pk.v_fd <= 1.0 && pk.a_reported <= 1.0 + 1e-12);
    // z rises linearly with the path length: 5 mm per turn.
    let half = states
        .iter()
        .find(|s| s.travelled >= 0.5 * states.last().unwrap().travelled)
        .unwrap();
    assert!((half.position[2] - 12.5).abs() < 0.2, "{:?}", half.position);
}

fn long_line(pl: &mut PathPlanner, v: f64) {
    let m = motion(
        line(p(&[0.0, 0.0]), p(&[300.0, 400.0]), 2),
        limits(v, 400.0, f64::INFINITY),
        Join::Buffered,
        Transition::None,
        1,
    );
    pl.push_motion(m).unwrap();
}

#[test]
fn override_scales_the_path_speed_without_a_step_and_within_the_axis_limits() {
    for (factor, expected) in [(0.5, 20.0), (2.0, 80.0), (10.0, 125.0)] {
        // Axis velocity 100 along x with tangent 0.6 and 75 along y with tangent 0.8: the path
        // may go 125 at most.
        let mut cfg = square_config();
        cfg.axes[1].velocity = 100.0;
        let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0, 0.0])).unwrap();
        long_line(&mut pl, 40.0);
        let mut events = Vec::new();
        let mut states = vec![*pl.state()];
        for _ in 0..1000 {
            states.push(*pl.step(&mut events));
        }
        assert_eq!(pl.state().path_velocity, 40.0);
        pl.set_override(factor);
        for _ in 0..1000 {
            states.push(*pl.step(&mut events));
        }
        assert!(
            (pl.state().path_velocity - expected).abs() < 1e-9,
            "{factor}: {}",
            pl.state().path_velocity
        );
        let (rest, _) = run(&mut pl, 100_000);
        states.extend_from_slice(&rest[1..]);
        assert_eq!(states.last().unwrap().position, p(&[300.0, 400.0]));
        let pk = peaks(&states, &cfg);
        assert!(
            pk.v_fd <= 1.0 && pk.a_fd <= 1.0,
            "{factor}: {} {}",
            pk.v_fd,
            pk.a_fd
        );
        // No velocity step: the path speed changes by at most one period of acceleration.
        for w in states.windows(2) {
            assert!((w[1].path_velocity - w[0].path_velocity).abs() <= 400.0 * 1e-3 + 1e-9);
        }
    }
}

#[test]
fn a_one_axis_path_samples_like_the_axis_profile() {
    use profile::{Goal, Limits, MotionState, Options, Profile};
    for (target, jerk) in [(37.5, f64::INFINITY), (-12.25, 20_000.0), (0.3, 5_000.0)] {
        let cfg = PlannerConfig::uniform(1, axis(100.0, 1000.0, jerk), 1e-3);
        let mut pl = PathPlanner::new(cfg, p(&[0.0])).unwrap();
        let m = motion(
            line(p(&[0.0]), p(&[target]), 1),
            limits(1e4, 1e6, f64::INFINITY),
            Join::Buffered,
            Transition::None,
            1,
        );
        pl.push_motion(m).unwrap();
        let (states, _) = run(&mut pl, 100_000);
        let lim = Limits {
            velocity: 100.0,
            acceleration: 1000.0,
            deceleration: 1000.0,
            jerk,
        };
        let goal = Goal::Position {
            target,
            end_velocity: 0.0,
        };
        let axis = Profile::plan(MotionState::default(), goal, &lim, &Options::default()).unwrap();
        assert_eq!(states.len() - 1, (axis.duration() / 1e-3).ceil() as usize);
        for (n, st) in states.iter().enumerate() {
            let s = axis.sample(n as f64 * 1e-3);
            assert!(
                (st.position[0] - s.p).abs() <= 1e-9,
                "{n}: {} {}",
                st.position[0],
                s.p
            );
            assert!(
                (st.velocity[0] - s.v).abs() <= 1e-6,
                "{n}: {} {}",
                st.velocity[0],
                s.v
            );
            assert!((st.acceleration[0] - s.a).abs() <= 1e-6 || n == 0);
        }
        assert_eq!(states.last().unwrap().position[0], target);
    }
}

#[test]
fn the_same_inputs_give_bit_identical_states() {
    let go = || {
        let mut pl = PathPlanner::new(square_config(), p(&[0.0, 0.0])).unwrap();
        three_lines(&mut pl, Join::BlendingHigh);
        let mut events = Vec::new();
        let mut states = Vec::new();
        for i in 0..3000 {
            if i == 200 {
                pl.set_override(1.7);
            }
            if i == 400 {
                pl.halt(None);
            }
            if i == 600 {
                pl.resume();
            }
            states.push(*pl.step(&mut events));
        }
        (states, events)
    };
    assert_eq!(go(), go());
}

/// PLCopen Part 4 buffer modes at a collinear junction between a slow (10) and a fast (50)
/// motion: the junction velocity is the lower, the first's, the second's or the higher.
#[test]
fn buffer_modes_set_the_junction_velocity() {
    let cfg = PlannerConfig::uniform(1, axis(100.0, 1000.0, f64::INFINITY), 1e-3);
    for (join, slow_first, expected) in [
        (Join::BlendingLow, true, 10.0),
        (Join::BlendingPrevious, true, 10.0),
        (Join::BlendingNext, true, 50.0),
        (Join::BlendingHigh, true, 50.0),
        (Join::BlendingPrevious, false, 50.0),
        (Join::BlendingNext, false, 10.0),
        (Join::Buffered, true, 0.0),
    ] {
        let (v1, v2) = if slow_first {
            (10.0, 50.0)
        } else {
            (50.0, 10.0)
        };
        let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0])).unwrap();
        let m1 = motion(
            line(p(&[0.0]), p(&[20.0]), 1),
            limits(v1, 1000.0, f64::INFINITY),
            Join::Buffered,
            Transition::None,
            1,
        );
        let m2 = motion(
            line(p(&[20.0]), p(&[40.0]), 1),
            limits(v2, 1000.0, f64::INFINITY),
            join,
            Transition::None,
            2,
        );
        pl.push_motion(m1).unwrap();
        pl.push_motion(m2).unwrap();
        let (states, _) = run(&mut pl, 100_000);
        assert_eq!(states.last().unwrap().position, p(&[40.0]));
        // The velocity as the path passes x = 20 (interpolated between ticks).
        let i = states.iter().position(|s| s.position[0] >= 20.0).unwrap();
        let (a, b) = (&states[i - 1], &states[i]);
        let f = (20.0 - a.position[0]) / (b.position[0] - a.position[0]);
        let at_junction = a.path_velocity + f * (b.path_velocity - a.path_velocity);
        assert!(
            (at_junction - expected).abs() <= 1000.0 * 1e-3 + 1e-9,
            "{join:?} {slow_first}: {at_junction}"
        );
        // Each motion runs at its own velocity in its middle (x = 10 and x = 30).
        for (x, v) in [(10.0, v1), (30.0, v2)] {
            let s = states.iter().find(|s| s.position[0] >= x).unwrap();
            assert!(
                (s.path_velocity - v).abs() < 1e-9,
                "{join:?} at {x}: {}",
                s.path_velocity
            );
        }
        let pk = peaks(&states, &cfg);
        assert!(pk.a_fd <= 1.0 && pk.v_fd <= 1.0);
    }
}

/// HIMC TV 55 (digest 004 §6.4): a motion blends only if the next is queued before it ends.
/// Pushed after the corner arc would have begun, the corner is passed on the corner rule
/// (no arc: the path goes through the programmed corner); pushed after the end, the next
/// motion starts from rest.
#[test]
fn a_motion_pushed_too_late_for_its_corner_goes_through_the_corner() {
    let cfg = square_config();
    for late_at in [9.5, 10.0] {
        let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0, 0.0])).unwrap();
        let a = motion(
            line(p(&[0.0, 0.0]), p(&[10.0, 0.0]), 2),
            limits(50.0, 500.0, f64::INFINITY),
            Join::Buffered,
            Transition::None,
            1,
        );
        pl.push_motion(a).unwrap();
        let mut events = Vec::new();
        let mut states = vec![*pl.state()];
        while pl.state().position[0] < late_at && !pl.is_idle() {
            states.push(*pl.step(&mut events));
        }
        let b = motion(
            line(p(&[10.0, 0.0]), p(&[10.0, 10.0]), 2),
            limits(50.0, 500.0, f64::INFINITY),
            Join::BlendingHigh,
            Transition::CornerDistance(2.0),
            2,
        );
        pl.push_motion(b).unwrap();
        let (rest, _) = run(&mut pl, 100_000);
        states.extend_from_slice(&rest[1..]);
        assert_eq!(states.last().unwrap().position, p(&[10.0, 10.0]));
        let pts = [p(&[0.0, 0.0]), p(&[10.0, 0.0]), p(&[10.0, 10.0])];
        for s in &states {
            assert!(
                distance_to_polyline(&s.position, &pts) < 1e-9,
                "{late_at}: {:?}",
                s.position
            );
        }
    }
}

/// A halt with a low deceleration brakes across several short motions, on the path.
#[test]
fn a_halt_brakes_across_motion_ends_and_resume_goes_on() {
    let cfg = square_config();
    let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0, 0.0])).unwrap();
    for i in 0..40 {
        let (x0, x1) = (i as f64, i as f64 + 1.0);
        let m = motion(
            line(p(&[x0, 0.5 * x0]), p(&[x1, 0.5 * x1]), 2),
            limits(50.0, 1000.0, f64::INFINITY),
            Join::BlendingLow,
            Transition::None,
            i,
        );
        pl.push_motion(m).unwrap();
    }
    let mut events = Vec::new();
    let mut states = vec![*pl.state()];
    for _ in 0..200 {
        states.push(*pl.step(&mut events));
    }
    let v0 = pl.state().path_velocity;
    let done_before = pl.state().completed;
    assert!(v0 > 40.0);
    pl.halt(Some(100.0));
    while !events.contains(&PathEvent::AtRest) {
        states.push(*pl.step(&mut events));
    }
    // v²/(2·d) = 12.5 mm at 50 mm/s: about 12 motions of 1.1 mm.
    let crossed = pl.state().completed - done_before;
    assert!(crossed >= 8, "{crossed}");
    assert!(pl.state().halted);
    for w in states.windows(2).skip(201) {
        assert!(w[1].path_velocity <= w[0].path_velocity + 1e-9);
        assert!((w[1].path_velocity - w[0].path_velocity).abs() <= 100.0 * 1e-3 + 1e-9);
    }
    pl.resume();
    let (rest, _) = run(&mut pl, 100_000);
    states.extend_from_slice(&rest[1..]);
    assert_eq!(states.last().unwrap().position, p(&[40.0, 20.0]));
    assert_eq!(states.last().unwrap().completed, 40);
    let pk = peaks(&states, &cfg);
    assert!(pk.a_fd <= 1.0 && pk.v_fd <= 1.0);
}

/// Dense G-code: 0.05 mm lines at 1 kHz. Each motion's speed is capped at its length per
/// period, so a step starts at most two motions, and the look-ahead work per step stays
/// within the window.
#[test]
fn dense_short_lines_start_a_bounded_number_of_motions_per_step() {
    let mut cfg = PlannerConfig::uniform(2, axis(200.0, 2000.0, f64::INFINITY), 1e-3);
    cfg.capacity = 1024;
    let mut pl = PathPlanner::new(cfg, p(&[0.0, 0.0])).unwrap();
    let (mut at, mut heading) = (p(&[0.0, 0.0]), 0.0f64);
    let mut events = Vec::new();
    let (mut pushed, mut max_starts, mut max_visits, mut top) = (0, 0, 0, 0.0f64);
    while pushed < 3000 || !pl.is_idle() {
        while pushed < 3000 && pl.queued() < 1024 {
            heading += if pushed % 7 < 3 { 0.02 } else { -0.015 };
            let to = p(&[at[0] + 0.05 * heading.cos(), at[1] + 0.05 * heading.sin()]);
            let m = motion(
                line(at, to, 2),
                limits(150.0, 3000.0, f64::INFINITY),
                Join::BlendingLow,
                Transition::None,
                pushed,
            );
            pl.push_motion(m).unwrap();
            at = to;
            pushed += 1;
        }
        let st = *pl.step(&mut events);
        top = top.max(st.path_velocity);
        max_starts = max_starts.max(pl.starts_last_step());
        max_visits = max_visits.max(pl.lookahead_visits());
    }
    assert_eq!(pl.state().position, at);
    assert_eq!(pl.state().completed, 3000);
    assert!(max_starts <= 2, "{max_starts}");
    assert!(max_visits <= 64, "{max_visits}");
    // Length per period: 0.05 mm / 1 ms = 50 mm/s.
    assert!(top <= 50.0 + 1e-9 && top > 45.0, "{top}");
}

/// Corners between lines and arcs, arcs and lines, and two arcs (issue 11 item 4): rounded
/// within the corner distance or deviation, passed well above the corner rule's speed
/// (A·T/|Δt| = 0.7 mm/s here), within every axis's limits.
#[test]
fn corners_with_arcs_are_blended_within_the_tolerance_without_stopping() {
    let segments = [
        line(p(&[0.0, 0.0]), p(&[20.0, 0.0]), 2),
        arc(
            p(&[20.0, 0.0]),
            p(&[30.0, -10.0]),
            p(&[30.0, 0.0]),
            Turn::Ccw,
            2,
        ),
        line(p(&[30.0, -10.0]), p(&[30.0, -30.0]), 2),
        arc(
            p(&[30.0, -30.0]),
            p(&[20.0, -40.0]),
            p(&[30.0, -40.0]),
            Turn::Ccw,
            2,
        ),
        arc(
            p(&[20.0, -40.0]),
            p(&[10.0, -50.0]),
            p(&[20.0, -50.0]),
            Turn::Ccw,
            2,
        ),
    ];
    let corners = [
        p(&[20.0, 0.0]),
        p(&[30.0, -10.0]),
        p(&[30.0, -30.0]),
        p(&[20.0, -40.0]),
    ];
    for tr in [
        Transition::CornerDistance(2.0),
        Transition::CornerDeviation(0.5),
    ] {
        let tol = match tr {
            Transition::CornerDistance(x) | Transition::CornerDeviation(x) => x,
            Transition::None => 0.0,
        };
        let cfg = square_config();
        let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0, 0.0])).unwrap();
        for (i, s) in segments.iter().enumerate() {
            let m = motion(
                s.clone(),
                limits(80.0, 800.0, f64::INFINITY),
                Join::BlendingLow,
                tr,
                i as u64,
            );
            pl.push_motion(m).unwrap();
        }
        let (states, _) = run(&mut pl, 100_000);
        assert_eq!(states.last().unwrap().position, p(&[10.0, -50.0]));
        let worst = states
            .iter()
            .map(|s| distance_to_path(&s.position, &segments))
            .fold(0.0, f64::max);
        assert!(worst <= tol + 1e-9, "{tr:?}: {worst}");
        for c in &corners {
            let near: Vec<_> = states
                .iter()
                .filter(|s| close(&s.position, c, tol + 0.5))
                .collect();
            // The path leaves the corner point (a blend), and does not crawl past it.
            let closest = near
                .iter()
                .map(|s| norm(&sub(&s.position, c)))
                .fold(f64::INFINITY, f64::min);
            assert!(closest > 0.01 * tol, "{tr:?} corner {c:?}: {closest}");
            let slowest = slowest(&near);
            assert!(slowest > 5.0, "{tr:?} corner {c:?}: {slowest}");
        }
        assert_within_limits(&states, &cfg);
    }
}

/// Issue 11 defect: at a corner without geometry (`Transition::None`, a blending join) the
/// finite-difference acceleration of an axis reached 2× its limit (the velocity step of the
/// corner rule on top of the motions' own acceleration). Now within 1×.
#[test]
fn a_corner_without_geometry_keeps_the_finite_difference_acceleration_within_the_limit() {
    for (turn, jerk) in [(90.0f64, f64::INFINITY), (30.0, f64::INFINITY), (60.0, 1e5)] {
        let cfg = square_config();
        let (s, c) = turn.to_radians().sin_cos();
        let corner = p(&[10.0, 0.0]);
        let end = p(&[10.0 + 10.0 * c, 10.0 * s]);
        let mut pl = PathPlanner::new(cfg.clone(), p(&[0.0, 0.0])).unwrap();
        for (i, (a, b)) in [(p(&[0.0, 0.0]), corner), (corner, end)].iter().enumerate() {
            let m = motion(
                line(*a, *b, 2),
                limits(80.0, 800.0, jerk),
                Join::BlendingHigh,
                Transition::None,
                i as u64,
            );
            pl.push_motion(m).unwrap();
        }
        let (states, _) = run(&mut pl, 100_000);
        assert_eq!(states.last().unwrap().position, end);
        // The corner is passed moving (a velocity step), not at rest.
        let at_corner = states
            .iter()
            .filter(|s| close(&s.position, &corner, 0.05))
            .map(|s| s.path_velocity)
            .fold(0.0, f64::max);
        assert!(at_corner > 0.0);
        let pk = peaks(&states, &cfg);
        assert!(pk.a_fd <= 1.0, "turn {turn}: FD a {}× the limit", pk.a_fd);
        assert!(pk.a_reported <= 1.0 + 1e-12);
    }
}
