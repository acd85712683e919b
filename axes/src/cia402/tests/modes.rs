//! Modes of operation: PP, PV, HM, CSP, CSV, CST, mode display, touch probes, inputs.

use super::*;
use crate::command::{
    AxisCommand, Disable, Halt, Home, MoveAbsolute, MoveRelative, MoveVelocity, Reset, Resume,
    SetPosition, Stop, StreamSetpoint,
};

const TR: u16 = sw::TARGET_REACHED;
const B12: u16 = sw::OMS_12;
const B13: u16 = sw::OMS_13;
const LIMIT: u16 = sw::INTERNAL_LIMIT_ACTIVE;

fn moves(c: &Command) -> bool {
    matches!(
        c,
        Command::Axis(AxisCommand::MoveAbsolute(MoveAbsolute { .. }))
            | Command::Axis(AxisCommand::MoveRelative(MoveRelative { .. }))
            | Command::Axis(AxisCommand::MoveVelocity(MoveVelocity { .. }))
    )
}

/// A rig in Operation enabled, mode PP, profile velocity 100 mm/s (0.1 mm per tick).
fn pp() -> Rig {
    let mut rig = Rig::new();
    rig.mode(OperationMode::ProfilePosition);
    rig.set(obj::PROFILE_VELOCITY, 0, Value::U32(100_000));
    rig.operation_enabled();
    rig
}

fn set_point(rig: &mut Rig, target: i32, controlword: u16) {
    rig.set(obj::TARGET_POSITION, 0, Value::I32(target));
    rig.cw(controlword);
}

#[test]
fn mode_display_follows_the_requested_mode() {
    let mut rig = Rig::new();
    for mode in OperationMode::ALL {
        rig.mode(mode);
        rig.tick();
        assert_eq!(
            rig.int(obj::MODES_OF_OPERATION_DISPLAY),
            i64::from(mode.code())
        );
        assert_eq!(rig.drive.mode(), mode);
    }
    // Unsupported modes are refused (SDO abort 0x0609_0030); the display keeps the old one.
    for code in [2i8, 4, 5, 7, 11, -1, -128] {
        let error = rig
            .drive
            .write(obj::MODES_OF_OPERATION, 0, Value::I8(code))
            .unwrap_err();
        assert!(matches!(error, OdError::InvalidValue { .. }), "{code}");
        assert_eq!(error.sdo_abort_code(), 0x0609_0030);
        let error = rig
            .drive
            .write_bytes(obj::MODES_OF_OPERATION, 0, &code.to_le_bytes())
            .unwrap_err();
        assert_eq!(error.sdo_abort_code(), 0x0609_0030);
    }
    rig.tick();
    assert_eq!(rig.int(obj::MODES_OF_OPERATION_DISPLAY), 10);
    // The display follows in Operation enabled too.
    rig.operation_enabled();
    rig.mode(OperationMode::ProfileVelocity);
    rig.tick();
    assert_eq!(rig.int(obj::MODES_OF_OPERATION_DISPLAY), 3);
}

#[test]
fn pp_set_point_handshake_and_target_reached() {
    let mut rig = pp();
    rig.tick();
    // No set-point yet: at rest counts as reached; no acknowledge.
    assert_eq!(rig.sw() & (TR | B12 | B13), TR);
    set_point(&mut rig, 1000, 0x1F);
    assert_eq!(
        rig.sent(moves),
        [Command::from(MoveAbsolute {
            axis: 0,
            position: 1.0,
            velocity: Some(100.0),
            acceleration: Some(100.0),
            deceleration: Some(100.0),
            jerk: Some(0.0),
            buffer_mode: BufferMode::Buffered,
        })]
    );
    assert_eq!(rig.sw() & (TR | B12), B12, "acknowledged, not reached");
    // Holding bit 4 is no new set-point.
    rig.tick();
    assert!(rig.sent(moves).is_empty());
    assert_ne!(rig.sw() & B12, 0);
    // Bit 4 low: the acknowledge drops (the buffer has room).
    rig.cw(0x0F);
    assert_eq!(rig.sw() & B12, 0);
    assert!(rig.until(50, |r| r.sw() & TR != 0));
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 1000);
    assert_eq!(rig.int(obj::POSITION_DEMAND), 1000);
    assert_eq!(rig.sw() & sw::MOVING, 0);
}

