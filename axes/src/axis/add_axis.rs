//! The axis's side of an HMC add axis (digest 000 §4.4 `HMC_SetAddAxis`; the registry is
//! `crate::coupling::add_axis`): another axis's travel laid on the axis's own command.

use super::{Activity, Axis, RunGoal, Setpoint, Source};
use crate::command::AxisIndex;

impl Axis {
    /// Before this tick's step: move the own command by `travel` of the add axis, so that
    /// the commanded position (HMC DPos) is the own command's displacement plus the add
    /// axis's, while the commanded velocity (HMC VpSpeed) stays the own command's. A plan,
    /// a stream and a standing axis shift with their target; an axis fed by a group or a
    /// coupling, or given absolute position setpoints, follows its feeder exactly
    /// (decisions.md, "HMC add axis"). A disabled axis tracks its actual position.
    pub(crate) fn add_displacement(&mut self, travel: f64) {
        if travel == 0.0 || !self.enabled {
            return;
        }
        match &mut self.source {
            Source::Hold => self.raw.p += travel,
            Source::Profile { shift, .. } => *shift += travel,
            Source::Stream { base, .. } => *base += travel,
            // Velocity and torque setpoints integrate from the last position.
            Source::External(Setpoint::Velocity { .. } | Setpoint::Torque { .. }) => {
                self.raw.p += travel;
            }
            Source::External(Setpoint::Position { .. }) | Source::Fed(_) => return,
        }
        self.target_pos += travel;
        if let Activity::Running(run) = &mut self.activity {
            if let RunGoal::Position { target } = &mut run.goal {
                *target += travel;
            }
        }
    }

    /// Record the axis's add axis for its status (HMC_GetAddAxis).
    pub(crate) fn set_add_axis(&mut self, add: Option<AxisIndex>) {
        self.add_axis = add;
    }
}
