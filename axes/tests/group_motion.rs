//! Axis groups in motion (issue 11 items 1, 3, 5, 7 and the manuals' cases as far as the engine
//! goes): paths reach their end exactly, members stay within their own limits, buffered
//! outputs, dwells, waits and single-axis moves happen where the path reaches them, stop / halt
//! / continue / override, a member's fault stops the whole group, the queue bound, command
//! states, a one-axis group against the axis's own profile, determinism, LinuxCNC #3773's small
//! blended arcs within the members' acceleration limit.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    ArcDirection, AxisInput, CircleMode, Command, CommandState, Enable, ErrorKind,
    ForceDigitalInput, ForceInput, GroupAxisMove, GroupBufferMode, GroupContinue, GroupCreate,
    GroupDwell, GroupEnable, GroupHalt, GroupParameter, GroupReset, GroupSetOrigin, GroupSetOutput,
    GroupSetOverride, GroupSetParameter, GroupStop, GroupWaitInput, GroupWaitPosition,
    InjectFollowingError, MoveAbsolute, MoveCircularAbsolute, MoveCircularRelative, MoveEllipse,
    MoveLinearAbsolute, MoveLinearRelative, MoveSpline, TransitionMode,
};
use axes::status::{GroupFault, GroupState, GroupStatus};
use axes::{AxisState, Engine, EngineConfig, EngineError, ParamId};
use common::{id_of, ok, refused, state_of, stepper_mm};

const TOL: f64 = 1e-9;

/// `n` stepper axes (speed 100 mm/s, accel 1000 mm/s², limits ±500 mm), all enabled, and a
/// group 1 of the first `members` of them, enabled.
fn machine(n: usize, members: &[u16]) -> Engine {
    let e = Engine::new(&EngineConfig {
        axes: (0..n).map(|_| stepper_mm()).collect(),
        ..EngineConfig::default()
    })
    .unwrap();
    common::with_group(e, members)
}

fn line(position: &[f64]) -> MoveLinearAbsolute {
    common::group_line(1, position)
}

fn circle(aux: &[f64], end: &[f64], direction: ArcDirection) -> MoveCircularAbsolute {
    common::group_arc(1, aux, end, direction)
}

fn group(e: &Engine) -> GroupStatus {
    e.snapshot().groups[0]
}

fn send(e: &mut Engine, c: impl Into<Command>) -> u32 {
    id_of(ok(e, c.into()))
}

/// Step until the group is back in Standby (at most `max_s`); returns the ticks taken.
fn run_to_standby(e: &mut Engine, max_s: f64) -> u64 {
    let n = (max_s / e.period()).round() as u64;
    for k in 1..=n {
        e.step();
        if group(e).state == GroupState::Standby {
            return k;
        }
    }
    panic!("still {:?} after {max_s} s", group(e));
}

fn positions(e: &Engine, axes: usize) -> Vec<f64> {
    (0..axes)
        .map(|a| e.axis_status(a).unwrap().cmd_pos)
        .collect()
}

/// Step through the whole path, checking every member against its own limits each tick.
fn run_within_limits(e: &mut Engine, members: usize, max_s: f64) {
    let n = (max_s / e.period()).round() as u64;
    for _ in 0..n {
        e.step();
        for a in 0..members {
            let s = e.axis_status(a).unwrap();
            assert!(
                s.cmd_vel.abs() <= 100.0 * (1.0 + 1e-9),
                "axis {a}: v {}",
                s.cmd_vel
            );
            assert!(
                s.cmd_acc.abs() <= 1000.0 * (1.0 + 1e-6),
                "axis {a}: a {}",
                s.cmd_acc
            );
        }
        if group(e).state == GroupState::Standby {
            return;
        }
    }
    panic!("path not done after {max_s} s");
}

#[test]
fn a_line_ends_exactly_with_members_synchronized_meanwhile_and_its_command_done() {
    let mut e = machine(3, &[0, 1]);
    let id = send(&mut e, line(&[30.0, 40.0]));
    assert_eq!(group(&e).state, GroupState::Moving);
    assert_eq!(state_of(&mut e, id), CommandState::Waiting);
    e.step();
    e.step();
    assert_eq!(state_of(&mut e, id), CommandState::Running);
    let g = group(&e);
    assert_eq!(g.current_command, Some(id));
    assert_eq!(g.segment, 1);
    assert!(g.path_velocity > 0.0);
    for a in 0..2 {
        assert_eq!(
            e.axis_status(a).unwrap().state,
            AxisState::SynchronizedMotion
        );
    }
    run_within_limits(&mut e, 2, 5.0);
    assert_eq!(positions(&e, 2), [30.0, 40.0]);
    assert_eq!(state_of(&mut e, id), CommandState::Done);
    for a in 0..2 {
        assert_eq!(e.axis_status(a).unwrap().state, AxisState::Standstill);
    }
    common::run(&mut e, 0.05);
    let g = group(&e);
    assert!(g.in_position, "{g:?}");
    assert_eq!(g.position(), &[30.0, 40.0]);
    assert_eq!((g.queue_used, g.current_command), (0, None));
}

#[test]
fn a_one_axis_group_follows_the_axis_own_profile() {
    // Axis 0 alone in a group, axis 1 free: the same move with the same limits.
    let mut e = machine(2, &[0]);
    send(
        &mut e,
        MoveLinearAbsolute {
            velocity: Some(100.0),
            acceleration: Some(1000.0),
            deceleration: Some(1000.0),
            jerk: Some(0.0),
            ..line(&[50.0])
        },
    );
    ok(
        &mut e,
        Command::from(MoveAbsolute {
            axis: 1,
            position: 50.0,
            velocity: Some(100.0),
            acceleration: Some(1000.0),
            deceleration: Some(1000.0),
            jerk: Some(0.0),
            buffer_mode: Default::default(),
        }),
    );
    // The group's first setpoint comes in the next tick's stage 2, the axis's own profile
    // starts sampling at the same tick: compare them tick by tick.
    let mut worst: f64 = 0.0;
    for _ in 0..1000 {
        e.step();
        let (g, a) = (e.axis_status(0).unwrap(), e.axis_status(1).unwrap());
        worst = worst.max((g.cmd_pos - a.cmd_pos).abs());
    }
    assert!(worst < 1e-6, "largest difference {worst}");
    assert_eq!(positions(&e, 2), [50.0, 50.0]);
}

