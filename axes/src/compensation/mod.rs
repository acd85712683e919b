//! Compensation after the planner (issue 12 item 8; digest 001 §2.19 and §4.1 position chain,
//! digest 004 §2.13): a correction added to an axis's planned position on its way to the drive.
//! The planned position does not include it; the output position and the drive do ("Reference
//! Position + Position Compensation = Position Output", digest 004 §2.13).
//!
//! Per tick the work is closed-form: a 1-D table walks from the segment it used last, a grid
//! finds its cell by division, the backlash moves one bounded step.

mod grid;
mod offset;
mod spline;
mod table;

pub use grid::{Grid, MAX_DIMENSIONS, MAX_GRID_VALUES};
pub use table::Table1d;

use serde::{Deserialize, Serialize};

use crate::command::{
    AxisIndex, BacklashDirection, CompensationBacklash, CompensationInterpolation,
    CompensationKind, CompensationLeadScrew, CompensationReference, CompensationTable,
    ReferenceSource, MAX_MAGNITUDE,
};
use crate::error::EngineError;

/// An axis's compensation tables and their state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Compensation {
    enabled: bool,
    lead_screw: Option<LeadScrew>,
    backlash: Option<Backlash>,
    table: Option<GridTable>,
    /// The backlash correction reached so far (it moves by at most `step` per tick).
    backlash_now: f64,
    /// The planned motion's last nonzero direction: +1 or −1 (at rest the last one holds).
    direction: f64,
    /// The reference positions of the grid as the engine gathered them before this tick.
    inputs: [f64; MAX_DIMENSIONS],
    /// The correction of the last tick.
    correction: f64,
    /// HMC axis position compensation: an offset moved by its own profile.
    offset: offset::Offset,
}

#[derive(Clone, Debug, PartialEq)]
struct LeadScrew {
    positive: Table1d,
    negative: Table1d,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Backlash {
    amount: f64,
    step: f64,
    direction: BacklashDirection,
}

#[derive(Clone, Debug, PartialEq)]
struct GridTable {
    references: Vec<CompensationReference>,
    grid: Grid,
}

/// What the status and snapshot show of an axis's compensation.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CompensationStatus {
    pub enabled: bool,
    /// The kinds installed.
    pub kinds: Vec<CompensationKind>,
    /// The correction added to the planned position this tick (user units).
    pub correction: f64,
    /// The backlash part of it.
    pub backlash: f64,
    /// NMC MtGetBacklash: (amount, step, direction).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub backlash_setting: Option<(f64, f64, BacklashDirection)>,
    /// The HMC position-compensation offset part of `correction`.
    #[serde(default)]
    pub offset: f64,
    /// Its move is in progress (HMC GetAxisCompenState 1; 0 done).
    #[serde(default)]
    pub offset_moving: bool,
}

impl Compensation {
    /// Install a lead-screw table pair (replacing the previous one).
    pub fn set_lead_screw(&mut self, c: &CompensationLeadScrew) -> Result<(), EngineError> {
        let id = u32::from(c.axis);
        let positive = Table1d::new(id, &c.positions, &c.positive)?;
        let negative = match &c.negative {
            Some(n) => Table1d::new(id, &c.positions, n)?,
            None => positive.clone(),
        };
        self.lead_screw = Some(LeadScrew { positive, negative });
        Ok(())
    }

    /// Install the backlash setting (an amount of 0 removes it).
    pub fn set_backlash(&mut self, c: &CompensationBacklash) -> Result<(), EngineError> {
        let bad = |reason: String| EngineError::InvalidCompensation {
            axis: u32::from(c.axis),
            reason,
        };
        let (amount, step) = (c.amount, c.step);
        if !amount.is_finite() || !(0.0..=MAX_MAGNITUDE).contains(&amount) {
            return Err(bad(format!(
                "backlash amount = {amount}: must be a finite number within 0..1e12"
            )));
        }
        if !step.is_finite() || step <= 0.0 {
            return Err(bad(format!(
                "backlash step = {step}: must be a finite number > 0"
            )));
        }
        self.backlash = (amount > 0.0).then_some(Backlash {
            amount,
            step,
            direction: c.direction,
        });
        Ok(())
    }

    /// Install a grid table (replacing the previous one). `count` axes exist.
    pub fn set_table(&mut self, c: &CompensationTable, count: u32) -> Result<(), EngineError> {
        let id = u32::from(c.axis);
        if c.references.len() != c.start.len() {
            return Err(EngineError::InvalidCompensation {
                axis: id,
                reason: format!(
                    "{} reference axes but {} start positions",
                    c.references.len(),
                    c.start.len()
                ),
            });
        }
        let grid = Grid::new(id, &c.start, &c.step, &c.count, &c.values)?.with_options(
            id,
            c.angle,
            c.interpolation == CompensationInterpolation::Cubic,
        )?;
        if let Some(r) = c.references.iter().find(|r| u32::from(r.axis) >= count) {
            return Err(EngineError::InvalidAxis {
                axis: u32::from(r.axis),
                count,
            });
        }
        self.table = Some(GridTable {
            references: c.references.clone(),
            grid,
        });
        Ok(())
    }

    pub fn set_enabled(&mut self, on: bool) {
        self.enabled = on;
    }

    /// Switch the tables on: refused while there are none.
    pub fn enable(&mut self, axis: u32) -> Result<(), EngineError> {
        if self.is_empty() {
            return Err(EngineError::InvalidCompensation {
                axis,
                reason: "no compensation table is set".into(),
            });
        }
        self.enabled = true;
        Ok(())
    }

