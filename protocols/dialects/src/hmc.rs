//! Hollysys HMC (digest 000): the AxisStatus and LimitState words, the motion functions'
//! return codes.
//!
//! The two status words are also the values of the engine's own `AxisStatus`/`LimitState`
//! parameters, and the engine switches the drive off on `AxisStatus & AxisErrMask` (digest 000
//! §6.4); so their bit layout is computed in `axes::param` and this module is the vendor-facing
//! name for it (docs/decisions.md, "Dialects (issue 10, item 3)").

use axes::command::EngineError;
use axes::status::{CaptureState, CaptureStatus, CompareState, CompareStatus};
use axes::AxisStatus;

/// AxisStatus bit 0: following error over FELimit 10 consecutive times, latched (digest 000 §2.2
/// table 2).
pub const AXIS_STATUS_FE_FAULT: u32 = 1;
/// AxisStatus bit 1: following error over FELimit once, auto-clearing.
pub const AXIS_STATUS_FE_WARNING: u32 = 2;
/// AxisStatus bit 2: axis parameter setting error, latched.
pub const AXIS_STATUS_PARAMETER_ERROR: u32 = 4;
/// AxisStatus bit 3: a forward or reverse limit (soft or hard) reached.
pub const AXIS_STATUS_LIMIT: u32 = 8;

/// LimitState bits (digest 000 §2.2): forward/reverse hard limit, forward/reverse soft limit,
/// soft-limit parameter error, both limits at once.
pub const LIMIT_FORWARD_HARD: u32 = 1;
pub const LIMIT_REVERSE_HARD: u32 = 2;
pub const LIMIT_FORWARD_SOFT: u32 = 4;
pub const LIMIT_REVERSE_SOFT: u32 = 8;
pub const LIMIT_SOFT_CONFIG: u32 = 16;
pub const LIMIT_BOTH: u32 = 32;

/// `AxisStatus` (digest 000 §2.2 table 2). Bit 4 (bus communication error) and the gantry bits
/// 5/6 are never set: the emulated axes have no RTEX/EtherCAT bus and no gantry.
pub fn axis_status(s: &AxisStatus) -> u32 {
    axes::param::axis_status_word(s.flags)
}

/// `LimitState` (digest 000 §2.2, finite travel).
pub fn limit_state(s: &AxisStatus) -> u32 {
    axes::param::limit_state_word(s.flags)
}

/// What every motion function returns on a parameter error, nothing being posted (digest 000
/// §6.3, §6.9).
pub const PARAMETER_ERROR: u32 = 0xFFFF_FFFF;
/// `HMC_WaitAxisIdle` with an axis number out of range (digest 000 §6.9, §8 item 46).
pub const WAIT_AXIS_IDLE_BAD_AXIS: u8 = 0x17;

/// `HMC_ClcJerk(dCurvature, dSpeed)` (digest 000 §4.4.7.2, §3.5): the jerk a curve of
/// curvature κ needs to run at `speed`, κ²·v³ — the inverse of the curve speed cap
/// `(Jerk/κ²)^(1/3)` the engine's planner applies with the path's jerk. A negative or
/// non-finite argument is the manual's parameter error, −1.
pub fn clc_jerk(curvature: f64, speed: f64) -> f64 {
    let valid = |x: f64| x.is_finite() && x >= 0.0;
    if valid(curvature) && valid(speed) {
        curvature * curvature * speed * speed * speed
    } else {
        -1.0
    }
}

/// The code a buffered motion function returns for a refused command: the manual lists one
/// code for every refusal, 0xFFFFFFFF (digest 000 §6.9 "function parameter error (all motion
/// functions)"); an accepted command returns its command id instead.
pub fn code_for(_e: &EngineError) -> u32 {
    PARAMETER_ERROR
}

/// `HMC_CaptureGetState` (digest 000 §4.4): 1 outside the window, 2 waiting for the signal, 3
/// idle (done, or a channel never configured: `None`). 0, configuring, never shows: a
/// configuration takes effect at once.
pub fn capture_state(c: Option<&CaptureStatus>) -> u8 {
    match c.map(|c| c.state) {
        Some(CaptureState::OutsideWindow) => 1,
        Some(CaptureState::Waiting) => 2,
        Some(CaptureState::Done) | None => 3,
    }
}

