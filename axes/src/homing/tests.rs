//! Tests of the homing machine against the kinematic test double in `sim.rs`.

use super::sim::{run, run_sim, run_with, Layout, Run, Sim, DT};
use super::*;

const SWITCH_V: f64 = 20.0;
const ZERO_V: f64 = 5.0;
const ACC: f64 = 2000.0;
const OFFSET: f64 = 7.5;
const EPS: f64 = 1e-9;

fn spec(method: i16) -> HomingSpec {
    HomingSpec {
        method,
        switch_velocity: SWITCH_V,
        zero_velocity: ZERO_V,
        acceleration: ACC,
        offset: OFFSET,
        timeout: 0.0,
        quirks: HomingQuirks::default(),
    }
}

fn with(method: i16, quirks: HomingQuirks) -> HomingSpec {
    HomingSpec {
        quirks,
        ..spec(method)
    }
}

const ALL: HomingHardware = HomingHardware::ALL;

// Physical start positions (layouts in sim.rs: limits ±100, cam [10, 30], index 4k + 1).
const LEFT: f64 = 0.0;
const INSIDE: f64 = 20.0;
const RIGHT: f64 = 50.0;
const ON_POS_LIMIT: f64 = 100.5;
const ON_NEG_LIMIT: f64 = -100.5;

struct Case {
    method: i16,
    layout: fn() -> Layout,
    start: f64,
    /// Physical home point.
    home: f64,
    /// Directions of travel.
    dirs: &'static [i8],
}

const fn case(
    method: i16,
    layout: fn() -> Layout,
    start: f64,
    home: f64,
    dirs: &'static [i8],
) -> Case {
    Case {
        method,
        layout,
        start,
        home,
        dirs,
    }
}

