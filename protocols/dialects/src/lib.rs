//! Vendor dialects, keyed by vendor and not by wire protocol (ARCHITECTURE §3.4, §5): each
//! module holds one controller family's tables, as pure functions of the engine's
//! vendor-neutral records ([`axes::AxisStatus`], [`axes::EngineError`] …) plus, where a vendor
//! bit needs state the engine does not keep, that state as an argument.
//!
//! - [`hmc`]: Hollysys HMC (digest 000): AxisStatus/LimitState words, return codes.
//! - [`himc`]: HIWIN HIMC (digest 004): `Is*` predicates, 0xCCNNVVVV error codes, units.
//! - [`nmc`]: Gaochuan NMC (digest 001): `BIT_AXIS_*` status word, return codes, units.
//! - [`cpu226h`]: Co-Trust CPU 226H and its E10 servo (digest 003): STATUS byte, units.
//! - [`cia402`]: CiA 301/402 (the standard CANopen drives speak): SDO abort codes.
//! - [`modbus`]: the Modbus exception an engine refusal becomes, for every register map.
//!
//! A front-end calls the functions of the vendor it emulates; no module here knows a socket or
//! a frame, and nothing here depends on another protocol crate.

pub mod cia402;
pub mod cpu226h;
pub mod himc;
pub mod hmc;
pub mod modbus;
pub mod nmc;

/// An axis's pulse scale, for the dialects that count in pulses (NMC, CPU 226H; ARCHITECTURE
/// §3.2): pulses per engine user unit, the axis's `units × Ks`, which the front-end reads from
/// the axis parameters. The same factor converts positions (pulse ↔ unit) and per-second rates
/// (pulse/s ↔ unit/s, pulse/s² ↔ unit/s²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PulseScale {
    pub pulses_per_unit: f64,
}

impl PulseScale {
    /// Pulses (or pulses per second, per second²) in user units (per second, per second²).
    pub fn to_engine(self, pulses: f64) -> f64 {
        pulses / self.pulses_per_unit
    }

    /// User units (per second, per second²) in pulses (per second, per second²).
    pub fn from_engine(self, units: f64) -> f64 {
        units * self.pulses_per_unit
    }
}

/// The number a vendor's code name stands for, for files that name codes instead of writing
/// numbers (a register map's `value = "eERR_AXIS_DRIVE_FAULT"`). Names are unique across
/// vendors (each vendor has its own prefix).
pub fn code_by_name(name: &str) -> Option<u32> {
    himc::AxisError::by_name(name).map(|e| u32::from(e.value))
}

/// Status records for the dialects' tests.
#[cfg(test)]
pub(crate) mod test_status {
    use axes::{AxisFlags, AxisState, AxisStatus};

    /// A status with only `state` and `flags` set.
    pub fn status(state: AxisState, flags: AxisFlags) -> AxisStatus {
        AxisStatus {
            state,
            flags,
            ..AxisStatus::default()
        }
    }

    /// A standstill status with `flags`.
    pub fn with(flags: AxisFlags) -> AxisStatus {
        status(AxisState::Standstill, flags)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pulse_scale_converts_both_ways() {
        let s = PulseScale {
            pulses_per_unit: 1000.0,
        };
        assert_eq!(s.to_engine(2500.0), 2.5);
        assert_eq!(s.from_engine(2.5), 2500.0);
    }

    #[test]
    fn a_himc_axis_error_name_gives_its_low_word() {
        assert_eq!(code_by_name("eERR_AXIS_DRIVE_FAULT"), Some(0x03f2));
        assert_eq!(code_by_name("eWRN_AXIS_VEL_LIMIT"), Some(0x4456));
        assert_eq!(code_by_name("eERR_AXIS_NO_SUCH_THING"), None);
    }
}
