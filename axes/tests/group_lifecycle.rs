//! Axis groups without motion (issue 11 items 1, 3 and "Bad input"): create and delete rules,
//! IN_GROUP and the refusal of single-axis motion, the state machine (enable, disable, reset,
//! emergency stop, a member disabled), and every refusal a typed `EngineError` that leaves the
//! engine and the other groups running.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::command::{
    AxisInput, Command, Disable, DisableAll, EmergencyStopAll, Enable, EnableAll, ErrorKind,
    ForceInput, GroupCreate, GroupDelete, GroupDisable, GroupDwell, GroupEmergencyStop,
    GroupEnable, GroupParameter, GroupReset, GroupSetOrigin, GroupSetOutput, GroupSetOverride,
    GroupSetParameter, GroupWaitInput, GroupWaitPosition, MoveAbsolute, MoveCircularAbsolute,
    MoveLinearAbsolute, MoveLinearRelative, Reset, ResetAll, Stop, StopMode, TransitionMode,
};
use axes::config::GroupsConfig;
use axes::status::{GroupFault, GroupState, GroupStatus};
use axes::{AxisFlags, AxisState, Engine, EngineConfig, EngineError};
use common::{move_abs, ok, refused, run, status, stepper_mm};

fn machine(axes: usize) -> Engine {
    Engine::new(&EngineConfig {
        axes: (0..axes).map(|_| stepper_mm()).collect(),
        groups: GroupsConfig {
            max_groups: 3,
            ..GroupsConfig::default()
        },
        ..EngineConfig::default()
    })
    .unwrap()
}

fn create(group: u16, axes: &[u16]) -> Command {
    Command::from(GroupCreate {
        group,
        axes: axes.to_vec(),
        queue_capacity: None,
        lookahead: None,
        result_axis: None,
        orientation: Default::default(),
    })
}

fn line(group: u16, position: &[f64]) -> MoveLinearAbsolute {
    common::group_line(group, position)
}

fn group(e: &Engine, id: u16) -> GroupStatus {
    *e.snapshot()
        .groups
        .iter()
        .find(|g| g.group == id)
        .expect("the group exists")
}

fn enable_all(e: &mut Engine) {
    for axis in 0..e.axis_count() as u16 {
        ok(e, Command::from(Enable { axis }));
    }
}

#[test]
fn a_group_is_created_disabled_with_its_members_in_group_and_deleted_frees_them() {
    let mut e = machine(3);
    ok(&mut e, create(1, &[2, 0]));
    let g = group(&e, 1);
    assert_eq!(g.state, GroupState::Disabled);
    assert_eq!(g.axes(), &[2, 0]);
    assert_eq!((g.queue_used, g.queue_free), (0, 512));
    for axis in [0, 2] {
        assert!(e.snapshot().axes[axis].flags.contains(AxisFlags::IN_GROUP));
    }
    assert!(!e.snapshot().axes[1].flags.contains(AxisFlags::IN_GROUP));
    ok(&mut e, Command::from(GroupDelete { group: 1 }));
    assert!(e.snapshot().groups.is_empty());
    assert!(!e.snapshot().axes[0].flags.contains(AxisFlags::IN_GROUP));
    let err = refused(&mut e, Command::from(GroupDelete { group: 1 }));
    assert_eq!(err, EngineError::UnknownGroup { group: 1 });
}

