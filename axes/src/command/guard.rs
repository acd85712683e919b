//! Guards (NMC `NMC_SetWatchDog` TV71, `NMC_MtSetEstopDI`, `NMC_SetEstopDIEx`,
//! `NMC_MtSetPtpComparePara`, digest 001 §2.3, §2.5, §2.20): watches the engine carries out itself, on the tick, so that a scaled or virtual
//! clock gives what real time gives. They are machine-family commands (`machine.rs`); the
//! state is `crate::guard`.

use serde::{Deserialize, Serialize};

use super::{AxisIndex, StopMode};

/// Input-stop slots the engine has (NMC: the `SetEstopDIEx` groups, then one per axis for
/// `MtSetEstopDI`; the front-end picks the slot).
pub const MAX_INPUT_STOPS: u16 = 256;

/// A digital output written when the watchdog fires.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputLevel {
    pub channel: u16,
    pub value: bool,
}

/// Arm (or, `deadline` absent, disarm) the machine's watchdog: at tick `deadline`, unless a
/// `watchdog_kick` moved it, every axis stops with `mode` and `outputs` are written, once.
/// JSON `type`: `watchdog_set`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WatchdogSet {
    #[serde(default)]
    pub deadline: Option<u64>,
    #[serde(default)]
    pub mode: StopMode,
    #[serde(default)]
    pub outputs: Vec<OutputLevel>,
}

/// Move an armed watchdog's deadline (the host was heard from); a watchdog that fired is armed
/// again. Nothing to do when none is armed. JSON `type`: `watchdog_kick`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WatchdogKick {
    pub deadline: u64,
}

/// The signal an input stop watches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum GuardInput {
    /// A digital input of the machine image.
    Digital {
        channel: u16,
    },
    /// An axis's negative or positive hardware limit, home switch or encoder index, as its
    /// status flags show them.
    NegativeLimit {
        axis: AxisIndex,
    },
    PositiveLimit {
        axis: AxisIndex,
    },
    Home {
        axis: AxisIndex,
    },
    Index {
        axis: AxisIndex,
    },
}

/// Watch `input`: once it has been at `level` for `filter` ticks more, `axes` stop with an
/// emergency stop (each latches ESTOP), moving or not; while it stays there, any of them that
/// moves again is stopped again. Replaces what `slot` watched. JSON `type`: `input_stop_set`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputStopSet {
    pub slot: u16,
    pub input: GuardInput,
    pub level: bool,
    #[serde(default)]
    pub filter: u32,
    pub axes: Vec<AxisIndex>,
}

/// Stop watching `slot`. JSON `type`: `input_stop_clear`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputStopClear {
    pub slot: u16,
}

/// Watch `axis`'s planned position: the first tick it is at or past `position` (moving in the
/// positive direction when `positive`, else the negative), its running move goes on at `speed`
/// (units/s; a position move keeps its target, a velocity move its direction). Once.
/// Replaces the axis's watch. JSON `type`: `position_watch_set`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PositionWatchSet {
    pub axis: AxisIndex,
    pub position: f64,
    pub positive: bool,
    pub speed: f64,
}

/// Forget `axis`'s position watch. JSON `type`: `position_watch_clear`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PositionWatchClear {
    pub axis: AxisIndex,
}
