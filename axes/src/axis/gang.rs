//! The axis's side of a gantry and a handwheel (issue 12 items 6–7): the frames a gantry
//! follows in, its deviation and fault, and the handwheel mark. The registry is
//! `crate::coupling`; these are the few things it needs from inside the axis.

use super::{Activity, Axis, Context, Ramp};
use crate::command::CommandState;
use crate::param::ParamId;
use crate::status::AxisFlags;
use crate::types::ErrorKind;

impl Axis {
    /// The commanded position in the motor's frame (user frame less `set_position` and homing
    /// shifts): what a gantry slave follows, so that redefining the master's position moves
    /// no slave.
    pub(crate) fn commanded_motor_frame(&self) -> f64 {
        self.raw.p - self.cmd_offset
    }

    /// The shift between the user frame and the motor frame of the commanded position.
    pub(crate) fn commanded_frame_offset(&self) -> f64 {
        self.cmd_offset
    }

    /// Whether the axis has power (a disabled axis's commanded frame tracks its actual one).
    pub(crate) fn is_enabled(&self) -> bool {
        self.enabled
    }

    /// Commanded minus actual position (the status's `following_error`).
    pub(crate) fn following_error(&self) -> f64 {
        self.cmd.p - self.act_pos
    }

    /// Move both user frames by `delta`, as `set_position` with both frames does: a gantry
    /// slave takes its master's redefinition (homing, `set_position`) so the offset between
    /// them, as read, stays (HMC GantryInit: all axes are redefined together).
    pub(crate) fn shift_frames(&mut self, delta: f64, homed: bool) {
        self.shift_commanded(delta);
        self.act_offset += delta;
        self.act_pos += delta;
        if homed {
            self.flags |= AxisFlags::HOMED;
        }
    }

    /// Set the live gantry flags and deviation this tick's gantry supervision found.
    pub(crate) fn set_gantry(&mut self, deviation: f64, warning: bool, fault_shown: bool) {
        self.gantry_deviation = deviation;
        self.flags.put(AxisFlags::GANTRY_WARNING, warning);
        self.gantry_fault_shown = fault_shown;
    }

    /// The gantry's deviation went over its fault limit (HMC AxisStatus bit 6): latch
    /// `GANTRY_FAULT` and stop with `fast_decel`, commands ended, ErrorStop until `reset`.
    /// Latched on the master only: its slaves follow its stop ramp, so the gantry stays square
    /// (decisions.md, issue 12 gantry).
    pub(crate) fn gantry_fault(&mut self, ctx: &mut Context) {
        if self.latched.contains(AxisFlags::GANTRY_FAULT) {
            return;
        }
        self.latched |= AxisFlags::GANTRY_FAULT | AxisFlags::MOTION_ERROR;
        self.blocking |= AxisFlags::GANTRY_FAULT;
        self.last_error = Some(ErrorKind::Fault);
        self.abort_all(ctx, CommandState::Error(ErrorKind::Fault));
        if self.enabled {
            let decel = self.param(ParamId::FastDecel);
            self.plan_stop(ctx.tick, decel);
            self.activity = Activity::Ramping(Ramp::Fault);
        }
    }

    /// Mark the axis as driven by a handwheel (single-axis motion refused) or free.
    pub(crate) fn set_handwheel(&mut self, on: bool) {
        self.handwheel = on;
    }

    /// Whether a handwheel drives the axis.
    pub fn on_handwheel(&self) -> bool {
        self.handwheel
    }

    /// The encoder counter (a handwheel input).
    pub(crate) fn encoder_counts(&self) -> i64 {
        self.encoder.counts()
    }
}
