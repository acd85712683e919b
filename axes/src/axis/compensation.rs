//! The axis's side of compensation after the planner (issue 12 item 8): commands install and
//! switch tables; the tick adds the correction in `Axis::step` (stage 2b).

use super::Axis;
use crate::command::{CompensationReference, ReferenceSource};
use crate::compensation::{Compensation, CompensationStatus, MAX_DIMENSIONS};

impl Axis {
    /// The axis's compensation, created empty on first use.
    pub(crate) fn compensation_mut(&mut self) -> &mut Compensation {
        self.compensation.get_or_insert_with(Box::default)
    }

    pub fn compensation(&self) -> Option<&Compensation> {
        self.compensation.as_deref()
    }

    /// Remove every table; the output steps back to the planned position at the next tick.
    pub(crate) fn clear_compensation(&mut self) {
        self.compensation = None;
        self.correction = 0.0;
    }

    /// Switch the tables off. The table part drops at once and the backlash part at its rate;
    /// either way the motor moves by the change, as a real drive would.
    pub(crate) fn disable_compensation(&mut self) {
        self.compensation_mut().set_enabled(false);
    }

    /// The compensation this tick is over `compensation_limit` (digest 004 §2.13): the cause
    /// of `COMPENSATION_LIMIT`.
    #[inline]
    pub(crate) fn compensation_over_limit(&self) -> bool {
        let limit = self.setup.compensation_limit;
        limit > 0.0
            && self
                .compensation
                .as_deref()
                .is_some_and(|c| c.last_correction().abs() > limit)
    }

    /// The limit `compensation_limit` sets, if any.
    pub(crate) fn compensation_limit(&self) -> Option<f64> {
        let limit = self.setup.compensation_limit;
        (limit > 0.0).then_some(limit)
    }

    /// The correction added this tick.
    pub fn correction(&self) -> f64 {
        self.correction
    }

    /// The position sent to the drive: planned + correction (NMC cmdPos, HIMC GetPosOut).
    pub fn output_position(&self) -> f64 {
        self.cmd.p + self.correction
    }

    /// NMC MtGetBacklash and the rest of the compensation state.
    pub fn compensation_status(&self) -> CompensationStatus {
        self.compensation
            .as_deref()
            .map(Compensation::status)
            .unwrap_or_default()
    }

    /// The reference axes of the axis's grid table, copied out so that the engine can read
    /// them from the other axes before the tick.
    pub(crate) fn compensation_references(
        &self,
    ) -> Option<[Option<CompensationReference>; MAX_DIMENSIONS]> {
        let refs = self.compensation.as_deref()?.references();
        if refs.is_empty() {
            return None;
        }
        let mut out = [None; MAX_DIMENSIONS];
        for (slot, r) in out.iter_mut().zip(refs) {
            *slot = Some(*r);
        }
        Some(out)
    }

    /// A reference position for another axis's grid.
    pub(crate) fn reference_position(&self, source: ReferenceSource) -> f64 {
        match source {
            ReferenceSource::Planned => self.cmd.p,
            ReferenceSource::Actual => self.act_pos,
        }
    }

    pub(crate) fn set_compensation_inputs(&mut self, inputs: [f64; MAX_DIMENSIONS]) {
        if let Some(c) = self.compensation.as_deref_mut() {
            c.set_inputs(inputs);
        }
    }
}
