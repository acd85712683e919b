//! Default PDO communication and mapping parameters (CiA 301 §7.5.2.35–38: 0x1400/0x1600 for
//! receive PDOs, 0x1800/0x1A00 for transmit PDOs), read from a file's initial values and checked
//! at load: every mapped object exists, is mappable in that direction, has the mapped length, and
//! a PDO carries at most 64 bits.

use axes::od::{DataType, PdoDirection, Value};

use super::error::{EdsError, Place, Reason};
use super::objects::SubObject;
use super::Eds;

/// COB-ID bit 31: the PDO does not exist / is not valid.
pub const COB_ID_INVALID: u32 = 1 << 31;
/// COB-ID bit 30: no RTR allowed on this PDO.
pub const COB_ID_NO_RTR: u32 = 1 << 30;
/// A PDO carries one CAN frame: 8 bytes.
pub const MAX_PDO_BITS: u32 = 64;

/// One mapping entry (0x1600:n / 0x1A00:n): index in bits 16–31, sub-index 8–15, length 0–7.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MappedObject {
    pub index: u16,
    pub subindex: u8,
    pub bits: u8,
}

impl MappedObject {
    pub const fn from_raw(raw: u32) -> MappedObject {
        MappedObject {
            index: (raw >> 16) as u16,
            subindex: (raw >> 8) as u8,
            bits: raw as u8,
        }
    }

    pub const fn raw(self) -> u32 {
        (self.index as u32) << 16 | (self.subindex as u32) << 8 | self.bits as u32
    }
}

/// One PDO's defaults for a node.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PdoDefault {
    pub direction: PdoDirection,
    /// 1-based: RPDO1 is 0x1400/0x1600, TPDO1 0x1800/0x1A00.
    pub number: u16,
    /// Raw sub-index 1: [`COB_ID_INVALID`], [`COB_ID_NO_RTR`], CAN id.
    pub cob_id: u32,
    /// Sub-index 2: 0 acyclic synchronous, 1–240 every n-th SYNC, 254/255 event-driven.
    pub transmission_type: u8,
    /// Sub-index 3, in 100 µs (TPDO).
    pub inhibit_time: u16,
    /// Sub-index 5, in ms (TPDO: event timer; RPDO: deadline monitoring).
    pub event_timer: u16,
    /// Sub-index 6 (TPDO): SYNC counter value to start at, 0 = not used.
    pub sync_start: u8,
    /// The first sub-index-0 entries of the mapping object.
    pub mapping: Vec<MappedObject>,
}

impl PdoDefault {
    /// Whether the PDO exists (COB-ID bit 31 clear).
    pub fn valid(&self) -> bool {
        self.cob_id & COB_ID_INVALID == 0
    }

    /// The CAN identifier (29 bits; 11-bit identifiers are below 0x800).
    pub fn can_id(&self) -> u32 {
        self.cob_id & 0x1FFF_FFFF
    }

    /// The communication parameter object (0x1400 + n − 1 or 0x1800 + n − 1).
    pub fn communication_index(&self) -> u16 {
        base(self.direction).wrapping_add(self.number.wrapping_sub(1))
    }

    /// The mapping parameter object (communication index + 0x200).
    pub fn mapping_index(&self) -> u16 {
        self.communication_index().wrapping_add(0x200)
    }

    /// Payload length in bits.
    pub fn bits(&self) -> u32 {
        self.mapping.iter().map(|m| u32::from(m.bits)).sum()
    }
}

const fn base(direction: PdoDirection) -> u16 {
    match direction {
        PdoDirection::Receive => 0x1400,
        PdoDirection::Transmit => 0x1800,
    }
}

const PDOS_PER_DIRECTION: u16 = 0x200;

/// The PDOs the file defines, receive then transmit, in number order, for `node_id`.
pub(crate) fn defaults(eds: &Eds, node_id: u8) -> Result<Vec<PdoDefault>, EdsError> {
    let mut pdos = Vec::new();
    for direction in [PdoDirection::Receive, PdoDirection::Transmit] {
        let first = base(direction);
        let last = first + PDOS_PER_DIRECTION - 1;
        for (&index, _) in eds.objects.range(first..=last) {
            pdos.push(read_pdo(eds, direction, index, node_id)?);
        }
        // A mapping object without its communication object.
        let mappings = first + PDOS_PER_DIRECTION..=last + PDOS_PER_DIRECTION;
        for (&index, _) in eds.objects.range(mappings) {
            if !eds.objects.contains_key(&(index - PDOS_PER_DIRECTION)) {
                return Err(error(
                    eds,
                    object_section(eds, index),
                    None,
                    format!(
                        "PDO mapping object without its communication object {:#06x}",
                        index - PDOS_PER_DIRECTION
                    ),
                ));
            }
        }
    }
    Ok(pdos)
}

/// Check the PDO objects once, for node id 1 (COB-IDs move with the node id; mappings do not).
pub(crate) fn check(eds: &Eds) -> Result<(), EdsError> {
    defaults(eds, 1).map(|_| ())
}

