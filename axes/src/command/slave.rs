//! The slave family: the object dictionaries of the CiA 402 drives on the engine's fieldbus.

use serde::{Deserialize, Serialize};

use super::command_from;
use crate::od::Value;

/// Read an object of a slave's object dictionary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReadObject {
    pub slave: u16,
    pub index: u16,
    pub subindex: u8,
}

/// Write an object of a slave's object dictionary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WriteObject {
    pub slave: u16,
    pub index: u16,
    pub subindex: u8,
    pub value: Value,
}

/// A command on one drive's object dictionary (slave numbers from 0, as in the config).
#[derive(Clone, Debug, PartialEq)]
pub enum SlaveCommand {
    ReadObject(ReadObject),
    WriteObject(WriteObject),
}

command_from!(
    SlaveCommand,
    Slave,
    [ReadObject => ReadObject, WriteObject => WriteObject]
);
