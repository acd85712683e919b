//! The JSON of every group command (issue 11 item 8), pinned as `command_json.rs` pins the
//! others: each variant with every field set serializes to a literal and back, and the form
//! with only the required fields reads back with its defaults (buffer mode `buffered`, no
//! transition, centre mode, counter-clockwise …).
#![allow(clippy::unwrap_used)]

mod common;

use axes::command::{
    ArcDirection, CircleMode, Command, CoordinateSet, GroupAxisMove, GroupBufferMode,
    GroupContinue, GroupCreate, GroupDelete, GroupDisable, GroupDwell, GroupEmergencyStop,
    GroupEnable, GroupHalt, GroupParameter, GroupReset, GroupSetOrigin, GroupSetOutput,
    GroupSetOverride, GroupSetParameter, GroupStop, GroupWaitInput, GroupWaitPosition,
    MoveCircularAbsolute, MoveCircularAngle, MoveCircularRelative, MoveEllipse, MoveLinearAbsolute,
    MoveLinearRelative, MoveSpline, PositionCondition, PositionSource, TransitionMode,
};
use axes::command::{
    CoordinateSystem, GroupDeleteTransform, GroupJog, GroupJogAxis, GroupSetCoordinateSystem,
    GroupSetCoordinateTransform, GroupSetRotaryTransform, GroupSetXyzaTransform,
    MoveProtectionDisable, MoveProtectionEnable, ProtectionMode,
};
use axes::command::{GroupBufferedHalt, GroupPulseOutput, GroupSetAnalogOutput, GroupStopInput};
use axes::command::{GroupDeletePolarTransform, GroupSetPolarTransform};

