//! The names the API gives flags and drive states. The flag table lives in `axes` (shared with
//! the register maps); it is fixed, so that renaming a constant cannot silently change the JSON.

pub use axes::status::{flag_by_name, flag_names, FLAG_NAMES};

/// A CiA 402 state as a snake_case name (`operation_enabled`), from a statusword.
pub fn drive_state_name(statusword: u16) -> Option<String> {
    axes::cia402::State::from_statusword(statusword).map(|s| s.name().replace(' ', "_"))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use axes::AxisFlags;

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
