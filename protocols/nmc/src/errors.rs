//! The return codes of `mtn_lib20_err.h`. The manual names only 0 (`RTN_CMD_SUCCESS`) and −1
//! (a communication error, digest 001 §1.2, §8 item 1); the rest are mcemu's and stable: never
//! renumbered, only added to (docs/decisions.md, "NMC front-end (issue 13)").
//!
//! Codes 1–21 are one per engine error kind and equal `mcemu_dialects::nmc::code_for_kind`
//! (a test in mcemu checks it); 30–39 are argument errors the server or the library finds; 40–49
//! protocol errors. `NMC_SetErrCodeMode(1)` turns each code into its [`Category`].

/// What kind of failure a code is, the "category" `NMC_SetErrCodeMode(1)` returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Category {
    /// −1: no reply (lost connection, timeout).
    Communication = -1,
    /// 1: a bad argument (handle, range, null pointer).
    Argument = 1,
    /// 2: the axis or device cannot do it now (disabled, in error, limit, busy …).
    State = 2,
    /// 3: the wire protocol (unknown function, version, malformed payload).
    Protocol = 3,
    /// 4: not supported by this device.
    Unsupported = 4,
}

/// One code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Code {
    pub code: i16,
    pub name: &'static str,
    pub category: Category,
    /// The general text; a reply's own text (naming the argument and the range) wins.
    pub description: &'static str,
}

pub const RTN_CMD_SUCCESS: i16 = 0;
pub const RTN_COMM_ERROR: i16 = -1;
pub const RTN_UNSUPPORTED: i16 = 10;
pub const RTN_INVALID_STATE: i16 = 11;
pub const RTN_INVALID_HANDLE: i16 = 30;
pub const RTN_WRONG_HANDLE_KIND: i16 = 31;
pub const RTN_NULL_POINTER: i16 = 32;
pub const RTN_ARG_RANGE: i16 = 33;
pub const RTN_NO_DEVICE: i16 = 34;
pub const RTN_NOT_ON_THIS_CARD: i16 = 35;
pub const RTN_PASSWORD: i16 = 36;
pub const RTN_FILE: i16 = 37;
pub const RTN_UNKNOWN_FUNCTION: i16 = 40;
pub const RTN_VERSION: i16 = 41;
pub const RTN_BAD_PAYLOAD: i16 = 42;
pub const RTN_FRAME_TOO_LARGE: i16 = 43;

use Category::*;

const fn c(code: i16, name: &'static str, category: Category, description: &'static str) -> Code {
    Code {
        code,
        name,
        category,
        description,
    }
}

