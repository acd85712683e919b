//! Gaochuan NMC (digest 001): the `BIT_AXIS_*` axis status word, the return codes, and the
//! library's units (pulse, pulse/ms, pulse/ms²).

use axes::command::{EngineError, ErrorKind};
use axes::status::{
    CaptureStatus, CompareState, CompareStatus, GroupFault, GroupState, GroupStatus,
};
use axes::{AxisFlags, AxisState, AxisStatus};

use crate::PulseScale;

// Axis status word bits, `NMC_MtGetSts` (digest 001 §3.1, verbatim macro names).
pub const BIT_AXIS_BUSY: u16 = 0x0001;
pub const BIT_AXIS_POSREC: u16 = 0x0002;
pub const BIT_AXIS_MVERR: u16 = 0x0004;
pub const BIT_AXIS_SVON: u16 = 0x0008;
pub const BIT_AXIS_CRD: u16 = 0x0010;
pub const BIT_AXIS_STEP: u16 = 0x0020;
pub const BIT_AXIS_LMTP: u16 = 0x0040;
pub const BIT_AXIS_LMTN: u16 = 0x0080;
pub const BIT_AXIS_SOFTPOSLMT: u16 = 0x0100;
pub const BIT_AXIS_SOFTNEGLMT: u16 = 0x0200;
pub const BIT_AXIS_ALM: u16 = 0x0400;
pub const BIT_AXIS_POSERR: u16 = 0x0800;
pub const BIT_AXIS_ESTP: u16 = 0x1000;
pub const BIT_AXIS_HWERR: u16 = 0x2000;
pub const BIT_AXIS_CAPTSET: u16 = 0x4000;

/// What the NMC status word shows that [`AxisStatus`] does not carry.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AxisExtra {
    /// The axis drives a stepper (`BIT_AXIS_STEP`, digest 001 §3.1: 1 stepper, 0 servo): a
    /// property of the configured axis, not of its motion.
    pub stepper: bool,
    /// An EtherCAT bus axis whose CiA 402 drive is in Fault or Fault reaction active
    /// (statusword bit 3): `BIT_AXIS_ALM` (digest 001 §3.1 "驱动器报警"), cleared by
    /// `NMC_MtClrError`'s fault reset.
    pub drive_fault: bool,
}

/// The axis status word of `NMC_MtGetSts` (digest 001 §3.1; bit 15 undefined, always 0). The C
/// API returns it as a `short`: the same 16 bits.
///
/// - BUSY: the profile generator is active, i.e. the commanded position moves or the axis is in
///   a motion state (PTP, JOG, PT, gear, follow, homing; digest 001 §4 "Busy").
/// - POSREC: in position (band and settle time, digest 001 §4).
/// - MVERR: the last motion ended in an error or could not start, latched until
///   `NMC_MtClrError` (the engine's `motion_error`).
/// - CRD: the axis belongs to a coordinate system (the engine's `in_group`).
/// - HWERR: the feedback is lost (the digest leaves the source open, §8 item 11; an encoder
///   break is the one hardware fault the engine models).
/// - ALM, POSERR, ESTP, CAPTSET, the limits: the engine flags of the same meaning.
pub fn axis_status(s: &AxisStatus, extra: AxisExtra) -> u16 {
    let f = s.flags;
    let busy = f.contains(AxisFlags::MOVING)
        || matches!(
            s.state,
            AxisState::Homing
                | AxisState::DiscreteMotion
                | AxisState::ContinuousMotion
                | AxisState::SynchronizedMotion
                | AxisState::Stopping
        );
    let mut w = 0;
    for (on, bit) in [
        (busy, BIT_AXIS_BUSY),
        (f.contains(AxisFlags::IN_POSITION), BIT_AXIS_POSREC),
        (f.contains(AxisFlags::MOTION_ERROR), BIT_AXIS_MVERR),
        (f.contains(AxisFlags::ENABLED), BIT_AXIS_SVON),
        (f.contains(AxisFlags::IN_GROUP), BIT_AXIS_CRD),
        (extra.stepper, BIT_AXIS_STEP),
        (f.contains(AxisFlags::HW_LIMIT_POS), BIT_AXIS_LMTP),
        (f.contains(AxisFlags::HW_LIMIT_NEG), BIT_AXIS_LMTN),
        (f.contains(AxisFlags::SW_LIMIT_POS), BIT_AXIS_SOFTPOSLMT),
        (f.contains(AxisFlags::SW_LIMIT_NEG), BIT_AXIS_SOFTNEGLMT),
        (
            f.contains(AxisFlags::DRIVE_ALARM) || extra.drive_fault,
            BIT_AXIS_ALM,
        ),
        (f.contains(AxisFlags::FE_FAULT), BIT_AXIS_POSERR),
        (f.contains(AxisFlags::ESTOP), BIT_AXIS_ESTP),
        (f.contains(AxisFlags::ENCODER_LOSS), BIT_AXIS_HWERR),
        (f.contains(AxisFlags::CAPTURE_TRIGGERED), BIT_AXIS_CAPTSET),
    ] {
        if on {
            w |= bit;
        }
    }
    w
}

