//! SDO write rules of PDO parameters (CiA 301 §7.5.2.35–§7.5.2.38): what may change while a
//! PDO is valid, transmission types, restricted CAN-IDs, and the dynamic mapping procedure
//! (invalidate the PDO, sub-index 0 = 0, write entries, sub-index 0 = n, validate).

use axes::od::{ObjectDictionary, PdoDirection};

use super::{check_entry, Mapping, PdoComm, EXTENDED, INVALID};
use crate::device::{get_u32, get_u8};
use crate::objects::{idx, restricted_can_id};
use crate::sdo::SdoAbort;

/// What PDO parameter an index addresses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PdoObject {
    Comm(PdoDirection, u16),
    Map(PdoDirection, u16),
}

impl PdoObject {
    pub(crate) fn of(index: u16) -> Option<PdoObject> {
        use PdoDirection::{Receive, Transmit};
        let r = idx::PDO_RANGE;
        Some(match index {
            i if (idx::RPDO_COMM..idx::RPDO_COMM + r).contains(&i) => {
                PdoObject::Comm(Receive, i - idx::RPDO_COMM)
            }
            i if (idx::RPDO_MAP..idx::RPDO_MAP + r).contains(&i) => {
                PdoObject::Map(Receive, i - idx::RPDO_MAP)
            }
            i if (idx::TPDO_COMM..idx::TPDO_COMM + r).contains(&i) => {
                PdoObject::Comm(Transmit, i - idx::TPDO_COMM)
            }
            i if (idx::TPDO_MAP..idx::TPDO_MAP + r).contains(&i) => {
                PdoObject::Map(Transmit, i - idx::TPDO_MAP)
            }
            _ => return None,
        })
    }
}

pub(crate) fn comm_index(dir: PdoDirection, n: u16) -> u16 {
    match dir {
        PdoDirection::Receive => idx::RPDO_COMM + n,
        PdoDirection::Transmit => idx::TPDO_COMM + n,
    }
}

pub(crate) fn map_index(dir: PdoDirection, n: u16) -> u16 {
    match dir {
        PdoDirection::Receive => idx::RPDO_MAP + n,
        PdoDirection::Transmit => idx::TPDO_MAP + n,
    }
}

/// Check a write of `value` (an unsigned integer) to a PDO parameter.
pub(crate) fn check_write(
    od: &ObjectDictionary,
    object: PdoObject,
    subindex: u8,
    value: u64,
) -> Result<(), SdoAbort> {
    match object {
        PdoObject::Comm(dir, n) => check_comm(od, dir, n, subindex, value),
        PdoObject::Map(dir, n) => check_map(od, dir, n, subindex, value),
    }
}

fn check_comm(
    od: &ObjectDictionary,
    dir: PdoDirection,
    n: u16,
    sub: u8,
    value: u64,
) -> Result<(), SdoAbort> {
    let comm = PdoComm::load(od, comm_index(dir, n));
    match sub {
        1 => {
            let new = u32::try_from(value).map_err(|_| SdoAbort::INVALID_VALUE)?;
            if new & EXTENDED != 0 {
                return Err(SdoAbort::INVALID_VALUE);
            }
            let id = (new & 0x7FF) as u16;
            // §7.5.2.35: the CAN-ID may change only while the PDO is invalid.
            if comm.valid() && new & INVALID == 0 && id != comm.can_id() {
                return Err(SdoAbort::INVALID_VALUE);
            }
            if new & INVALID == 0 {
                if restricted_can_id(id) {
                    return Err(SdoAbort::INVALID_VALUE);
                }
                // Validating needs a consistent mapping.
                let count = get_u8(od, map_index(dir, n), 0).unwrap_or(0);
                Mapping::check(od, map_index(dir, n), dir, count)
                    .map_err(|_| SdoAbort::PARAMETER_INCOMPATIBLE)?;
            }
            Ok(())
        }
        2 => {
            let t = u8::try_from(value).map_err(|_| SdoAbort::INVALID_VALUE)?;
            let ok = match dir {
                PdoDirection::Receive => matches!(t, 0..=240 | 254 | 255),
                PdoDirection::Transmit => matches!(t, 0..=240 | 252..=255),
            };
            if !ok {
                return Err(SdoAbort::INVALID_VALUE);
            }
            // RTR-only types need RTR allowed (bit 30 clear).
            if matches!(t, 252 | 253) && !comm.rtr_allowed() && comm.valid() {
                return Err(SdoAbort::PARAMETER_INCOMPATIBLE);
            }
            Ok(())
        }
        // §7.5.2.36: inhibit time and SYNC start value change only while the PDO is invalid.
        3 | 6 if comm.valid() => Err(SdoAbort::INVALID_VALUE),
        6 if value > 240 => Err(SdoAbort::INVALID_VALUE),
        _ => Ok(()),
    }
}

fn check_map(
    od: &ObjectDictionary,
    dir: PdoDirection,
    n: u16,
    sub: u8,
    value: u64,
) -> Result<(), SdoAbort> {
    let comm = PdoComm::load(od, comm_index(dir, n));
    let index = map_index(dir, n);
    // Mapping changes only while the PDO is invalid (step 1 of the procedure).
    if comm.valid() {
        return Err(SdoAbort::UNSUPPORTED_ACCESS);
    }
    let raw = u32::try_from(value).map_err(|_| SdoAbort::INVALID_VALUE)?;
    if sub == 0 {
        let count = u8::try_from(raw).map_err(|_| SdoAbort::VALUE_HIGH)?;
        let available = (1..=u8::MAX)
            .take_while(|&s| get_u32(od, index, s).is_some())
            .count();
        if usize::from(count) > available {
            return Err(SdoAbort::VALUE_HIGH);
        }
        // Step 4: every entry must be mappable and the total must fit in 64 bits.
        Mapping::check(od, index, dir, count)?;
        return Ok(());
    }
    // Step 3 needs sub-index 0 = 0 first.
    if get_u8(od, index, 0).unwrap_or(0) != 0 {
        return Err(SdoAbort::UNSUPPORTED_ACCESS);
    }
    if raw == 0 {
        return Ok(());
    }
    check_entry(od, raw, dir).map(|_| ())
}
