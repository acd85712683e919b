//! Buffered I/O and stop commands of an axis group beyond `group_set_output` (NMC CrdBufOut,
//! CrdBufDoBitPulseEnable / Disable, CrdAdvBufIoOnAfterLen / OffBeforeLen, CrdBufSetEstopDI,
//! CrdBufEstopDIExOnOff, CrdBufStopMtn; digest 001 §2.7): each is a pass-through marker of the
//! group's queue that acts when the path reaches it.

use serde::{Deserialize, Serialize};

use super::GroupId;

/// Buffered: digital output `channel` is written `level` and then toggled `toggles` times, as
/// `pulse_digital_output` does (`level` holds `level_time` s, the other level `other_time` s;
/// `u32::MAX` toggles forever); `toggles` 0 writes `level` only and ends a train running on the
/// channel; `level` absent (with `toggles` 0) only ends the train. It acts when the path
/// reaches this point, or with `after_length` that many path units later, or with
/// `before_end` that many path units before the end of the motion queued when the path
/// reaches it (at once if the path is already nearer the end), at the tick the path crosses
/// the point. A stop, an error or a reset of the group drops one still waiting for its point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupPulseOutput {
    pub group: GroupId,
    pub channel: u16,
    #[serde(default)]
    pub level: Option<bool>,
    #[serde(default)]
    pub level_time: f64,
    #[serde(default)]
    pub other_time: f64,
    #[serde(default)]
    pub toggles: u32,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub after_length: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub before_end: Option<f64>,
}

/// Buffered: set an analog output channel when the path reaches this point (NMC CrdBufOut
/// with BUF_OUT_GROUP_DA).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetAnalogOutput {
    pub group: GroupId,
    pub channel: u16,
    pub value: f64,
}

/// Buffered: from this point of the path on, digital input `channel` at `level` stops the group
/// as `group_emergency_stop` does; `slot` (0 … 63) names the watch, a later one in the same slot
/// replaces it, and one without `channel` ends it. A reset of the group ends every watch (NMC
/// CrdBufSetEstopDI, CrdBufEstopDIExOnOff).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupStopInput {
    pub group: GroupId,
    pub slot: u16,
    #[serde(default)]
    pub channel: Option<u16>,
    #[serde(default)]
    pub level: bool,
}

/// Buffered: when the path reaches this point, group `target` (this one or another) halts as by
/// `group_halt` with `deceleration` (its queue kept; `group_continue` goes on) (NMC
/// CrdBufStopMtn).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupBufferedHalt {
    pub group: GroupId,
    pub target: GroupId,
    #[serde(default)]
    pub deceleration: Option<f64>,
}