/// The engine latches that `NMC_MtClrStsByBits(ax, stsMask)` clears (digest 001 §2.4, TV26):
/// each latched bit of the §3.1 word maps to the faults behind it; the bits that are not
/// latches (BUSY, POSREC, SVON, CRD, STEP, CAPTSET) clear nothing. MVERR covers the faults
/// that show only as MVERR (a PT stream run dry, a gantry deviation).
pub fn latched_faults_of(sts_mask: u16) -> AxisFlags {
    let mut f = AxisFlags::empty();
    for (bit, faults) in [
        (
            BIT_AXIS_MVERR,
            AxisFlags::MOTION_ERROR | AxisFlags::STREAM_UNDERRUN | AxisFlags::GANTRY_FAULT,
        ),
        (BIT_AXIS_LMTP, AxisFlags::HW_LIMIT_POS),
        (BIT_AXIS_LMTN, AxisFlags::HW_LIMIT_NEG),
        (BIT_AXIS_SOFTPOSLMT, AxisFlags::SW_LIMIT_POS),
        (BIT_AXIS_SOFTNEGLMT, AxisFlags::SW_LIMIT_NEG),
        (BIT_AXIS_ALM, AxisFlags::DRIVE_ALARM),
        (BIT_AXIS_POSERR, AxisFlags::FE_FAULT),
        (BIT_AXIS_ESTP, AxisFlags::ESTOP),
        (BIT_AXIS_HWERR, AxisFlags::ENCODER_LOSS),
    ] {
        if sts_mask & bit != 0 {
            f |= faults;
        }
    }
    f
}

/// `NMC_EcatGetHomeSts` (digest 001 §3.14) from a bus drive's statusword (0x6041) and mode
/// display (0x6061): in homing mode (6) bits 13/12/10 (homing error, attained, target
/// reached) packed into bits 2/1/0 — 000 searching, 010 found and stopping, 011 done, 100
/// failed and stopping, 101 failed, 001 interrupted; in any other mode 001 (not started).
pub fn ecat_home_status(statusword: u16, mode: i8) -> u8 {
    const HOMING_MODE: i8 = 6;
    if mode != HOMING_MODE {
        return 0b001;
    }
    let bit = |n: u16| u8::from(statusword & (1 << n) != 0);
    bit(13) << 2 | bit(12) << 1 | bit(10)
}

/// `NMC_MtGetAdvCaptPos`'s `captSts` (digest 001 §2.18): bit 0 the leading edge latched, bit 1
/// the trailing edge (a channel armed on both edges with `repeat` 2; TV 61 reads 0x3).
pub fn adv_capture_status(c: Option<&CaptureStatus>) -> i16 {
    match c.map(|c| c.latches.len()) {
        Some(0) | None => 0,
        Some(1) => 0x1,
        Some(_) => 0x3,
    }
}

