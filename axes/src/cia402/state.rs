//! The CiA 402 device control vocabulary (CiA 402-2 / IEC 61800-7-201 §6.2 "Device control"):
//! states, controlword commands, statusword and controlword bits, modes of operation, and the
//! master-side helper [`controlword_for`].

use serde::{Deserialize, Serialize};

/// Controlword (0x6040) bits.
pub mod cw {
    pub const SWITCH_ON: u16 = 1 << 0;
    pub const ENABLE_VOLTAGE: u16 = 1 << 1;
    /// Active low: 0 commands a quick stop.
    pub const QUICK_STOP: u16 = 1 << 2;
    pub const ENABLE_OPERATION: u16 = 1 << 3;
    /// PP: new set-point (rising edge). HM: homing operation start.
    pub const NEW_SET_POINT: u16 = 1 << 4;
    pub const HOMING_START: u16 = 1 << 4;
    /// PP: change set immediately.
    pub const CHANGE_SET_IMMEDIATELY: u16 = 1 << 5;
    /// PP: 1 = the target is relative.
    pub const RELATIVE: u16 = 1 << 6;
    /// Fault reset on the 0 → 1 edge.
    pub const FAULT_RESET: u16 = 1 << 7;
    pub const HALT: u16 = 1 << 8;
    /// PP: change on set-point (blend into the next set-point).
    pub const CHANGE_ON_SET_POINT: u16 = 1 << 9;

    /// The device control commands (bits 0–3 and 7), as a master writes them.
    pub const SHUTDOWN: u16 = 0x0006;
    pub const SWITCH_ON_COMMAND: u16 = 0x0007;
    pub const DISABLE_VOLTAGE: u16 = 0x0000;
    pub const QUICK_STOP_COMMAND: u16 = 0x0002;
    pub const DISABLE_OPERATION: u16 = 0x0007;
    pub const ENABLE_OPERATION_COMMAND: u16 = 0x000F;
    pub const FAULT_RESET_COMMAND: u16 = 0x0080;
    /// Bits that select the device control command.
    pub const COMMAND_MASK: u16 = 0x008F;
}

/// Statusword (0x6041) bits.
pub mod sw {
    pub const READY_TO_SWITCH_ON: u16 = 1 << 0;
    pub const SWITCHED_ON: u16 = 1 << 1;
    pub const OPERATION_ENABLED: u16 = 1 << 2;
    pub const FAULT: u16 = 1 << 3;
    pub const VOLTAGE_ENABLED: u16 = 1 << 4;
    /// Active low: 0 while a quick stop is active.
    pub const QUICK_STOP: u16 = 1 << 5;
    pub const SWITCH_ON_DISABLED: u16 = 1 << 6;
    pub const WARNING: u16 = 1 << 7;
    /// The controlword is processed (always set: mcemu's drives have no local mode).
    pub const REMOTE: u16 = 1 << 9;
    pub const TARGET_REACHED: u16 = 1 << 10;
    pub const INTERNAL_LIMIT_ACTIVE: u16 = 1 << 11;
    /// PP set-point acknowledge, PV speed = 0, HM homing attained, CSx drive follows command.
    pub const OMS_12: u16 = 1 << 12;
    /// PP/CSP following error, HM homing error.
    pub const OMS_13: u16 = 1 << 13;
    /// Manufacturer-specific (mcemu): the bound axis is homed.
    pub const HOMED: u16 = 1 << 14;
    /// Manufacturer-specific (mcemu): the bound axis's commanded position is changing.
    pub const MOVING: u16 = 1 << 15;
    /// The bits that encode the state (CiA 402 Table 30 masks 0x4F / 0x6F).
    pub const STATE_MASK: u16 = 0x006F;
}

/// The states of the CiA 402 power state machine.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum State {
    NotReadyToSwitchOn,
    SwitchOnDisabled,
    ReadyToSwitchOn,
    SwitchedOn,
    OperationEnabled,
    QuickStopActive,
    FaultReactionActive,
    Fault,
}

impl State {
    pub const ALL: [State; 8] = [
        State::NotReadyToSwitchOn,
        State::SwitchOnDisabled,
        State::ReadyToSwitchOn,
        State::SwitchedOn,
        State::OperationEnabled,
        State::QuickStopActive,
        State::FaultReactionActive,
        State::Fault,
    ];