#[test]
fn a_square_with_rounded_corners_never_stops_at_a_corner_and_ends_exactly() {
    let mut e = machine(2, &[0, 1]);
    let corner = |p: &[f64]| MoveLinearAbsolute {
        buffer_mode: GroupBufferMode::BlendingLow,
        transition: TransitionMode::CornerDistance(2.0),
        velocity: Some(50.0),
        ..line(p)
    };
    for p in [[20.0, 0.0], [20.0, 20.0], [0.0, 20.0], [0.0, 0.0]] {
        send(&mut e, corner(&p));
    }
    let mut slowest_mid_path = f64::INFINITY;
    let mut farthest_outside: f64 = 0.0;
    let mut started = false;
    for _ in 0..5000 {
        e.step();
        let g = group(&e);
        if g.state != GroupState::Moving {
            break;
        }
        let [x, y] = [g.position()[0], g.position()[1]];
        farthest_outside = farthest_outside.max(-x).max(-y).max(x - 20.0).max(y - 20.0);
        if g.path_velocity > 1.0 {
            started = true;
        }
        // Between the first and the last segment the speed never drops to 0.
        if started && g.segment >= 2 && g.segment <= 4 && g.remaining_length > 2.0 {
            slowest_mid_path = slowest_mid_path.min(g.path_velocity);
        }
    }
    assert!(slowest_mid_path > 1.0, "slowest {slowest_mid_path}");
    assert!(
        farthest_outside <= TOL,
        "left the square by {farthest_outside}"
    );
    run_to_standby(&mut e, 1.0);
    assert_eq!(positions(&e, 2), [0.0, 0.0]);
}

#[test]
fn a_full_circle_stays_on_its_radius_and_ends_where_it_started() {
    let mut e = machine(2, &[0, 1]);
    send(&mut e, line(&[10.0, 0.0]));
    send(&mut e, circle(&[0.0, 0.0], &[10.0, 0.0], ArcDirection::Ccw));
    let mut worst: f64 = 0.0;
    let mut went_up = false;
    for _ in 0..10_000 {
        e.step();
        let g = group(&e);
        if g.segment == 2 {
            let r = g.position()[0].hypot(g.position()[1]);
            worst = worst.max((r - 10.0).abs());
            went_up |= g.position()[1] > 9.0;
        }
        if g.state == GroupState::Standby {
            break;
        }
    }
    assert!(
        went_up,
        "counter-clockwise from (10, 0) goes through +y first"
    );
    assert!(worst < 1e-6, "off the radius by {worst}");
    assert_eq!(positions(&e, 2), [10.0, 0.0]);
}

#[test]
fn radius_arcs_take_the_minor_or_the_major_arc_by_the_sign() {
    for (radius, min_y) in [(10.0, -0.1), (-10.0, -10.0)] {
        let mut e = machine(2, &[0, 1]);
        send(
            &mut e,
            MoveCircularAbsolute {
                mode: CircleMode::Radius,
                radius: Some(radius),
                ..circle(&[], &[10.0, 10.0], ArcDirection::Ccw)
            },
        );
        let mut lowest = f64::INFINITY;
        for _ in 0..10_000 {
            e.step();
            lowest = lowest.min(group(&e).position()[1]);
            if group(&e).state == GroupState::Standby {
                break;
            }
        }
        // Minor arc (centre (0, 10)): y never below 0; major arc (centre (10, 0)) dips to −10.
        assert!(lowest >= min_y - 1e-6, "r {radius}: lowest {lowest}");
        if radius < 0.0 {
            assert!(lowest < -9.9, "r {radius}: lowest {lowest}");
        }
        assert_eq!(positions(&e, 2), [10.0, 10.0]);
    }
}

#[test]
fn a_five_turn_helix_climbs_linearly_and_ends_exactly() {
    // NMC TV 46: centre (5, 0), end = start in XY, z to 10 over 5 turns.
    let mut e = machine(3, &[0, 1, 2]);
    send(
        &mut e,
        MoveCircularAbsolute {
            turns: 4,
            velocity: Some(100.0),
            ..circle(&[5.0, 0.0, 0.0], &[0.0, 0.0, 10.0], ArcDirection::Ccw)
        },
    );
    // The angle about the centre, unwrapped: z = 10 · angle / (5 · 2π) all the way.
    let tau = std::f64::consts::TAU;
    let mut angle = 0.0;
    let mut last = std::f64::consts::PI;
    for _ in 0..20_000 {
        e.step();
        let g = group(&e);
        let (x, y, z) = (g.position()[0], g.position()[1], g.position()[2]);
        let now = y.atan2(x - 5.0);
        angle += (now - last + std::f64::consts::PI).rem_euclid(tau) - std::f64::consts::PI;
        last = now;
        assert!(
            (z - 10.0 * angle / (5.0 * tau)).abs() < 1e-6,
            "z {z} at {angle} rad"
        );
        if g.state == GroupState::Standby {
            break;
        }
    }
    assert!((angle - 5.0 * tau).abs() < 1e-6, "{angle}");
    assert_eq!(positions(&e, 3), [0.0, 0.0, 10.0]);
}

#[test]
fn extra_axes_ride_along_an_arc_in_proportion() {
    // NMC D8 / HMC MoveND: a 4-axis group, an arc in XY, the 3rd and 4th axes linear.
    let mut e = machine(4, &[0, 1, 2, 3]);
    send(
        &mut e,
        MoveCircularRelative {
            group: 1,
            mode: CircleMode::Center,
            aux_point: vec![10.0, 0.0, 0.0, 0.0],
            radius: None,
            end_point: vec![20.0, 0.0, 8.0, -4.0],
            direction: ArcDirection::Cw,
            plane: Some([0, 1]),
            normal: None,
            turns: 0,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: GroupBufferMode::Buffered,
            transition: TransitionMode::None,
            user_segment: None,
            independent: Default::default(),
            coordinate_system: None,
        },
    );
    for _ in 0..10_000 {
        e.step();
        let g = group(&e);
        let p = g.position();
        // Half a circle: the angle from the start is proportional to z and w.
        let angle = (p[1]).atan2(10.0 - p[0]).abs();
        let progress = if p[0] > 10.0 {
            std::f64::consts::PI - (-p[1]).atan2(p[0] - 10.0).abs()
        } else {
            angle
        } / std::f64::consts::PI;
        assert!((p[2] - 8.0 * progress).abs() < 1e-6, "{p:?}");
        assert!((p[3] + 4.0 * progress).abs() < 1e-6, "{p:?}");
        if g.state == GroupState::Standby {
            break;
        }
    }
    assert_eq!(positions(&e, 4), [20.0, 0.0, 8.0, -4.0]);
}

