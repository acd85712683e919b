//! Object dictionaries (ARCHITECTURE §3.8): (index, subindex) → typed value with access rights,
//! PDO mappability, default and limits. The same dictionary answers CANopen SDO/PDO, NMC
//! EtherCAT SDO, HIMC ReadSDO/WriteSDO and HMC CANopenReadDict/WriteDict.
//!
//! Two kinds of access:
//! - **bus access** ([`ObjectDictionary::read`], [`write`](ObjectDictionary::write),
//!   [`read_bytes`](ObjectDictionary::read_bytes), [`write_bytes`](ObjectDictionary::write_bytes)):
//!   what a master may do; checks existence, access rights, type, length and limits and answers
//!   with an [`OdError`] that maps to one SDO abort code;
//! - **device access** ([`get`](ObjectDictionary::get), [`set`](ObjectDictionary::set)): what
//!   the device behind the dictionary does to its own objects (statusword, actual values); only
//!   the type is checked.
//!
//! A dictionary is built from a table of [`EntryDef`]s. The table form is what an EDS loader will
//! produce later ([`DataType::from_code`], [`Access::from_eds`] are its vocabulary).

mod error;
mod value;

use std::borrow::Cow;
use std::cmp::Ordering;
use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use error::OdError;
pub use value::{DataType, DecodeError, Value};

/// Longest VISIBLE_STRING, OCTET_STRING or DOMAIN value a bus write may store. Bounds memory
/// a master can make a device hold (ARCHITECTURE §8: request sizes are bounded). 1 MiB: large
/// enough for the 100 kB DOMAIN block transfers of issue 5's conformance tests.
pub const MAX_VARIABLE_LEN: usize = 1 << 20;

/// Access type of an entry (CiA 306 EDS `AccessType`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Access {
    /// Read only; the device may change it (actual values, statusword).
    Ro,
    /// Write only.
    Wo,
    /// Read and write.
    Rw,
    /// Read and write; mapped, it goes into transmit PDOs (process input).
    Rwr,
    /// Read and write; mapped, it comes from receive PDOs (process output).
    Rww,
    /// Read only and never changes.
    Const,
}

impl Access {
    pub const fn readable(self) -> bool {
        !matches!(self, Access::Wo)
    }

    pub const fn writable(self) -> bool {
        matches!(self, Access::Wo | Access::Rw | Access::Rwr | Access::Rww)
    }

    /// Whether a PDO-mappable entry with this access may go into a PDO of `direction`.
    pub const fn maps_to(self, direction: PdoDirection) -> bool {
        match direction {
            PdoDirection::Transmit => {
                matches!(self, Access::Ro | Access::Const | Access::Rw | Access::Rwr)
            }
            PdoDirection::Receive => matches!(self, Access::Wo | Access::Rw | Access::Rww),
        }
    }

    /// The EDS spelling.
    pub const fn eds_name(self) -> &'static str {
        match self {
            Access::Ro => "ro",
            Access::Wo => "wo",
            Access::Rw => "rw",
            Access::Rwr => "rwr",
            Access::Rww => "rww",
            Access::Const => "const",
        }
    }

    /// Parse an EDS `AccessType` (case-insensitive).
    pub fn from_eds(text: &str) -> Option<Access> {
        [
            Access::Ro,
            Access::Wo,
            Access::Rw,
            Access::Rwr,
            Access::Rww,
            Access::Const,
        ]
        .into_iter()
        .find(|a| a.eds_name().eq_ignore_ascii_case(text.trim()))
    }
}

/// Direction of a PDO, seen from the device.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PdoDirection {
    /// TPDO: the device sends the object.
    Transmit,
    /// RPDO: the device receives the object.
    Receive,
}

/// One row of a dictionary table: everything about an entry except its current value.
#[derive(Clone, Debug, PartialEq)]
pub struct EntryDef {
    pub index: u16,
    pub subindex: u8,
    pub name: Cow<'static, str>,
    pub data_type: DataType,
    pub access: Access,
    pub pdo_mappable: bool,
    pub default: Value,
    /// Smallest value a bus write may store (numeric types).
    pub low: Option<Value>,
    /// Largest value a bus write may store (numeric types).
    pub high: Option<Value>,
}

impl EntryDef {
    /// An entry whose data type is the default value's own (`Bytes` → OCTET_STRING; use
    /// [`EntryDef::data_type`] for DOMAIN).
    pub fn new(
        index: u16,
        subindex: u8,
        name: impl Into<Cow<'static, str>>,
        access: Access,
        default: Value,
    ) -> EntryDef {
        EntryDef {
            index,
            subindex,
            name: name.into(),
            data_type: default.data_type(),
            access,
            pdo_mappable: false,
            default,
            low: None,
            high: None,
        }
    }

    /// Mark the entry PDO-mappable.
    pub fn pdo(mut self) -> EntryDef {
        self.pdo_mappable = true;
        self
    }

