//! An e-stop that keeps the path (issue 13, NMC `CrdEstopMtn` then `CrdGotoBreak`): the
//! planner frozen mid-motion, a return line put in front of the remainder, the program
//! finished from the break exactly as programmed.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use path::geometry::{norm, sub, Segment, Turn};
use path::planner::{Join, PathEvent, PathPlanner, PlannerConfig, Transition};

fn program() -> Vec<Segment> {
    vec![
        line(p(&[0.0, 0.0]), p(&[10.0, 0.0]), 2),
        line(p(&[10.0, 0.0]), p(&[10.0, 10.0]), 2),
        arc(
            p(&[10.0, 10.0]),
            p(&[0.0, 10.0]),
            p(&[5.0, 10.0]),
            Turn::Ccw,
            2,
        ),
    ]
}

fn planner() -> PathPlanner {
    let cfg = PlannerConfig::uniform(2, axis(100.0, 1000.0, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg, p(&[0.0, 0.0])).unwrap();
    for (tag, s) in program().into_iter().enumerate() {
        let m = motion(
            s,
            limits(20.0, 200.0, f64::INFINITY),
            Join::Buffered,
            Transition::None,
            tag as u64,
        );
        pl.push_motion(m).unwrap();
    }
    pl
}

fn done_tags(events: &[PathEvent]) -> Vec<u64> {
    events
        .iter()
        .filter_map(|e| match e {
            PathEvent::Done { tag } => Some(*tag),
            _ => None,
        })
        .collect()
}

/// What is left of programmed motion `tag` from the break `at` on.
fn remainder_of(tag: u64, at: &path::Point) -> Segment {
    let s = program()[tag as usize].clone();
    let mut best = (f64::INFINITY, 0.0);
    let n = 100_000;
    for i in 0..=n {
        let x = s.length() * i as f64 / n as f64;
        let d = norm(&sub(&s.sample(x).p, at));
        if d < best.0 {
            best = (d, x);
        }
    }
    s.trimmed(best.1, s.length())
}

/// Freeze after `ticks` steps, the axes off the path by `(dx, dy)`, return, resume.
fn break_and_return(ticks: usize, dx: f64, dy: f64, breaking_in: u64) {
    let mut pl = planner();
    let mut events = Vec::new();
    for _ in 0..ticks {
        pl.step(&mut events);
    }
    assert_eq!(
        pl.state().tag,
        Some(breaking_in),
        "the break is in that motion"
    );
    assert!(
        pl.state().path_velocity > 0.0,
        "moving when the e-stop comes"
    );
    let done_before = done_tags(&events);
    pl.freeze();
    let at = pl.state().position;
    assert_eq!(pl.state().path_velocity, 0.0);
    // Frozen: steps go nowhere.
    let mut frozen = Vec::new();
    for _ in 0..50 {
        assert_eq!(pl.step(&mut frozen).position, at);
    }
    assert!(frozen.is_empty(), "{frozen:?}");
    assert_eq!(pl.queued(), program().len() - done_before.len());
    // The axes ramped down off the path: the return line goes from there to the break.
    let off = p(&[at[0] + dx, at[1] + dy]);
    let back = motion(
        line(off, at, 2),
        limits(5.0, 50.0, f64::INFINITY),
        Join::Buffered,
        Transition::None,
        99,
    );
    pl.resume();
    // Not frozen any more: refused (the return goes in front of a path halted at rest).
    assert!(pl.insert_front(back.clone()).is_err());
    pl.freeze();
    pl.insert_front(back).unwrap();
    assert_eq!(pl.state().position, off);
    pl.resume();
    let (states, after) = run(&mut pl, 200_000);
    assert!(pl.is_idle());
    let mut expected = vec![99];
    expected.extend((done_before.len() as u64)..program().len() as u64);
    assert_eq!(done_tags(&after), expected, "every remaining motion ends");
    let last = states.last().unwrap();
    assert!(close(&last.position, &p(&[0.0, 10.0]), 1e-9), "{last:?}");
    // From the break on, the path is the programmed one (no point off it).
    let returned = states
        .iter()
        .position(|s| s.tag.is_some_and(|t| t != 99))
        .unwrap();
    for s in &states[..returned] {
        let d = distance_to_segment(&s.position, &line(off, at, 2));
        assert!(d < 1e-9, "return line: {d}");
    }
    for s in &states[returned..] {
        let d = distance_to_path(&s.position, &program());
        assert!(d < 1e-9, "{:?} is {d} off the path", s.position);
    }
    // The remainder starts at the break (nothing of the cut motion is run twice or skipped):
    // the tick that ends the return line goes on into the remainder, within one period of
    // either side of the break (20 units/s × 1 ms).
    let step = 20.0 * 1e-3 + 1e-9;
    assert!(norm(&sub(&states[returned - 1].position, &at)) <= step);
    assert!(norm(&sub(&states[returned].position, &at)) <= step);
    let first_after =
        distance_to_segment(&states[returned].position, &remainder_of(breaking_in, &at));
    assert!(first_after < 1e-9, "{first_after}");
}

#[test]
fn a_frozen_line_is_finished_from_the_break_after_a_return() {
    // 20 units/s reached after 0.1 s (1 unit): 300 ticks are 5 units into the first line.
    break_and_return(300, 0.5, -0.75, 0);
}

#[test]
fn a_frozen_arc_is_cut_by_its_centre_and_end() {
    // The lines take about 0.6 s each; 1500 ticks are part-way round the arc.
    break_and_return(1500, -0.4, 0.3, 2);
}
