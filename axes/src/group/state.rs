//! The group state machine (PLCopen Part 4; HIMC §3.1, digest 004): which commands each state
//! takes, and the member checks behind enable, reset and ErrorStop.
//!
//! ```text
//! Disabled ──enable (every member enabled, at rest)──▶ Standby ──motion──▶ Moving
//!     ▲                                                 ▲  ▲                │ │ │
//!     └──────────── disable (from any state) ───────────┘  │    path done ──┘ │ │
//!                                                          │                  │ │
//!                       Stopping ◀──stop────────────────────────────────────────┘ │
//!                       │ at rest ──▶ Standby        Halted ◀──halt──────────────┘
//!                                                    │ continue ──▶ Moving
//! any enabled state ──member fault / refusal / e-stop──▶ ErrorStop ──reset (causes gone)──▶ Standby
//!                                     (every member disabled, no fault: reset ──▶ Disabled)
//! ```

use super::Group;
use crate::axis::Axis;
use crate::command::{AxisIndex, EngineError, ErrorKind};
use crate::status::{AxisFlags, AxisState, GroupFault, GroupState};

impl Group {
    /// Refuse `action` unless the group is in one of `states`.
    pub(super) fn require(
        &self,
        states: &[GroupState],
        action: &'static str,
    ) -> Result<(), EngineError> {
        if states.contains(&self.state) {
            Ok(())
        } else {
            Err(self.state_error(action))
        }
    }

    /// `action` refused in the group's present state.
    pub(super) fn state_error(&self, action: &'static str) -> EngineError {
        EngineError::GroupState {
            group: self.id,
            state: self.state,
            action,
        }
    }

    /// Motion and buffered commands are queued in Standby, Moving and Halted (PLCopen: a
    /// disabled, stopping or faulted group takes no motion).
    pub(super) fn require_accepts_motion(&self) -> Result<(), EngineError> {
        if self.jog.is_some() {
            // A jog is not a path: it is stopped before a program runs (docs/decisions.md,
            // "Group jog").
            return Err(EngineError::GroupState {
                group: self.id,
                state: self.state,
                action: "take path motion while it jogs (stop the jog first)",
            });
        }
        if self.off_path {
            return Err(EngineError::GroupState {
                group: self.id,
                state: self.state,
                action: "take motion off the path (a linear move back to the break point first)",
            });
        }
        self.require(
            &[GroupState::Standby, GroupState::Moving, GroupState::Halted],
            "take motion",
        )
    }

    /// The first member (or the result axis) that is not enabled and at rest (Standstill), with
    /// its state: enable and reset need every one there (HIMC: "only after all errors are
    /// cleared").
    pub(super) fn member_not_ready(&self, axes: &[Axis]) -> Option<(AxisIndex, AxisState)> {
        self.bound_axes().find_map(|a| {
            let state = axes
                .get(a as usize)
                .map_or(AxisState::Disabled, Axis::state);
            (state != AxisState::Standstill).then_some((a, state))
        })
    }

    /// Where a reset takes the group from ErrorStop once the causes are gone: Standby when
    /// every member is enabled and at rest; Disabled when every member is disabled without a
    /// fault (as an axis's reset leaves a disabled axis Disabled, PLCopen MC_Reset; after
    /// `emergency_stop_all` has disabled them); else the first member not ready, with its state.
    pub(super) fn reset_target(&self, axes: &[Axis]) -> Result<GroupState, (AxisIndex, AxisState)> {
        let state = |a: AxisIndex| {
            axes.get(a as usize)
                .map_or(AxisState::Disabled, Axis::state)
        };
        let all_disabled = self
            .members
            .iter()
            .all(|&a| state(a) == AxisState::Disabled);
        match self.member_not_ready(axes) {
            None => Ok(GroupState::Standby),
            Some(_) if all_disabled => Ok(GroupState::Disabled),
            Some(first) => Err(first),
        }
    }

    /// A member's trouble while the group is enabled: in ErrorStop, disabled, a latched fault,
    /// or (while the group feeds it) no longer in SynchronizedMotion (a limit stop, a
    /// single-axis stop). Any of these stops the whole group (issue 11 item 3); the result
    /// axis's too (digest 000 §6.1 (b): the whole interpolation is cancelled).
    pub(super) fn member_fault(&self, axes: &[Axis]) -> Option<GroupFault> {
        for a in self.bound_axes() {
            let Some(axis) = axes.get(a as usize) else {
                continue;
            };
            let state = axis.state();
            let faults = axis.latched() & AxisFlags::ERROR_STOP_FAULTS;
            let error = if state == AxisState::ErrorStop || !faults.is_empty() {
                Some(ErrorKind::Fault)
            } else if state == AxisState::Disabled {
                Some(ErrorKind::AxisDisabled)
            } else if self.feeding && state != AxisState::SynchronizedMotion {
                let limits = AxisFlags::HW_LIMIT_POS
                    | AxisFlags::HW_LIMIT_NEG
                    | AxisFlags::SW_LIMIT_POS
                    | AxisFlags::SW_LIMIT_NEG;
                Some(if axis.live_flags().intersects(limits) {
                    ErrorKind::LimitReached
                } else {
                    ErrorKind::InvalidState
                })
            } else {
                None
            };
            if let Some(error) = error {
                return Some(GroupFault::Member { axis: a, error });
            }
        }
        None
    }
}
