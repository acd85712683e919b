//! CiA 301 data types (CiA 301 §7.1) and typed values with their little-endian encoding, the
//! form in which SDO and PDO transfers carry them.

use std::cmp::Ordering;
use std::fmt;

use serde::{Deserialize, Serialize};

/// A CiA 301 basic data type. The discriminant-free enum keeps serde names stable; [`code`]
/// gives the data type index a device description (EDS `DataType=`) uses.
///
/// [`code`]: DataType::code
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DataType {
    Boolean,
    Integer8,
    Integer16,
    Integer32,
    Integer64,
    Unsigned8,
    Unsigned16,
    Unsigned32,
    Unsigned64,
    Real32,
    Real64,
    VisibleString,
    OctetString,
    Domain,
}

impl DataType {
    /// Every supported type, in CiA 301 order of their codes.
    pub const ALL: [DataType; 14] = [
        DataType::Boolean,
        DataType::Integer8,
        DataType::Integer16,
        DataType::Integer32,
        DataType::Unsigned8,
        DataType::Unsigned16,
        DataType::Unsigned32,
        DataType::Real32,
        DataType::VisibleString,
        DataType::OctetString,
        DataType::Domain,
        DataType::Real64,
        DataType::Integer64,
        DataType::Unsigned64,
    ];

    /// The data type's object index in CiA 301 Table 44 (what EDS files write as `DataType=`).
    pub const fn code(self) -> u16 {
        match self {
            DataType::Boolean => 0x0001,
            DataType::Integer8 => 0x0002,
            DataType::Integer16 => 0x0003,
            DataType::Integer32 => 0x0004,
            DataType::Unsigned8 => 0x0005,
            DataType::Unsigned16 => 0x0006,
            DataType::Unsigned32 => 0x0007,
            DataType::Real32 => 0x0008,
            DataType::VisibleString => 0x0009,
            DataType::OctetString => 0x000A,
            DataType::Domain => 0x000F,
            DataType::Real64 => 0x0011,
            DataType::Integer64 => 0x0015,
            DataType::Unsigned64 => 0x001B,
        }
    }

    /// The type with a CiA 301 data type code, for EDS loading. `None` for types mcemu does not
    /// store (INTEGER24, TIME_OF_DAY, UNICODE_STRING …).
    pub const fn from_code(code: u16) -> Option<DataType> {
        Some(match code {
            0x0001 => DataType::Boolean,
            0x0002 => DataType::Integer8,
            0x0003 => DataType::Integer16,
            0x0004 => DataType::Integer32,
            0x0005 => DataType::Unsigned8,
            0x0006 => DataType::Unsigned16,
            0x0007 => DataType::Unsigned32,
            0x0008 => DataType::Real32,
            0x0009 => DataType::VisibleString,
            0x000A => DataType::OctetString,
            0x000F => DataType::Domain,
            0x0011 => DataType::Real64,
            0x0015 => DataType::Integer64,
            0x001B => DataType::Unsigned64,
            _ => return None,
        })
    }

    /// Encoded size in bytes; `None` for the variable-length types.
    pub const fn size(self) -> Option<usize> {
        match self {
            DataType::Boolean | DataType::Integer8 | DataType::Unsigned8 => Some(1),
            DataType::Integer16 | DataType::Unsigned16 => Some(2),
            DataType::Integer32 | DataType::Unsigned32 | DataType::Real32 => Some(4),
            DataType::Integer64 | DataType::Unsigned64 | DataType::Real64 => Some(8),
            DataType::VisibleString | DataType::OctetString | DataType::Domain => None,
        }
    }

    /// The CiA 301 name, e.g. `UNSIGNED16`.
    pub const fn name(self) -> &'static str {
        match self {
            DataType::Boolean => "BOOLEAN",
            DataType::Integer8 => "INTEGER8",
            DataType::Integer16 => "INTEGER16",
            DataType::Integer32 => "INTEGER32",
            DataType::Integer64 => "INTEGER64",
            DataType::Unsigned8 => "UNSIGNED8",
            DataType::Unsigned16 => "UNSIGNED16",
            DataType::Unsigned32 => "UNSIGNED32",
            DataType::Unsigned64 => "UNSIGNED64",
            DataType::Real32 => "REAL32",
            DataType::Real64 => "REAL64",
            DataType::VisibleString => "VISIBLE_STRING",
            DataType::OctetString => "OCTET_STRING",
            DataType::Domain => "DOMAIN",
        }
    }
}

