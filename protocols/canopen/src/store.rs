//! Store and restore parameters (CiA 301 §7.5.2.13/§7.5.2.14, objects 0x1010/0x1011) as a
//! byte image. The sans-IO node only builds and reads images; the transport writes them to disk
//! (write a temporary file, fsync, rename) so that a kill during a save loses nothing saved
//! before.
//!
//! Image format (little-endian): `MCEMUPAR`, version 1, entry count (u32), then per entry index
//! (u16), sub-index (u8), data type code (u16), length (u32), value bytes; last a CRC-32
//! (IEEE 802.3) of everything before it.

use axes::od::{Access, DataType, Entry, ObjectDictionary, Value};

use crate::objects::idx;

const MAGIC: &[u8; 8] = b"MCEMUPAR";
const VERSION: u8 = 1;

/// "save" written to 0x1010 sub-indices (CiA 301 §7.5.2.13).
pub const SAVE_SIGNATURE: u32 = 0x6576_6173;
/// "load" written to 0x1011 sub-indices (CiA 301 §7.5.2.14).
pub const LOAD_SIGNATURE: u32 = 0x6461_6F6C;

/// The parameter groups of 0x1010/0x1011 sub-indices 1–3.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ParameterGroup {
    /// Sub-index 1: all parameters.
    All,
    /// Sub-index 2: communication parameters, 0x1000–0x1FFF.
    Communication,
    /// Sub-index 3: application parameters, 0x2000–0x9FFF (manufacturer and profile areas).
    Application,
}

impl ParameterGroup {
    pub const fn from_subindex(sub: u8) -> Option<ParameterGroup> {
        match sub {
            1 => Some(ParameterGroup::All),
            2 => Some(ParameterGroup::Communication),
            3 => Some(ParameterGroup::Application),
            _ => None,
        }
    }

    pub const fn contains(self, index: u16) -> bool {
        match self {
            ParameterGroup::All => matches!(index, 0x1000..=0x9FFF),
            ParameterGroup::Communication => matches!(index, 0x1000..=0x1FFF),
            ParameterGroup::Application => matches!(index, 0x2000..=0x9FFF),
        }
    }
}

/// Whether an entry is a stored parameter: read-write (`rw`) entries; process data
/// (`rww`/`rwr`), read-only values, the error history, the store/restore commands and DOMAINs
/// are not. A DOMAIN is a block of data (up to 1 MiB), not a parameter: storing it would put
/// whatever a master last transferred into every power-on image (docs/decisions.md, "CANopen
/// node").
pub fn storable(entry: &Entry) -> bool {
    entry.def.access == Access::Rw
        && entry.def.data_type != DataType::Domain
        && !matches!(
            entry.def.index,
            idx::ERROR_HISTORY | idx::STORE | idx::RESTORE
        )
}

/// One stored value.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredEntry {
    pub index: u16,
    pub subindex: u8,
    pub value: Value,
}

/// An image that cannot be read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ImageError {
    #[error("not a parameter image (bad magic)")]
    Magic,
    #[error("parameter image version {0} is not supported")]
    Version(u8),
    #[error("parameter image is truncated")]
    Truncated,
    #[error(
        "parameter image checksum mismatch (stored {stored:#010x}, computed {computed:#010x})"
    )]
    Checksum { stored: u32, computed: u32 },
    #[error("parameter image entry {index:#06x}:{subindex} is invalid")]
    Entry { index: u16, subindex: u8 },
}

/// What loading an image did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadReport {
    pub applied: usize,
    /// Entries the dictionary lacks or whose type changed since the image was written.
    pub skipped: usize,
}

/// The storable entries of `group`, as an image.
pub fn serialize(od: &ObjectDictionary, group: ParameterGroup) -> Vec<u8> {
    encode(
        od.entries()
            .filter(|e| group.contains(e.def.index) && storable(e))
            .map(|e| StoredEntry {
                index: e.def.index,
                subindex: e.def.subindex,
                value: e.value.clone(),
            }),
    )
}

