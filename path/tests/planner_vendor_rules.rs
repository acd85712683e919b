//! Vendor junction and curve rules of the planner: HMC/NMC corner angles and HMC's curvature
//! jerk limit.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use path::geometry::{Arc, Segment, Turn};
use path::planner::{CornerAngles, Join, PathEvent, PathPlanner, PlannerConfig, Transition};

/// Two lines of 100 with a turn of `angle` between them, blended at the previous motion's
/// velocity (HMC Merge 1); the path velocity when the second motion starts.
fn junction_velocity(angle: f64, angles: Option<CornerAngles>) -> f64 {
    // Axis accelerations so high that the corner rule (A·T/|Δt|) never binds.
    let cfg = PlannerConfig::uniform(2, axis(1e6, 1e9, f64::INFINITY), 1e-3);
    let mut pl = PathPlanner::new(cfg, p(&[0.0, 0.0])).unwrap();
    pl.set_corner_angles(angles).unwrap();
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