fn read_pdo(
    eds: &Eds,
    direction: PdoDirection,
    comm: u16,
    node_id: u8,
) -> Result<PdoDefault, EdsError> {
    let number = comm - base(direction) + 1;
    let label = match direction {
        PdoDirection::Receive => "RPDO",
        PdoDirection::Transmit => "TPDO",
    };
    let map_index = comm + PDOS_PER_DIRECTION;
    let Some(map_object) = eds.objects.get(&map_index) else {
        return Err(error(
            eds,
            object_section(eds, comm),
            None,
            format!("{label}{number} has no mapping object [{map_index:04X}]"),
        ));
    };
    let value = |index: u16, subindex: u8, data_type: DataType| -> Result<Option<u64>, EdsError> {
        let Some(sub) = eds.objects.get(&index).and_then(|o| o.sub(subindex)) else {
            return Ok(None);
        };
        if sub.data_type != data_type {
            return Err(error(
                eds,
                sub.section.clone(),
                Some("DataType"),
                format!(
                    "{label}{number} parameter {index:#06x}:{subindex} is {data_type}, not {}",
                    sub.data_type
                ),
            ));
        }
        Ok(sub
            .initial()
            .resolve(node_id)
            .as_ref()
            .and_then(Value::as_u64))
    };
    let required = |subindex: u8, what: &str| {
        error(
            eds,
            object_section(eds, comm),
            None,
            format!("{label}{number} has no {what} (sub-index {subindex})"),
        )
    };
    let narrow = |v: Option<u64>| v.and_then(|v| u16::try_from(v).ok()).unwrap_or(0);
    let cob_id = value(comm, 1, DataType::Unsigned32)?.ok_or_else(|| required(1, "COB-ID"))?;
    let transmission_type =
        value(comm, 2, DataType::Unsigned8)?.ok_or_else(|| required(2, "transmission type"))?;
    let inhibit_time = narrow(value(comm, 3, DataType::Unsigned16)?);
    let event_timer = narrow(value(comm, 5, DataType::Unsigned16)?);
    let sync_start = narrow(value(comm, 6, DataType::Unsigned8)?);

    let count = value(map_index, 0, DataType::Unsigned8)?.ok_or_else(|| {
        error(
            eds,
            object_section(eds, map_index),
            None,
            format!("{label}{number} mapping has no sub-index 0"),
        )
    })?;
    let mut mapping = Vec::new();
    let mut bits = 0u32;
    for n in 1..=count {
        let n = u8::try_from(n).unwrap_or(u8::MAX);
        let Some(entry_sub) = map_object.sub(n) else {
            let sub0 = map_object.sub(0);
            return Err(error(
                eds,
                sub0.map_or_else(|| object_section(eds, map_index), |s| s.section.clone()),
                sub0.map(value_key),
                format!("{label}{number} maps {count} objects, but sub-index {n} does not exist"),
            ));
        };
        let raw = value(map_index, n, DataType::Unsigned32)?.unwrap_or(0);
        let entry = MappedObject::from_raw(u32::try_from(raw).unwrap_or(0));
        let fail = |why: String| {
            error(
                eds,
                entry_sub.section.clone(),
                Some(value_key(entry_sub)),
                format!(
                    "{label}{number} entry {n} maps {:#06x}:{:02x} ({} bits): {why}",
                    entry.index, entry.subindex, entry.bits
                ),
            )
        };
        check_entry(eds, direction, entry).map_err(fail)?;
        bits += u32::from(entry.bits);
        if bits > MAX_PDO_BITS {
            return Err(fail(format!(
                "the PDO would carry {bits} bits; at most {MAX_PDO_BITS}"
            )));
        }
        mapping.push(entry);
    }
    Ok(PdoDefault {
        direction,
        number,
        cob_id: u32::try_from(cob_id).unwrap_or(COB_ID_INVALID),
        transmission_type: u8::try_from(transmission_type).unwrap_or(0),
        inhibit_time,
        event_timer,
        sync_start: u8::try_from(sync_start).unwrap_or(0),
        mapping,
    })
}

fn check_entry(eds: &Eds, direction: PdoDirection, entry: MappedObject) -> Result<(), String> {
    // Dummy entries: the data type's index, sub-index 0 (CiA 301 §7.4.7.1).
    if (1..=7).contains(&entry.index) && entry.subindex == 0 {
        if !eds.dummy_usage.supports(entry.index) {
            return Err(format!(
                "a dummy entry, but [DummyUsage] Dummy{:04} is not 1",
                entry.index
            ));
        }
        let data_type = DataType::from_code(entry.index);
        return check_length(data_type, entry.bits);
    }
    let Some(sub) = eds
        .objects
        .get(&entry.index)
        .and_then(|o| o.sub(entry.subindex))
    else {
        return Err("no such object in this file".into());
    };
    if !sub.pdo_mappable {
        return Err("the object is not PDO-mappable (PDOMapping=0)".into());
    }
    if !sub.access.maps_to(direction) {
        return Err(format!(
            "AccessType={} cannot go into a {}",
            sub.access.eds_name(),
            match direction {
                PdoDirection::Receive => "receive PDO",
                PdoDirection::Transmit => "transmit PDO",
            }
        ));
    }
    check_length(Some(sub.data_type), entry.bits)
}

fn check_length(data_type: Option<DataType>, bits: u8) -> Result<(), String> {
    let expected = match data_type {
        Some(DataType::Boolean) if bits == 1 || bits == 8 => return Ok(()),
        Some(t) => t.size().map(|s| s * 8),
        None => None,
    };
    match expected {
        Some(e) if usize::from(bits) != e => Err(format!("the object has {e} bits")),
        None if bits == 0 || !bits.is_multiple_of(8) => {
            Err("a length of whole bytes is needed".into())
        }
        _ => Ok(()),
    }
}

/// The key whose value a mapping entry came from.
fn value_key(sub: &SubObject) -> &'static str {
    if sub.parameter_value.is_some() {
        "ParameterValue"
    } else {
        "DefaultValue"
    }
}

fn object_section(eds: &Eds, index: u16) -> String {
    eds.objects
        .get(&index)
        .map_or_else(|| format!("{index:04X}"), |o| o.section.clone())
}

fn error(eds: &Eds, section: String, key: Option<&str>, reason: String) -> EdsError {
    Place {
        section: Some(&section),
        key,
        line: None,
    }
    .error(&eds.file_name, Reason::Pdo(reason))
}
