//! The register-map file format, as serde reads it. [`super::compile`] turns it into the tables
//! the service runs on and refuses what cannot work, naming the key.
//!
//! ```toml
//! [map]
//! name = "generic"
//! word_order = "abcd"            # 32/64-bit values; points may override
//!
//! [identity]                     # FC 17 and FC 43/14
//! vendor_name = "mcemu"
//!
//! [[point]]                      # one value at a fixed address
//! table = "holding_registers"
//! address = 8208
//! name = "controller_status"
//! read = "machine.error"
//! values = { "0" = 2, "1" = 4 }
//!
//! [[block]]                      # one copy per axis the front-end serves
//! table = "holding_registers"
//! base = 0
//! stride = 100
//! [[block.point]]
//! offset = 4
//! name = "position"
//! type = "f64"
//! read = "axis.act_pos"
//! ```

use std::collections::BTreeMap;

use serde::Deserialize;

use super::value::{PointType, WordOrder};

/// A whole map file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapFile {
    pub map: MapHeader,
    #[serde(default)]
    pub identity: IdentityFile,
    /// Points at fixed addresses.
    #[serde(default)]
    pub point: Vec<PointFile>,
    /// Per-axis blocks.
    #[serde(default)]
    pub block: Vec<BlockFile>,
    /// Plain memory areas (PLC V-memory, user tables): registers or bits that hold what was
    /// written.
    #[serde(default)]
    pub memory: Vec<MemoryFile>,
    /// Every I/O channel of one kind the machine has, one point each from a base address.
    #[serde(default)]
    pub channels: Vec<ChannelsFile>,
}

/// `di`, `do`, `ai` or `ao` channel N at `base + N × width`; outputs take writes when the table
/// does (coils, holding registers).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChannelsFile {
    pub table: Table,
    pub base: u16,
    pub kind: ChannelKind,
    /// For analog channels in registers; `f32` unless given.
    #[serde(default, rename = "type")]
    pub ty: Option<PointType>,
    #[serde(default)]
    pub scale: Option<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ChannelKind {
    Di,
    Do,
    Ai,
    Ao,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapHeader {
    pub name: String,
    #[serde(default)]
    pub description: String,
    /// Word order of values wider than one register, unless a point says otherwise.
    #[serde(default)]
    pub word_order: WordOrder,
    /// What a read that covers an address no point defines gets.
    #[serde(default)]
    pub gaps: Gaps,
    /// Parameter writes follow the HMC rule (HMC §3.5.1): a negative value is made positive and
    /// zero restores the default, instead of being refused.
    #[serde(default)]
    pub lenient_parameters: bool,
}

/// Reads of undefined addresses inside a request's range.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Gaps {
    /// Exception 02, as the specification has it for an address the server does not have.
    #[default]
    Error,
    /// Zeros, as many devices answer.
    Zero,
}

pub use crate::tables::Table;

#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IdentityFile {
    /// FC 17 server id bytes.
    #[serde(default)]
    pub server_id: Vec<u8>,
    #[serde(default)]
    pub vendor_name: String,
    #[serde(default)]
    pub product_code: String,
    #[serde(default)]
    pub revision: String,
    #[serde(default)]
    pub vendor_url: String,
    #[serde(default)]
    pub product_name: String,
    #[serde(default)]
    pub model_name: String,
    #[serde(default)]
    pub user_application_name: String,
}

