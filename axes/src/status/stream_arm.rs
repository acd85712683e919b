//! A stream armed to start on a digital input edge (NMC MtPtStartMtnEx), as
//! `Snapshot::stream_input_starts` shows it.

use serde::{Deserialize, Serialize};

use super::CaptureEdge;
use crate::types::AxisIndex;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct StreamInputStart {
    pub axis: AxisIndex,
    pub input: u16,
    pub edge: CaptureEdge,
}
