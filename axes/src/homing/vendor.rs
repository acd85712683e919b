//! Vendor homing modes mapped onto CiA 402 methods with their quirks, and the vendors' homing
//! status values as functions of [`HomingStatus`].
//!
//! Every function takes the vendor's parameters already converted to engine units (user units,
//! seconds) by the dialect, and returns the [`HomingSpec`] to start. Errors that the vendor
//! reports as "bad parameter" come back as [`HomingError`]s; whatever the table leaves to the
//! machine (speeds ≤ 0, missing inputs) is refused by [`super::Homing::start`].

use super::{
    AfterHome, HomingError, HomingFailure, HomingPhase, HomingQuirks, HomingSpec, HomingStatus,
    Latch,
};
use serde::{Deserialize, Serialize};

fn bad(name: &str, value: f64, requirement: &str) -> HomingError {
    HomingError::BadParameter {
        name: name.to_owned(),
        value,
        requirement: requirement.to_owned(),
    }
}

/// Errors a vendor reports as a parameter error rather than as a failed search.
fn is_parameter_error(e: &HomingError) -> bool {
    matches!(
        e,
        HomingError::UnsupportedMethod { .. }
            | HomingError::MissingInput { .. }
            | HomingError::BadParameter { .. }
    )
}

// ---- Hollysys HMC (digest 000 §5, §2.7) ----

/// Which HMC instruction started the homing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HmcInstruction {
    /// HMC_Home: the DI and Z are polled once per servo period.
    Home,
    /// HMC_HomeEx: the origin comes from the hardware capture latch.
    HomeEx,
}

/// HMC mode (index) → CiA 402 method. 0: DI, search +, origin at the falling edge while creeping
/// back (19); 1: the mirror (21); 2/3: Z only, + / − (34/33); 4/5: DI then the first Z after the
/// falling edge (3/5). Digest 000 §5.
pub const HMC_METHODS: [i16; 6] = [19, 21, 34, 33, 3, 5];

/// HMC_Home / HMC_HomeEx `mode` with the axis's `Speed` (phase-1 search), `CreepSpeed`
/// (creep back; the whole search of the Z-only modes) and `Accel` (all ramps; the machine has one
/// acceleration, so `Decel` is not used). No offset and no timeout exist (digest 000 §9.5
/// item 21): the origin reads 0 and the axis returns to it.
pub fn hmc(
    instruction: HmcInstruction,
    mode: u8,
    speed: f64,
    creep_speed: f64,
    accel: f64,
) -> Result<HomingSpec, HomingError> {
    let method =
        HMC_METHODS
            .get(usize::from(mode))
            .copied()
            .ok_or(HomingError::UnsupportedMethod {
                method: i16::from(mode),
            })?;
    let latch = match instruction {
        HmcInstruction::Home => Latch::Polled,
        HmcInstruction::HomeEx => Latch::Exact,
    };
    Ok(HomingSpec {
        method,
        switch_velocity: speed,
        zero_velocity: creep_speed,
        acceleration: accel,
        offset: 0.0,
        timeout: 0.0,
        quirks: HomingQuirks {
            // "set origin here, decelerate to stop, return to the origin position" (§5).
            after_home: AfterHome::ReturnToHome,
            switch_latch: latch,
            index_latch: latch,
            ..HomingQuirks::default()
        },
    })
}

/// The HMC `HomeState` parameter (0–4, digest 000 §2.7) for an axis homing with `mode`.
/// 1 searching, 2 found the DI (Z for modes 2/3) and decelerating, 3 creeping back for the
/// falling edge / Z, 4 found it and decelerating; the return leg still reads 4 (2 for the Z-only
/// modes, which have no creep phase); 0 idle, done or failed.
pub fn hmc_home_state(mode: u8, status: &HomingStatus) -> u8 {
    let HomingStatus::Running(phase) = status else {
        return 0;
    };
    let z_only = matches!(mode, 2 | 3);
    match phase {
        HomingPhase::Backoff | HomingPhase::Search => 1,
        HomingPhase::Index if z_only => 1,
        HomingPhase::Stopping | HomingPhase::Returning if z_only => 2,
        HomingPhase::Reversing => 2,
        HomingPhase::Approach | HomingPhase::Rescan | HomingPhase::Index => 3,
        HomingPhase::Stopping | HomingPhase::Returning => 4,
        HomingPhase::Aborting => 0,
    }
}