impl fmt::Display for DataType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A typed object value.
///
/// `String` carries VISIBLE_STRING; `Bytes` carries OCTET_STRING and DOMAIN.
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

impl Value {
    /// The data type this value naturally has (`Bytes` reports OCTET_STRING).
    pub const fn data_type(&self) -> DataType {
        match self {
            Value::Bool(_) => DataType::Boolean,
            Value::I8(_) => DataType::Integer8,
            Value::I16(_) => DataType::Integer16,
            Value::I32(_) => DataType::Integer32,
            Value::I64(_) => DataType::Integer64,
            Value::U8(_) => DataType::Unsigned8,
            Value::U16(_) => DataType::Unsigned16,
            Value::U32(_) => DataType::Unsigned32,
            Value::U64(_) => DataType::Unsigned64,
            Value::F32(_) => DataType::Real32,
            Value::F64(_) => DataType::Real64,
            Value::String(_) => DataType::VisibleString,
            Value::Bytes(_) => DataType::OctetString,
        }
    }

    /// Whether the value can be stored in an object of type `data_type`. No conversions: a bus
    /// write of the wrong width is a type error (SDO abort 0x0607_0010), not a cast.
    pub const fn fits(&self, data_type: DataType) -> bool {
        match (self, data_type) {
            (Value::Bytes(_), DataType::OctetString | DataType::Domain) => true,
            _ => self.data_type() as u8 == data_type as u8,
        }
    }

    /// An integer value (BOOLEAN excluded) as i128, which holds every CiA integer type exactly.
    pub const fn as_i128(&self) -> Option<i128> {
        Some(match *self {
            Value::I8(v) => v as i128,
            Value::I16(v) => v as i128,
            Value::I32(v) => v as i128,
            Value::I64(v) => v as i128,
            Value::U8(v) => v as i128,
            Value::U16(v) => v as i128,
            Value::U32(v) => v as i128,
            Value::U64(v) => v as i128,
            _ => return None,
        })
    }

    /// An integer value that fits in i64.
    pub fn as_i64(&self) -> Option<i64> {
        self.as_i128().and_then(|v| i64::try_from(v).ok())
    }

    /// An integer value that fits in u64.
    pub fn as_u64(&self) -> Option<u64> {
        self.as_i128().and_then(|v| u64::try_from(v).ok())
    }

    /// Any numeric value as f64 (integers beyond 2^53 round).
    pub fn as_f64(&self) -> Option<f64> {
        match *self {
            Value::F32(v) => Some(f64::from(v)),
            Value::F64(v) => Some(v),
            Value::Bool(_) | Value::String(_) | Value::Bytes(_) => None,
            _ => self.as_i128().map(|v| v as f64),
        }
    }

    /// Order two numeric values of any integer or float types; `None` for non-numbers and NaN.
    pub fn compare(&self, other: &Value) -> Option<Ordering> {
        match (self.as_i128(), other.as_i128()) {
            (Some(a), Some(b)) => Some(a.cmp(&b)),
            _ => self.as_f64()?.partial_cmp(&other.as_f64()?),
        }
    }

    /// Little-endian encoding, as CiA 301 transfers it (BOOLEAN as one byte 0/1).
    pub fn to_le_bytes(&self) -> Vec<u8> {
        match self {
            Value::Bool(v) => vec![u8::from(*v)],
            Value::I8(v) => v.to_le_bytes().to_vec(),
            Value::I16(v) => v.to_le_bytes().to_vec(),
            Value::I32(v) => v.to_le_bytes().to_vec(),
            Value::I64(v) => v.to_le_bytes().to_vec(),
            Value::U8(v) => v.to_le_bytes().to_vec(),
            Value::U16(v) => v.to_le_bytes().to_vec(),
            Value::U32(v) => v.to_le_bytes().to_vec(),
            Value::U64(v) => v.to_le_bytes().to_vec(),
            Value::F32(v) => v.to_le_bytes().to_vec(),
            Value::F64(v) => v.to_le_bytes().to_vec(),
            Value::String(v) => v.as_bytes().to_vec(),
            Value::Bytes(v) => v.clone(),
        }
    }

