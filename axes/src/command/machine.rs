//! The machine family: commands about the whole machine rather than one axis, group or slave.

use serde::{Deserialize, Serialize};

use super::{command_from, CommandId};

/// State of a command by id. Ids are engine-wide, so the query is too. JSON `type`:
/// `command_state`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GetCommandState {
    pub id: CommandId,
}

/// A machine-wide command.
#[derive(Clone, Debug, PartialEq)]
pub enum MachineCommand {
    CommandState(GetCommandState),
}

command_from!(MachineCommand, Machine, [GetCommandState => CommandState]);
