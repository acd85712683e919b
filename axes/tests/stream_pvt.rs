//! PVT streams per axis (issue 12 item 3): cubic Hermite between (position, velocity, time)
//! knots, NMC `MtPvtData` (digest 001 §2.14, §4.7) and HIMC `MovePVT` (digest 004 §5.2.8,
//! TV20–21). The property: the axis passes every knot with its position and velocity.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    Command, CommandState, Enable, ErrorKind, PvtMove, PvtPoint, PvtPush, Reply, StreamConfig,
    StreamMode, StreamStart,
};
use axes::config::AxisConfig;
use axes::error::StreamPointProblem;
use axes::{AxisState, Engine, EngineError, ParamId};
use common::*;
use proptest::prelude::*;

/// A virtual axis in mm: commanded = actual, no plant.
fn mm_axis() -> AxisConfig {
    let mut a = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 0.0),
        (ParamId::Units, 1000.0),
        (ParamId::RepMode, 0.0),
        (ParamId::Decel, 1e5),
    ] {
        a.params.insert(p, v);
    }
    a
}

fn machine() -> Engine {
    let mut e = engine_with(vec![mm_axis()]);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    e
}

fn knots(points: &[(f64, f64, f64)]) -> Vec<PvtPoint> {
    points
        .iter()
        .map(|&(time_ms, position, velocity)| PvtPoint {
            position,
            velocity,
            time_ms,
        })
        .collect()
}

/// digest 004 TV20: time, position, velocity of each knot.
const TV20: [(f64, f64, f64); 6] = [
    (0.0, 0.0, 0.0),
    (2000.0, 153.333, 1000.0),
    (3000.0, 42.123, 800.0),
    (4000.0, 161.21, 1660.0),
    (6000.0, 177.0, 450.0),
    (11000.0, 83.333, 0.0),
];

#[test]
fn himc_tv20_move_pvt_passes_its_knots_and_ends_at_rest() {
    let mut e = machine();
    let reply = ok(
        &mut e,
        Command::from(PvtMove {
            axis: 0,
            points: knots(&TV20),
        }),
    );
    let Reply::Accepted { id } = reply else {
        panic!("{reply:?}")
    };
    assert_eq!(status(&e).stream.mode, StreamMode::Once);
    let mut t = 0.0;
    for &(at, p, v) in &TV20[1..] {
        run(&mut e, (at - t) / 1e3);
        t = at;
        let s = status(&e);
        assert_eq!(s.cmd_pos, p, "position at {at} ms");
        assert!(
            (s.cmd_vel - v).abs() < 1e-9,
            "velocity at {at} ms: {}",
            s.cmd_vel
        );
    }
    let s = status(&e);
    assert_eq!(s.state, AxisState::Standstill);
    assert_eq!(state_of(&mut e, id), CommandState::Done);
    // A pvt_move leaves nothing behind.
    assert_eq!((s.stream.used, s.stream.mode), (0, StreamMode::Refresh));
}

#[test]
fn himc_tv21_a_move_pvt_of_51_knots_is_refused() {
    let mut e = machine();
    let points: Vec<_> = (0..51)
        .map(|i| (f64::from(i) * 10.0, f64::from(i), 0.0))
        .collect();
    let err = refused(
        &mut e,
        Command::from(PvtMove {
            axis: 0,
            points: knots(&points),
        }),
    );
    assert!(
        matches!(err, EngineError::InvalidArgument { name: "points", value, .. } if value == 51.0),
        "{err}"
    );
    assert_eq!(status(&e).state, AxisState::Standstill);
    ok(
        &mut e,
        Command::from(PvtMove {
            axis: 0,
            points: knots(&points[..50]),
        }),
    );
}

#[test]
fn a_pvt_segment_beyond_max_velocity_is_refused_before_anything_moves() {
    let mut e = machine();
    set(&mut e, ParamId::MaxVelocity, 1000.0);
    let err = refused(
        &mut e,
        Command::from(PvtMove {
            axis: 0,
            points: knots(&TV20),
        }),
    );
    // The first two segments stay within ±1000 mm/s; the third ends at 1660.
    match err {
        EngineError::StreamPoint {
            point: 3,
            problem: StreamPointProblem::VelocityLimit { velocity, limit },
            ..
        } => assert_eq!((velocity, limit), (1660.0, 1000.0)),
        other => panic!("{other}"),
    }
    let s = status(&e);
    assert_eq!((s.state, s.stream.used), (AxisState::Standstill, 0));
}

