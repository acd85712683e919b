//! Property tests of the planner (issue 11 tests): thousands of random paths of lines and arcs
//! under random per-axis limits, joins and transitions.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use path::geometry::{Arc, Segment, Turn};
use path::planner::{Join, PathPlanner, PathState, PlannerConfig, Transition};
use path::Point;
use proptest::prelude::*;

/// One random piece of path: a line by its displacement, or an arc in the (0, 1) plane by
/// its centre offset from the start, its sweep and a rise of the other axes.
#[derive(Clone, Debug)]
enum Piece {
    Line([f64; 3]),
    Arc {
        center: (f64, f64),
        sweep: f64,
        ccw: bool,
        rise: f64,
    },
}

fn piece(arcs: bool) -> impl Strategy<Value = Piece> {
    let line = prop::array::uniform3(-20.0..20.0f64).prop_map(Piece::Line);
    let arc = (
        (-8.0..8.0f64, -8.0..8.0f64),
        0.05..6.0f64,
        any::<bool>(),
        -3.0..3.0f64,
    )
        .prop_filter("radius", |(c, ..)| c.0.hypot(c.1) > 0.2)
        .prop_map(|(center, sweep, ccw, rise)| Piece::Arc {
            center,
            sweep,
            ccw,
            rise,
        });
    if arcs {
        prop_oneof![2 => line, 1 => arc].boxed()
    } else {
        line.boxed()
    }
}

fn join() -> impl Strategy<Value = Join> {
    prop_oneof![
        Just(Join::Buffered),
        Just(Join::BlendingLow),
        Just(Join::BlendingPrevious),
        Just(Join::BlendingNext),
        Just(Join::BlendingHigh),
    ]
}

fn transition() -> impl Strategy<Value = Transition> {
    prop_oneof![
        Just(Transition::None),
        (0.0..5.0f64).prop_map(Transition::CornerDistance),
        (0.0..1.0f64).prop_map(Transition::CornerDeviation),
    ]
}

#[derive(Clone, Debug)]
struct Case {
    dims: usize,
    axes: Vec<(f64, f64, f64)>,
    period: f64,
    pieces: Vec<(Piece, f64, f64, Join, Transition)>,
}

fn case(arcs: bool, jerk: bool, joins: bool) -> impl Strategy<Value = Case> {
    let j: BoxedStrategy<f64> = if jerk {
        (2e4..2e6f64).boxed()
    } else {
        Just(f64::INFINITY).boxed()
    };
    (
        2..=3usize,
        prop::collection::vec((20.0..500.0f64, 200.0..10_000.0f64, j), 3),
        prop_oneof![Just(1e-3), Just(5e-4), Just(2e-3)],
        prop::collection::vec(
            (
                piece(arcs),
                10.0..800.0f64,
                200.0..20_000.0f64,
                if joins {
                    join().boxed()
                } else {
                    Just(Join::Buffered).boxed()
                },
                transition(),
            ),
            1..8,
        ),
    )
        .prop_map(|(dims, axes, period, pieces)| Case {
            dims,
            axes,
            period,
            pieces,
        })
}

struct Outcome {
    config: PlannerConfig,
    states: Vec<PathState>,
    corners: Vec<Point>,
    segments: Vec<Segment>,
    end: Point,
    tolerance: f64,
}

#[derive(Clone, Copy, Debug)]
enum Action {
    Override(f64),
    Halt(Option<f64>),
    Resume,
}

fn action() -> impl Strategy<Value = (usize, Action)> {
    (
        0..3000usize,
        prop_oneof![
            (0.05..4.0f64).prop_map(Action::Override),
            prop::option::of(20.0..5000.0f64).prop_map(Action::Halt),
            Just(Action::Resume),
        ],
    )
}

fn simulate(c: &Case, jerk: bool) -> Outcome {
    simulate_with(c, jerk, &[])
}

