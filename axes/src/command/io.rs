//! The I/O family: the machine's digital and analog I/O image.

use serde::{Deserialize, Serialize};

use super::command_from;

/// Force a digital input channel, or release it (`value` absent).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceDigitalInput {
    pub channel: u16,
    #[serde(default)]
    pub value: Option<bool>,
}

/// Set an analog input channel, or release it (`value` absent).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceAnalogInput {
    pub channel: u16,
    #[serde(default)]
    pub value: Option<f64>,
}

/// Set a digital output channel.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WriteDigitalOutput {
    pub channel: u16,
    pub value: bool,
}

/// Set an analog output channel.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WriteAnalogOutput {
    pub channel: u16,
    pub value: f64,
}

/// A command on the machine's I/O image; it takes effect at once, between ticks.
#[derive(Clone, Debug, PartialEq)]
pub enum IoCommand {
    ForceDigitalInput(ForceDigitalInput),
    ForceAnalogInput(ForceAnalogInput),
    WriteDigitalOutput(WriteDigitalOutput),
    WriteAnalogOutput(WriteAnalogOutput),
}

command_from!(
    IoCommand,
    Io,
    [
        ForceDigitalInput => ForceDigitalInput,
        ForceAnalogInput => ForceAnalogInput,
        WriteDigitalOutput => WriteDigitalOutput,
        WriteAnalogOutput => WriteAnalogOutput,
    ]
);
