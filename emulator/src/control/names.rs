//! The names the API gives flags: a fixed table, so that renaming a constant in `axes` cannot
//! silently change the JSON (a test checks the table covers every flag).

use axes::AxisFlags;

/// Every axis flag and its JSON name, in bit order.
pub const FLAG_NAMES: [(AxisFlags, &str); 25] = [
    (AxisFlags::ENABLED, "enabled"),
    (AxisFlags::MOVING, "moving"),
    (AxisFlags::IN_POSITION, "in_position"),
    (AxisFlags::HOMED, "homed"),
    (AxisFlags::HW_LIMIT_POS, "hw_limit_pos"),
    (AxisFlags::HW_LIMIT_NEG, "hw_limit_neg"),
    (AxisFlags::SW_LIMIT_POS, "sw_limit_pos"),
    (AxisFlags::SW_LIMIT_NEG, "sw_limit_neg"),
    (AxisFlags::HOME_SWITCH, "home_switch"),
    (AxisFlags::INDEX, "index"),
    (AxisFlags::FE_WARNING, "fe_warning"),
    (AxisFlags::FE_FAULT, "fe_fault"),
    (AxisFlags::DRIVE_ALARM, "drive_alarm"),
    (AxisFlags::ESTOP, "estop"),
    (AxisFlags::CAPTURE_TRIGGERED, "capture_triggered"),
    (AxisFlags::PARAMETER_ERROR, "parameter_error"),
    (AxisFlags::QUEUE_FULL, "queue_full"),
    (AxisFlags::IN_GROUP, "in_group"),
    (AxisFlags::ENCODER_LOSS, "encoder_loss"),
    (AxisFlags::HALTED, "halted"),
    (AxisFlags::HOMING_FAILED, "homing_failed"),
    (AxisFlags::MOTION_ERROR, "motion_error"),
    (AxisFlags::SW_LIMIT_CONFIG, "sw_limit_config"),
    (AxisFlags::BOTH_LIMITS, "both_limits"),
    (AxisFlags::ACCELERATING, "accelerating"),
];

/// The names of the flags set in `flags`, in bit order.
pub fn flag_names(flags: AxisFlags) -> Vec<&'static str> {
    FLAG_NAMES
        .iter()
        .filter(|(flag, _)| flags.contains(*flag))
        .map(|(_, name)| *name)
        .collect()
}

/// The flag called `name`.
pub fn flag_by_name(name: &str) -> Option<AxisFlags> {
    FLAG_NAMES
        .iter()
        .find(|(_, n)| *n == name)
        .map(|(flag, _)| *flag)
}

/// A CiA 402 state as a snake_case name (`operation_enabled`), from a statusword.
pub fn drive_state_name(statusword: u16) -> Option<String> {
    axes::cia402::State::from_statusword(statusword).map(|s| s.name().replace(' ', "_"))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn the_table_names_every_flag_as_its_constant_in_snake_case() {
        let table: Vec<(AxisFlags, String)> = FLAG_NAMES
            .iter()
            .map(|(f, n)| (*f, n.to_string()))
            .collect();
        let constants: Vec<(AxisFlags, String)> = AxisFlags::all()
            .iter_names()
            .map(|(n, f)| (f, n.to_ascii_lowercase()))
            .collect();
        assert_eq!(table, constants);
    }

    #[test]
    fn names_round_trip() {
        let flags = AxisFlags::ENABLED | AxisFlags::MOVING | AxisFlags::ACCELERATING;
        assert_eq!(flag_names(flags), ["enabled", "moving", "accelerating"]);
        assert_eq!(flag_names(AxisFlags::empty()), Vec::<&str>::new());
        assert_eq!(flag_by_name("in_position"), Some(AxisFlags::IN_POSITION));
        assert_eq!(flag_by_name("IN_POSITION"), None);
        assert_eq!(
            drive_state_name(0x0237).as_deref(),
            Some("operation_enabled")
        );
    }
}
