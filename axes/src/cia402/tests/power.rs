//! The power state machine: transitions 0–16, illegal controlwords, quick stop and fault
//! reactions, fault reset, and the master-side helper.

use super::*;
use crate::command::{AxisCommand, Disable, Reset, Stop};

#[test]
fn statusword_bits_for_every_state() {
    // (state, bits 0–6 and 9 as the drive reports them, python-canopen mask/value)
    let table = [
        (State::NotReadyToSwitchOn, 0x0200, 0x4F, 0x00),
        (State::SwitchOnDisabled, 0x0250, 0x4F, 0x40),
        (State::ReadyToSwitchOn, 0x0231, 0x6F, 0x21),
        (State::SwitchedOn, 0x0233, 0x6F, 0x23),
        (State::OperationEnabled, 0x0237, 0x6F, 0x27),
        (State::QuickStopActive, 0x0217, 0x6F, 0x07),
        (State::FaultReactionActive, 0x021F, 0x4F, 0x0F),
        (State::Fault, 0x0218, 0x4F, 0x08),
    ];
    for (state, word, mask, value) in table {
        let bits = state.statusword_bits() | sw::REMOTE;
        assert_eq!(bits, word, "{state}");
        assert_eq!(bits & mask, value, "{state}");
        assert_eq!(State::from_statusword(bits), Some(state), "{state}");
        // Bits outside the state bits do not change the decoding.
        assert_eq!(
            State::from_statusword(bits | 0xFC80),
            Some(state),
            "{state}"
        );
    }
    assert_eq!(State::from_statusword(0x0001), None);
    // And the drive reports them in each state it can be driven to (bits 10–15 masked: they
    // belong to the mode and the axis).
    for (state, word, _, _) in table.into_iter().skip(1) {
        let mut rig = Rig::new();
        rig.goto(state);
        assert_eq!(rig.sw() & 0x03FF, word, "{state}");
    }
}

#[test]
fn transitions_0_and_1_happen_by_themselves() {
    let config = DriveConfig::default();
    let mut drive = Cia402Drive::new(config).unwrap();
    assert_eq!(drive.state(), State::NotReadyToSwitchOn);
    assert_eq!(drive.last_transitions(), [0]);
    assert_eq!(drive.statusword(), 0);
    let mut out = Vec::new();
    drive.step(&AxisStatus::default(), 0.0, &mut out);
    assert_eq!(drive.state(), State::SwitchOnDisabled);
    assert_eq!(drive.last_transitions(), [1]);
    assert!(out.is_empty());
    // An axis found powered is switched off: the drive owns its power.
    let mut drive = Cia402Drive::new(DriveConfig::default()).unwrap();
    let powered = AxisStatus {
        flags: AxisFlags::ENABLED,
        ..AxisStatus::default()
    };
    drive.step(&powered, 0.0, &mut out);
    assert_eq!(out, [Command::from(Disable { axis: 0 })]);
}

/// One transition: from a state, a controlword → a state, the transitions made, and whether the
/// axis was powered on / off in that tick.
struct Case {
    from: State,
    controlword: u16,
    to: State,
    transitions: &'static [u8],
    enable: bool,
    disable: bool,
}

