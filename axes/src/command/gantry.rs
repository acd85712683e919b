//! Gantry commands (issue 12 item 6): a master and up to 7 slaves that receive the master's
//! command (HMC_GantrySynchro, digest 000 §4.4; NMC SetGantryMaster/SetGantrySlave, digest 001
//! §2.10; HIMC EnableGantryPair, digest 004 §2.6). PLCopen has no gantry block.

use serde::{Deserialize, Serialize};

use super::AxisIndex;

/// Most slaves of one gantry (HMC: ucSlaveAxisNum ≤ 7).
pub const MAX_GANTRY_SLAVES: usize = 7;

/// Gang `slaves` to `master`: each slave's commanded position is the master's plus the offset
/// between them at this command, and single-axis motion of a slave is refused until
/// `gantry_disable`. The deviation (slave − master actual, less that offset) over
/// `warning_limit` sets `gantry_warning` (HMC AxisStatus bit 5); over `fault_limit` latches
/// `gantry_fault` on the master (bit 6), which stops with its `fast_decel` and the slaves with
/// it. A limit of 0 is no limit. JSON `type`: `gantry_enable`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GantryEnable {
    pub master: AxisIndex,
    /// 1 to 7 slaves, each once, none the master.
    pub slaves: Vec<AxisIndex>,
    #[serde(default)]
    pub warning_limit: f64,
    #[serde(default)]
    pub fault_limit: f64,
    /// HIMC `EnableGantryPair` (digest 004 §2.6, TV 38): refuse unless the master and every
    /// slave are disabled. The pair is made at rest; `enable` of the master then enables the
    /// slaves too (TV 39), as it does on any gantry.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub require_disabled: bool,
}

/// Release the slaves of `master`'s gantry: each decelerates to rest with its `decel` from the
/// velocity it has (as `gear_out`) and takes single-axis motion again (HMC GantrySynchro cancel, NMC DelGantryGroup, HIMC DisableGantryPair). JSON
/// `type`: `gantry_disable`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GantryDisable {
    pub master: AxisIndex,
}