    /// Limit bus writes to `low..=high`.
    pub fn range(mut self, low: Value, high: Value) -> EntryDef {
        self.low = Some(low);
        self.high = Some(high);
        self
    }

    pub fn data_type(mut self, data_type: DataType) -> EntryDef {
        self.data_type = data_type;
        self
    }

    /// The most bytes a bus write may bring: the type's size, or [`MAX_VARIABLE_LEN`] for
    /// strings and DOMAINs. More is "length too high" (SDO abort 0x06070012).
    pub const fn max_len(&self) -> usize {
        match self.data_type.size() {
            Some(size) => size,
            None => MAX_VARIABLE_LEN,
        }
    }
}

/// An entry with its current value.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    pub def: EntryDef,
    pub value: Value,
}

/// A table that cannot become a dictionary.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DefinitionError {
    #[error("object {index:#06x}:{subindex} is defined twice")]
    Duplicate { index: u16, subindex: u8 },
    #[error("object {index:#06x}:{subindex}: {what} is not a {data_type}")]
    TypeMismatch {
        index: u16,
        subindex: u8,
        what: &'static str,
        data_type: DataType,
    },
    #[error("object {index:#06x}:{subindex}: the default is outside its limits")]
    DefaultOutOfRange { index: u16, subindex: u8 },
}

/// An object dictionary: entries ordered by (index, subindex).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjectDictionary {
    entries: BTreeMap<(u16, u8), Entry>,
}

impl ObjectDictionary {
    /// Build a dictionary from a table. Every entry starts at its default.
    pub fn from_defs(
        defs: impl IntoIterator<Item = EntryDef>,
    ) -> Result<ObjectDictionary, DefinitionError> {
        let mut entries = BTreeMap::new();
        for def in defs {
            let (index, subindex) = (def.index, def.subindex);
            let mismatch = |what| DefinitionError::TypeMismatch {
                index,
                subindex,
                what,
                data_type: def.data_type,
            };
            if !def.default.fits(def.data_type) {
                return Err(mismatch("the default"));
            }
            for (what, limit) in [("the low limit", &def.low), ("the high limit", &def.high)] {
                if limit.as_ref().is_some_and(|l| !l.fits(def.data_type)) {
                    return Err(mismatch(what));
                }
            }
            if check_limits(&def, &def.default).is_err() {
                return Err(DefinitionError::DefaultOutOfRange { index, subindex });
            }
            let entry = Entry {
                value: def.default.clone(),
                def,
            };
            if entries.insert((index, subindex), entry).is_some() {
                return Err(DefinitionError::Duplicate { index, subindex });
            }
        }
        Ok(ObjectDictionary { entries })
    }

