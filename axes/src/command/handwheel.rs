//! Handwheel (MPG) commands (issue 12 item 7; NMC SetHandWheel, SetHandWheelInput,
//! ClrHandWheel, S-HANDWHEEL, digest 001 §2.9).

use serde::{Deserialize, Serialize};

use super::AxisIndex;

/// The first external encoder's input number (NMC SetHandWheelInput: 256 = first external
/// encoder, 257 the second); below it, an axis's own encoder.
pub const HANDWHEEL_EXTERNAL_BASE: u16 = 256;
/// External handwheel encoders the machine has.
pub const HANDWHEEL_EXTERNAL_ENCODERS: u16 = 2;

/// What happens to wheel travel the axis cannot follow within its velocity limit.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HandwheelExcess {
    /// The axis catches up: it ends where counts × ratio say, however fast the wheel turned.
    #[default]
    CatchUp,
    /// Counts beyond velocity × period per tick are dropped, as MPG modes that discard excess
    /// pulses: the axis stops when the wheel stops.
    Drop,
}

/// Drive `axis` from handwheel `input`: the axis follows its position at this command plus
/// (counts − counts at this command) × numerator / denominator (user units per count), never
/// faster than `velocity` nor with more than `acceleration` (NMC SetHandWheel(axis, ratio, acc,
/// vel)). `input` < 256 is that axis's encoder; 256 and 257 are the external encoders that
/// `handwheel_turn` turns. JSON `type`: `handwheel_in`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HandwheelIn {
    pub axis: AxisIndex,
    pub input: u16,
    pub numerator: f64,
    pub denominator: f64,
    pub velocity: f64,
    pub acceleration: f64,
    #[serde(default)]
    pub excess: HandwheelExcess,
}

/// Stop following the handwheel: the axis decelerates to rest with its `decel` and takes
/// single-axis motion again (NMC ClrHandWheel). JSON `type`: `handwheel_out`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HandwheelOut {
    pub axis: AxisIndex,
}

/// Turn external handwheel encoder `input` (256 or 257) by `counts` (signed): the machine's
/// stand-in for an operator at the wheel. JSON `type`: `handwheel_turn`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HandwheelTurn {
    pub input: u16,
    pub counts: i64,
}

/// Change the ratio of a running handwheel without a jump: from this command on the axis
/// follows its target here plus (counts − counts now) × numerator / denominator (NMC
/// SetHandWheelRatio, digest 001 §2.9). Without `axis`, every handwheel (NMC has one per
/// device). JSON `type`: `handwheel_set_ratio`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HandwheelSetRatio {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<AxisIndex>,
    pub numerator: f64,
    pub denominator: f64,
}