/// `NMC_Comp2DimensStatusEx` (digest 001 §3.16 `TComp2DimensSts`): `sts` 1 busy / 0 idle,
/// `usedSpace` the points not yet output, `outCount` the outputs so far. A channel not started
/// reads idle and empty.
pub fn compare_status(c: Option<&CompareStatus>) -> (i16, i32, i32) {
    match c {
        Some(c) => (
            i16::from(c.state == CompareState::Running),
            i32::try_from(c.remaining).unwrap_or(i32::MAX),
            i32::try_from(c.count).unwrap_or(i32::MAX),
        ),
        None => (0, 0, 0),
    }
}

/// `RTN_CMD_SUCCESS` (digest 001 §1.2).
pub const RTN_CMD_SUCCESS: i16 = 0;
/// A lost connection (digest 001 §8 item 1: the one other code the manual names).
pub const RTN_COMM_ERROR: i16 = -1;

/// The return code of a refused call. `mtn_lib20_err.h` is not in the manual (digest 001 §8 item
/// 1), so the codes are mcemu's: one positive code per engine error kind, stable across
/// releases (docs/decisions.md, "Dialects"). A program checks `rc != 0`, as the manual's
/// examples do.
pub fn code_for(e: &EngineError) -> i16 {
    code_for_kind(e.kind())
}

/// [`code_for`] by error kind (what a status record keeps of the last refusal).
pub fn code_for_kind(kind: ErrorKind) -> i16 {
    match kind {
        ErrorKind::InvalidAxis => 1,
        ErrorKind::UnknownParameter => 2,
        ErrorKind::InvalidParameter => 3,
        ErrorKind::ReadOnlyParameter => 4,
        ErrorKind::InvalidArgument => 5,
        ErrorKind::AxisDisabled => 6,
        ErrorKind::AxisInError => 7,
        ErrorKind::LimitActive => 8,
        ErrorKind::QueueFull => 9,
        ErrorKind::Unsupported => 10,
        ErrorKind::InvalidState => 11,
        ErrorKind::CauseStillPresent => 12,
        ErrorKind::UnknownCommand => 13,
        ErrorKind::Homing => 14,
        ErrorKind::Object => 15,
        ErrorKind::InvalidSlave => 16,
        ErrorKind::InvalidChannel => 17,
        ErrorKind::LimitReached => 18,
        ErrorKind::Fault => 19,
        ErrorKind::InvalidGroup => 20,
        ErrorKind::GroupState => 21,
    }
}

/// NMC velocities (pulse/ms, digest 001 §1.3) in user units/s; positions are pulses, converted
/// by the [`PulseScale`] itself.
pub fn velocity_to_engine(scale: PulseScale, pulse_per_ms: f64) -> f64 {
    scale.to_engine(pulse_per_ms * 1e3)
}

/// User units/s in pulse/ms.
pub fn velocity_from_engine(scale: PulseScale, units_per_s: f64) -> f64 {
    scale.from_engine(units_per_s) / 1e3
}

/// NMC accelerations (pulse/ms², digest 001 §1.3) in user units/s².
pub fn acceleration_to_engine(scale: PulseScale, pulse_per_ms2: f64) -> f64 {
    scale.to_engine(pulse_per_ms2 * 1e6)
}

/// User units/s² in pulse/ms².
pub fn acceleration_from_engine(scale: PulseScale, units_per_s2: f64) -> f64 {
    scale.from_engine(units_per_s2) / 1e6
}

// Coordinate-system status bits, `NMC_CrdGetSts` (bits 0-5) and `NMC_CrdGetInnerSts` (bits 6-11),
// digest 001 §3.8, verbatim macro names.
pub const BIT_CORD_BUSY: u32 = 0x0001;
pub const BIT_CORD_MVERR: u32 = 0x0002;
pub const BIT_CORD_EMPTY: u32 = 0x0004;
pub const BIT_CORD_FULL: u32 = 0x0008;
pub const BIT_CORD_NODATASTOP: u32 = 0x0010;
pub const BIT_CORD_POSREC: u32 = 0x0040;
pub const BIT_CORD_AXIS_ERR: u32 = 0x0200;