#[test]
fn group_definitions_that_cannot_be_are_refused_with_the_reason() {
    let mut e = machine(10);
    ok(&mut e, create(1, &[0, 1]));
    let reason = |err: EngineError| match err {
        EngineError::InvalidGroup { reason, .. } => reason,
        other => panic!("{other:?}"),
    };
    assert_eq!(reason(refused(&mut e, create(1, &[2]))), "exists already");
    assert_eq!(
        reason(refused(&mut e, create(2, &[2, 1]))),
        "axis 1 is already in group 1"
    );
    assert_eq!(
        reason(refused(&mut e, create(2, &[]))),
        "a group has 1 to 9 axes, not 0"
    );
    assert_eq!(
        reason(refused(&mut e, create(2, &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]))),
        "a group has 1 to 9 axes, not 10"
    );
    assert_eq!(
        reason(refused(&mut e, create(2, &[3, 4, 3]))),
        "axis 3 is listed twice"
    );
    assert_eq!(
        refused(&mut e, create(2, &[3, 40])),
        EngineError::InvalidAxis {
            axis: 40,
            count: 10
        }
    );
    ok(&mut e, create(2, &[2]));
    ok(&mut e, create(3, &[3]));
    assert_eq!(
        reason(refused(&mut e, create(4, &[4]))),
        "at most 3 groups may exist at once ([groups] max_groups)"
    );
    // None of the refusals left an axis marked.
    assert!(!e.snapshot().axes[4].flags.contains(AxisFlags::IN_GROUP));
    let kinds: Vec<ErrorKind> = [
        refused(&mut e, create(1, &[5])),
        refused(&mut e, Command::from(GroupEnable { group: 9 })),
    ]
    .iter()
    .map(EngineError::kind)
    .collect();
    assert_eq!(kinds, [ErrorKind::InvalidGroup, ErrorKind::InvalidGroup]);
    ok(&mut e, Command::from(GroupDelete { group: 3 }));
    for (capacity, lookahead) in [(Some(0), None), (Some(1025), None), (None, Some(0))] {
        let err = refused(
            &mut e,
            Command::from(GroupCreate {
                group: 5,
                axes: vec![5],
                queue_capacity: capacity,
                lookahead,
                result_axis: None,
                orientation: Default::default(),
            }),
        );
        assert_eq!(err.kind(), ErrorKind::InvalidArgument, "{err}");
    }
}

#[test]
fn a_grouped_axis_refuses_single_axis_motion_and_takes_it_again_once_free() {
    let mut e = machine(2);
    enable_all(&mut e);
    ok(&mut e, create(1, &[0]));
    let err = refused(&mut e, move_abs(10.0));
    assert_eq!(err, EngineError::AxisInGroup { axis: 0, group: 1 });
    assert_eq!(err.kind(), ErrorKind::InvalidState);
    ok(&mut e, Command::from(GroupDelete { group: 1 }));
    ok(&mut e, move_abs(10.0));
}

#[test]
fn enable_needs_every_member_enabled_and_motion_needs_an_enabled_group() {
    let mut e = machine(2);
    ok(&mut e, create(1, &[0, 1]));
    let err = refused(&mut e, Command::from(line(1, &[1.0, 1.0])));
    assert_eq!(
        err,
        EngineError::GroupState {
            group: 1,
            state: GroupState::Disabled,
            action: "take motion",
        }
    );
    ok(&mut e, Command::from(Enable { axis: 0 }));
    let err = refused(&mut e, Command::from(GroupEnable { group: 1 }));
    assert!(
        matches!(err, EngineError::GroupMember { axis: 1, .. }),
        "{err:?}"
    );
    assert_eq!(err.kind(), ErrorKind::GroupState);
    assert_eq!(group(&e, 1).last_error, Some(ErrorKind::GroupState));
    ok(&mut e, Command::from(Enable { axis: 1 }));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    assert_eq!(group(&e, 1).state, GroupState::Standby);
    ok(&mut e, Command::from(GroupDisable { group: 1 }));
    assert_eq!(group(&e, 1).state, GroupState::Disabled);
}

