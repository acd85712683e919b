//! HMC add axis (digest 000 §4.4 `HMC_SetAddAxis`): base displacement = its own command's +
//! the add axis's commanded displacement. Unlike a coupling the base keeps its own command
//! source (moves, jogs, streams); the add axis's travel of each tick is laid on top of it
//! (`Axis::add_displacement`) just before the base steps, the add axis having stepped first.
//!
//! The add axis's travel is read in its motor frame (`commanded_motor_frame`), so redefining
//! the add axis's position (`set_position`, homing) does not move the base.

use crate::axis::Axis;
use crate::command::AxisIndex;

/// One base axis and the axis whose displacement is added to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AddLink {
    pub base: AxisIndex,
    pub add: AxisIndex,
    /// The add axis's commanded position (motor frame) of the last tick.
    previous: f64,
}

impl AddLink {
    /// Start adding `add`'s travel from where it stands now.
    pub fn new(base: AxisIndex, add: &Axis, add_index: AxisIndex) -> AddLink {
        AddLink {
            base,
            add: add_index,
            previous: add.commanded_motor_frame(),
        }
    }

    /// The add axis's travel since the last tick (it has stepped this tick).
    pub fn travel(&mut self, add: &Axis) -> f64 {
        let now = add.commanded_motor_frame();
        let travel = now - self.previous;
        self.previous = now;
        travel
    }
}