// ---- Gaochuan NMC (digest 001 §2.6, §3.13, §3.14, §4.5) ----

/// `THomeSetting` (digest 001 §3.13) in engine units. `mode` is `HM_MODE1`..`HM_MODE6` (1–6,
/// the header values are not in the manual) or `1000 + method` (CiA 402 pass-through).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NmcHomeSetting {
    pub mode: i16,
    /// 0 negative, 1 positive.
    pub dir: i16,
    pub offset: f64,
    pub scan1st_vel: f64,
    pub scan2nd_vel: f64,
    pub acc: f64,
    pub rescan_en: bool,
    /// `homeEdge`, `lmtEdge`, `zEdge` describe the wiring (which electrical edge means
    /// "activated", digest 001 §4.5); the axis applies them as input polarity, so the mapping
    /// does not use them.
    pub home_edge: u8,
    pub lmt_edge: u8,
    pub z_edge: u8,
    pub ini_ret_pos: f64,
    pub ret_sw_offset: f64,
    pub safe_len: f64,
}

/// `THomeSetting.mode` values above this pass a CiA 402 method through (digest 001 §2.6).
pub const NMC_PASS_THROUGH: i16 = 1000;

/// `NMC_MtGetHomeSts` bits (digest 001 §3.13).
pub const NMC_HOME_RUNNING: u16 = 1 << 0;
pub const NMC_HOME_OK: u16 = 1 << 1;
pub const NMC_HOME_FAIL: u16 = 1 << 2;
/// Bad motion parameters: homing did not move.
pub const NMC_HOME_ERR_MV: u16 = 1 << 3;
/// The switch did not trigger during the search.
pub const NMC_HOME_ERR_SWT: u16 = 1 << 4;

/// NMC_MtHome with `setting`. For NMC_MtTryHome set `quirks.trial` on the result.
///
/// HM_MODE1..6 run on the controller: MODE1 homes where the home switch activates while moving
/// in `dir`, reversing at the limit in `dir` (24 / 28); MODE2 on the limit in `dir` (18 / 17);
/// MODE3 on the next index in `dir` (34 / 33); MODE4 on the next index forward after the home
/// switch (8 / 12); MODE5 on the next index in reverse after it (7 / 11); MODE6 on the next index
/// in reverse after the limit (2 / 1). The first search runs at `scan1stVel`; `scan2ndVel` is the
/// index search and the second scan (`reScanEn`), and MODE1–3 without a second scan use
/// `scan1stVel` throughout. `offset` moves the zero: the new zero is `offset` past the found
/// point, so that point reads −offset (digest 001 §4.5 step 5). `1000 + method` is a drive's
/// CiA 402 homing: `scan1stVel`/`scan2ndVel` are 0x6099:01/02 and `offset` is 0x607C (the home
/// point reads +offset).
pub fn nmc(setting: &NmcHomeSetting) -> Result<HomingSpec, HomingError> {
    let s = setting;
    if s.mode > NMC_PASS_THROUGH {
        return Ok(HomingSpec {
            method: s.mode - NMC_PASS_THROUGH,
            switch_velocity: s.scan1st_vel,
            zero_velocity: s.scan2nd_vel,
            acceleration: s.acc,
            offset: s.offset,
            timeout: 0.0,
            quirks: HomingQuirks::default(),
        });
    }
    let positive = match s.dir {
        0 => false,
        1 => true,
        d => return Err(bad("dir", f64::from(d), "0 (negative) or 1 (positive)")),
    };
    let method = match (s.mode, positive) {
        (1, true) => 24,
        (1, false) => 28,
        (2, true) => 18,
        (2, false) => 17,
        (3, true) => 34,
        (3, false) => 33,
        (4, true) => 8,
        (4, false) => 12,
        (5, true) => 7,
        (5, false) => 11,
        (6, true) => 2,
        (6, false) => 1,
        _ => return Err(HomingError::UnsupportedMethod { method: s.mode }),
    };
    if !(s.scan1st_vel.is_finite() && s.scan1st_vel > 0.0) {
        return Err(bad("scan1stVel", s.scan1st_vel, "must be positive"));
    }
    let second = s.rescan_en || (4..=6).contains(&s.mode);
    let zero_velocity = if second {
        if !(s.scan2nd_vel.is_finite() && s.scan2nd_vel > 0.0) {
            return Err(bad(
                "scan2ndVel",
                s.scan2nd_vel,
                "must be positive for the index search and the second scan",
            ));
        }
        s.scan2nd_vel
    } else {
        s.scan1st_vel
    };
    Ok(HomingSpec {
        method,
        switch_velocity: s.scan1st_vel,
        zero_velocity,
        acceleration: s.acc,
        offset: -s.offset,
        timeout: 0.0,
        quirks: HomingQuirks {
            // The controller captures the encoder position at the edge (§4.5).
            switch_latch: Latch::Exact,
            index_latch: Latch::Exact,
            max_search_distance: s.safe_len,
            initial_backoff: s.ini_ret_pos,
            rescan: s.rescan_en.then_some(s.ret_sw_offset),
            ..HomingQuirks::default()
        },
    })
}

