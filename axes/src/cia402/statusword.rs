//! Inputs and outputs of a tick: touch probes and actual values in, the statusword (common bits
//! and each mode's bits 10/12/13, window dwell times 0x6066–0x6070) out (CiA 402 §6.2.1.2).

use super::*;

impl Cia402Drive {
    /// 0x60FD from the switches; touch probes latch 0x6064 on edges of their inputs (probe 1
    /// input: the home switch; probe 2 has no input of its own; either may select the index
    /// pulse). Latching has servo-tick resolution.
    pub(super) fn update_inputs(&mut self, axis: &AxisStatus) {
        let f = axis.flags;
        let inputs = u32::from(f.contains(AxisFlags::HW_LIMIT_NEG))
            | u32::from(f.contains(AxisFlags::HW_LIMIT_POS)) << 1
            | u32::from(f.contains(AxisFlags::HOME_SWITCH)) << 2;
        self.put(obj::DIGITAL_INPUTS, 0, Value::U32(inputs));
        let function = self.int(obj::TOUCH_PROBE_FUNCTION, 0) as u16;
        let position = saturate(self.to_increments(axis.act_pos));
        let mut latched = [(false, false); 2];
        for (n, (probe, latch)) in self.probes.iter_mut().zip(&mut latched).enumerate() {
            let bits = (function >> (8 * n)) as u8;
            let own_input = n == 0 && f.contains(AxisFlags::HOME_SWITCH);
            let level = match (bits >> 2) & 0x03 {
                0 => own_input,
                1 => f.contains(AxisFlags::INDEX),
                _ => false,
            };
            *latch = probe.update(bits, level);
        }
        let [(p1_pos, p1_neg), (p2_pos, p2_neg)] = latched;
        for (hit, index) in [
            (p1_pos, obj::TOUCH_PROBE_1_POSITIVE),
            (p1_neg, obj::TOUCH_PROBE_1_NEGATIVE),
            (p2_pos, obj::TOUCH_PROBE_2_POSITIVE),
            (p2_neg, obj::TOUCH_PROBE_2_NEGATIVE),
        ] {
            if hit {
                self.put(index, 0, Value::I32(position));
            }
        }
        let [p1, p2] = self.probes;
        let status = p1.status() | p2.status() << 8;
        self.put(obj::TOUCH_PROBE_STATUS, 0, Value::U16(status));
    }

    pub(super) fn publish(&mut self, cw: u16, axis: &AxisStatus, now: f64) {
        let demand = self.to_increments(axis.cmd_pos);
        let actual = self.to_increments(axis.act_pos);
        let values = [
            (obj::POSITION_DEMAND, demand),
            (
                obj::POSITION_DEMAND_INTERNAL,
                demand.saturating_sub(self.home_shift),
            ),
            (obj::POSITION_ACTUAL, actual),
            (
                obj::POSITION_ACTUAL_INTERNAL,
                actual.saturating_sub(self.home_shift),
            ),
            (obj::VELOCITY_DEMAND, self.to_increments(axis.cmd_vel)),
            (obj::VELOCITY_ACTUAL, self.to_increments(axis.act_vel)),
            (
                obj::FOLLOWING_ERROR_ACTUAL,
                self.to_increments(axis.following_error),
            ),
        ];
        for (index, value) in values {
            self.put(index, 0, Value::I32(saturate(value)));
        }
        let torque = if self.streaming && self.mode == OperationMode::CyclicTorque {
            self.torque_demand
        } else {
            0
        };
        self.put(
            obj::TORQUE_ACTUAL,
            0,
            Value::I16(torque.clamp(-32768, 32767) as i16),
        );
        self.put(
            obj::MODES_OF_OPERATION_DISPLAY,
            0,
            Value::I8(self.mode.code()),
        );
        let statusword = self.compose_statusword(cw, axis, now);
        self.put(obj::STATUSWORD, 0, Value::U16(statusword));
    }

    pub(super) fn compose_statusword(&mut self, cw: u16, axis: &AxisStatus, now: f64) -> u16 {
        let f = axis.flags;
        let mut s = self.state.statusword_bits() | sw::REMOTE;
        if self.warning || f.contains(AxisFlags::FE_WARNING) {
            s |= sw::WARNING;
        }
        if f.intersects(LIMIT_FLAGS) || self.clamped || self.limit_refused {
            s |= sw::INTERNAL_LIMIT_ACTIVE;
        }
        if f.contains(AxisFlags::HOMED) {
            s |= sw::HOMED;
        }
        if f.contains(AxisFlags::MOVING) {
            s |= sw::MOVING;
        }
        s | self.mode_bits(cw, axis, now)
    }