    /// Decode `bytes` as a value of `data_type`. Fixed-size types need exactly their size.
    /// VISIBLE_STRING must be printable ASCII; trailing NULs (padding some masters send) are
    /// dropped.
    pub fn from_le_bytes(data_type: DataType, bytes: &[u8]) -> Result<Value, DecodeError> {
        if let Some(size) = data_type.size() {
            match bytes.len().cmp(&size) {
                Ordering::Greater => {
                    return Err(DecodeError::TooLong {
                        expected: size,
                        found: bytes.len(),
                    })
                }
                Ordering::Less => {
                    return Err(DecodeError::TooShort {
                        expected: size,
                        found: bytes.len(),
                    })
                }
                Ordering::Equal => {}
            }
        }
        Ok(match data_type {
            DataType::Boolean => match bytes {
                [0] => Value::Bool(false),
                [1] => Value::Bool(true),
                _ => return Err(DecodeError::Invalid("a BOOLEAN is 0 or 1")),
            },
            DataType::Integer8 => Value::I8(i8::from_le_bytes(array(bytes)?)),
            DataType::Integer16 => Value::I16(i16::from_le_bytes(array(bytes)?)),
            DataType::Integer32 => Value::I32(i32::from_le_bytes(array(bytes)?)),
            DataType::Integer64 => Value::I64(i64::from_le_bytes(array(bytes)?)),
            DataType::Unsigned8 => Value::U8(u8::from_le_bytes(array(bytes)?)),
            DataType::Unsigned16 => Value::U16(u16::from_le_bytes(array(bytes)?)),
            DataType::Unsigned32 => Value::U32(u32::from_le_bytes(array(bytes)?)),
            DataType::Unsigned64 => Value::U64(u64::from_le_bytes(array(bytes)?)),
            DataType::Real32 => Value::F32(f32::from_le_bytes(array(bytes)?)),
            DataType::Real64 => Value::F64(f64::from_le_bytes(array(bytes)?)),
            DataType::VisibleString => {
                let end = bytes.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
                let text = bytes.get(..end).unwrap_or_default();
                if !text.iter().all(|b| (0x20..=0x7E).contains(b)) {
                    return Err(DecodeError::Invalid(
                        "a VISIBLE_STRING holds printable ASCII only",
                    ));
                }
                Value::String(text.iter().map(|&b| char::from(b)).collect())
            }
            DataType::OctetString | DataType::Domain => Value::Bytes(bytes.to_vec()),
        })
    }
}

/// Copy a slice whose length was already checked into an array.
fn array<const N: usize>(bytes: &[u8]) -> Result<[u8; N], DecodeError> {
    <[u8; N]>::try_from(bytes).map_err(|_| DecodeError::TooShort {
        expected: N,
        found: bytes.len(),
    })
}

/// Why bytes do not decode as a data type; the dictionary adds index and subindex.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DecodeError {
    TooLong { expected: usize, found: usize },
    TooShort { expected: usize, found: usize },
    Invalid(&'static str),
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Bool(v) => write!(f, "{v}"),
            Value::I8(v) => write!(f, "{v}"),
            Value::I16(v) => write!(f, "{v}"),
            Value::I32(v) => write!(f, "{v}"),
            Value::I64(v) => write!(f, "{v}"),
            Value::U8(v) => write!(f, "{v}"),
            Value::U16(v) => write!(f, "{v}"),
            Value::U32(v) => write!(f, "{v}"),
            Value::U64(v) => write!(f, "{v}"),
            Value::F32(v) => write!(f, "{v}"),
            Value::F64(v) => write!(f, "{v}"),
            Value::String(v) => write!(f, "{v:?}"),
            Value::Bytes(v) => {
                f.write_str("0x")?;
                v.iter().try_for_each(|b| write!(f, "{b:02x}"))
            }
        }
    }
}
