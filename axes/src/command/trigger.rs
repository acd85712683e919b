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
    /// 2-D on the `actual` position: the anti-jitter threshold (HMC NormalSwitch2D
    /// `dDisturbValue`, NMC `vibrateRange`): once the path entered the zone a point fires when
    /// the distance has grown more than this beyond the least distance seen (the approach is
    /// over; leaving the zone counts once it is this far beyond the least), or when both axes'
    /// commands stand still; 0 = the exact closest approach of each tick's travel. Ignored on
    /// the commanded position, which does not jitter.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub disturbance: f64,
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

fn is_zero(v: &f64) -> bool {
    *v == 0.0
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
    ZCompareStart(ZCompareStart),
    ZCompareStop(ZCompareStop),
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
        ZCompareStart => ZCompareStart,
        ZCompareStop => ZCompareStop,
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

/// Start Z-phase compare channel `channel` (0–7): each time `axis`'s `source` position passes
/// the next of `positions`, in order, drive the Z-phase output of `output_axis` (HMC
/// `HMC_SwitchTZConfig`, manual §4.4.3.4, digest 000 §4.4 "High-speed position compare"; also
/// HMC `HMC_SwitchConfig` with ucOutputMode 1, "axis Z-phase output"). `mode` `toggle` (SwitchTZ
/// ucTimeMode 0, as Switch): the output toggles at each position, to `level` at the first.
/// `pulse` (ucTimeMode 1): `level` for exactly `pulse_width` seconds from the moment of the
/// crossing (HMC dTime, 1–100 000 µs), then back; a position passed while a pulse is still on
/// is missed (manual §4.4.3.4 note 5: targets closer than V·T are not answered), counted in
/// `missed`. The level a pulse shows in the axis status is on for every tick the pulse
/// overlaps. One channel per output axis. Restarting a channel replaces it. JSON `type`:
/// `z_compare_start`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ZCompareStart {
    #[serde(default)]
    pub channel: u8,
    /// The trigger axis (HMC ucTrigAxis).
    pub axis: AxisIndex,
    /// HMC compares MPos: default `actual`.
    #[serde(default = "actual")]
    pub source: PositionSource,
    pub positions: Vec<f64>,
    /// The axis whose Z-phase output is driven (HMC ucOutputAxis).
    pub output_axis: AxisIndex,
    #[serde(default = "toggle")]
    pub mode: CompareOutputMode,
    /// A pulse's level; a toggle's level at the first position (HMC bSwitchValue).
    #[serde(default = "high")]
    pub level: bool,
    /// Seconds, exact (not rounded to servo periods); mode `pulse` only.
    #[serde(default)]
    pub pulse_width: f64,
}

fn actual() -> PositionSource {
    PositionSource::Actual
}

fn toggle() -> CompareOutputMode {
    CompareOutputMode::Toggle
}

/// Stop Z-phase compare channel `channel` and drop it; a pulse in progress ends (HMC
/// `HMC_CloseSwitchTZ`). JSON `type`: `z_compare_stop`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ZCompareStop {
    #[serde(default)]
    pub channel: u8,
}
