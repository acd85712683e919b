//! Why an object access failed. Each variant corresponds to one CiA 301 SDO abort code
//! (CiA 301 §7.2.4.3.17, Table 22); the CANopen crate sends it, other dialects map it to their
//! own codes. Nothing here knows frames.

use serde::{Deserialize, Serialize};

use super::value::{DataType, Value};

/// An object access refused by a dictionary or by the device behind it.
///
/// | variant          | SDO abort code | CiA 301 text                                                  |
/// |------------------|----------------|---------------------------------------------------------------|
/// | `NoObject`       | `0x0602_0000`  | Object does not exist in the object dictionary               |
/// | `NoSubindex`     | `0x0609_0011`  | Sub-index does not exist                                      |
/// | `ReadOnly`       | `0x0601_0002`  | Attempt to write a read only object                           |
/// | `WriteOnly`      | `0x0601_0001`  | Attempt to read a write only object                           |
/// | `WrongType`      | `0x0607_0010`  | Data type does not match, length of service parameter does not match |
/// | `LengthTooHigh`  | `0x0607_0012`  | Data type does not match, length of service parameter too high |
/// | `LengthTooLow`   | `0x0607_0013`  | Data type does not match, length of service parameter too low |
/// | `ValueTooHigh`   | `0x0609_0031`  | Value of parameter written too high (download only)           |
/// | `ValueTooLow`    | `0x0609_0032`  | Value of parameter written too low (download only)            |
/// | `InvalidValue`   | `0x0609_0030`  | Invalid value for parameter (download only)                   |
/// | `NotMappable`    | `0x0604_0041`  | Object cannot be mapped to the PDO                            |
/// | `MaxBelowMin`    | `0x0609_0036`  | Maximum value is less than minimum value                      |
/// | `DeviceState`    | `0x0800_0022`  | Data cannot be transferred or stored to the application because of the present device state |
/// | `DeviceFailure`  | `0x0800_0000`  | General error                                                 |
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize, Deserialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum OdError {
    #[error("object {index:#06x} does not exist")]
    NoObject { index: u16 },
    #[error("object {index:#06x} has no sub-index {subindex}")]
    NoSubindex { index: u16, subindex: u8 },
    #[error("object {index:#06x}:{subindex} is read-only")]
    ReadOnly { index: u16, subindex: u8 },
    #[error("object {index:#06x}:{subindex} is write-only")]
    WriteOnly { index: u16, subindex: u8 },
    #[error("object {index:#06x}:{subindex} is {expected}, not {found}")]
    WrongType {
        index: u16,
        subindex: u8,
        expected: DataType,
        found: DataType,
    },
    #[error("object {index:#06x}:{subindex} takes {expected} bytes, got {found}")]
    LengthTooHigh {
        index: u16,
        subindex: u8,
        expected: usize,
        found: usize,
    },
    #[error("object {index:#06x}:{subindex} takes {expected} bytes, got {found}")]
    LengthTooLow {
        index: u16,
        subindex: u8,
        expected: usize,
        found: usize,
    },
    #[error("object {index:#06x}:{subindex}: {value} is above the maximum {high}")]
    ValueTooHigh {
        index: u16,
        subindex: u8,
        value: Value,
        high: Value,
    },
    #[error("object {index:#06x}:{subindex}: {value} is below the minimum {low}")]
    ValueTooLow {
        index: u16,
        subindex: u8,
        value: Value,
        low: Value,
    },
    #[error("object {index:#06x}:{subindex}: {detail}")]
    InvalidValue {
        index: u16,
        subindex: u8,
        detail: String,
    },
    #[error("object {index:#06x}:{subindex} cannot be mapped to this PDO")]
    NotMappable { index: u16, subindex: u8 },
    /// The write would leave a configured range with its maximum below its minimum (0x607D
    /// software position limits …); `min` and `max` are the pair the write would make.
    #[error(
        "object {index:#06x}:{subindex}: the maximum {max} would be less than the minimum {min}"
    )]
    MaxBelowMin {
        index: u16,
        subindex: u8,
        min: Value,
        max: Value,
    },
    #[error("object {index:#06x}:{subindex} cannot be written now: {detail}")]
    DeviceState {
        index: u16,
        subindex: u8,
        detail: String,
    },
    /// The device failed inside, for a reason no other variant names (its back end is gone …).
    #[error("object {index:#06x}:{subindex}: the device failed: {detail}")]
    DeviceFailure {
        index: u16,
        subindex: u8,
        detail: String,
    },
}

impl OdError {
    /// The CiA 301 SDO abort code of this error (table above).
    pub const fn sdo_abort_code(&self) -> u32 {
        match self {
            OdError::NoObject { .. } => 0x0602_0000,
            OdError::NoSubindex { .. } => 0x0609_0011,
            OdError::ReadOnly { .. } => 0x0601_0002,
            OdError::WriteOnly { .. } => 0x0601_0001,
            OdError::WrongType { .. } => 0x0607_0010,
            OdError::LengthTooHigh { .. } => 0x0607_0012,
            OdError::LengthTooLow { .. } => 0x0607_0013,
            OdError::ValueTooHigh { .. } => 0x0609_0031,
            OdError::ValueTooLow { .. } => 0x0609_0032,
            OdError::InvalidValue { .. } => 0x0609_0030,
            OdError::NotMappable { .. } => 0x0604_0041,
            OdError::MaxBelowMin { .. } => 0x0609_0036,
            OdError::DeviceState { .. } => 0x0800_0022,
            OdError::DeviceFailure { .. } => 0x0800_0000,
        }
    }

    /// The object index the access addressed.
    pub const fn index(&self) -> u16 {
        match *self {
            OdError::NoObject { index }
            | OdError::NoSubindex { index, .. }
            | OdError::ReadOnly { index, .. }
            | OdError::WriteOnly { index, .. }
            | OdError::WrongType { index, .. }
            | OdError::LengthTooHigh { index, .. }
            | OdError::LengthTooLow { index, .. }
            | OdError::ValueTooHigh { index, .. }
            | OdError::ValueTooLow { index, .. }
            | OdError::InvalidValue { index, .. }
            | OdError::NotMappable { index, .. }
            | OdError::MaxBelowMin { index, .. }
            | OdError::DeviceState { index, .. }
            | OdError::DeviceFailure { index, .. } => index,
        }
    }
}
