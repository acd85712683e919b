//! SDO abort codes (CiA 301 §7.2.4.3.17, Table 22).

use std::fmt;

use axes::od::OdError;

/// An SDO abort code.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct SdoAbort(pub u32);

impl SdoAbort {
    pub const TOGGLE: SdoAbort = SdoAbort(0x0503_0000);
    pub const TIMEOUT: SdoAbort = SdoAbort(0x0504_0000);
    pub const COMMAND: SdoAbort = SdoAbort(0x0504_0001);
    pub const BLOCK_SIZE: SdoAbort = SdoAbort(0x0504_0002);
    pub const SEQUENCE: SdoAbort = SdoAbort(0x0504_0003);
    pub const CRC: SdoAbort = SdoAbort(0x0504_0004);
    pub const OUT_OF_MEMORY: SdoAbort = SdoAbort(0x0504_0005);
    pub const UNSUPPORTED_ACCESS: SdoAbort = SdoAbort(0x0601_0000);
    pub const WRITE_ONLY: SdoAbort = SdoAbort(0x0601_0001);
    pub const READ_ONLY: SdoAbort = SdoAbort(0x0601_0002);
    pub const NO_OBJECT: SdoAbort = SdoAbort(0x0602_0000);
    pub const NOT_MAPPABLE: SdoAbort = SdoAbort(0x0604_0041);
    pub const PDO_LENGTH: SdoAbort = SdoAbort(0x0604_0042);
    pub const PARAMETER_INCOMPATIBLE: SdoAbort = SdoAbort(0x0604_0043);
    pub const INTERNAL_INCOMPATIBLE: SdoAbort = SdoAbort(0x0604_0047);
    pub const HARDWARE: SdoAbort = SdoAbort(0x0606_0000);
    pub const LENGTH: SdoAbort = SdoAbort(0x0607_0010);
    pub const LENGTH_HIGH: SdoAbort = SdoAbort(0x0607_0012);
    pub const LENGTH_LOW: SdoAbort = SdoAbort(0x0607_0013);
    pub const NO_SUBINDEX: SdoAbort = SdoAbort(0x0609_0011);
    pub const INVALID_VALUE: SdoAbort = SdoAbort(0x0609_0030);
    pub const VALUE_HIGH: SdoAbort = SdoAbort(0x0609_0031);
    pub const VALUE_LOW: SdoAbort = SdoAbort(0x0609_0032);
    pub const MAX_BELOW_MIN: SdoAbort = SdoAbort(0x0609_0036);
    pub const GENERAL: SdoAbort = SdoAbort(0x0800_0000);
    pub const CANNOT_STORE: SdoAbort = SdoAbort(0x0800_0020);
    pub const LOCAL_CONTROL: SdoAbort = SdoAbort(0x0800_0021);
    pub const DEVICE_STATE: SdoAbort = SdoAbort(0x0800_0022);

    /// The CiA 301 text of the code (`None` for codes outside Table 22).
    pub fn description(self) -> Option<&'static str> {
        DESCRIPTIONS
            .iter()
            .find(|(code, _)| *code == self)
            .map(|(_, text)| *text)
    }
}

const DESCRIPTIONS: [(SdoAbort, &str); 28] = [
    (SdoAbort::TOGGLE, "toggle bit not alternated"),
    (SdoAbort::TIMEOUT, "SDO protocol timed out"),
    (SdoAbort::COMMAND, "client/server command specifier not valid or unknown"),
    (SdoAbort::BLOCK_SIZE, "invalid block size"),
    (SdoAbort::SEQUENCE, "invalid sequence number"),
    (SdoAbort::CRC, "CRC error"),
    (SdoAbort::OUT_OF_MEMORY, "out of memory"),
    (SdoAbort::UNSUPPORTED_ACCESS, "unsupported access to an object"),
    (SdoAbort::WRITE_ONLY, "attempt to read a write only object"),
    (SdoAbort::READ_ONLY, "attempt to write a read only object"),
    (SdoAbort::NO_OBJECT, "object does not exist in the object dictionary"),
    (SdoAbort::NOT_MAPPABLE, "object cannot be mapped to the PDO"),
    (SdoAbort::PDO_LENGTH, "the number and length of the objects to be mapped would exceed PDO length"),
    (SdoAbort::PARAMETER_INCOMPATIBLE, "general parameter incompatibility reason"),
    (SdoAbort::INTERNAL_INCOMPATIBLE, "general internal incompatibility in the device"),
    (SdoAbort::HARDWARE, "access failed due to a hardware error"),
    (SdoAbort::LENGTH, "data type does not match, length of service parameter does not match"),
    (SdoAbort::LENGTH_HIGH, "data type does not match, length of service parameter too high"),
    (SdoAbort::LENGTH_LOW, "data type does not match, length of service parameter too low"),
    (SdoAbort::NO_SUBINDEX, "sub-index does not exist"),
    (SdoAbort::INVALID_VALUE, "invalid value for parameter"),
    (SdoAbort::VALUE_HIGH, "value of parameter written too high"),
    (SdoAbort::VALUE_LOW, "value of parameter written too low"),
    (SdoAbort::MAX_BELOW_MIN, "maximum value is less than minimum value"),
    (SdoAbort::GENERAL, "general error"),
    (SdoAbort::CANNOT_STORE, "data cannot be transferred or stored to the application"),
    (SdoAbort::LOCAL_CONTROL, "data cannot be transferred or stored to the application because of local control"),
    (SdoAbort::DEVICE_STATE, "data cannot be transferred or stored to the application because of the present device state"),
];

impl From<OdError> for SdoAbort {
    fn from(e: OdError) -> SdoAbort {
        SdoAbort(e.sdo_abort_code())
    }
}

impl From<&OdError> for SdoAbort {
    fn from(e: &OdError) -> SdoAbort {
        SdoAbort(e.sdo_abort_code())
    }
}

impl fmt::Debug for SdoAbort {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "SdoAbort({:#010x})", self.0)
    }
}

impl fmt::Display for SdoAbort {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.description() {
            Some(text) => write!(f, "{:#010x} ({text})", self.0),
            None => write!(f, "{:#010x}", self.0),
        }
    }
}