    pub fn is_enabled(&self) -> bool {
        self.enabled
    }

    /// Whether any table is installed.
    pub fn is_empty(&self) -> bool {
        self.lead_screw.is_none() && self.backlash.is_none() && self.table.is_none()
    }

    /// The grid's references that the engine reads from the axes before the tick (the axis's
    /// own planned position is read in the tick itself).
    pub fn references(&self) -> &[CompensationReference] {
        self.table.as_ref().map_or(&[], |t| t.references.as_slice())
    }

    /// The engine's gathered reference positions, one per reference.
    pub fn set_inputs(&mut self, inputs: [f64; MAX_DIMENSIONS]) {
        self.inputs = inputs;
    }

    /// The correction for this tick from the planned position and velocity of `axis`.
    pub fn correction(&mut self, axis: AxisIndex, planned: f64, velocity: f64) -> f64 {
        if velocity > 0.0 {
            self.direction = 1.0;
        } else if velocity < 0.0 {
            self.direction = -1.0;
        }
        // The HMC offset is commanded on its own, apart from the tables' enable.
        let offset = self.offset.step();
        if !self.enabled {
            // Disabled: the backlash is taken back at its rate, the tables drop out at once.
            self.backlash_now = self.step_backlash(0.0);
            self.correction = self.backlash_now + offset;
            return self.correction;
        }
        let mut c = offset + self.lead_screw_value(planned);
        if let Some(b) = self.backlash {
            // TV 72: moving in the compensated direction, ±amount is added at `step` per period.
            let target = match b.direction {
                BacklashDirection::Positive if self.direction > 0.0 => b.amount,
                BacklashDirection::Negative if self.direction < 0.0 => -b.amount,
                _ => 0.0,
            };
            self.backlash_now = self.step_backlash(target);
        } else {
            self.backlash_now = 0.0;
        }
        c += self.backlash_now;
        c += self.grid_value(axis, planned);
        self.correction = c;
        c
    }

    /// What the correction would be with the tables enabled, the axis at rest at `planned` and
    /// the references at `inputs`: the up-front check of the compensation limit when the
    /// tables are switched on (digest 004 §2.13, TV 63 "at the current ref position").
    pub fn value_at_rest(
        &mut self,
        axis: AxisIndex,
        planned: f64,
        inputs: [f64; MAX_DIMENSIONS],
    ) -> f64 {
        self.inputs = inputs;
        self.offset.position()
            + self.lead_screw_value(planned)
            + self.backlash_now
            + self.grid_value(axis, planned)
    }

    /// The lead-screw table's value at `planned` in the last direction of motion.
    fn lead_screw_value(&mut self, planned: f64) -> f64 {
        let Some(ls) = self.lead_screw.as_mut() else {
            return 0.0;
        };
        if self.direction < 0.0 {
            ls.negative.value_at(planned)
        } else {
            ls.positive.value_at(planned)
        }
    }

    /// The grid's value at the gathered inputs, `axis`'s own planned position at `planned`.
    fn grid_value(&self, axis: AxisIndex, planned: f64) -> f64 {
        let Some(t) = self.table.as_ref() else {
            return 0.0;
        };
        let mut x = self.inputs;
        for (slot, r) in x.iter_mut().zip(&t.references) {
            if r.axis == axis && r.source == ReferenceSource::Planned {
                *slot = planned;
            }
        }
        t.grid.value_at(&x)
    }

    /// One tick of the backlash towards `target`, by at most its step.
    fn step_backlash(&self, target: f64) -> f64 {
        let step = self.backlash.map_or(f64::INFINITY, |b| b.step);
        let now = self.backlash_now;
        now + (target - now).clamp(-step, step)
    }

    /// The correction of the last tick.
    pub fn last_correction(&self) -> f64 {
        self.correction
    }

    pub fn status(&self) -> CompensationStatus {
        let mut kinds = Vec::new();
        if self.lead_screw.is_some() {
            kinds.push(CompensationKind::LeadScrew);
        }
        if self.backlash.is_some() {
            kinds.push(CompensationKind::Backlash);
        }
        if self.table.is_some() {
            kinds.push(CompensationKind::Table);
        }
        CompensationStatus {
            enabled: self.enabled,
            kinds,
            correction: self.correction,
            backlash: self.backlash_now,
            backlash_setting: self.backlash.map(|b| (b.amount, b.step, b.direction)),
            offset: self.offset.position(),
            offset_moving: self.offset.is_moving(),
        }
    }

    /// `compensation_offset_amount` (HMC_SetAxisCompenPos).
    pub fn set_offset_amount(&mut self, axis: AxisIndex, amount: f64) -> Result<(), EngineError> {
        self.offset.set_amount(u32::from(axis), amount)
    }

    /// `compensation_offset_profile` (HMC_SetAxisCompenPara).
    pub fn set_offset_profile(
        &mut self,
        c: &crate::command::CompensationOffsetProfile,
    ) -> Result<(), EngineError> {
        self.offset.set_profile(u32::from(c.axis), c)
    }

    /// `compensation_offset_trigger` (HMC_TrigAxisCompens), ticks of `period` seconds.
    pub fn trigger_offset(&mut self, axis: AxisIndex, period: f64) -> Result<(), EngineError> {
        self.offset.trigger(u32::from(axis), period)
    }

    /// `compensation_offset_stop` (HMC_StopAxisCompens).
    pub fn stop_offset(&mut self) {
        self.offset.stop();
    }

    /// The HMC offset now, and whether it moves.
    pub fn offset(&self) -> (f64, bool) {
        (self.offset.position(), self.offset.is_moving())
    }
}