#[test]
fn a_buffered_output_is_set_where_the_path_reaches_it_and_a_dwell_holds_the_path() {
    let mut e = machine(2, &[0, 1]);
    send(&mut e, line(&[10.0, 0.0]));
    let do_id = send(
        &mut e,
        GroupSetOutput {
            group: 1,
            channel: 5,
            value: true,
        },
    );
    let dwell = send(
        &mut e,
        GroupDwell {
            group: 1,
            seconds: 0.2,
        },
    );
    send(&mut e, line(&[10.0, 10.0]));
    assert_eq!(group(&e).queue_used, 4);
    let mut set_at = None;
    let mut still_ticks = 0;
    for _ in 0..5000 {
        e.step();
        let s = e.snapshot();
        if set_at.is_none() && s.io.do_[5] {
            set_at = Some(s.groups[0].position().to_vec());
        }
        if s.groups[0].current_command == Some(dwell) {
            still_ticks += 1;
            assert_eq!(s.groups[0].position(), &[10.0, 0.0]);
        }
        if s.groups[0].state == GroupState::Standby {
            break;
        }
    }
    assert_eq!(set_at, Some(vec![10.0, 0.0]));
    assert_eq!(still_ticks, 200);
    assert_eq!(state_of(&mut e, do_id), CommandState::Done);
    assert_eq!(state_of(&mut e, dwell), CommandState::Done);
    assert_eq!(positions(&e, 2), [10.0, 10.0]);
}

#[test]
fn a_wait_for_an_input_holds_the_path_until_the_level_and_times_out_to_error_stop() {
    let mut e = machine(2, &[0, 1]);
    send(&mut e, line(&[5.0, 0.0]));
    let wait = send(
        &mut e,
        GroupWaitInput {
            group: 1,
            channel: 3,
            level: true,
            timeout: None,
        },
    );
    send(&mut e, line(&[5.0, 5.0]));
    common::run(&mut e, 1.0);
    assert_eq!(group(&e).current_command, Some(wait));
    assert_eq!(positions(&e, 2), [5.0, 0.0]);
    ok(
        &mut e,
        Command::from(ForceDigitalInput {
            channel: 3,
            value: Some(true),
        }),
    );
    run_to_standby(&mut e, 2.0);
    assert_eq!(positions(&e, 2), [5.0, 5.0]);

    let timed = send(
        &mut e,
        GroupWaitInput {
            group: 1,
            channel: 4,
            level: true,
            timeout: Some(0.1),
        },
    );
    let after = send(&mut e, line(&[0.0, 0.0]));
    common::run(&mut e, 0.2);
    let g = group(&e);
    assert_eq!(g.state, GroupState::ErrorStop);
    assert_eq!(g.fault, Some(GroupFault::WaitTimeout { command: timed }));
    assert_eq!(
        state_of(&mut e, timed),
        CommandState::Error(ErrorKind::Fault)
    );
    assert_eq!(state_of(&mut e, after), CommandState::Aborted);
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(group(&e).state, GroupState::Standby);
}

#[test]
fn a_buffered_axis_move_starts_with_the_next_segment_and_a_position_wait_follows_it() {
    let mut e = machine(3, &[0, 1]);
    send(&mut e, line(&[10.0, 0.0]));
    send(
        &mut e,
        GroupAxisMove {
            group: 1,
            axis: 2,
            position: 20.0,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
        },
    );
    send(&mut e, line(&[10.0, 10.0]));
    send(
        &mut e,
        GroupWaitPosition {
            group: 1,
            axis: 2,
            position: 20.0,
            tolerance: Some(0.01),
            timeout: None,
            condition: Default::default(),
            source: Default::default(),
        },
    );
    send(&mut e, line(&[0.0, 10.0]));
    let mut axis2_started_at = None;
    for _ in 0..10_000 {
        e.step();
        let s = e.snapshot();
        if axis2_started_at.is_none() && s.axes[2].cmd_pos != 0.0 {
            axis2_started_at = Some(s.groups[0].position().to_vec());
        }
        let p = s.groups[0].position();
        if p[1] == 10.0 && p[0] < 10.0 {
            // The last segment starts only once axis 2 has arrived.
            assert!((s.axes[2].act_pos - 20.0).abs() <= 0.01, "{:?}", s.axes[2]);
        }
        if s.groups[0].state == GroupState::Standby {
            break;
        }
    }
    let start = axis2_started_at.unwrap();
    assert_eq!(start[0], 10.0);
    assert!(start[1] < 1.0, "{start:?}");
    assert_eq!(positions(&e, 3), [0.0, 10.0, 20.0]);
}

#[test]
fn stop_drops_the_queue_and_halt_keeps_it_for_continue() {
    let mut e = machine(2, &[0, 1]);
    let first = send(&mut e, line(&[100.0, 0.0]));
    let second = send(&mut e, line(&[100.0, 100.0]));
    common::run(&mut e, 0.3);
    ok(
        &mut e,
        Command::from(GroupHalt {
            group: 1,
            deceleration: None,
        }),
    );
    assert_eq!(group(&e).state, GroupState::Halted);
    common::run(&mut e, 0.5);
    let held = positions(&e, 2);
    common::run(&mut e, 0.1);
    assert_eq!(positions(&e, 2), held, "at rest while halted");
    assert_eq!(group(&e).queue_used, 2, "the queue is kept");
    ok(&mut e, Command::from(GroupContinue { group: 1 }));
    assert_eq!(group(&e).state, GroupState::Moving);
    common::run(&mut e, 0.2);
    ok(
        &mut e,
        Command::from(GroupStop {
            group: 1,
            deceleration: Some(2000.0),
        }),
    );
    assert_eq!(group(&e).state, GroupState::Stopping);
    assert_eq!(
        refused(&mut e, Command::from(line(&[0.0, 0.0]))).kind(),
        ErrorKind::GroupState
    );
    run_to_standby(&mut e, 1.0);
    assert_eq!(state_of(&mut e, first), CommandState::Aborted);
    assert_eq!(state_of(&mut e, second), CommandState::Aborted);
    let g = group(&e);
    assert_eq!(g.queue_used, 0);
    assert!(g.position()[0] < 100.0 && g.position()[1] == 0.0, "{g:?}");
    // And it takes motion again.
    send(&mut e, line(&[0.0, 0.0]));
    run_to_standby(&mut e, 3.0);
    assert_eq!(positions(&e, 2), [0.0, 0.0]);
}