#[test]
fn an_edge_written_between_two_steps_is_not_lost() {
    let mut rig = pp();
    rig.tick();
    // Bit 4 written low then high before the next step (two SDOs or RPDOs within a tick).
    rig.set(obj::TARGET_POSITION, 0, Value::I32(1000));
    rig.set(obj::CONTROLWORD, 0, Value::U16(0x0F));
    rig.set(obj::CONTROLWORD, 0, Value::U16(0x1F));
    rig.tick();
    assert_eq!(
        rig.sent(moves).len(),
        1,
        "the rising edge of bit 4 took the set-point"
    );
    assert_ne!(rig.sw() & B12, 0);
    // Held high, then 1 → 0 → 1 between steps: a second edge, a second set-point.
    rig.tick();
    assert!(rig.sent(moves).is_empty());
    rig.set(obj::TARGET_POSITION, 0, Value::I32(2000));
    rig.set(obj::CONTROLWORD, 0, Value::U16(0x0F));
    rig.set(obj::CONTROLWORD, 0, Value::U16(0x1F));
    rig.tick();
    assert_eq!(
        rig.sent(moves).len(),
        1,
        "the second edge took the second set-point"
    );
}

#[test]
fn pp_position_window_time_delays_target_reached() {
    let mut rig = pp();
    rig.set(obj::POSITION_WINDOW_TIME, 0, Value::U16(5));
    set_point(&mut rig, 500, 0x1F);
    rig.cw(0x0F);
    assert!(rig.until(20, |r| r.int(obj::POSITION_ACTUAL) == 500));
    let arrived = rig.now;
    assert!(rig.until(20, |r| r.sw() & TR != 0));
    assert!(rig.now - arrived >= 0.005 - 1e-9);
}

#[test]
fn pp_buffered_set_points_fill_a_two_deep_buffer() {
    let mut rig = pp();
    set_point(&mut rig, 1000, 0x1F);
    rig.cw(0x0F);
    set_point(&mut rig, 2000, 0x1F);
    assert_eq!(rig.sent(moves).len(), 1);
    assert!(matches!(
        rig.sent(moves)[..],
        [Command::Axis(AxisCommand::MoveAbsolute(MoveAbsolute {
            buffer_mode: BufferMode::Buffered,
            ..
        }))]
    ));
    // Buffer full (running + next): the acknowledge stays after bit 4 drops, and a further
    // set-point is not taken.
    rig.cw(0x0F);
    assert_ne!(rig.sw() & B12, 0);
    set_point(&mut rig, 3000, 0x1F);
    assert!(rig.sent(moves).is_empty());
    rig.cw(0x0F);
    // The first move ends, the buffer has room: acknowledge drops.
    assert!(rig.until(30, |r| r.sw() & B12 == 0));
    assert!(rig.int(obj::POSITION_ACTUAL) >= 1000);
    assert!(rig.until(30, |r| r.sw() & TR != 0));
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 2000);
}

#[test]
fn pp_change_set_immediately_aborts_the_running_move() {
    let mut rig = pp();
    set_point(&mut rig, 5000, 0x1F);
    rig.cw(0x0F);
    rig.ticks(3);
    set_point(&mut rig, 500, 0x3F);
    assert!(matches!(
        rig.sent(moves)[..],
        [Command::Axis(AxisCommand::MoveAbsolute(MoveAbsolute { position, buffer_mode: BufferMode::Aborting, .. }))] if approx(position, 0.5)
    ));
    assert_ne!(rig.sw() & B12, 0);
    rig.cw(0x2F);
    assert_eq!(rig.sw() & B12, 0);
    assert!(rig.until(60, |r| r.sw() & TR != 0));
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 500);
}

#[test]
fn pp_relative_set_points_add_to_the_preceding_target() {
    let mut rig = pp();
    // Buffered relative: MoveRelative from the preceding target.
    set_point(&mut rig, 300, 0x5F);
    assert!(matches!(
        rig.sent(moves)[..],
        [Command::Axis(AxisCommand::MoveRelative(MoveRelative { distance, buffer_mode: BufferMode::Buffered, .. }))] if approx(distance, 0.3)
    ));
    rig.cw(0x4F);
    set_point(&mut rig, 300, 0x5F);
    rig.cw(0x4F);
    assert!(rig.until(30, |r| r.sw() & TR != 0));
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 600);
    // Changed immediately: the absolute target it means (600 + 100), aborting.
    set_point(&mut rig, 100, 0x7F);
    assert!(matches!(
        rig.sent(moves)[..],
        [Command::Axis(AxisCommand::MoveAbsolute(MoveAbsolute { position, buffer_mode: BufferMode::Aborting, .. }))] if approx(position, 0.7)
    ));
    rig.cw(0x6F);
    assert!(rig.until(30, |r| r.sw() & TR != 0));
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 700);
}