    /// Statusword bits 0–6 of the state. Bit 4 (voltage enabled) is set whenever the drive is
    /// initialised: the simulated supply is always on.
    pub const fn statusword_bits(self) -> u16 {
        use sw::*;
        match self {
            State::NotReadyToSwitchOn => 0,
            State::SwitchOnDisabled => SWITCH_ON_DISABLED | VOLTAGE_ENABLED,
            State::ReadyToSwitchOn => READY_TO_SWITCH_ON | QUICK_STOP | VOLTAGE_ENABLED,
            State::SwitchedOn => READY_TO_SWITCH_ON | SWITCHED_ON | QUICK_STOP | VOLTAGE_ENABLED,
            State::OperationEnabled => {
                READY_TO_SWITCH_ON | SWITCHED_ON | OPERATION_ENABLED | QUICK_STOP | VOLTAGE_ENABLED
            }
            State::QuickStopActive => {
                READY_TO_SWITCH_ON | SWITCHED_ON | OPERATION_ENABLED | VOLTAGE_ENABLED
            }
            State::FaultReactionActive => {
                READY_TO_SWITCH_ON | SWITCHED_ON | OPERATION_ENABLED | FAULT | VOLTAGE_ENABLED
            }
            State::Fault => FAULT | VOLTAGE_ENABLED,
        }
    }

    /// Decode a statusword with the CiA 402 masks (0x4F for the states whose bit 5 is "x",
    /// 0x6F for the others). `None` for bit patterns that are no state.
    pub const fn from_statusword(statusword: u16) -> Option<State> {
        Some(match (statusword & 0x4F, statusword & 0x6F) {
            (0x00, _) => State::NotReadyToSwitchOn,
            (0x40, _) => State::SwitchOnDisabled,
            (_, 0x21) => State::ReadyToSwitchOn,
            (_, 0x23) => State::SwitchedOn,
            (_, 0x27) => State::OperationEnabled,
            (_, 0x07) => State::QuickStopActive,
            (0x0F, _) => State::FaultReactionActive,
            (0x08, _) => State::Fault,
            _ => return None,
        })
    }

    /// Whether the drive function is enabled (the motor is under control).
    pub const fn is_operational(self) -> bool {
        matches!(self, State::OperationEnabled | State::QuickStopActive)
    }

    pub const fn name(self) -> &'static str {
        match self {
            State::NotReadyToSwitchOn => "not ready to switch on",
            State::SwitchOnDisabled => "switch on disabled",
            State::ReadyToSwitchOn => "ready to switch on",
            State::SwitchedOn => "switched on",
            State::OperationEnabled => "operation enabled",
            State::QuickStopActive => "quick stop active",
            State::FaultReactionActive => "fault reaction active",
            State::Fault => "fault",
        }
    }
}

impl std::fmt::Display for State {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A device control command: what bits 0–3 and 7 of a controlword ask for (CiA 402 Table 28).
/// Every controlword decodes to exactly one command; whether it causes a transition depends on
/// the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeviceCommand {
    /// `0xxx x110`: transitions 2, 6, 8.
    Shutdown,
    /// `0xxx 0111`: transition 3; in Operation enabled it is "disable operation" (5).
    SwitchOn,
    /// `0xxx 1111`: transitions 4, 16; from Ready to switch on it is 3 then 4.
    EnableOperation,
    /// `0xxx xx0x`: transitions 7, 9, 10, 12.
    DisableVoltage,
    /// `0xxx x01x`: transitions 7, 10, 11.
    QuickStop,
    /// `1xxx xxxx`: transition 15 on the rising edge of bit 7; no transition elsewhere.
    FaultReset,
}

impl DeviceCommand {
    pub const fn decode(controlword: u16) -> DeviceCommand {
        if controlword & cw::FAULT_RESET != 0 {
            DeviceCommand::FaultReset
        } else if controlword & cw::ENABLE_VOLTAGE == 0 {
            DeviceCommand::DisableVoltage
        } else if controlword & cw::QUICK_STOP == 0 {
            DeviceCommand::QuickStop
        } else if controlword & cw::SWITCH_ON == 0 {
            DeviceCommand::Shutdown
        } else if controlword & cw::ENABLE_OPERATION == 0 {
            DeviceCommand::SwitchOn
        } else {
            DeviceCommand::EnableOperation
        }
    }
}

/// Modes of operation (0x6060/0x6061) that mcemu's drive supports.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OperationMode {
    /// 0: no mode assigned; the drive holds whatever the axis does.
    NoMode,
    /// 1: profile position (PP).
    ProfilePosition,
    /// 3: profile velocity (PV).
    ProfileVelocity,
    /// 6: homing (HM).
    Homing,
    /// 8: cyclic synchronous position (CSP).
    CyclicPosition,
    /// 9: cyclic synchronous velocity (CSV).
    CyclicVelocity,
    /// 10: cyclic synchronous torque (CST).
    CyclicTorque,
}