#[test]
fn an_override_of_one_half_takes_about_twice_as_long() {
    let timed = |factor: f64| {
        let mut e = machine(2, &[0, 1]);
        ok(&mut e, Command::from(GroupSetOverride { group: 1, factor }));
        send(
            &mut e,
            MoveLinearAbsolute {
                velocity: Some(20.0),
                ..line(&[60.0, 80.0])
            },
        );
        run_to_standby(&mut e, 30.0)
    };
    let (full, half) = (timed(1.0), timed(0.5));
    let ratio = half as f64 / full as f64;
    assert!((1.8..2.05).contains(&ratio), "{full} vs {half} ticks");
}

/// Axis 1 meets its positive limit switch.
fn limit_switch_on_axis_1(e: &mut Engine) {
    ok(
        e,
        Command::from(ForceInput {
            axis: 1,
            input: AxisInput::LimitPos,
            value: Some(true),
        }),
    );
}

/// The group's fault after axis 1 meets its positive limit switch.
const LIMIT_ON_AXIS_1: Option<GroupFault> = Some(GroupFault::Member {
    axis: 1,
    error: ErrorKind::LimitReached,
});

#[test]
fn a_member_on_a_limit_switch_stops_the_whole_group_in_error_stop() {
    let mut e = machine(2, &[0, 1]);
    let id = send(&mut e, line(&[200.0, 200.0]));
    common::run(&mut e, 0.5);
    limit_switch_on_axis_1(&mut e);
    common::run(&mut e, 0.01);
    let g = group(&e);
    assert_eq!((g.state, g.fault), (GroupState::ErrorStop, LIMIT_ON_AXIS_1));
    assert_eq!(g.last_error, Some(ErrorKind::LimitReached));
    assert_eq!(
        state_of(&mut e, id),
        CommandState::Error(ErrorKind::LimitReached)
    );
    // Both members come to rest on their own.
    common::run(&mut e, 1.0);
    for a in 0..2 {
        assert_eq!(e.axis_status(a).unwrap().cmd_vel, 0.0);
    }
    // The motion is refused until a reset, which works once the members are at rest.
    assert_eq!(
        refused(&mut e, Command::from(line(&[0.0, 0.0]))).kind(),
        ErrorKind::GroupState
    );
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    send(&mut e, line(&[0.0, 0.0]));
    run_to_standby(&mut e, 10.0);
    assert_eq!(positions(&e, 2), [0.0, 0.0]);
}

/// How far axis 0 travels after axis 1 of a group running (200, 200) at 100 mm/s hits its
/// limit switch, and axis 0's states meanwhile; the members' own `decel` is 200 mm/s², their
/// acceleration limit 1000 mm/s². `fault_deceleration` is set first if given.
fn stop_after_a_members_limit(fault_deceleration: Option<f64>) -> (f64, Vec<AxisState>, Engine) {
    let mut axis = stepper_mm();
    axis.params.insert(ParamId::Decel, 200.0);
    let e = Engine::new(&EngineConfig {
        axes: vec![axis; 2],
        ..EngineConfig::default()
    })
    .unwrap();
    let mut e = common::with_group(e, &[0, 1]);
    if let Some(value) = fault_deceleration {
        ok(
            &mut e,
            Command::from(GroupSetParameter {
                group: 1,
                name: GroupParameter::FaultDeceleration,
                value,
            }),
        );
    }
    send(&mut e, line(&[200.0, 200.0]));
    common::run(&mut e, 0.5);
    let from = e.axis_status(0).unwrap().cmd_pos;
    limit_switch_on_axis_1(&mut e);
    let mut states = Vec::new();
    for _ in 0..2000 {
        e.step();
        let s = e.axis_status(0).unwrap();
        states.push(s.state);
        if s.cmd_vel == 0.0 {
            break;
        }
    }
    let g = group(&e);
    assert_eq!((g.state, g.fault), (GroupState::ErrorStop, LIMIT_ON_AXIS_1));
    (e.axis_status(0).unwrap().cmd_pos - from, states, e)
}

/// HMC §4.3, §6.1 (b)/(c) (digest 000): a member at its limit cancels the whole interpolation,
/// which stops along the path with max(deceleration, FastDecel): the other members stay on it
/// (SynchronizedMotion) until it rests. The default (NMC, HIMC §3.6: the group drops out of
/// sync): each member ramps down with its own `decel`.
#[test]
fn with_a_fault_deceleration_a_members_limit_stops_the_path_along_itself() {
    // 70.7 mm/s per axis: own decel 200 → 12.5 mm; along the path, max(5000, 8000) capped by
    // the members' 1000 mm/s² (1414 along the diagonal) → 2.5 mm plus the jerk ramp.
    let (own, states, _) = stop_after_a_members_limit(None);
    assert!(own > 12.0, "{own}");
    // Fed for the tick in which axis 1 meets its switch, then on its own.
    let fed = |states: &[AxisState]| {
        states
            .iter()
            .filter(|s| **s == AxisState::SynchronizedMotion)
            .count()
    };
    assert!(fed(&states) <= 1, "{states:?}");
    let (along, states, mut e) = stop_after_a_members_limit(Some(8000.0));
    assert!(along < 4.0, "{along}");
    assert!(fed(&states) >= states.len() - 1, "{states:?}");
    common::run(&mut e, 0.1);
    assert_eq!(e.axis_status(0).unwrap().state, AxisState::Standstill);
    assert_eq!(group(&e).path_velocity, 0.0);
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(group(&e).state, GroupState::Standby);
    // 0 turns the rule off again; a negative value is refused.
    for (value, accepted) in [(0.0, true), (-1.0, false), (f64::NAN, false)] {
        let c = Command::from(GroupSetParameter {
            group: 1,
            name: GroupParameter::FaultDeceleration,
            value,
        });
        if accepted {
            ok(&mut e, c);
        } else {
            assert_eq!(refused(&mut e, c).kind(), ErrorKind::InvalidArgument);
        }
    }
}

