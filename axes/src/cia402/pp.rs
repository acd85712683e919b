//! Profile position mode (PP, CiA 402 §6.3.1): set-point handshake, single set-point and
//! change-set-immediately, relative and absolute targets.

use super::*;

impl Cia402Drive {
    /// PP set-point handshake (CiA 402 §10 profile position): a rising edge of bit 4 hands over
    /// 0x607A; bit 12 acknowledges and stays set while the set-point buffer (the running move
    /// plus one) is full; bit 5 aborts the running move, else the set-point is queued. Bit 9
    /// (change on set-point) is accepted but queued set-points stop in between: the engine has
    /// no blending buffer mode yet.
    pub(super) fn profile_position(
        &mut self,
        cw: u16,
        rises: u16,
        halt: bool,
        axis: &AxisStatus,
        out: &mut Vec<Command>,
    ) {
        let immediate = cw & cw::CHANGE_SET_IMMEDIATELY != 0;
        let room = immediate || axis.fifo_len < 2;
        if rises & cw::NEW_SET_POINT != 0 && room && !halt {
            let raw = self.int(obj::TARGET_POSITION, 0);
            let relative = cw & cw::RELATIVE != 0;
            let wanted = if relative {
                self.pp_reference.saturating_add(raw)
            } else {
                raw
            };
            let (target, clamped_position) = self.clamp_position(wanted);
            let (velocity, clamped_velocity) = self.profile_velocity_limit();
            let (velocity, acceleration, deceleration, jerk) = (
                Some(self.to_units(velocity)),
                Some(self.to_units(self.int(obj::PROFILE_ACCELERATION, 0))),
                Some(self.to_units(self.int(obj::PROFILE_DECELERATION, 0))),
                self.jerk(),
            );
            let axis_index = self.config.axis;
            // A relative set-point is relative to the preceding target (0x60F2 default). The
            // engine's buffered MoveRelative starts from the previous command's end, which is
            // that target; an aborting one would start from the current position, so a changed-
            // immediately relative set-point goes out as the absolute target it means.
            let command = if relative && !immediate {
                Command::from(MoveRelative {
                    axis: axis_index,
                    distance: self.to_units(target - self.pp_reference),
                    velocity,
                    acceleration,
                    deceleration,
                    jerk,
                    buffer_mode: BufferMode::Buffered,
                })
            } else {
                Command::from(MoveAbsolute {
                    axis: axis_index,
                    position: self.to_units(target),
                    velocity,
                    acceleration,
                    deceleration,
                    jerk,
                    buffer_mode: if immediate {
                        BufferMode::Aborting
                    } else {
                        BufferMode::Buffered
                    },
                })
            };
            out.push(command);
            self.pp_reference = target;
            self.pp_target = Some(target);
            self.set_point_ack = true;
            self.clamped = clamped_position || clamped_velocity;
            self.target_dwell.reset();
        } else if cw & cw::NEW_SET_POINT == 0 && room {
            self.set_point_ack = false;
        }
    }
}