#[test]
fn pp_targets_are_limited_by_software_limits_and_velocity_limits() {
    let mut rig = pp();
    rig.set(obj::SOFTWARE_POSITION_LIMIT, 1, Value::I32(-1500));
    rig.set(obj::SOFTWARE_POSITION_LIMIT, 2, Value::I32(1500));
    set_point(&mut rig, 5000, 0x1F);
    assert!(matches!(
        rig.sent(moves)[..],
        [Command::Axis(AxisCommand::MoveAbsolute(MoveAbsolute { position, .. }))] if approx(position, 1.5)
    ));
    assert_ne!(rig.sw() & LIMIT, 0);
    rig.cw(0x0F);
    assert!(rig.until(30, |r| r.sw() & TR != 0));
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 1500);
    // A set-point inside the limits clears bit 11; a velocity over 0x607F sets it.
    rig.set(obj::MAX_PROFILE_VELOCITY, 0, Value::U32(50_000));
    set_point(&mut rig, 0, 0x1F);
    assert!(matches!(
        rig.sent(moves)[..],
        [Command::Axis(AxisCommand::MoveAbsolute(MoveAbsolute { velocity: Some(v), .. }))] if approx(v, 50.0)
    ));
    assert_ne!(rig.sw() & LIMIT, 0);
    rig.cw(0x0F);
    rig.set(obj::MAX_PROFILE_VELOCITY, 0, Value::U32(u32::MAX));
    set_point(&mut rig, 100, 0x1F);
    assert_eq!(rig.sw() & LIMIT, 0);
}

#[test]
fn pp_refused_by_a_limit_sets_internal_limit_active() {
    let mut rig = pp();
    rig.axis.status.flags.insert(AxisFlags::HW_LIMIT_POS);
    set_point(&mut rig, 1000, 0x1F);
    assert!(matches!(
        rig.drive.last_refusal(),
        Some(EngineError::LimitActive { .. })
    ));
    // The switch is released; the refusal still shows, and the target is not reached.
    rig.axis.status.flags.remove(AxisFlags::HW_LIMIT_POS);
    rig.cw(0x0F);
    assert_eq!(rig.sw() & (LIMIT | TR), LIMIT);
    // The next accepted set-point clears it.
    set_point(&mut rig, 0, 0x1F);
    rig.tick();
    assert_eq!(rig.sw() & LIMIT, 0);
    // Other refusals are warnings (bit 7).
    rig.drive.on_reply(
        &Command::from(MoveAbsolute {
            axis: 0,
            position: 1.0,
            velocity: None,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: BufferMode::Buffered,
        }),
        &Err(EngineError::QueueFull { axis: 0, depth: 64 }),
    );
    rig.tick();
    assert_ne!(rig.sw() & sw::WARNING, 0);
    assert_eq!(rig.sw() & LIMIT, 0);
}

#[test]
fn pp_halt_pauses_and_resumes() {
    let mut rig = pp();
    set_point(&mut rig, 5000, 0x1F);
    rig.cw(0x0F);
    rig.ticks(3);
    rig.cw(0x10F);
    assert_eq!(
        rig.sent(|c| matches!(c, Command::Axis(AxisCommand::Halt(Halt { .. })))),
        [Command::Axis(AxisCommand::Halt(Halt {
            axis: 0,
            deceleration: Some(100.0)
        }))]
    );
    rig.tick();
    // Halted and at rest: target reached means "velocity 0" while halt is set.
    assert_ne!(rig.sw() & TR, 0);
    let held = rig.int(obj::POSITION_ACTUAL);
    // No set-point is taken while halted.
    set_point(&mut rig, 100, 0x11F);
    assert!(rig.sent(moves).is_empty());
    assert_eq!(rig.int(obj::POSITION_ACTUAL), held);
    rig.cw(0x0F);
    assert_eq!(
        rig.sent(|c| matches!(c, Command::Axis(AxisCommand::Resume(Resume { .. }))))
            .len(),
        1
    );
    rig.tick();
    assert_eq!(rig.sw() & TR, 0);
    assert!(rig.until(100, |r| r.sw() & TR != 0));
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 5000);
    // At rest, halt pauses nothing: no Halt, no Resume, and no set-point starts.
    rig.tick();
    rig.cw(0x10F);
    assert!(rig.last.is_empty());
    assert_ne!(rig.sw() & TR, 0);
    rig.cw(0x0F);
    assert!(rig.last.is_empty());
    // Halt option 2: the quick stop deceleration.
    rig.set(obj::HALT_OPTION, 0, Value::I16(2));
    set_point(&mut rig, 0, 0x1F);
    rig.cw(0x10F);
    assert_eq!(
        rig.sent(|c| matches!(c, Command::Axis(AxisCommand::Halt(Halt { .. })))),
        [Command::Axis(AxisCommand::Halt(Halt {
            axis: 0,
            deceleration: Some(1000.0)
        }))]
    );
}

