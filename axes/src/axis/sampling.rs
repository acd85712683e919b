//! What a sampler reads of an axis (issue 12 item 9), as the last tick left it: the same
//! numbers the status record shows.

use super::Axis;
use crate::command::SampledVariable;

impl Axis {
    /// The axis quantity `variable` names; 0 for a variable that is not an axis quantity.
    pub fn sampled(&self, variable: &SampledVariable) -> f64 {
        match variable {
            SampledVariable::PlannedPosition { .. } => self.cmd.p,
            SampledVariable::PlannedVelocity { .. } => self.cmd.v,
            SampledVariable::ActualPosition { .. } => self.act_pos,
            SampledVariable::ActualVelocity { .. } => self.act_vel,
            SampledVariable::FollowingError { .. } => self.cmd.p - self.act_pos,
            SampledVariable::OutputPosition { .. } => self.cmd.p + self.correction,
            SampledVariable::DigitalInput { .. }
            | SampledVariable::DigitalOutput { .. }
            | SampledVariable::GroupCoordinate { .. }
            | SampledVariable::GroupVelocity { .. } => 0.0,
        }
    }
}
