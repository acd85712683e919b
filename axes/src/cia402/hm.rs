//! Homing mode (HM, CiA 402 §6.3.5): start on the rising edge of bit 4, the engine's homing does
//! the motion, the drive tracks it into statusword bits 10/12/13.

use super::*;

impl Cia402Drive {
    /// HM: the rising edge of bit 4 starts homing with 0x6098/0x6099/0x609A/0x607C; its falling
    /// edge, or halt, interrupts it (stopping with the homing acceleration).
    pub(super) fn homing_mode(
        &mut self,
        rises: u16,
        falls: u16,
        halt: bool,
        out: &mut Vec<Command>,
    ) {
        let running = matches!(self.homing, HomingProgress::InProgress { .. });
        if running && (falls & cw::HOMING_START != 0 || (halt && rises & cw::HALT != 0)) {
            out.push(self.stop(
                StopMode::Smooth,
                Some(self.int(obj::HOMING_ACCELERATION, 0)),
            ));
            self.homing = HomingProgress::Interrupted;
        } else if !running && rises & cw::HOMING_START != 0 && !halt {
            self.start_homing(true, out);
        }
    }

    /// Start homing. Outside Operation enabled only method 37 (and its older number 35) runs,
    /// as a redefinition of the position: no motion, so no power is needed.
    pub(super) fn start_homing(&mut self, operational: bool, out: &mut Vec<Command>) {
        let method = self.int(obj::HOMING_METHOD, 0);
        self.homing_offset = self.int(obj::HOME_OFFSET, 0);
        let axis = self.config.axis;
        let direct = !operational;
        if direct {
            if !matches!(method, 35 | 37) {
                return;
            }
            out.push(Command::from(SetPosition {
                axis,
                position: self.to_units(self.homing_offset),
                frame: PositionFrame::Both,
            }));
        } else {
            out.push(Command::from(Home {
                axis,
                method: i16::try_from(method).ok(),
                switch_velocity: Some(self.to_units(self.int(obj::HOMING_SPEEDS, 1))),
                zero_velocity: Some(self.to_units(self.int(obj::HOMING_SPEEDS, 2))),
                acceleration: Some(self.to_units(self.int(obj::HOMING_ACCELERATION, 0))),
                offset: Some(self.to_units(self.homing_offset)),
                timeout: None,
                quirks: HomingQuirks::default(),
                buffer_mode: BufferMode::Aborting,
            }));
        }
        self.homing = HomingProgress::InProgress {
            since: self.steps,
            direct,
        };
    }

    /// Learn how a homing ended from the axis: HOMING_FAILED → error; no longer homing and
    /// HOMED → attained; no longer homing otherwise → interrupted.
    pub(super) fn track_homing(&mut self, axis: &AxisStatus, out: &mut Vec<Command>) {
        let HomingProgress::InProgress { since, direct } = self.homing else {
            return;
        };
        if since >= self.steps {
            return;
        }
        if direct {
            // A refused SetPosition has already turned this into an error (on_reply).
            self.homing_attained();
            return;
        }
        if axis.flags.contains(AxisFlags::HOMING_FAILED) {
            self.homing = HomingProgress::Error;
            // A failed homing is a homing error (bit 13), not a drive fault: clear the axis's
            // latch so that the master can move it again.
            if !axis.flags.intersects(axis_fault_flags()) {
                out.push(Command::from(Reset {
                    axis: self.config.axis,
                }));
            }
            return;
        }
        let busy = axis.state == AxisState::Homing
            || axis
                .current_command
                .is_some_and(|c| c.kind == CommandKind::Home);
        if busy {
            return;
        }
        if axis.flags.contains(AxisFlags::HOMED) {
            self.homing_attained();
        } else {
            self.homing = HomingProgress::Interrupted;
        }
    }

    pub(super) fn homing_attained(&mut self) {
        self.homing = HomingProgress::Attained;
        // HIMC §20 method 37: 0x6063 = 0x60FC = 0 where 0x6064 = 0x6062 = 0x607C.
        self.home_shift = self.homing_offset;
    }
}
