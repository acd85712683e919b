//! PT streams per axis (issue 12 item 3; NMC digest 001 §2.13, §4.7, S-PT-STATIC, S-PT-STREAM,
//! TV55–57): the manual's velocity rules, static loops, refresh-mode refills, the underrun
//! fault, several axes started in the same tick, the axis's own limits, bad input.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    AxisCommand, Command, CommandState, Enable, ErrorKind, MoveVelocity, PtKind, PtPoint, PtPush,
    Reply, Reset, Stop, StreamClear, StreamConfig, StreamMode, StreamStart,
};
use axes::config::AxisConfig;
use axes::error::StreamPointProblem;
use axes::{AxisFlags, AxisState, Engine, EngineError, ParamId};
use common::*;

/// A virtual axis counted in pulses (NMC units): commanded = actual, no plant.
fn pulse_axis() -> AxisConfig {
    let mut a = AxisConfig::default();
    for (p, v) in [
        (ParamId::AxisType, 0.0),
        (ParamId::Units, 1.0),
        (ParamId::RepMode, 0.0),
        (ParamId::Decel, 1e6),
        (ParamId::FastDecel, 1e7),
    ] {
        a.params.insert(p, v);
    }
    a
}

fn pulse_machine(axes: usize) -> Engine {
    let mut e = engine_with(vec![pulse_axis(); axes]);
    for axis in 0..axes as u16 {
        ok(&mut e, Command::from(Enable { axis }));
    }
    e
}

fn config(axis: u16, mode: StreamMode, loop_count: u32) -> Command {
    Command::from(StreamConfig {
        axis,
        mode,
        loop_count,
        stop_deceleration: None,
    })
}

fn push(axis: u16, points: &[(f64, f64, PtKind)]) -> Command {
    Command::from(PtPush {
        axis,
        points: points
            .iter()
            .map(|&(position, time_ms, kind)| PtPoint {
                position,
                time_ms,
                kind,
            })
            .collect(),
    })
}

fn start_ok(e: &mut Engine, axes: &[u16]) -> Vec<u32> {
    match ok(
        e,
        Command::from(StreamStart {
            axes: axes.to_vec(),
        }),
    ) {
        Reply::AcceptedAll { ids } => ids,
        other => panic!("{other:?}"),
    }
}

/// S-PT-STATIC's points (digest 001 §5, C3§3.3a).
const STATIC_POINTS: [(f64, f64, PtKind); 3] = [
    (10_000.0, 100.0, PtKind::Normal),
    (30_000.0, 200.0, PtKind::Normal),
    (40_000.0, 300.0, PtKind::Normal),
];

fn step_n(e: &mut Engine, n: u32) {
    for _ in 0..n {
        e.step();
    }
}

#[test]
fn tv55_static_pt_runs_at_the_manuals_velocities_and_ends_at_rest() {
    let mut e = pulse_machine(1);
    ok(&mut e, config(0, StreamMode::Static, 1));
    ok(&mut e, push(0, &STATIC_POINTS));
    let ids = start_ok(&mut e, &[0]);
    assert_eq!(ids.len(), 1);
    let s = status(&e);
    assert_eq!(s.state, AxisState::DiscreteMotion);
    assert!(s.stream.running);
    // 1 ms per tick: tick k is stream time k ms. v in pulse/ms = cmd_vel (pulse/s) / 1000.
    step_n(&mut e, 50);
    assert_eq!(status(&e).cmd_pos, 2_500.0, "½·2 p/ms²·(50 ms)²");
    step_n(&mut e, 50);
    let s = status(&e);
    assert_eq!(
        (s.cmd_pos, s.cmd_vel / 1e3),
        (10_000.0, 200.0),
        "TV55 v(100 ms)"
    );
    step_n(&mut e, 100);
    let s = status(&e);
    assert_eq!(
        (s.cmd_pos, s.cmd_vel / 1e3),
        (30_000.0, 200.0),
        "TV55 v(200 ms)"
    );
    step_n(&mut e, 100);
    let s = status(&e);
    assert_eq!((s.cmd_pos, s.cmd_vel), (40_000.0, 0.0), "TV55 pos(300 ms)");
    // BUSY → 0: the run is done at the last point.
    assert_eq!(s.state, AxisState::Standstill);
    assert!(!s.stream.running);
    assert_eq!(state_of(&mut e, ids[0]), CommandState::Done);
    // Static mode keeps the buffer (NMC "运动完后不会清除缓冲区数据").
    assert_eq!((s.stream.used, s.stream.space), (3, 29));
}

