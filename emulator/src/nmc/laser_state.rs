//! The laser, SHIO and PWM settings of an NMC device (digest 001 §2.12, §3.20). mcemu has no
//! laser source, PWM generator or high-speed gate: what is written is stored and read back,
//! and the outputs a real card drives are echoed on the machine's I/O image
//! (`crate::nmc::handlers::laser` says which; docs/decisions.md "NMC laser, SHIO and PWM").

use std::collections::BTreeMap;

use mcemu_nmc::laser::{LaserPower, ShioPara, TimeArrayPara};

/// Laser channels (`ch` ∈ [0, 1]); SHIO and the gate have channel 0 only ("目前只为 0").
pub const LASER_CHANNELS: usize = 2;
/// Power compensation tables ("支持 20 张表").
pub const CMP_TABLES: usize = 20;

/// `NMC_SetLaserPowerCmpTable`: the grid and its powers (row-major, x fastest).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CmpTable {
    pub x: Vec<i64>,
    pub y: Vec<i64>,
    pub power_min: u64,
    pub power_max: u64,
    pub power: Vec<u64>,
}

/// One laser channel.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LaserChannel {
    /// `LASER_DISABLE_MODE` 0 … `SHIO_OUTPUT_MODE` 3.
    pub mode: i16,
    /// `LASER_NONE` 0 … `LASER_PWM_FRQ_EXT` 4, the output `index` and the type's option
    /// (PWM frequency, duty or pulse width).
    pub output_type: i16,
    pub index: i16,
    pub option: f64,
    /// µs.
    pub on_delay: i64,
    pub off_delay: i64,
    pub min_value: i64,
    pub max_value: i64,
    pub standby_power: i64,
    pub power: f64,
    /// On/off when the channel has no output image (LASER_NONE); otherwise its output's level.
    pub on: bool,
    pub follow_filter: i16,
    pub follow_mode: i16,
    /// `NMC_CrdBufLaserSetFollow`: override (0 off) and type (0 planned, 1 actual velocity).
    pub follow_override: f64,
    pub follow_type: i16,
    pub time_array: TimeArrayPara,
    /// `NMC_StartLaserPowerComp`'s axes while the compensation runs.
    pub comp_axes: Option<[i16; 2]>,
    /// `NMC_SetPWMPort`: 0 the channel's own pin, 1 general output `pwm_port_idx`.
    pub pwm_port_type: i16,
    pub pwm_port_idx: i16,
    /// `NMC_PwmPulseOut`: on time µs, frequency Hz, count (0 continuous).
    pub pwm_pulse: Option<(f64, f64, i64)>,
}

/// The SHIO channel (0).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Shio {
    pub para: ShioPara,
    /// Hz while the minimum-frequency function is on.
    pub min_frq: Option<i64>,
    /// `NMC_SHIOTriggerOn`: frequency Hz, width s.
    pub trigger: Option<(f64, f64)>,
    /// `NMC_SHIOGatePulse`: gate time µs, frequency Hz, count (0 continuous).
    pub gate_pulse: Option<(f64, f64, i64)>,
    /// `NMC_SetPwmToGate(0, 0, 1)`: PWM 0 comes out on the gate pin.
    pub pwm_to_gate: bool,
}

/// The device's laser state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LaserState {
    pub channels: [LaserChannel; LASER_CHANNELS],
    /// `NMC_LaserSetTimeArrayPower` by group [0, 11].
    pub power_arrays: BTreeMap<i16, LaserPower>,
    pub cmp_tables: BTreeMap<i16, CmpTable>,
    pub shio: Shio,
}
