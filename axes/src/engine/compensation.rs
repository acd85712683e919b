//! The engine's side of compensation after the planner (issue 12 item 8): the commands, and
//! the reference positions a grid table reads from other axes before stage 3.

use super::Engine;
use crate::command::{
    AxisIndex, CompensationCommand, CompensationReference, EngineError, ReferenceSource, Reply,
};
use crate::compensation::{Compensation, MAX_DIMENSIONS};

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
            CompensationCommand::Enable(_) => true,
            _ => false,
        };
        match command {
            CompensationCommand::Disable(_) => axis.disable_compensation(),
            CompensationCommand::Clear(_) => axis.clear_compensation(),
            _ => {
                if enable {
                    next.enable(u32::from(index))?;
                }
                if next.is_enabled() {
                    self.check_compensation_limit(index, &mut next)?;
                }
                if let Some(axis) = self.axes.get_mut(index as usize) {
                    *axis.compensation_mut() = next;
                }
            }
        }
        Ok(Reply::Done)
    }

    /// Digest 004 §2.13, TV 63: tables switched on whose value at the axes' present positions
    /// is already over the axis's `compensation_limit` are refused at once.
    fn check_compensation_limit(
        &self,
        index: AxisIndex,
        next: &mut Compensation,
    ) -> Result<(), EngineError> {
        let Some(axis) = self.axes.get(index as usize) else {
            return Ok(());
        };
        let Some(limit) = axis.compensation_limit() else {
            return Ok(());
        };
        let inputs = self.reference_inputs(next.references());
        let planned = axis.reference_position(ReferenceSource::Planned);
        let value = next.value_at_rest(index, planned, inputs);
        if value.abs() > limit {
            return Err(EngineError::CompensationLimit {
                axis: u32::from(index),
                value,
                limit,
            });
        }
        Ok(())
    }

    /// The reference axes' positions, one per reference, in table order (0 beyond them).
    fn reference_inputs<'a>(
        &self,
        refs: impl IntoIterator<Item = &'a CompensationReference>,
    ) -> [f64; MAX_DIMENSIONS] {
        let mut inputs = [0.0; MAX_DIMENSIONS];
        for (slot, r) in inputs.iter_mut().zip(refs) {
            *slot = self
                .axes
                .get(r.axis as usize)
                .map_or(0.0, |a| a.reference_position(r.source));
        }
        inputs
    }

    /// Before stage 3: every grid table reads its reference axes as the previous tick left
    /// them (as a coupling reads its master), so the order of the axes does not matter.
    pub(super) fn gather_compensation_inputs(&mut self) {
        for i in 0..self.axes.len() {
            let Some(refs) = self.axes.get(i).and_then(|a| a.compensation_references()) else {
                continue;
            };
            // The references are a prefix of the slots (`compensation_references`).
            let inputs = self.reference_inputs(refs.iter().map_while(Option::as_ref));
            if let Some(axis) = self.axes.get_mut(i) {
                axis.set_compensation_inputs(inputs);
            }
        }
    }
}