#[test]
fn s_pt_static_loops_five_times_each_run_continuing_from_the_last() {
    let mut e = pulse_machine(1);
    ok(&mut e, config(0, StreamMode::Static, 5));
    ok(&mut e, push(0, &STATIC_POINTS));
    start_ok(&mut e, &[0]);
    step_n(&mut e, 400);
    let s = status(&e);
    // Loop 2 at 100 ms into it: one run (40 000) plus the first point.
    assert_eq!((s.cmd_pos, s.cmd_vel / 1e3), (50_000.0, 200.0));
    assert_eq!(s.stream.loops_done, 1);
    step_n(&mut e, 1100);
    let s = status(&e);
    assert_eq!((s.cmd_pos, s.cmd_vel), (200_000.0, 0.0));
    assert_eq!(s.state, AxisState::Standstill);
    assert_eq!(s.stream.loops_done, 5);
    // Started again, the kept buffer runs again from here.
    start_ok(&mut e, &[0]);
    step_n(&mut e, 1500);
    assert_eq!(status(&e).cmd_pos, 400_000.0);
}

#[test]
fn tv56_a_push_of_33_points_is_refused_and_changes_nothing() {
    let mut e = pulse_machine(1);
    let points: Vec<_> = (1..=33)
        .map(|i| (f64::from(i), f64::from(i), PtKind::Normal))
        .collect();
    let err = refused(&mut e, push(0, &points));
    assert!(
        matches!(err, EngineError::InvalidArgument { name: "points", value, .. } if value == 33.0),
        "{err}"
    );
    assert_eq!(status(&e).stream.used, 0);
    ok(&mut e, push(0, &points[..32]));
    assert_eq!(status(&e).stream.used, 32);
    let err = refused(&mut e, push(0, &[]));
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
}

#[test]
fn tv57_space_and_used_after_a_clear_in_each_mode() {
    let mut e = pulse_machine(1);
    ok(&mut e, config(0, StreamMode::Static, 5));
    ok(&mut e, push(0, &STATIC_POINTS));
    ok(&mut e, Command::from(StreamClear { axis: 0 }));
    let s = status(&e).stream;
    assert_eq!((s.mode, s.space, s.used), (StreamMode::Static, 32, 0));
    ok(&mut e, config(0, StreamMode::Refresh, 0));
    let s = status(&e).stream;
    assert_eq!((s.mode, s.space, s.used), (StreamMode::Refresh, 64, 0));
    // A static buffer holds 32: the 33rd point does not fit.
    ok(&mut e, config(0, StreamMode::Static, 1));
    let points: Vec<_> = (1..=32)
        .map(|i| (f64::from(i), f64::from(i), PtKind::Even))
        .collect();
    ok(&mut e, push(0, &points));
    let err = refused(&mut e, push(0, &[(40.0, 40.0, PtKind::Stop)]));
    assert!(
        matches!(
            err,
            EngineError::StreamFull {
                axis: 0,
                space: 0,
                count: 1
            }
        ),
        "{err}"
    );
}

/// The host side of S-PT-STREAM (digest 001 §5, C3§3.3b): a sine velocity (A = 50 p/ms, T =
/// 1 s) cut in 16 ms NORMAL points, a STOP point back at 0 at each period's end, 2 periods.
/// Times are whole milliseconds (the example's `(long)(time*1000)` of an accumulated double
/// would sometimes truncate a step to 15 ms).
struct SineHost {
    pos: f64,
    vel_pre: f64,
    t_ms: i64,
    period: i64,
}

