//! Modes of operation (0x6060/0x6061): switching between them and running the active one; the
//! halt bit shared by the profile modes (CiA 402 §6.3).

use super::*;

impl Cia402Drive {
    /// Follow 0x6060. Leaving a mode in Operation enabled ends what it started: a setpoint
    /// stream, a homing, a profile move (stopped with the slow-down ramp).
    pub(super) fn switch_mode(&mut self, axis: &AxisStatus, out: &mut Vec<Command>) {
        let code = self.int(obj::MODES_OF_OPERATION, 0);
        let requested = i8::try_from(code)
            .ok()
            .and_then(OperationMode::from_code)
            .unwrap_or(self.mode);
        if requested == self.mode {
            return;
        }
        let old = self.mode;
        // Between cyclic modes the next setpoint simply takes over.
        let bumpless = old.is_cyclic() && requested.is_cyclic();
        if self.state == State::OperationEnabled && !bumpless && old != OperationMode::NoMode {
            let busy = axis.flags.contains(AxisFlags::MOVING)
                || axis.fifo_len > 0
                || matches!(self.homing, HomingProgress::InProgress { .. });
            let deceleration = self.slow_down_deceleration();
            self.wind_down(out);
            if busy {
                out.push(self.stop(StopMode::Smooth, Some(deceleration)));
            }
        }
        self.mode = requested;
        self.enter_mode(axis);
    }

    pub(super) fn enter_mode(&mut self, axis: &AxisStatus) {
        self.set_point_ack = false;
        self.csp_segment = None;
        self.pp_reference = self.to_increments(axis.cmd_pos);
        self.pp_target = None;
        self.last_velocity_command = None;
        self.clamped = false;
        self.target_dwell.reset();
    }

    /// End the mode's activity when leaving Operation enabled or the mode.
    pub(super) fn wind_down(&mut self, out: &mut Vec<Command>) {
        if self.streaming {
            out.push(Command::from(StreamSetpoint {
                axis: self.config.axis,
                setpoint: None,
            }));
            self.streaming = false;
        }
        if matches!(
            self.homing,
            HomingProgress::InProgress { direct: false, .. }
        ) {
            self.homing = HomingProgress::Interrupted;
        }
        self.engine_halted = false;
        self.set_point_ack = false;
        self.last_velocity_command = None;
        self.torque_demand = 0;
        self.clamped = false;
    }

    pub(super) fn run_mode(
        &mut self,
        cw: u16,
        rises: u16,
        falls: u16,
        axis: &AxisStatus,
        out: &mut Vec<Command>,
    ) {
        let halt = cw & cw::HALT != 0;
        match self.mode {
            OperationMode::NoMode => {}
            OperationMode::ProfilePosition => {
                self.halt_profile(halt, axis, out);
                self.profile_position(cw, rises, halt, axis, out);
            }
            OperationMode::ProfileVelocity => {
                self.halt_profile(halt, axis, out);
                if !halt {
                    self.profile_velocity(out);
                }
            }
            OperationMode::Homing => self.homing_mode(rises, falls, halt, out),
            OperationMode::CyclicPosition
            | OperationMode::CyclicVelocity
            | OperationMode::CyclicTorque => self.cyclic(halt, rises, out),
        }
    }

    /// Bit 8 in PP and PV: pause with 0x605D's ramp, keeping the plan (engine Halt/Resume).
    /// An idle axis gets no Halt: nothing starts while bit 8 is set anyway.
    pub(super) fn halt_profile(&mut self, halt: bool, axis: &AxisStatus, out: &mut Vec<Command>) {
        let busy = axis.flags.contains(AxisFlags::MOVING) || axis.fifo_len > 0;
        if halt && !self.engine_halted && busy {
            out.push(Command::from(Halt {
                axis: self.config.axis,
                deceleration: Some(self.to_units(self.halt_deceleration())),
            }));
            self.engine_halted = true;
        } else if !halt && self.engine_halted {
            out.push(Command::from(Resume {
                axis: self.config.axis,
            }));
            self.engine_halted = false;
        }
    }
}
