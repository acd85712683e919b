//! The stream family: PT and PVT streams per axis (issue 12 item 3). An axis's stream is a
//! buffer of points — position and time (PT), or position, velocity and time (PVT) — that the
//! axis runs through on its own clock once started: NMC `MtPt*` / `MtPvt*` (digest 001
//! §2.13–2.14, §4.7), HIMC `MovePVT` (digest 004 §5.2.8).
//!
//! Units: positions in user units relative to where the axis stands when the stream starts
//! ("相对于 PT 起点的绝对位置"), times in milliseconds from the start (both vendors), PVT
//! velocities in user units per second (the engine's unit; HIMC's mm/s).

use serde::{Deserialize, Serialize};

use super::{command_from, AxisIndex, StreamMode};

/// Most points one `pt_push` / `pvt_push` carries (NMC `MtPtPush` count ∈ [1, 32], TV56).
pub const MAX_PUSH_POINTS: usize = 32;

/// Most points of one `pvt_move` (HIMC `MovePVT` num_pt ≤ 50, digest 004 TV21).
pub const MAX_PVT_MOVE_POINTS: usize = 50;

/// How a PT point's segment (from the previous point to this one) takes its velocities (NMC
/// `MT_PT_*`, digest 001 §3.17, §4.7). Within a segment the acceleration is constant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PtKind {
    /// `MT_PT_NORMAL` (0): starts at the previous segment's end velocity (0 for the first) and
    /// ends at 2·Δp/Δt − v_start.
    #[default]
    Normal,
    /// `MT_PT_STOP` (1): ends at rest; starts at 2·Δp/Δt whatever the previous segment ended at.
    Stop,
    /// `MT_PT_EVEN` (2): constant velocity Δp/Δt.
    Even,
}

/// One PT point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PtPoint {
    /// User units, relative to the position the stream started from.
    pub position: f64,
    /// Milliseconds from the start; each point's later than the one before.
    pub time_ms: f64,
    #[serde(default)]
    pub kind: PtKind,
}

/// One PVT knot: the axis passes `position` at `time_ms` with `velocity`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PvtPoint {
    /// User units, relative to the position the stream started from.
    pub position: f64,
    /// User units per second.
    pub velocity: f64,
    /// Milliseconds from the start; each knot's later than the one before.
    pub time_ms: f64,
}

/// Set the axis's buffer mode (NMC `MtPtSetStatic`, `MtPvtSetPara`, `MtPtSetPara`). Clears
/// the buffer. Refused while the stream runs. JSON `type`: `stream_config`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StreamConfig {
    pub axis: AxisIndex,
    /// `refresh` (default) or `static`.
    #[serde(default)]
    pub mode: StreamMode,
    /// Static mode: how many times the buffer runs (0 = until stopped). Default 1.
    #[serde(default = "one_loop")]
    pub loop_count: u32,
    /// Deceleration of the stop when the stream runs dry while moving (NMC `smoothDec`);
    /// default the axis's `decel`.
    #[serde(default)]
    pub stop_deceleration: Option<f64>,
}

fn one_loop() -> u32 {
    1
}

/// Append 1–32 PT points to the axis's buffer (NMC `MtPtPush`), all or none. Allowed while a
/// refresh-mode stream runs. JSON `type`: `pt_push`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PtPush {
    pub axis: AxisIndex,
    pub points: Vec<PtPoint>,
}

/// Append 1–32 PVT knots to the axis's buffer (NMC `MtPvtData`), all or none. JSON `type`:
/// `pvt_push`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PvtPush {
    pub axis: AxisIndex,
    pub points: Vec<PvtPoint>,
}

/// Empty the axis's buffer (NMC `MtPtBufClr`, `MtPvtBufClr`). Refused while the stream runs.
/// JSON `type`: `stream_clear`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StreamClear {
    pub axis: AxisIndex,
}

/// Start the streams of these axes in the same tick, all or none (NMC `MtPtStartMtn` /
/// `MtPvtStartMtn` with their other axes). The reply lists one command id per axis, in order.
/// JSON `type`: `stream_start`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StreamStart {
    pub axes: Vec<AxisIndex>,
}

/// HIMC `MovePVT`: replace the axis's buffer with these 1–50 knots and start it at once; the
/// stream runs once. A first knot at time 0 must be the start itself (position 0, velocity 0).
/// JSON `type`: `pvt_move`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PvtMove {
    pub axis: AxisIndex,
    pub points: Vec<PvtPoint>,
}

/// A command on axes' PT/PVT streams.
#[derive(Clone, Debug, PartialEq)]
pub enum StreamCommand {
    Config(StreamConfig),
    PtPush(PtPush),
    PvtPush(PvtPush),
    Clear(StreamClear),
    Start(StreamStart),
    PvtMove(PvtMove),
    StartOnInput(StreamStartOnInput),
}

impl StreamCommand {
    /// The axis the command addresses, when it addresses one.
    pub fn axis(&self) -> Option<AxisIndex> {
        match self {
            StreamCommand::Config(StreamConfig { axis, .. })
            | StreamCommand::PtPush(PtPush { axis, .. })
            | StreamCommand::PvtPush(PvtPush { axis, .. })
            | StreamCommand::Clear(StreamClear { axis })
            | StreamCommand::PvtMove(PvtMove { axis, .. })
            | StreamCommand::StartOnInput(StreamStartOnInput { axis, .. }) => Some(*axis),
            StreamCommand::Start(_) => None,
        }
    }
}

command_from!(
    StreamCommand,
    Stream,
    [
        StreamConfig => Config,
        PtPush => PtPush,
        PvtPush => PvtPush,
        StreamClear => Clear,
        StreamStart => Start,
        PvtMove => PvtMove,
        StreamStartOnInput => StartOnInput,
    ]
);

/// Start `axis`'s stream at an edge of digital input `input` (NMC `MtPtStartMtnEx(axis,
/// diIndex, diSns)`, "DI 沿触发", digest 001 §2.8: `diSns` 0 = `falling`, 1 = `rising`). Armed
/// until the edge: an edge seen by a tick starts the stream before the next tick, as a
/// `stream_start` sent then would, so it takes its first sample one period later. Arming again
/// replaces the arm; `stream_clear` disarms. A start the stream refuses at the edge (nothing
/// pushed, the axis moving or faulted) drops the arm. JSON `type`: `stream_start_on_input`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StreamStartOnInput {
    pub axis: AxisIndex,
    pub input: u16,
    pub edge: super::CaptureEdge,
}
