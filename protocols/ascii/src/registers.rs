//! [`Registers`]: what the controller keeps beside the engine for HMPL: the last error of the
//! system, of each axis and of each group (chapter 18), and the settings the engine does not
//! hold (axis buffer and op modes, the homed flag `SetHomedStatus` sets, group members,
//! profiles and modes, gear links, gantry pairs, slave output images, analog conversion types,
//! the user table, PT, touch-probe and filter settings).

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
    /// `SetGrpAngMotionProfile` by group (absent: the defaults, TV 49).
    pub group_angular_profiles: BTreeMap<u16, ProfileValues>,
    /// `SetGrpBufferMode` by group, `BM_*` (absent: `BM_BUFF`).
    pub group_buffer_modes: BTreeMap<u16, i64>,
    /// `SetGrpTransMode` by group, `TM_*` (absent: `TM_NONE`).
    pub group_transition_modes: BTreeMap<u16, i64>,
    /// `SetGrpTransPrm` by group.
    pub group_transition_parameters: BTreeMap<u16, TransitionParameters>,
    /// `SetGrpCoordTrans` by (group, `CS_*` mask): {X, Y, Z, A, B, C}.
    pub group_transforms: BTreeMap<(u16, i64), [f64; 6]>,
    /// `SetGrpLookAheadPrm` by (group, prm_id).
    pub group_lookahead: BTreeMap<(u16, u8), f64>,
    /// The group limits `SetConfigVar` lowered, by (group, HCV address 0x00ca … 0x00d6;
    /// absent: the profile's maximum, §8.3.6–8.3.7).
    pub group_limits: BTreeMap<(u16, u16), f64>,
    /// `SetGrpQueueSize` by group: n of 2ⁿ entries.
    pub group_queue_sizes: BTreeMap<u16, u8>,
    /// The digital outputs (0x60FE:1) the controller writes to each drive (`SetSlvGPO`).
    pub slave_outputs: BTreeMap<u16, u32>,
    /// `SetSlvAIType` / `SetSlvAOType` by analog channel (absent: `HMPL_DAC_NONE`).
    pub ai_types: BTreeMap<u16, i64>,
    pub ao_types: BTreeMap<u16, i64>,
    /// `SetSlvAOMonitor` by analog output: the variable id.
    pub ao_monitors: BTreeMap<u16, i64>,
    /// `SetSlvAOParam` by analog output: scale and offset (absent: 1, 0).
    pub ao_scales: BTreeMap<u16, (f64, f64)>,
    /// Analog outputs bound to their monitor variable (`SetSlvAOParam` `ao_en_bind` 1).
    pub ao_bound: std::collections::BTreeSet<u16>,
    /// `ForceWritePDO` objects (slave, index, subindex) not yet released.
    pub forced_pdos: std::collections::BTreeSet<(i64, i64, i64)>,
    /// The user table (§11.1), sparse: an entry not here is 0.
    pub user_table: BTreeMap<u32, f64>,
    /// What `SaveUserTable` wrote (the controller's disk), sparse.
    pub saved_user_table: BTreeMap<u32, f64>,
    /// `SetPT_*` by axis.
    pub pt: BTreeMap<u16, PtSettings>,
    /// `SetTouchProbeNFunc` by (axis, probe 0/1).
    pub probe_functions: BTreeMap<(u16, u8), ProbeFunction>,
    /// `SetAxisVsf`, `SetAxisInShape` (by axis), `SetGrpInShape` (by group).
    pub filters: BTreeMap<(Filter, u16), FilterSettings>,
    /// The filters `Enable*` switched on (in the engine), by (filter, axis or group).
    pub filters_on: std::collections::BTreeSet<(Filter, u16)>,
    /// `EnableGantryPair`: RHS → LHS (§7.2).
    pub gantry_pairs: BTreeMap<u16, u16>,
    /// Axes `EnableComp` switched on (`IsCompActive`).
    pub compensating: std::collections::BTreeSet<u16>,
    /// `SetCompAlgType(axis, 1)`: axes whose compensation is a cubic spline (§14.8).
    pub compensation_cubic: std::collections::BTreeSet<u16>,
    /// The last `SetupComp` table command by axis, re-sent when the algorithm changes.
    pub compensation_tables: BTreeMap<u16, serde_json::Value>,
    /// `EnableGear` links, slave → master (§6.2); `DisableGear` removes them.
    pub gear_links: BTreeMap<u16, u16>,
    /// The last `GearIn` ratio by slave (`GetGearRatio` after `GearOut`).
    pub gear_ratios: BTreeMap<u16, f64>,
    /// `SetGPIInvert` / `SetGPOInvert`: the controller pins (1-based) inverted (§9.2.4–5).
    pub gpi_inverted: std::collections::BTreeSet<usize>,
    pub gpo_inverted: std::collections::BTreeSet<usize>,
    /// `BindEMO`'s pin (§9.2.6): absent = never called, the default GPI 8; 0 = none.
    pub emo_pin: Option<usize>,
    /// `SetConfigVar` of the free variables `HCV_ID_ltest0…9`, `HCV_ID_dtest0…9` by id
    /// (digest 004 §1.11; an absent one is 0).
    pub free_variables: BTreeMap<u32, f64>,
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

    /// The E-stop input's channel (pin − 1), if one is bound.
    pub fn emo_channel(&self) -> Option<usize> {
        self.emo_pin.unwrap_or(8).checked_sub(1)
    }

    /// The E-stop input's channel and whether it is inverted (`SetGPIInvert`), if one is bound.
    pub fn estop_binding(&self) -> Option<(usize, bool)> {
        self.emo_channel()
            .map(|c| (c, self.gpi_inverted.contains(&(c + 1))))
    }
}

/// The group's transition parameters (§8.3.26): trans_vel, trans_dis, trans_dev, trans_curv.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TransitionParameters {
    pub velocity: f64,
    pub distance: f64,
    pub deviation: f64,
    pub curvature: f64,
}

/// `SetPT_*` of one axis.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PtSettings {
    pub start: Option<f64>,
    pub end: Option<f64>,
    pub interval: Option<f64>,
    /// ns (absent: one servo period).
    pub pulse_ns: Option<i64>,
}

/// `SetTouchProbeNFunc` of one probe: input (0 external, 1 Z), continuous, edge (0 rising).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ProbeFunction {
    pub input: i64,
    pub continuous: bool,
    pub falling: bool,
}

/// A filter's frequency (Hz), damping ratio and shaper type as set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilterSettings {
    pub frequency: f64,
    pub damping: f64,
    /// `SHAPER_NORMAL` 1, `SHAPER_ROBUST` 0 (VSF: none).
    pub shaper: Option<i64>,
}

/// Which filter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Filter {
    AxisVsf,
    AxisInShape,
    GroupInShape,
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