#[test]
fn a_member_disabled_puts_the_group_in_error_stop_and_reset_waits_for_the_cause() {
    let mut e = machine(3);
    enable_all(&mut e);
    ok(&mut e, create(1, &[0, 1]));
    ok(&mut e, create(2, &[2]));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    ok(&mut e, Command::from(GroupEnable { group: 2 }));
    ok(&mut e, Command::from(Disable { axis: 1 }));
    run(&mut e, 0.01);
    let g = group(&e, 1);
    assert_eq!(g.state, GroupState::ErrorStop);
    assert_eq!(
        g.fault,
        Some(GroupFault::Member {
            axis: 1,
            error: ErrorKind::AxisDisabled
        })
    );
    // The other group is untouched.
    assert_eq!(group(&e, 2).state, GroupState::Standby);
    let err = refused(&mut e, Command::from(line(1, &[1.0, 1.0])));
    assert_eq!(err.kind(), ErrorKind::GroupState);
    let err = refused(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(err.kind(), ErrorKind::CauseStillPresent);
    assert!(
        matches!(err, EngineError::GroupCauseStillPresent { axis: 1, .. }),
        "{err:?}"
    );
    ok(&mut e, Command::from(Enable { axis: 1 }));
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    let g = group(&e, 1);
    assert_eq!((g.state, g.fault), (GroupState::Standby, None));
}

/// A group e-stop is an e-stop of each member (`stop` with mode `emergency`, NMC MtEstp,
/// digest 001 TV19: ESTOP latched, the axis held in ErrorStop until a reset) plus the group in
/// ErrorStop; the group's reset waits for its members' resets.
#[test]
fn a_group_emergency_stop_latches_every_members_estop_until_the_members_are_reset() {
    let moving = || {
        let mut e = machine(2);
        enable_all(&mut e);
        ok(&mut e, create(1, &[0, 1]));
        ok(&mut e, Command::from(GroupEnable { group: 1 }));
        ok(&mut e, Command::from(line(1, &[30.0, 40.0])));
        run(&mut e, 0.1);
        e
    };
    let mut e = moving();
    ok(
        &mut e,
        Command::from(GroupEmergencyStop {
            group: 1,
            keep_path: false,
        }),
    );
    let g = group(&e, 1);
    assert_eq!(
        (g.state, g.fault),
        (GroupState::ErrorStop, Some(GroupFault::EmergencyStop))
    );
    // The members ramp down with their fast_decel (10 000 mm/s²) and stay latched.
    run(&mut e, 0.05);
    for axis in 0..2 {
        let s = e.axis_status(axis).unwrap();
        assert_eq!(s.state, AxisState::ErrorStop, "axis {axis}");
        assert!(s.latched.contains(AxisFlags::ESTOP), "axis {axis}");
        assert_eq!(s.cmd_vel, 0.0, "axis {axis}");
    }
    let err = refused(&mut e, Command::from(GroupEnable { group: 1 }));
    assert_eq!(err.kind(), ErrorKind::GroupState);
    let err = refused(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(
        err,
        EngineError::GroupCauseStillPresent {
            group: 1,
            axis: 0,
            state: AxisState::ErrorStop
        }
    );
    let err = refused(&mut e, Command::from(Enable { axis: 1 }));
    assert_eq!(err.kind(), ErrorKind::AxisInError);
    for axis in 0..2 {
        ok(&mut e, Command::from(Reset { axis }));
    }
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(group(&e, 1).state, GroupState::Standby);
    ok(&mut e, Command::from(line(1, &[0.0, 0.0])));

    // `reset_all` clears the members' latches and then the group, in one command.
    let mut e = moving();
    ok(
        &mut e,
        Command::from(GroupEmergencyStop {
            group: 1,
            keep_path: false,
        }),
    );
    run(&mut e, 0.05);
    ok(&mut e, Command::from(ResetAll {}));
    assert_eq!(group(&e, 1).state, GroupState::Standby);
}

/// The members' states after a group e-stop are those after e-stopping each of them.
#[test]
fn a_group_emergency_stop_leaves_the_members_as_their_own_emergency_stops_do() {
    let mut grouped = machine(2);
    enable_all(&mut grouped);
    ok(&mut grouped, create(1, &[0, 1]));
    ok(&mut grouped, Command::from(GroupEnable { group: 1 }));
    let mut single = machine(2);
    enable_all(&mut single);
    ok(
        &mut grouped,
        Command::from(GroupEmergencyStop {
            group: 1,
            keep_path: false,
        }),
    );
    for axis in 0..2 {
        ok(
            &mut single,
            Command::from(Stop {
                axis,
                mode: StopMode::Emergency,
                deceleration: None,
            }),
        );
    }
    run(&mut grouped, 0.01);
    run(&mut single, 0.01);
    for axis in 0..2 {
        let (g, s) = (
            grouped.axis_status(axis).unwrap(),
            single.axis_status(axis).unwrap(),
        );
        assert_eq!((g.state, g.latched), (s.state, s.latched), "axis {axis}");
    }
    // A disabled group's members are e-stopped too; the group stays Disabled.
    let mut e = machine(2);
    enable_all(&mut e);
    ok(&mut e, create(1, &[0, 1]));
    ok(
        &mut e,
        Command::from(GroupEmergencyStop {
            group: 1,
            keep_path: false,
        }),
    );
    assert_eq!(group(&e, 1).state, GroupState::Disabled);
    assert!(e.axis_status(1).unwrap().latched.contains(AxisFlags::ESTOP));
}

/// Every bad input of the list that needs no motion to see: a typed error, nothing
/// queued, the group still Standby.
#[test]
fn bad_motion_input_is_refused_with_a_typed_error_and_nothing_is_queued() {
    let mut e = machine(3);
    enable_all(&mut e);
    ok(&mut e, create(1, &[0, 1]));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    let circle = |aux: Vec<f64>, end: Vec<f64>| {
        common::group_arc(1, &aux, &end, axes::command::ArcDirection::Ccw)
    };
    let cases: Vec<(Command, ErrorKind, &str)> = vec![
        (
            Command::from(line(1, &[1.0])),
            ErrorKind::InvalidArgument,
            "group 1: position has 1 coordinates; the group has 2 axes",
        ),
        (
            Command::from(line(1, &[1.0, f64::NAN])),
            ErrorKind::InvalidArgument,
            "position = NaN: must be a finite number",
        ),
        (
            Command::from(line(1, &[f64::INFINITY, 0.0])),
            ErrorKind::InvalidArgument,
            "position = inf: must be a finite number",
        ),
        (
            Command::from(MoveLinearAbsolute {
                velocity: Some(0.0),
                ..line(1, &[1.0, 1.0])
            }),
            ErrorKind::InvalidArgument,
            "velocity = 0: must be greater than zero",
        ),
        (
            Command::from(MoveLinearAbsolute {
                acceleration: Some(-5.0),
                ..line(1, &[1.0, 1.0])
            }),
            ErrorKind::InvalidArgument,
            "acceleration = -5: must be greater than zero",
        ),
        (
            Command::from(MoveLinearAbsolute {
                jerk: Some(-1.0),
                ..line(1, &[1.0, 1.0])
            }),
            ErrorKind::InvalidArgument,
            "jerk = -1: must be ≥ 0",
        ),
        (
            Command::from(MoveLinearAbsolute {
                transition: TransitionMode::CornerDistance(-1.0),
                ..line(1, &[1.0, 1.0])
            }),
            ErrorKind::InvalidArgument,
            "corner_distance = -1: must be ≥ 0",
        ),
        (
            Command::from(MoveLinearRelative {
                group: 7,
                distance: vec![1.0, 1.0],
                velocity: None,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode: Default::default(),
                transition: TransitionMode::None,
                user_segment: None,
                independent: Default::default(),
                coordinate_system: None,
            }),
            ErrorKind::InvalidGroup,
            "group 7 does not exist",
        ),
        (
            // Centre (5, 0): 5 from the start (0, 0), 6 from the end (11, 0).
            Command::from(circle(vec![5.0, 0.0], vec![11.0, 0.0])),
            ErrorKind::InvalidArgument,
            "group 1: the arc's centre is not equidistant from its start and end",
        ),
        (
            Command::from(MoveCircularAbsolute {
                mode: axes::command::CircleMode::Radius,
                radius: Some(4.0),
                ..circle(vec![], vec![10.0, 0.0])
            }),
            ErrorKind::InvalidArgument,
            "group 1: radius 4 is smaller than half the chord (5): no arc joins the points",
        ),
        (
            Command::from(MoveCircularAbsolute {
                mode: axes::command::CircleMode::Border,
                ..circle(vec![0.0, 0.0], vec![10.0, 0.0])
            }),
            ErrorKind::InvalidArgument,
            "group 1: start and via are the same point",
        ),
        (
            Command::from(MoveCircularAbsolute {
                plane: Some([0, 2]),
                ..circle(vec![5.0, 0.0], vec![10.0, 0.0])
            }),
            ErrorKind::InvalidArgument,
            "group 1: plane [0, 2] needs two different coordinates of the group's 2",
        ),
        (
            Command::from(MoveCircularAbsolute {
                normal: Some(vec![0.0, 0.0, 1.0]),
                ..circle(vec![5.0, 0.0], vec![10.0, 0.0])
            }),
            ErrorKind::InvalidArgument,
            "group 1: a normal needs 3 coordinates; the group has 2",
        ),
        (
            Command::from(GroupSetOverride {
                group: 1,
                factor: 0.0,
            }),
            ErrorKind::InvalidArgument,
            "factor = 0: must be in (0, 10) (1 = 100 %)",
        ),
        (
            Command::from(GroupSetOverride {
                group: 1,
                factor: 10.0,
            }),
            ErrorKind::InvalidArgument,
            "factor = 10: must be in (0, 10) (1 = 100 %)",
        ),
        (
            Command::from(GroupSetParameter {
                group: 1,
                name: GroupParameter::Acceleration,
                value: 0.0,
            }),
            ErrorKind::InvalidArgument,
            "acceleration = 0: must be greater than zero",
        ),
        (
            Command::from(GroupSetOrigin {
                group: 1,
                offset: vec![1.0, 2.0, 3.0],
            }),
            ErrorKind::InvalidArgument,
            "group 1: offset has 3 coordinates; the group has 2 axes",
        ),
        (
            Command::from(GroupSetOutput {
                group: 1,
                channel: 64,
                value: true,
            }),
            ErrorKind::InvalidChannel,
            "I/O channel 64 does not exist (digital outputs has 64 channels)",
        ),
        (
            Command::from(GroupDwell {
                group: 1,
                seconds: -1.0,
            }),
            ErrorKind::InvalidArgument,
            "seconds = -1: must be 0 to 1e9 seconds",
        ),
        (
            Command::from(GroupWaitInput {
                group: 1,
                channel: 0,
                level: true,
                timeout: Some(0.0),
            }),
            ErrorKind::InvalidArgument,
            "timeout = 0: must be greater than zero",
        ),
        (
            Command::from(GroupWaitPosition {
                group: 1,
                axis: 9,
                position: 0.0,
                tolerance: None,
                timeout: None,
                condition: Default::default(),
                source: Default::default(),
            }),
            ErrorKind::InvalidAxis,
            "axis 9 does not exist (the machine has 3 axes)",
        ),
    ];
    for (command, kind, message) in cases {
        let err = refused(&mut e, command.clone());
        assert_eq!((err.kind(), err.to_string().as_str()), (kind, message));
        let g = group(&e, 1);
        assert_eq!(
            (g.state, g.queue_used),
            (GroupState::Standby, 0),
            "{command:?}"
        );
    }
    // The engine runs on, and the axes are where they were.
    run(&mut e, 0.01);
    assert_eq!(status(&e).cmd_pos, 0.0);
    assert_eq!(group(&e, 1).state, GroupState::Standby);
}

/// Issue 11 "Bad input": "the engine and the other groups keep running". Group 2 runs a
/// path; every bad input of the list is thrown at group 1 (at rest), at group 2 itself
/// and at the group table while it runs. Group 2's members and status, and the free axis, are
/// bit for bit what they are in a run without the refusals, and group 2 ends on its target.
#[test]
fn refusals_leave_a_running_group_and_the_engine_exactly_as_without_them() {
    let bad_inputs = || -> Vec<Command> {
        let circle = |group: u16, aux: Vec<f64>, end: Vec<f64>| {
            common::group_arc(group, &aux, &end, axes::command::ArcDirection::Ccw)
        };
        vec![
            Command::from(line(7, &[1.0, 1.0])),
            create(3, &[2, 4]),
            create(3, &[]),
            create(3, &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]),
            Command::from(circle(1, vec![5.0, 0.0], vec![11.0, 0.0])),
            Command::from(MoveCircularAbsolute {
                mode: axes::command::CircleMode::Radius,
                radius: Some(4.0),
                ..circle(1, vec![], vec![10.0, 0.0])
            }),
            Command::from(MoveCircularAbsolute {
                mode: axes::command::CircleMode::Border,
                ..circle(1, vec![0.0, 0.0], vec![10.0, 0.0])
            }),
            Command::from(line(1, &[f64::NAN, 0.0])),
            Command::from(line(2, &[0.0, f64::INFINITY])),
            Command::from(MoveLinearAbsolute {
                velocity: Some(0.0),
                ..line(2, &[1.0, 1.0])
            }),
            Command::from(MoveLinearAbsolute {
                deceleration: Some(-1.0),
                ..line(1, &[1.0, 1.0])
            }),
            Command::from(GroupSetOverride {
                group: 2,
                factor: f64::NAN,
            }),
            // Motion on a disabled group (group 3 of the free axis 4, never enabled).
            Command::from(line(3, &[1.0])),
        ]
    };
    let run_with = |refusals: bool| {
        let mut e = machine(5);
        enable_all(&mut e);
        ok(&mut e, create(1, &[0, 1]));
        ok(&mut e, create(2, &[2, 3]));
        ok(&mut e, Command::from(GroupEnable { group: 1 }));
        ok(&mut e, Command::from(GroupEnable { group: 2 }));
        ok(&mut e, Command::from(line(2, &[30.0, -20.0])));
        ok(&mut e, Command::from(line(2, &[-10.0, 5.0])));
        let (mut trace, mut kinds) = (Vec::new(), Vec::new());
        for k in 0..3000 {
            if k == 100 && refusals {
                for (i, command) in bad_inputs().into_iter().enumerate() {
                    if i == 4 {
                        // After the bad definitions: a disabled group for the last case.
                        ok(&mut e, create(3, &[4]));
                    }
                    kinds.push(refused(&mut e, command).kind());
                }
                ok(&mut e, Command::from(GroupDelete { group: 3 }));
            }
            e.step();
            let s = e.snapshot();
            // A refusal aimed at group 2 is its `last_error` (status, issue 11 item 7), and
            // nothing else of it.
            let g2 = s.groups.iter().find(|g| g.group == 2).map(|g| GroupStatus {
                last_error: None,
                ..*g
            });
            trace.push(serde_json::to_string(&(&s.axes[2..], g2)).unwrap());
        }
        (e, trace, kinds)
    };
    let (clean, clean_trace, _) = run_with(false);
    let (e, trace, kinds) = run_with(true);
    use ErrorKind::{GroupState as Refused, InvalidArgument as Argument, InvalidGroup as Group};
    #[rustfmt::skip]
    let expected = [
        Group, Group, Group, Group,
        Argument, Argument, Argument, Argument, Argument, Argument, Argument, Argument,
        Refused,
    ];
    assert_eq!(kinds, expected);
    assert_eq!(trace.len(), clean_trace.len());
    for (k, (a, b)) in trace.iter().zip(&clean_trace).enumerate() {
        assert!(a == b, "tick {k}: the running group differs");
    }
    assert_eq!(group(&e, 2).last_error, Some(ErrorKind::InvalidArgument));
    assert_eq!(group(&clean, 2).last_error, None);
    assert_eq!(group(&e, 2).position(), &[-10.0, 5.0]);
    assert_eq!(group(&e, 2).state, GroupState::Standby);
    let g1 = group(&e, 1);
    assert_eq!((g1.state, g1.queue_used), (GroupState::Standby, 0));
    assert_eq!(group(&clean, 1).state, GroupState::Standby);
}

#[test]
fn a_refused_group_motion_takes_no_command_id() {
    let mut e = machine(3);
    enable_all(&mut e);
    ok(&mut e, create(1, &[0, 1]));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    refused(&mut e, Command::from(line(1, &[f64::NAN, 0.0])));
    // The next id the engine hands out is still 1.
    let r = ok(
        &mut e,
        Command::from(MoveAbsolute {
            axis: 2,
            position: 1.0,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: Default::default(),
        }),
    );
    assert_eq!(r, axes::Reply::Accepted { id: 1 });
}

#[test]
fn a_bad_groups_section_is_refused_with_its_key_and_reason() {
    for (groups, key, reason) in [
        (
            GroupsConfig {
                queue_capacity: 2000,
                ..GroupsConfig::default()
            },
            "groups.queue_capacity",
            "2000 is outside 1 … 1024",
        ),
        (
            GroupsConfig {
                max_groups: 0,
                ..GroupsConfig::default()
            },
            "groups.max_groups",
            "0 is outside 1 … 64",
        ),
        (
            GroupsConfig {
                queue_capacity: 32,
                lookahead: 64,
                ..GroupsConfig::default()
            },
            "groups.lookahead",
            "64 is outside 1 … queue_capacity (32)",
        ),
    ] {
        let err = Engine::new(&EngineConfig {
            groups,
            ..EngineConfig::default()
        })
        .unwrap_err();
        assert_eq!((err.key.as_str(), err.reason.as_str()), (key, reason));
    }
}

/// `enable_all` (HMC DriveEnable(1), digest 000 §4.1) enables every Disabled group whose members
/// are all enabled once the axes are (PLCopen MC_GroupEnable's condition); `disable_all` (HIMC
/// DisableAll, digest 004 §2.7) disables every group. A refused `enable_all` leaves every axis
/// and group as it was; a group in ErrorStop stays there until a reset.
#[test]
fn enable_all_enables_the_groups_whose_members_are_enabled_and_disable_all_disables_them() {
    let mut e = machine(4);
    ok(&mut e, create(1, &[0, 1]));
    ok(&mut e, create(2, &[2]));
    let alarm = |value| {
        Command::from(ForceInput {
            axis: 3,
            input: AxisInput::DriveAlarm,
            value: Some(value),
        })
    };
    ok(&mut e, alarm(true));
    run(&mut e, 0.01);
    let err = refused(&mut e, Command::from(EnableAll {}));
    assert_eq!(err.kind(), ErrorKind::AxisInError);
    for id in [1, 2] {
        assert_eq!(group(&e, id).state, GroupState::Disabled, "group {id}");
    }
    assert_eq!(e.axis_status(0).unwrap().state, AxisState::Disabled);
    ok(&mut e, alarm(false));
    run(&mut e, 0.01);
    ok(&mut e, Command::from(Reset { axis: 3 }));
    ok(&mut e, Command::from(EnableAll {}));
    for id in [1, 2] {
        assert_eq!(group(&e, id).state, GroupState::Standby, "group {id}");
    }
    ok(&mut e, Command::from(line(1, &[1.0, 1.0])));
    ok(&mut e, Command::from(DisableAll {}));
    for id in [1, 2] {
        assert_eq!(group(&e, id).state, GroupState::Disabled, "group {id}");
    }
    assert_eq!(group(&e, 1).queue_used, 0);
    // A group in ErrorStop is not enabled by enable_all: its fault needs a reset.
    ok(&mut e, Command::from(EnableAll {}));
    ok(&mut e, Command::from(Disable { axis: 2 }));
    run(&mut e, 0.01);
    assert_eq!(group(&e, 2).state, GroupState::ErrorStop);
    ok(&mut e, Command::from(EnableAll {}));
    assert_eq!(group(&e, 2).state, GroupState::ErrorStop);
    ok(&mut e, Command::from(GroupReset { group: 2 }));
    assert_eq!(group(&e, 2).state, GroupState::Standby);
}

/// `emergency_stop_all` disables the axes (HIMC EStop); `reset_all` then clears their latches
/// and, their members all disabled without a fault, takes the groups from ErrorStop to
/// Disabled (as an axis's reset leaves a disabled axis Disabled), so `enable_all` brings axes
/// and groups back. A group with an enabled and a disabled member still waits for its cause.
#[test]
fn after_emergency_stop_all_reset_all_and_enable_all_bring_the_groups_back() {
    let mut e = machine(3);
    enable_all(&mut e);
    ok(&mut e, create(1, &[0, 1]));
    ok(&mut e, Command::from(GroupEnable { group: 1 }));
    ok(&mut e, Command::from(line(1, &[20.0, 20.0])));
    run(&mut e, 0.1);
    ok(&mut e, Command::from(EmergencyStopAll {}));
    run(&mut e, 0.05);
    assert_eq!(group(&e, 1).state, GroupState::ErrorStop);
    ok(&mut e, Command::from(ResetAll {}));
    let g = group(&e, 1);
    assert_eq!((g.state, g.fault), (GroupState::Disabled, None));
    ok(&mut e, Command::from(EnableAll {}));
    assert_eq!(group(&e, 1).state, GroupState::Standby);
    ok(&mut e, Command::from(line(1, &[0.0, 0.0])));
    // One member enabled, one disabled: the reset is refused, naming the disabled one.
    ok(&mut e, Command::from(Disable { axis: 1 }));
    run(&mut e, 0.5);
    assert_eq!(group(&e, 1).state, GroupState::ErrorStop);
    let err = refused(&mut e, Command::from(GroupReset { group: 1 }));
    assert!(
        matches!(
            err,
            EngineError::GroupCauseStillPresent {
                axis: 1,
                state: AxisState::Disabled,
                ..
            }
        ),
        "{err:?}"
    );
    ok(&mut e, Command::from(Disable { axis: 0 }));
    ok(&mut e, Command::from(GroupReset { group: 1 }));
    assert_eq!(group(&e, 1).state, GroupState::Disabled);
}

/// A member on an engine-mastered CiA 402 drive is powered ticks after `enable_all` (its drive
/// walks to Operation enabled): its group is enabled once the walks have ended, if its members
/// are all enabled then. `disable_all` meanwhile cancels that.
#[test]
fn enable_all_enables_a_group_once_its_engine_mastered_drives_are_powered() {
    let build = || {
        let mut e = common::engine_with_mastered_drive(vec![stepper_mm(), stepper_mm()]);
        ok(&mut e, create(1, &[0, 1]));
        ok(&mut e, Command::from(EnableAll {}));
        assert_eq!(group(&e, 1).state, GroupState::Disabled);
        e
    };
    let mut e = build();
    let mut ticks = 0;
    while e.axis_status(1).unwrap().state != AxisState::Standstill && ticks < 100 {
        e.step();
        ticks += 1;
    }
    assert!(ticks < 100, "the drive powers its axis");
    e.step();
    assert_eq!(group(&e, 1).state, GroupState::Standby);
    // Disabled while the drive still walks: the group stays Disabled.
    let mut e = build();
    e.step();
    ok(&mut e, Command::from(DisableAll {}));
    run(&mut e, 0.2);
    assert_eq!(group(&e, 1).state, GroupState::Disabled);
    assert_eq!(e.axis_status(1).unwrap().state, AxisState::Disabled);
}