#[test]
fn pv_commands_target_velocity_and_reports_speed_bits() {
    let mut rig = Rig::new();
    rig.mode(OperationMode::ProfileVelocity);
    rig.set(obj::TARGET_VELOCITY, 0, Value::I32(5000));
    rig.operation_enabled();
    assert_eq!(
        rig.sent(moves),
        [Command::from(MoveVelocity {
            axis: 0,
            velocity: 5.0,
            acceleration: Some(100.0),
            deceleration: Some(100.0),
            jerk: Some(0.0),
            buffer_mode: BufferMode::Aborting,
        })]
    );
    rig.tick();
    assert!(
        rig.sent(moves).is_empty(),
        "unchanged target, no new command"
    );
    assert_eq!(rig.int(obj::VELOCITY_ACTUAL), 5000);
    assert_eq!(rig.sw() & (TR | B12), TR, "reached, speed ≠ 0");
    // Profile type 3 (jerk-limited) leaves the jerk to the axis; a change re-sends.
    rig.set(obj::MOTION_PROFILE_TYPE, 0, Value::I16(3));
    rig.tick();
    assert!(matches!(
        rig.sent(moves)[..],
        [Command::Axis(AxisCommand::MoveVelocity(MoveVelocity {
            jerk: None,
            ..
        }))]
    ));
    // Zero: speed = 0 (bit 12).
    rig.set(obj::TARGET_VELOCITY, 0, Value::I32(0));
    rig.ticks(2);
    assert_eq!(rig.sw() & (TR | B12), TR | B12);
    // Limited by 0x607F / 0x6080: bit 11.
    rig.set(obj::MAX_MOTOR_SPEED, 0, Value::U32(3000));
    rig.set(obj::TARGET_VELOCITY, 0, Value::I32(-5000));
    rig.tick();
    assert!(matches!(
        rig.sent(moves)[..],
        [Command::Axis(AxisCommand::MoveVelocity(MoveVelocity { velocity, .. }))] if approx(velocity, -3.0)
    ));
    assert_ne!(rig.sw() & LIMIT, 0);
    // Not reached while the actual velocity is off by more than 0x606D.
    rig.axis.velocity = Some(-1.0);
    rig.ticks(2);
    assert_eq!(rig.sw() & TR, 0);
    // Halt stops it; at rest target reached is set.
    rig.cw(0x10F);
    assert_eq!(
        rig.sent(|c| matches!(c, Command::Axis(AxisCommand::Halt(Halt { .. }))))
            .len(),
        1
    );
    rig.tick();
    assert_ne!(rig.sw() & TR, 0);
    rig.cw(0x0F);
    assert_eq!(
        rig.sent(|c| matches!(c, Command::Axis(AxisCommand::Resume(Resume { .. }))))
            .len(),
        1
    );
}

/// A rig in Operation enabled, mode HM, with homing parameters set.
fn hm(method: i8) -> Rig {
    let mut rig = Rig::new();
    rig.mode(OperationMode::Homing);
    rig.set(obj::HOMING_METHOD, 0, Value::I8(method));
    rig.set(obj::HOME_OFFSET, 0, Value::I32(250));
    rig.set(obj::HOMING_SPEEDS, 1, Value::U32(20_000));
    rig.set(obj::HOMING_SPEEDS, 2, Value::U32(2_000));
    rig.set(obj::HOMING_ACCELERATION, 0, Value::U32(300_000));
    rig.operation_enabled();
    rig
}

fn homing_bits(rig: &Rig) -> u16 {
    rig.sw() & (B13 | B12 | TR)
}

