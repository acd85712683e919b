//! NMC settings the engine has no model of, kept and read back (digest 001 §2.3; decisions.md,
//! "NMC basic configuration"): the pulse-output mode and filter, the velocity filter, the
//! encoder mode words. They are the device's, shared by its connections.

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

/// The device's stored settings.
#[derive(Clone, Debug, Default)]
pub struct Stored {
    pub axes: BTreeMap<usize, AxisStored>,
    /// `NMC_SetEncMode` words by encoder channel (default 0x0100, internal: digest 001 §6).
    pub enc_mode: BTreeMap<u8, u16>,
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
