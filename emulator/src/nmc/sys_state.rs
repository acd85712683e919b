//! What the system family (0x18xx, helper nmcsys) keeps per device: the data collection
//! `NMC_ConfigCollect` set up and how far `NMC_GetCollectData` has read it, the user USER1's
//! password and login, the execution-time calculation in progress, and where the dedicated
//! inputs' change counters start (`NMC_SetDiReverseCount` types 1–4, served in `io_extras.rs`). Shared by the device's
//! connections.

use std::collections::BTreeMap;

use axes::command::SamplingConfigure;

use super::crd::{CrdState, CRD_COUNT};
use super::io_state::DEFAULT_PASSWORD;

/// What one collected variable is (its `COLLECT_ADDRESS_*` type and index): how its engine
/// value turns into the manual's units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CollectUnit {
    /// Pulses of axis `axis`.
    Position { axis: usize },
    /// pulse/ms of axis `axis`.
    Velocity { axis: usize },
    /// A digital level, 0 or 1.
    Level,
}

/// `NMC_ConfigCollect`'s collection, as the engine's sampler carries it.
#[derive(Clone, Debug, PartialEq)]
pub struct Collect {
    pub config: SamplingConfigure,
    pub units: Vec<CollectUnit>,
}

impl Collect {
    /// Bytes one sample takes (8 per variable).
    pub fn row_bytes(&self) -> u64 {
        8 * self.units.len() as u64
    }
}

#[derive(Clone, Debug)]
pub struct SysState {
    pub collect: Option<Collect>,
    /// Bytes `NMC_GetCollectData` returned since the collection started or was cleared.
    pub read_bytes: u64,
    /// USER1's password (`NMC_UserSetPassword`) and whether USER1 is logged in.
    pub user_password: String,
    pub user_logged_in: bool,
    /// `NMC_CrdStartExeTimeCalc`: the coordinate systems as they were when it started (they
    /// are put back by `NMC_CrdGetExeTime`: what was pushed meanwhile never runs).
    pub exe_calc: Option<Box<[CrdState; CRD_COUNT]>>,
    /// `NMC_SetDiReverseCount` of the dedicated inputs: the engine's change count at which the
    /// counter read 0 (wrapping), by (`input_edges` slot, axis).
    pub dedicated_edge_base: BTreeMap<(usize, usize), u32>,
}

impl Default for SysState {
    fn default() -> SysState {
        SysState {
            collect: None,
            read_bytes: 0,
            user_password: DEFAULT_PASSWORD.to_string(),
            user_logged_in: false,
            exe_calc: None,
            dedicated_edge_base: BTreeMap::new(),
        }
    }
}