#[test]
fn hm_start_attained_and_method_37_semantics() {
    let mut rig = hm(1);
    assert_eq!(homing_bits(&rig), TR, "not started: 0 0 1");
    rig.axis.status.cmd_pos = 3.0;
    rig.cw(0x1F);
    assert_eq!(
        rig.sent(|c| matches!(c, Command::Axis(AxisCommand::Home(Home { .. })))),
        [Command::Axis(AxisCommand::Home(Home {
            axis: 0,
            method: Some(1),
            switch_velocity: Some(20.0),
            zero_velocity: Some(2.0),
            acceleration: Some(300.0),
            offset: Some(0.25),
            timeout: None,
            quirks: HomingQuirks::default(),
            buffer_mode: BufferMode::Aborting,
        }))]
    );
    assert_eq!(homing_bits(&rig), 0, "in progress: 0 0 0");
    // Homing parameters cannot change while homing runs.
    let error = rig
        .drive
        .write(obj::HOMING_METHOD, 0, Value::I8(2))
        .unwrap_err();
    assert!(matches!(error, OdError::DeviceState { .. }));
    assert_eq!(error.sdo_abort_code(), 0x0800_0022);
    rig.tick();
    assert_eq!(homing_bits(&rig), 0);
    assert!(rig.until(20, |r| r.sw() & B12 != 0));
    rig.tick();
    assert_eq!(homing_bits(&rig), B12 | TR, "completed: 0 1 1");
    assert_ne!(rig.sw() & sw::HOMED, 0);
    // HIMC §20 method 37 relations hold after any homing here: 6064 = 6062 = 607C,
    // 6063 = 60FC = 0.
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 250);
    assert_eq!(rig.int(obj::POSITION_DEMAND), 250);
    assert_eq!(rig.int(obj::POSITION_ACTUAL_INTERNAL), 0);
    assert_eq!(rig.int(obj::POSITION_DEMAND_INTERNAL), 0);
    // Attained is remembered across modes (python-canopen `is_homed`).
    rig.mode(OperationMode::ProfilePosition);
    rig.tick();
    rig.mode(OperationMode::Homing);
    rig.tick();
    assert_eq!(homing_bits(&rig), B12 | TR);
    // Method 37 in Operation enabled goes to the axis as homing method 37.
    let mut rig = hm(37);
    rig.set(obj::HOME_OFFSET, 0, Value::I32(-400));
    rig.cw(0x1F);
    assert!(matches!(
        rig.sent(|c| matches!(c, Command::Axis(AxisCommand::Home(Home { .. }))))[..],
        [Command::Axis(AxisCommand::Home(Home { method: Some(37), offset: Some(o), .. }))] if approx(o, -0.4)
    ));
    rig.ticks(2);
    assert_eq!(homing_bits(&rig), B12 | TR);
    assert_eq!(rig.int(obj::POSITION_ACTUAL), -400);
    assert_eq!(rig.int(obj::POSITION_ACTUAL_INTERNAL), 0);
}

#[test]
fn hm_method_37_runs_without_operation_enabled() {
    let mut rig = Rig::new();
    rig.mode(OperationMode::Homing);
    rig.set(obj::HOMING_METHOD, 0, Value::I8(37));
    rig.set(obj::HOME_OFFSET, 0, Value::I32(1234));
    rig.cw(cw::SHUTDOWN);
    rig.cw(cw::SWITCH_ON_COMMAND);
    rig.axis.status.cmd_pos = 0.5;
    rig.axis.status.act_pos = 0.5;
    rig.cw(cw::SWITCH_ON_COMMAND | cw::HOMING_START);
    assert_eq!(rig.state(), State::SwitchedOn);
    assert_eq!(
        rig.last,
        [Command::from(SetPosition {
            axis: 0,
            position: 1.234,
            frame: PositionFrame::Both
        })]
    );
    rig.tick();
    assert_eq!(homing_bits(&rig), B12 | TR);
    assert!(!rig.axis.enabled(), "no power needed");
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 1234);
    assert_eq!(rig.int(obj::POSITION_DEMAND), 1234);
    assert_eq!(rig.int(obj::POSITION_ACTUAL_INTERNAL), 0);
    assert_eq!(rig.int(obj::POSITION_DEMAND_INTERNAL), 0);
    // Other methods need Operation enabled: the edge is ignored.
    let mut rig = Rig::new();
    rig.mode(OperationMode::Homing);
    rig.set(obj::HOMING_METHOD, 0, Value::I8(33));
    rig.cw(cw::SHUTDOWN);
    rig.cw(cw::SHUTDOWN | cw::HOMING_START);
    assert!(rig.last.is_empty());
    assert_eq!(homing_bits(&rig), TR);
}

#[test]
fn hm_error_and_interruption() {
    let mut rig = hm(17);
    rig.axis.fail_homing = true;
    rig.cw(0x1F);
    assert!(rig.until(20, |r| r.sw() & B13 != 0));
    assert_eq!(homing_bits(&rig), B13 | TR, "error, velocity 0: 1 0 1");
    // The axis's latch is cleared so the master can move it again; no drive fault.
    assert_eq!(
        rig.sent(|c| matches!(c, Command::Axis(AxisCommand::Reset(Reset { .. }))))
            .len(),
        1
    );
    rig.tick();
    assert!(!rig.axis.status.flags.contains(AxisFlags::HOMING_FAILED));
    assert_eq!(rig.state(), State::OperationEnabled);
    // A new start clears the error.
    rig.axis.fail_homing = false;
    rig.cw(0x0F);
    rig.cw(0x1F);
    assert_eq!(homing_bits(&rig), 0);
    // Bit 4 falling interrupts, stopping with the homing acceleration.
    rig.tick();
    rig.cw(0x0F);
    assert_eq!(
        rig.sent(is_stop),
        [Command::from(Stop {
            axis: 0,
            mode: StopMode::Smooth,
            deceleration: Some(300.0)
        })]
    );
    assert_eq!(homing_bits(&rig), TR, "interrupted: 0 0 1");
    // So does halt.
    rig.cw(0x1F);
    rig.cw(0x11F);
    assert_eq!(rig.sent(is_stop).len(), 1);
    assert_eq!(homing_bits(&rig), TR);
    // A homing the axis refuses is a homing error.
    let mut rig = hm(17);
    rig.axis.apply(&Command::from(Disable { axis: 0 })).unwrap();
    rig.cw(0x1F);
    assert!(matches!(
        rig.drive.last_refusal(),
        Some(EngineError::AxisDisabled { .. })
    ));
    rig.tick();
    assert_ne!(rig.sw() & B13, 0);
}

