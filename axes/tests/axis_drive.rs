//! CiA 402 drives on the engine (ARCHITECTURE §3.8): an external master walking the state
//! machine and moving the axis in PP and CSP through the object dictionary; the engine mastering
//! a drive's power itself; faults crossing from the axis to the drive.

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use axes::cia402::{cw, obj, sw, DriveConfig, DriveMaster, State};
use axes::command::{
    Command, Disable, Enable, EngineError, InjectFollowingError, ReadObject, Reply, Reset,
    WriteObject,
};
use axes::od::{OdError, Value};
use axes::{AxisFlags, AxisState, Engine, EngineConfig};
use common::*;

fn machine(master: DriveMaster) -> Engine {
    Engine::new(&EngineConfig {
        axes: vec![stepper_mm()],
        drives: vec![DriveConfig {
            axis: 0,
            master,
            increments_per_unit: 1000.0,
            ..DriveConfig::default()
        }],
        ..EngineConfig::default()
    })
    .unwrap()
}

fn write(e: &mut Engine, index: u16, subindex: u8, value: Value) {
    ok(
        e,
        Command::from(WriteObject {
            slave: 0,
            index,
            subindex,
            value,
        }),
    );
}

fn read(e: &mut Engine, index: u16, subindex: u8) -> Value {
    match ok(
        e,
        Command::from(ReadObject {
            slave: 0,
            index,
            subindex,
        }),
    ) {
        Reply::Object { value } => value,
        other => panic!("{other:?}"),
    }
}

fn statusword(e: &mut Engine) -> u16 {
    match read(e, obj::STATUSWORD, 0) {
        Value::U16(v) => v,
        other => panic!("{other:?}"),
    }
}

fn state(e: &mut Engine) -> State {
    let s = statusword(e);
    State::from_statusword(s).unwrap_or_else(|| panic!("statusword {s:#06x}"))
}

/// Write a controlword and let the drive see it.
fn control(e: &mut Engine, word: u16) {
    write(e, obj::CONTROLWORD, 0, Value::U16(word));
    run(e, 0.002);
}

#[test]
fn an_external_master_enables_the_drive_and_moves_in_profile_position() {
    let mut e = machine(DriveMaster::External);
    run(&mut e, 0.002);
    assert_eq!(state(&mut e), State::SwitchOnDisabled);
    control(&mut e, cw::SHUTDOWN);
    assert_eq!(state(&mut e), State::ReadyToSwitchOn);
    control(&mut e, cw::SWITCH_ON_COMMAND);
    assert_eq!(state(&mut e), State::SwitchedOn);
    control(&mut e, cw::ENABLE_OPERATION_COMMAND);
    assert_eq!(state(&mut e), State::OperationEnabled);
    assert!(
        status(&e).flags.contains(AxisFlags::ENABLED),
        "the drive powered its axis"
    );

    write(&mut e, obj::MODES_OF_OPERATION, 0, Value::I8(1));
    write(&mut e, obj::PROFILE_VELOCITY, 0, Value::U32(50_000)); // 50 mm/s
    write(&mut e, obj::PROFILE_ACCELERATION, 0, Value::U32(500_000));
    write(&mut e, obj::PROFILE_DECELERATION, 0, Value::U32(500_000));
    write(&mut e, obj::TARGET_POSITION, 0, Value::I32(20_000)); // 20 mm
    control(&mut e, cw::ENABLE_OPERATION_COMMAND | cw::NEW_SET_POINT);
    assert_eq!(
        read(&mut e, obj::MODES_OF_OPERATION_DISPLAY, 0),
        Value::I8(1)
    );
    assert!(
        statusword(&mut e) & sw::OMS_12 != 0,
        "set-point acknowledged"
    );
    control(&mut e, cw::ENABLE_OPERATION_COMMAND);
    assert!(run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill).is_some());
    run(&mut e, 0.01);
    assert_eq!(status(&e).act_pos, 20.0);
    assert_eq!(read(&mut e, obj::POSITION_ACTUAL, 0), Value::I32(20_000));
    assert!(statusword(&mut e) & sw::TARGET_REACHED != 0);
    // Masters cannot write what the drive computes.
    match refused(
        &mut e,
        Command::from(WriteObject {
            slave: 0,
            index: obj::STATUSWORD,
            subindex: 0,
            value: Value::U16(0),
        }),
    ) {
        EngineError::Object {
            slave: 0,
            error: OdError::ReadOnly { .. },
        } => {}
        other => panic!("{other}"),
    }
    assert!(matches!(
        refused(
            &mut e,
            Command::from(ReadObject {
                slave: 3,
                index: 0x6041,
                subindex: 0
            })
        ),
        EngineError::InvalidSlave { slave: 3, count: 1 }
    ));
    let snap = e.snapshot();
    assert_eq!(snap.drives.len(), 1);
    assert_eq!(snap.drives[0].mode, 1);
}

