//! Cyclic synchronous modes (CSP, CSV, CST; CiA 402 §6.3.7–6.3.9): one target per sync period,
//! interpolated between periods, streamed to the axis as setpoints.

use super::*;

impl Cia402Drive {
    /// The interpolation period (0x60C2), seconds; 0 when unset.
    pub(super) fn interpolation_period(&self) -> f64 {
        let value = self.int(obj::INTERPOLATION_TIME_PERIOD, 1) as f64;
        let index = self.int(obj::INTERPOLATION_TIME_PERIOD, 2) as i32;
        value * 10f64.powi(index)
    }

    /// CSP (CiA 402 §6.3.4): a new target is reached linearly over the interpolation period
    /// from where the set-point stood, so a master whose SYNC is slower than the servo tick
    /// still gives a smooth stream; a period at or below the tick passes targets through.
    pub(super) fn interpolate(&mut self, target: i64) -> f64 {
        let period = self.interpolation_period();
        let current = match self.csp_segment {
            Some(s) => s.at(self.now, period),
            None => target as f64,
        };
        match self.csp_segment {
            Some(s) if s.to == target => {}
            _ => {
                self.csp_segment = Some(CspSegment {
                    from: current,
                    to: target,
                    started: self.now,
                })
            }
        }
        self.csp_segment
            .map_or(target as f64, |s| s.at(self.now + self.dt, period))
    }

    /// CSP/CSV/CST: one setpoint every tick from 0x607A / 0x60FF / 0x6071; halt ends the stream
    /// and stops with 0x605D's ramp.
    pub(super) fn cyclic(&mut self, halt: bool, rises: u16, out: &mut Vec<Command>) {
        let axis = self.config.axis;
        if halt {
            if self.streaming {
                out.push(Command::from(StreamSetpoint {
                    axis,
                    setpoint: None,
                }));
                self.streaming = false;
            }
            if rises & cw::HALT != 0 {
                out.push(self.stop(StopMode::Smooth, Some(self.halt_deceleration())));
            }
            self.clamped = false;
            return;
        }
        let setpoint = match self.mode {
            OperationMode::CyclicVelocity => {
                let limit = self.max_velocity();
                let raw = self.int(obj::TARGET_VELOCITY, 0);
                let velocity = raw.clamp(-limit, limit);
                self.clamped = velocity != raw;
                Setpoint::Velocity {
                    velocity: self.to_units(velocity),
                }
            }
            OperationMode::CyclicTorque => {
                let limit = self.int(obj::MAX_TORQUE, 0);
                let raw = self.int(obj::TARGET_TORQUE, 0);
                let torque = raw.clamp(-limit, limit);
                self.clamped = torque != raw;
                self.torque_demand = torque;
                // ‰ of rated torque → fraction of rated torque.
                Setpoint::Torque {
                    torque: torque as f64 / 1000.0,
                }
            }
            _ => {
                let (position, clamped) = self.clamp_position(self.int(obj::TARGET_POSITION, 0));
                self.clamped = clamped;
                let interpolated = self.interpolate(position);
                Setpoint::Position {
                    position: self.to_units_f64(interpolated),
                }
            }
        };
        if !self.streaming {
            self.stream_accepted = true;
        }
        out.push(Command::from(StreamSetpoint {
            axis,
            setpoint: Some(setpoint),
        }));
        self.streaming = true;
    }
}