/// `NMC_MtGetHomeSts`. A failure always sets bit 2; parameter errors (nothing moved) add bit 3,
/// a search that ended without its switch or index (search distance, a limit, a sweep between
/// the limits) adds bit 4. An abort (NMC_MtHomeStop) is a plain failure.
pub fn nmc_home_status(status: &HomingStatus) -> u16 {
    match status {
        HomingStatus::Idle => 0,
        HomingStatus::Running(_) => NMC_HOME_RUNNING,
        HomingStatus::Succeeded => NMC_HOME_OK,
        HomingStatus::Failed(e) => nmc_home_failure(e.failure()),
    }
}

/// The `NMC_MtGetHomeSts` word of a failed homing (see [`nmc_home_status`]).
pub fn nmc_home_failure(failure: HomingFailure) -> u16 {
    match failure {
        HomingFailure::UnsupportedMethod
        | HomingFailure::MissingInput
        | HomingFailure::BadParameter => NMC_HOME_FAIL | NMC_HOME_ERR_MV,
        HomingFailure::NotFound | HomingFailure::LimitHit => NMC_HOME_FAIL | NMC_HOME_ERR_SWT,
        HomingFailure::Timeout | HomingFailure::Aborted => NMC_HOME_FAIL,
    }
}

/// `NMC_EcatGetHomeSts` (digest 001 §3.14): the CiA 402 statusword bits 13/12/10 (error,
/// attained, target reached) as bits 2/1/0. 000 searching; 010 found, still stopping; 011 done;
/// 100 failed, still stopping; 101 failed at rest; 001 not started or interrupted
/// (NMC_EcatStopHome).
pub fn nmc_ecat_home_status(status: &HomingStatus) -> u8 {
    match status {
        HomingStatus::Idle | HomingStatus::Failed(HomingError::Aborted) => 0b001,
        HomingStatus::Running(HomingPhase::Stopping | HomingPhase::Returning) => 0b010,
        HomingStatus::Running(HomingPhase::Aborting) => 0b100,
        HomingStatus::Running(_) => 0b000,
        HomingStatus::Succeeded => 0b011,
        HomingStatus::Failed(_) => 0b101,
    }
}

// ---- HIWIN HIMC (digest 004 §4) ----

/// The methods `SetHomeMethod` accepts (digest 004 §4.3); 3–6, 19–22 and 35 are refused.
pub const HIMC_METHODS: [i16; 23] = [
    1, 2, 7, 8, 9, 10, 11, 12, 13, 14, 17, 18, 23, 24, 25, 26, 27, 28, 29, 30, 33, 34, 37,
];

pub fn himc_method_supported(method: i16) -> bool {
    HIMC_METHODS.contains(&method)
}

/// The homing settings of one HIMC axis (SetHomeMethod, SetHomeSwitchVel, SetHomeZeroVel,
/// SetHomeAcc, SetHomeOffset, SetHomeTimeout), in engine units; the timeout in ms as the API
/// takes it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HimcHomeSettings {
    pub method: i16,
    pub switch_vel: f64,
    pub zero_vel: f64,
    pub acc: f64,
    pub offset: f64,
    pub timeout_ms: f64,
}

impl Default for HimcHomeSettings {
    /// HOME_METHOD_33, 20, 5, 2000, 0, 120 000 ms (digest 004 §4.2).
    fn default() -> Self {
        HimcHomeSettings {
            method: 33,
            switch_vel: 20.0,
            zero_vel: 5.0,
            acc: 2000.0,
            offset: 0.0,
            timeout_ms: 120_000.0,
        }
    }
}

