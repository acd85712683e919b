//! The status records of capture channels and position-compare channels (issue 12 items 4–5),
//! and the small enums their commands and records share. A leaf like the axis record: it names
//! only the leaf types, so the command family above it and the snapshot beside it both use it.

use serde::{Deserialize, Serialize};

use crate::types::AxisIndex;

/// The signal a capture channel watches (NMC `CAPT_IO_SRC_*` and `CAPT_MODE_Z`, digest 001
/// §3.15; HMC `ucTrigType` Z or DI, digest 000 §4.4; HIMC `tp_input`, digest 004 §2.12).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CaptureSource {
    /// The encoder index (Z) pulse of the source axis.
    Index,
    /// The home switch of the source axis, as the controller reads it.
    Home,
    /// The positive hardware limit of the source axis.
    LimitPos,
    /// The negative hardware limit of the source axis.
    LimitNeg,
    /// A general digital input of the machine (`input` names the channel).
    Di,
    /// The commanded position of the source axis crossing a threshold
    /// (`capture_arm_threshold`; NMC CAPT_EX_SRC_PRFPOS).
    CommandedPosition,
    /// The actual (encoder) position of the source axis crossing a threshold (NMC
    /// CAPT_EX_SRC_ENCPOS).
    ActualPosition,
}

/// Which edges latch (NMC `level`, HMC `bTrigEdge`, HIMC `detect_edge`, CiA 402 0x60B8 bits
/// 4–5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CaptureEdge {
    #[default]
    Rising,
    Falling,
    /// Both edges (NMC advanced capture: leading and trailing).
    Both,
}

impl CaptureEdge {
    /// Whether an edge of this polarity latches (`None`: an index pulse, which is one count
    /// wide, so it has both edges at once).
    pub fn accepts(self, rising: Option<bool>) -> bool {
        match (self, rising) {
            (_, None) | (CaptureEdge::Both, _) => true,
            (CaptureEdge::Rising, Some(r)) => r,
            (CaptureEdge::Falling, Some(r)) => !r,
        }
    }
}

/// HMC capture window (`bWinModeEnable`, digest 000 §4.4): edges latch only while the capture
/// axis's actual position is inside `[low, high]`, or only outside it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaptureWindow {
    pub low: f64,
    pub high: f64,
    /// Latch only outside the window (HMC mode 2) instead of inside it (mode 1).
    #[serde(default)]
    pub outside: bool,
}

impl CaptureWindow {
    /// Whether an edge at actual position `p` may latch.
    pub fn admits(&self, p: f64) -> bool {
        (self.low <= p && p <= self.high) != self.outside
    }
}

/// Where a capture channel stands (HMC `HMC_CaptureGetState`: waiting 2, outside the window 1,
/// done 3; a channel never armed or cleared has no record and reads 3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CaptureState {
    /// Armed, waiting for the edge.
    #[default]
    Waiting,
    /// Armed with a window the capture axis is not in: edges are ignored.
    OutsideWindow,
    /// Latched `repeat` edges (a continuous channel never gets here).
    Done,
}

/// One latch: the capture axis at the moment of the edge, interpolated inside the tick as a
/// hardware latch sees it (digest 000 §9 item 34).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Latch {
    /// The tick during which the edge happened (a command's edge: the tick before it).
    pub tick: u64,
    /// The edge's polarity; an index pulse counts as rising.
    pub rising: bool,
    /// Commanded position, user units.
    pub cmd_pos: f64,
    /// Actual position, user units: the encoder count below converted (a virtual axis: the
    /// exact position).
    pub act_pos: f64,
    /// Encoder counter.
    pub encoder_counts: i64,
}

/// A capture channel (`capture_arm` until `capture_clear`). HIMC touch probe: enabled while the
/// record exists, triggered once `count` > 0; NMC `BIT_AXIS_CAPTSET`: the axis flag
/// `capture_triggered`, set while any of its channels has latched.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaptureStatus {
    /// The axis whose positions are latched.
    pub axis: AxisIndex,
    pub channel: u8,
    pub source: CaptureSource,
    /// The axis whose signal is watched (index, home, limits).
    pub source_axis: AxisIndex,
    /// The digital input watched (source `di`).
    pub input: Option<u16>,
    pub edge: CaptureEdge,
    /// Edges to latch before the channel is done (NMC repeat capture, ≤ 64).
    pub repeat: u16,
    /// Keep latching after `repeat` edges, keeping the last `repeat` latches (HIMC / CiA 402
    /// continuous mode).
    pub continuous: bool,
    pub window: Option<CaptureWindow>,
    pub state: CaptureState,
    /// Edges latched since the channel was armed.
    pub count: u32,
    /// The latches kept, oldest first (at most `repeat`).
    pub latches: Vec<Latch>,
}

/// Which position a compare channel follows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PositionSource {
    /// The commanded (planned) position (NMC posSrc 0, HMC DPos).
    #[default]
    Commanded,
    /// The actual position (NMC posSrc 1 encoder, HMC MPos).
    Actual,
}

/// What a compare channel does to its output at a position (NMC `outputType`, HMC
/// `ucOutputType`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CompareOutputMode {
    /// The output goes to `level` for `pulse_width`, then back.
    #[default]
    Pulse,
    /// The output toggles; it goes to `level` at the first position (HMC Switch).
    Toggle,
}

/// Where a compare channel stands (NMC `sts` 1 busy / 0 idle, HMC Switch state 0 working / 3
/// idle).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CompareState {
    /// Positions remain.
    #[default]
    Running,
    /// Every position has fired.
    Done,
}

/// A position-compare channel (`compare_start` until `compare_stop`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CompareStatus {
    pub channel: u8,
    pub axis: AxisIndex,
    /// The second axis of a 2-D compare.
    pub axis_y: Option<AxisIndex>,
    pub source: PositionSource,
    /// The digital output channel.
    pub output: u16,
    pub state: CompareState,
    /// Outputs fired so far (NMC outCount, HMC GetSwitchNum).
    pub count: u32,
    /// Positions not yet fired (NMC usedSpace).
    pub remaining: u32,
    /// Positions in all.
    pub total: u32,
}

/// A Z-phase compare channel (`z_compare_start` until `z_compare_stop`; HMC SwitchTZ).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ZCompareStatus {
    pub channel: u8,
    /// The trigger axis.
    pub axis: AxisIndex,
    pub source: PositionSource,
    /// The axis whose Z-phase output the channel drives.
    pub output_axis: AxisIndex,
    pub mode: CompareOutputMode,
    /// `done` (HMC GetSwitchTZState 3) once every position was passed.
    pub state: CompareState,
    /// Outputs made so far (HMC GetSwitchTZNum).
    pub count: u32,
    /// Positions passed while a pulse was still on, so not answered (manual §4.4.3.4 note 5).
    pub missed: u32,
    /// Positions not yet passed.
    pub remaining: u32,
    pub total: u32,
}
