//! Vendor junction and curve rules of the planner: HMC/NMC corner angles and HMC's curvature
//! jerk limit.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use path::geometry::{Arc, Segment, Turn};
use path::planner::{
    ChordErrorBands, CornerAngles, Join, LookaheadLimits, PathEvent, PathPlanner, PlannerConfig,
    Transition,
};

/// Two lines of 100 with a turn of `angle` between them, blended at the previous motion's
/// velocity (HMC Merge 1); the path velocity when the second motion starts.
fn junction_velocity(angle: f64, angles: Option<CornerAngles>) -> f64 {
    junction_velocity_with(angle, angles, LookaheadLimits::default())
}

fn junction_velocity_with(angle: f64, angles: Option<CornerAngles>, rules: LookaheadLimits) -> f64 {
    // Axis accelerations so high that the corner rule (A·T/|Δt|) never binds.
    let cfg = PlannerConfig::uniform(2, axis(1e6, 1e9, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg, p(&[0.0, 0.0])).unwrap();
    pl.set_corner_angles(angles).unwrap();
    pl.set_lookahead_limits(rules).unwrap();
    let corner = p(&[100.0, 0.0]);
    let (dx, dy) = rotate(100.0, 0.0, angle);
    let end = p(&[100.0 + dx, dy]);
    let lim = limits(100.0, 1000.0, f64::INFINITY);
    pl.push_motion(motion(
        line(p(&[0.0, 0.0]), corner, 2),
        lim,
        Join::Buffered,
        Transition::None,
        1,
    ))
    .unwrap();
    pl.push_motion(motion(
        line(corner, end, 2),
        lim,
        Join::BlendingPrevious,
        Transition::None,
        2,
    ))
    .unwrap();
    let (states, events) = run(&mut pl, 100_000);
    assert!(close(&states.last().unwrap().position, &end, 0.0));
    // The step in which motion 2 started: its first state's speed is the junction's, less
    // at most one step of acceleration.
    assert!(events.contains(&PathEvent::Started { tag: 2 }));
    let index = states.iter().position(|st| st.tag == Some(2)).unwrap();
    states[index - 1]
        .path_velocity
        .max(states[index].path_velocity)
}

#[test]
fn hmc_corner_angles_scale_the_merge_velocity_between_the_decel_and_stop_angles() {
    let theta = std::f64::consts::FRAC_PI_4;
    let free = junction_velocity(theta, None);
    assert!((free - 100.0).abs() < 1.5, "no angle rule: {free}");
    // k = (θ − stop)/(decel − stop) = (π/4 − π/2)/(π/6 − π/2) = 0.75 (digest 000 §3.4).
    let scaled = junction_velocity(theta, Some(CornerAngles::HMC_DEFAULT));
    assert!((scaled - 75.0).abs() < 1.5, "decel band: {scaled}");
    // Below the decel angle no limit; at the stop angle and beyond, an exact stop.
    let small = junction_velocity(0.4, Some(CornerAngles::HMC_DEFAULT));
    assert!((small - 100.0).abs() < 1.5, "below decel angle: {small}");
    let stop = junction_velocity(std::f64::consts::FRAC_PI_2, Some(CornerAngles::HMC_DEFAULT));
    assert!(stop < 1.5, "stop angle: {stop}");
}

#[test]
fn corner_angles_out_of_order_are_refused() {
    let cfg = PlannerConfig::uniform(2, axis(100.0, 1000.0, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg, p(&[0.0, 0.0])).unwrap();
    for (slow, stop) in [(1.0, 0.5), (-0.1, 1.0), (0.5, 4.0), (f64::NAN, 1.0)] {
        assert!(pl
            .set_corner_angles(Some(CornerAngles { slow, stop }))
            .is_err());
    }
    assert_eq!(pl.corner_angles(), None);
}

#[test]
fn hmc_curvature_jerk_limit_caps_a_circle_at_the_cube_root_of_jerk_over_curvature_squared() {
    // HMC digest 000 §3.5: a circle of radius 10 000 at Speed 20 000 and Jerk 5 000 reaches
    // only (5000 · 10000²)^(1/3) = 7937.005.
    let cfg = PlannerConfig::uniform(2, axis(1e9, 1e9, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg, p(&[10_000.0, 0.0])).unwrap();
    let circle = Arc::from_center(
        p(&[10_000.0, 0.0]),
        p(&[10_000.0, 0.0]),
        p(&[0.0, 0.0]),
        (0, 1),
        Turn::Ccw,
        0,
        2,
    )
    .unwrap();
    let lim = limits(20_000.0, 1e6, 5_000.0);
    pl.push_motion(motion(
        Segment::Arc(circle),
        lim,
        Join::Buffered,
        Transition::None,
        1,
    ))
    .unwrap();
    let (states, _) = run(&mut pl, 1_000_000);
    let peak = states.iter().map(|s| s.path_velocity).fold(0.0, f64::max);
    assert!((peak - 7937.005).abs() < 0.01, "peak path velocity {peak}");
}

/// Peak path velocity over one full circle of radius 10 at a programmed 1000, axes far faster.
fn circle_peak(rules: LookaheadLimits) -> f64 {
    let cfg = PlannerConfig::uniform(2, axis(1e9, 1e9, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg, p(&[10.0, 0.0])).unwrap();
    pl.set_lookahead_limits(rules).unwrap();
    let circle = Arc::from_center(
        p(&[10.0, 0.0]),
        p(&[10.0, 0.0]),
        p(&[0.0, 0.0]),
        (0, 1),
        Turn::Ccw,
        0,
        2,
    )
    .unwrap();
    pl.push_motion(motion(
        Segment::Arc(circle),
        limits(1000.0, 1e6, f64::INFINITY),
        Join::Buffered,
        Transition::None,
        1,
    ))
    .unwrap();
    let (states, _) = run(&mut pl, 1_000_000);
    states.iter().map(|s| s.path_velocity).fold(0.0, f64::max)
}

#[test]
fn himc_arc_acceleration_caps_arc_speed_at_the_root_of_a_arc_times_r() {
    // HIMC V_arc = √(A_arc·r) (digest 004 §2.7): √(100 · 10) = 31.62.
    let peak = circle_peak(LookaheadLimits::HIMC_DEFAULT);
    assert!((peak - 1000f64.sqrt()).abs() < 1e-6, "{peak}");
    assert!(circle_peak(LookaheadLimits::default()) > 900.0);
}

#[test]
fn himc_chord_error_caps_arc_speed() {
    // V_chord = 2·r·φ/T with cos φ = 1 − ε/r: r = 10, ε = 0.001, T = 1 ms → 282.84.
    let rules = LookaheadLimits {
        chord_error: Some(0.001),
        ..LookaheadLimits::default()
    };
    let expected = 2.0 * 10.0 * (1.0 - 0.0001f64).acos() / 1e-3;
    let peak = circle_peak(rules);
    assert!((peak - expected).abs() < 1e-6, "{peak} vs {expected}");
}

#[test]
fn himc_corner_acceleration_caps_a_corner_without_geometry() {
    // A right angle: |t₁ − t₂| = √2, so A_corner·T/√2 = 5000 · 0.001 / 1.414 = 3.54.
    let v = junction_velocity_with(
        std::f64::consts::FRAC_PI_2,
        None,
        LookaheadLimits::HIMC_DEFAULT,
    );
    // The sample nearest the junction is within one step of path acceleration (1 mm/s) of it.
    let cap = 5.0 / 2f64.sqrt();
    assert!(v > cap - 0.01 && v < cap + 1.01, "{v} vs {cap}");
    assert!(junction_velocity(std::f64::consts::FRAC_PI_2, None) > 90.0);
}

#[test]
fn lookahead_limits_must_be_positive() {
    let cfg = PlannerConfig::uniform(2, axis(100.0, 1000.0, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg, p(&[0.0, 0.0])).unwrap();
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let rules = LookaheadLimits {
            arc_acceleration: Some(bad),
            ..LookaheadLimits::default()
        };
        assert!(pl.set_lookahead_limits(rules).is_err());
    }
    assert_eq!(pl.lookahead_limits(), LookaheadLimits::default());
}

/// Two 4-D lines turning in XY with the fourth coordinate moving along both: the path
/// velocity when the second starts.
fn fourth_coordinate_corner(rules: LookaheadLimits) -> f64 {
    let cfg = PlannerConfig::uniform(4, axis(1e6, 1e9, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg, p(&[0.0; 4])).unwrap();
    pl.set_lookahead_limits(rules).unwrap();
    let corner = p(&[100.0, 0.0, 0.0, 100.0]);
    let end = p(&[100.0, 100.0, 0.0, 200.0]);
    let lim = limits(100.0, 1000.0, f64::INFINITY);
    pl.push_motion(motion(
        line(p(&[0.0; 4]), corner, 4),
        lim,
        Join::Buffered,
        Transition::None,
        1,
    ))
    .unwrap();
    pl.push_motion(motion(
        line(corner, end, 4),
        lim,
        Join::BlendingPrevious,
        Transition::None,
        2,
    ))
    .unwrap();
    let (states, _) = run(&mut pl, 100_000);
    assert!(close(&states.last().unwrap().position, &end, 0.0));
    let index = states.iter().position(|st| st.tag == Some(2)).unwrap();
    states[index - 1]
        .path_velocity
        .max(states[index].path_velocity)
}

#[test]
fn nmc_fourth_axis_turn_velocity_caps_the_corner_where_the_path_turns() {
    // NMC_CrdSetFourthAxisToTurnVel(10): A moves at v/√2 on both lines, so the corner is at
    // most 10·√2 = 14.14 (within one step of path acceleration, 1).
    let capped = fourth_coordinate_corner(LookaheadLimits {
        corner_coordinate_velocity: Some((3, 10.0)),
        ..LookaheadLimits::default()
    });
    let cap = 10.0 * 2f64.sqrt();
    assert!(
        capped > cap - 0.01 && capped < cap + 1.01,
        "{capped} vs {cap}"
    );
    assert!(fourth_coordinate_corner(LookaheadLimits::default()) > 50.0);
    // A straight continuation is no corner: the limit does not apply.
    let cfg = PlannerConfig::uniform(4, axis(1e6, 1e9, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg, p(&[0.0; 4])).unwrap();
    pl.set_lookahead_limits(LookaheadLimits {
        corner_coordinate_velocity: Some((3, 10.0)),
        ..LookaheadLimits::default()
    })
    .unwrap();
    let lim = limits(100.0, 1000.0, f64::INFINITY);
    let mid = p(&[100.0, 0.0, 0.0, 100.0]);
    let end = p(&[200.0, 0.0, 0.0, 200.0]);
    pl.push_motion(motion(
        line(p(&[0.0; 4]), mid, 4),
        lim,
        Join::Buffered,
        Transition::None,
        1,
    ))
    .unwrap();
    pl.push_motion(motion(
        line(mid, end, 4),
        lim,
        Join::BlendingPrevious,
        Transition::None,
        2,
    ))
    .unwrap();
    let (states, _) = run(&mut pl, 100_000);
    let index = states.iter().position(|st| st.tag == Some(2)).unwrap();
    assert!(
        states[index].path_velocity > 90.0,
        "{}",
        states[index].path_velocity
    );
}

#[test]
fn nmc_arc_section_bands_pick_the_chord_error_by_radius() {
    // TArcSecSetting: [0, r0] → err0, [r0, r1] → err1, beyond → err2. The circle's radius is
    // 10: with r0 = 5, r1 = 50 it takes err1; with r0 = 20 err0; with r1 = 8 err2.
    let peak_for = |edges: [f64; 2]| {
        circle_peak(LookaheadLimits {
            chord_error: Some(0.001),
            chord_error_bands: Some(ChordErrorBands {
                edges,
                errors: [Some(0.004), Some(0.0001)],
            }),
            ..LookaheadLimits::default()
        })
    };
    let expected = |e: f64| 2.0 * 10.0 * (1.0 - e / 10.0).acos() / 1e-3;
    for (edges, e) in [
        ([5.0, 50.0], 0.004),
        ([20.0, 50.0], 0.001),
        ([5.0, 8.0], 0.0001),
    ] {
        let peak = peak_for(edges);
        assert!(
            (peak - expected(e)).abs() < 1e-6,
            "{edges:?}: {peak} vs {}",
            expected(e)
        );
    }
    // Both edges 0: no bands, the chord error everywhere; a band without an error: no limit.
    assert!((peak_for([0.0, 0.0]) - expected(0.001)).abs() < 1e-6);
    let free = circle_peak(LookaheadLimits {
        chord_error: Some(0.001),
        chord_error_bands: Some(ChordErrorBands {
            edges: [5.0, 50.0],
            errors: [None, None],
        }),
        ..LookaheadLimits::default()
    });
    assert!(free > 900.0, "{free}");
}