/// A new image: `previous` (if readable) with `group` replaced by the dictionary's values.
pub fn merge(previous: Option<&[u8]>, od: &ObjectDictionary, group: ParameterGroup) -> Vec<u8> {
    let kept = previous
        .and_then(|p| decode(p).ok())
        .unwrap_or_default()
        .into_iter()
        .filter(|e| !group.contains(e.index));
    let fresh = od
        .entries()
        .filter(|e| group.contains(e.def.index) && storable(e))
        .map(|e| StoredEntry {
            index: e.def.index,
            subindex: e.def.subindex,
            value: e.value.clone(),
        });
    let mut all: Vec<StoredEntry> = kept.chain(fresh).collect();
    all.sort_by_key(|e| (e.index, e.subindex));
    encode(all)
}

/// A new image: `previous` without `group` (restore default parameters).
pub fn remove(previous: Option<&[u8]>, group: ParameterGroup) -> Vec<u8> {
    encode(
        previous
            .and_then(|p| decode(p).ok())
            .unwrap_or_default()
            .into_iter()
            .filter(|e| !group.contains(e.index)),
    )
}

/// Apply the entries of `group` in `image` to the dictionary (device access).
pub fn load(
    od: &mut ObjectDictionary,
    image: &[u8],
    group: ParameterGroup,
) -> Result<LoadReport, ImageError> {
    let mut report = LoadReport::default();
    for e in decode(image)? {
        if !group.contains(e.index) {
            continue;
        }
        match od.set(e.index, e.subindex, e.value) {
            Ok(()) => report.applied += 1,
            Err(_) => report.skipped += 1,
        }
    }
    Ok(report)
}

/// Encode entries as an image.
pub fn encode(entries: impl IntoIterator<Item = StoredEntry>) -> Vec<u8> {
    let mut body = Vec::new();
    let mut count: u32 = 0;
    for e in entries {
        let bytes = e.value.to_le_bytes();
        let data_type = match &e.value {
            Value::Bytes(_) => DataType::Domain,
            v => v.data_type(),
        };
        body.extend_from_slice(&e.index.to_le_bytes());
        body.push(e.subindex);
        body.extend_from_slice(&data_type.code().to_le_bytes());
        body.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
        body.extend_from_slice(&bytes);
        count += 1;
    }
    let mut out = Vec::with_capacity(body.len() + 17);
    out.extend_from_slice(MAGIC);
    out.push(VERSION);
    out.extend_from_slice(&count.to_le_bytes());
    out.extend_from_slice(&body);
    let crc = crc32(&out);
    out.extend_from_slice(&crc.to_le_bytes());
    out
}

/// Decode an image, checking magic, version, checksum and every entry.
pub fn decode(image: &[u8]) -> Result<Vec<StoredEntry>, ImageError> {
    let split = image.len().checked_sub(4).ok_or(ImageError::Truncated)?;
    let (content, tail) = image.split_at(split);
    if content.get(..8) != Some(&MAGIC[..]) {
        return Err(ImageError::Magic);
    }
    let stored = u32::from_le_bytes(tail.try_into().map_err(|_| ImageError::Truncated)?);
    let computed = crc32(content);
    if stored != computed {
        return Err(ImageError::Checksum { stored, computed });
    }
    let mut r = Reader {
        rest: content.get(8..).unwrap_or_default(),
    };
    let version = r.take(1)?.first().copied().unwrap_or(0);
    if version != VERSION {
        return Err(ImageError::Version(version));
    }
    let count = u32::from_le_bytes(r.array()?);
    let mut out = Vec::new();
    for _ in 0..count {
        let index = u16::from_le_bytes(r.array()?);
        let subindex = r.take(1)?.first().copied().unwrap_or(0);
        let code = u16::from_le_bytes(r.array()?);
        let len = u32::from_le_bytes(r.array()?) as usize;
        let bytes = r.take(len)?;
        let bad = ImageError::Entry { index, subindex };
        let data_type = DataType::from_code(code).ok_or(bad.clone())?;
        let value = Value::from_le_bytes(data_type, bytes).map_err(|_| bad)?;
        out.push(StoredEntry {
            index,
            subindex,
            value,
        });
    }
    if !r.rest.is_empty() {
        return Err(ImageError::Truncated);
    }
    Ok(out)
}

