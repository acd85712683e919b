//! A cam started by a capture (HMC_Cam event modes 2 and 6, digest 000 §4.3): "the capture
//! channel dTrigMes fires (its CaptureAxis must be the cam master); start = the captured MPos".
//!
//! The capture channels run after stage 3 (`crate::trigger`), the couplings inside it. Before
//! stage 3 each waiting cam is offered its channel's latch count and newest latch; a latch
//! newer than the cam starts it in that tick's stage 3, anchored at the latched position
//! exactly (as a position start is anchored at the crossed position), so the slave stands
//! where it would have stood had the cam started at the edge itself.

use super::{CamStart, Couplings, Law};
use crate::command::{EngineError, MasterSource};
use crate::trigger::{Triggers, CAPTURE_CHANNELS};

/// The start of a cam on capture channel `channel` of its master, checked.
pub(super) fn cam_capture_start(channel: u8) -> Result<CamStart, EngineError> {
    if channel < CAPTURE_CHANNELS {
        Ok(CamStart::Capture(channel))
    } else {
        Err(EngineError::InvalidArgument {
            name: "start_capture",
            value: f64::from(channel),
            reason: "capture channels are 0 to 7",
        })
    }
}

impl Couplings {
    /// Whether a cam waits for a capture (the engine then offers it the channels each tick).
    pub(crate) fn waits_for_captures(&self) -> bool {
        self.list
            .iter()
            .any(|c| matches!(&c.law, Law::Cam(cam) if cam.waits_for_capture().is_some()))
    }

    /// Offer each waiting cam its master's capture channel: the latch count and the newest
    /// latched master position, commanded for a `commanded` master source, actual otherwise
    /// (HMC latches MPos).
    pub(crate) fn offer_captures(&mut self, triggers: &Triggers) {
        for c in self.list.iter_mut() {
            let Law::Cam(cam) = &mut c.law else { continue };
            let Some(channel) = cam.waits_for_capture() else {
                continue;
            };
            let status = triggers.capture(c.master, channel);
            let latched = status
                .and_then(|s| s.latches.last())
                .map_or(0.0, |l| match c.source {
                    MasterSource::Commanded => l.cmd_pos,
                    MasterSource::Actual | MasterSource::Encoder => l.act_pos,
                });
            cam.offer_capture(status.map(|s| s.count), latched);
        }
    }
}