#[test]
fn hm_rejects_unsupported_methods() {
    let mut rig = Rig::new();
    for method in [0i8, 36, 38, -1, -4, 127] {
        let error = rig
            .drive
            .write(obj::HOMING_METHOD, 0, Value::I8(method))
            .unwrap_err();
        assert!(matches!(error, OdError::InvalidValue { .. }), "{method}");
    }
    for method in [1i8, 17, 33, 34, 35, 37] {
        rig.set(obj::HOMING_METHOD, 0, Value::I8(method));
    }
}

#[test]
fn csp_csv_cst_stream_a_setpoint_every_tick() {
    // CSP: 0x607A increments → user units.
    let mut rig = Rig::new();
    rig.mode(OperationMode::CyclicPosition);
    rig.set(obj::TARGET_POSITION, 0, Value::I32(2500));
    rig.operation_enabled();
    let setpoints = |r: &Rig| {
        r.sent(|c| {
            matches!(
                c,
                Command::Axis(AxisCommand::Setpoint(StreamSetpoint { .. }))
            )
        })
    };
    assert_eq!(
        setpoints(&rig),
        [Command::from(StreamSetpoint {
            axis: 0,
            setpoint: Some(Setpoint::Position { position: 2.5 })
        })]
    );
    for target in [2600, 2700, 2700, 2650] {
        rig.set(obj::TARGET_POSITION, 0, Value::I32(target));
        rig.tick();
        assert_eq!(
            setpoints(&rig),
            [Command::from(StreamSetpoint {
                axis: 0,
                setpoint: Some(Setpoint::Position {
                    position: f64::from(target) / IPU
                })
            })]
        );
        assert_ne!(rig.sw() & B12, 0, "drive follows the command value");
    }
    rig.tick();
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 2650);
    assert_ne!(rig.sw() & TR, 0);
    // Bumpless to CSV: the stream goes on with velocities.
    rig.set(obj::TARGET_VELOCITY, 0, Value::I32(-3000));
    rig.mode(OperationMode::CyclicVelocity);
    rig.tick();
    assert_eq!(
        rig.last,
        [Command::from(StreamSetpoint {
            axis: 0,
            setpoint: Some(Setpoint::Velocity { velocity: -3.0 })
        })]
    );
    rig.tick();
    assert_eq!(rig.int(obj::VELOCITY_ACTUAL), -3000);
    assert_eq!(rig.sw() & (TR | B12), TR | B12);
    // CST: ‰ of rated torque → fraction; limited by 0x6072.
    rig.set(obj::TARGET_TORQUE, 0, Value::I16(250));
    rig.mode(OperationMode::CyclicTorque);
    rig.tick();
    assert_eq!(
        setpoints(&rig),
        [Command::from(StreamSetpoint {
            axis: 0,
            setpoint: Some(Setpoint::Torque { torque: 0.25 })
        })]
    );
    assert_eq!(rig.int(obj::TORQUE_ACTUAL), 250);
    rig.set(obj::MAX_TORQUE, 0, Value::U16(200));
    rig.tick();
    assert_eq!(
        setpoints(&rig),
        [Command::from(StreamSetpoint {
            axis: 0,
            setpoint: Some(Setpoint::Torque { torque: 0.2 })
        })]
    );
    assert_ne!(rig.sw() & LIMIT, 0);
    // Leaving the cyclic modes ends the stream.
    rig.mode(OperationMode::ProfilePosition);
    rig.tick();
    assert!(setpoints(&rig).contains(&Command::from(StreamSetpoint {
        axis: 0,
        setpoint: None
    })));
    assert_eq!(rig.sw() & B12, 0);
    assert_eq!(rig.int(obj::TORQUE_ACTUAL), 0);
    rig.tick();
    assert!(setpoints(&rig).is_empty());
}