struct Reader<'a> {
    rest: &'a [u8],
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], ImageError> {
        if n > self.rest.len() {
            return Err(ImageError::Truncated);
        }
        let (head, tail) = self.rest.split_at(n);
        self.rest = tail;
        Ok(head)
    }

    fn array<const N: usize>(&mut self) -> Result<[u8; N], ImageError> {
        self.take(N)?.try_into().map_err(|_| ImageError::Truncated)
    }
}

/// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320).
pub fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use axes::od::EntryDef;

    fn od() -> ObjectDictionary {
        ObjectDictionary::from_defs([
            EntryDef::new(0x1017, 0, "hb", Access::Rw, Value::U16(0)),
            EntryDef::new(0x1001, 0, "reg", Access::Ro, Value::U8(0)),
            EntryDef::new(0x2000, 0, "gain", Access::Rw, Value::F32(1.0)),
            EntryDef::new(0x2001, 0, "name", Access::Rw, Value::String("a".into())),
            EntryDef::new(0x6040, 0, "cw", Access::Rww, Value::U16(0)),
        ])
        .unwrap()
    }

    #[test]
    fn round_trip_by_group_and_checksum_detects_damage() {
        let mut src = od();
        src.write(0x1017, 0, Value::U16(100)).unwrap();
        src.write(0x2000, 0, Value::F32(2.5)).unwrap();
        src.write(0x2001, 0, Value::String("hello".into())).unwrap();
        src.write(0x6040, 0, Value::U16(15)).unwrap();
        let image = serialize(&src, ParameterGroup::All);
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        let mut dst = od();
        let report = load(&mut dst, &image, ParameterGroup::Communication).unwrap();
        assert_eq!(
            report,
            LoadReport {
                applied: 1,
                skipped: 0
            }
        );
        assert_eq!(dst.get(0x1017, 0), Some(&Value::U16(100)));
        assert_eq!(dst.get(0x2000, 0), Some(&Value::F32(1.0)));
        load(&mut dst, &image, ParameterGroup::All).unwrap();
        assert_eq!(dst.get(0x2001, 0), Some(&Value::String("hello".into())));
        // Process data is not a parameter.
        assert_eq!(dst.get(0x6040, 0), Some(&Value::U16(0)));
        for i in 0..image.len() {
            let mut bad = image.clone();
            bad[i] ^= 0x01;
            assert!(decode(&bad).is_err(), "flip at {i}");
        }
        for n in 0..image.len() {
            assert!(decode(&image[..n]).is_err());
        }
    }

    #[test]
    fn merge_replaces_one_group_and_remove_drops_it() {
        let mut a = od();
        a.write(0x1017, 0, Value::U16(5)).unwrap();
        a.write(0x2000, 0, Value::F32(3.0)).unwrap();
        let all = serialize(&a, ParameterGroup::All);
        a.write(0x1017, 0, Value::U16(7)).unwrap();
        a.write(0x2000, 0, Value::F32(4.0)).unwrap();
        let merged = merge(Some(&all), &a, ParameterGroup::Communication);
        let entries = decode(&merged).unwrap();
        assert!(entries.contains(&StoredEntry {
            index: 0x1017,
            subindex: 0,
            value: Value::U16(7)
        }));
        assert!(entries.contains(&StoredEntry {
            index: 0x2000,
            subindex: 0,
            value: Value::F32(3.0)
        }));
        let removed = remove(Some(&merged), ParameterGroup::Application);
        assert!(decode(&removed).unwrap().iter().all(|e| e.index < 0x2000));
    }
}