#[test]
fn cyclic_synchronous_position_follows_the_master_every_tick() {
    let mut e = machine(DriveMaster::External);
    for w in [
        cw::SHUTDOWN,
        cw::SWITCH_ON_COMMAND,
        cw::ENABLE_OPERATION_COMMAND,
    ] {
        control(&mut e, w);
    }
    write(&mut e, obj::MODES_OF_OPERATION, 0, Value::I8(8));
    run(&mut e, 0.002);
    for k in 1..=200 {
        write(&mut e, obj::TARGET_POSITION, 0, Value::I32(k * 10));
        e.step();
    }
    run(&mut e, 0.003);
    assert_eq!(status(&e).state, AxisState::SynchronizedMotion);
    assert!(
        (status(&e).cmd_pos - 2.0).abs() < 1e-9,
        "{}",
        status(&e).cmd_pos
    );
}

#[test]
fn the_engine_masters_power_through_the_drive_state_machine() {
    let mut e = machine(DriveMaster::Engine);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    assert!(run_until(&mut e, 0.1, |s| s.flags.contains(AxisFlags::ENABLED)).is_some());
    assert_eq!(state(&mut e), State::OperationEnabled);
    // Motion comes from the engine's own planner; the drive reports it.
    ok(&mut e, move_abs(5.0));
    assert!(run_until(&mut e, 5.0, |s| s.state == AxisState::Standstill).is_some());
    run(&mut e, 0.002);
    assert_eq!(read(&mut e, obj::POSITION_ACTUAL, 0), Value::I32(5_000));
    // A following-error fault: the drive goes to Fault with 0x8611; reset walks both back.
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: Some(3.0),
        }),
    );
    run(&mut e, 0.05);
    assert_eq!(state(&mut e), State::Fault);
    assert_eq!(read(&mut e, obj::ERROR_CODE, 0), Value::U16(0x8611));
    assert_eq!(status(&e).state, AxisState::ErrorStop);
    ok(
        &mut e,
        Command::from(InjectFollowingError {
            axis: 0,
            amount: None,
        }),
    );
    run(&mut e, 0.002);
    ok(&mut e, Command::from(Reset { axis: 0 }));
    assert!(run_until(&mut e, 0.1, |_| true).is_some());
    run(&mut e, 0.01);
    assert_eq!(state(&mut e), State::SwitchOnDisabled);
    ok(&mut e, Command::from(Enable { axis: 0 }));
    assert!(run_until(&mut e, 0.1, |s| s.flags.contains(AxisFlags::ENABLED)).is_some());
    ok(&mut e, Command::from(Disable { axis: 0 }));
    assert!(run_until(&mut e, 0.1, |s| !s.flags.contains(AxisFlags::ENABLED)).is_some());
    run(&mut e, 0.005);
    assert_eq!(state(&mut e), State::SwitchOnDisabled);
}

#[test]
fn drive_config_errors_name_the_key() {
    let err = Engine::new(&EngineConfig {
        axes: vec![stepper_mm()],
        drives: vec![DriveConfig {
            axis: 4,
            ..DriveConfig::default()
        }],
        ..EngineConfig::default()
    })
    .unwrap_err();
    assert_eq!(err.key, "drives[0].axis");
    let err = Engine::new(&EngineConfig {
        axes: vec![stepper_mm()],
        drives: vec![DriveConfig::default(), DriveConfig::default()],
        ..EngineConfig::default()
    })
    .unwrap_err();
    assert!(err.reason.contains("already has a drive"), "{}", err.reason);
}
