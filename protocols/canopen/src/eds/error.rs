//! Why an EDS/DCF file cannot be loaded, with the place to fix it: file, section, key and line.

use std::fmt;

use axes::od::DataType;

/// A load error (or, in [`Eds::warnings`](super::Eds::warnings), a problem that did not stop the
/// load). Displays as `cia402-drive.eds: [6040] DataType: unknown data type 0x00ff (line 57)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EdsError {
    /// The file name the caller gave (usually the path).
    pub file: Box<str>,
    /// The section, as the file spells it (`6040`, `1018sub2`, `DeviceInfo`).
    pub section: Option<Box<str>>,
    /// The key, as the file spells it (`DataType`), or a list entry number (`3`).
    pub key: Option<Box<str>>,
    /// The 1-based line of the key or section, where there is one.
    pub line: Option<usize>,
    pub reason: Reason,
}

impl std::error::Error for EdsError {}

impl fmt::Display for EdsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.file)?;
        if let Some(section) = &self.section {
            write!(f, "[{section}] ")?;
        }
        if let Some(key) = &self.key {
            write!(f, "{key}: ")?;
        }
        write!(f, "{}", self.reason)?;
        if let Some(line) = self.line {
            write!(f, " (line {line})")?;
        }
        Ok(())
    }
}

/// What is wrong. The [`EdsError`] around it says where.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Reason {
    #[error("cannot read the file: {0}")]
    Io(String),
    #[error("the file has {size} bytes; the limit is {max}")]
    TooLarge { size: u64, max: usize },

    // ---- INI syntax ----
    #[error("expected `[section]`, `key=value` or a `;` comment, found {0:?}")]
    Syntax(String),
    #[error("a section name ends with `]`")]
    UnclosedSection,
    #[error("empty section name")]
    EmptySectionName,
    #[error("empty key")]
    EmptyKey,
    #[error("key before the first section")]
    KeyOutsideSection,
    #[error("section defined twice (first on line {first_line})")]
    DuplicateSection { first_line: usize },
    #[error("key given twice in this section (first on line {first_line})")]
    DuplicateKey { first_line: usize },

    // ---- keys and values ----
    #[error("missing")]
    Missing,
    #[error("section missing")]
    MissingSection,
    #[error("{text:?} is not a number ({why})")]
    NotANumber { text: String, why: &'static str },
    #[error("{text:?} is out of range for {data_type}")]
    OutOfRange { text: String, data_type: DataType },
    #[error("{text:?} is out of range ({range})")]
    OutOfRangeFor { text: String, range: &'static str },
    #[error("{text:?}: expected 0 or 1")]
    NotABool { text: String },
    #[error("{text:?}: a VISIBLE_STRING holds printable ASCII only")]
    NotVisibleString { text: String },
    #[error("{text:?}: expected hex digit pairs")]
    NotHexBytes { text: String },
    #[error("{text:?}: $NODEID applies to integer types only, not {data_type}")]
    NodeIdNotInteger { text: String, data_type: DataType },
    #[error("{text:?} is out of range for {data_type} with node id {node_id}")]
    NodeIdOutOfRange {
        text: String,
        data_type: DataType,
        node_id: u8,
    },
    #[error("unknown data type {code:#06x}")]
    UnknownDataType { code: u32 },
    #[error("data type {code:#06x} ({name}) is not supported")]
    UnsupportedDataType { code: u32, name: &'static str },
    #[error("unknown object type {code:#x} (expected 0x2 DOMAIN, 0x5 DEFTYPE, 0x6 DEFSTRUCT, 0x7 VAR, 0x8 ARRAY or 0x9 RECORD)")]
    UnknownObjectType { code: u32 },
    #[error("unknown access type {text:?} (expected ro, wo, rw, rwr, rww or const)")]
    UnknownAccessType { text: String },
    #[error("{data_type} takes no limits")]
    LimitsNotNumeric { data_type: DataType },
    #[error("{value} is below LowLimit {low}")]
    BelowLowLimit { value: String, low: String },
    #[error("{value} is above HighLimit {high}")]
    AboveHighLimit { value: String, high: String },
    #[error("LowLimit {low} is above HighLimit {high}")]
    LimitsCrossed { low: String, high: String },

    // ---- object structure ----
    #[error("object {index:#06x} has no section [{index:04X}]")]
    ListedObjectMissing { index: u16 },
    #[error("object {index:#06x} is listed twice")]
    ListedTwice { index: u16 },
    #[error("object {index:#06x} is mandatory (CiA 301) and missing")]
    MandatoryObjectMissing { index: u16 },
    #[error("index 0x0000 is not an object")]
    IndexZero,
    #[error("not an object or sub-index section name")]
    BadObjectSectionName,
    #[error("no object section [{index:04X}] for this sub-index")]
    SubWithoutObject { index: u16 },
    #[error("object {index:#06x} is a {object_type}; only ARRAY, RECORD and DEFSTRUCT have sub-index sections")]
    SubOfVar {
        index: u16,
        object_type: &'static str,
    },
    #[error("says {declared}, but there are {found} sub-index sections")]
    SubNumberMismatch { declared: u32, found: usize },
    #[error(
        "an ARRAY, RECORD or DEFSTRUCT needs sub-index 0 ([{index:04X}sub0]) or CompactSubObj"
    )]
    NoSubIndexZero { index: u16 },
    #[error("sub-index 0 of an ARRAY, RECORD or DEFSTRUCT is UNSIGNED8, not {data_type}")]
    SubIndexZeroType { data_type: DataType },
    #[error("with CompactSubObj the object has no sub-index sections, but [{section}] exists")]
    CompactWithSubs { section: String },
    #[error("entry {entry} is outside the sub-indices 1–{count} of CompactSubObj")]
    CompactEntryBeyond { entry: u32, count: u32 },
    #[error("says {declared}, but the section has {found} entries")]
    EntryCountMismatch { declared: u32, found: usize },

    #[error("entry beyond SupportedObjects={count}: ignored")]
    ListEntryBeyond { count: u16 },
    #[error("no object list names this object (loaded all the same)")]
    Unlisted,
    #[error("says {declared}, but the file has {found} PDO communication objects")]
    PdoCount { declared: u16, found: usize },

    // ---- PDOs ----
    #[error("{0}")]
    Pdo(String),

    // ---- building a dictionary ----
    #[error("node id {node_id} is outside 1–127")]
    NodeIdInvalid { node_id: u32 },
    #[error("{0}")]
    Definition(String),
}

/// Where a problem is, before the file name is attached.
#[derive(Clone, Debug, Default)]
pub(crate) struct Place<'a> {
    pub section: Option<&'a str>,
    pub key: Option<&'a str>,
    pub line: Option<usize>,
}

impl<'a> Place<'a> {
    pub fn section(section: &'a str, line: usize) -> Place<'a> {
        Place {
            section: Some(section),
            key: None,
            line: Some(line),
        }
    }

    pub fn key(section: &'a str, key: &'a str, line: usize) -> Place<'a> {
        Place {
            section: Some(section),
            key: Some(key),
            line: Some(line),
        }
    }

    pub fn error(&self, file: &str, reason: Reason) -> EdsError {
        EdsError {
            file: file.into(),
            section: self.section.map(Box::from),
            key: self.key.map(Box::from),
            line: self.line,
            reason,
        }
    }
}