/// HMC's stop along the path that ends where a dwell holds the path: the stop ends there, the
/// members are let go and the group can be reset.
#[test]
fn a_fault_stop_along_the_path_ends_at_a_dwell_it_reaches() {
    let mut e = machine(2, &[0, 1]);
    ok(
        &mut e,
        Command::from(GroupSetParameter {
            group: 1,
            name: GroupParameter::FaultDeceleration,
            value: 8000.0,
        }),
    );
    send(&mut e, line(&[10.0, 10.0]));
    send(
        &mut e,
        GroupDwell {
            group: 1,
            seconds: 5.0,
        },
    );
    send(&mut e, line(&[0.0, 0.0]));
    // In the last ramp of the first line: the stop ends at its end, the dwell's place.
    common::run(&mut e, 0.2);
    assert!(group(&e).path_velocity > 0.0);
    limit_switch_on_axis_1(&mut e);
    common::run(&mut e, 0.3);
    let g = group(&e);
    assert_eq!((g.state, g.fault), (GroupState::ErrorStop, LIMIT_ON_AXIS_1));
    assert_eq!(g.path_velocity, 0.0);
    assert_eq!(e.axis_status(0).unwrap().state, AxisState::Standstill);
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(group(&e).queue_used, 0);
}

#[test]
fn a_member_following_error_fault_stops_the_group_and_reset_needs_the_fault_cleared() {
    let mut e = machine(2, &[0, 1]);
    send(&mut e, line(&[100.0, 50.0]));
    common::run(&mut e, 0.2);
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: Some(5.0),
        }),
    );
    common::run(&mut e, 0.05);
    let g = group(&e);
    assert_eq!(g.state, GroupState::ErrorStop);
    assert!(
        matches!(g.fault, Some(GroupFault::Member { axis: 0, .. })),
        "{g:?}"
    );
    assert_eq!(
        refused(&mut e, Command::from(GroupReset { group: 1 })).kind(),
        ErrorKind::CauseStillPresent
    );
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: None,
        }),
    );
    common::run(&mut e, 1.0);
    ok(&mut e, Command::from(axes::command::Reset { axis: 0 }));
    ok(&mut e, Command::from(Enable { axis: 0 }));
    common::run(&mut e, 0.01);
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(group(&e).state, GroupState::Standby);
}

#[test]
fn the_queue_bound_holds_motions_and_buffered_commands_together() {
    let mut e = Engine::new(&EngineConfig {
        axes: vec![stepper_mm(), stepper_mm()],
        ..EngineConfig::default()
    })
    .unwrap();
    for axis in 0..2 {
        ok(&mut e, Command::from(Enable { axis }));
    }
    ok(
        &mut e,
        Command::from(GroupCreate {
            group: 1,
            axes: vec![0, 1],
            queue_capacity: Some(3),
            lookahead: None,
            result_axis: None,
            orientation: Default::default(),
        }),
    );
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    send(&mut e, line(&[1.0, 0.0]));
    send(
        &mut e,
        GroupSetOutput {
            group: 1,
            channel: 0,
            value: true,
        },
    );
    send(&mut e, line(&[1.0, 1.0]));
    let err = refused(&mut e, Command::from(line(&[0.0, 0.0])));
    assert_eq!(
        err,
        EngineError::GroupQueueFull {
            group: 1,
            capacity: 3
        }
    );
    assert_eq!(err.kind(), ErrorKind::QueueFull);
    assert_eq!((group(&e).queue_used, group(&e).queue_free), (3, 0));
    run_to_standby(&mut e, 2.0);
    assert_eq!(positions(&e, 2), [1.0, 1.0]);
}

#[test]
fn an_aborting_motion_stops_the_path_and_goes_to_its_own_target() {
    let mut e = machine(2, &[0, 1]);
    let first = send(&mut e, line(&[100.0, 0.0]));
    common::run(&mut e, 0.3);
    let second = send(
        &mut e,
        MoveLinearAbsolute {
            buffer_mode: GroupBufferMode::Aborting,
            ..line(&[0.0, 30.0])
        },
    );
    assert_eq!(state_of(&mut e, second), CommandState::Waiting);
    run_to_standby(&mut e, 10.0);
    assert_eq!(state_of(&mut e, first), CommandState::Aborted);
    assert_eq!(state_of(&mut e, second), CommandState::Done);
    assert_eq!(positions(&e, 2), [0.0, 30.0]);
}

#[test]
fn relative_moves_chain_from_the_queue_end_and_the_origin_offsets_group_coordinates() {
    let mut e = machine(2, &[0, 1]);
    ok(
        &mut e,
        Command::from(GroupSetOrigin {
            group: 1,
            offset: vec![100.0, -50.0],
        }),
    );
    assert_eq!(group(&e).position(), &[-100.0, 50.0]);
    send(&mut e, line(&[-90.0, 50.0]));
    for _ in 0..2 {
        send(
            &mut e,
            MoveLinearRelative {
                group: 1,
                distance: vec![0.0, 5.0],
                velocity: None,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode: GroupBufferMode::Buffered,
                transition: TransitionMode::None,
                user_segment: Some(42),
                independent: Default::default(),
                coordinate_system: None,
            },
        );
    }
    let mut saw_user_segment = false;
    for _ in 0..5000 {
        e.step();
        saw_user_segment |= group(&e).user_segment == 42;
        if group(&e).state == GroupState::Standby {
            break;
        }
    }
    assert!(saw_user_segment);
    assert_eq!(group(&e).position(), &[-90.0, 60.0]);
    // Machine coordinates = group coordinates + origin.
    assert_eq!(positions(&e, 2), [10.0, 10.0]);
}

