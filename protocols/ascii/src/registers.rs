//! [`Registers`]: what the controller keeps beside the engine for HMPL: the last error of the
//! system, of each axis and of each group (chapter 18), and the axis settings the engine does
//! not hold (buffer mode, op mode, the homed flag `SetHomedStatus` sets).

use std::collections::BTreeMap;

use mcemu_dialects::himc::group::ProfileValues;
use mcemu_dialects::himc::{AXIS_CLASS, GROUP_CLASS};

/// The controller's registers, shared by every Native ASCII client.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Registers {
    /// `GetSystemLastErr` (§18.2).
    pub system_error: u32,
    /// `GetAxisLastErr` by axis (§18.3).
    pub axis_errors: BTreeMap<u16, u32>,
    /// `GetGrpLastErr` by group (§18.5).
    pub group_errors: BTreeMap<u16, u32>,
    /// `SetBufferMode` by axis: 0 immediate, 1 buffered (§5.3.42; absent: 0).
    pub buffer_modes: BTreeMap<u16, i64>,
    /// `SetOpMode` by axis (§5.3.41; absent: 8, CSP).
    pub op_modes: BTreeMap<u16, i64>,
    /// `SetHomedStatus` by axis (§20.9): overrides the engine's homed flag until the next
    /// homing.
    pub homed: BTreeMap<u16, bool>,
    /// `AddAxisToGrp` by group: the members in the order added, {X, Y, Z, A, B, C} (§8.3.1).
    pub group_members: BTreeMap<u16, Vec<u16>>,
    /// `SetGrpMotionProfile` by group (absent: the defaults, TV 48).
    pub group_profiles: BTreeMap<u16, ProfileValues>,
    /// `SetGrpCoordSys` by group: the `CS_*` mask (absent: `CS_MCS`, 0).
    pub group_coordinate_systems: BTreeMap<u16, i64>,
}

impl Registers {
    /// Latch `code` where its class says: 0x83NN… in axis NN's register, 0x82NN… in group NN's,
    /// anything else in the system's.
    pub fn latch(&mut self, code: u32) {
        let [class, id, _, _] = code.to_be_bytes();
        match class {
            AXIS_CLASS => {
                self.axis_errors.insert(u16::from(id), code);
            }
            GROUP_CLASS => {
                self.group_errors.insert(u16::from(id), code);
            }
            _ => self.system_error = code,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_latch_by_class() {
        let mut r = Registers::default();
        r.latch(0x8302_07da);
        r.latch(0x8200_03fc);
        r.latch(0x1451);
        assert_eq!(r.axis_errors.get(&2), Some(&0x8302_07da));
        assert_eq!(r.group_errors.get(&0), Some(&0x8200_03fc));
        assert_eq!(r.system_error, 0x1451);
    }
}
