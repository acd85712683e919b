//! The machine snapshot. A child of `status` but above `param` in the module chain (it carries
//! every axis's [`ParamSet`]), so that `status` itself stays below `param`; `status` re-exports
//! [`Snapshot`] under its old path.

use serde::{Deserialize, Serialize};

use super::{
    AxisStatus, CaptureStatus, CompareStatus, CouplingStatus, DriveStatus, FollowStatus,
    GroupStatus, HandwheelStatus, IoImage, ZCompareStatus,
};
use crate::param::ParamSet;
use crate::sampling::SamplerStatus;

/// The machine's state after a tick: what front-ends read without waiting for the servo thread.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// Ticks since start.
    pub tick: u64,
    /// Servo period, seconds.
    pub period: f64,
    pub axes: Vec<AxisStatus>,
    /// The axis groups (issue 11), by group number.
    #[serde(default)]
    pub groups: Vec<GroupStatus>,
    /// The couplings (issue 12: gear, cam), by slave axis.
    #[serde(default)]
    pub couplings: Vec<CouplingStatus>,
    /// The armed (or done) capture channels (issue 12 item 4), by axis and channel.
    #[serde(default)]
    pub captures: Vec<CaptureStatus>,
    /// The position-compare channels (issue 12 item 5), by channel.
    #[serde(default)]
    pub compares: Vec<CompareStatus>,
    pub io: IoImage,
    /// Changes whenever the I/O image changes: readers (and the snapshot refresh) can skip
    /// comparing images that did not change.
    pub io_version: u64,
    /// The configured data samplers (issue 12 item 9); their data are read with
    /// `sampling_read`.
    #[serde(default)]
    pub samplers: Vec<SamplerStatus>,
    /// The CiA 402 drives, by slave number.
    pub drives: Vec<DriveStatus>,
    /// Every axis's stored parameters, shared between snapshots until one changes, so that
    /// front-ends read parameters without a round trip to the servo thread. Live values
    /// (positions, status words) come from [`crate::param::parameter_value`].
    #[serde(skip)]
    pub params: std::sync::Arc<Vec<ParamSet>>,
    /// Changes whenever a parameter of any axis changes.
    pub params_version: u64,
    /// The handwheels (issue 12 item 7), by axis.
    #[serde(default)]
    pub handwheels: Vec<HandwheelStatus>,
    /// The external encoders' counts (inputs 256 and 257), which `handwheel_turn` turns.
    #[serde(default)]
    pub external_encoders: [i64; 2],
    /// The NMC Follow slaves (issue 12 item 2: FIFOs, loops, start event), by axis.
    #[serde(default)]
    pub follows: Vec<FollowStatus>,
    /// Streams armed to start on a digital input edge (NMC MtPtStartMtnEx), by arming order.
    #[serde(default)]
    pub stream_input_starts: Vec<super::StreamInputStart>,
    /// The gantry homings (HMC_GantryInit), running or ended, by start order.
    #[serde(default)]
    pub gantry_homes: Vec<super::GantryHomeStatus>,
    /// The Z-phase compare channels (HMC SwitchTZ), by channel.
    #[serde(default)]
    pub z_compares: Vec<ZCompareStatus>,
    /// The position watches (NMC PTP compare, `crate::guard`), by axis.
    #[serde(default)]
    pub position_watches: Vec<crate::guard::PositionWatchStatus>,
}

impl Snapshot {
    /// Engine time, seconds.
    pub fn time(&self) -> f64 {
        self.tick as f64 * self.period
    }
}