    /// Add one entry after construction (a protocol stack adding the communication objects a
    /// device table lacks). Checks as [`from_defs`](Self::from_defs) does; the entry starts at
    /// its default.
    pub fn insert(&mut self, def: EntryDef) -> Result<(), DefinitionError> {
        let (index, subindex) = (def.index, def.subindex);
        if self.entries.contains_key(&(index, subindex)) {
            return Err(DefinitionError::Duplicate { index, subindex });
        }
        let single = ObjectDictionary::from_defs([def])?;
        self.entries.extend(single.entries);
        Ok(())
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Every entry, in (index, subindex) order.
    pub fn entries(&self) -> impl Iterator<Item = &Entry> {
        self.entries.values()
    }

    /// Whether any subindex of `index` exists.
    pub fn contains_object(&self, index: u16) -> bool {
        self.entries
            .range((index, 0)..=(index, u8::MAX))
            .next()
            .is_some()
    }

    /// The entry at (index, subindex), or why there is none.
    pub fn entry(&self, index: u16, subindex: u8) -> Result<&Entry, OdError> {
        match self.entries.get(&(index, subindex)) {
            Some(entry) => Ok(entry),
            None if self.contains_object(index) => Err(OdError::NoSubindex { index, subindex }),
            None => Err(OdError::NoObject { index }),
        }
    }

    // ---- bus access ----

    /// Read as a master would (SDO upload).
    pub fn read(&self, index: u16, subindex: u8) -> Result<Value, OdError> {
        let entry = self.entry(index, subindex)?;
        if !entry.def.access.readable() {
            return Err(OdError::WriteOnly { index, subindex });
        }
        Ok(entry.value.clone())
    }

    /// Read as little-endian bytes (the payload of an SDO upload).
    pub fn read_bytes(&self, index: u16, subindex: u8) -> Result<Vec<u8>, OdError> {
        self.read(index, subindex).map(|v| v.to_le_bytes())
    }

    /// Check a bus write without storing it: existence, access, type, length, limits.
    pub fn validate(&self, index: u16, subindex: u8, value: &Value) -> Result<(), OdError> {
        let entry = self.writable_entry(index, subindex)?;
        if !value.fits(entry.def.data_type) {
            return Err(OdError::WrongType {
                index,
                subindex,
                expected: entry.def.data_type,
                found: value.data_type(),
            });
        }
        let len = match value {
            Value::String(s) => s.len(),
            Value::Bytes(b) => b.len(),
            _ => 0,
        };
        if len > MAX_VARIABLE_LEN {
            return Err(OdError::LengthTooHigh {
                index,
                subindex,
                expected: MAX_VARIABLE_LEN,
                found: len,
            });
        }
        check_limits(&entry.def, value)
    }

    /// Decode the payload of a bus write into the entry's type, checking access and length
    /// (not limits: [`validate`](Self::validate) does that).
    pub fn decode(&self, index: u16, subindex: u8, bytes: &[u8]) -> Result<Value, OdError> {
        let entry = self.writable_entry(index, subindex)?;
        Value::from_le_bytes(entry.def.data_type, bytes).map_err(|e| match e {
            DecodeError::TooLong { expected, found } => OdError::LengthTooHigh {
                index,
                subindex,
                expected,
                found,
            },
            DecodeError::TooShort { expected, found } => OdError::LengthTooLow {
                index,
                subindex,
                expected,
                found,
            },
            DecodeError::Invalid(why) => OdError::InvalidValue {
                index,
                subindex,
                detail: why.to_string(),
            },
        })
    }

    /// Write as a master would (SDO download, RPDO).
    pub fn write(&mut self, index: u16, subindex: u8, value: Value) -> Result<(), OdError> {
        self.validate(index, subindex, &value)?;
        self.store(index, subindex, value);
        Ok(())
    }

    /// Write little-endian bytes as a master would.
    pub fn write_bytes(&mut self, index: u16, subindex: u8, bytes: &[u8]) -> Result<(), OdError> {
        let value = self.decode(index, subindex, bytes)?;
        self.write(index, subindex, value)
    }

    /// Whether the entry may go into a PDO of `direction`.
    pub fn check_mappable(
        &self,
        index: u16,
        subindex: u8,
        direction: PdoDirection,
    ) -> Result<&Entry, OdError> {
        let entry = self.entry(index, subindex)?;
        if entry.def.pdo_mappable && entry.def.access.maps_to(direction) {
            Ok(entry)
        } else {
            Err(OdError::NotMappable { index, subindex })
        }
    }

    // ---- device access ----

    /// The current value, for the device itself (no access check).
    pub fn get(&self, index: u16, subindex: u8) -> Option<&Value> {
        self.entries.get(&(index, subindex)).map(|e| &e.value)
    }

    /// Store a value as the device itself: read-only objects included, limits not applied;
    /// only existence and type are checked.
    pub fn set(&mut self, index: u16, subindex: u8, value: Value) -> Result<(), OdError> {
        let entry = self.entry(index, subindex)?;
        if !value.fits(entry.def.data_type) {
            return Err(OdError::WrongType {
                index,
                subindex,
                expected: entry.def.data_type,
                found: value.data_type(),
            });
        }
        self.store(index, subindex, value);
        Ok(())
    }

    /// Every entry back to its default (CiA 301 NMT reset node).
    pub fn restore_defaults(&mut self) {
        for entry in self.entries.values_mut() {
            entry.value.clone_from(&entry.def.default);
        }
    }

    fn writable_entry(&self, index: u16, subindex: u8) -> Result<&Entry, OdError> {
        let entry = self.entry(index, subindex)?;
        if entry.def.access.writable() {
            Ok(entry)
        } else {
            Err(OdError::ReadOnly { index, subindex })
        }
    }

    fn store(&mut self, index: u16, subindex: u8, value: Value) {
        if let Some(entry) = self.entries.get_mut(&(index, subindex)) {
            entry.value = value;
        }
    }
}

/// Check `value` against the entry's limits. A NaN never passes a limit.
fn check_limits(def: &EntryDef, value: &Value) -> Result<(), OdError> {
    let (index, subindex) = (def.index, def.subindex);
    if let Some(low) = &def.low {
        match value.compare(low) {
            Some(Ordering::Less) => {
                return Err(OdError::ValueTooLow {
                    index,
                    subindex,
                    value: value.clone(),
                    low: low.clone(),
                })
            }
            Some(_) => {}
            None => return Err(not_a_number(def)),
        }
    }
    if let Some(high) = &def.high {
        match value.compare(high) {
            Some(Ordering::Greater) => {
                return Err(OdError::ValueTooHigh {
                    index,
                    subindex,
                    value: value.clone(),
                    high: high.clone(),
                })
            }
            Some(_) => {}
            None => return Err(not_a_number(def)),
        }
    }
    Ok(())
}

fn not_a_number(def: &EntryDef) -> OdError {
    OdError::InvalidValue {
        index: def.index,
        subindex: def.subindex,
        detail: "not a number".to_string(),
    }
}

#[cfg(test)]
mod tests;