/// Every supported switch/index method from every starting region its CiA 402 diagram covers.
/// Methods 17–30 are 1–14 without the index: the same travel, home at the edge.
fn matrix() -> Vec<Case> {
    let cam = Layout::cam as fn() -> Layout;
    let pos = Layout::positive_switch as fn() -> Layout;
    let neg = Layout::negative_switch as fn() -> Layout;
    // (method with index, layout, start, index home, edge home, dirs)
    type Row = (i16, fn() -> Layout, f64, f64, f64, &'static [i8]);
    let rows: Vec<Row> = vec![
        // 1/17: negative limit; 2/18: positive limit.
        (1, cam, LEFT, -99.0, -100.0, &[-1, 1]),
        (1, cam, ON_NEG_LIMIT, -99.0, -100.0, &[1]),
        (2, cam, LEFT, 97.0, 100.0, &[1, -1]),
        (2, cam, ON_POS_LIMIT, 97.0, 100.0, &[-1]),
        // 3/19, 4/20: positive home switch (active x ≥ 10); 5/21, 6/22: negative (x ≤ 30).
        (3, pos, LEFT, 9.0, 10.0, &[1, -1]),
        (3, pos, INSIDE, 9.0, 10.0, &[-1]),
        (4, pos, LEFT, 13.0, 10.0, &[1]),
        (4, pos, INSIDE, 13.0, 10.0, &[-1, 1]),
        (5, neg, RIGHT, 33.0, 30.0, &[-1, 1]),
        (5, neg, INSIDE, 33.0, 30.0, &[1]),
        (6, neg, RIGHT, 29.0, 30.0, &[-1]),
        (6, neg, INSIDE, 29.0, 30.0, &[1, -1]),
        // 7–10/23–26: cam with the positive limit as reversal.
        (7, cam, LEFT, 9.0, 10.0, &[1, -1]),
        (7, cam, INSIDE, 9.0, 10.0, &[-1]),
        (7, cam, RIGHT, 9.0, 10.0, &[1, -1]),
        (7, cam, ON_POS_LIMIT, 9.0, 10.0, &[-1]),
        (8, cam, LEFT, 13.0, 10.0, &[1]),
        (8, cam, INSIDE, 13.0, 10.0, &[-1, 1]),
        (8, cam, RIGHT, 13.0, 10.0, &[1, -1, 1]),
        (8, cam, ON_POS_LIMIT, 13.0, 10.0, &[-1, 1]),
        (9, cam, LEFT, 29.0, 30.0, &[1, -1]),
        (9, cam, INSIDE, 29.0, 30.0, &[1, -1]),
        (9, cam, RIGHT, 29.0, 30.0, &[1, -1]),
        (9, cam, ON_POS_LIMIT, 29.0, 30.0, &[-1]),
        (10, cam, LEFT, 33.0, 30.0, &[1]),
        (10, cam, INSIDE, 33.0, 30.0, &[1]),
        (10, cam, RIGHT, 33.0, 30.0, &[1, -1, 1]),
        (10, cam, ON_POS_LIMIT, 33.0, 30.0, &[-1, 1]),
        // 11–14/27–30: cam with the negative limit as reversal (mirror images of 7–10).
        (11, cam, RIGHT, 33.0, 30.0, &[-1, 1]),
        (11, cam, INSIDE, 33.0, 30.0, &[1]),
        (11, cam, LEFT, 33.0, 30.0, &[-1, 1]),
        (11, cam, ON_NEG_LIMIT, 33.0, 30.0, &[1]),
        (12, cam, RIGHT, 29.0, 30.0, &[-1]),
        (12, cam, INSIDE, 29.0, 30.0, &[1, -1]),
        (12, cam, LEFT, 29.0, 30.0, &[-1, 1, -1]),
        (12, cam, ON_NEG_LIMIT, 29.0, 30.0, &[1, -1]),
        (13, cam, RIGHT, 13.0, 10.0, &[-1, 1]),
        (13, cam, INSIDE, 13.0, 10.0, &[-1, 1]),
        (13, cam, LEFT, 13.0, 10.0, &[-1, 1]),
        (13, cam, ON_NEG_LIMIT, 13.0, 10.0, &[1]),
        (14, cam, RIGHT, 9.0, 10.0, &[-1]),
        (14, cam, INSIDE, 9.0, 10.0, &[-1]),
        (14, cam, LEFT, 9.0, 10.0, &[-1, 1, -1]),
        (14, cam, ON_NEG_LIMIT, 9.0, 10.0, &[1, -1]),
    ];
    let mut cases = Vec::new();
    for (m, layout, start, index_home, edge_home, dirs) in rows {
        cases.push(case(m, layout, start, index_home, dirs));
        cases.push(case(m + 16, layout, start, edge_home, dirs));
    }
    cases.push(case(33, cam, LEFT, -3.0, &[-1]));
    cases.push(case(33, cam, INSIDE, 17.0, &[-1]));
    cases.push(case(34, cam, LEFT, 1.0, &[1]));
    cases.push(case(34, cam, INSIDE, 21.0, &[1]));
    cases
}

fn approach(method: i16) -> f64 {
    match method::MethodDef::lookup(method) {
        Ok(def) => def.approach.sign(),
        Err(e) => panic!("{e}"),
    }
}

fn check_success(r: &Run, what: &str) {
    assert_eq!(r.result, Some(Ok(())), "{what}: {r:?}");
    assert_eq!(r.final_v, 0.0, "{what}: not at rest");
}

#[test]
fn homing_every_method_from_every_region() {
    let cases = matrix();
    // 44 rows × (with, without index) + 4 index-only runs.
    assert_eq!(cases.len(), 92);
    for c in cases {
        let what = format!("method {} from {}", c.method, c.start);
        let r = run(&spec(c.method), ALL, (c.layout)(), c.start);
        check_success(&r, &what);
        let home = r.home.unwrap_or(f64::NAN);
        assert!(
            (home - c.home).abs() < EPS,
            "{what}: home at {home}, want {}",
            c.home
        );
        assert_eq!(r.dirs, c.dirs, "{what}: directions");
        // CiA 402: decelerate after the home event, in the approach direction; the home point
        // reads the offset.
        let overshoot = (r.final_x - home) * approach(c.method);
        let speed = r.detect_speed.unwrap_or(f64::NAN);
        let bound = speed * speed / (2.0 * ACC) + 2.0 * speed * DT + EPS;
        assert!(
            (-EPS..=bound).contains(&overshoot),
            "{what}: overshoot {overshoot} > {bound}"
        );
        assert!(
            (r.final_reading - (OFFSET + r.final_x - home)).abs() < EPS,
            "{what}: frame"
        );
    }
}

#[test]
fn homing_final_approach_uses_zero_velocity_after_a_reversal() {
    // Method 7 from the left: search at the switch velocity, reverse, cross the edge slowly.
    let r = run(&spec(7), ALL, Layout::cam(), LEFT);
    check_success(&r, "7");
    let speed = r.detect_speed.unwrap_or(f64::NAN);
    assert!((speed - ZERO_V).abs() < EPS, "index found at {speed}");
    let velocities: Vec<f64> = r
        .outputs
        .iter()
        .filter_map(|o| match o.motion {
            Some(MotionRequest::Velocity { velocity, .. }) => Some(velocity),
            _ => None,
        })
        .collect();
    assert_eq!(velocities, vec![SWITCH_V, -ZERO_V]);
    assert_eq!(
        r.phases,
        vec![
            HomingPhase::Search,
            HomingPhase::Reversing,
            HomingPhase::Approach,
            HomingPhase::Index,
            HomingPhase::Stopping
        ]
    );
}

#[test]
fn homing_current_position_methods() {
    for method in [35, 37] {
        let r = run(
            &spec(method),
            HomingHardware::default(),
            Layout::cam(),
            42.25,
        );
        check_success(&r, "35/37");
        assert_eq!(r.home, Some(42.25));
        assert_eq!(r.final_reading, OFFSET);
        assert!(r.outputs.iter().all(|o| o.motion.is_none()));
        assert_eq!(r.ticks, 0, "done in the first step");
    }
    // Speeds are irrelevant for 37 (HIWIN: the drive need not even move).
    let s = HomingSpec {
        switch_velocity: 0.0,
        zero_velocity: 0.0,
        acceleration: 0.0,
        ..spec(37)
    };
    check_success(&run(&s, ALL, Layout::cam(), 1.0), "37 no speeds");
}

#[test]
fn homing_narrow_cam_overshoot_is_recovered() {
    // The stop after entering a 0.05 wide cam at 20 units/s overshoots it (0.1 units).
    let layout = Layout {
        home: Some((10.0, 10.05)),
        ..Layout::cam()
    };
    let r = run(&spec(7), ALL, layout, LEFT);
    check_success(&r, "narrow");
    assert_eq!(r.home, Some(9.0));
    assert_eq!(r.dirs, vec![1, -1]);
    let r = run(&spec(23), ALL, layout, LEFT);
    assert_eq!(r.home, Some(10.0));
}

#[test]
fn homing_unsupported_methods() {
    for method in [i16::MIN, -1, 0, 15, 16, 31, 32, 36, 38, 100, i16::MAX] {
        let r = run(&spec(method), ALL, Layout::cam(), LEFT);
        assert_eq!(
            r.result,
            Some(Err(HomingError::UnsupportedMethod { method })),
            "{method}"
        );
        assert!(r.outputs.is_empty());
    }
}

#[test]
fn homing_missing_hardware_is_refused_at_start() {
    use HomingInput::*;
    let without = |f: fn(&mut HomingHardware)| {
        let mut hw = ALL;
        f(&mut hw);
        hw
    };
    let no_neg = without(|h| h.limit_neg = false);
    let no_pos = without(|h| h.limit_pos = false);
    let no_home = without(|h| h.home = false);
    let no_index = without(|h| h.index = false);
    let cases = [
        (1, no_neg, NegativeLimit),
        (1, no_index, Index),
        (2, no_pos, PositiveLimit),
        (3, no_home, HomeSwitch),
        (6, no_index, Index),
        (7, no_pos, PositiveLimit),
        (10, no_home, HomeSwitch),
        (11, no_neg, NegativeLimit),
        (14, no_index, Index),
        (17, no_neg, NegativeLimit),
        (18, no_pos, PositiveLimit),
        (21, no_home, HomeSwitch),
        (23, no_pos, PositiveLimit),
        (30, no_neg, NegativeLimit),
        (33, no_index, Index),
        (34, no_index, Index),
    ];
    for (method, hw, input) in cases {
        let r = run(&spec(method), hw, Layout::cam(), LEFT);
        assert_eq!(
            r.result,
            Some(Err(HomingError::MissingInput { method, input })),
            "{method}"
        );
    }
    // What each method does not need may be missing.
    let only = |f: fn(&mut HomingHardware)| {
        let mut hw = HomingHardware::default();
        f(&mut hw);
        hw
    };
    check_success(
        &run(
            &spec(19),
            only(|h| h.home = true),
            Layout::positive_switch(),
            LEFT,
        ),
        "19 home only",
    );
    check_success(
        &run(&spec(34), only(|h| h.index = true), Layout::cam(), LEFT),
        "34 index only",
    );
    check_success(
        &run(&spec(17), only(|h| h.limit_neg = true), Layout::cam(), LEFT),
        "17 limit only",
    );
}

#[test]
fn homing_bad_parameters_are_refused_at_start() {
    let bad = [
        HomingSpec {
            switch_velocity: 0.0,
            ..spec(19)
        },
        HomingSpec {
            zero_velocity: -5.0,
            ..spec(19)
        },
        HomingSpec {
            acceleration: f64::NAN,
            ..spec(33)
        },
        HomingSpec {
            timeout: -1.0,
            ..spec(19)
        },
        HomingSpec {
            offset: f64::INFINITY,
            ..spec(37)
        },
        with(
            19,
            HomingQuirks {
                rescan: Some(-1.0),
                ..HomingQuirks::default()
            },
        ),
    ];
    for s in bad {
        let r = run(&s, ALL, Layout::cam(), LEFT);
        assert!(
            matches!(r.result, Some(Err(HomingError::BadParameter { .. }))),
            "{s:?}: {r:?}"
        );
        assert!(r.outputs.is_empty(), "no motion");
    }
}

#[test]
fn homing_timeout_stops_then_fails() {
    // An index method without index pulses never finds its home point.
    let layout = Layout {
        index_pitch: 0.0,
        limit_neg: None,
        ..Layout::cam()
    };
    let s = HomingSpec {
        timeout: 0.5,
        ..spec(33)
    };
    let r = run(&s, ALL, layout, LEFT);
    assert_eq!(r.result, Some(Err(HomingError::Timeout { seconds: 0.5 })));
    assert_eq!(r.final_v, 0.0);
    assert!(r.time >= 0.5 && r.time < 0.5 + 0.01, "{}", r.time);
    assert_eq!(r.phases.last(), Some(&HomingPhase::Aborting));
    assert!(matches!(
        r.outputs.iter().rev().find_map(|o| o.motion),
        Some(MotionRequest::Stop { .. })
    ));
}

#[test]
fn homing_search_distance_exhausted() {
    let q = HomingQuirks {
        max_search_distance: 3.0,
        ..HomingQuirks::default()
    };
    let layout = Layout {
        index_pitch: 0.0,
        ..Layout::cam()
    };
    let r = run(&with(34, q), ALL, layout, LEFT);
    assert_eq!(
        r.result,
        Some(Err(HomingError::NotFound {
            input: HomingInput::Index,
            distance: 3.0
        }))
    );
    assert!(r.final_x < 3.1);
    let q = HomingQuirks {
        max_search_distance: 20.0,
        ..HomingQuirks::default()
    };
    let r = run(&with(20, q), ALL, Layout::positive_switch(), -50.0);
    assert_eq!(
        r.result,
        Some(Err(HomingError::NotFound {
            input: HomingInput::HomeSwitch,
            distance: 20.0
        }))
    );
    // Within the distance it succeeds.
    check_success(
        &run(&with(20, q), ALL, Layout::positive_switch(), -5.0),
        "near",
    );
}

#[test]
fn homing_cam_not_found_between_the_limits() {
    let layout = Layout {
        home: None,
        ..Layout::cam()
    };
    for method in [7, 12, 26, 27] {
        let r = run(&spec(method), ALL, layout, LEFT);
        assert!(
            matches!(
                r.result,
                Some(Err(HomingError::NotFound {
                    input: HomingInput::HomeSwitch,
                    ..
                }))
            ),
            "{method}: {r:?}"
        );
        assert_eq!(r.dirs.len(), 2, "{method}: reversed once, then gave up");
    }
}

#[test]
fn homing_unexpected_limit_is_an_error() {
    use crate::command::Direction::{Negative, Positive};
    let far = |home: (f64, f64)| Layout {
        home: Some(home),
        ..Layout::cam()
    };
    let cases = [
        // Home switch beyond the limit: methods 3–6, 19–22 do not reverse.
        (3, far((150.0, f64::INFINITY)), Positive),
        (20, far((150.0, f64::INFINITY)), Positive),
        (5, far((f64::NEG_INFINITY, -150.0)), Negative),
        (22, far((f64::NEG_INFINITY, -150.0)), Negative),
        // Index-only methods do not reverse either.
        (
            33,
            Layout {
                index_pitch: 0.0,
                ..Layout::cam()
            },
            Negative,
        ),
        // Method 1 leaves the negative limit and finds no index before the positive one.
        (
            1,
            Layout {
                index_pitch: 0.0,
                ..Layout::cam()
            },
            Positive,
        ),
    ];
    for (method, layout, direction) in cases {
        let r = run(&spec(method), ALL, layout, LEFT);
        assert_eq!(
            r.result,
            Some(Err(HomingError::LimitHit { direction })),
            "{method}"
        );
        assert_eq!(r.final_v, 0.0);
    }
    // Starting on the limit in the search direction fails without moving.
    let r = run(&spec(34), ALL, Layout::cam(), ON_POS_LIMIT);
    assert_eq!(
        r.result,
        Some(Err(HomingError::LimitHit {
            direction: Positive
        }))
    );
    assert!(r.dirs.is_empty());
}

#[test]
fn homing_return_to_home_ends_at_the_offset_exactly() {
    let q = HomingQuirks {
        after_home: AfterHome::ReturnToHome,
        ..HomingQuirks::default()
    };
    for (method, layout, start) in [
        (19, Layout::positive_switch(), LEFT),
        (8, Layout::cam(), RIGHT),
        (34, Layout::cam(), LEFT),
    ] {
        let r = run(&with(method, q), ALL, layout, start);
        check_success(&r, "return");
        assert!(
            (r.final_reading - OFFSET).abs() < EPS,
            "{}",
            r.final_reading
        );
        assert!((r.final_x - r.home.unwrap_or(f64::NAN)).abs() < EPS);
        assert_eq!(r.phases.last(), Some(&HomingPhase::Returning));
        // The return leg goes against the approach direction.
        let a = approach(method) as i8;
        assert_eq!(r.dirs.last(), Some(&-a));
    }
}

#[test]
fn homing_stop_immediately_has_no_deceleration_distance() {
    let q = HomingQuirks {
        after_home: AfterHome::StopImmediately,
        ..HomingQuirks::default()
    };
    // Method 24 from the left crosses the home edge at the switch velocity.
    let r = run(&with(24, q), ALL, Layout::cam(), LEFT);
    check_success(&r, "stop immediately");
    assert_eq!(Some(r.final_x), r.detect_x);
    assert!(r.final_x - 10.0 <= SWITCH_V * DT + EPS);
    // With deceleration the same run ends farther.
    let d = run(&spec(24), ALL, Layout::cam(), LEFT);
    assert!(
        d.final_x - r.final_x > 0.05,
        "{} vs {}",
        d.final_x,
        r.final_x
    );
}

#[test]
fn homing_polled_latch_is_late_by_up_to_one_tick() {
    let q = HomingQuirks {
        switch_latch: Latch::Polled,
        index_latch: Latch::Polled,
        ..HomingQuirks::default()
    };
    let mut max_late: f64 = 0.0;
    for k in 0..20 {
        let start = LEFT - 0.001 * f64::from(k);
        let exact = run(&spec(24), ALL, Layout::cam(), start);
        assert_eq!(exact.home, Some(10.0));
        let polled = run(&with(24, q), ALL, Layout::cam(), start);
        check_success(&polled, "polled");
        let late = polled.home.unwrap_or(f64::NAN) - 10.0;
        assert!((0.0..=SWITCH_V * DT + EPS).contains(&late), "{late}");
        max_late = max_late.max(late);
        // The home point reads the offset: the reading is off by the latch error.
        assert!((polled.final_reading - OFFSET - (polled.final_x - 10.0 - late)).abs() < EPS);
    }
    assert!(max_late > 0.5 * SWITCH_V * DT, "{max_late}");
    // The index too, at the zero velocity.
    let r = run(&with(34, q), ALL, Layout::cam(), 0.0004);
    let late = r.home.unwrap_or(f64::NAN) - 1.0;
    assert!(late > 0.0 && late <= ZERO_V * DT + EPS, "{late}");
}

#[test]
fn homing_switch_sampling_delays_detection() {
    const N: u32 = 10;
    let sampled = |latch| HomingQuirks {
        switch_scan_ticks: N,
        switch_latch: latch,
        ..HomingQuirks::default()
    };
    let window = f64::from(N) * SWITCH_V * DT;
    let (mut max_polled, mut max_detect): (f64, f64) = (0.0, 0.0);
    for k in 0..25 {
        let start = LEFT - 0.0137 * f64::from(k);
        // Polled (CPU 226H): the origin itself is late by up to N ticks of travel.
        let r = run(&with(24, sampled(Latch::Polled)), ALL, Layout::cam(), start);
        check_success(&r, "sampled polled");
        let late = r.home.unwrap_or(f64::NAN) - 10.0;
        assert!((0.0..=window + EPS).contains(&late), "{late}");
        max_polled = max_polled.max(late);
        // Exact latch: the origin is exact, only the reaction is late.
        let r = run(&with(24, sampled(Latch::Exact)), ALL, Layout::cam(), start);
        assert_eq!(r.home, Some(10.0));
        let detect = r.detect_x.unwrap_or(f64::NAN) - 10.0;
        assert!((0.0..=window + EPS).contains(&detect), "{detect}");
        max_detect = max_detect.max(detect);
    }
    assert!(max_polled > 2.0 * SWITCH_V * DT, "{max_polled}");
    assert!(max_detect > 2.0 * SWITCH_V * DT, "{max_detect}");
    // The index is not sampled: method 8 still homes on the exact index.
    let r = run(&with(8, sampled(Latch::Polled)), ALL, Layout::cam(), LEFT);
    assert_eq!(r.home, Some(13.0));
}

#[test]
fn homing_rescan_approaches_the_edge_twice() {
    let q = HomingQuirks {
        rescan: Some(2.0),
        ..HomingQuirks::default()
    };
    let r = run(&with(24, q), ALL, Layout::cam(), LEFT);
    check_success(&r, "rescan");
    assert_eq!(r.home, Some(10.0));
    assert_eq!(r.dirs, vec![1, -1, 1]);
    assert!(r.phases.contains(&HomingPhase::Rescan));
    // The second crossing is at the zero velocity, from 2 units before the edge.
    assert!((r.detect_speed.unwrap_or(f64::NAN) - ZERO_V).abs() < EPS);
    let back = r
        .outputs
        .iter()
        .find_map(|o| match o.motion {
            Some(MotionRequest::MoveTo { position, .. }) => Some(position),
            _ => None,
        })
        .unwrap_or(f64::NAN);
    assert!((back - 8.0).abs() < EPS, "{back}");
    // Index-only methods re-scan the index.
    let q = HomingQuirks {
        rescan: Some(0.5),
        ..HomingQuirks::default()
    };
    let r = run(&with(34, q), ALL, Layout::cam(), LEFT);
    check_success(&r, "rescan index");
    assert_eq!(r.home, Some(1.0));
    assert_eq!(r.dirs, vec![1, -1, 1]);
}

#[test]
fn homing_initial_backoff() {
    let q = HomingQuirks {
        initial_backoff: 5.0,
        ..HomingQuirks::default()
    };
    // Backs off opposite to the nominal direction, then searches.
    let r = run(&with(24, q), ALL, Layout::cam(), LEFT);
    check_success(&r, "backoff");
    assert_eq!(r.dirs, vec![-1, 1]);
    assert_eq!(r.phases.first(), Some(&HomingPhase::Backoff));
    assert_eq!(r.home, Some(10.0));
    // Backing off out of the cam: the side learnt on the way is kept.
    let r = run(&with(24, q), ALL, Layout::cam(), 12.0);
    check_success(&r, "backoff out of the cam");
    assert_eq!(r.dirs, vec![-1, 1]);
    assert_eq!(r.home, Some(10.0));
    // A limit cuts the back-off short.
    let r = run(&with(24, q), ALL, Layout::cam(), -98.0);
    check_success(&r, "backoff into the limit");
    assert_eq!(r.dirs, vec![-1, 1]);
    assert_eq!(r.home, Some(10.0));
}

#[test]
fn homing_trial_keeps_the_frame() {
    let q = HomingQuirks {
        trial: true,
        ..HomingQuirks::default()
    };
    let r = run(&with(19, q), ALL, Layout::positive_switch(), LEFT);
    check_success(&r, "trial");
    assert_eq!(r.home, Some(10.0));
    assert_eq!(r.final_reading, r.final_x);
    assert!(r.outputs.iter().all(|o| o.set_home.is_none()));
    let q = HomingQuirks {
        trial: true,
        after_home: AfterHome::ReturnToHome,
        ..HomingQuirks::default()
    };
    let r = run(&with(19, q), ALL, Layout::positive_switch(), LEFT);
    assert!((r.final_x - 10.0).abs() < EPS);
    assert_eq!(r.final_reading, r.final_x);
}

#[test]
fn homing_abort_stops_then_reports() {
    let r = run_with(&spec(7), ALL, Layout::cam(), RIGHT, |tick, _| tick == 300);
    assert_eq!(r.result, Some(Err(HomingError::Aborted)));
    assert_eq!(r.final_v, 0.0);
    assert!(r.final_x > RIGHT + 5.0);
}

#[test]
fn homing_started_in_motion_stops_first() {
    // Moving away from the cam at the switch velocity when method 8 starts.
    let mut sim = Sim::new(Layout::cam(), LEFT);
    sim.request(MotionRequest::Velocity {
        velocity: -SWITCH_V,
        acceleration: ACC,
    });
    for _ in 0..100 {
        sim.tick();
    }
    let start = sim.x;
    let r = run_sim(&spec(8), ALL, sim, |_, _| false);
    check_success(&r, "moving");
    assert_eq!(r.home, Some(13.0));
    assert_eq!(r.dirs, vec![-1, 1]);
    assert!(matches!(
        r.outputs.first().and_then(|o| o.motion),
        Some(MotionRequest::Stop { .. })
    ));
    // Stopped within the ramp, then searched from rest.
    let stopped = r
        .outputs
        .iter()
        .position(|o| matches!(o.motion, Some(MotionRequest::Velocity { .. })))
        .unwrap_or(0);
    assert!(stopped >= 10, "{stopped}");
    assert!(start < LEFT - 1.0);
}

#[test]
fn homing_status_follows_the_run() {
    let s = spec(19);
    let mut sim = super::sim::Sim::new(Layout::positive_switch(), LEFT);
    let mut inputs = sim.inputs(LEFT);
    let mut homing = match Homing::start(&s, ALL, &inputs) {
        Ok(h) => h,
        Err(e) => panic!("{e}"),
    };
    assert_eq!(homing.status(), HomingStatus::Running(HomingPhase::Search));
    loop {
        let out = homing.step(&inputs);
        if let Some(p) = out.set_home {
            sim.set_home(p, s.offset);
        }
        if let Some(m) = out.motion {
            sim.request(m);
        }
        if out.done.is_some() {
            break;
        }
        assert!(matches!(homing.status(), HomingStatus::Running(_)));
        inputs = sim.tick();
    }
    assert_eq!(homing.status(), HomingStatus::Succeeded);
    // Later steps are empty.
    let out = homing.step(&inputs);
    assert_eq!((out.motion, out.done), (None, None));
}

#[test]
fn homing_is_deterministic() {
    let a = run(&spec(12), ALL, Layout::cam(), LEFT);
    let b = run(&spec(12), ALL, Layout::cam(), LEFT);
    assert_eq!(a, b);
}

#[test]
fn homing_quirks_serde() {
    let q: HomingQuirks = serde_json::from_str("{}").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(q, HomingQuirks::default());
    let q: HomingQuirks = serde_json::from_str(
        r#"{"after_home":"return_to_home","switch_latch":"polled","switch_scan_ticks":4,
            "rescan":1.5,"max_search_distance":100.0}"#,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(q.after_home, AfterHome::ReturnToHome);
    assert_eq!(q.switch_latch, Latch::Polled);
    assert_eq!(q.index_latch, Latch::Exact);
    assert_eq!(q.rescan, Some(1.5));
    assert!(serde_json::from_str::<HomingQuirks>(r#"{"bogus":1}"#).is_err());
    let e = HomingError::MissingInput {
        method: 7,
        input: HomingInput::PositiveLimit,
    };
    let json = serde_json::to_string(&e).unwrap_or_default();
    assert_eq!(
        json,
        r#"{"reason":"missing_input","method":7,"input":"positive_limit"}"#
    );
    assert_eq!(serde_json::from_str::<HomingError>(&json).ok(), Some(e));
    assert_eq!(
        HomingError::MissingInput {
            method: 1,
            input: HomingInput::NegativeLimit
        }
        .to_string(),
        "homing method 1 needs a negative limit switch, and the axis has none"
    );
}