    /// Bits 10, 12 and 13 (see `docs/decisions.md`, CiA 402 drive, for "target reached").
    pub(super) fn mode_bits(&mut self, cw: u16, axis: &AxisStatus, now: f64) -> u16 {
        let at_rest = at_rest(axis);
        let bit = |on: bool, mask: u16| if on { mask } else { 0 };
        if self.mode == OperationMode::Homing {
            // Homing status is kept across modes and states (python-canopen's `is_homed`).
            return match self.homing {
                HomingProgress::NotStarted | HomingProgress::Interrupted => sw::TARGET_REACHED,
                HomingProgress::InProgress { .. } => 0,
                HomingProgress::Attained => sw::OMS_12 | bit(at_rest, sw::TARGET_REACHED),
                HomingProgress::Error => sw::OMS_13 | bit(at_rest, sw::TARGET_REACHED),
            };
        }
        if self.state != State::OperationEnabled {
            self.target_dwell.reset();
            self.following_dwell.reset();
            self.zero_speed_dwell.reset();
            return 0;
        }
        let halt = cw & cw::HALT != 0;
        let following_error = self.following_error(axis, now);
        let follows = bit(self.streaming && self.stream_accepted, sw::OMS_12);
        match self.mode {
            OperationMode::NoMode | OperationMode::Homing => 0,
            OperationMode::ProfilePosition => {
                let idle = at_rest && axis.fifo_len == 0;
                let reached = if halt {
                    at_rest
                } else {
                    let near = self.pp_target.is_none_or(|t| self.near_position(axis, t));
                    self.dwell_position(idle && near, now)
                };
                bit(reached, sw::TARGET_REACHED)
                    | bit(self.set_point_ack, sw::OMS_12)
                    | bit(following_error, sw::OMS_13)
            }
            OperationMode::ProfileVelocity => {
                let target = self.last_velocity_command.map_or(0, |k| k.0);
                let reached = if halt {
                    at_rest
                } else {
                    self.dwell_velocity(axis, target, now)
                };
                let threshold = self.int(obj::VELOCITY_THRESHOLD, 0);
                let slow = self.to_increments(axis.act_vel).abs() <= threshold;
                let zero = self.zero_speed_dwell.update(
                    slow,
                    now,
                    self.int(obj::VELOCITY_THRESHOLD_TIME, 0),
                );
                bit(reached, sw::TARGET_REACHED) | bit(zero, sw::OMS_12)
            }
            OperationMode::CyclicPosition => {
                let (target, _) = self.clamp_position(self.int(obj::TARGET_POSITION, 0));
                let reached = if halt {
                    at_rest
                } else {
                    let near = self.near_position(axis, target);
                    self.dwell_position(near, now)
                };
                bit(reached, sw::TARGET_REACHED) | follows | bit(following_error, sw::OMS_13)
            }
            OperationMode::CyclicVelocity => {
                let limit = self.max_velocity();
                let target = self.int(obj::TARGET_VELOCITY, 0).clamp(-limit, limit);
                let reached = if halt {
                    at_rest
                } else {
                    self.dwell_velocity(axis, target, now)
                };
                bit(reached, sw::TARGET_REACHED) | follows
            }
            OperationMode::CyclicTorque => bit(halt && at_rest, sw::TARGET_REACHED) | follows,
        }
    }

    /// |actual − target| within 0x6067 (0xFFFFFFFF: window off, always near).
    pub(super) fn near_position(&self, axis: &AxisStatus, target: i64) -> bool {
        let window = self.int(obj::POSITION_WINDOW, 0);
        window == i64::from(u32::MAX) || (self.to_increments(axis.act_pos) - target).abs() <= window
    }

    pub(super) fn dwell_position(&mut self, condition: bool, now: f64) -> bool {
        let time = self.int(obj::POSITION_WINDOW_TIME, 0);
        self.target_dwell.update(condition, now, time)
    }

    /// |actual velocity − target| within 0x606D for 0x606E.
    pub(super) fn dwell_velocity(&mut self, axis: &AxisStatus, target: i64, now: f64) -> bool {
        let window = self.int(obj::VELOCITY_WINDOW, 0);
        let near = (self.to_increments(axis.act_vel) - target).abs() <= window;
        let time = self.int(obj::VELOCITY_WINDOW_TIME, 0);
        self.target_dwell.update(near, now, time)
    }

    /// |following error| beyond 0x6065 for longer than 0x6066 (0xFFFFFFFF: monitoring off).
    pub(super) fn following_error(&mut self, axis: &AxisStatus, now: f64) -> bool {
        let window = self.int(obj::FOLLOWING_ERROR_WINDOW, 0);
        let over = window != i64::from(u32::MAX)
            && self.to_increments(axis.following_error).abs() > window;
        let time = self.int(obj::FOLLOWING_ERROR_TIMEOUT, 0);
        self.following_dwell.update(over, now, time)
    }
}
