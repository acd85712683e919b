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

/// Write digital output `channel` to `level` now, then toggle it `toggles` times on the
/// virtual clock: `level` holds `level_time` s, the opposite level `other_time` s, and so on
/// (whole ticks, at least one). `toggles` 0 ends the channel's running train and writes
/// nothing (the output stays where the train left it); `u32::MAX` toggles forever. A `write_digital_output` to the channel does not end it (NMC
/// SetDOBitAutoReverse, DoBitPulseEnable / Disable, digest 001 §2.8). JSON `type`:
/// `pulse_digital_output`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PulseDigitalOutput {
    pub channel: u16,
    pub level: bool,
    pub level_time: f64,
    pub other_time: f64,
    pub toggles: u32,
}

/// A command on the machine's I/O image; it takes effect at once, between ticks.
#[derive(Clone, Debug, PartialEq)]
pub enum IoCommand {
    ForceDigitalInput(ForceDigitalInput),
    ForceAnalogInput(ForceAnalogInput),
    WriteDigitalOutput(WriteDigitalOutput),
    WriteAnalogOutput(WriteAnalogOutput),
    PulseDigitalOutput(PulseDigitalOutput),
}

command_from!(
    IoCommand,
    Io,
    [
        ForceDigitalInput => ForceDigitalInput,
        ForceAnalogInput => ForceAnalogInput,
        WriteDigitalOutput => WriteDigitalOutput,
        WriteAnalogOutput => WriteAnalogOutput,
        PulseDigitalOutput => PulseDigitalOutput,
    ]
);