impl SineHost {
    fn new() -> SineHost {
        SineHost {
            pos: 0.0,
            vel_pre: 0.0,
            t_ms: 0,
            period: 1,
        }
    }

    /// The next point, `None` after the second period.
    fn next(&mut self) -> Option<(f64, f64, PtKind)> {
        if self.period > 2 {
            return None;
        }
        self.t_ms += 16;
        let time = self.t_ms as f64 / 1e3;
        let vel = 50.0 * (2.0 * std::f64::consts::PI * time).sin();
        self.pos += 1000.0 * (vel + self.vel_pre) * 0.016 / 2.0;
        self.vel_pre = vel;
        if self.t_ms < self.period * 1000 {
            return Some((self.pos, self.t_ms as f64, PtKind::Normal));
        }
        let end = (0.0, (self.period * 1000) as f64, PtKind::Stop);
        self.pos = 0.0;
        self.t_ms = self.period * 1000;
        self.vel_pre = 0.0;
        self.period += 1;
        Some(end)
    }
}

/// Run S-PT-STREAM: push while there is space, start once the buffer first fills, refill
/// every tick. Returns axis 0's record.
fn run_s_pt_stream(e: &mut Engine) -> Vec<axes::AxisStatus> {
    ok(e, config(0, StreamMode::Refresh, 0));
    let mut host = SineHost::new();
    let mut started = false;
    let mut pending = host.next();
    let mut record = Vec::new();
    for _ in 0..3000 {
        while let Some(point) = pending {
            if status(e).stream.space == 0 {
                break;
            }
            ok(e, push(0, &[point]));
            pending = host.next();
        }
        if !started && (status(e).stream.space == 0 || pending.is_none()) {
            start_ok(e, &[0]);
            started = true;
        }
        e.step();
        record.push(status(e));
    }
    assert!(pending.is_none(), "the host pushed every point");
    record
}

#[test]
fn s_pt_stream_refilled_while_running_oscillates_and_ends_at_zero() {
    let mut e = pulse_machine(1);
    let record = run_s_pt_stream(&mut e);
    let peak = record.iter().map(|s| s.cmd_pos).fold(f64::MIN, f64::max);
    // ∫ 50 sin(2πt) dt over half a period = 50 000/π pulses.
    let expected = 50_000.0 / std::f64::consts::PI;
    assert!((peak - expected).abs() < 0.01 * expected, "peak {peak}");
    let vmax = record.iter().map(|s| s.cmd_vel.abs()).fold(0.0, f64::max);
    assert!((vmax / 1e3 - 50.0).abs() < 0.5, "peak velocity {vmax}");
    let last = record.last().unwrap();
    assert_eq!((last.cmd_pos, last.cmd_vel), (0.0, 0.0));
    assert_eq!(last.state, AxisState::Standstill);
    assert_eq!(last.stream.underruns, 0);
    assert!(last.latched.is_empty(), "{}", last.latched);
    // The buffer gave its room back a FIFO half at a time while it ran.
    assert!(record
        .iter()
        .any(|s| s.stream.running && s.stream.space == 32));
    assert_eq!((last.stream.used, last.stream.space), (0, 64));
}

#[test]
fn a_pt_stream_is_deterministic_to_the_bit() {
    let a = run_s_pt_stream(&mut pulse_machine(1));
    let b = run_s_pt_stream(&mut pulse_machine(1));
    assert_eq!(format!("{a:?}"), format!("{b:?}"));
}

