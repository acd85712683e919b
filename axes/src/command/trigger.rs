//! The trigger family (issue 12 items 4–5): capture channels that latch an axis's positions on
//! an edge, and position-compare channels that drive a digital output at positions.

use serde::{Deserialize, Serialize};

use super::{command_from, AxisIndex};
pub use crate::status::{
    CaptureEdge, CaptureSource, CaptureWindow, CompareOutputMode, PositionSource,
};

/// Arm capture channel `channel` of `axis` (NMC `MtSetCaptSns` + `MtSetCapt`,
/// `MtSetCaptRepeat`, `MtSetAdvCaptParam`; HMC `HMC_CaptureConfig`; HIMC `SetTouchProbe1Func` +
/// `EnableTouchProbe1`). Re-arming a channel forgets its latches.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaptureArm {
    /// The axis whose positions are latched.
    pub axis: AxisIndex,
    #[serde(default)]
    pub channel: u8,
    pub source: CaptureSource,
    /// The digital input (source `di`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub input: Option<u16>,
    /// The axis whose index, home or limit is watched (default: `axis`; HMC captures one
    /// axis on another's Z).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source_axis: Option<AxisIndex>,
    #[serde(default)]
    pub edge: CaptureEdge,
    /// Edges to latch, 1 to 64 (NMC `REPEAT_CAPT_MAX_NUM`); default 1 (single shot).
    #[serde(default = "one")]
    pub repeat: u16,
    /// Keep latching after `repeat` edges, keeping the newest `repeat`.
    #[serde(default)]
    pub continuous: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub window: Option<CaptureWindow>,
}

fn one() -> u16 {
    1
}

/// Disarm channel `channel` of `axis` and forget its latches (NMC `MtClrCaptSts`,
/// `MtClrAdvCaptSts`; HIMC `DisableTouchProbe1`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaptureClear {
    pub axis: AxisIndex,
    #[serde(default)]
    pub channel: u8,
}

/// Start position-compare channel `channel`: fire `output` when `axis` (1-D) or `axis` and
/// `axis_y` (2-D) reach each position in turn. Positions come from exactly one of `positions`
/// (1-D list: NMC 1-D compare, HMC `NormalSwitch1D`/`Switch`), `start` + `interval` + `end`
/// (1-D grid: HIMC PT trigger) or `points` (2-D, with `error_zone`: NMC 2-D compare, HMC
/// `NormalSwitch2D`). Restarting a channel replaces it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareStart {
    #[serde(default)]
    pub channel: u8,
    pub axis: AxisIndex,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis_y: Option<AxisIndex>,
    #[serde(default)]
    pub source: PositionSource,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub positions: Vec<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interval: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end: Option<f64>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<[f64; 2]>,
    /// 2-D: the radius around a point within which the closest approach fires.
    #[serde(default)]
    pub error_zone: f64,
    /// The digital output channel.
    pub output: u16,
    #[serde(default)]
    pub mode: CompareOutputMode,
    /// The active level of a pulse; a toggle's level at the first position.
    #[serde(default = "high")]
    pub level: bool,
    /// Seconds; rounded up to whole servo periods, at least one.
    #[serde(default)]
    pub pulse_width: f64,
    /// Seconds between two outputs at least (NMC `minIntervalTime`): a position reached sooner
    /// fires when the interval has passed.
    #[serde(default)]
    pub min_interval: f64,
}

fn high() -> bool {
    true
}

/// Stop compare channel `channel` and drop it; a pulse in progress ends (NMC `Comp2DimensOnoff`
/// 0, HMC `HMC_CloseSwitch`, HIMC `DisablePT`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareStop {
    #[serde(default)]
    pub channel: u8,
}

/// Fire compare channel `channel`'s output once now, as one of its positions would, without
/// using up a position (NMC `Comp2DimensOnoff` 2, "manual output", S-CMP-MANUAL, digest 001
/// §2.11). The channel must have been started (it may be done). JSON `type`: `compare_fire`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareFire {
    #[serde(default)]
    pub channel: u8,
}

/// A command on the capture and compare channels; it takes effect at once, between ticks.
#[derive(Clone, Debug, PartialEq)]
pub enum TriggerCommand {
    CaptureArm(CaptureArm),
    CaptureClear(CaptureClear),
    CompareStart(CompareStart),
    CompareStop(CompareStop),
    CompareFire(CompareFire),
    CaptureArmThreshold(CaptureArmThreshold),
}

command_from!(
    TriggerCommand,
    Trigger,
    [
        CaptureArm => CaptureArm,
        CaptureClear => CaptureClear,
        CompareStart => CompareStart,
        CompareStop => CompareStop,
        CompareFire => CompareFire,
        CaptureArmThreshold => CaptureArmThreshold,
    ]
);

/// Arm capture channel `channel` of `axis` to latch when the position of `source_axis`
/// (default `axis`) crosses `threshold` (NMC `MtSetAdvCaptParam` with `trigSrc`
/// `CAPT_EX_SRC_PRFPOS` 5 → `source` `commanded`, `CAPT_EX_SRC_ENCPOS` 6 → `actual`;
/// `trigIndex` → `source_axis`, `trigValue` → `threshold`, `capPosIndex` → `axis`; digest 001
/// §2.18, §3.15, S-ADVCAPT). Crossing upward is a rising edge, downward a falling one; the latch
/// is taken at the crossing's fraction of the tick. Otherwise as `capture_arm`. JSON `type`:
/// `capture_arm_threshold`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaptureArmThreshold {
    pub axis: AxisIndex,
    #[serde(default)]
    pub channel: u8,
    #[serde(default)]
    pub source: PositionSource,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source_axis: Option<AxisIndex>,
    pub threshold: f64,
    #[serde(default)]
    pub edge: CaptureEdge,
    #[serde(default = "one")]
    pub repeat: u16,
    #[serde(default)]
    pub continuous: bool,
}
