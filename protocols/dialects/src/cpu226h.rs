//! Co-Trust CPU 226H and its CT E10 servo (digest 003): the motion instructions' STATUS byte,
//! the E10's refusals as SDO aborts when it is reached over CANopen, and the ramp of its units
//! (pulses, Hz, ms).

use axes::od::OdError;
use axes::AxisStatus;

use crate::{modbus, PulseScale};

/// STATUS bit 0: parameter-configuration error (digest 003 §2.0 "Standard STATUS byte").
pub const STATUS_PARAMETER_ERROR: u8 = 0x01;
/// STATUS bit 1: running (this instruction is emitting pulses and has not finished).
pub const STATUS_RUNNING: u8 = 0x02;
/// STATUS bit 2: done (this instruction has finished).
pub const STATUS_DONE: u8 = 0x04;
/// STATUS bit 3: busy — the axis (or the interpolation module) is occupied by **another**
/// instruction; not PLCopen's Busy.
pub const STATUS_BUSY: u8 = 0x08;
/// STATUS bit 5, `MC_HOMING` only: origin found.
pub const STATUS_ORIGIN_FOUND: u8 = 0x20;

/// What one instruction instance knows of itself, which [`AxisStatus`] does not carry: the
/// STATUS byte is per instruction (each call site in the PLC program has its own), so whether
/// *this* instruction owns the axis and has finished is the front-end's latched state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Instruction {
    /// The axis runs this instruction's motion.
    pub owns_axis: bool,
    /// Another instruction holds the axis (or the interpolation module).
    pub blocked: bool,
    /// This instruction's motion finished (latched until its RUN rises again).
    pub done: bool,
    /// The instruction is `MC_HOMING`, whose STATUS adds bit 5.
    pub homing: bool,
}

/// The STATUS byte of a motion instruction (digest 003 §2.0; `MC_HOMING` §2.1). Bit 0 is the
/// axis's parameter error (speeds and times are clamped, never errors); bit 1 is set while this
/// instruction owns the moving axis; bit 5 on `MC_HOMING` is the axis's homed flag.
pub fn status_byte(s: &AxisStatus, i: Instruction) -> u8 {
    let f = s.flags;
    let mut b = 0;
    for (on, bit) in [
        (
            f.contains(axes::AxisFlags::PARAMETER_ERROR),
            STATUS_PARAMETER_ERROR,
        ),
        (
            i.owns_axis && f.contains(axes::AxisFlags::MOVING) && !i.done,
            STATUS_RUNNING,
        ),
        (i.done, STATUS_DONE),
        (i.blocked, STATUS_BUSY),
        (
            i.homing && f.contains(axes::AxisFlags::HOMED),
            STATUS_ORIGIN_FOUND,
        ),
    ] {
        if on {
            b |= bit;
        }
    }
    b
}

/// The object error a refused write to the E10's map-backed objects (0x2000 + n = holding
/// register n, digest 003 §6) becomes, from the map's Modbus `exception`:
/// 02 (no such register, or not one that takes writes) → object does not exist 0x06020000;
/// 03 (the value is refused: a parameter's range, a command argument) → invalid value
/// 0x06090030; any other exception (04: the engine refused in its present state, 06: its queue
/// is full) → 0x08000022, cannot be stored because of the present device state (CiA 301
/// Table 22).
pub fn od_error_for_exception(exception: u8, index: u16, subindex: u8, reason: &str) -> OdError {
    match exception {
        modbus::ILLEGAL_DATA_ADDRESS => OdError::NoObject { index },
        modbus::ILLEGAL_DATA_VALUE => OdError::InvalidValue {
            index,
            subindex,
            detail: reason.to_owned(),
        },
        _ => OdError::DeviceState {
            index,
            subindex,
            detail: reason.to_owned(),
        },
    }
}

/// The acceleration, in user units/s², of a ramp from `min_speed` to `max_speed` (Hz) in
/// `ta_ms` ms (digest 003 §2.0 tip 3: accel = (MAX_SPEED − MIN_SPEED) / TA); `None` for TA = 0,
/// where the instruction takes `MC_SET_MAX_ACCELE`'s value instead. Positions (pulses) and
/// speeds (Hz = pulses/s) convert with the [`PulseScale`] itself (digest 003 §2.0: 1 pulse = 1
/// coordinate unit).
pub fn ramp_acceleration(
    scale: PulseScale,
    min_speed: f64,
    max_speed: f64,
    ta_ms: f64,
) -> Option<f64> {
    (ta_ms > 0.0).then(|| scale.to_engine(max_speed - min_speed) / (ta_ms / 1e3))
}

/// Below 5 Hz the CPU emits no pulses (digest 003 §2.0).
pub const MIN_PULSE_HZ: f64 = 5.0;
/// The pulse outputs' maximum frequency, 200 kHz (digest 003 §1.1).
pub const MAX_PULSE_HZ: f64 = 200_000.0;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_status::with;
    use axes::AxisFlags;

    #[test]
    fn status_bits_follow_the_standard_status_byte() {
        let idle = Instruction::default();
        assert_eq!(status_byte(&with(AxisFlags::empty()), idle), 0);
        // TV-12: a parameter fault is bit 0.
        assert_eq!(status_byte(&with(AxisFlags::PARAMETER_ERROR), idle), 0x01);
        let owner = Instruction {
            owns_axis: true,
            ..idle
        };
        assert_eq!(status_byte(&with(AxisFlags::MOVING), owner), 0x02);
        // Another instruction's motion is not this one's running bit.
        assert_eq!(status_byte(&with(AxisFlags::MOVING), idle), 0);
        let done = Instruction {
            done: true,
            ..owner
        };
        assert_eq!(status_byte(&with(AxisFlags::empty()), done), 0x04);
        // TV-39: the second instruction on a held axis: busy, not running.
        let blocked = Instruction {
            blocked: true,
            ..idle
        };
        assert_eq!(status_byte(&with(AxisFlags::MOVING), blocked), 0x08);
    }

    #[test]
    fn homing_adds_origin_found() {
        // TV-26: origin found and done.
        let homing = Instruction {
            owns_axis: true,
            done: true,
            homing: true,
            ..Instruction::default()
        };
        assert_eq!(status_byte(&with(AxisFlags::HOMED), homing), 0x24);
        // Other instructions keep bit 5 reserved.
        let ptp = Instruction {
            homing: false,
            ..homing
        };
        assert_eq!(status_byte(&with(AxisFlags::HOMED), ptp), 0x04);
    }

    #[test]
    fn map_exceptions_become_these_sdo_aborts() {
        for (exception, abort) in [
            (0x02, 0x0602_0000),
            (0x03, 0x0609_0030),
            (0x04, 0x0800_0022),
            (0x06, 0x0800_0022),
        ] {
            let e = od_error_for_exception(exception, 0x2000, 0, "why");
            assert_eq!(e.sdo_abort_code(), abort, "{exception:#04x}");
        }
    }

    #[test]
    fn a_ramp_is_speed_difference_over_ta() {
        let scale = PulseScale {
            pulses_per_unit: 100.0,
        };
        // (10 500 − 500) Hz in 100 ms = 100 000 Hz/s = 1000 units/s².
        assert_eq!(
            ramp_acceleration(scale, 500.0, 10_500.0, 100.0),
            Some(1000.0)
        );
        assert_eq!(ramp_acceleration(scale, 500.0, 10_500.0, 0.0), None);
    }
}