#[test]
fn running_dry_while_moving_is_an_underrun_fault_with_the_stop_deceleration() {
    let mut e = pulse_machine(1);
    ok(
        &mut e,
        Command::from(StreamConfig {
            axis: 0,
            mode: StreamMode::Refresh,
            loop_count: 0,
            stop_deceleration: Some(50_000.0),
        }),
    );
    // Up to 10 p/ms (10 000 units/s), then even: still moving at the last point.
    ok(
        &mut e,
        push(
            0,
            &[
                (500.0, 100.0, PtKind::Normal),
                (1500.0, 200.0, PtKind::Even),
            ],
        ),
    );
    let id = start_ok(&mut e, &[0])[0];
    step_n(&mut e, 199);
    assert_eq!(status(&e).cmd_vel, 10_000.0);
    e.step();
    let s = status(&e);
    assert_eq!(s.state, AxisState::ErrorStop);
    assert!(s
        .latched
        .contains(AxisFlags::STREAM_UNDERRUN | AxisFlags::MOTION_ERROR));
    assert_eq!(s.last_error, Some(ErrorKind::Fault));
    assert_eq!(s.stream.underruns, 1);
    assert!(!s.stream.running);
    assert_eq!(state_of(&mut e, id), CommandState::Error(ErrorKind::Fault));
    // 10 000 units/s at 50 000 units/s²: at rest 0.2 s later.
    step_n(&mut e, 100);
    let v = status(&e).cmd_vel;
    assert!((v - 5_000.0).abs() < 100.0, "{v}");
    step_n(&mut e, 150);
    let s = status(&e);
    assert_eq!(s.cmd_vel, 0.0);
    // 1500 + 10 000 units/s · 0.2 s / 2.
    assert!((s.cmd_pos - 2_500.0).abs() < 15.0, "{}", s.cmd_pos);
    assert_eq!(s.state, AxisState::ErrorStop);
    let err = refused(&mut e, Command::from(StreamStart { axes: vec![0] }));
    assert_eq!(err.innermost().kind(), ErrorKind::AxisInError);
    ok(&mut e, Command::from(Reset { axis: 0 }));
    let s = status(&e);
    assert_eq!(s.state, AxisState::Standstill);
    assert!(s.latched.is_empty());
    assert_eq!(s.stream.underruns, 1);
}