#[test]
fn the_same_commands_at_the_same_ticks_give_bit_identical_snapshots() {
    let trace = || {
        let mut e = machine(3, &[0, 1, 2]);
        let mut out = Vec::new();
        send(
            &mut e,
            MoveLinearAbsolute {
                buffer_mode: GroupBufferMode::BlendingHigh,
                transition: TransitionMode::CornerDeviation(0.5),
                ..line(&[20.0, 10.0, 5.0])
            },
        );
        send(
            &mut e,
            MoveCircularAbsolute {
                buffer_mode: GroupBufferMode::BlendingLow,
                ..circle(&[20.0, 20.0, 5.0], &[20.0, 30.0, 0.0], ArcDirection::Cw)
            },
        );
        for k in 0..3000 {
            if k == 700 {
                ok(
                    &mut e,
                    Command::from(GroupSetOverride {
                        group: 1,
                        factor: 0.7,
                    }),
                );
            }
            e.step();
            let s = e.snapshot();
            out.push((s.axes.clone(), s.groups.clone()));
        }
        out
    };
    let (a, b) = (trace(), trace());
    assert!(a == b, "two runs differ");
    let last = &a.last().unwrap().1[0];
    assert_eq!(last.position(), &[20.0, 30.0, 0.0]);
}

#[test]
fn a_parameter_change_of_a_member_limits_the_next_path() {
    let mut e = machine(2, &[0, 1]);
    ok(
        &mut e,
        Command::from(axes::command::SetParameter {
            axis: 0,
            name: ParamId::MaxVelocity,
            value: 10.0,
            lenient: false,
        }),
    );
    send(&mut e, line(&[50.0, 0.0]));
    let mut fastest: f64 = 0.0;
    for _ in 0..10_000 {
        e.step();
        fastest = fastest.max(e.axis_status(0).unwrap().cmd_vel.abs());
        if group(&e).state == GroupState::Standby {
            break;
        }
    }
    assert!(fastest <= 10.0 + 1e-9, "{fastest}");
    assert_eq!(positions(&e, 2), [50.0, 0.0]);
}

#[test]
fn a_member_refuses_set_position_while_the_path_runs_and_takes_it_between_paths() {
    let mut e = machine(2, &[0, 1]);
    send(&mut e, line(&[50.0, 0.0]));
    common::run(&mut e, 0.1);
    let set = |position| {
        Command::from(axes::command::SetPosition {
            axis: 0,
            position,
            frame: Default::default(),
        })
    };
    let err = refused(&mut e, set(0.0));
    assert_eq!(err, EngineError::AxisInGroup { axis: 0, group: 1 });
    run_to_standby(&mut e, 5.0);
    ok(&mut e, set(100.0));
    // The next path starts from the re-based position.
    assert_eq!(group(&e).position(), &[100.0, 0.0]);
    send(&mut e, line(&[110.0, 0.0]));
    run_to_standby(&mut e, 5.0);
    assert_eq!(positions(&e, 2), [110.0, 0.0]);
}

#[test]
fn a_refused_batch_with_group_commands_leaves_the_groups_as_they_were() {
    let mut e = machine(2, &[0, 1]);
    let before = group(&e);
    let err = e
        .apply_batch(vec![
            Command::from(line(&[10.0, 0.0])),
            Command::from(line(&[f64::NAN, 0.0])),
        ])
        .unwrap_err();
    assert_eq!(err.kind(), ErrorKind::InvalidArgument);
    assert_eq!(group(&e), before, "the first motion was taken back");
    common::run(&mut e, 0.1);
    assert_eq!(positions(&e, 2), [0.0, 0.0]);
    let replies = e
        .apply_batch(vec![Command::from(line(&[10.0, 0.0]))])
        .unwrap();
    assert_eq!(replies.len(), 1);
    run_to_standby(&mut e, 5.0);
    assert_eq!(positions(&e, 2), [10.0, 0.0]);
}

#[test]
fn machine_wide_stop_drops_the_path_and_emergency_stop_puts_the_group_in_error_stop() {
    let mut e = machine(2, &[0, 1]);
    let id = send(&mut e, line(&[100.0, 0.0]));
    common::run(&mut e, 0.3);
    ok(
        &mut e,
        Command::from(axes::command::StopAll {
            mode: Default::default(),
            deceleration: None,
        }),
    );
    assert_eq!(group(&e).state, GroupState::Standby);
    assert_eq!(state_of(&mut e, id), CommandState::Aborted);
    common::run(&mut e, 1.0);
    assert_eq!(group(&e).state, GroupState::Standby, "{:?}", group(&e));
    send(&mut e, line(&[0.0, 0.0]));
    common::run(&mut e, 0.1);
    ok(&mut e, Command::from(axes::command::EmergencyStopAll {}));
    let g = group(&e);
    assert_eq!(
        (g.state, g.fault),
        (GroupState::ErrorStop, Some(GroupFault::EmergencyStop))
    );
}

/// Peak path velocity over a full circle of radius 10 after `parameters` are set on group 1.
fn circle_peak(parameters: &[(GroupParameter, f64)]) -> f64 {
    let mut e = machine(2, &[0, 1]);
    for &(name, value) in parameters {
        common::group_parameter(&mut e, name, value);
    }
    send(&mut e, line(&[10.0, 0.0]));
    run_to_standby(&mut e, 10.0);
    send(&mut e, circle(&[0.0, 0.0], &[10.0, 0.0], ArcDirection::Ccw));
    let mut peak: f64 = 0.0;
    for _ in 0..100_000 {
        e.step();
        let g = group(&e);
        peak = peak.max(g.path_velocity);
        if g.state == GroupState::Standby {
            break;
        }
    }
    assert_eq!(positions(&e, 2), [10.0, 0.0]);
    peak
}

