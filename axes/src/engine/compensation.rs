//! The engine's side of compensation after the planner (issue 12 item 8): the commands, and
//! the reference positions a grid table reads from other axes before stage 3.

use super::Engine;
use crate::command::{CompensationCommand, EngineError, Reply};
use crate::compensation::MAX_DIMENSIONS;

impl Engine {
    /// `compensation_set` / `_enable` / `_disable` / `_clear` on one axis. A refused table
    /// leaves the axis's previous tables as they were.
    pub(super) fn apply_compensation_command(
        &mut self,
        command: CompensationCommand,
    ) -> Result<Reply, EngineError> {
        let count = self.axes.len() as u32;
        let period = self.period;
        let index = command.axis();
        let axis = self
            .axes
            .get_mut(index as usize)
            .ok_or(EngineError::InvalidAxis {
                axis: u32::from(index),
                count,
            })?;
        match &command {
            CompensationCommand::FilterInputShaping(c) => {
                axis.set_input_shaping(c)?;
                return Ok(Reply::Done);
            }
            CompensationCommand::FilterVsf(c) => {
                axis.set_vsf(c)?;
                return Ok(Reply::Done);
            }
            CompensationCommand::FilterDisable(c) => {
                axis.disable_filter(c)?;
                return Ok(Reply::Done);
            }
            _ => {}
        }
        // A table is built on a copy, so that a refusal changes nothing.
        let mut next = axis.compensation().cloned().unwrap_or_default();
        let offset = match &command {
            CompensationCommand::OffsetAmount(c) => Some(next.set_offset_amount(index, c.amount)),
            CompensationCommand::OffsetProfile(c) => Some(next.set_offset_profile(c)),
            CompensationCommand::OffsetTrigger(_) => Some(next.trigger_offset(index, period)),
            CompensationCommand::OffsetStop(_) => {
                next.stop_offset();
                Some(Ok(()))
            }
            _ => None,
        };
        if let Some(result) = offset {
            result?;
            *axis.compensation_mut() = next;
            return Ok(Reply::Done);
        }
        let enable = match &command {
            CompensationCommand::LeadScrew(c) => next.set_lead_screw(c).map(|()| c.enable)?,
            CompensationCommand::Backlash(c) => next.set_backlash(c).map(|()| c.enable)?,
            CompensationCommand::Table(c) => next.set_table(c, count).map(|()| c.enable)?,
            _ => false,
        };
        match command {
            CompensationCommand::LeadScrew(_)
            | CompensationCommand::Backlash(_)
            | CompensationCommand::Table(_) => {
                if enable {
                    next.set_enabled(true);
                }
                *axis.compensation_mut() = next;
            }
            CompensationCommand::Enable(_) => axis.enable_compensation(true)?,
            CompensationCommand::Disable(_) => axis.enable_compensation(false)?,
            CompensationCommand::Clear(_) => axis.clear_compensation(),
            CompensationCommand::OffsetAmount(_)
            | CompensationCommand::OffsetProfile(_)
            | CompensationCommand::OffsetTrigger(_)
            | CompensationCommand::OffsetStop(_)
            | CompensationCommand::FilterInputShaping(_)
            | CompensationCommand::FilterVsf(_)
            | CompensationCommand::FilterDisable(_) => {}
        }
        Ok(Reply::Done)
    }

    /// Before stage 3: every grid table reads its reference axes as the previous tick left
    /// them (as a coupling reads its master), so the order of the axes does not matter.
    pub(super) fn gather_compensation_inputs(&mut self) {
        for i in 0..self.axes.len() {
            let Some(refs) = self.axes.get(i).and_then(|a| a.compensation_references()) else {
                continue;
            };
            let mut inputs = [0.0; MAX_DIMENSIONS];
            for (slot, r) in inputs.iter_mut().zip(refs) {
                if let Some(r) = r {
                    *slot = self
                        .axes
                        .get(r.axis as usize)
                        .map_or(0.0, |a| a.reference_position(r.source));
                }
            }
            if let Some(axis) = self.axes.get_mut(i) {
                axis.set_compensation_inputs(inputs);
            }
        }
    }
}
