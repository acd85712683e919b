//! Object dictionaries from CiA 306 electronic data sheets (EDS) and device configuration files
//! (DCF), ARCHITECTURE §3.8 and §5.
//!
//! [`Eds::load`] (or [`Eds::parse`]) reads a file into a model — device information, the
//! objects with their types, access, PDO mappability, defaults and limits, the default PDO
//! parameters — and [`Eds::dictionary`] builds the [`ObjectDictionary`] a node with a given node
//! id starts with (`$NODEID` values resolved, a DCF's `ParameterValue`s in place of defaults).
//! Every error names the file, section and key; no input makes the parser panic.
//!
//! ```
//! # fn main() -> Result<(), mcemu_canopen::eds::EdsError> {
//! use mcemu_canopen::eds::Eds;
//! let eds = Eds::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/canopen/cia402-drive.eds"))?;
//! let od = eds.dictionary(5)?;
//! assert_eq!(od.read(0x1200, 2).ok(), Some(axes::od::Value::U32(0x585)));
//! # Ok(()) }
//! ```

mod error;
mod fields;
mod info;
mod ini;
mod load;
mod objects;
mod pdo;
mod value;

use std::collections::BTreeMap;
use std::io::Read;
use std::path::Path;

use axes::od::{EntryDef, ObjectDictionary, PdoDirection};

pub use error::{EdsError, Reason};
pub use info::{Commissioning, DeviceInfo, DummyUsage, FileInfo, BIT_RATES_KBIT};
pub use objects::{Object, ObjectList, ObjectType, SubObject};
pub use pdo::{MappedObject, PdoDefault, COB_ID_INVALID, COB_ID_NO_RTR, MAX_PDO_BITS};
pub use value::{format_value, parse_value, EdsValue, NODE_IDS};

use error::Place;

/// A loaded EDS or DCF.
#[derive(Clone, Debug, PartialEq)]
pub struct Eds {
    /// The name errors show (the path given to [`Eds::load`]).
    pub file_name: String,
    pub file_info: FileInfo,
    pub device_info: DeviceInfo,
    pub dummy_usage: DummyUsage,
    /// [DeviceComissioning], in a DCF.
    pub commissioning: Option<Commissioning>,
    /// [Comments] lines.
    pub comments: Vec<String>,
    objects: BTreeMap<u16, Object>,
    /// Problems that did not stop the load: a missing [FileInfo] or [DeviceInfo], object sections
    /// no list names, `NrOfRXPDO`/`NrOfTXPDO` that disagree with the file's PDO objects.
    pub warnings: Vec<EdsError>,
}

impl Eds {
    /// Largest file [`Eds::load`] reads (real EDS files are well under 1 MiB).
    pub const MAX_FILE_SIZE: usize = 16 << 20;

    /// Read and parse a file.
    pub fn load(path: impl AsRef<Path>) -> Result<Eds, EdsError> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let io = |e: std::io::Error| Place::default().error(&name, Reason::Io(e.to_string()));
        let file = std::fs::File::open(path).map_err(io)?;
        let mut bytes = Vec::new();
        let limit = u64::try_from(Eds::MAX_FILE_SIZE).unwrap_or(u64::MAX);
        file.take(limit + 1).read_to_end(&mut bytes).map_err(io)?;
        if bytes.len() > Eds::MAX_FILE_SIZE {
            let size = std::fs::metadata(path).map_or(limit + 1, |m| m.len());
            return Err(Place::default().error(
                &name,
                Reason::TooLarge {
                    size,
                    max: Eds::MAX_FILE_SIZE,
                },
            ));
        }
        Eds::parse_bytes(&name, &bytes)
    }

    /// Parse file contents. UTF-8 (with or without BOM); other bytes are read as Latin-1, the
    /// usual encoding of EDS files written on Windows.
    pub fn parse_bytes(file_name: &str, bytes: &[u8]) -> Result<Eds, EdsError> {
        match std::str::from_utf8(bytes) {
            Ok(text) => Eds::parse(file_name, text),
            Err(_) => {
                let text: String = bytes.iter().map(|&b| char::from(b)).collect();
                Eds::parse(file_name, &text)
            }
        }
    }

    /// Parse file contents; `file_name` is what errors show.
    pub fn parse(file_name: &str, text: &str) -> Result<Eds, EdsError> {
        load::load(file_name, text)
    }

    /// Whether this is a device configuration (a DCF: it has [DeviceComissioning]).
    pub fn is_dcf(&self) -> bool {
        self.commissioning.is_some()
    }

    /// Every object, in index order.
    pub fn objects(&self) -> impl Iterator<Item = &Object> {
        self.objects.values()
    }

    pub fn object(&self, index: u16) -> Option<&Object> {
        self.objects.get(&index)
    }

    pub fn sub_object(&self, index: u16, subindex: u8) -> Option<&SubObject> {
        self.objects.get(&index).and_then(|o| o.sub(subindex))
    }

    /// Every sub-object, in (index, sub-index) order.
    pub fn sub_objects(&self) -> impl Iterator<Item = &SubObject> {
        self.objects.values().flat_map(|o| o.sub_objects.values())
    }

    /// The sub-objects that may be mapped into a PDO of `direction`.
    pub fn mappable(&self, direction: PdoDirection) -> impl Iterator<Item = &SubObject> {
        self.sub_objects()
            .filter(move |s| s.pdo_mappable && s.access.maps_to(direction))
    }

    /// The dictionary table for `node_id` (1–127).
    pub fn entry_defs(&self, node_id: u8) -> Result<Vec<EntryDef>, EdsError> {
        self.check_node_id(node_id)?;
        Ok(self.sub_objects().map(|s| s.entry_def(node_id)).collect())
    }

    /// The dictionary a node with `node_id` (1–127) starts with.
    pub fn dictionary(&self, node_id: u8) -> Result<ObjectDictionary, EdsError> {
        ObjectDictionary::from_defs(self.entry_defs(node_id)?).map_err(|e| {
            // Checked at load; kept as an error, not a panic, should the two checks diverge.
            Place::default().error(&self.file_name, Reason::Definition(e.to_string()))
        })
    }

    /// The default PDO parameters for `node_id` (1–127): receive PDOs, then transmit PDOs, each
    /// in number order.
    pub fn default_pdos(&self, node_id: u8) -> Result<Vec<PdoDefault>, EdsError> {
        self.check_node_id(node_id)?;
        pdo::defaults(self, node_id)
    }

    fn check_node_id(&self, node_id: u8) -> Result<(), EdsError> {
        if NODE_IDS.contains(&node_id) {
            Ok(())
        } else {
            Err(Place::default().error(
                &self.file_name,
                Reason::NodeIdInvalid {
                    node_id: u32::from(node_id),
                },
            ))
        }
    }
}