/// MoveHome: the drive's CiA 402 homing (digest 004 §4.1), so plain drive behaviour: exact
/// latch, decelerate after the home point, which reads `offset` (method 37: 6064h = 607Ch).
/// Methods outside [`HIMC_METHODS`] are refused as SetHomeMethod refuses them (TV 75).
pub fn himc(settings: &HimcHomeSettings) -> Result<HomingSpec, HomingError> {
    let s = settings;
    if !himc_method_supported(s.method) {
        return Err(HomingError::UnsupportedMethod { method: s.method });
    }
    Ok(HomingSpec {
        method: s.method,
        switch_velocity: s.switch_vel,
        zero_velocity: s.zero_vel,
        acceleration: s.acc,
        offset: s.offset,
        timeout: s.timeout_ms / 1000.0,
        quirks: HomingQuirks::default(),
    })
}

// ---- Co-Trust CPU 226H (digest 003 §2.1, §3) ----

/// MC_HOMING `HOMING_MODE` 1–14 (index + 1) → CiA 402 method. 1/2: home switch on the negative /
/// positive side, then the next Z leaving it (5 / 3); 3/4: the same, origin at the switch's
/// falling edge (21 / 19); 5/6: Z only, − / + (33 / 34); 7–14: CiA 402 7–14 (digest 003 §3).
pub const CPU226H_METHODS: [i16; 14] = [5, 3, 21, 19, 33, 34, 7, 8, 9, 10, 11, 12, 13, 14];

/// Pulse output range of a CPU 226H axis, Hz (digest 003 §2.0: below 5 Hz nothing is output).
const CPU226H_SPEED: (f64, f64) = (5.0, 200_000.0);

/// `STATUS` bits of MC_HOMING (digest 003 §2.0).
pub const CPU226H_PARAMETER_ERROR: u8 = 1 << 0;
pub const CPU226H_RUNNING: u8 = 1 << 1;
pub const CPU226H_DONE: u8 = 1 << 2;
pub const CPU226H_ORIGIN_FOUND: u8 = 1 << 5;

/// MC_HOMING with `SEARCH_SPEED` (switch search), `APPROACH_SPEED` (moving out of the switch and
/// the Z search), the acceleration the dialect derived from TA, and the PLC scan in servo ticks.
/// Speeds are in pulses/s (1 pulse = 1 unit on this PLC) and are clamped, never refused
/// (digest 003 §2.0). The switches are scanned, the Z is captured in hardware (§2.1 ④, TV-30); at
/// the origin the motor stops immediately and the origin reads 0 (§3).
pub fn cpu226h(
    mode: u8,
    search_speed: f64,
    approach_speed: f64,
    acceleration: f64,
    scan_ticks: u32,
) -> Result<HomingSpec, HomingError> {
    let method = usize::from(mode)
        .checked_sub(1)
        .and_then(|i| CPU226H_METHODS.get(i))
        .copied()
        // Mode 0 or 15+: STATUS.Bit0 (TV-25).
        .ok_or(HomingError::UnsupportedMethod {
            method: i16::from(mode),
        })?;
    let clamp = |v: f64| v.clamp(CPU226H_SPEED.0, CPU226H_SPEED.1);
    Ok(HomingSpec {
        method,
        switch_velocity: clamp(search_speed),
        zero_velocity: clamp(approach_speed),
        acceleration,
        offset: 0.0,
        timeout: 0.0,
        quirks: HomingQuirks {
            after_home: AfterHome::StopImmediately,
            switch_latch: Latch::Polled,
            index_latch: Latch::Exact,
            switch_scan_ticks: scan_ticks,
            ..HomingQuirks::default()
        },
    })
}

/// MC_HOMING `STATUS`: bit 0 parameter error (nothing moved), bit 1 running, bit 2 done,
/// bit 5 origin found. A search that failed after moving is done without an origin.
pub fn cpu226h_status(status: &HomingStatus) -> u8 {
    match status {
        HomingStatus::Idle => 0,
        HomingStatus::Running(_) => CPU226H_RUNNING,
        HomingStatus::Succeeded => CPU226H_DONE | CPU226H_ORIGIN_FOUND,
        HomingStatus::Failed(e) if is_parameter_error(e) => CPU226H_PARAMETER_ERROR,
        HomingStatus::Failed(_) => CPU226H_DONE,
    }
}

#[cfg(test)]
mod tests;
