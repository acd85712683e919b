//! How the node reaches the object dictionary it serves.
//!
//! The node owns a [`Device`]: something that has an [`ObjectDictionary`] and may add rules of
//! its own to a master's writes. A plain dictionary is a device. A CiA 402 drive
//! (`axes::cia402::Cia402Drive`) owns its dictionary and checks its own rules (supported modes,
//! homing methods …) in its `write`; the CiA 402 binding implements `Device` for it so that SDO,
//! RPDO and the drive's servo tick all use one dictionary — the node's
//! [`device_mut`](crate::Node::device_mut) hands the drive back to the binding between frames.

use axes::od::{DataType, ObjectDictionary, OdError, Value};

/// An object dictionary plus the device behaviour behind it.
pub trait Device {
    /// The dictionary, for reads.
    fn od(&self) -> &ObjectDictionary;

    /// The dictionary, for device access (the node stores its communication state here:
    /// 0x1001, 0x1003, PDO parameters restored at reset).
    fn od_mut(&mut self) -> &mut ObjectDictionary;

    /// A master's write (SDO download, RPDO): the dictionary's checks plus the device's own
    /// rules. The default is the dictionary's checks alone.
    fn write(&mut self, index: u16, subindex: u8, value: Value) -> Result<(), OdError> {
        self.od_mut().write(index, subindex, value)
    }
}

impl Device for ObjectDictionary {
    fn od(&self) -> &ObjectDictionary {
        self
    }

    fn od_mut(&mut self) -> &mut ObjectDictionary {
        self
    }
}

/// An integer object as u64 (`None` if absent or not an unsigned-representable integer).
pub(crate) fn get_u64(od: &ObjectDictionary, index: u16, subindex: u8) -> Option<u64> {
    match od.get(index, subindex)? {
        Value::Bool(b) => Some(u64::from(*b)),
        v => v.as_u64(),
    }
}

pub(crate) fn get_u32(od: &ObjectDictionary, index: u16, subindex: u8) -> Option<u32> {
    get_u64(od, index, subindex).and_then(|v| u32::try_from(v).ok())
}

pub(crate) fn get_u16(od: &ObjectDictionary, index: u16, subindex: u8) -> Option<u16> {
    get_u64(od, index, subindex).and_then(|v| u16::try_from(v).ok())
}

pub(crate) fn get_u8(od: &ObjectDictionary, index: u16, subindex: u8) -> Option<u8> {
    get_u64(od, index, subindex).and_then(|v| u8::try_from(v).ok())
}

/// An unsigned value in the entry's own integer type, if it fits.
pub(crate) fn typed_uint(od: &ObjectDictionary, index: u16, subindex: u8, v: u64) -> Option<Value> {
    let entry = od.entry(index, subindex).ok()?;
    Some(match entry.def.data_type {
        DataType::Unsigned8 => Value::U8(u8::try_from(v).ok()?),
        DataType::Unsigned16 => Value::U16(u16::try_from(v).ok()?),
        DataType::Unsigned32 => Value::U32(u32::try_from(v).ok()?),
        DataType::Unsigned64 => Value::U64(v),
        DataType::Integer8 => Value::I8(i8::try_from(v).ok()?),
        DataType::Integer16 => Value::I16(i16::try_from(v).ok()?),
        DataType::Integer32 => Value::I32(i32::try_from(v).ok()?),
        DataType::Integer64 => Value::I64(i64::try_from(v).ok()?),
        DataType::Boolean => Value::Bool(v != 0),
        _ => return None,
    })
}

/// Device-access store of an unsigned value; silently nothing if the entry is absent or its
/// type cannot hold the value (the node keeps working with what the dictionary offers).
pub(crate) fn set_uint(od: &mut ObjectDictionary, index: u16, subindex: u8, v: u64) {
    if let Some(value) = typed_uint(od, index, subindex, v) {
        let _ = od.set(index, subindex, value);
    }
}