#[test]
fn cyclic_halt_and_disable_end_the_stream() {
    let mut rig = Rig::new();
    rig.mode(OperationMode::CyclicPosition);
    rig.operation_enabled();
    rig.cw(0x10F);
    assert_eq!(
        rig.last,
        [
            Command::from(StreamSetpoint {
                axis: 0,
                setpoint: None
            }),
            Command::from(Stop {
                axis: 0,
                mode: StopMode::Smooth,
                deceleration: Some(100.0)
            }),
        ]
    );
    rig.tick();
    assert!(rig.last.is_empty(), "no setpoints while halted");
    assert_eq!(rig.sw() & B12, 0, "target ignored");
    rig.cw(0x0F);
    assert_eq!(rig.last.len(), 1);
    assert_ne!(rig.sw() & B12, 0);
    // Disable voltage ends the stream before removing power.
    rig.cw(cw::DISABLE_VOLTAGE);
    assert_eq!(
        rig.last,
        [
            Command::from(StreamSetpoint {
                axis: 0,
                setpoint: None
            }),
            Command::from(Disable { axis: 0 })
        ]
    );
    // A stream the axis refuses is not followed.
    let mut rig = Rig::new();
    rig.mode(OperationMode::CyclicVelocity);
    rig.operation_enabled();
    rig.drive.on_reply(
        &Command::from(StreamSetpoint {
            axis: 0,
            setpoint: Some(Setpoint::Velocity { velocity: 0.0 }),
        }),
        &Err(EngineError::AxisDisabled { axis: 0 }),
    );
    rig.tick();
    assert_eq!(rig.sw() & B12, 0);
    rig.tick();
    assert_ne!(rig.sw() & B12, 0);
}

#[test]
fn leaving_a_profile_mode_stops_its_motion() {
    let mut rig = Rig::new();
    rig.mode(OperationMode::ProfileVelocity);
    rig.set(obj::TARGET_VELOCITY, 0, Value::I32(2000));
    rig.operation_enabled();
    rig.ticks(2);
    rig.mode(OperationMode::ProfilePosition);
    rig.tick();
    assert_eq!(
        rig.sent(is_stop),
        [Command::from(Stop {
            axis: 0,
            mode: StopMode::Smooth,
            deceleration: Some(100.0)
        })]
    );
    rig.tick();
    assert_eq!(rig.sw() & sw::MOVING, 0);
}

#[test]
fn actual_values_are_published_in_increments() {
    let mut rig = Rig::new();
    rig.axis.status.cmd_pos = 1.5;
    rig.axis.status.cmd_vel = -2.25;
    rig.axis.status.act_pos = 1.4996;
    rig.axis.status.act_vel = -2.2;
    rig.axis.status.following_error = 0.0004;
    let mut out = Vec::new();
    rig.drive.step(&rig.axis.status, 0.0, &mut out);
    assert_eq!(rig.int(obj::POSITION_DEMAND), 1500);
    assert_eq!(rig.int(obj::VELOCITY_DEMAND), -2250);
    assert_eq!(rig.int(obj::POSITION_ACTUAL), 1500); // rounded
    assert_eq!(rig.int(obj::VELOCITY_ACTUAL), -2200);
    assert_eq!(rig.int(obj::FOLLOWING_ERROR_ACTUAL), 0);
    rig.axis.status.act_pos = 1.0e9; // beyond INTEGER32 increments: saturates
    rig.drive.step(&rig.axis.status, 0.0, &mut out);
    assert_eq!(rig.int(obj::POSITION_ACTUAL), i64::from(i32::MAX));
}

#[test]
fn following_error_bit_needs_window_and_timeout() {
    let mut rig = pp();
    rig.set(obj::FOLLOWING_ERROR_WINDOW, 0, Value::U32(50));
    rig.set(obj::FOLLOWING_ERROR_TIMEOUT, 0, Value::U16(3));
    rig.axis.status.following_error = 0.2; // 200 increments
    rig.tick();
    assert_eq!(rig.int(obj::FOLLOWING_ERROR_ACTUAL), 200);
    assert_eq!(rig.sw() & B13, 0);
    rig.ticks(3);
    assert_ne!(rig.sw() & B13, 0);
    rig.axis.status.following_error = 0.0;
    rig.tick();
    rig.tick();
    assert_eq!(rig.sw() & B13, 0);
}

