//! Object dictionaries (ARCHITECTURE §3.8): (index, subindex) → typed value with access rights,
//! PDO mappability and default. The same dictionary answers CANopen SDO/PDO, NMC EtherCAT SDO,
//! HIMC ReadSDO/WriteSDO and HMC CANopenReadDict/WriteDict.

use serde::{Deserialize, Serialize};

/// A typed object value.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Value {
    Bool(bool),
    I8(i8),
    I16(i16),
    I32(i32),
    I64(i64),
    U8(u8),
    U16(u16),
    U32(u32),
    U64(u64),
    F32(f32),
    F64(f64),
    String(String),
    Bytes(Vec<u8>),
}

/// Why an object access failed (each maps to one CiA 301 SDO abort code in the CANopen crate).
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize, Deserialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum OdError {
    #[error("object {index:#06x} does not exist")]
    NoObject { index: u16 },
}