#[test]
fn every_controlword_transition_2_to_16() {
    use State::*;
    let c = |from, controlword, to, transitions, enable, disable| Case {
        from,
        controlword,
        to,
        transitions,
        enable,
        disable,
    };
    let cases = [
        c(SwitchOnDisabled, 0x06, ReadyToSwitchOn, &[2], false, false),
        c(ReadyToSwitchOn, 0x07, SwitchedOn, &[3], false, false),
        c(
            ReadyToSwitchOn,
            0x0F,
            OperationEnabled,
            &[3, 4],
            true,
            false,
        ),
        c(SwitchedOn, 0x0F, OperationEnabled, &[4], true, false),
        // 0x605C default 1: ramp first, power off when at rest (below).
        c(OperationEnabled, 0x07, SwitchedOn, &[5], false, false),
        c(SwitchedOn, 0x06, ReadyToSwitchOn, &[6], false, false),
        c(ReadyToSwitchOn, 0x00, SwitchOnDisabled, &[7], false, false),
        c(ReadyToSwitchOn, 0x02, SwitchOnDisabled, &[7], false, false),
        // 0x605B default 0: power off at once.
        c(OperationEnabled, 0x06, ReadyToSwitchOn, &[8], false, true),
        c(OperationEnabled, 0x00, SwitchOnDisabled, &[9], false, true),
        c(OperationEnabled, 0x04, SwitchOnDisabled, &[9], false, true),
        c(SwitchedOn, 0x00, SwitchOnDisabled, &[10], false, false),
        c(SwitchedOn, 0x02, SwitchOnDisabled, &[10], false, false),
        // 0x605A default 2: quick stop ramp; 12 follows at rest (below).
        c(OperationEnabled, 0x02, QuickStopActive, &[11], false, false),
        // QuickStopActive is reached with option 6 (stays).
        c(QuickStopActive, 0x00, SwitchOnDisabled, &[12], false, true),
        c(QuickStopActive, 0x0F, OperationEnabled, &[16], false, false),
    ];
    for case in cases {
        let mut rig = Rig::new();
        rig.goto(case.from);
        rig.cw(case.controlword);
        let what = format!("{} + {:#06x}", case.from, case.controlword);
        assert_eq!(rig.state(), case.to, "{what}");
        assert_eq!(rig.drive.last_transitions(), case.transitions, "{what}");
        assert_eq!(!rig.sent(is_enable).is_empty(), case.enable, "{what}");
        assert_eq!(!rig.sent(is_disable).is_empty(), case.disable, "{what}");
    }
}

#[test]
fn transitions_12_13_14_15_follow_events() {
    // 12 automatically after a quick stop with option 2.
    let mut rig = Rig::new();
    rig.operation_enabled();
    rig.cw(cw::QUICK_STOP_COMMAND);
    assert_eq!(rig.state(), State::QuickStopActive);
    rig.tick();
    assert_eq!(rig.state(), State::SwitchOnDisabled);
    assert_eq!(rig.drive.last_transitions(), [12]);
    assert_eq!(rig.sent(is_disable).len(), 1);
    // 13, 14, 15.
    let mut rig = Rig::new();
    rig.operation_enabled();
    rig.axis.status.flags.insert(AxisFlags::FE_FAULT);
    rig.tick();
    assert_eq!(rig.state(), State::FaultReactionActive);
    assert_eq!(rig.drive.last_transitions(), [13]);
    rig.tick();
    assert_eq!(rig.state(), State::Fault);
    assert_eq!(rig.drive.last_transitions(), [14]);
    rig.cw(cw::FAULT_RESET_COMMAND);
    assert_eq!(
        rig.sent(|c| matches!(c, Command::Axis(AxisCommand::Reset(Reset { .. }))))
            .len(),
        1
    );
    rig.tick();
    assert_eq!(rig.state(), State::SwitchOnDisabled);
    assert_eq!(rig.drive.last_transitions(), [15]);
    // Transition 5's ramp ends in power off once the axis is at rest.
    let mut rig = Rig::new();
    rig.operation_enabled();
    rig.cw(cw::DISABLE_OPERATION);
    assert_eq!(rig.sent(is_stop).len(), 1);
    rig.tick();
    assert_eq!(rig.sent(is_disable).len(), 1);
    assert!(!rig.axis.enabled());
}