fn full() -> Vec<(Command, &'static str)> {
    vec![
        (
            Command::from(GroupCreate {
                group: 1,
                axes: vec![0, 2, 1],
                queue_capacity: Some(1024),
                lookahead: Some(128),
                result_axis: Some(3),
                orientation: CoordinateSet::from_indices(&[1, 2]).unwrap(),
            }),
            r#"{"type":"group_create","group":1,"axes":[0,2,1],"queue_capacity":1024,"lookahead":128,"result_axis":3,"orientation":[1,2]}"#,
        ),
        (
            Command::from(GroupDelete { group: 2 }),
            r#"{"type":"group_delete","group":2}"#,
        ),
        (
            Command::from(GroupEnable { group: 3 }),
            r#"{"type":"group_enable","group":3}"#,
        ),
        (
            Command::from(GroupDisable { group: 4 }),
            r#"{"type":"group_disable","group":4}"#,
        ),
        (
            Command::from(GroupReset { group: 5 }),
            r#"{"type":"group_reset","group":5}"#,
        ),
        (
            Command::from(MoveLinearAbsolute {
                group: 1,
                position: vec![10.0, -2.5],
                velocity: Some(50.0),
                acceleration: Some(500.0),
                deceleration: Some(600.0),
                jerk: Some(0.0),
                buffer_mode: GroupBufferMode::BlendingLow,
                transition: TransitionMode::CornerDistance(1.5),
                user_segment: Some(7),
                independent: Default::default(),
                coordinate_system: Some("offset|wcs2|pcs".parse().unwrap()),
            }),
            r#"{"type":"move_linear_absolute","group":1,"position":[10.0,-2.5],"velocity":50.0,"acceleration":500.0,"deceleration":600.0,"jerk":0.0,"buffer_mode":"blending_low","transition":{"corner_distance":1.5},"user_segment":7,"coordinate_system":"offset|wcs2|pcs"}"#,
        ),
        (
            Command::from(MoveLinearRelative {
                group: 1,
                distance: vec![1.0, 2.0, 3.0],
                velocity: Some(5.0),
                acceleration: None,
                deceleration: None,
                jerk: Some(1e6),
                buffer_mode: GroupBufferMode::Aborting,
                transition: TransitionMode::CornerDeviation(0.01),
                user_segment: None,
                independent: CoordinateSet::from_indices(&[2]).unwrap(),
                coordinate_system: None,
            }),
            r#"{"type":"move_linear_relative","group":1,"distance":[1.0,2.0,3.0],"velocity":5.0,"acceleration":null,"deceleration":null,"jerk":1000000.0,"buffer_mode":"aborting","transition":{"corner_deviation":0.01},"user_segment":null,"independent":[2]}"#,
        ),
        (
            Command::from(MoveCircularAbsolute {
                group: 1,
                mode: CircleMode::Radius,
                aux_point: vec![],
                radius: Some(-10.0),
                end_point: vec![20.0, 0.0],
                direction: ArcDirection::Cw,
                plane: Some([0, 1]),
                normal: None,
                turns: 0,
                velocity: Some(20.0),
                acceleration: Some(200.0),
                deceleration: Some(200.0),
                jerk: None,
                buffer_mode: GroupBufferMode::BlendingPrevious,
                transition: TransitionMode::None,
                user_segment: Some(3),
                independent: Default::default(),
                coordinate_system: None,
            }),
            r#"{"type":"move_circular_absolute","group":1,"mode":"radius","aux_point":[],"radius":-10.0,"end_point":[20.0,0.0],"direction":"cw","plane":[0,1],"normal":null,"turns":0,"velocity":20.0,"acceleration":200.0,"deceleration":200.0,"jerk":null,"buffer_mode":"blending_previous","transition":"none","user_segment":3}"#,
        ),
        (
            Command::from(MoveCircularRelative {
                group: 2,
                mode: CircleMode::Border,
                aux_point: vec![5.0, 5.0, 0.0],
                radius: None,
                end_point: vec![10.0, 0.0, 1.0],
                direction: ArcDirection::Ccw,
                plane: None,
                normal: Some(vec![0.0, 0.0, 1.0]),
                turns: 4,
                velocity: None,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode: GroupBufferMode::BlendingHigh,
                transition: TransitionMode::None,
                user_segment: None,
                independent: Default::default(),
                coordinate_system: None,
            }),
            r#"{"type":"move_circular_relative","group":2,"mode":"border","aux_point":[5.0,5.0,0.0],"radius":null,"end_point":[10.0,0.0,1.0],"direction":"ccw","plane":null,"normal":[0.0,0.0,1.0],"turns":4,"velocity":null,"acceleration":null,"deceleration":null,"jerk":null,"buffer_mode":"blending_high","transition":"none","user_segment":null}"#,
        ),
        (
            Command::from(GroupStop {
                group: 1,
                deceleration: Some(1000.0),
            }),
            r#"{"type":"group_stop","group":1,"deceleration":1000.0}"#,
        ),
        (
            Command::from(GroupHalt {
                group: 1,
                deceleration: None,
            }),
            r#"{"type":"group_halt","group":1,"deceleration":null}"#,
        ),
        (
            Command::from(GroupContinue { group: 1 }),
            r#"{"type":"group_continue","group":1}"#,
        ),
        (
            Command::from(GroupEmergencyStop {
                group: 1,
                keep_path: false,
            }),
            r#"{"type":"group_emergency_stop","group":1}"#,
        ),
        (
            Command::from(GroupSetOverride {
                group: 1,
                factor: 0.5,
            }),
            r#"{"type":"group_set_override","group":1,"factor":0.5}"#,
        ),
        (
            Command::from(GroupSetOrigin {
                group: 1,
                offset: vec![100.0, 200.0],
            }),
            r#"{"type":"group_set_origin","group":1,"offset":[100.0,200.0]}"#,
        ),
        (
            Command::from(GroupSetParameter {
                group: 1,
                name: GroupParameter::Deceleration,
                value: 2500.0,
            }),
            r#"{"type":"group_set_parameter","group":1,"name":"deceleration","value":2500.0}"#,
        ),
        (
            Command::from(GroupSetOutput {
                group: 1,
                channel: 3,
                value: true,
            }),
            r#"{"type":"group_set_output","group":1,"channel":3,"value":true}"#,
        ),
        (
            Command::from(GroupDwell {
                group: 1,
                seconds: 0.25,
            }),
            r#"{"type":"group_dwell","group":1,"seconds":0.25}"#,
        ),
        (
            Command::from(GroupWaitInput {
                group: 1,
                channel: 4,
                level: false,
                timeout: Some(2.0),
            }),
            r#"{"type":"group_wait_input","group":1,"channel":4,"level":false,"timeout":2.0}"#,
        ),
        (
            Command::from(GroupWaitPosition {
                group: 1,
                axis: 3,
                position: 50.0,
                tolerance: None,
                timeout: Some(2.0),
                condition: PositionCondition::AtLeast,
                source: Some(PositionSource::Commanded),
            }),
            r#"{"type":"group_wait_position","group":1,"axis":3,"position":50.0,"tolerance":null,"timeout":2.0,"condition":"at_least","source":"commanded"}"#,
        ),
        (
            Command::from(GroupAxisMove {
                group: 1,
                axis: 3,
                position: -5.0,
                velocity: Some(10.0),
                acceleration: None,
                deceleration: None,
                jerk: None,
            }),
            r#"{"type":"group_axis_move","group":1,"axis":3,"position":-5.0,"velocity":10.0,"acceleration":null,"deceleration":null,"jerk":null}"#,
        ),
        (
            Command::from(GroupPulseOutput {
                group: 1,
                channel: 2,
                level: Some(true),
                level_time: 0.005,
                other_time: 0.003,
                toggles: 6,
                after_length: Some(30.0),
                before_end: None,
            }),
            r#"{"type":"group_pulse_output","group":1,"channel":2,"level":true,"level_time":0.005,"other_time":0.003,"toggles":6,"after_length":30.0}"#,
        ),
        (
            Command::from(GroupSetAnalogOutput {
                group: 1,
                channel: 1,
                value: 2.5,
            }),
            r#"{"type":"group_set_analog_output","group":1,"channel":1,"value":2.5}"#,
        ),
        (
            Command::from(GroupStopInput {
                group: 1,
                slot: 3,
                channel: Some(7),
                level: true,
            }),
            r#"{"type":"group_stop_input","group":1,"slot":3,"channel":7,"level":true}"#,
        ),
        (
            Command::from(GroupBufferedHalt {
                group: 1,
                target: 2,
                deceleration: Some(100.0),
            }),
            r#"{"type":"group_buffered_halt","group":1,"target":2,"deceleration":100.0}"#,
        ),
        (
            Command::from(MoveSpline {
                group: 1,
                points: vec![vec![1.0, 2.0], vec![3.0, -1.5]],
                relative: true,
                velocity: Some(20.0),
                acceleration: None,
                deceleration: Some(100.0),
                jerk: None,
                buffer_mode: GroupBufferMode::BlendingNext,
                transition: TransitionMode::None,
                user_segment: Some(4),
                coordinate_system: None,
                independent: Default::default(),
            }),
            r#"{"type":"move_spline","group":1,"points":[[1.0,2.0],[3.0,-1.5]],"relative":true,"velocity":20.0,"acceleration":null,"deceleration":100.0,"jerk":null,"buffer_mode":"blending_next","transition":"none","user_segment":4}"#,
        ),
        (
            Command::from(MoveEllipse {
                group: 2,
                center: vec![-5.0, 0.0],
                ratio: 0.5,
                direction: ArcDirection::Cw,
                plane: Some([0, 1]),
                relative: true,
                velocity: None,
                acceleration: Some(50.0),
                deceleration: None,
                jerk: Some(0.0),
                buffer_mode: GroupBufferMode::Buffered,
                transition: TransitionMode::None,
                user_segment: None,
                coordinate_system: None,
            }),
            r#"{"type":"move_ellipse","group":2,"center":[-5.0,0.0],"ratio":0.5,"direction":"cw","plane":[0,1],"relative":true,"velocity":null,"acceleration":50.0,"deceleration":null,"jerk":0.0,"buffer_mode":"buffered","transition":"none","user_segment":null}"#,
        ),
        (
            Command::from(MoveCircularAngle {
                group: 1,
                center: vec![10.0, 10.0],
                angle: -45.0,
                plane: None,
                relative: false,
                velocity: Some(100.0),
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode: GroupBufferMode::Aborting,
                transition: TransitionMode::None,
                user_segment: Some(3),
                coordinate_system: None,
            }),
            r#"{"type":"move_circular_angle","group":1,"center":[10.0,10.0],"angle":-45.0,"plane":null,"relative":false,"velocity":100.0,"acceleration":null,"deceleration":null,"jerk":null,"buffer_mode":"aborting","transition":"none","user_segment":3}"#,
        ),
        (
            Command::from(GroupSetCoordinateTransform {
                group: 1,
                frame: "wcs15".parse().unwrap(),
                pose: [400.0, 200.0, 0.0, 0.0, 0.0, 45.0],
            }),
            r#"{"type":"group_set_coordinate_transform","group":1,"frame":"wcs15","pose":[400.0,200.0,0.0,0.0,0.0,45.0]}"#,
        ),
        (
            Command::from(GroupSetCoordinateSystem {
                group: 1,
                coordinate_system: CoordinateSystem::Xyza,
            }),
            r#"{"type":"group_set_coordinate_system","group":1,"coordinate_system":"xyza"}"#,
        ),
        (
            Command::from(GroupSetRotaryTransform {
                group: 1,
                rotary_axis: 3,
                rad_per_unit: 0.5,
                center: [0.0, 15.0],
                plane: Some([1, 2]),
            }),
            r#"{"type":"group_set_rotary_transform","group":1,"rotary_axis":3,"rad_per_unit":0.5,"center":[0.0,15.0],"plane":[1,2]}"#,
        ),
        (
            Command::from(GroupSetXyzaTransform {
                group: 1,
                rad_per_unit: 0.25,
                tool: [-1.5, 2.0],
            }),
            r#"{"type":"group_set_xyza_transform","group":1,"rad_per_unit":0.25,"tool":[-1.5,2.0]}"#,
        ),
        (
            Command::from(GroupDeleteTransform { group: 1 }),
            r#"{"type":"group_delete_transform","group":1}"#,
        ),
        (
            Command::from(MoveProtectionEnable {
                protection: 0,
                groups: [1, 2],
                axes: [0, 1],
                move_direction: [1, -1],
                origin_distance: 100.0,
                protection_distance: 20.0,
                mode: ProtectionMode::Retreat,
                stop_group: Some(2),
                safe_wait_position: Some(80.0),
                retreat_velocity: Some(50.0),
                retreat_acceleration: Some(500.0),
            }),
            r#"{"type":"move_protection_enable","protection":0,"groups":[1,2],"axes":[0,1],"move_direction":[1,-1],"origin_distance":100.0,"protection_distance":20.0,"mode":"retreat","stop_group":2,"safe_wait_position":80.0,"retreat_velocity":50.0,"retreat_acceleration":500.0}"#,
        ),
        (
            Command::from(MoveProtectionDisable { protection: 0 }),
            r#"{"type":"move_protection_disable","protection":0}"#,
        ),
        (
            Command::from(GroupJog {
                group: 1,
                coordinate: 2,
                velocity: -12.5,
                coordinate_system: Some(CoordinateSystem::MCS),
            }),
            r#"{"type":"group_jog","group":1,"coordinate":2,"velocity":-12.5,"coordinate_system":"mcs"}"#,
        ),
        (
            Command::from(GroupJogAxis {
                group: 1,
                member: 4,
                velocity: 30.0,
            }),
            r#"{"type":"group_jog_axis","group":1,"member":4,"velocity":30.0}"#,
        ),
        (
            Command::from(GroupSetPolarTransform {
                group: 1,
                rotary: 3,
                feed: 1,
                rotary_units_per_radian: 1591.5,
                plane: Some([1, 2]),
            }),
            r#"{"type":"group_set_polar_transform","group":1,"rotary":3,"feed":1,"rotary_units_per_radian":1591.5,"plane":[1,2]}"#,
        ),
        (
            Command::from(GroupDeletePolarTransform { group: 1 }),
            r#"{"type":"group_delete_polar_transform","group":1}"#,
        ),
    ]
}

