//! Declarative register maps (`fixtures/modbus/*.toml`): the file format, its compiler and the
//! value codec.

pub mod compile;
pub mod schema;
pub mod service;
pub mod source;
pub mod value;

use std::fmt;

pub use compile::{compile, Binding, CompileError, UnitMap};
pub use schema::MapFile;
pub use service::{MapModel, UnitService};
pub use source::MachineShape;

/// The maps shipped in `fixtures/modbus/`, embedded so a config can name them without the
/// fixtures directory: `map = "himc"`.
pub const SHIPPED: &[(&str, &str)] = &[
    (
        "generic",
        include_str!("../../../../fixtures/modbus/generic.toml"),
    ),
    (
        "ct-e10-servo",
        include_str!("../../../../fixtures/modbus/ct-e10-servo.toml"),
    ),
    (
        "himc",
        include_str!("../../../../fixtures/modbus/himc.toml"),
    ),
    (
        "hollysys-mc",
        include_str!("../../../../fixtures/modbus/hollysys-mc.toml"),
    ),
];

/// A map file that cannot be used: which file, which key, why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MapError {
    pub file: String,
    /// Key path inside the map file; empty for the file as a whole.
    pub key: String,
    pub reason: String,
}

impl fmt::Display for MapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.key.is_empty() {
            write!(f, "{}: {}", self.file, self.reason)
        } else {
            write!(f, "{}: {}: {}", self.file, self.key, self.reason)
        }
    }
}

impl std::error::Error for MapError {}

/// Read a map file's text; `file` names it in errors.
pub fn parse(text: &str, file: &str) -> Result<MapFile, MapError> {
    let error = |key: String, reason: String| MapError {
        file: file.to_string(),
        key,
        reason,
    };
    let deserializer = toml::Deserializer::parse(text)
        .map_err(|e| error(String::new(), e.to_string().trim_end().to_string()))?;
    serde_path_to_error::deserialize(deserializer).map_err(|e| {
        let key = match e.path().to_string() {
            p if p == "." => String::new(),
            p => p,
        };
        error(key, e.inner().to_string().trim_end().to_string())
    })
}

/// Parse and compile in one step, errors naming `file`.
pub fn load(
    text: &str,
    file: &str,
    machine: &MachineShape,
    binding: &Binding,
) -> Result<UnitMap, MapError> {
    let map = parse(text, file)?;
    compile(&map, machine, binding).map_err(|e| MapError {
        file: file.to_string(),
        key: e.key,
        reason: e.reason,
    })
}

/// The text of a shipped map by name.
pub fn shipped(name: &str) -> Option<&'static str> {
    SHIPPED.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::schema::*;
    use super::value::{PointType, WordOrder};

    #[test]
    fn the_file_format_reads_as_documented() {
        let text = r#"
[map]
name = "example"
word_order = "cdab"

[identity]
vendor_name = "mcemu"
server_id = [77, 1]

[[point]]
table = "holding_registers"
address = 8208
name = "controller_status"
read = "machine.error"
values = { "0" = 2, "1" = 4 }

[[block]]
table = "holding_registers"
base = 0
stride = 100
[[block.point]]
offset = 0
name = "motion_status"
type = "u32"
read = { bits = { 0 = "enabled", 1 = "moving" } }
[[block.point]]
offset = 30
name = "enable"
read = { bits = { 0 = "enabled" } }
on_write = [
  { when = "bit0", command = "enable" },
  { when = "!bit0", command = "disable" },
]
[[block.point]]
offset = 44
name = "start"
write = "memory"
on_write = [{ when = "nonzero", command = "move_absolute", args = { position = "@target", velocity = 10.5 } }]

[[memory]]
name = "user_table"
table = "holding_registers"
start = 8704
count = 256
persist = true
"#;
        let file: MapFile = toml::from_str(text).unwrap();
        assert_eq!(file.map.word_order, WordOrder::Cdab);
        assert_eq!(file.identity.server_id, [77, 1]);
        assert_eq!(file.point[0].values["1"], 4.0);
        let block = &file.block[0];
        assert_eq!(block.point[0].ty, Some(PointType::U32));
        assert!(
            matches!(&block.point[0].read, Some(ReadFile::Bits { bits }) if bits["1"] == "moving")
        );
        assert_eq!(block.point[1].on_write[1].when, "!bit0");
        assert!(matches!(
            block.point[2].on_write[0].args["position"],
            ArgFile::Text(ref t) if t == "@target"
        ));
        assert!(file.memory[0].persist);
        let e =
            toml::from_str::<MapFile>("[map]\nname = \"x\"\nwordorder = \"abcd\"\n").unwrap_err();
        assert!(e.to_string().contains("unknown field `wordorder`"), "{e}");
    }
}