/// LinuxCNC issue #3773 through the engine (issue 11 "Blending cases"): 200 tangent arcs of
/// radius 3.8–4.2 mm and 20–90° (alternating turn, a slight climb in z), blended at a higher
/// programmed speed than the arcs allow, at 1 kHz; every member's acceleration limit 1750
/// mm/s². The members' commanded positions, differenced twice, never exceed 1.00× the limit
/// (LinuxCNC measured 1.9–8×), and the path ends on the last arc's end.
#[test]
fn linuxcnc_3773_small_blended_arcs_keep_every_members_acceleration_within_its_limit() {
    const ACCEL: f64 = 1750.0;
    let mut e = Engine::new(&EngineConfig {
        axes: (0..3).map(|_| common::fast_mm_axis(400.0, ACCEL)).collect(),
        ..EngineConfig::default()
    })
    .unwrap();
    e = common::with_group(e, &[0, 1, 2]);
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut x, mut y, mut heading) = (0.0f64, 0.0f64, 0.0f64);
    let mut end = [0.0; 3];
    for i in 0..200 {
        let r = 3.8 + 0.4 * rnd();
        let sweep = (20.0 + 70.0 * rnd()).to_radians();
        let ccw = i % 2 == 0;
        let side = if ccw { 1.0 } else { -1.0 };
        // The centre on the left (CCW) or right (CW) of the heading: tangent junctions.
        let normal = heading + side * std::f64::consts::FRAC_PI_2;
        let (cx, cy) = (x + r * normal.cos(), y + r * normal.sin());
        let (sin, cos) = (side * sweep).sin_cos();
        let (dx, dy) = (x - cx, y - cy);
        let (ex, ey) = (cx + dx * cos - dy * sin, cy + dx * sin + dy * cos);
        end = [ex, ey, 0.01 * f64::from(i + 1)];
        send(
            &mut e,
            MoveCircularAbsolute {
                velocity: Some(2000.0),
                acceleration: Some(20_000.0),
                deceleration: Some(20_000.0),
                jerk: Some(0.0),
                buffer_mode: GroupBufferMode::BlendingHigh,
                ..circle(
                    &[cx, cy, 0.0],
                    &end,
                    if ccw {
                        ArcDirection::Ccw
                    } else {
                        ArcDirection::Cw
                    },
                )
            },
        );
        (x, y) = (ex, ey);
        heading += side * sweep;
    }
    let t = e.period();
    let mut trace: Vec<Vec<f64>> = vec![positions(&e, 3)];
    let mut top: f64 = 0.0;
    for _ in 0..60_000 {
        e.step();
        trace.push(positions(&e, 3));
        top = top.max(group(&e).path_velocity);
        if group(&e).state == GroupState::Standby {
            break;
        }
    }
    assert_eq!(group(&e).state, GroupState::Standby);
    assert_eq!(positions(&e, 3), end);
    let mut peak: f64 = 0.0;
    for k in 0..3 {
        // A second difference of three rounded positions errs by ≤ 4ε|x|/T².
        let scale = trace.iter().map(|p| p[k].abs()).fold(1.0, f64::max);
        let slack = 4.0 * f64::EPSILON * scale / (t * t);
        for w in trace.windows(3) {
            let a = (w[2][k] - 2.0 * w[1][k] + w[0][k]) / (t * t);
            peak = peak.max((a.abs() - slack).max(0.0) / ACCEL);
        }
    }
    assert!(peak <= 1.0, "peak acceleration {peak}× the limit");
    // Nor does it crawl: the arcs run near their curvature speed, √(A/√2·r) ≈ 70 mm/s.
    assert!(top > 60.0, "top path speed {top}");
}

#[test]
fn himc_look_ahead_parameters_cap_the_arc_speed_and_zero_turns_them_off() {
    // HIMC SetGrpLookAheadPrm prm 1 (digest 004 §2.7): v ≤ √(A_arc·r) = √(20 · 10).
    let capped = circle_peak(&[(GroupParameter::ArcAcceleration, 20.0)]);
    assert!((capped - 200f64.sqrt()).abs() < 1e-6, "{capped}");
    let off = circle_peak(&[
        (GroupParameter::ArcAcceleration, 20.0),
        (GroupParameter::ArcAcceleration, 0.0),
    ]);
    assert!(off > 20.0, "{off}");
    let mut e = machine(2, &[0, 1]);
    for (name, value) in [
        (GroupParameter::ChordError, -1.0),
        (GroupParameter::CornerSlowAngle, 2.0), // above the default stop angle π/2
        (GroupParameter::CornerStopAngle, 4.0), // beyond π
    ] {
        let kind = refused(
            &mut e,
            Command::from(GroupSetParameter {
                group: 1,
                name,
                value,
            }),
        );
        assert_eq!(
            kind.kind(),
            ErrorKind::InvalidArgument,
            "{name:?} = {value}"
        );
    }
}

/// A buffered spline of group 1 through `points` (absolute), group defaults but `velocity`.
fn spline(points: Vec<Vec<f64>>, velocity: Option<f64>) -> MoveSpline {
    MoveSpline {
        velocity,
        ..common::group_spline(1, points)
    }
}

/// A buffered counter-clockwise ellipse of group 1 around `center` (absolute), group defaults.
fn ellipse(center: Vec<f64>, ratio: f64) -> MoveEllipse {
    MoveEllipse {
        group: 1,
        center,
        ratio,
        direction: ArcDirection::Ccw,
        plane: None,
        relative: false,
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: GroupBufferMode::Buffered,
        transition: TransitionMode::None,
        user_segment: None,
        coordinate_system: None,
    }
}

#[test]
fn a_spline_passes_through_its_points_and_ends_exactly_within_the_axis_limits() {
    // HMC MoveSplineND (digest 000 §4.3): a natural cubic spline through the nodes.
    let mut e = machine(2, &[0, 1]);
    let nodes = [[10.0, 5.0], [20.0, -5.0], [30.0, 0.0]];
    send(
        &mut e,
        spline(nodes.iter().map(|n| n.to_vec()).collect(), Some(50.0)),
    );
    // Nearest approach to each node over the run.
    let mut nearest = [f64::INFINITY; 3];
    for _ in 0..20_000 {
        e.step();
        let g = group(&e);
        let (x, y) = (g.position()[0], g.position()[1]);
        for (d, n) in nearest.iter_mut().zip(&nodes) {
            *d = d.min((x - n[0]).hypot(y - n[1]));
        }
        if g.state == GroupState::Standby {
            break;
        }
    }
    assert_eq!(positions(&e, 2), [30.0, 0.0]);
    // Within one tick's travel (≤ 50 mm/s × 1 ms) of every node.
    assert!(nearest.iter().all(|&d| d < 0.05), "{nearest:?}");
    let mut e = machine(2, &[0, 1]);
    send(
        &mut e,
        spline(nodes.iter().map(|n| n.to_vec()).collect(), Some(80.0)),
    );
    run_within_limits(&mut e, 2, 20.0);
}

