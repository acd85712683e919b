//! The JSON of every command, pinned: scenarios and the control API take commands in this form,
//! so it must not change when the Rust shape of `Command` does (issue 10). Each variant is
//! serialized with representative values and compared with a literal; the literal, and a form
//! with only the required fields, deserialize back. The error messages serde gives for a wrong
//! `type`, a missing or an unknown field are pinned too: the control API and the scenario loader
//! show them to users, and the control API reads the field name out of them.

mod common;

use axes::command::{
    AxisInput, BufferMode, Cancel, CancelScope, Command, Disable, DisableAll, EmergencyStopAll,
    Enable, EnableAll, ForceAnalogInput, ForceDigitalInput, ForceInput, GetCommandState,
    GetParameter, Halt, Home, InjectFollowingError, ModifyTarget, MoveAbsolute, MoveRelative,
    MoveTogether, MoveVelocity, PositionFrame, PulseDigitalOutput, ReadObject, Reset, ResetAll,
    Resume, SetParameter, SetPosition, Setpoint, Stop, StopAll, StopAxes, StopMode, StreamSetpoint,
    TogetherMove, WriteAnalogOutput, WriteDigitalOutput, WriteObject,
};
use axes::command::{
    CaptureArm, CaptureClear, CaptureEdge, CaptureSource, CaptureWindow, CompareFire,
    CompareOutputMode, CompareStart, CompareStop, PositionSource, PtKind, PtPoint, PtPush, PvtMove,
    PvtPoint, PvtPush, StreamClear, StreamConfig, StreamMode, StreamStart,
};
use axes::homing::{AfterHome, HomingQuirks, Latch};
use axes::od::Value;
use axes::ParamId;
use common::assert_pinned;