#[test]
fn a_knot_at_time_zero_must_be_the_start() {
    let mut e = machine();
    let err = refused(
        &mut e,
        Command::from(PvtMove {
            axis: 0,
            points: knots(&[(0.0, 5.0, 0.0), (100.0, 10.0, 0.0)]),
        }),
    );
    assert!(
        matches!(
            err,
            EngineError::StreamPoint {
                point: 0,
                problem: StreamPointProblem::StartMismatch,
                ..
            }
        ),
        "{err}"
    );
    let err = refused(
        &mut e,
        Command::from(PvtMove {
            axis: 0,
            points: knots(&[(0.0, 0.0, 0.0)]),
        }),
    );
    assert_eq!(err.kind(), ErrorKind::InvalidArgument, "{err}");
    let err = refused(
        &mut e,
        Command::from(PvtPush {
            axis: 0,
            points: knots(&[(10.0, 1.0, f64::NAN)]),
        }),
    );
    assert!(
        matches!(
            err,
            EngineError::StreamPoint {
                problem: StreamPointProblem::NotFinite {
                    name: "velocity",
                    ..
                },
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn a_static_pvt_buffer_loops_each_run_continuing_from_the_last() {
    let mut e = machine();
    ok(
        &mut e,
        Command::from(StreamConfig {
            axis: 0,
            mode: StreamMode::Static,
            loop_count: 3,
            stop_deceleration: None,
        }),
    );
    ok(
        &mut e,
        Command::from(PvtPush {
            axis: 0,
            points: knots(&[(100.0, 5.0, 80.0), (200.0, 10.0, 0.0)]),
        }),
    );
    ok(&mut e, Command::from(StreamStart { axes: vec![0] }));
    run(&mut e, 0.3);
    let s = status(&e);
    assert_eq!((s.cmd_pos, s.cmd_vel), (15.0, 80.0));
    run(&mut e, 0.3);
    let s = status(&e);
    assert_eq!(
        (s.cmd_pos, s.cmd_vel, s.state),
        (30.0, 0.0, AxisState::Standstill)
    );
    assert_eq!(s.stream.loops_done, 3);
}

/// Knots as (gap ms, position, velocity units/s); the last one ends at rest.
fn knot_strategy() -> impl Strategy<Value = Vec<(u32, f64, f64)>> {
    prop::collection::vec((1u32..60, -500.0f64..500.0, -20_000.0f64..20_000.0), 1..=32)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Issue 12 property: PVT passes every knot with its position and velocity. Knots at whole
    /// milliseconds are sampled exactly at 1 ms ticks; the knots arrive in two pushes (the
    /// second continues the chain of the first), after a start elsewhere than 0.
    #[test]
    fn pvt_passes_every_knot_with_its_position_and_velocity(
        raw in knot_strategy(),
        split in 0usize..32,
        start in -100.0f64..100.0,
    ) {
        let mut e = machine();
        ok(&mut e, move_abs(start));
        run(&mut e, 2.0);
        prop_assert_eq!(status(&e).state, AxisState::Standstill);
        let base = status(&e).cmd_pos;
        let mut t = 0.0;
        let last = raw.len() - 1;
        let points: Vec<PvtPoint> = raw
            .iter()
            .enumerate()
            .map(|(i, &(gap, position, velocity))| {
                t += f64::from(gap);
                PvtPoint { position, velocity: if i == last { 0.0 } else { velocity }, time_ms: t }
            })
            .collect();
        let split = split.min(points.len() - 1);
        let (first, second) = points.split_at(split + 1);
        ok(&mut e, Command::from(PvtPush { axis: 0, points: first.to_vec() }));
        if !second.is_empty() {
            ok(&mut e, Command::from(PvtPush { axis: 0, points: second.to_vec() }));
        }
        ok(&mut e, Command::from(StreamStart { axes: vec![0] }));
        let mut now = 0.0;
        for k in &points {
            while now < k.time_ms {
                e.step();
                now += 1.0;
            }
            let s = status(&e);
            prop_assert_eq!(s.cmd_pos, base + k.position, "position at {} ms", k.time_ms);
            prop_assert!(
                (s.cmd_vel - k.velocity).abs() <= 1e-9 * (1.0 + k.velocity.abs()),
                "velocity at {} ms: {} for {}", k.time_ms, s.cmd_vel, k.velocity
            );
        }
        let s = status(&e);
        prop_assert_eq!(s.state, AxisState::Standstill);
        prop_assert_eq!(s.stream.underruns, 0);
    }
}
