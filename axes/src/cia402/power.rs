//! The power state machine (CiA 402 §6.2.1, transitions 0–16): controlword commands, stop
//! ramps on leaving Operation enabled, quick stop, fault detection, reaction and reset.

use super::*;

impl Cia402Drive {
    pub(super) fn run_state_machine(
        &mut self,
        cw: u16,
        rises: u16,
        axis: &AxisStatus,
        out: &mut Vec<Command>,
    ) {
        if let Some(stop) = self.pending_stop {
            if stop.issued_at < self.steps && at_rest(axis) {
                self.pending_stop = None;
                self.finish_stop(stop.then, axis, out);
            }
        }
        match self.state {
            State::NotReadyToSwitchOn => {
                // The drive owns its axis's power: start unpowered.
                if axis.flags.contains(AxisFlags::ENABLED) {
                    self.power_off(out);
                }
                self.go(State::SwitchOnDisabled, 1);
                return;
            }
            // Waits for its stop ramp (above).
            State::FaultReactionActive => return,
            State::Fault => {
                self.fault_reset(rises, axis, out);
                return;
            }
            _ => {}
        }
        if let Some(code) = self.detect_fault(axis) {
            self.fault_reaction(code, axis, out);
            return;
        }
        use DeviceCommand as C;
        use State as S;
        match (self.state, DeviceCommand::decode(cw)) {
            (S::SwitchOnDisabled, C::Shutdown) => self.go(S::ReadyToSwitchOn, 2),
            (S::ReadyToSwitchOn, C::SwitchOn) => self.go(S::SwitchedOn, 3),
            // "Switch on + enable operation": 3, then 4 at once.
            (S::ReadyToSwitchOn, C::EnableOperation) => {
                self.go(S::SwitchedOn, 3);
                self.enable_operation(axis, out, 4);
            }
            (S::ReadyToSwitchOn, C::DisableVoltage | C::QuickStop) => self.disable_voltage(out, 7),
            (S::SwitchedOn, C::EnableOperation) => self.enable_operation(axis, out, 4),
            (S::SwitchedOn, C::Shutdown) => self.go(S::ReadyToSwitchOn, 6),
            (S::SwitchedOn, C::DisableVoltage | C::QuickStop) => self.disable_voltage(out, 10),
            (S::OperationEnabled, C::SwitchOn) => {
                self.leave_operation(S::SwitchedOn, 5, obj::DISABLE_OPERATION_OPTION, out)
            }
            (S::OperationEnabled, C::Shutdown) => {
                self.leave_operation(S::ReadyToSwitchOn, 8, obj::SHUTDOWN_OPTION, out)
            }
            (S::OperationEnabled, C::DisableVoltage) => {
                self.wind_down(out);
                self.power_off(out);
                self.go(S::SwitchOnDisabled, 9);
            }
            (S::OperationEnabled, C::QuickStop) => self.quick_stop(out),
            (S::QuickStopActive, C::DisableVoltage) => {
                self.pending_stop = None;
                self.power_off(out);
                self.go(S::SwitchOnDisabled, 12);
            }
            (S::QuickStopActive, C::EnableOperation)
                if self.int(obj::QUICK_STOP_OPTION, 0) >= 5 =>
            {
                self.pending_stop = None;
                self.enable_operation(axis, out, 16);
            }
            // Every other (state, command) pair is no transition.
            _ => {}
        }
    }

    pub(super) fn go(&mut self, state: State, transition: u8) {
        self.state = state;
        self.transitions.push(transition);
    }

    pub(super) fn finish_stop(
        &mut self,
        then: AfterStop,
        axis: &AxisStatus,
        out: &mut Vec<Command>,
    ) {
        match then {
            AfterStop::Disable => self.power_off(out),
            AfterStop::QuickStopDone => {
                if self.int(obj::QUICK_STOP_OPTION, 0) <= 4 {
                    self.power_off(out);
                    self.go(State::SwitchOnDisabled, 12);
                }
            }
            AfterStop::FaultDone => {
                if axis.flags.contains(AxisFlags::ENABLED) {
                    self.power_off(out);
                }
                self.powered_since = None;
                self.go(State::Fault, 14);
            }
        }
    }

    /// Transitions 7 and 10. A ramp still running from transition 5 or 8 ends in coasting.
    pub(super) fn disable_voltage(&mut self, out: &mut Vec<Command>, transition: u8) {
        if self.pending_stop.take().is_some() || self.powered_since.is_some() {
            self.power_off(out);
        }
        self.go(State::SwitchOnDisabled, transition);
    }

    pub(super) fn enable_operation(
        &mut self,
        axis: &AxisStatus,
        out: &mut Vec<Command>,
        transition: u8,
    ) {
        self.pending_stop = None;
        if self.powered_since.is_none() {
            self.power_on(out);
        }
        self.go(State::OperationEnabled, transition);
        self.enter_mode(axis);
        self.limit_refused = false;
    }