/// The CiA 402 transition table, written independently of the drive: the state a command leads
/// to, or `None` for no transition.
fn reference(state: State, controlword: u16, quick_stop_option: i16) -> Option<State> {
    use State::*;
    let bit = |n: u16| controlword & (1 << n) != 0;
    if bit(7) {
        return None; // only a rising edge in Fault does something
    }
    let disable_voltage = !bit(1);
    let quick_stop = bit(1) && !bit(2);
    let shutdown = bit(1) && bit(2) && !bit(0);
    let switch_on = bit(0) && bit(1) && bit(2) && !bit(3);
    let enable = bit(0) && bit(1) && bit(2) && bit(3);
    match state {
        SwitchOnDisabled if shutdown => Some(ReadyToSwitchOn),
        ReadyToSwitchOn if switch_on => Some(SwitchedOn),
        ReadyToSwitchOn if enable => Some(OperationEnabled),
        ReadyToSwitchOn if disable_voltage || quick_stop => Some(SwitchOnDisabled),
        SwitchedOn if enable => Some(OperationEnabled),
        SwitchedOn if shutdown => Some(ReadyToSwitchOn),
        SwitchedOn if disable_voltage || quick_stop => Some(SwitchOnDisabled),
        OperationEnabled if switch_on => Some(SwitchedOn),
        OperationEnabled if shutdown => Some(ReadyToSwitchOn),
        OperationEnabled if disable_voltage => Some(SwitchOnDisabled),
        OperationEnabled if quick_stop => Some(QuickStopActive),
        QuickStopActive if disable_voltage => Some(SwitchOnDisabled),
        QuickStopActive if enable && quick_stop_option >= 5 => Some(OperationEnabled),
        _ => None,
    }
}

#[test]
fn illegal_controlwords_make_no_transition() {
    let states = [
        State::SwitchOnDisabled,
        State::ReadyToSwitchOn,
        State::SwitchedOn,
        State::OperationEnabled,
        State::QuickStopActive,
    ];
    for state in states {
        // Every pattern of the command bits 0–3 and 7, with and without bits 4–6 and 8.
        for low in 0..16u16 {
            for extra in [0x0000, 0x0080, 0x0170] {
                let controlword = low | extra;
                let mut rig = Rig::new();
                rig.goto(state);
                let before = rig.state();
                rig.cw(controlword);
                let what = format!("{state} + {controlword:#06x}");
                match reference(state, controlword, 6) {
                    Some(to) => assert_eq!(rig.state(), to, "{what}"),
                    None => {
                        assert_eq!(rig.state(), before, "{what}");
                        assert!(rig.drive.last_transitions().is_empty(), "{what}");
                    }
                }
            }
        }
    }
    // Quick stop active with options 1–4 does not take "enable operation" (16), not even while
    // its ramp is still running.
    let mut rig = Rig::new();
    rig.set(obj::QUICK_STOP_OPTION, 0, Value::I16(2));
    rig.operation_enabled();
    rig.cw(cw::QUICK_STOP_COMMAND);
    assert_eq!(rig.state(), State::QuickStopActive);
    rig.set(
        obj::CONTROLWORD,
        0,
        Value::U16(cw::ENABLE_OPERATION_COMMAND),
    );
    let moving = AxisStatus {
        flags: AxisFlags::ENABLED | AxisFlags::MOVING,
        ..rig.axis.status
    };
    let mut out = Vec::new();
    rig.drive.step(&moving, rig.now, &mut out);
    assert_eq!(rig.state(), State::QuickStopActive);
    assert!(rig.drive.last_transitions().is_empty());
    // Fault ignores everything but a rising edge of bit 7.
    let mut rig = Rig::new();
    rig.goto(State::Fault);
    rig.axis.status.flags.remove(AxisFlags::DRIVE_ALARM);
    for controlword in [0x00, 0x06, 0x07, 0x0F, 0x02] {
        rig.cw(controlword);
        assert_eq!(rig.state(), State::Fault);
    }
}

#[test]
fn fault_reset_needs_a_rising_edge_and_a_cleared_cause() {
    let mut rig = Rig::new();
    rig.goto(State::Fault);
    assert_eq!(rig.drive.error_code(), error_code::DRIVE_ALARM);
    // The alarm's cause is still there: the reset fails and the drive stays in Fault.
    rig.axis.alarm_forced = true;
    rig.cw(cw::FAULT_RESET_COMMAND);
    rig.tick();
    assert_eq!(rig.state(), State::Fault);
    assert!(matches!(
        rig.drive.last_refusal(),
        Some(EngineError::CauseStillPresent { .. })
    ));
    // Holding bit 7 is no new edge.
    rig.axis.alarm_forced = false;
    rig.axis.status.flags.remove(AxisFlags::DRIVE_ALARM);
    rig.ticks(3);
    assert_eq!(rig.state(), State::Fault);
    // A new edge resets.
    rig.cw(0x00);
    rig.cw(cw::FAULT_RESET_COMMAND);
    rig.tick();
    assert_eq!(rig.state(), State::SwitchOnDisabled);
    assert_eq!(rig.drive.error_code(), 0);
    assert_eq!(rig.int(obj::ERROR_REGISTER), 0);
}