fn simulate_with(c: &Case, jerk: bool, actions: &[(usize, Action)]) -> Outcome {
    let mut config = PlannerConfig::uniform(c.dims, axis(1.0, 1.0, f64::INFINITY), c.period);
    for (k, &(v, a, j)) in c.axes.iter().enumerate() {
        config.axes[k] = axis(v, a, j);
    }
    let mut pl = PathPlanner::new(config.clone(), p(&[0.0; 3])).unwrap();
    let mut at = p(&[0.0; 3]);
    let mut corners = vec![at];
    let mut segments = Vec::new();
    let mut tolerance: f64 = 0.0;
    for (i, (pc, v, a, jn, tr)) in c.pieces.iter().enumerate() {
        let mut to = at;
        let seg = match pc {
            Piece::Line(d) => {
                for k in 0..c.dims {
                    to[k] += d[k];
                }
                line(at, to, c.dims)
            }
            Piece::Arc {
                center,
                sweep,
                ccw,
                rise,
            } => {
                let mut ctr = at;
                ctr[0] += center.0;
                ctr[1] += center.1;
                let angle = if *ccw { *sweep } else { -*sweep };
                let (x, y) = rotate(at[0] - ctr[0], at[1] - ctr[1], angle);
                to[0] = ctr[0] + x;
                to[1] = ctr[1] + y;
                if c.dims == 3 {
                    to[2] += rise;
                }
                let turn = if *ccw { Turn::Ccw } else { Turn::Cw };
                Segment::Arc(Arc::from_center(at, to, ctr, (0, 1), turn, 0, c.dims).unwrap())
            }
        };
        let j = if jerk { 1e5 } else { f64::INFINITY };
        let limits = path::planner::PathLimits {
            velocity: *v,
            acceleration: *a,
            deceleration: *a,
            jerk: j,
        };
        if *jn != Join::Buffered {
            tolerance = tolerance.max(match tr {
                Transition::None => 0.0,
                Transition::CornerDistance(d) => *d,
                Transition::CornerDeviation(e) => *e,
            });
        }
        segments.push(seg.clone());
        pl.push_motion(motion(seg, limits, *jn, *tr, i as u64))
            .unwrap();
        at = to;
        corners.push(at);
    }
    let mut states = vec![*pl.state()];
    let mut events = Vec::new();
    for tick in 0..2_000_000usize {
        for (_, a) in actions.iter().filter(|(t, _)| *t == tick) {
            match a {
                Action::Override(f) => pl.set_override(*f),
                Action::Halt(d) => pl.halt(*d),
                Action::Resume => pl.resume(),
            }
        }
        if tick > 3000 {
            pl.resume();
        }
        states.push(*pl.step(&mut events));
        if pl.is_idle() && tick > 3000 {
            break;
        }
    }
    assert!(pl.is_idle(), "not done");
    Outcome {
        config,
        states,
        corners,
        segments,
        end: at,
        tolerance,
    }
}

