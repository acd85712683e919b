//! Process data objects (CiA 301 §7.2.2): communication parameters, mapping, and the write
//! rules of the dynamic mapping procedure (§7.5.2.35–§7.5.2.38).

pub(crate) mod config;
pub(crate) mod rpdo;
pub(crate) mod tpdo;

use axes::od::{DataType, ObjectDictionary, OdError, PdoDirection, Value};

use crate::device::{get_u16, get_u32, get_u8};
use crate::sdo::SdoAbort;

/// COB-ID bits (CiA 301 §7.5.2.35, Table 68).
pub(crate) const INVALID: u32 = 0x8000_0000;
pub(crate) const NO_RTR: u32 = 0x4000_0000;
pub(crate) const EXTENDED: u32 = 0x2000_0000;

/// A PDO's communication parameter record.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct PdoComm {
    pub cob: u32,
    pub ttype: u8,
    /// 100 µs units (TPDO).
    pub inhibit: u16,
    /// ms: transmission period of an event-driven TPDO, deadline of an RPDO.
    pub event_ms: u16,
    pub sync_start: u8,
}

impl PdoComm {
    pub(crate) fn load(od: &ObjectDictionary, index: u16) -> PdoComm {
        PdoComm {
            cob: get_u32(od, index, 1).unwrap_or(INVALID),
            ttype: get_u8(od, index, 2).unwrap_or(254),
            inhibit: get_u16(od, index, 3).unwrap_or(0),
            event_ms: get_u16(od, index, 5).unwrap_or(0),
            sync_start: get_u8(od, index, 6).unwrap_or(0),
        }
    }

    pub(crate) fn valid(&self) -> bool {
        self.cob & INVALID == 0
    }

    pub(crate) fn can_id(&self) -> u16 {
        (self.cob & 0x7FF) as u16
    }

    pub(crate) fn rtr_allowed(&self) -> bool {
        self.cob & NO_RTR == 0
    }
}

/// One mapped object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct MapEntry {
    pub index: u16,
    pub subindex: u8,
    pub data_type: Option<DataType>,
    pub len: usize,
    /// A dummy entry (data type index 0x0001–0x0007) that only skips bytes of an RPDO.
    pub dummy: bool,
}

/// A PDO's mapping.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Mapping {
    pub entries: Vec<MapEntry>,
    pub len: usize,
}

impl Mapping {
    /// Read the mapping record at `index`; an invalid mapping reads as empty.
    pub(crate) fn load(od: &ObjectDictionary, index: u16, dir: PdoDirection) -> Mapping {
        Mapping::check(od, index, dir, get_u8(od, index, 0).unwrap_or(0)).unwrap_or_default()
    }

    /// The mapping that `count` entries of the record would make, or why it cannot be.
    pub(crate) fn check(
        od: &ObjectDictionary,
        index: u16,
        dir: PdoDirection,
        count: u8,
    ) -> Result<Mapping, SdoAbort> {
        let mut m = Mapping::default();
        for sub in 1..=count {
            let raw = get_u32(od, index, sub).ok_or(SdoAbort::VALUE_HIGH)?;
            let e = check_entry(od, raw, dir)?;
            m.len += e.len;
            if m.len > 8 {
                return Err(SdoAbort::PDO_LENGTH);
            }
            m.entries.push(e);
        }
        Ok(m)
    }

    /// The PDO's data from the dictionary.
    pub(crate) fn pack(&self, od: &ObjectDictionary) -> ([u8; 8], usize) {
        let mut buf = [0u8; 8];
        let mut pos = 0;
        for e in &self.entries {
            if !e.dummy {
                let bytes = od
                    .get(e.index, e.subindex)
                    .map(Value::to_le_bytes)
                    .unwrap_or_default();
                for (i, b) in bytes.iter().take(e.len).enumerate() {
                    if let Some(slot) = buf.get_mut(pos + i) {
                        *slot = *b;
                    }
                }
            }
            pos += e.len;
        }
        (buf, self.len.min(8))
    }
}

/// Check one mapping entry value (index << 16 | sub-index << 8 | bit length).
pub(crate) fn check_entry(
    od: &ObjectDictionary,
    raw: u32,
    dir: PdoDirection,
) -> Result<MapEntry, SdoAbort> {
    let index = (raw >> 16) as u16;
    let subindex = (raw >> 8) as u8;
    let bits = (raw & 0xFF) as usize;
    // Byte-granular mapping only (bit-wise mapping is optional in CiA 301).
    if bits == 0 || !bits.is_multiple_of(8) {
        return Err(SdoAbort::NOT_MAPPABLE);
    }
    let len = bits / 8;
    if len > 8 {
        return Err(SdoAbort::PDO_LENGTH);
    }
    // Dummy mapping (§7.4.7.1): RPDOs may skip bytes with a data type index.
    if (0x0001..=0x0007).contains(&index) && subindex == 0 {
        let size = DataType::from_code(index).and_then(DataType::size);
        return match (dir, size) {
            (PdoDirection::Receive, Some(s)) if s == len => Ok(MapEntry {
                index,
                subindex,
                data_type: None,
                len,
                dummy: true,
            }),
            _ => Err(SdoAbort::NOT_MAPPABLE),
        };
    }
    let entry = od
        .check_mappable(index, subindex, dir)
        .map_err(|e| match e {
            OdError::NotMappable { .. } => SdoAbort::NOT_MAPPABLE,
            other => SdoAbort::from(other),
        })?;
    if entry.def.data_type.size() != Some(len) {
        return Err(SdoAbort::NOT_MAPPABLE);
    }
    Ok(MapEntry {
        index,
        subindex,
        data_type: Some(entry.def.data_type),
        len,
        dummy: false,
    })
}