#[test]
fn digital_inputs_and_touch_probes() {
    let mut rig = Rig::new();
    for (flag, bit) in [
        (AxisFlags::HW_LIMIT_NEG, 1),
        (AxisFlags::HW_LIMIT_POS, 2),
        (AxisFlags::HOME_SWITCH, 4),
    ] {
        rig.axis.status.flags.insert(flag);
        rig.tick();
        assert_eq!(rig.int(obj::DIGITAL_INPUTS), bit);
        rig.axis.status.flags.remove(flag);
    }
    rig.tick();
    // Probe 1: home switch, first event, both edges.
    rig.set(obj::TOUCH_PROBE_FUNCTION, 0, Value::U16(0x0031));
    rig.tick();
    assert_eq!(rig.int(obj::TOUCH_PROBE_STATUS), 0x0001);
    let at = |rig: &mut Rig, position: f64, home: bool| {
        rig.axis.status.cmd_pos = position;
        rig.axis.status.act_pos = position;
        rig.axis.status.flags.set(AxisFlags::HOME_SWITCH, home);
        rig.tick();
    };
    at(&mut rig, 0.75, true);
    assert_eq!(rig.int(obj::TOUCH_PROBE_1_POSITIVE), 750);
    assert_eq!(rig.int(obj::TOUCH_PROBE_STATUS), 0x0003);
    at(&mut rig, 0.80, false);
    assert_eq!(rig.int(obj::TOUCH_PROBE_1_NEGATIVE), 800);
    assert_eq!(rig.int(obj::TOUCH_PROBE_STATUS), 0x0007);
    // First event only: a second rising edge does not latch …
    at(&mut rig, 0.9, true);
    assert_eq!(rig.int(obj::TOUCH_PROBE_1_POSITIVE), 750);
    // … until the positive edge is re-armed (bit 4 0 → 1).
    rig.set(obj::TOUCH_PROBE_FUNCTION, 0, Value::U16(0x0021));
    at(&mut rig, 0.9, false);
    rig.set(obj::TOUCH_PROBE_FUNCTION, 0, Value::U16(0x0031));
    at(&mut rig, 0.95, true);
    assert_eq!(rig.int(obj::TOUCH_PROBE_1_POSITIVE), 950);
    // Continuous mode latches every edge.
    rig.set(obj::TOUCH_PROBE_FUNCTION, 0, Value::U16(0x0033));
    at(&mut rig, 1.0, false);
    at(&mut rig, 1.1, true);
    assert_eq!(rig.int(obj::TOUCH_PROBE_1_POSITIVE), 1100);
    // Probe 2 on the index pulse (source 01).
    rig.set(obj::TOUCH_PROBE_FUNCTION, 0, Value::U16(0x1500));
    rig.tick();
    assert_eq!(rig.int(obj::TOUCH_PROBE_STATUS), 0x0100);
    rig.axis.status.cmd_pos = -0.25;
    rig.axis.status.act_pos = -0.25;
    rig.axis.status.flags.insert(AxisFlags::INDEX);
    rig.tick();
    assert_eq!(rig.int(obj::TOUCH_PROBE_2_POSITIVE), -250);
    assert_eq!(rig.int(obj::TOUCH_PROBE_STATUS), 0x0300);
    // Disabling clears the status.
    rig.set(obj::TOUCH_PROBE_FUNCTION, 0, Value::U16(0));
    rig.tick();
    assert_eq!(rig.int(obj::TOUCH_PROBE_STATUS), 0);
}

#[test]
fn csp_targets_are_interpolated_over_the_interpolation_period() {
    // A master whose SYNC is 4 ticks: 0x60C2 = 4 × 10⁻³ s. A new target is reached in four
    // equal steps from where the set-point stood (CiA 402 §6.3.4).
    let mut rig = Rig::new();
    rig.set(obj::INTERPOLATION_TIME_PERIOD, 1, Value::U8(4));
    rig.mode(OperationMode::CyclicPosition);
    rig.set(obj::TARGET_POSITION, 0, Value::I32(0));
    rig.operation_enabled();
    let position = |r: &Rig| {
        r.last
            .iter()
            .find_map(|c| match c {
                Command::Axis(AxisCommand::Setpoint(StreamSetpoint {
                    setpoint: Some(Setpoint::Position { position }),
                    ..
                })) => Some(*position),
                _ => None,
            })
            .expect("a CSP set-point")
    };
    rig.set(obj::TARGET_POSITION, 0, Value::I32(4000));
    let mut seen = Vec::new();
    for _ in 0..6 {
        rig.tick();
        seen.push((position(&rig) * IPU).round() as i64);
    }
    assert_eq!(seen, [1000, 2000, 3000, 4000, 4000, 4000]);
    // A target changed mid-segment starts the next segment where the set-point is.
    rig.set(obj::TARGET_POSITION, 0, Value::I32(0));
    rig.tick();
    rig.set(obj::TARGET_POSITION, 0, Value::I32(8000));
    rig.tick();
    let p = (position(&rig) * IPU).round() as i64;
    assert_eq!(p, 3000 + (8000 - 3000) / 4, "from 3000 toward 8000");
    // The default period (1 ms, one tick) passes targets straight through.
    rig.set(obj::INTERPOLATION_TIME_PERIOD, 1, Value::U8(1));
    rig.set(obj::TARGET_POSITION, 0, Value::I32(500));
    rig.tick();
    assert_eq!((position(&rig) * IPU).round() as i64, 500);
}
