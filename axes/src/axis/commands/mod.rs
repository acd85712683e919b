//! Commands addressed to one axis (ARCHITECTURE §3.5): validation, admission, the FIFO, and the
//! immediate ones (enable, stop, set parameter …). This file holds the admission checks every
//! command passes; the commands themselves are in `power`, `motion`, `parameters` and `streams`.

mod motion;
mod parameters;
mod power;
mod pvt;
mod streams;

pub use streams::Feed;

use super::{
    apply_rollover, counts_per_unit, pulses_per_unit, setup::Setup, smoothing_window, Activity,
    Axis, Context, MotionAction, Overrides, Queued, Ramp, Run, RunGoal, Source,
};
use crate::command::{
    bounded, finite, positive, AxisInput, BufferMode, CancelScope, CommandKind, CommandState,
    Direction, EngineError, ErrorKind, PositionFrame, Reply, Setpoint, StopMode,
};
use crate::homing::{Homing, HomingHardware, HomingSpec};
use crate::hw::AxisClass;
use crate::param::{ParamAccess, ParamId};
use crate::profile::{Goal, MovingAverage, PlanError};
use crate::status::AxisFlags;

/// A motion request as it arrives, before it gets an id.
pub(crate) struct MotionSubmission {
    pub kind: CommandKind,
    pub action: MotionAction,
    pub overrides: Overrides,
    pub buffer_mode: BufferMode,
}

impl Axis {
    fn refuse<T>(&mut self, e: EngineError) -> Result<T, EngineError> {
        self.last_error = Some(e.kind());
        Err(e)
    }

    fn invalid_state(&self, action: &'static str) -> EngineError {
        EngineError::InvalidState {
            axis: self.index,
            state: self.state(),
            action,
        }
    }

    /// Refuse motion unless the axis can move now.
    fn check_can_move(&self) -> Result<(), EngineError> {
        if !self.class.can_move() {
            return Err(EngineError::Unsupported {
                what: format!(
                    "motion on axis {} of type {} (encoder-only or unused)",
                    self.index,
                    self.param(ParamId::AxisType)
                ),
            });
        }
        if !self.blocking.is_empty() {
            return Err(EngineError::AxisInError {
                axis: self.index,
                faults: self.blocking,
            });
        }
        if !self.enabled {
            return Err(EngineError::AxisDisabled { axis: self.index });
        }
        if self.class == AxisClass::ClosedLoop && !self.flag(ParamId::ServoLoop) {
            return Err(EngineError::Unsupported {
                what: format!(
                    "motion on axis {} with servo_loop = 0: in open loop the commanded position tracks the actual one (HMC §2.1)",
                    self.index
                ),
            });
        }
        if let Activity::Ramping(Ramp::Stop(_) | Ramp::Fault) = self.activity {
            return Err(self.invalid_state("start motion before the stop has finished"));
        }
        Ok(())
    }

    /// Refuse motion further into an active limit; motion out of it is fine (HMC §3.3.5,
    /// NMC §3.2 "reverse motion allowed, same direction blocked").
    pub(super) fn admit(&self, direction: Option<Direction>) -> Result<(), EngineError> {
        let Some(direction) = direction else {
            return Ok(());
        };
        let blocked = match direction {
            Direction::Positive => {
                self.flags.intersects(AxisFlags::SW_LIMIT_POS)
                    || (self.flags.contains(AxisFlags::HW_LIMIT_POS)
                        && !self.flag(ParamId::IgnoreHwLimits))
            }
            Direction::Negative => {
                self.flags.intersects(AxisFlags::SW_LIMIT_NEG)
                    || (self.flags.contains(AxisFlags::HW_LIMIT_NEG)
                        && !self.flag(ParamId::IgnoreHwLimits))
            }
        };
        if blocked {
            Err(EngineError::LimitActive {
                axis: self.index,
                direction,
            })
        } else {
            Ok(())
        }
    }

    fn check_overrides(o: &Overrides) -> Result<(), EngineError> {
        if let Some(v) = o.velocity {
            positive("velocity", bounded("velocity", v)?)?;
        }
        if let Some(a) = o.acceleration {
            positive("acceleration", a)?;
        }
        if let Some(d) = o.deceleration {
            positive("deceleration", d)?;
        }
        if let Some(j) = o.jerk {
            let j = finite("jerk", j)?;
            if j < 0.0 {
                return Err(EngineError::InvalidArgument {
                    name: "jerk",
                    value: j,
                    reason: "must be ≥ 0 (0 = trapezoid)",
                });
            }
        }
        Ok(())
    }

    // ------------------------------------------------------------------ motion commands
}

/// The direction of a signed distance or velocity, none for 0.
fn direction_of_travel(delta: f64) -> Option<Direction> {
    if delta > 0.0 {
        Some(Direction::Positive)
    } else if delta < 0.0 {
        Some(Direction::Negative)
    } else {
        None
    }
}

/// A planner refusal as an engine error. Limits come from validated parameters and checked
/// overrides, so this is reached only with extreme but finite values.
fn plan_error(e: PlanError) -> EngineError {
    let (name, value, reason) = match e {
        PlanError::InvalidLimit { name, value } => (name, value, "must be a positive number"),
        PlanError::NotFinite { name, value } => (name, value, "must be finite"),
        PlanError::Negative { name, value } => (name, value, "must not be negative"),
        PlanError::Unrepresentable => (
            "profile",
            f64::NAN,
            "does not fit in f64: the limits or the distance are too extreme",
        ),
    };
    EngineError::InvalidArgument {
        name,
        value,
        reason,
    }
}