#[test]
fn several_axes_start_in_the_same_tick_or_none_does() {
    let mut e = pulse_machine(3);
    for axis in 0..3 {
        ok(&mut e, config(axis, StreamMode::Static, 1));
    }
    ok(&mut e, push(0, &STATIC_POINTS));
    ok(&mut e, push(1, &[(-1_000.0, 50.0, PtKind::Stop)]));
    // Axis 2 has no points: the whole start is refused and names it.
    let err = refused(
        &mut e,
        Command::from(StreamStart {
            axes: vec![0, 1, 2],
        }),
    );
    assert!(
        matches!(
            &err,
            EngineError::Item {
                list: "axes",
                index: 2,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(err.kind(), ErrorKind::InvalidState);
    for axis in 0..3 {
        let s = e.axis_status(axis).unwrap();
        assert_eq!(s.state, AxisState::Standstill);
        assert!(!s.stream.running);
    }
    ok(&mut e, push(2, &[(7.0, 10.0, PtKind::Even)]));
    let ids = start_ok(&mut e, &[2, 0, 1]);
    assert_eq!(ids.len(), 3);
    e.step();
    // All three take their first sample on the same tick.
    let s: Vec<_> = (0..3).map(|a| e.axis_status(a).unwrap()).collect();
    assert_eq!(s[0].cmd_pos, 1.0, "½·2 p/ms²·(1 ms)²");
    // STOP: starts at 2·Δp/Δt = −40 p/ms and ends at rest: −40·1 + ½·0.8·1².
    assert!((s[1].cmd_pos + 39.6).abs() < 1e-9, "{}", s[1].cmd_pos);
    assert!((s[2].cmd_pos - 0.7).abs() < 1e-12, "{}", s[2].cmd_pos);
    assert!(s.iter().all(|s| s.stream.time_ms == 1.0));
}

#[test]
fn a_refused_push_names_the_point_and_leaves_the_buffer_as_it_was() {
    let mut e = pulse_machine(1);
    ok(&mut e, push(0, &[(100.0, 10.0, PtKind::Normal)]));
    for (points, bad, problem) in [
        (
            vec![(200.0, 20.0, PtKind::Normal), (300.0, 20.0, PtKind::Normal)],
            1,
            "not after",
        ),
        (vec![(200.0, 5.0, PtKind::Normal)], 0, "not after"),
        (vec![(200.0, 10.0, PtKind::Normal)], 0, "not after"),
        (
            vec![
                (200.0, 20.0, PtKind::Normal),
                (f64::NAN, 30.0, PtKind::Normal),
            ],
            1,
            "finite",
        ),
        (vec![(200.0, f64::INFINITY, PtKind::Normal)], 0, "finite"),
        (vec![(1e13, 20.0, PtKind::Normal)], 0, "finite"),
    ] {
        let err = refused(&mut e, push(0, &points));
        match &err {
            EngineError::StreamPoint { axis: 0, point, .. } => assert_eq!(*point, bad, "{err}"),
            other => panic!("{other}"),
        }
        assert!(err.to_string().contains(problem), "{err}");
        assert_eq!(err.kind(), ErrorKind::InvalidArgument);
        assert_eq!(status(&e).stream.used, 1, "{err}");
    }
    let err = refused(&mut e, push(7, &[(1.0, 1.0, PtKind::Normal)]));
    assert_eq!(err.kind(), ErrorKind::InvalidAxis);
}

#[test]
fn the_axis_velocity_and_acceleration_limits_refuse_a_stream_that_would_exceed_them() {
    let mut e = pulse_machine(1);
    set(&mut e, ParamId::MaxVelocity, 150_000.0);
    let err = refused(&mut e, push(0, &STATIC_POINTS));
    match err {
        EngineError::StreamPoint {
            point: 0,
            problem: StreamPointProblem::VelocityLimit { velocity, limit },
            ..
        } => assert_eq!((velocity, limit), (200_000.0, 150_000.0)),
        other => panic!("{other}"),
    }
    set(&mut e, ParamId::MaxVelocity, 200_000.0);
    set(&mut e, ParamId::MaxAccel, 1e6);
    let err = refused(&mut e, push(0, &STATIC_POINTS));
    assert!(
        matches!(
            err,
            EngineError::StreamPoint {
                problem: StreamPointProblem::AccelerationLimit { .. },
                ..
            }
        ),
        "{err}"
    );
    set(&mut e, ParamId::MaxAccel, 2e6);
    ok(&mut e, push(0, &STATIC_POINTS));
}

#[test]
fn a_hard_limit_ends_the_stream_and_the_axis_stops_with_the_limit_deceleration() {
    let mut e = enabled(stepper_mm());
    // 0 → 600 mm at 0.6 mm/ms: the positive limit at 500 mm comes first.
    ok(&mut e, push(0, &[(600.0, 1000.0, PtKind::Even)]));
    let id = start_ok(&mut e, &[0])[0];
    run_until(&mut e, 2.0, |s| s.flags.contains(AxisFlags::HW_LIMIT_POS)).unwrap();
    assert_eq!(
        state_of(&mut e, id),
        CommandState::Error(ErrorKind::LimitReached)
    );
    run(&mut e, 0.5);
    let s = status(&e);
    assert_eq!(s.cmd_vel, 0.0);
    assert!(s.cmd_pos < 600.0 && s.cmd_pos > 500.0, "{}", s.cmd_pos);
    // The refresh buffer went with the aborted run.
    assert_eq!(s.stream.used, 0);
}

#[test]
fn stop_aborts_the_stream_a_refresh_buffer_is_dropped_a_static_one_kept() {
    for (mode, kept) in [(StreamMode::Refresh, 0), (StreamMode::Static, 3)] {
        let mut e = pulse_machine(1);
        ok(&mut e, config(0, mode, 1));
        ok(&mut e, push(0, &STATIC_POINTS));
        let id = start_ok(&mut e, &[0])[0];
        step_n(&mut e, 150);
        ok(
            &mut e,
            Command::Axis(AxisCommand::Stop(Stop {
                axis: 0,
                mode: Default::default(),
                deceleration: None,
            })),
        );
        assert_eq!(state_of(&mut e, id), CommandState::Aborted);
        let s = status(&e);
        assert_eq!(s.state, AxisState::Stopping);
        assert_eq!((s.stream.used, s.stream.running), (kept, false));
    }
}

#[test]
fn a_running_stream_refuses_what_would_change_it_under_its_feet() {
    let mut e = pulse_machine(1);
    ok(&mut e, config(0, StreamMode::Static, 1));
    ok(&mut e, push(0, &STATIC_POINTS));
    start_ok(&mut e, &[0]);
    e.step();
    for c in [
        push(0, &[(50_000.0, 400.0, PtKind::Stop)]),
        config(0, StreamMode::Refresh, 0),
        Command::from(StreamClear { axis: 0 }),
        Command::from(StreamStart { axes: vec![0] }),
    ] {
        let err = refused(&mut e, c);
        assert_eq!(err.kind(), ErrorKind::InvalidState, "{err}");
    }
    let err = refused(
        &mut e,
        Command::Axis(AxisCommand::Halt(axes::command::Halt {
            axis: 0,
            deceleration: None,
        })),
    );
    assert_eq!(err.kind(), ErrorKind::InvalidState);
    // Still running as planned.
    step_n(&mut e, 99);
    assert_eq!(status(&e).cmd_pos, 10_000.0);
}

#[test]
fn a_stream_starts_only_at_rest() {
    let mut e = pulse_machine(1);
    ok(&mut e, push(0, &STATIC_POINTS));
    ok(
        &mut e,
        Command::from(MoveVelocity {
            axis: 0,
            velocity: 1_000.0,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: Default::default(),
        }),
    );
    e.step();
    let err = refused(&mut e, Command::from(StreamStart { axes: vec![0] }));
    assert_eq!(err.kind(), ErrorKind::InvalidState, "{err}");
    assert_eq!(status(&e).state, AxisState::ContinuousMotion);
}

#[test]
fn a_stream_into_an_active_limit_is_refused_one_out_of_it_runs() {
    let mut e = enabled(stepper_mm());
    force(&mut e, axes::command::AxisInput::LimitPos, Some(true));
    e.step();
    ok(&mut e, push(0, &[(5.0, 100.0, PtKind::Stop)]));
    let err = refused(&mut e, Command::from(StreamStart { axes: vec![0] }));
    assert_eq!(err.kind(), ErrorKind::LimitActive, "{err}");
    ok(&mut e, Command::from(StreamClear { axis: 0 }));
    ok(&mut e, push(0, &[(-5.0, 100.0, PtKind::Stop)]));
    start_ok(&mut e, &[0]);
    run(&mut e, 0.2);
    assert_eq!(status(&e).cmd_pos, -5.0);
}

#[test]
fn an_aborting_move_or_a_disable_takes_over_from_a_running_stream() {
    let mut e = pulse_machine(1);
    ok(&mut e, push(0, &STATIC_POINTS));
    let id = start_ok(&mut e, &[0])[0];
    step_n(&mut e, 100);
    ok(&mut e, move_abs(0.0));
    assert_eq!(state_of(&mut e, id), CommandState::Aborted);
    let s = status(&e);
    assert_eq!(s.state, AxisState::DiscreteMotion);
    assert_eq!((s.stream.running, s.stream.used), (false, 0));
    // The move starts from the stream's state: no jump in position or velocity.
    e.step();
    let s = status(&e);
    assert!((s.cmd_pos - 10_200.0).abs() < 1.0, "{}", s.cmd_pos);
    ok(&mut e, push(0, &STATIC_POINTS));
    run_until(&mut e, 20.0, |s| s.state == AxisState::Standstill).unwrap();
    let id = start_ok(&mut e, &[0])[0];
    step_n(&mut e, 10);
    ok(&mut e, Command::from(axes::command::Disable { axis: 0 }));
    assert_eq!(state_of(&mut e, id), CommandState::Aborted);
    assert_eq!(status(&e).stream.used, 0);
}
