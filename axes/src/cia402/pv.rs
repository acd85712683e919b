//! Profile velocity mode (PV, CiA 402 §6.3.3).

use super::*;

impl Cia402Drive {
    /// PV: command 0x60FF (limited by 0x607F/0x6080) with 0x6083/0x6084 whenever any changes.
    pub(super) fn profile_velocity(&mut self, out: &mut Vec<Command>) {
        let limit = self.max_velocity();
        let raw = self.int(obj::TARGET_VELOCITY, 0);
        let velocity = raw.clamp(-limit, limit);
        self.clamped = velocity != raw;
        let key = (
            velocity,
            self.int(obj::PROFILE_ACCELERATION, 0),
            self.int(obj::PROFILE_DECELERATION, 0),
            self.int(obj::MOTION_PROFILE_TYPE, 0),
        );
        if self.last_velocity_command != Some(key) {
            out.push(Command::from(MoveVelocity {
                axis: self.config.axis,
                velocity: self.to_units(velocity),
                acceleration: Some(self.to_units(key.1)),
                deceleration: Some(self.to_units(key.2)),
                jerk: self.jerk(),
                buffer_mode: BufferMode::Aborting,
            }));
            self.last_velocity_command = Some(key);
        }
    }
}