/// `HMC_GetSwitchState` / `HMC_GetNormalSwitchState` (digest 000 §4.4): 0 working, 3 idle (done
/// or not configured).
pub fn switch_state(c: Option<&CompareStatus>) -> u8 {
    match c.map(|c| c.state) {
        Some(CompareState::Running) => 0,
        Some(CompareState::Done) | None => 3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_status::with;
    use axes::AxisFlags;

    #[test]
    fn axis_status_bits_follow_table_2() {
        assert_eq!(axis_status(&with(AxisFlags::empty())), 0);
        assert_eq!(
            axis_status(&with(AxisFlags::FE_FAULT)),
            AXIS_STATUS_FE_FAULT
        );
        assert_eq!(
            axis_status(&with(AxisFlags::FE_WARNING)),
            AXIS_STATUS_FE_WARNING
        );
        assert_eq!(
            axis_status(&with(AxisFlags::PARAMETER_ERROR)),
            AXIS_STATUS_PARAMETER_ERROR
        );
        for limit in [
            AxisFlags::HW_LIMIT_POS,
            AxisFlags::HW_LIMIT_NEG,
            AxisFlags::SW_LIMIT_POS,
            AxisFlags::SW_LIMIT_NEG,
        ] {
            assert_eq!(axis_status(&with(limit)), AXIS_STATUS_LIMIT, "{limit}");
        }
        // Flags the word does not show.
        assert_eq!(
            axis_status(&with(
                AxisFlags::ENABLED | AxisFlags::MOVING | AxisFlags::HOMED
            )),
            0
        );
    }

    #[test]
    fn limit_state_bits_follow_the_digest() {
        for (flag, bit) in [
            (AxisFlags::HW_LIMIT_POS, LIMIT_FORWARD_HARD),
            (AxisFlags::HW_LIMIT_NEG, LIMIT_REVERSE_HARD),
            (AxisFlags::SW_LIMIT_POS, LIMIT_FORWARD_SOFT),
            (AxisFlags::SW_LIMIT_NEG, LIMIT_REVERSE_SOFT),
            (AxisFlags::SW_LIMIT_CONFIG, LIMIT_SOFT_CONFIG),
            (AxisFlags::BOTH_LIMITS, LIMIT_BOTH),
        ] {
            assert_eq!(limit_state(&with(flag)), bit, "{flag}");
        }
        assert_eq!(
            limit_state(&with(AxisFlags::HW_LIMIT_POS | AxisFlags::SW_LIMIT_NEG)),
            LIMIT_FORWARD_HARD | LIMIT_REVERSE_SOFT
        );
    }

    #[test]
    fn every_refusal_is_the_parameter_error_code() {
        let e = EngineError::Unsupported { what: "x".into() };
        assert_eq!(code_for(&e), 0xFFFF_FFFF);
    }

    #[test]
    fn capture_and_switch_states_follow_section_4_4() {
        // Digest 000 §8 vector 31: outside the window 1, waiting 2, captured 3.
        let mut c = CaptureStatus {
            axis: 0,
            channel: 0,
            source: axes::status::CaptureSource::Index,
            source_axis: 0,
            input: None,
            edge: Default::default(),
            repeat: 1,
            continuous: false,
            window: None,
            state: CaptureState::OutsideWindow,
            count: 0,
            latches: vec![],
        };
        assert_eq!(capture_state(Some(&c)), 1);
        c.state = CaptureState::Waiting;
        assert_eq!(capture_state(Some(&c)), 2);
        c.state = CaptureState::Done;
        assert_eq!(capture_state(Some(&c)), 3);
        assert_eq!(capture_state(None), 3);
        // Vector 32: 0 while active, 3 after the 10th target.
        let mut s = CompareStatus::default();
        assert_eq!(switch_state(Some(&s)), 0);
        s.state = CompareState::Done;
        assert_eq!(switch_state(Some(&s)), 3);
        assert_eq!(switch_state(None), 3);
    }

    #[test]
    fn clc_jerk_is_curvature_squared_times_speed_cubed_vector_36() {
        // Digest 000 TV 36: 1/(100·√2) at 1000 → 50000; 1/(50·√2) → 200000; negative → −1.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
        assert!(close(
            clc_jerk(1.0 / (100.0 * 2f64.sqrt()), 1000.0),
            50_000.0
        ));
        assert!(close(
            clc_jerk(1.0 / (50.0 * 2f64.sqrt()), 1000.0),
            200_000.0
        ));
        assert_eq!(clc_jerk(0.0, 1000.0), 0.0);
        for (k, v) in [
            (-1e-3, 1000.0),
            (1e-3, -1.0),
            (f64::NAN, 1.0),
            (1.0, f64::INFINITY),
        ] {
            assert_eq!(clc_jerk(k, v), -1.0, "({k}, {v})");
        }
    }
}