/// One value: where it lies, its type, where reads come from and what writes do.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointFile {
    /// The table; inside a block, the block's.
    #[serde(default)]
    pub table: Option<Table>,
    /// PDU address (0-based) of the first register or bit; for points outside blocks.
    #[serde(default)]
    pub address: Option<u16>,
    /// Offset from the block's base; for points inside blocks.
    #[serde(default)]
    pub offset: Option<u16>,
    pub name: String,
    /// `bool` in bit tables; `u16` in register tables unless given.
    #[serde(default, rename = "type")]
    pub ty: Option<PointType>,
    /// Registers of a `string`.
    #[serde(default)]
    pub length: Option<u16>,
    #[serde(default)]
    pub word_order: Option<WordOrder>,
    /// Raw value = engineering value × scale (e.g. 1000 for µm in a register, mm in the engine).
    #[serde(default)]
    pub scale: Option<f64>,
    /// Where reads come from; absent: the point's own memory cell.
    #[serde(default)]
    pub read: Option<ReadFile>,
    /// Where writes go: a target path, or `"memory"` to hold the value; absent with no
    /// `on_write`: the point is read-only.
    #[serde(default)]
    pub write: Option<String>,
    /// Commands a write issues, after the value is stored or applied.
    #[serde(default)]
    pub on_write: Vec<ActionFile>,
    /// Lookup applied to what `read` gives (keys: numbers or names such as an error kind).
    #[serde(default)]
    pub values: BTreeMap<String, f64>,
    /// Value for a read the lookup does not list; without it such a read passes through.
    #[serde(default)]
    pub default: Option<f64>,
    /// Compose a nonzero value with its axis as `code << 24 | axis << 16 | value` (the HIMC's
    /// `0x83NNVVVV` axis error codes, digest 004 §5).
    #[serde(default)]
    pub axis_code: Option<u8>,
    /// Initial value of a memory cell or constant.
    #[serde(default)]
    pub init: Option<InitValue>,
}

/// A read source: a path, or a status word composed bit by bit.
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum ReadFile {
    Path(String),
    /// `{ bits = { 0 = "enabled", 1 = "moving", 5 = "!homed", 8 = "state.error_stop" } }`: an
    /// axis flag (`latched.` for its latched copy), `state.` a PLCopen state, or `mode.` one of
    /// `gantry`, `gear`, `input_shaping`, `vsf`.
    Bits {
        bits: BTreeMap<String, String>,
    },
    /// The value of the first case that holds, else 0: a vendor's error-code table.
    /// `{ first = [{ when = "latched.drive_alarm", value = 0x03f2 }, …] }`; a value may be a
    /// code's name instead (`value = "eERR_AXIS_DRIVE_FAULT"`). With
    /// `all_axes = true` the cases are tried on each served axis in turn and the first axis
    /// with a nonzero value answers (a controller-wide "latest error").
    Select {
        first: Vec<CaseFile>,
        #[serde(default)]
        all_axes: bool,
    },
}

/// A case of a `first` table: a flag, `latched.FLAG`, `state.NAME` (each may start with `!`) or
/// `last_error.KIND`; and the value it gives.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    pub when: String,
    pub value: CodeFile,
}

/// A code: a number, or a vendor's name for one (`"eERR_AXIS_DRIVE_FAULT"`), looked up in the
/// dialects' tables ([`mcemu_dialects::code_by_name`]).
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum CodeFile {
    Number(f64),
    Name(String),
}

#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum InitValue {
    Number(f64),
    Text(String),
}

/// A command a write issues.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActionFile {
    /// When it fires: `always`, `nonzero`, `zero`, `=N` (the value is N), `bitN` (bit N of the
    /// written value is set),
    /// `!bitN` (clear), `rising_bitN` (bit N went from 0 to 1 against the previous write).
    #[serde(default = "always")]
    pub when: String,
    /// The engine command's `type` (`enable`, `move_absolute` …); the axis is the block's.
    pub command: String,
    /// Its other fields: numbers, booleans, names, `"value"` (the written value, scaled), or
    /// `"@point"` (the current value of another point of the same block or map; `"-@point"`
    /// negated). A limit
    /// (`velocity`, `acceleration`, `deceleration`, `jerk`) read from a point as 0 is left out,
    /// so the axis parameter applies — except a jog's velocity.
    #[serde(default)]
    pub args: BTreeMap<String, ArgFile>,
}

fn always() -> String {
    "always".into()
}

#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum ArgFile {
    Bool(bool),
    Number(f64),
    Text(String),
}

/// Points repeated for each axis the front-end serves: axis k (k-th of the served axes) at
/// `base + k × stride`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockFile {
    pub table: Table,
    pub base: u16,
    pub stride: u16,
    /// Axes at most (the HIMC reserves 32); the served axes beyond it are not mapped.
    #[serde(default)]
    pub max_axes: Option<u16>,
    pub point: Vec<PointFile>,
}

/// Registers or bits that hold what was written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MemoryFile {
    pub name: String,
    pub table: Table,
    pub start: u16,
    pub count: u16,
    /// Kept across runs in the machine's state directory; flushed on shutdown.
    #[serde(default)]
    pub persist: bool,
}
