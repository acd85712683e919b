//! The axis's side of the command filters (issue 14, digest 004 §2.14): commands install and
//! remove them (only at rest: "not applicable while the motor is moving"); the tick runs the
//! active one after smoothing in `Axis::step` (stage 2a).

use super::Axis;
use crate::command::{FilterDisable, FilterInputShaping, FilterVsf};
use crate::error::EngineError;
use crate::filter::{CommandFilter, CommandFilters, FilterSlot, FilterStatus, Notch, Shaper};

impl Axis {
    /// The slot in use: the group's while the axis is in a group, else the axis's own.
    fn filter_slot(&self) -> FilterSlot {
        if self.group.is_some() {
            FilterSlot::Group
        } else {
            FilterSlot::Axis
        }
    }

    /// This tick's filtered position for the (smoothed) command `input`; `None` without an
    /// active filter. A slot that becomes active (group join or leave) starts at rest on the
    /// output it takes over.
    pub(super) fn filter_command(&mut self, input: f64) -> Option<f64> {
        let slot = self.filter_slot();
        let previous = self.cmd.p;
        let filters = self.filters.as_deref_mut()?;
        let switched = filters.active != Some(slot);
        filters.active = Some(slot);
        let f = filters.slot_mut(slot).as_mut()?;
        if switched {
            f.reset(previous);
        }
        Some(f.next(input))
    }

    /// The active filter has arrived at its input (or there is none).
    pub(super) fn filter_settled(&self) -> bool {
        self.filters
            .as_deref()
            .and_then(|f| f.slot(self.filter_slot()))
            .is_none_or(CommandFilter::is_settled)
    }

    /// Smoothing and the command filter have both arrived.
    pub(crate) fn output_settled(&self) -> bool {
        self.smoothing.as_ref().is_none_or(|f| f.is_settled()) && self.filter_settled()
    }

    pub(super) fn reset_command_filters(&mut self, position: f64) {
        if let Some(filters) = self.filters.as_deref_mut() {
            for f in [&mut filters.axis, &mut filters.group]
                .into_iter()
                .flatten()
            {
                f.reset(position);
            }
        }
    }

    /// What the status shows: the active filter.
    pub fn filter_status(&self) -> Option<FilterStatus> {
        let slot = self.filter_slot();
        self.filters
            .as_deref()
            .and_then(|f| f.slot(slot))
            .map(|f| f.status(slot))
    }

    /// Filters change only at rest (digest 004 §2.14).
    fn filters_at_rest(&self, action: &'static str) -> Result<(), EngineError> {
        if self.moving() || !self.output_settled() {
            return Err(EngineError::InvalidState {
                axis: self.index,
                state: self.state(),
                action,
            });
        }
        Ok(())
    }

    fn install_filter(&mut self, slot: FilterSlot, filter: CommandFilter) {
        let filters = self.filters.get_or_insert_with(Box::default);
        *filters.slot_mut(slot) = Some(filter);
        filters.active = None;
    }

    pub(crate) fn set_input_shaping(&mut self, c: &FilterInputShaping) -> Result<(), EngineError> {
        self.filters_at_rest("change a command filter while moving")?;
        let shaper = Shaper::new(c.shaper, c.frequency, c.damping, self.period, self.cmd.p)?;
        self.install_filter(c.slot, CommandFilter::Shaper(shaper));
        Ok(())
    }

    pub(crate) fn set_vsf(&mut self, c: &FilterVsf) -> Result<(), EngineError> {
        self.filters_at_rest("change a command filter while moving")?;
        let notch = Notch::new(c.frequency, c.damping, self.period, self.cmd.p)?;
        self.install_filter(FilterSlot::Axis, CommandFilter::Notch(notch));
        Ok(())
    }

    pub(crate) fn disable_filter(&mut self, c: &FilterDisable) -> Result<(), EngineError> {
        self.filters_at_rest("change a command filter while moving")?;
        if let Some(filters) = self.filters.as_deref_mut() {
            match c.slot {
                Some(slot) => *filters.slot_mut(slot) = None,
                None => *filters = CommandFilters::default(),
            }
            if filters.is_empty() {
                self.filters = None;
            }
        }
        Ok(())
    }
}