#[test]
fn an_ellipse_returns_to_its_start_with_semi_axes_from_the_start_and_the_ratio() {
    // NMC CrdEllipse (digest 001 §4.4): centre relative to the start, semi-major = start − centre.
    let mut e = machine(2, &[0, 1]);
    send(&mut e, line(&[10.0, 0.0]));
    run_to_standby(&mut e, 10.0);
    send(
        &mut e,
        MoveEllipse {
            relative: true,
            velocity: Some(40.0),
            ..ellipse(vec![-10.0, 0.0], 0.5)
        },
    );
    let (mut max_y, mut min_x, mut worst) = (f64::MIN, f64::MAX, 0.0f64);
    for _ in 0..20_000 {
        e.step();
        let g = group(&e);
        let (x, y) = (g.position()[0], g.position()[1]);
        max_y = max_y.max(y);
        min_x = min_x.min(x);
        // (x/10)² + (y/5)² = 1 about the centre (0, 0).
        worst = worst.max(((x / 10.0).powi(2) + (y / 5.0).powi(2) - 1.0).abs());
        if g.state == GroupState::Standby {
            break;
        }
    }
    assert_eq!(positions(&e, 2), [10.0, 0.0]);
    assert!(
        (max_y - 5.0).abs() < 1e-3 && (min_x + 10.0).abs() < 1e-3,
        "{max_y} {min_x}"
    );
    assert!(worst < 1e-6, "off the ellipse by {worst}");
}

#[test]
fn bad_splines_and_ellipses_are_refused_and_nothing_is_queued() {
    let mut e = machine(2, &[0, 1]);
    for c in [
        Command::from(spline(vec![], None)),
        Command::from(spline(vec![vec![1.0]], None)),
        Command::from(spline(vec![vec![1.0, f64::NAN]], None)),
        Command::from(spline(vec![vec![1.0, 1.0]; 1001], None)),
        Command::from(ellipse(vec![5.0, 0.0], 0.01)),
        Command::from(ellipse(vec![5.0, 0.0], 1.5)),
        Command::from(ellipse(vec![5.0, 0.0], f64::INFINITY)),
    ] {
        let err = refused(&mut e, c.clone());
        assert_eq!(err.kind(), ErrorKind::InvalidArgument, "{c:?}: {err}");
    }
    assert_eq!(group(&e).queue_used, 0);
}

/// Issue 13 (NMC arc sections, `TArcSecSetting` → `chord_error`): every tick's commanded
/// point lies on the arc, and the chord between two ticks leaves it by at most the chord
/// error (its sagitta r − |midpoint − centre|): the error is between samples, never of them.
#[test]
fn chord_error_samples_lie_on_the_arc_and_chords_stay_within_the_error() {
    let mut e = machine(2, &[0, 1]);
    let epsilon = 1e-6;
    common::group_parameter(&mut e, GroupParameter::ChordError, epsilon);
    // A full circle of radius 10 about (10, 0) from the origin, at 100 mm/s requested: the
    // chord error caps it at 2·r·acos(1 − ε/r)/T = 8.94 mm/s (the axes allow 100).
    common::group_parameter(&mut e, GroupParameter::Velocity, 100.0);
    send(&mut e, circle(&[10.0, 0.0], &[0.0, 0.0], ArcDirection::Ccw));
    let mut last = positions(&e, 2);
    let mut worst_sagitta = 0.0_f64;
    let n = (20.0 / e.period()).round() as u64;
    for _ in 0..n {
        e.step();
        let p = positions(&e, 2);
        let r = ((p[0] - 10.0).powi(2) + p[1].powi(2)).sqrt();
        assert!((r - 10.0).abs() < 1e-9, "a sample off the arc: r {r}");
        let mid = [(p[0] + last[0]) / 2.0, (p[1] + last[1]) / 2.0];
        let sagitta = 10.0 - ((mid[0] - 10.0).powi(2) + mid[1].powi(2)).sqrt();
        worst_sagitta = worst_sagitta.max(sagitta);
        last = p;
        if group(&e).state == GroupState::Standby {
            break;
        }
    }
    assert_eq!(group(&e).state, GroupState::Standby);
    // The cap binds (the chords come within 1 % of ε) and holds.
    assert!(
        worst_sagitta <= epsilon * (1.0 + 1e-6),
        "sagitta {worst_sagitta}"
    );
    assert!(worst_sagitta > 0.99 * epsilon, "sagitta {worst_sagitta}");
}

/// NMC `NMC_CrdSetFourthAxisToTurnVel` (issue 13): `fourth_coordinate_corner_velocity` limits
/// the fourth coordinate's speed where the path turns; a junction without it runs faster.
#[test]
fn the_fourth_coordinate_corner_velocity_slows_a_turning_junction() {
    fn slowest_at_the_corner(limit: Option<f64>) -> f64 {
        let mut e = machine(4, &[0, 1, 2, 3]);
        if let Some(v) = limit {
            common::group_parameter(&mut e, GroupParameter::FourthCoordinateCornerVelocity, v);
        }
        send(&mut e, line(&[40.0, 0.0, 0.0, 40.0]));
        send(
            &mut e,
            MoveLinearAbsolute {
                buffer_mode: GroupBufferMode::BlendingPrevious,
                // A slight turn in XY (0.01 rad), which the axes' own corner rule lets pass
                // at full speed.
                ..line(&[80.0, 0.4, 0.0, 80.0])
            },
        );
        let mut slowest = f64::INFINITY;
        let n = (20.0 / e.period()).round() as u64;
        for _ in 0..n {
            e.step();
            let g = group(&e);
            let p = positions(&e, 4);
            if (p[0] - 40.0).abs() < 1.0 {
                slowest = slowest.min(g.path_velocity);
            }
            if g.state == GroupState::Standby {
                break;
            }
        }
        slowest
    }
    // A moves at about v/√2 on both lines: at most 5 mm/s at the corner is a path speed of
    // 7.07 (plus at most one tick of path acceleration).
    let capped = slowest_at_the_corner(Some(5.0));
    assert!(capped <= 5.0 * 2f64.sqrt() + 1.0 + 1e-9, "{capped}");
    assert!(capped > 0.0, "a blended corner does not stop");
    let free = slowest_at_the_corner(None);
    assert!(free > capped + 5.0, "{free} vs {capped}");
    // Negative or non-finite: refused; 0: off.
    let mut e = machine(4, &[0, 1, 2, 3]);
    for bad in [-1.0, f64::NAN] {
        refused(
            &mut e,
            Command::from(GroupSetParameter {
                group: 1,
                name: GroupParameter::FourthCoordinateCornerVelocity,
                value: bad,
            }),
        );
    }
    common::group_parameter(&mut e, GroupParameter::FourthCoordinateCornerVelocity, 0.0);
}