/// Check every axis's velocity and acceleration (finite differences and reported), the path
/// speed ≥ 0 and the exact end. Windows across a junction with a direction step (the corner
/// rule) too: the velocity step and the motions' acceleration share each axis's budget.
fn check(o: &Outcome) {
    let cfg = &o.config;
    let t = cfg.period;
    assert_eq!(o.states.last().unwrap().position, o.end);
    for k in 0..cfg.dims {
        let lim = cfg.axes[k];
        let scale = o
            .states
            .iter()
            .map(|s| s.position[k].abs())
            .fold(1.0, f64::max);
        let slack_v = 2.0 * f64::EPSILON * scale / t;
        let slack_a = 4.0 * f64::EPSILON * scale / (t * t);
        for w in o.states.windows(2) {
            let v = (w[1].position[k] - w[0].position[k]) / t;
            assert!(
                v.abs() <= lim.velocity * (1.0 + 1e-9) + slack_v,
                "axis {k}: v {v} > {}",
                lim.velocity
            );
            assert!(w[1].velocity[k].abs() <= lim.velocity * (1.0 + 1e-9));
            assert!(
                w[1].acceleration[k].abs() <= lim.acceleration * (1.0 + 1e-9),
                "axis {k}: reported a {} > {}",
                w[1].acceleration[k],
                lim.acceleration
            );
            assert!(w[1].path_velocity >= 0.0);
        }
        for w in o.states.windows(3) {
            let a = (w[2].position[k] - 2.0 * w[1].position[k] + w[0].position[k]) / (t * t);
            let junction = w[0].completed != w[2].completed || w[0].tag != w[2].tag;
            let bound = lim.acceleration * (1.0 + 1e-9) + slack_a;
            assert!(
                a.abs() <= bound,
                "axis {k}: FD a {a} > {} (junction {junction})",
                lim.acceleration
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    #[test]
    fn random_paths_of_lines_and_arcs_keep_every_axis_within_its_limits(c in case(true, false, true)) {
        let o = simulate(&c, false);
        check(&o);
    }

    #[test]
    fn random_line_paths_stay_within_the_corner_tolerance(c in case(false, false, true)) {
        let o = simulate(&c, false);
        check(&o);
        let scale = o.corners.iter().flat_map(|p| p.iter()).fold(1.0f64, |m, x| m.max(x.abs()));
        for s in &o.states {
            let d = distance_to_polyline(&s.position, &o.corners);
            prop_assert!(d <= o.tolerance + 1e-12 * scale, "{d} > {}", o.tolerance);
        }
    }
}

/// Every state within the corner tolerance of the programmed path of lines and arcs (a blend
/// lies within it of its corner; everything else on the segments).
fn check_tolerance(o: &Outcome) -> Result<(), TestCaseError> {
    let scale = o
        .corners
        .iter()
        .flat_map(|p| p.iter())
        .fold(1.0f64, |m, x| m.max(x.abs()));
    for s in &o.states {
        let d = distance_to_path(&s.position, &o.segments);
        prop_assert!(
            d <= o.tolerance + 1e-9 * scale,
            "{d} > {} at {:?}",
            o.tolerance,
            s.position
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    /// Blends on corners with arcs (issue 11 item 4): within the tolerance, within the limits.
    #[test]
    fn random_paths_of_lines_and_arcs_stay_within_the_corner_tolerance(c in case(true, false, true)) {
        let o = simulate(&c, false);
        check(&o);
        check_tolerance(&o)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    /// The same with S-curves along the path and jerk-limited axes: every axis's jerk (third
    /// finite differences) within its limit too, through arcs, blends and corners without
    /// geometry (the junction rule and the curve rules of the planner). Factor 1: the third
    /// difference of a motion is a weighted mean of its jerk, and a junction's steps weigh at
    /// most `Δv/T² + ¾·Δa/T`, which the junction rule keeps within the jerk the motions
    /// beside it leave; only the rounding of four positions is discounted (`jerk_peak`).
    #[test]
    fn random_blended_paths_of_lines_and_arcs_with_s_curves_keep_the_limits(c in case(true, true, true)) {
        let o = simulate(&c, true);
        check(&o);
        check_tolerance(&o)?;
        let j = jerk_peak(&o.states, &o.config);
        prop_assert!(j <= 1.0 + 1e-9, "FD jerk {j}× the limit");
    }

    /// Overrides, halts and resumes at random ticks, S-curves or trapezoids, arcs, blends:
    /// the same limits hold, the path ends exactly.
    #[test]
    fn random_overrides_and_halts_keep_the_limits(
        c in case(true, false, true),
        jerk in any::<bool>(),
        actions in prop::collection::vec(action(), 0..6),
    ) {
        let o = simulate_with(&c, jerk, &actions);
        check(&o);
    }

    /// The same with S-curves and jerk-limited axes: every axis's jerk within its limit.
    #[test]
    fn random_overrides_and_halts_with_s_curves_keep_the_jerk_within_the_limits(
        c in case(true, true, true),
        actions in prop::collection::vec(action(), 0..6),
    ) {
        let o = simulate_with(&c, true, &actions);
        check(&o);
        let j = jerk_peak(&o.states, &o.config);
        prop_assert!(j <= 1.0 + 1e-9, "FD jerk {j}× the limit");
    }

    /// S-curves on buffered line paths: every axis's jerk (third finite differences) within
    /// its limit too.
    #[test]
    fn random_buffered_line_paths_with_s_curves_keep_the_jerk_within_the_limits(c in case(false, true, false)) {
        let o = simulate(&c, true);
        check(&o);
        let t = o.config.period;
        for k in 0..o.config.dims {
            let lim = o.config.axes[k];
            let scale = o.states.iter().map(|s| s.position[k].abs()).fold(1.0, f64::max);
            let slack = 8.0 * f64::EPSILON * scale / (t * t * t);
            for w in o.states.windows(4) {
                let j = (w[3].position[k] - 3.0 * w[2].position[k] + 3.0 * w[1].position[k] - w[0].position[k]) / (t * t * t);
                prop_assert!(j.abs() <= lim.jerk * (1.0 + 1e-9) + slack, "axis {k}: j {j} > {}", lim.jerk);
            }
        }
    }
}