#[test]
fn quick_stop_option_codes() {
    // (option, expected stop, state after the ramp, powered after the ramp)
    let slow = Some(100_000.0 / IPU);
    let quick = Some(1_000_000.0 / IPU);
    let cases = [
        (1, StopMode::Smooth, slow, State::SwitchOnDisabled, false),
        (2, StopMode::Smooth, quick, State::SwitchOnDisabled, false),
        (3, StopMode::Immediate, None, State::SwitchOnDisabled, false),
        (5, StopMode::Smooth, slow, State::QuickStopActive, true),
        (6, StopMode::Smooth, quick, State::QuickStopActive, true),
        (7, StopMode::Immediate, None, State::QuickStopActive, true),
    ];
    for (option, mode, deceleration, after, powered) in cases {
        let mut rig = Rig::new();
        rig.set(obj::QUICK_STOP_OPTION, 0, Value::I16(option));
        rig.mode(OperationMode::ProfileVelocity);
        rig.set(obj::TARGET_VELOCITY, 0, Value::I32(2000));
        rig.operation_enabled();
        rig.ticks(2);
        assert!(rig.axis.status.flags.contains(AxisFlags::MOVING));
        rig.cw(cw::QUICK_STOP_COMMAND);
        assert_eq!(rig.state(), State::QuickStopActive, "option {option}");
        assert_eq!(
            rig.sent(is_stop),
            [Command::from(Stop {
                axis: 0,
                mode,
                deceleration
            })],
            "option {option}"
        );
        assert!(rig.sent(is_disable).is_empty(), "option {option}");
        rig.ticks(2);
        assert_eq!(rig.state(), after, "option {option}");
        assert_eq!(rig.axis.enabled(), powered, "option {option}");
        // PV does not restart while quick stop is active.
        assert!(rig.axis.velocity.is_none(), "option {option}");
    }
    // Option 0: disable drive, straight to Switch on disabled.
    let mut rig = Rig::new();
    rig.set(obj::QUICK_STOP_OPTION, 0, Value::I16(0));
    rig.operation_enabled();
    rig.cw(cw::QUICK_STOP_COMMAND);
    assert_eq!(rig.state(), State::SwitchOnDisabled);
    assert_eq!(rig.drive.last_transitions(), [11, 12]);
    assert!(rig.sent(is_stop).is_empty());
    assert_eq!(rig.sent(is_disable).len(), 1);
    // Options 5–8 go back to Operation enabled (16) and the mode resumes.
    let mut rig = Rig::new();
    rig.set(obj::QUICK_STOP_OPTION, 0, Value::I16(6));
    rig.mode(OperationMode::ProfileVelocity);
    rig.set(obj::TARGET_VELOCITY, 0, Value::I32(2000));
    rig.operation_enabled();
    rig.cw(cw::QUICK_STOP_COMMAND);
    rig.ticks(2);
    rig.cw(cw::ENABLE_OPERATION_COMMAND);
    assert_eq!(rig.drive.last_transitions(), [16]);
    assert!(rig.sent(is_enable).is_empty(), "still powered");
    assert_eq!(rig.axis.velocity, Some(2.0));
}

