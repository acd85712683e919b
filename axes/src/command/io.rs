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

/// An axis variable an analog output can follow (`bind_analog_output`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AnalogSource {
    /// The commanded position, velocity, acceleration (after smoothing and filters).
    CmdPos,
    CmdVel,
    CmdAcc,
    /// The actual position and velocity, and the actual velocity's change per second.
    ActPos,
    ActVel,
    ActAcc,
    /// The drive's torque, a fraction of rated torque.
    Torque,
}

/// Bind analog output `channel` to `source` of `axis`: every tick, once the axes have
/// stepped, the output is `source × scale + offset`, held within `min` … `max` where given (a
/// converter's range) (HIMC SetSlvAOMonitor with SetSlvAOParam `ao_en_bind` 1, digest 004
/// §10.4). Without `axis` the binding is released and the output keeps its last value. A
/// `write_analog_output` to a bound channel lasts until the next tick.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BindAnalogOutput {
    pub channel: u16,
    #[serde(default)]
    pub axis: Option<u16>,
    #[serde(default = "default_source")]
    pub source: AnalogSource,
    #[serde(default = "one")]
    pub scale: f64,
    #[serde(default)]
    pub offset: f64,
    #[serde(default)]
    pub min: Option<f64>,
    #[serde(default)]
    pub max: Option<f64>,
}

fn default_source() -> AnalogSource {
    AnalogSource::CmdPos
}

fn one() -> f64 {
    1.0
}

/// A command on the machine's I/O image; it takes effect at once, between ticks.
#[derive(Clone, Debug, PartialEq)]
pub enum IoCommand {
    ForceDigitalInput(ForceDigitalInput),
    ForceAnalogInput(ForceAnalogInput),
    WriteDigitalOutput(WriteDigitalOutput),
    WriteAnalogOutput(WriteAnalogOutput),
    PulseDigitalOutput(PulseDigitalOutput),
    BindAnalogOutput(BindAnalogOutput),
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
        BindAnalogOutput => BindAnalogOutput,
    ]
);