impl OperationMode {
    pub const ALL: [OperationMode; 7] = [
        OperationMode::NoMode,
        OperationMode::ProfilePosition,
        OperationMode::ProfileVelocity,
        OperationMode::Homing,
        OperationMode::CyclicPosition,
        OperationMode::CyclicVelocity,
        OperationMode::CyclicTorque,
    ];

    pub const fn code(self) -> i8 {
        match self {
            OperationMode::NoMode => 0,
            OperationMode::ProfilePosition => 1,
            OperationMode::ProfileVelocity => 3,
            OperationMode::Homing => 6,
            OperationMode::CyclicPosition => 8,
            OperationMode::CyclicVelocity => 9,
            OperationMode::CyclicTorque => 10,
        }
    }

    /// The mode with a 0x6060 code, if mcemu supports it.
    pub const fn from_code(code: i8) -> Option<OperationMode> {
        Some(match code {
            0 => OperationMode::NoMode,
            1 => OperationMode::ProfilePosition,
            3 => OperationMode::ProfileVelocity,
            6 => OperationMode::Homing,
            8 => OperationMode::CyclicPosition,
            9 => OperationMode::CyclicVelocity,
            10 => OperationMode::CyclicTorque,
            _ => return None,
        })
    }

    /// Bit of 0x6502 "supported drive modes" (CiA 402: bit 0 pp, 2 pv, 5 hm, 7 csp, 8 csv,
    /// 9 cst).
    pub const fn supported_bit(self) -> u32 {
        match self {
            OperationMode::NoMode => 0,
            OperationMode::ProfilePosition => 1 << 0,
            OperationMode::ProfileVelocity => 1 << 2,
            OperationMode::Homing => 1 << 5,
            OperationMode::CyclicPosition => 1 << 7,
            OperationMode::CyclicVelocity => 1 << 8,
            OperationMode::CyclicTorque => 1 << 9,
        }
    }

    pub const fn is_cyclic(self) -> bool {
        matches!(
            self,
            OperationMode::CyclicPosition
                | OperationMode::CyclicVelocity
                | OperationMode::CyclicTorque
        )
    }
}

/// Where a master wants the power state machine to go (for [`controlword_for`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PowerTarget {
    SwitchOnDisabled,
    ReadyToSwitchOn,
    SwitchedOn,
    OperationEnabled,
}

/// The next controlword a master writes to walk a drive from the state its `statusword` shows
/// towards `target`, one transition per call (the way python-canopen's `BaseNode402` and
/// HIMC's Enable/Disable/Reset do it). `previous` is the controlword written last: its bits
/// outside the device control command (4–6, 8–15: set-point, halt, mode bits) are kept, and it
/// makes a fault reset a fresh 0 → 1 edge of bit 7 each time (a failed reset is retried by
/// dropping bit 7 for one call).
///
/// Call it once per cycle after the drive has answered; the result is idempotent while the
/// drive has not moved.
pub fn controlword_for(target: PowerTarget, statusword: u16, previous: u16) -> u16 {
    use PowerTarget as T;
    let keep = previous & !cw::COMMAND_MASK;
    let command = match State::from_statusword(statusword) {
        Some(State::Fault) => {
            if previous & cw::FAULT_RESET != 0 {
                cw::DISABLE_VOLTAGE // re-arm the edge
            } else {
                cw::FAULT_RESET_COMMAND
            }
        }
        // Automatic transitions: wait with a command that changes nothing, bit 7 low so that
        // the reset edge is ready when Fault is reached.
        None | Some(State::NotReadyToSwitchOn | State::FaultReactionActive) => cw::DISABLE_VOLTAGE,
        Some(state) => match (state, target) {
            (_, T::SwitchOnDisabled) => cw::DISABLE_VOLTAGE,
            // Quick stop active leaves only towards Switch on disabled (12) or back to
            // Operation enabled (16).
            (State::QuickStopActive, T::OperationEnabled) => cw::ENABLE_OPERATION_COMMAND,
            (State::QuickStopActive, _) => cw::DISABLE_VOLTAGE,
            (State::SwitchOnDisabled, _) => cw::SHUTDOWN,
            (State::ReadyToSwitchOn, T::ReadyToSwitchOn) => cw::SHUTDOWN,
            (State::ReadyToSwitchOn, _) => cw::SWITCH_ON_COMMAND,
            (State::SwitchedOn | State::OperationEnabled, T::ReadyToSwitchOn) => cw::SHUTDOWN,
            (State::SwitchedOn | State::OperationEnabled, T::SwitchedOn) => cw::SWITCH_ON_COMMAND,
            (_, T::OperationEnabled) => cw::ENABLE_OPERATION_COMMAND,
            // Handled above.
            (State::NotReadyToSwitchOn | State::FaultReactionActive | State::Fault, _) => {
                cw::DISABLE_VOLTAGE
            }
        },
    };
    keep | command
}