#[test]
fn axis_faults_go_through_fault_reaction_with_their_error_codes() {
    let cases: [(AxisFlags, u16, u8); 4] = [
        (AxisFlags::FE_FAULT, 0x8611, 0x21),
        (AxisFlags::ENCODER_LOSS, 0x7305, 0x21),
        (AxisFlags::DRIVE_ALARM, 0xFF00, 0x81),
        (AxisFlags::ESTOP, 0x5441, 0x21),
    ];
    for (flag, code, register) in cases {
        let mut rig = Rig::new();
        rig.operation_enabled();
        rig.axis.status.flags.insert(flag);
        rig.tick();
        assert_eq!(rig.state(), State::FaultReactionActive, "{flag}");
        assert_eq!(rig.drive.error_code(), code, "{flag}");
        assert_eq!(rig.int(obj::ERROR_CODE), i64::from(code));
        assert_eq!(rig.int(obj::ERROR_REGISTER), i64::from(register), "{flag}");
        // 0x605E default 2: quick stop ramp.
        assert_eq!(
            rig.sent(is_stop),
            [Command::from(Stop {
                axis: 0,
                mode: StopMode::Smooth,
                deceleration: Some(1000.0)
            })]
        );
        rig.tick();
        assert_eq!(rig.state(), State::Fault, "{flag}");
        assert_eq!(rig.sent(is_disable).len(), 1);
        assert_eq!(rig.sw() & 0x4F, 0x08);
        assert_eq!(rig.drive.take_emergencies(), [Emergency { code, register }]);
        rig.axis.status.flags.remove(flag);
        rig.cw(cw::FAULT_RESET_COMMAND);
        rig.tick();
        assert_eq!(rig.state(), State::SwitchOnDisabled, "{flag}");
        assert_eq!(
            rig.drive.take_emergencies(),
            [Emergency {
                code: 0,
                register: 0
            }]
        );
    }
    // A fault while not enabled faults too, without a stop.
    let mut rig = Rig::new();
    rig.axis.status.flags.insert(AxisFlags::DRIVE_ALARM);
    rig.tick();
    assert_eq!(rig.state(), State::FaultReactionActive);
    assert!(rig.last.is_empty());
    rig.tick();
    assert_eq!(rig.state(), State::Fault);
}

#[test]
fn fault_reaction_option_codes() {
    let cases = [
        (1, Some(StopMode::Smooth), Some(100.0)),
        (2, Some(StopMode::Smooth), Some(1000.0)),
        (3, Some(StopMode::Immediate), None),
        (0, None, None),
    ];
    for (option, mode, deceleration) in cases {
        let mut rig = Rig::new();
        rig.set(obj::FAULT_REACTION_OPTION, 0, Value::I16(option));
        rig.operation_enabled();
        rig.axis.status.flags.insert(AxisFlags::FE_FAULT);
        rig.tick();
        match mode {
            Some(mode) => assert_eq!(
                rig.sent(is_stop),
                [Command::from(Stop {
                    axis: 0,
                    mode,
                    deceleration
                })]
            ),
            None => {
                assert!(rig.sent(is_stop).is_empty());
                assert_eq!(rig.sent(is_disable).len(), 1);
            }
        }
        rig.tick();
        assert_eq!(rig.state(), State::Fault);
        assert!(!rig.axis.enabled());
    }
}

#[test]
fn refused_and_lost_power_are_faults() {
    // The engine refuses Enable: 0xFF01.
    let mut rig = Rig::new();
    rig.axis.status.flags.insert(AxisFlags::HOMING_FAILED); // refuses Enable, no drive fault
    rig.cw(cw::SHUTDOWN);
    rig.cw(cw::SWITCH_ON_COMMAND);
    rig.cw(cw::ENABLE_OPERATION_COMMAND);
    assert_eq!(rig.state(), State::OperationEnabled);
    rig.tick();
    assert_eq!(rig.state(), State::FaultReactionActive);
    assert_eq!(rig.drive.error_code(), error_code::ENABLE_REFUSED);
    // Someone else disables the axis: 0xFF02.
    let mut rig = Rig::new();
    rig.operation_enabled();
    rig.tick();
    rig.axis.apply(&Command::from(Disable { axis: 0 })).unwrap();
    rig.tick();
    assert_eq!(rig.state(), State::FaultReactionActive);
    assert_eq!(rig.drive.error_code(), error_code::POWER_LOST);
}