/// What the coordinate-system word shows that [`GroupStatus`] does not carry: the commands
/// the front-end holds until `NMC_CrdStartMtn` (digest 001 §4.4: push first, then start).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CrdExtra {
    /// Commands pushed and not yet handed to the engine.
    pub pending: usize,
    /// Places left for pushing (the engine queue's, less `pending`).
    pub free: usize,
}

/// The coordinate-system status word (digest 001 §3.8): `NMC_CrdGetSts` is its low 6 bits,
/// `NMC_CrdGetInnerSts` all of it.
///
/// - BUSY: the path runs (Moving, Stopping, or a halt still decelerating); a path halted at rest
///   by `NMC_CrdStopMtn` is not busy (TV49).
/// - MVERR: the group is in ErrorStop (a member fault, an e-stop, a wait timeout).
/// - EMPTY: nothing queued and nothing pending; FULL: no place left.
/// - NODATASTOP: the path was e-stopped (`NMC_CrdEstopMtn`).
/// - POSREC (inner): every member in position with nothing queued.
/// - AXIS_ERR (inner): a member's fault stopped the path.
pub fn crd_status(g: Option<&GroupStatus>, extra: CrdExtra) -> u32 {
    let Some(g) = g else {
        let mut w = 0;
        if extra.pending == 0 {
            w |= BIT_CORD_EMPTY;
        }
        if extra.free == 0 {
            w |= BIT_CORD_FULL;
        }
        return w;
    };
    let busy = match g.state {
        GroupState::Moving | GroupState::Stopping => true,
        GroupState::Halted => g.path_velocity != 0.0,
        GroupState::Disabled | GroupState::Standby | GroupState::ErrorStop => false,
    };
    let mut w = 0;
    for (on, bit) in [
        (busy, BIT_CORD_BUSY),
        (g.state == GroupState::ErrorStop, BIT_CORD_MVERR),
        (g.queue_used == 0 && extra.pending == 0, BIT_CORD_EMPTY),
        (extra.free == 0, BIT_CORD_FULL),
        (
            g.fault == Some(GroupFault::EmergencyStop),
            BIT_CORD_NODATASTOP,
        ),
        (g.in_position && extra.pending == 0, BIT_CORD_POSREC),
        (
            matches!(g.fault, Some(GroupFault::Member { .. })),
            BIT_CORD_AXIS_ERR,
        ),
    ] {
        if on {
            w |= bit;
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_status::status;

    #[test]
    fn each_flag_sets_its_bit_of_section_3_1() {
        let standstill = AxisState::Standstill;
        for (flag, bit) in [
            (AxisFlags::IN_POSITION, 0x0002),
            (AxisFlags::MOTION_ERROR, 0x0004),
            (AxisFlags::ENABLED, 0x0008),
            (AxisFlags::IN_GROUP, 0x0010),
            (AxisFlags::HW_LIMIT_POS, 0x0040),
            (AxisFlags::HW_LIMIT_NEG, 0x0080),
            (AxisFlags::SW_LIMIT_POS, 0x0100),
            (AxisFlags::SW_LIMIT_NEG, 0x0200),
            (AxisFlags::DRIVE_ALARM, 0x0400),
            (AxisFlags::FE_FAULT, 0x0800),
            (AxisFlags::ESTOP, 0x1000),
            (AxisFlags::ENCODER_LOSS, 0x2000),
            (AxisFlags::CAPTURE_TRIGGERED, 0x4000),
        ] {
            let s = status(standstill, flag);
            assert_eq!(axis_status(&s, AxisExtra::default()), bit, "{flag}");
        }
        // Flags the word has no bit for.
        let quiet = AxisFlags::HOMED | AxisFlags::HOME_SWITCH | AxisFlags::FE_WARNING;
        assert_eq!(
            axis_status(&status(standstill, quiet), AxisExtra::default()),
            0
        );
    }

    /// A bus drive in Fault shows as the drive alarm (TV34's bus axes, decisions.md).
    #[test]
    fn a_faulted_bus_drive_is_the_alarm_bit() {
        let s = status(AxisState::Standstill, AxisFlags::empty());
        let extra = AxisExtra {
            drive_fault: true,
            ..AxisExtra::default()
        };
        assert_eq!(axis_status(&s, extra), BIT_AXIS_ALM);
    }

    /// Digest 001 §3.14: statusword bits 13/12/10 in homing mode; 001 outside it.
    #[test]
    fn ecat_home_status_packs_bits_13_12_10() {
        for (sw, mode, want) in [
            (0x0000, 6, 0b000),
            (0x0400, 6, 0b001),
            (0x1000, 6, 0b010),
            (0x1400, 6, 0b011),
            (0x2000, 6, 0b100),
            (0x2400, 6, 0b101),
            (0x1637, 6, 0b011),
            (0x1400, 0, 0b001),
            (0x0000, 8, 0b001),
        ] {
            assert_eq!(ecat_home_status(sw, mode), want, "{sw:#06x} mode {mode}");
        }
    }

    #[test]
    fn busy_while_moving_or_in_a_motion_state() {
        let none = AxisExtra::default();
        let moving = status(AxisState::Standstill, AxisFlags::MOVING);
        assert_eq!(axis_status(&moving, none), BIT_AXIS_BUSY);
        for state in [
            AxisState::Homing,
            AxisState::DiscreteMotion,
            AxisState::ContinuousMotion,
            AxisState::SynchronizedMotion,
            AxisState::Stopping,
        ] {
            let s = status(state, AxisFlags::empty());
            assert_eq!(axis_status(&s, none), BIT_AXIS_BUSY, "{state}");
        }
        for state in [
            AxisState::Disabled,
            AxisState::Standstill,
            AxisState::ErrorStop,
        ] {
            let s = status(state, AxisFlags::empty());
            assert_eq!(axis_status(&s, none), 0, "{state}");
        }
    }

    #[test]
    fn the_stepper_bit_comes_from_the_axis_configuration() {
        let s = status(AxisState::Standstill, AxisFlags::ENABLED);
        let stepper = AxisExtra {
            stepper: true,
            ..AxisExtra::default()
        };
        assert_eq!(axis_status(&s, stepper), BIT_AXIS_SVON | BIT_AXIS_STEP);
    }

    #[test]
    fn test_vectors_of_section_6() {
        // TV19: E-stop during jog sets 0x1000, busy clears once stopped.
        let s = status(AxisState::ErrorStop, AxisFlags::ENABLED | AxisFlags::ESTOP);
        assert_eq!(axis_status(&s, AxisExtra::default()) & 0x1001, 0x1000);
        // TV21: the positive hardware limit is 0x40.
        let s = status(AxisState::Standstill, AxisFlags::HW_LIMIT_POS);
        assert_eq!(axis_status(&s, AxisExtra::default()), 0x40);
    }

    #[test]
    fn return_codes_are_distinct_and_nonzero() {
        let kinds = [
            ErrorKind::InvalidAxis,
            ErrorKind::UnknownParameter,
            ErrorKind::InvalidParameter,
            ErrorKind::ReadOnlyParameter,
            ErrorKind::InvalidArgument,
            ErrorKind::AxisDisabled,
            ErrorKind::AxisInError,
            ErrorKind::LimitActive,
            ErrorKind::QueueFull,
            ErrorKind::Unsupported,
            ErrorKind::InvalidState,
            ErrorKind::CauseStillPresent,
            ErrorKind::UnknownCommand,
            ErrorKind::Homing,
            ErrorKind::Object,
            ErrorKind::InvalidSlave,
            ErrorKind::InvalidChannel,
            ErrorKind::LimitReached,
            ErrorKind::Fault,
            ErrorKind::InvalidGroup,
            ErrorKind::GroupState,
        ];
        let mut codes: Vec<i16> = kinds.iter().map(|k| code_for_kind(*k)).collect();
        assert!(codes.iter().all(|c| *c > 0));
        codes.sort_unstable();
        codes.dedup();
        assert_eq!(codes.len(), kinds.len());
        let e = EngineError::QueueFull { axis: 0, depth: 64 };
        assert_eq!(code_for(&e), 9);
    }

    #[test]
    fn units_are_pulse_pulse_per_ms_and_pulse_per_ms2() {
        let scale = PulseScale {
            pulses_per_unit: 1000.0,
        };
        // 10 pulse/ms = 10 000 pulse/s = 10 units/s.
        assert_eq!(velocity_to_engine(scale, 10.0), 10.0);
        assert_eq!(velocity_from_engine(scale, 10.0), 10.0);
        // 0.1 pulse/ms² = 100 000 pulse/s² = 100 units/s².
        assert!((acceleration_to_engine(scale, 0.1) - 100.0).abs() < 1e-9);
        assert!((acceleration_from_engine(scale, 100.0) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn tv61_and_tv63_status_words() {
        let latch = axes::status::Latch::default();
        let mut c = CaptureStatus {
            axis: 0,
            channel: 0,
            source: axes::status::CaptureSource::Di,
            source_axis: 0,
            input: Some(0),
            edge: axes::status::CaptureEdge::Both,
            repeat: 2,
            continuous: false,
            window: None,
            state: axes::status::CaptureState::Waiting,
            count: 1,
            latches: vec![latch],
        };
        assert_eq!(adv_capture_status(Some(&c)), 0x1);
        c.latches.push(latch);
        assert_eq!(adv_capture_status(Some(&c)), 0x3);
        assert_eq!(adv_capture_status(None), 0);
        let done = CompareStatus {
            state: CompareState::Done,
            count: 100,
            remaining: 0,
            total: 100,
            ..CompareStatus::default()
        };
        assert_eq!(compare_status(Some(&done)), (0, 0, 100));
        let busy = CompareStatus {
            state: CompareState::Running,
            count: 40,
            remaining: 60,
            ..done
        };
        assert_eq!(compare_status(Some(&busy)), (1, 60, 40));
    }

    /// Digest 001 §3.8: BUSY only while the path runs (a halt at rest is not busy, TV49),
    /// EMPTY with nothing queued or pending (TV50), MVERR and NODATASTOP after an e-stop.
    #[test]
    fn crd_status_bits() {
        let free = CrdExtra {
            pending: 0,
            free: 1024,
        };
        assert_eq!(
            crd_status(None, free),
            BIT_CORD_EMPTY,
            "a coordinate system without a group"
        );
        let moving = GroupStatus {
            state: GroupState::Moving,
            queue_used: 2,
            path_velocity: 10.0,
            ..GroupStatus::default()
        };
        assert_eq!(crd_status(Some(&moving), free), BIT_CORD_BUSY);
        let halted = GroupStatus {
            state: GroupState::Halted,
            path_velocity: 0.0,
            ..moving
        };
        assert_eq!(crd_status(Some(&halted), free), 0);
        let pending = CrdExtra {
            pending: 3,
            free: 0,
        };
        let standby = GroupStatus {
            state: GroupState::Standby,
            ..GroupStatus::default()
        };
        assert_eq!(crd_status(Some(&standby), pending), BIT_CORD_FULL);
        let estop = GroupStatus {
            state: GroupState::ErrorStop,
            fault: Some(GroupFault::EmergencyStop),
            ..GroupStatus::default()
        };
        assert_eq!(
            crd_status(Some(&estop), free),
            BIT_CORD_MVERR | BIT_CORD_EMPTY | BIT_CORD_NODATASTOP
        );
    }
}