/// Every code but success, in code order.
pub const CODES: &[Code] = &[
    c(-1, "RTN_COMM_ERROR", Communication, "communication error: no reply within the timeout (NMC_SetCommPara) or the connection is lost"),
    c(1, "RTN_INVALID_AXIS", Argument, "no such axis"),
    c(2, "RTN_UNKNOWN_PARAMETER", Argument, "no such parameter"),
    c(3, "RTN_INVALID_PARAMETER", Argument, "parameter value out of range"),
    c(4, "RTN_READ_ONLY_PARAMETER", Argument, "the parameter is read-only"),
    c(5, "RTN_INVALID_ARGUMENT", Argument, "argument out of range"),
    c(6, "RTN_AXIS_DISABLED", State, "the axis is not enabled (servo off)"),
    c(7, "RTN_AXIS_IN_ERROR", State, "the axis has a latched error: NMC_MtClrError first"),
    c(8, "RTN_LIMIT_ACTIVE", State, "a limit blocks motion in this direction"),
    c(9, "RTN_QUEUE_FULL", State, "the command queue is full"),
    c(RTN_UNSUPPORTED, "RTN_UNSUPPORTED", Unsupported, "not supported by this axis or device"),
    c(RTN_INVALID_STATE, "RTN_INVALID_STATE", State, "not allowed in the axis's present state"),
    c(12, "RTN_CAUSE_STILL_PRESENT", State, "the error's cause is still present"),
    c(13, "RTN_UNKNOWN_COMMAND", Unsupported, "unknown command"),
    c(14, "RTN_HOMING", State, "homing failed or is running"),
    c(15, "RTN_OBJECT", Argument, "object dictionary access failed"),
    c(16, "RTN_INVALID_SLAVE", Argument, "no such slave"),
    c(17, "RTN_INVALID_CHANNEL", Argument, "no such channel"),
    c(18, "RTN_LIMIT_REACHED", State, "a limit was reached"),
    c(19, "RTN_FAULT", State, "a fault stopped the command"),
    c(20, "RTN_INVALID_GROUP", Argument, "no such coordinate system"),
    c(21, "RTN_GROUP_STATE", State, "not allowed in the coordinate system's present state"),
    c(RTN_INVALID_HANDLE, "RTN_INVALID_HANDLE", Argument, "the handle is not open"),
    c(RTN_WRONG_HANDLE_KIND, "RTN_WRONG_HANDLE_KIND", Argument, "a handle of the wrong kind (an axis handle where a device handle is expected, or the reverse)"),
    c(RTN_NULL_POINTER, "RTN_NULL_POINTER", Argument, "a pointer argument is NULL"),
    c(RTN_ARG_RANGE, "RTN_ARG_RANGE", Argument, "an argument is outside its allowed range"),
    c(RTN_NO_DEVICE, "RTN_NO_DEVICE", Argument, "no device with this index, ID or IP address"),
    c(RTN_NOT_ON_THIS_CARD, "RTN_NOT_ON_THIS_CARD", Unsupported, "not available on this kind of card (e.g. NMC_DevOpenByIP on a PCIe card)"),
    c(RTN_PASSWORD, "RTN_PASSWORD", Argument, "wrong system password (NMC_SetTime, NMC_ChangePassword, NMC_VerifyPassword)"),
    c(RTN_FILE, "RTN_FILE", Argument, "the file cannot be read or written, or is not an mcemu NMC configuration (NMC_LoadConfigFromFile, NMC_SaveConfigToFile, NMC_SetCmdDebug)"),
    c(RTN_UNKNOWN_FUNCTION, "RTN_UNKNOWN_FUNCTION", Protocol, "the server does not know this function"),
    c(RTN_VERSION, "RTN_VERSION", Protocol, "library and server share no protocol version"),
    c(RTN_BAD_PAYLOAD, "RTN_BAD_PAYLOAD", Protocol, "malformed request or reply payload"),
    c(RTN_FRAME_TOO_LARGE, "RTN_FRAME_TOO_LARGE", Protocol, "frame larger than the protocol allows"),
];

/// The row of `code`.
pub fn lookup(code: i16) -> Option<&'static Code> {
    CODES.iter().find(|c| c.code == code)
}

/// `code` as `NMC_SetErrCodeMode(1)` reports it: its category (0 stays 0).
pub fn category_code(code: i16) -> i16 {
    match (code, lookup(code)) {
        (0, _) => 0,
        (_, Some(c)) => c.category as i16,
        // A code this build does not know (a newer server): call it a protocol error.
        (_, None) => Category::Protocol as i16,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_ascend_and_names_are_unique() {
        for pair in CODES.windows(2) {
            assert!(pair[0].code < pair[1].code);
        }
        let mut names: Vec<&str> = CODES.iter().map(|c| c.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), CODES.len());
    }

    #[test]
    fn categories() {
        assert_eq!(category_code(0), 0);
        assert_eq!(category_code(-1), -1);
        assert_eq!(category_code(RTN_ARG_RANGE), 1);
        assert_eq!(category_code(7), 2);
        assert_eq!(category_code(RTN_UNKNOWN_FUNCTION), 3);
        assert_eq!(category_code(999), 3);
    }
}
