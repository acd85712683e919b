//! HMC add axis (附加轴, digest 000 §4.4 `HMC_SetAddAxis`/`HMC_GetAddAxis`): a base axis whose
//! displacement is its own command's plus another axis's. Part of the coupling family; the
//! per-tick work is `crate::coupling::add_axis`.

use serde::{Deserialize, Serialize};

use super::AxisIndex;

/// Make `base` move by its own command plus every commanded displacement of `add` from now on
/// (HMC_SetAddAxis); without `add` (HMC 255) the association ends and the base keeps the
/// position it has. A new `add` replaces the old one. The base's commanded position (HMC DPos)
/// and actual position show the sum, its commanded velocity (HMC VpSpeed) only its own
/// command's. An `add` that follows the base, directly or down a chain of couplings and add
/// axes, is refused (`coupling_loop`; HMC does not check). JSON `type`: `add_axis_set`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AddAxisSet {
    pub base: AxisIndex,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub add: Option<AxisIndex>,
}
