//! Command filters after the planner (issue 14; digest 004 §2.14, HIMC chapter 15): an input
//! shaper (a sum of delayed impulses) or a vibration suppression filter (a notch) between the
//! planned (and smoothed) position and the output stage. The planned position stays the
//! planner's; the commanded position is the filtered one, and a move is done only once the
//! filter has settled on its input.
//!
//! Per tick the work is bounded: a shaper sums at most 4 interpolated ring-buffer samples, the
//! notch is one biquad step.

mod notch;
mod shaper;

pub use notch::Notch;
pub use shaper::{Shaper, MAX_SHAPER_TICKS};

use serde::{Deserialize, Serialize};

/// Which impulse sequence an input shaper uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShaperType {
    /// Zero vibration: 2 impulses over half a damped period (HIMC `SHAPER_NORMAL` 1).
    #[default]
    Zv,
    /// Zero vibration and derivative: 3 impulses over a damped period, robust to a frequency
    /// error (HIMC `SHAPER_ROBUST` 0).
    Zvd,
    /// Extra insensitive (5 % tolerated vibration): 3 impulses over a damped period.
    Ei,
}

/// Which slot a filter is installed in: the axis's own (used while the axis is not in a group)
/// or its group's (used while it is; digest 004 §2.14: "Axis InShape has no effect on
/// coordinated (group) motion; use Group InShape there").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilterSlot {
    #[default]
    Axis,
    Group,
}

/// What the status shows of an axis's active command filter.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum FilterStatus {
    InputShaping {
        shaper: ShaperType,
        frequency: f64,
        damping: f64,
        /// The slot it sits in.
        slot: FilterSlot,
        /// The shaper's length: how much later than the plan the output arrives (s).
        delay: f64,
    },
    Vsf {
        frequency: f64,
        damping: f64,
    },
}

/// One command filter.
#[derive(Clone, Debug, PartialEq)]
pub enum CommandFilter {
    Shaper(Shaper),
    Notch(Notch),
}

impl CommandFilter {
    /// This tick's output for this tick's input.
    pub fn next(&mut self, input: f64) -> f64 {
        match self {
            CommandFilter::Shaper(s) => s.next(input),
            CommandFilter::Notch(n) => n.next(input),
        }
    }

    /// The output has arrived at the (constant) input and stays there.
    pub fn is_settled(&self) -> bool {
        match self {
            CommandFilter::Shaper(s) => s.is_settled(),
            CommandFilter::Notch(n) => n.is_settled(),
        }
    }

    /// Forget the past: at rest at `position`.
    pub fn reset(&mut self, position: f64) {
        match self {
            CommandFilter::Shaper(s) => s.reset(position),
            CommandFilter::Notch(n) => n.reset(position),
        }
    }

    pub fn status(&self, slot: FilterSlot) -> FilterStatus {
        match self {
            CommandFilter::Shaper(s) => FilterStatus::InputShaping {
                shaper: s.shaper(),
                frequency: s.frequency(),
                damping: s.damping(),
                slot,
                delay: s.delay(),
            },
            CommandFilter::Notch(n) => FilterStatus::Vsf {
                frequency: n.frequency(),
                damping: n.damping(),
            },
        }
    }
}

/// An axis's two filter slots.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CommandFilters {
    pub axis: Option<CommandFilter>,
    pub group: Option<CommandFilter>,
    /// The slot the last tick ran (none: reset the active one before its next tick).
    pub active: Option<FilterSlot>,
}

impl CommandFilters {
    pub fn slot_mut(&mut self, slot: FilterSlot) -> &mut Option<CommandFilter> {
        match slot {
            FilterSlot::Axis => &mut self.axis,
            FilterSlot::Group => &mut self.group,
        }
    }

    pub fn slot(&self, slot: FilterSlot) -> Option<&CommandFilter> {
        match slot {
            FilterSlot::Axis => self.axis.as_ref(),
            FilterSlot::Group => self.group.as_ref(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.axis.is_none() && self.group.is_none()
    }
}

#[cfg(test)]
mod tests;