#[test]
fn every_group_command_serializes_to_its_pinned_json_and_back() {
    let cases = full();
    assert_eq!(cases.len(), 39, "one case per group command");
    common::assert_pinned(cases);
}

#[test]
fn a_motion_with_only_its_required_fields_is_buffered_without_transition() {
    let c: Command =
        serde_json::from_str(r#"{"type":"move_linear_absolute","group":1,"position":[1,2]}"#)
            .unwrap();
    assert_eq!(
        c,
        Command::from(MoveLinearAbsolute {
            group: 1,
            position: vec![1.0, 2.0],
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: GroupBufferMode::Buffered,
            transition: TransitionMode::None,
            user_segment: None,
            independent: Default::default(),
            coordinate_system: None,
        })
    );
    let c: Command = serde_json::from_str(
        r#"{"type":"move_circular_absolute","group":1,"aux_point":[0,0],"end_point":[10,0]}"#,
    )
    .unwrap();
    let Command::Group(axes::command::GroupCommand::MoveCircularAbsolute(m)) = c else {
        panic!("{c:?}");
    };
    assert_eq!(
        (m.mode, m.direction, m.plane, m.normal, m.turns),
        (CircleMode::Center, ArcDirection::Ccw, None, None, 0)
    );
    let c: Command =
        serde_json::from_str(r#"{"type":"group_create","group":1,"axes":[0]}"#).unwrap();
    assert_eq!(
        c,
        Command::from(GroupCreate {
            group: 1,
            axes: vec![0],
            queue_capacity: None,
            lookahead: None,
            result_axis: None,
            orientation: Default::default(),
        })
    );
}

#[test]
fn group_serde_errors_name_the_field() {
    for (json, message) in [
        (
            r#"{"type":"move_linear_absolute","group":1,"positon":[1]}"#,
            "unknown field `positon`, expected one of `group`, `position`, `velocity`, `acceleration`, `deceleration`, `jerk`, `buffer_mode`, `transition`, `user_segment`, `independent`, `coordinate_system`",
        ),
        (
            r#"{"type":"move_linear_absolute","group":1,"position":[1],"buffer_mode":"blend"}"#,
            "unknown variant `blend`, expected one of `aborting`, `buffered`, `blending_low`, `blending_previous`, `blending_next`, `blending_high`",
        ),
        (
            r#"{"type":"move_linear_absolute","group":1,"position":[1],"transition":{"corner_radius":1}}"#,
            "unknown variant `corner_radius`, expected one of `none`, `corner_distance`, `corner_deviation`",
        ),
        (
            r#"{"type":"move_circular_absolute","group":1,"end_point":[1,0],"direction":"left"}"#,
            "unknown variant `left`, expected `cw` or `ccw`",
        ),
        (
            r#"{"type":"group_create","axes":[0]}"#,
            "missing field `group`",
        ),
    ] {
        let e = serde_json::from_str::<Command>(json).unwrap_err();
        assert_eq!(e.to_string(), message, "{json}");
    }
}

/// The vendor rules added as group parameters (docs/decisions.md, "Group safety"): HMC's stop
/// along the path after a member's trouble, CPU 226H's smallest acceleration, HIMC's angular
/// profile.
#[test]
fn the_safety_acceleration_and_angular_parameters_have_their_pinned_names() {
    for (name, json) in [
        (
            GroupParameter::FaultDeceleration,
            r#"{"type":"group_set_parameter","group":1,"name":"fault_deceleration","value":1.0}"#,
        ),
        (
            GroupParameter::SmallestAxisAcceleration,
            r#"{"type":"group_set_parameter","group":1,"name":"smallest_axis_acceleration","value":1.0}"#,
        ),
        (
            GroupParameter::AngularVelocity,
            r#"{"type":"group_set_parameter","group":1,"name":"angular_velocity","value":1.0}"#,
        ),
        (
            GroupParameter::AngularAcceleration,
            r#"{"type":"group_set_parameter","group":1,"name":"angular_acceleration","value":1.0}"#,
        ),
        (
            GroupParameter::AngularDeceleration,
            r#"{"type":"group_set_parameter","group":1,"name":"angular_deceleration","value":1.0}"#,
        ),
        (
            GroupParameter::AngularJerk,
            r#"{"type":"group_set_parameter","group":1,"name":"angular_jerk","value":1.0}"#,
        ),
        (
            GroupParameter::MergeSpeedTolerance,
            r#"{"type":"group_set_parameter","group":1,"name":"merge_speed_tolerance","value":1.0}"#,
        ),
        (
            GroupParameter::Mergeable,
            r#"{"type":"group_set_parameter","group":1,"name":"mergeable","value":1.0}"#,
        ),
    ] {
        let c = Command::from(GroupSetParameter {
            group: 1,
            name,
            value: 1.0,
        });
        assert_eq!(serde_json::to_string(&c).unwrap(), json);
        assert_eq!(serde_json::from_str::<Command>(json).unwrap(), c);
    }
}

#[test]
fn frames_and_protections_read_back_with_their_defaults() {
    let c: Command = serde_json::from_str(
        r#"{"type":"move_protection_enable","protection":0,"groups":[1,2],"axes":[0,0],"move_direction":[1,-1],"origin_distance":100,"protection_distance":20}"#,
    )
    .unwrap();
    let Command::Group(axes::command::GroupCommand::ProtectionEnable(p)) = c else {
        panic!("{c:?}");
    };
    assert_eq!(p.mode, ProtectionMode::BothStop);
    assert_eq!((p.stop_group, p.safe_wait_position), (None, None));
    let c: Command = serde_json::from_str(
        r#"{"type":"move_linear_relative","group":1,"distance":[1],"coordinate_system":"mcs"}"#,
    )
    .unwrap();
    let Command::Group(axes::command::GroupCommand::MoveLinearRelative(m)) = c else {
        panic!("{c:?}");
    };
    assert_eq!(m.coordinate_system, Some(CoordinateSystem::MCS));
    for (text, system) in [
        (
            "pcs",
            CoordinateSystem::Chain {
                offset: false,
                wcs: None,
                pcs: true,
            },
        ),
        (
            "wcs1|pcs",
            CoordinateSystem::Chain {
                offset: false,
                wcs: Some(1),
                pcs: true,
            },
        ),
        ("rotary", CoordinateSystem::Rotary),
    ] {
        assert_eq!(text.parse::<CoordinateSystem>().unwrap(), system);
        assert_eq!(system.to_string(), text);
    }
    let err = serde_json::from_str::<Command>(
        r#"{"type":"group_set_coordinate_system","group":1,"coordinate_system":"world"}"#,
    )
    .unwrap_err();
    assert!(
        err.to_string().contains("coordinate system `world`"),
        "{err}"
    );
}