#[test]
fn connection_loss_follows_the_abort_connection_option() {
    // 1 (default): fault 0x8130.
    let mut rig = Rig::new();
    rig.operation_enabled();
    rig.drive.connection_lost();
    rig.tick();
    assert_eq!(rig.state(), State::FaultReactionActive);
    assert_eq!(rig.drive.error_code(), 0x8130);
    assert_eq!(rig.int(obj::ERROR_REGISTER), 0x11);
    // 2: disable voltage.
    let mut rig = Rig::new();
    rig.set(obj::ABORT_CONNECTION_OPTION, 0, Value::I16(2));
    rig.operation_enabled();
    rig.drive.connection_lost();
    rig.tick();
    assert_eq!(rig.state(), State::SwitchOnDisabled);
    // 3: quick stop (option 6 stays in Quick stop active, not re-enabled by the old command).
    let mut rig = Rig::new();
    rig.set(obj::ABORT_CONNECTION_OPTION, 0, Value::I16(3));
    rig.set(obj::QUICK_STOP_OPTION, 0, Value::I16(6));
    rig.operation_enabled();
    rig.drive.connection_lost();
    rig.ticks(3);
    assert_eq!(rig.state(), State::QuickStopActive);
    // 0: nothing.
    let mut rig = Rig::new();
    rig.set(obj::ABORT_CONNECTION_OPTION, 0, Value::I16(0));
    rig.operation_enabled();
    rig.drive.connection_lost();
    rig.ticks(2);
    assert_eq!(rig.state(), State::OperationEnabled);
}

#[test]
fn controlword_for_walks_a_drive_to_any_state() {
    let mut rig = Rig::new();
    rig.walk(PowerTarget::OperationEnabled);
    assert_eq!(rig.state(), State::OperationEnabled);
    assert!(rig.axis.enabled());
    rig.walk(PowerTarget::SwitchedOn);
    assert_eq!(rig.state(), State::SwitchedOn);
    rig.walk(PowerTarget::ReadyToSwitchOn);
    assert_eq!(rig.state(), State::ReadyToSwitchOn);
    rig.walk(PowerTarget::SwitchOnDisabled);
    assert_eq!(rig.state(), State::SwitchOnDisabled);
    // From Fault: reset, retried with a fresh edge while the cause is present.
    rig.walk(PowerTarget::OperationEnabled);
    rig.axis.status.flags.insert(AxisFlags::DRIVE_ALARM);
    rig.axis.alarm_forced = true;
    rig.ticks(2);
    assert_eq!(rig.state(), State::Fault);
    rig.walk(PowerTarget::OperationEnabled);
    assert_eq!(rig.state(), State::Fault);
    rig.axis.alarm_forced = false;
    rig.axis.status.flags.remove(AxisFlags::DRIVE_ALARM);
    rig.walk(PowerTarget::OperationEnabled);
    assert_eq!(rig.state(), State::OperationEnabled);
    // Quick stop active goes back up with 16, or down through 12.
    let sw_qs = State::QuickStopActive.statusword_bits();
    assert_eq!(
        controlword_for(PowerTarget::OperationEnabled, sw_qs, 0x02),
        0x0F
    );
    assert_eq!(controlword_for(PowerTarget::SwitchedOn, sw_qs, 0x02), 0x00);
    // Mode bits of the previous controlword are kept, the command bits replaced.
    let sw_oe = State::OperationEnabled.statusword_bits();
    assert_eq!(
        controlword_for(PowerTarget::OperationEnabled, sw_oe, 0x011F),
        0x011F
    );
    assert_eq!(
        controlword_for(PowerTarget::SwitchedOn, sw_oe, 0x011F),
        0x0117
    );
}

#[test]
fn controlwords_written_back_to_back_walk_the_state_machine() {
    let mut rig = Rig::new();
    rig.tick();
    assert_eq!(rig.state(), State::SwitchOnDisabled);
    // Shutdown, switch on, enable operation: three SDOs answered within one servo period.
    for cw in [0x06u16, 0x07, 0x0F] {
        rig.set(obj::CONTROLWORD, 0, Value::U16(cw));
    }
    rig.tick();
    assert!(
        rig.until(10, |r| r.state() == State::OperationEnabled),
        "state {:?}",
        rig.state()
    );
}
