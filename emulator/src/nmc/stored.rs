//! NMC settings the engine has no model of, kept and read back (digest 001 §2.3; decisions.md,
//! "NMC basic configuration"): the pulse-output mode and filter, the velocity filter, the
//! encoder mode words, the analog channels' ranges, raw values, bias and limits. They are the device's, shared by its connections.

use std::collections::BTreeMap;

/// One axis's stored settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AxisStored {
    /// `NMC_MtSetStepMode`: inv 0/1, mode 0 pulse+dir / 1 CW/CCW (default 0, 0, TV08).
    pub step_inv: i16,
    pub step_mode: i16,
    /// `NMC_MtSetStepFilter` 0–65535 (default 0, TV08).
    pub step_filter: u16,
    /// `NMC_MtSetAxisVelFilter` [0, 5] ms (default 0).
    pub vel_filter: i16,
}

/// One analog output's settings (digest 001 §2.8): the engine keeps only its voltage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DacStored {
    /// `NMC_SetDacMode` range code 0–5 (default 4, ±10 V, TV41).
    pub mode: i16,
    /// The raw value last written (`NMC_GetDac` reads it back, TV41).
    pub raw: i16,
    pub bias: i16,
    pub max: i16,
    pub min: i16,
}

impl Default for DacStored {
    fn default() -> DacStored {
        DacStored {
            mode: 4,
            raw: 0,
            bias: 0,
            max: i16::MAX,
            min: i16::MIN,
        }
    }
}

/// One analog input's settings: range code (default 4) and filter [0, 64] ms (default 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AdcStored {
    pub range: i16,
    pub filter: i16,
}

impl Default for AdcStored {
    fn default() -> AdcStored {
        AdcStored {
            range: 4,
            filter: 0,
        }
    }
}

/// The device's stored settings.
#[derive(Clone, Debug, Default)]
pub struct Stored {
    pub axes: BTreeMap<usize, AxisStored>,
    /// `NMC_SetEncMode` words by encoder channel (default 0x0100, internal: digest 001 §6).
    pub enc_mode: BTreeMap<u8, u16>,
    pub dac: BTreeMap<usize, DacStored>,
    pub adc: BTreeMap<usize, AdcStored>,
    /// The EtherCAT master (GCE cards): the `.gml` name last loaded, and whether it runs.
    pub ecat_config: Option<String>,
    pub ecat_started: bool,
    /// The user parameter areas (`NMC_UserParaWr`, `…Ex`), zero until written; saved in the
    /// state directory (`user_para_file`, decisions.md).
    pub user_para: Vec<u8>,
    pub user_para_ex: Vec<u8>,
    /// The laser, SHIO and PWM settings (`crate::nmc::laser_state`).
    pub laser: super::laser_state::LaserState,
}

/// The encoder mode of a channel never written: internal pulse counting (digest 001 §6).
pub const DEFAULT_ENC_MODE: u16 = 0x0100;

impl Stored {
    pub fn axis(&self, axis: usize) -> AxisStored {
        self.axes.get(&axis).copied().unwrap_or_default()
    }

    pub fn axis_mut(&mut self, axis: usize) -> &mut AxisStored {
        self.axes.entry(axis).or_default()
    }
}