    /// Transitions 5 and 8: 0x605C / 0x605B option 0 removes power at once, 1 ramps down with
    /// the profile deceleration first.
    pub(super) fn leave_operation(
        &mut self,
        state: State,
        transition: u8,
        option: u16,
        out: &mut Vec<Command>,
    ) {
        self.wind_down(out);
        if self.int(option, 0) == 1 {
            out.push(self.stop(StopMode::Smooth, Some(self.slow_down_deceleration())));
            self.pending_stop = Some(PendingStop {
                issued_at: self.steps,
                then: AfterStop::Disable,
            });
        } else {
            self.power_off(out);
        }
        self.go(state, transition);
    }

    /// Transition 11 with 0x605A: 0 disable drive (and 12 at once); 1/5 slow-down ramp; 2/6
    /// quick stop ramp (0x6085); 3/4/7/8 current/voltage limit, i.e. as fast as the axis can.
    pub(super) fn quick_stop(&mut self, out: &mut Vec<Command>) {
        self.wind_down(out);
        let option = self.int(obj::QUICK_STOP_OPTION, 0);
        self.go(State::QuickStopActive, 11);
        if option == 0 {
            self.power_off(out);
            self.go(State::SwitchOnDisabled, 12);
            return;
        }
        let stop = match option {
            1 | 5 => self.stop(StopMode::Smooth, Some(self.slow_down_deceleration())),
            2 | 6 => self.stop(
                StopMode::Smooth,
                Some(self.int(obj::QUICK_STOP_DECELERATION, 0)),
            ),
            _ => self.stop(StopMode::Immediate, None),
        };
        out.push(stop);
        self.pending_stop = Some(PendingStop {
            issued_at: self.steps,
            then: AfterStop::QuickStopDone,
        });
    }

    pub(super) fn detect_fault(&mut self, axis: &AxisStatus) -> Option<u16> {
        if let Some(code) = self.pending_fault.take() {
            return Some(code);
        }
        if let Some((_, code)) = AXIS_FAULTS.iter().find(|(f, _)| axis.flags.contains(*f)) {
            return Some(*code);
        }
        let lost = self.state.is_operational()
            && self.power_confirmed
            && !axis.flags.contains(AxisFlags::ENABLED);
        lost.then_some(error_code::POWER_LOST)
    }

    /// Transition 13 with 0x605E: 0 disable drive; 1 slow-down ramp; 2 quick stop ramp; 3/4 as
    /// fast as possible. Fault (14) follows when the axis is at rest.
    pub(super) fn fault_reaction(&mut self, code: u16, axis: &AxisStatus, out: &mut Vec<Command>) {
        self.wind_down(out);
        self.set_error(code);
        self.go(State::FaultReactionActive, 13);
        if axis.flags.contains(AxisFlags::ENABLED) {
            let stop = match self.int(obj::FAULT_REACTION_OPTION, 0) {
                0 => None,
                1 => Some(self.stop(StopMode::Smooth, Some(self.slow_down_deceleration()))),
                2 => Some(self.stop(
                    StopMode::Smooth,
                    Some(self.int(obj::QUICK_STOP_DECELERATION, 0)),
                )),
                _ => Some(self.stop(StopMode::Immediate, None)),
            };
            match stop {
                Some(stop) => out.push(stop),
                None => self.power_off(out),
            }
        }
        self.pending_stop = Some(PendingStop {
            issued_at: self.steps,
            then: AfterStop::FaultDone,
        });
    }

    /// Transition 15: the 0 → 1 edge of bit 7 resets the axis; the drive leaves Fault once the
    /// axis shows no fault any more.
    pub(super) fn fault_reset(&mut self, rises: u16, axis: &AxisStatus, out: &mut Vec<Command>) {
        if rises & cw::FAULT_RESET != 0 {
            out.push(Command::from(Reset {
                axis: self.config.axis,
            }));
            self.reset_requested_at = Some(self.steps);
            return;
        }
        let Some(at) = self.reset_requested_at else {
            return;
        };
        if at < self.steps {
            self.reset_requested_at = None;
            if !axis.flags.intersects(axis_fault_flags()) {
                self.clear_error();
                self.warning = false;
                self.go(State::SwitchOnDisabled, 15);
            }
        }
    }

    pub(super) fn set_error(&mut self, code: u16) {
        let register = error_register(code);
        self.pending_fault = None;
        self.put(obj::ERROR_CODE, 0, Value::U16(code));
        self.put(obj::ERROR_REGISTER, 0, Value::U8(register));
        self.emergencies.push(Emergency { code, register });
    }

    pub(super) fn clear_error(&mut self) {
        self.put(obj::ERROR_CODE, 0, Value::U16(error_code::NO_ERROR));
        self.put(obj::ERROR_REGISTER, 0, Value::U8(0));
        self.emergencies.push(Emergency {
            code: error_code::NO_ERROR,
            register: 0,
        });
    }

    pub(super) fn power_on(&mut self, out: &mut Vec<Command>) {
        out.push(Command::from(Enable {
            axis: self.config.axis,
        }));
        self.powered_since = Some(self.steps);
        self.power_confirmed = false;
    }

    pub(super) fn power_off(&mut self, out: &mut Vec<Command>) {
        out.push(Command::from(Disable {
            axis: self.config.axis,
        }));
        self.powered_since = None;
        self.power_confirmed = false;
    }
}