/// Every variant with all fields set to non-default values, and its JSON.
fn full() -> Vec<(Command, &'static str)> {
    let quirks = HomingQuirks {
        after_home: AfterHome::ReturnToHome,
        switch_latch: Latch::Polled,
        index_latch: Latch::Exact,
        switch_scan_ticks: 4,
        max_search_distance: 500.0,
        initial_backoff: 2.5,
        rescan: Some(1.5),
        trial: true,
    };
    vec![
        (
            Command::from(Enable { axis: 1 }),
            r#"{"type":"enable","axis":1}"#,
        ),
        (
            Command::from(Disable { axis: 2 }),
            r#"{"type":"disable","axis":2}"#,
        ),
        (
            Command::from(Reset { axis: 3 }),
            r#"{"type":"reset","axis":3}"#,
        ),
        (
            Command::from(MoveAbsolute {
                axis: 0,
                position: 100.5,
                velocity: Some(10.0),
                acceleration: Some(20.0),
                deceleration: Some(30.0),
                jerk: Some(0.0),
                buffer_mode: BufferMode::Buffered,
            }),
            r#"{"type":"move_absolute","axis":0,"position":100.5,"velocity":10.0,"acceleration":20.0,"deceleration":30.0,"jerk":0.0,"buffer_mode":"buffered"}"#,
        ),
        (
            Command::from(MoveRelative {
                axis: 1,
                distance: -7.25,
                velocity: Some(1.0),
                acceleration: Some(2.0),
                deceleration: Some(3.0),
                jerk: Some(400.0),
                buffer_mode: BufferMode::Buffered,
            }),
            r#"{"type":"move_relative","axis":1,"distance":-7.25,"velocity":1.0,"acceleration":2.0,"deceleration":3.0,"jerk":400.0,"buffer_mode":"buffered"}"#,
        ),
        (
            Command::from(MoveVelocity {
                axis: 2,
                velocity: -3.5,
                acceleration: Some(2.0),
                deceleration: Some(3.0),
                jerk: Some(4.0),
                buffer_mode: BufferMode::Buffered,
            }),
            r#"{"type":"move_velocity","axis":2,"velocity":-3.5,"acceleration":2.0,"deceleration":3.0,"jerk":4.0,"buffer_mode":"buffered"}"#,
        ),
        (
            Command::from(Stop {
                axis: 0,
                mode: StopMode::Emergency,
                deceleration: Some(99.0),
            }),
            r#"{"type":"stop","axis":0,"mode":"emergency","deceleration":99.0}"#,
        ),
        (
            Command::from(Halt {
                axis: 0,
                deceleration: Some(5.0),
            }),
            r#"{"type":"halt","axis":0,"deceleration":5.0}"#,
        ),
        (
            Command::from(Resume { axis: 0 }),
            r#"{"type":"resume","axis":0}"#,
        ),
        (
            Command::from(Home {
                axis: 1,
                method: Some(17),
                switch_velocity: Some(10.0),
                zero_velocity: Some(1.0),
                acceleration: Some(100.0),
                offset: Some(-0.5),
                timeout: Some(30.0),
                quirks,
                buffer_mode: BufferMode::Buffered,
            }),
            r#"{"type":"home","axis":1,"method":17,"switch_velocity":10.0,"zero_velocity":1.0,"acceleration":100.0,"offset":-0.5,"timeout":30.0,"quirks":{"after_home":"return_to_home","switch_latch":"polled","index_latch":"exact","switch_scan_ticks":4,"max_search_distance":500.0,"initial_backoff":2.5,"rescan":1.5,"trial":true},"buffer_mode":"buffered"}"#,
        ),
        (
            Command::from(SetPosition {
                axis: 0,
                position: 12.0,
                frame: PositionFrame::Actual,
            }),
            r#"{"type":"set_position","axis":0,"position":12.0,"frame":"actual"}"#,
        ),
        (
            Command::from(SetParameter {
                axis: 0,
                name: ParamId::Speed,
                value: 42.0,
                lenient: true,
            }),
            r#"{"type":"set_parameter","axis":0,"name":"speed","value":42.0,"lenient":true}"#,
        ),
        (
            Command::from(GetParameter {
                axis: 1,
                name: ParamId::Accel,
            }),
            r#"{"type":"get_parameter","axis":1,"name":"accel"}"#,
        ),
        (
            Command::from(ModifyTarget {
                axis: 0,
                position: 3.0,
                relative: true,
            }),
            r#"{"type":"modify_target","axis":0,"position":3.0,"relative":true}"#,
        ),
        (
            Command::from(Cancel {
                axis: 0,
                scope: CancelScope::All,
            }),
            r#"{"type":"cancel","axis":0,"scope":"all"}"#,
        ),
        (
            Command::from(GetCommandState { id: 7 }),
            r#"{"type":"command_state","id":7}"#,
        ),
        (
            Command::from(ForceInput {
                axis: 0,
                input: AxisInput::LimitPos,
                value: Some(true),
            }),
            r#"{"type":"force_input","axis":0,"input":"limit_pos","value":true}"#,
        ),
        (
            Command::from(ForceDigitalInput {
                channel: 3,
                value: Some(false),
            }),
            r#"{"type":"force_digital_input","channel":3,"value":false}"#,
        ),
        (
            Command::from(ForceAnalogInput {
                channel: 1,
                value: Some(2.5),
            }),
            r#"{"type":"force_analog_input","channel":1,"value":2.5}"#,
        ),
        (
            Command::from(WriteDigitalOutput {
                channel: 4,
                value: true,
            }),
            r#"{"type":"write_digital_output","channel":4,"value":true}"#,
        ),
        (
            Command::from(PulseDigitalOutput {
                channel: 3,
                level: true,
                level_time: 0.5,
                other_time: 0.25,
                toggles: 4,
            }),
            r#"{"type":"pulse_digital_output","channel":3,"level":true,"level_time":0.5,"other_time":0.25,"toggles":4}"#,
        ),
        (
            Command::from(WriteAnalogOutput {
                channel: 0,
                value: -1.25,
            }),
            r#"{"type":"write_analog_output","channel":0,"value":-1.25}"#,
        ),
        (
            Command::from(InjectFollowingError {
                axis: 0,
                amount: Some(0.75),
            }),
            r#"{"type":"inject_following_error","axis":0,"amount":0.75}"#,
        ),
        (
            Command::from(StreamSetpoint {
                axis: 0,
                setpoint: Some(Setpoint::Velocity { velocity: 5.0 }),
            }),
            r#"{"type":"setpoint","axis":0,"setpoint":{"mode":"velocity","velocity":5.0}}"#,
        ),
        (
            Command::from(ReadObject {
                slave: 1,
                index: 0x6041,
                subindex: 0,
            }),
            r#"{"type":"read_object","slave":1,"index":24641,"subindex":0}"#,
        ),
        (
            Command::from(WriteObject {
                slave: 0,
                index: 0x6060,
                subindex: 0,
                value: Value::I8(8),
            }),
            r#"{"type":"write_object","slave":0,"index":24672,"subindex":0,"value":{"i8":8}}"#,
        ),
        (
            Command::from(MoveTogether {
                moves: vec![
                    TogetherMove::MoveAbsolute(MoveAbsolute {
                        axis: 0,
                        position: 1000.0,
                        velocity: Some(50.0),
                        acceleration: None,
                        deceleration: None,
                        jerk: None,
                        buffer_mode: BufferMode::Aborting,
                    }),
                    TogetherMove::MoveRelative(MoveRelative {
                        axis: 1,
                        distance: -2.0,
                        velocity: None,
                        acceleration: Some(100.0),
                        deceleration: None,
                        jerk: Some(0.0),
                        buffer_mode: BufferMode::Aborting,
                    }),
                    TogetherMove::MoveVelocity(MoveVelocity {
                        axis: 2,
                        velocity: 3.0,
                        acceleration: None,
                        deceleration: Some(9.0),
                        jerk: None,
                        buffer_mode: BufferMode::Aborting,
                    }),
                ],
            }),
            concat!(
                r#"{"type":"move_together","moves":["#,
                r#"{"type":"move_absolute","axis":0,"position":1000.0,"velocity":50.0,"acceleration":null,"deceleration":null,"jerk":null,"buffer_mode":"aborting"},"#,
                r#"{"type":"move_relative","axis":1,"distance":-2.0,"velocity":null,"acceleration":100.0,"deceleration":null,"jerk":0.0,"buffer_mode":"aborting"},"#,
                r#"{"type":"move_velocity","axis":2,"velocity":3.0,"acceleration":null,"deceleration":9.0,"jerk":null,"buffer_mode":"aborting"}]}"#
            ),
        ),
        (
            Command::from(StopAxes {
                axes: vec![0, 2],
                mode: StopMode::Emergency,
                deceleration: Some(500.0),
            }),
            r#"{"type":"stop_axes","axes":[0,2],"mode":"emergency","deceleration":500.0}"#,
        ),
        (
            Command::from(StopAll {
                mode: StopMode::Smooth,
                deceleration: Some(20.0),
            }),
            r#"{"type":"stop_all","mode":"smooth","deceleration":20.0}"#,
        ),
        (Command::from(EnableAll {}), r#"{"type":"enable_all"}"#),
        (Command::from(DisableAll {}), r#"{"type":"disable_all"}"#),
        (
            Command::from(EmergencyStopAll {}),
            r#"{"type":"emergency_stop_all"}"#,
        ),
        (Command::from(ResetAll {}), r#"{"type":"reset_all"}"#),
        (
            Command::from(CaptureArm {
                axis: 1,
                channel: 2,
                source: CaptureSource::Di,
                input: Some(3),
                source_axis: Some(0),
                edge: CaptureEdge::Both,
                repeat: 2,
                continuous: true,
                window: Some(CaptureWindow {
                    low: -100.0,
                    high: 1000.0,
                    outside: true,
                }),
            }),
            r#"{"type":"capture_arm","axis":1,"channel":2,"source":"di","input":3,"source_axis":0,"edge":"both","repeat":2,"continuous":true,"window":{"low":-100.0,"high":1000.0,"outside":true}}"#,
        ),
        (
            Command::from(CaptureClear {
                axis: 1,
                channel: 2,
            }),
            r#"{"type":"capture_clear","axis":1,"channel":2}"#,
        ),
        (
            Command::from(CompareStart {
                channel: 1,
                axis: 0,
                axis_y: Some(1),
                source: PositionSource::Actual,
                positions: vec![],
                start: None,
                interval: None,
                end: None,
                points: vec![[100.0, 100.0], [200.0, 200.0]],
                error_zone: 10.0,
                disturbance: 0.0,
                output: 5,
                mode: CompareOutputMode::Toggle,
                level: false,
                pulse_width: 0.002,
                min_interval: 0.001,
            }),
            r#"{"type":"compare_start","channel":1,"axis":0,"axis_y":1,"source":"actual","points":[[100.0,100.0],[200.0,200.0]],"error_zone":10.0,"output":5,"mode":"toggle","level":false,"pulse_width":0.002,"min_interval":0.001}"#,
        ),
        (
            Command::from(CompareStop { channel: 1 }),
            r#"{"type":"compare_stop","channel":1}"#,
        ),
        (
            // NMC Comp2DimensOnoff 2, the manual output (S-CMP-MANUAL).
            Command::from(CompareFire { channel: 1 }),
            r#"{"type":"compare_fire","channel":1}"#,
        ),
        (
            Command::from(StreamConfig {
                axis: 0,
                mode: StreamMode::Static,
                loop_count: 5,
                stop_deceleration: Some(1000.0),
            }),
            r#"{"type":"stream_config","axis":0,"mode":"static","loop_count":5,"stop_deceleration":1000.0}"#,
        ),
        (
            Command::from(PtPush {
                axis: 0,
                points: vec![PtPoint {
                    position: 10000.0,
                    time_ms: 100.0,
                    kind: PtKind::Stop,
                }],
            }),
            r#"{"type":"pt_push","axis":0,"points":[{"position":10000.0,"time_ms":100.0,"kind":"stop"}]}"#,
        ),
        (
            Command::from(PvtPush {
                axis: 1,
                points: vec![PvtPoint {
                    position: 1.5,
                    velocity: -2.0,
                    time_ms: 20.0,
                }],
            }),
            r#"{"type":"pvt_push","axis":1,"points":[{"position":1.5,"velocity":-2.0,"time_ms":20.0}]}"#,
        ),
        (
            Command::from(StreamClear { axis: 2 }),
            r#"{"type":"stream_clear","axis":2}"#,
        ),
        (
            Command::from(StreamStart { axes: vec![0, 1] }),
            r#"{"type":"stream_start","axes":[0,1]}"#,
        ),
        (
            Command::from(PvtMove {
                axis: 0,
                points: vec![PvtPoint {
                    position: 153.333,
                    velocity: 1000.0,
                    time_ms: 2000.0,
                }],
            }),
            r#"{"type":"pvt_move","axis":0,"points":[{"position":153.333,"velocity":1000.0,"time_ms":2000.0}]}"#,
        ),
    ]
}

/// Every variant from its required fields only, and the command that reads as.
fn minimal() -> Vec<(&'static str, Command, &'static str)> {
    vec![
        (
            r#"{"type":"move_absolute","axis":0,"position":1.0}"#,
            Command::from(MoveAbsolute {
                axis: 0,
                position: 1.0,
                velocity: None,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode: BufferMode::Aborting,
            }),
            r#"{"type":"move_absolute","axis":0,"position":1.0,"velocity":null,"acceleration":null,"deceleration":null,"jerk":null,"buffer_mode":"aborting"}"#,
        ),
        (
            r#"{"type":"move_relative","axis":0,"distance":1.0}"#,
            Command::from(MoveRelative {
                axis: 0,
                distance: 1.0,
                velocity: None,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode: BufferMode::Aborting,
            }),
            r#"{"type":"move_relative","axis":0,"distance":1.0,"velocity":null,"acceleration":null,"deceleration":null,"jerk":null,"buffer_mode":"aborting"}"#,
        ),
        (
            r#"{"type":"move_velocity","axis":0,"velocity":1.0}"#,
            Command::from(MoveVelocity {
                axis: 0,
                velocity: 1.0,
                acceleration: None,
                deceleration: None,
                jerk: None,
                buffer_mode: BufferMode::Aborting,
            }),
            r#"{"type":"move_velocity","axis":0,"velocity":1.0,"acceleration":null,"deceleration":null,"jerk":null,"buffer_mode":"aborting"}"#,
        ),
        (
            r#"{"type":"stop","axis":0}"#,
            Command::from(Stop {
                axis: 0,
                mode: StopMode::Smooth,
                deceleration: None,
            }),
            r#"{"type":"stop","axis":0,"mode":"smooth","deceleration":null}"#,
        ),
        (
            r#"{"type":"halt","axis":0}"#,
            Command::from(Halt {
                axis: 0,
                deceleration: None,
            }),
            r#"{"type":"halt","axis":0,"deceleration":null}"#,
        ),
        (
            r#"{"type":"home","axis":0}"#,
            Command::from(Home {
                axis: 0,
                method: None,
                switch_velocity: None,
                zero_velocity: None,
                acceleration: None,
                offset: None,
                timeout: None,
                quirks: HomingQuirks::default(),
                buffer_mode: BufferMode::Aborting,
            }),
            r#"{"type":"home","axis":0,"method":null,"switch_velocity":null,"zero_velocity":null,"acceleration":null,"offset":null,"timeout":null,"quirks":{"after_home":"decelerate","switch_latch":"exact","index_latch":"exact","switch_scan_ticks":0,"max_search_distance":0.0,"initial_backoff":0.0,"rescan":null,"trial":false},"buffer_mode":"aborting"}"#,
        ),
        (
            r#"{"type":"set_position","axis":0,"position":2.0}"#,
            Command::from(SetPosition {
                axis: 0,
                position: 2.0,
                frame: PositionFrame::Both,
            }),
            r#"{"type":"set_position","axis":0,"position":2.0,"frame":"both"}"#,
        ),
        (
            r#"{"type":"set_parameter","axis":0,"name":"decel","value":3.0}"#,
            Command::from(SetParameter {
                axis: 0,
                name: ParamId::Decel,
                value: 3.0,
                lenient: false,
            }),
            r#"{"type":"set_parameter","axis":0,"name":"decel","value":3.0,"lenient":false}"#,
        ),
        (
            r#"{"type":"modify_target","axis":0,"position":4.0}"#,
            Command::from(ModifyTarget {
                axis: 0,
                position: 4.0,
                relative: false,
            }),
            r#"{"type":"modify_target","axis":0,"position":4.0,"relative":false}"#,
        ),
        (
            r#"{"type":"cancel","axis":0}"#,
            Command::from(Cancel {
                axis: 0,
                scope: CancelScope::Current,
            }),
            r#"{"type":"cancel","axis":0,"scope":"current"}"#,
        ),
        (
            r#"{"type":"force_input","axis":0,"input":"drive_alarm"}"#,
            Command::from(ForceInput {
                axis: 0,
                input: AxisInput::DriveAlarm,
                value: None,
            }),
            r#"{"type":"force_input","axis":0,"input":"drive_alarm","value":null}"#,
        ),
        (
            r#"{"type":"force_digital_input","channel":0}"#,
            Command::from(ForceDigitalInput {
                channel: 0,
                value: None,
            }),
            r#"{"type":"force_digital_input","channel":0,"value":null}"#,
        ),
        (
            r#"{"type":"force_analog_input","channel":0}"#,
            Command::from(ForceAnalogInput {
                channel: 0,
                value: None,
            }),
            r#"{"type":"force_analog_input","channel":0,"value":null}"#,
        ),
        (
            r#"{"type":"inject_following_error","axis":0}"#,
            Command::from(InjectFollowingError {
                axis: 0,
                amount: None,
            }),
            r#"{"type":"inject_following_error","axis":0,"amount":null}"#,
        ),
        (
            r#"{"type":"setpoint","axis":0}"#,
            Command::from(StreamSetpoint {
                axis: 0,
                setpoint: None,
            }),
            r#"{"type":"setpoint","axis":0,"setpoint":null}"#,
        ),
        (
            r#"{"type":"move_together","moves":[{"type":"move_relative","axis":1,"distance":5}]}"#,
            Command::from(MoveTogether {
                moves: vec![TogetherMove::MoveRelative(MoveRelative {
                    axis: 1,
                    distance: 5.0,
                    velocity: None,
                    acceleration: None,
                    deceleration: None,
                    jerk: None,
                    buffer_mode: BufferMode::Aborting,
                })],
            }),
            r#"{"type":"move_together","moves":[{"type":"move_relative","axis":1,"distance":5.0,"velocity":null,"acceleration":null,"deceleration":null,"jerk":null,"buffer_mode":"aborting"}]}"#,
        ),
        (
            r#"{"type":"stop_axes","axes":[1]}"#,
            Command::from(StopAxes {
                axes: vec![1],
                mode: StopMode::Smooth,
                deceleration: None,
            }),
            r#"{"type":"stop_axes","axes":[1],"mode":"smooth","deceleration":null}"#,
        ),
        (
            r#"{"type":"stop_all"}"#,
            Command::from(StopAll {
                mode: StopMode::Abrupt,
                deceleration: None,
            }),
            r#"{"type":"stop_all","mode":"abrupt","deceleration":null}"#,
        ),
        (
            r#"{"type":"capture_arm","axis":0,"source":"index"}"#,
            Command::from(CaptureArm {
                axis: 0,
                channel: 0,
                source: CaptureSource::Index,
                input: None,
                source_axis: None,
                edge: CaptureEdge::Rising,
                repeat: 1,
                continuous: false,
                window: None,
            }),
            r#"{"type":"capture_arm","axis":0,"channel":0,"source":"index","edge":"rising","repeat":1,"continuous":false}"#,
        ),
        (
            r#"{"type":"capture_clear","axis":0}"#,
            Command::from(CaptureClear {
                axis: 0,
                channel: 0,
            }),
            r#"{"type":"capture_clear","axis":0,"channel":0}"#,
        ),
        (
            r#"{"type":"compare_start","axis":0,"start":10,"interval":10,"end":50,"output":0}"#,
            Command::from(CompareStart {
                channel: 0,
                axis: 0,
                axis_y: None,
                source: PositionSource::Commanded,
                positions: vec![],
                start: Some(10.0),
                interval: Some(10.0),
                end: Some(50.0),
                points: vec![],
                error_zone: 0.0,
                disturbance: 0.0,
                output: 0,
                mode: CompareOutputMode::Pulse,
                level: true,
                pulse_width: 0.0,
                min_interval: 0.0,
            }),
            r#"{"type":"compare_start","channel":0,"axis":0,"source":"commanded","start":10.0,"interval":10.0,"end":50.0,"error_zone":0.0,"output":0,"mode":"pulse","level":true,"pulse_width":0.0,"min_interval":0.0}"#,
        ),
        (
            r#"{"type":"compare_stop"}"#,
            Command::from(CompareStop { channel: 0 }),
            r#"{"type":"compare_stop","channel":0}"#,
        ),
        (
            r#"{"type":"stream_config","axis":0}"#,
            Command::from(StreamConfig {
                axis: 0,
                mode: StreamMode::Refresh,
                loop_count: 1,
                stop_deceleration: None,
            }),
            r#"{"type":"stream_config","axis":0,"mode":"refresh","loop_count":1,"stop_deceleration":null}"#,
        ),
        (
            r#"{"type":"pt_push","axis":0,"points":[{"position":1,"time_ms":2}]}"#,
            Command::from(PtPush {
                axis: 0,
                points: vec![PtPoint {
                    position: 1.0,
                    time_ms: 2.0,
                    kind: PtKind::Normal,
                }],
            }),
            r#"{"type":"pt_push","axis":0,"points":[{"position":1.0,"time_ms":2.0,"kind":"normal"}]}"#,
        ),
    ]
}

/// Inputs whose error serde reports, and the text it reports today.
const ERRORS: &[(&str, &str)] = &[
    (r#"{"type":"teleport","axis":0}"#, "unknown variant `teleport`, expected one of `enable`, `disable`, `reset`, `move_absolute`, `move_relative`, `move_velocity`, `stop`, `halt`, `resume`, `home`, `set_position`, `set_parameter`, `get_parameter`, `modify_target`, `cancel`, `command_state`, `force_input`, `force_digital_input`, `force_analog_input`, `write_digital_output`, `write_analog_output`, `inject_following_error`, `setpoint`, `read_object`, `write_object`, `move_together`, `stop_axes`, `stop_all`, `enable_all`, `disable_all`, `emergency_stop_all`, `reset_all`, `group_create`, `group_delete`, `group_enable`, `group_disable`, `group_reset`, `move_linear_absolute`, `move_linear_relative`, `move_circular_absolute`, `move_circular_relative`, `group_stop`, `group_halt`, `group_continue`, `group_emergency_stop`, `group_set_override`, `group_set_origin`, `group_set_parameter`, `group_set_output`, `group_dwell`, `group_wait_input`, `group_wait_position`, `group_axis_move`, `move_spline`, `move_ellipse`, `group_set_coordinate_transform`, `group_set_coordinate_system`, `group_set_rotary_transform`, `group_set_xyza_transform`, `group_delete_transform`, `move_protection_enable`, `move_protection_disable`, `move_circular_angle`, `group_jog`, `group_jog_axis`, `gear_in`, `gear_set_ratio`, `gear_out`, `cam_table`, `cam_in`, `cam_out`, `capture_arm`, `capture_clear`, `compare_start`, `compare_stop`, `stream_config`, `pt_push`, `pvt_push`, `stream_clear`, `stream_start`, `pvt_move`, `compensation_lead_screw`, `compensation_backlash`, `compensation_table`, `compensation_enable`, `compensation_disable`, `compensation_clear`, `sampling_configure`, `sampling_start`, `sampling_trigger`, `sampling_stop`, `sampling_read`, `superimpose_in`, `superimpose_set_ratios`, `superimpose_out`, `tangential_in`, `tangential_out`, `gantry_enable`, `gantry_disable`, `handwheel_in`, `handwheel_out`, `handwheel_turn`, `compare_fire`, `follow_config`, `follow_push`, `follow_clear`, `follow_start`, `follow_switch`, `follow_out`, `handwheel_set_ratio`, `stream_start_on_input`, `capture_arm_threshold`, `gantry_home`, `pulse_digital_output`, `tangential_corner_mode`, `tangential_corner_follow_next`, `tangential_corner_continue`, `cam_table_link`, `group_pulse_output`, `group_set_analog_output`, `group_stop_input`, `group_buffered_halt`, `z_compare_start`, `z_compare_stop`, `gantry_set_position`, `gantry_set_pid`, `compensation_offset_amount`, `compensation_offset_profile`, `compensation_offset_trigger`, `compensation_offset_stop`, `reset_faults`, `set_estop_input`, `estimate_group_time`, `watchdog_set`, `watchdog_kick`, `input_stop_set`, `input_stop_clear`, `position_watch_set`, `position_watch_clear`, `add_axis_set`, `filter_input_shaping`, `filter_vsf`, `filter_disable`, `bind_analog_output`, `group_set_polar_transform`, `group_delete_polar_transform` at line 1 column 18"),
    (r#"{"axis":0}"#, "missing field `type` at line 1 column 10"),
    (r#"{"type":"move_absolute","axis":0}"#, "missing field `position`"),
    (r#"{"type":"move_absolute","axis":0,"positon":10}"#, "unknown field `positon`, expected one of `axis`, `position`, `velocity`, `acceleration`, `deceleration`, `jerk`, `buffer_mode`"),
    (r#"{"type":"enable","axis":"zero"}"#, "invalid type: string \"zero\", expected u16"),
    (r#"{"type":"enable","axis":-1}"#, "invalid value: integer `-1`, expected u16"),
    (r#"{"type":"stop","axis":0,"mode":"gently"}"#, "unknown variant `gently`, expected one of `smooth`, `abrupt`, `emergency`, `immediate`"),
    (r#"{"type":"command_state","id":1,"axis":0}"#, "unknown field `axis`, expected `id`"),
    (r#"{"type":"write_object","slave":0,"index":1,"subindex":0,"value":{"q1":1}}"#, "unknown variant `q1`, expected one of `bool`, `i8`, `i16`, `i32`, `i64`, `u8`, `u16`, `u32`, `u64`, `f32`, `f64`, `string`, `bytes`"),
    (r#"{"type":"setpoint","axis":0,"setpoint":{"mode":"jerk"}}"#, "unknown variant `jerk`, expected one of `position`, `velocity`, `torque`"),
    (r#"{"type":"enable"}"#, "missing field `axis`"),
    (r#""enable""#, "invalid type: string \"enable\", expected internally tagged enum Command at line 1 column 8"),
    (r#"[1]"#, "invalid type: integer `1`, expected variant identifier at line 1 column 2"),
    (r#"{"type":"move_together","moves":[{"type":"stop","axis":0}]}"#, "unknown variant `stop`, expected one of `move_absolute`, `move_relative`, `move_velocity`"),
    (r#"{"type":"stop_all","mode":"abrupt","axes":[0]}"#, "unknown field `axes`, expected `mode` or `deceleration`"),
    (r#"{"type":"disable_all","axis":0}"#, "unknown field `axis`, there are no fields"),
    (r#"{"type":"pt_push","axis":0,"points":[{"position":1,"time_ms":1,"kind":"fast"}]}"#, "unknown variant `fast`, expected one of `normal`, `stop`, `even`"),
    (r#"{"type":"pvt_push","axis":0,"points":[{"position":1,"time_ms":1}]}"#, "missing field `velocity`"),
];

#[test]
fn every_variant_serializes_to_its_pinned_json_and_back() {
    let cases = full();
    assert_eq!(
        cases.len(),
        44,
        "one case per variant but the group commands (group_json.rs)"
    );
    assert_pinned(cases);
}

#[test]
fn absent_optional_fields_take_their_defaults_and_serialize_explicitly() {
    for (input, command, json) in minimal() {
        assert_eq!(
            serde_json::from_str::<Command>(input).unwrap(),
            command,
            "{input}"
        );
        assert_eq!(serde_json::to_string(&command).unwrap(), json);
        assert_eq!(
            serde_json::from_str::<Command>(json).unwrap(),
            command,
            "{json}"
        );
    }
}

#[test]
fn the_tag_may_come_anywhere_and_a_sequence_reads_tag_first() {
    let json: Command = serde_json::from_str(r#"{"axis":2,"type":"enable"}"#).unwrap();
    assert_eq!(json, Command::from(Enable { axis: 2 }));
    // serde also takes an internally tagged enum as a sequence, tag first.
    let seq: Command = serde_json::from_str(r#"["enable",2]"#).unwrap();
    assert_eq!(seq, Command::from(Enable { axis: 2 }));
}

#[test]
fn serde_errors_keep_their_wording() {
    for (json, message) in ERRORS {
        let e = serde_json::from_str::<Command>(json).unwrap_err();
        assert_eq!(e.to_string(), *message, "{json}");
    }
}

/// The compensation family (issue 12 item 8), with every field set, and its JSON.
fn compensation() -> Vec<(Command, &'static str)> {
    use axes::command::{
        BacklashDirection, CompensationBacklash, CompensationClear, CompensationDisable,
        CompensationEnable, CompensationLeadScrew, CompensationReference, CompensationTable,
        ReferenceSource,
    };
    vec![
        (
            Command::from(CompensationLeadScrew {
                axis: 0,
                positions: vec![0.0, 10.0],
                positive: vec![0.5, -0.5],
                negative: Some(vec![0.25, 0.0]),
                enable: false,
            }),
            r#"{"type":"compensation_lead_screw","axis":0,"positions":[0.0,10.0],"positive":[0.5,-0.5],"negative":[0.25,0.0],"enable":false}"#,
        ),
        (
            Command::from(CompensationBacklash {
                axis: 1,
                amount: 1000.0,
                step: 200.0,
                direction: BacklashDirection::Negative,
                enable: true,
            }),
            r#"{"type":"compensation_backlash","axis":1,"amount":1000.0,"step":200.0,"direction":"negative","enable":true}"#,
        ),
        (
            Command::from(CompensationTable {
                axis: 2,
                references: vec![
                    CompensationReference {
                        axis: 0,
                        source: ReferenceSource::Actual,
                    },
                    CompensationReference {
                        axis: 1,
                        source: ReferenceSource::Planned,
                    },
                ],
                start: vec![0.0, 0.0],
                step: vec![3.0, 4.0],
                count: vec![2, 2],
                values: vec![0.0, 1.0, 2.0, 3.0],
                enable: true,
                angle: 0.0,
                interpolation: axes::command::CompensationInterpolation::Linear,
            }),
            r#"{"type":"compensation_table","axis":2,"references":[{"axis":0,"source":"actual"},{"axis":1,"source":"planned"}],"start":[0.0,0.0],"step":[3.0,4.0],"count":[2,2],"values":[0.0,1.0,2.0,3.0],"enable":true}"#,
        ),
        (
            Command::from(CompensationTable {
                axis: 2,
                references: vec![
                    CompensationReference {
                        axis: 0,
                        source: ReferenceSource::Planned,
                    },
                    CompensationReference {
                        axis: 1,
                        source: ReferenceSource::Planned,
                    },
                ],
                start: vec![0.0, 0.0],
                step: vec![3000.0, 4000.0],
                count: vec![3, 4],
                values: vec![0.0; 12],
                enable: false,
                angle: 30.0,
                interpolation: axes::command::CompensationInterpolation::Cubic,
            }),
            r#"{"type":"compensation_table","axis":2,"references":[{"axis":0,"source":"planned"},{"axis":1,"source":"planned"}],"start":[0.0,0.0],"step":[3000.0,4000.0],"count":[3,4],"values":[0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0],"enable":false,"angle":30.0,"interpolation":"cubic"}"#,
        ),
        (
            Command::from(CompensationEnable { axis: 3 }),
            r#"{"type":"compensation_enable","axis":3}"#,
        ),
        (
            Command::from(CompensationDisable { axis: 3 }),
            r#"{"type":"compensation_disable","axis":3}"#,
        ),
        (
            Command::from(CompensationClear { axis: 3 }),
            r#"{"type":"compensation_clear","axis":3}"#,
        ),
    ]
}

#[test]
fn compensation_commands_keep_their_json() {
    assert_pinned(compensation());
    // Optional fields: `negative` is the positive table, `direction` positive, `enable` true,
    // a reference's `source` the planned position.
    let minimal: Command = serde_json::from_str(
        r#"{"type":"compensation_backlash","axis":0,"amount":1.0,"step":0.5}"#,
    )
    .unwrap();
    assert_eq!(
        serde_json::to_string(&minimal).unwrap(),
        r#"{"type":"compensation_backlash","axis":0,"amount":1.0,"step":0.5,"direction":"positive","enable":true}"#
    );
    let table: Command = serde_json::from_str(
        r#"{"type":"compensation_table","axis":0,"references":[{"axis":1}],"start":[0],"step":[1],"count":[2],"values":[0,1]}"#,
    )
    .unwrap();
    assert!(serde_json::to_string(&table)
        .unwrap()
        .contains(r#""references":[{"axis":1,"source":"planned"}]"#));
    let e = serde_json::from_str::<Command>(
        r#"{"type":"compensation_lead_screw","axis":0,"positions":[0,1],"positive":[0,1],"negatve":[1,0]}"#,
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("unknown field `negatve`"), "{e}");
}

#[test]
fn sampling_commands_keep_their_json() {
    use axes::command::{
        SampledVariable, SamplingConfigure, SamplingRead, SamplingStart, SamplingStop,
        SamplingTrigger, SamplingTriggerNow,
    };
    let cases = vec![
        (
            Command::from(SamplingConfigure {
                sampler: 1,
                variables: vec![
                    SampledVariable::PlannedPosition { axis: 0 },
                    SampledVariable::DigitalInput { channel: 3 },
                ],
                interval: 10,
                points: 3000,
                trigger: SamplingTrigger::Rising {
                    variable: SampledVariable::ActualVelocity { axis: 2 },
                    value: 5.0,
                },
                delay: 0,
            }),
            r#"{"type":"sampling_configure","sampler":1,"variables":[{"kind":"planned_position","axis":0},{"kind":"digital_input","channel":3}],"interval":10,"points":3000,"trigger":{"kind":"rising","variable":{"kind":"actual_velocity","axis":2},"value":5.0}}"#,
        ),
        (
            Command::from(SamplingStart { sampler: 0 }),
            r#"{"type":"sampling_start","sampler":0}"#,
        ),
        (
            Command::from(SamplingTriggerNow { sampler: 0 }),
            r#"{"type":"sampling_trigger","sampler":0}"#,
        ),
        (
            Command::from(SamplingStop { sampler: 0 }),
            r#"{"type":"sampling_stop","sampler":0}"#,
        ),
        (
            Command::from(SamplingRead {
                sampler: 2,
                from: 100,
                count: Some(50),
            }),
            r#"{"type":"sampling_read","sampler":2,"from":100,"count":50}"#,
        ),
    ];
    assert_pinned(cases);
    let minimal: Command = serde_json::from_str(
        r#"{"type":"sampling_configure","sampler":0,"points":2,"variables":[{"kind":"following_error","axis":0}]}"#,
    )
    .unwrap();
    assert_eq!(
        serde_json::to_string(&minimal).unwrap(),
        r#"{"type":"sampling_configure","sampler":0,"variables":[{"kind":"following_error","axis":0}],"interval":1,"points":2,"trigger":{"kind":"immediate"}}"#
    );
    let e = serde_json::from_str::<Command>(
        r#"{"type":"sampling_configure","sampler":0,"points":2,"variables":[{"kind":"torque","axis":0}]}"#,
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("unknown variant `torque`, expected one of `planned_position`"),
        "{e}"
    );
}

#[test]
fn superimpose_and_tangential_commands_keep_their_json() {
    use axes::command::CamTableLink;
    use axes::command::{
        AddAxisSet, MasterSource, SafeZMode, SuperimposeIn, SuperimposeOut, SuperimposeSetRatios,
        TangentialCornerContinue, TangentialCornerFollowNext, TangentialCornerMode,
        TangentialCornerModeKind, TangentialIn, TangentialOut,
    };
    let cases = vec![
        (
            Command::from(SuperimposeIn {
                slave: 3,
                masters: [0, 1],
                ratios: [0.707, -0.707],
                master_source: MasterSource::Actual,
            }),
            r#"{"type":"superimpose_in","slave":3,"masters":[0,1],"ratios":[0.707,-0.707],"master_source":"actual"}"#,
        ),
        (
            Command::from(SuperimposeSetRatios {
                slave: 3,
                ratios: [1.0, -1.0],
            }),
            r#"{"type":"superimpose_set_ratios","slave":3,"ratios":[1.0,-1.0]}"#,
        ),
        (
            Command::from(SuperimposeOut { slave: 3 }),
            r#"{"type":"superimpose_out","slave":3}"#,
        ),
        (
            Command::from(TangentialIn {
                axis: 2,
                group: 1,
                coordinates: [1, 2],
                offset: 90.0,
                units_per_turn: 20000.0,
            }),
            r#"{"type":"tangential_in","axis":2,"group":1,"coordinates":[1,2],"offset":90.0,"units_per_turn":20000.0}"#,
        ),
        (
            Command::from(TangentialOut { axis: 2 }),
            r#"{"type":"tangential_out","axis":2}"#,
        ),
        (
            Command::from(TangentialCornerMode {
                axis: 2,
                mode: TangentialCornerModeKind::Manual,
                angle_limit: 0.5,
                z_axis: None,
                safe_z: 0.0,
                safe_z_mode: SafeZMode::Incremental,
            }),
            r#"{"type":"tangential_corner_mode","axis":2,"mode":"manual","angle_limit":0.5}"#,
        ),
        (
            Command::from(TangentialCornerMode {
                axis: 2,
                mode: TangentialCornerModeKind::Auto,
                angle_limit: 0.5,
                z_axis: Some(3),
                safe_z: 10.0,
                safe_z_mode: SafeZMode::Absolute,
            }),
            r#"{"type":"tangential_corner_mode","axis":2,"mode":"auto","angle_limit":0.5,"z_axis":3,"safe_z":10.0,"safe_z_mode":"absolute"}"#,
        ),
        (
            Command::from(AddAxisSet {
                base: 1,
                add: Some(4),
            }),
            r#"{"type":"add_axis_set","base":1,"add":4}"#,
        ),
        (
            Command::from(AddAxisSet { base: 1, add: None }),
            r#"{"type":"add_axis_set","base":1}"#,
        ),
        (
            Command::from(TangentialCornerFollowNext { axis: 2 }),
            r#"{"type":"tangential_corner_follow_next","axis":2}"#,
        ),
        (
            Command::from(TangentialCornerContinue { axis: 2 }),
            r#"{"type":"tangential_corner_continue","axis":2}"#,
        ),
        (
            Command::from(CamTableLink {
                table: 4,
                slave_distance: 200.0,
                master_distance: 400.0,
                master_acceleration_distance: 125.0,
                master_deceleration_distance: 125.0,
                s_ratio: 0.5,
                slave_base_distance: 400.0,
                master_before_distance: 75.0,
                master_after_distance: 75.0,
            }),
            r#"{"type":"cam_table_link","table":4,"slave_distance":200.0,"master_distance":400.0,"master_acceleration_distance":125.0,"master_deceleration_distance":125.0,"s_ratio":0.5,"slave_base_distance":400.0,"master_before_distance":75.0,"master_after_distance":75.0}"#,
        ),
    ];
    assert_pinned(cases);
    let minimal: Command =
        serde_json::from_str(r#"{"type":"tangential_in","axis":2,"group":1}"#).unwrap();
    assert_eq!(
        minimal,
        Command::from(TangentialIn {
            axis: 2,
            group: 1,
            coordinates: [0, 1],
            offset: 0.0,
            units_per_turn: 360.0,
        })
    );
    let minimal: Command = serde_json::from_str(
        r#"{"type":"superimpose_in","slave":2,"masters":[0,1],"ratios":[1,1]}"#,
    )
    .unwrap();
    assert_eq!(
        serde_json::to_string(&minimal).unwrap(),
        r#"{"type":"superimpose_in","slave":2,"masters":[0,1],"ratios":[1.0,1.0],"master_source":"commanded"}"#
    );
    let e = serde_json::from_str::<Command>(
        r#"{"type":"superimpose_in","slave":2,"masters":[0,1,2],"ratios":[1,1]}"#,
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("invalid length 3, expected 2 elements"),
        "{e}"
    );
}

#[test]
fn gantry_and_handwheel_commands_keep_their_json() {
    use axes::command::{
        GantryDisable, GantryEnable, GantryHome, HandwheelExcess, HandwheelIn, HandwheelOut,
        HandwheelTurn,
    };
    let cases = vec![
        (
            Command::from(GantryEnable {
                master: 0,
                slaves: vec![1, 2],
                warning_limit: 0.5,
                fault_limit: 2.0,
                require_disabled: false,
                closed_loop: false,
            }),
            r#"{"type":"gantry_enable","master":0,"slaves":[1,2],"warning_limit":0.5,"fault_limit":2.0}"#,
        ),
        (
            // HIMC EnableGantryPair (digest 004 TV 38).
            Command::from(GantryEnable {
                master: 0,
                slaves: vec![1],
                warning_limit: 0.0,
                fault_limit: 0.0,
                require_disabled: true,
                closed_loop: false,
            }),
            r#"{"type":"gantry_enable","master":0,"slaves":[1],"warning_limit":0.0,"fault_limit":0.0,"require_disabled":true}"#,
        ),
        (
            Command::from(GantryDisable { master: 0 }),
            r#"{"type":"gantry_disable","master":0}"#,
        ),
        (
            Command::from(GantryHome {
                axes: vec![1, 2],
                instruction: axes::homing::vendor::HmcInstruction::HomeEx,
                home_mode: 4,
                reference_position: -1000.0,
                position_error: 10.0,
            }),
            r#"{"type":"gantry_home","axes":[1,2],"instruction":"home_ex","home_mode":4,"reference_position":-1000.0,"position_error":10.0}"#,
        ),
        (
            Command::from(HandwheelIn {
                axis: 0,
                input: 256,
                numerator: 5.0,
                denominator: 1.0,
                velocity: 10.0,
                acceleration: 1.0,
                excess: HandwheelExcess::Drop,
            }),
            r#"{"type":"handwheel_in","axis":0,"input":256,"numerator":5.0,"denominator":1.0,"velocity":10.0,"acceleration":1.0,"excess":"drop"}"#,
        ),
        (
            Command::from(HandwheelOut { axis: 0 }),
            r#"{"type":"handwheel_out","axis":0}"#,
        ),
        (
            Command::from(HandwheelTurn {
                input: 257,
                counts: -40,
            }),
            r#"{"type":"handwheel_turn","input":257,"counts":-40}"#,
        ),
    ];
    assert_pinned(cases);
    // The limits default to 0 (none) and the excess to catch_up.
    let minimal: Command =
        serde_json::from_str(r#"{"type":"gantry_enable","master":3,"slaves":[4]}"#).unwrap();
    assert_eq!(
        serde_json::to_string(&minimal).unwrap(),
        r#"{"type":"gantry_enable","master":3,"slaves":[4],"warning_limit":0.0,"fault_limit":0.0}"#
    );
    let minimal: Command = serde_json::from_str(
        r#"{"type":"handwheel_in","axis":0,"input":0,"numerator":1,"denominator":2,"velocity":1,"acceleration":1}"#,
    )
    .unwrap();
    assert!(serde_json::to_string(&minimal)
        .unwrap()
        .ends_with(r#""excess":"catch_up"}"#));
}

#[test]
fn follow_and_handwheel_ratio_commands_keep_their_json() {
    use axes::command::{
        CamPoint, Direction, FollowClear, FollowConfig, FollowDirection, FollowEvent, FollowOut,
        FollowPush, FollowSegment, FollowStart, FollowSwitch, HandwheelSetRatio, MasterSource,
    };
    let cases = vec![
        (
            Command::from(FollowConfig {
                axis: 1,
                master: Some(0),
                master_source: Some(MasterSource::Actual),
                loop_count: Some(3),
                event: Some(FollowEvent::MasterCrossing),
                start_position: Some(50000.0),
                start_direction: Some(Direction::Negative),
                direction: Some(FollowDirection::Positive),
            }),
            r#"{"type":"follow_config","axis":1,"master":0,"master_source":"actual","loop_count":3,"event":"master_crossing","start_position":50000.0,"start_direction":"negative","direction":"positive"}"#,
        ),
        (
            Command::from(FollowPush {
                axis: 1,
                fifo: 1,
                points: vec![CamPoint {
                    master: 20000.0,
                    slave: 10000.0,
                    segment: FollowSegment::Continuous,
                }],
            }),
            r#"{"type":"follow_push","axis":1,"fifo":1,"points":[{"master":20000.0,"slave":10000.0,"segment":"continuous"}]}"#,
        ),
        (
            Command::from(FollowClear { axis: 1, fifo: 0 }),
            r#"{"type":"follow_clear","axis":1,"fifo":0}"#,
        ),
        (
            Command::from(FollowStart { axes: vec![1, 2] }),
            r#"{"type":"follow_start","axes":[1,2]}"#,
        ),
        (
            Command::from(FollowSwitch { axes: vec![1] }),
            r#"{"type":"follow_switch","axes":[1]}"#,
        ),
        (
            Command::from(FollowOut { axis: 1 }),
            r#"{"type":"follow_out","axis":1}"#,
        ),
        (
            Command::from(HandwheelSetRatio {
                axis: Some(2),
                numerator: 3.0,
                denominator: 2.0,
            }),
            r#"{"type":"handwheel_set_ratio","axis":2,"numerator":3.0,"denominator":2.0}"#,
        ),
        (
            Command::from(axes::command::StreamStartOnInput {
                axis: 1,
                input: 5,
                edge: CaptureEdge::Falling,
            }),
            r#"{"type":"stream_start_on_input","axis":1,"input":5,"edge":"falling"}"#,
        ),
        (
            Command::from(axes::command::CaptureArmThreshold {
                axis: 0,
                channel: 2,
                source: PositionSource::Actual,
                source_axis: Some(3),
                threshold: 1500.0,
                edge: CaptureEdge::Both,
                repeat: 4,
                continuous: true,
            }),
            r#"{"type":"capture_arm_threshold","axis":0,"channel":2,"source":"actual","source_axis":3,"threshold":1500.0,"edge":"both","repeat":4,"continuous":true}"#,
        ),
    ];
    assert_pinned(cases);
    // Every setting is optional (one NMC setter each); a ratio for every handwheel.
    for minimal in [
        r#"{"type":"follow_config","axis":1}"#,
        r#"{"type":"handwheel_set_ratio","numerator":1.0,"denominator":4.0}"#,
    ] {
        let c: Command = serde_json::from_str(minimal).unwrap();
        assert_eq!(serde_json::to_string(&c).unwrap(), minimal);
    }
}

#[test]
fn hmc_z_compare_disturbance_gantry_and_offset_commands_keep_their_json() {
    use axes::command::{
        CompareOutputMode, CompareStart, GantryEnable, GantrySetPid, GantrySetPosition,
        PositionSource, ZCompareStart, ZCompareStop,
    };
    let cases = vec![
        (
            // HMC_SwitchTZConfig(1, 2, 0, 1, 50 µs, 1, targets, 2).
            Command::from(ZCompareStart {
                channel: 1,
                axis: 0,
                source: PositionSource::Actual,
                positions: vec![100.0, 200.0],
                output_axis: 2,
                mode: CompareOutputMode::Pulse,
                level: true,
                pulse_width: 5e-5,
            }),
            r#"{"type":"z_compare_start","channel":1,"axis":0,"source":"actual","positions":[100.0,200.0],"output_axis":2,"mode":"pulse","level":true,"pulse_width":0.00005}"#,
        ),
        (
            Command::from(ZCompareStop { channel: 1 }),
            r#"{"type":"z_compare_stop","channel":1}"#,
        ),
        (
            // HMC NormalSwitch2D with dDisturbValue 0.5.
            Command::from(CompareStart {
                channel: 2,
                axis: 0,
                axis_y: Some(1),
                source: PositionSource::Actual,
                positions: vec![],
                start: None,
                interval: None,
                end: None,
                points: vec![[10.0, 20.0]],
                error_zone: 2.0,
                disturbance: 0.5,
                output: 3,
                mode: CompareOutputMode::Pulse,
                level: true,
                pulse_width: 0.001,
                min_interval: 0.0,
            }),
            r#"{"type":"compare_start","channel":2,"axis":0,"axis_y":1,"source":"actual","points":[[10.0,20.0]],"error_zone":2.0,"disturbance":0.5,"output":3,"mode":"pulse","level":true,"pulse_width":0.001,"min_interval":0.0}"#,
        ),
        (
            // HMC_GantrySynchro ucMode 1.
            Command::from(GantryEnable {
                master: 0,
                slaves: vec![1],
                warning_limit: 100.0,
                fault_limit: 500.0,
                require_disabled: false,
                closed_loop: true,
            }),
            r#"{"type":"gantry_enable","master":0,"slaves":[1],"warning_limit":100.0,"fault_limit":500.0,"closed_loop":true}"#,
        ),
        (
            Command::from(GantrySetPosition {
                master: 0,
                position: -1000.0,
            }),
            r#"{"type":"gantry_set_position","master":0,"position":-1000.0}"#,
        ),
        (
            Command::from(GantrySetPid {
                axis: 1,
                kp: 20.0,
                ki: 5.0,
                kd: 0.1,
            }),
            r#"{"type":"gantry_set_pid","axis":1,"kp":20.0,"ki":5.0,"kd":0.1}"#,
        ),
    ];
    assert_pinned(cases);
    {
        use axes::command::{
            CompensationOffsetAmount, CompensationOffsetProfile, CompensationOffsetStop,
            CompensationOffsetTrigger,
        };
        assert_pinned(vec![
            (
                // HMC_SetAxisCompenPos(2, -0.25).
                Command::from(CompensationOffsetAmount {
                    axis: 2,
                    amount: -0.25,
                }),
                r#"{"type":"compensation_offset_amount","axis":2,"amount":-0.25}"#,
            ),
            (
                // HMC_SetAxisCompenPara(2, 1, 10, 100, 200, 5000).
                Command::from(CompensationOffsetProfile {
                    axis: 2,
                    s_curve: true,
                    velocity: 10.0,
                    acceleration: 100.0,
                    deceleration: 200.0,
                    jerk: 5000.0,
                }),
                r#"{"type":"compensation_offset_profile","axis":2,"s_curve":true,"velocity":10.0,"acceleration":100.0,"deceleration":200.0,"jerk":5000.0}"#,
            ),
            (
                Command::from(CompensationOffsetTrigger { axis: 2 }),
                r#"{"type":"compensation_offset_trigger","axis":2}"#,
            ),
            (
                Command::from(CompensationOffsetStop { axis: 2 }),
                r#"{"type":"compensation_offset_stop","axis":2}"#,
            ),
        ]);
    }
    // A Z compare toggles on the actual position by default (SwitchTZ ucTimeMode 0, MPos).
    let minimal: Command = serde_json::from_str(
        r#"{"type":"z_compare_start","axis":0,"positions":[5],"output_axis":0}"#,
    )
    .unwrap();
    assert_eq!(
        serde_json::to_string(&minimal).unwrap(),
        r#"{"type":"z_compare_start","channel":0,"axis":0,"source":"actual","positions":[5.0],"output_axis":0,"mode":"toggle","level":true,"pulse_width":0.0}"#
    );
    let minimal: Command =
        serde_json::from_str(r#"{"type":"gantry_set_pid","axis":1,"kp":1}"#).unwrap();
    assert_eq!(
        serde_json::to_string(&minimal).unwrap(),
        r#"{"type":"gantry_set_pid","axis":1,"kp":1.0,"ki":0.0,"kd":0.0}"#
    );
}

/// NMC_MtClrStsByBits (issue 13): the latches to clear, by flag name (bitflags text).
#[test]
fn reset_faults_names_its_latches() {
    use axes::command::ResetFaults;
    use axes::AxisFlags;
    assert_pinned(vec![(
        Command::from(ResetFaults {
            axis: 1,
            faults: AxisFlags::ESTOP | AxisFlags::HW_LIMIT_POS,
        }),
        r#"{"type":"reset_faults","axis":1,"faults":"HW_LIMIT_POS | ESTOP"}"#,
    )]);
}
