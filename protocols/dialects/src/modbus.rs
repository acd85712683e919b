//! The Modbus exception an engine refusal becomes (Modbus Application Protocol §7), the same for
//! every vendor's register map: the codes are the protocol's, not a controller's, so they sit
//! beside the vendors as the one table all maps share.

use axes::command::{EngineError, ErrorKind};

/// 02: the address is not in the map, or not one that takes writes.
pub const ILLEGAL_DATA_ADDRESS: u8 = 0x02;
/// 03: the value is refused (a parameter's range, a command argument).
pub const ILLEGAL_DATA_VALUE: u8 = 0x03;
/// 04: the server failed to perform the action (the engine refused it in its present state).
pub const SERVER_DEVICE_FAILURE: u8 = 0x04;
/// 06: busy, try again later (the engine's command queue is full).
pub const SERVER_DEVICE_BUSY: u8 = 0x06;

/// The engine's value checks are the point's value checks (03); other refusals are 04.
pub fn exception_for(e: &EngineError) -> u8 {
    match e.kind() {
        ErrorKind::InvalidParameter | ErrorKind::InvalidArgument => ILLEGAL_DATA_VALUE,
        _ => SERVER_DEVICE_FAILURE,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_refusals_are_03_and_the_rest_04() {
        let value = EngineError::InvalidArgument {
            name: "velocity",
            value: -1.0,
            reason: "must be positive",
        };
        assert_eq!(exception_for(&value), 0x03);
        let param = EngineError::InvalidParameter {
            name: "speed",
            value: -1.0,
            reason: "below 0".into(),
        };
        assert_eq!(exception_for(&param), 0x03);
        assert_eq!(exception_for(&EngineError::AxisDisabled { axis: 0 }), 0x04);
        let full = EngineError::QueueFull { axis: 0, depth: 64 };
        assert_eq!(exception_for(&full), 0x04);
    }
}
