//! Data sampling commands (issue 12 item 9): chosen variables copied into a bounded buffer
//! every N servo periods once a trigger fires (HMC SetSampleVar/SetSamplePara/TriggerSample,
//! digest 000 §4.4, TV 33–34; NMC ConfigCollect/CollectOnOff/GetCollectData, digest 001 §2.20,
//! §3.19, S-COLLECT). Front-ends read the data with `sampling_read` and the state in the
//! snapshot's `samplers`.

use serde::{Deserialize, Serialize};

use super::{command_from, AxisIndex, GroupId};

/// A sampler's number: 0 … [`MAX_SAMPLERS`]−1 (HMC MC1008: four sample channels).
pub type SamplerId = u16;

/// Samplers the engine has (HMC MC1008/MC1004: 4 sample channels).
pub const MAX_SAMPLERS: u16 = 4;
/// Variables one sampler records (HMC: 4 sub-channels; NMC COLLECT_LIST_MAX is larger).
pub const MAX_SAMPLED_VARIABLES: usize = 8;
/// Values (points × variables) one sampler may hold: 8 MB of f64.
pub const MAX_SAMPLE_VALUES: usize = 1_000_000;

/// One variable a sampler records each sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum SampledVariable {
    /// The planned position, before compensation (NMC COLLECT_ADDRESS_PRF_POS).
    PlannedPosition {
        axis: AxisIndex,
    },
    /// The planned velocity (NMC CMD_VEL).
    PlannedVelocity {
        axis: AxisIndex,
    },
    /// The actual position (NMC AXIS_POS / ENC_POS, HMC MPos).
    ActualPosition {
        axis: AxisIndex,
    },
    /// The actual velocity (NMC ENC_VEL).
    ActualVelocity {
        axis: AxisIndex,
    },
    FollowingError {
        axis: AxisIndex,
    },
    /// The position sent to the drive, compensation included (NMC CMD_POS).
    OutputPosition {
        axis: AxisIndex,
    },
    /// One digital input of the machine image, 0 or 1 (NMC COLLECT_ADDRESS_DI).
    DigitalInput {
        channel: u16,
    },
    /// One digital output, 0 or 1 (NMC COLLECT_ADDRESS_DO).
    DigitalOutput {
        channel: u16,
    },
    /// Coordinate `coordinate` (0 the first member) of a group's commanded position, origin
    /// offset taken off (NMC COLLECT_ADDRESS_CRD_POS0 / CRD_POS1).
    GroupCoordinate {
        group: GroupId,
        coordinate: u8,
    },
    /// A group's commanded velocity along its path (NMC COLLECT_ADDRESS_CRD_VEL0 / CRD_VEL1).
    GroupVelocity {
        group: GroupId,
    },
}

impl SampledVariable {
    /// The axis it reads, if it is an axis quantity.
    pub fn axis(&self) -> Option<AxisIndex> {
        match *self {
            SampledVariable::PlannedPosition { axis }
            | SampledVariable::PlannedVelocity { axis }
            | SampledVariable::ActualPosition { axis }
            | SampledVariable::ActualVelocity { axis }
            | SampledVariable::FollowingError { axis }
            | SampledVariable::OutputPosition { axis } => Some(axis),
            SampledVariable::DigitalInput { .. }
            | SampledVariable::DigitalOutput { .. }
            | SampledVariable::GroupCoordinate { .. }
            | SampledVariable::GroupVelocity { .. } => None,
        }
    }

    /// The group it reads, if it is a group quantity.
    pub fn group(&self) -> Option<GroupId> {
        match *self {
            SampledVariable::GroupCoordinate { group, .. }
            | SampledVariable::GroupVelocity { group } => Some(group),
            _ => None,
        }
    }
}

/// When a started sampler begins to record.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum SamplingTrigger {
    /// At the first tick after `sampling_start` (NMC COLLECT_MODE_NONE).
    #[default]
    Immediate,
    /// At the first tick after `sampling_trigger` (HMC TriggerSample).
    Command,
    /// When `variable` goes from below `value` to at or above it.
    Rising {
        variable: SampledVariable,
        value: f64,
    },
    /// When `variable` goes from above `value` to at or below it.
    Falling {
        variable: SampledVariable,
        value: f64,
    },
    /// At the first tick `variable` ≥ `value` (a level).
    Above {
        variable: SampledVariable,
        value: f64,
    },
    /// At the first tick `variable` ≤ `value`.
    Below {
        variable: SampledVariable,
        value: f64,
    },
}

/// Set a sampler up (it stops and its data are cleared): HMC SetSampleVar + SetSamplePara,
/// NMC ConfigCollect.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SamplingConfigure {
    pub sampler: SamplerId,
    /// 1 … [`MAX_SAMPLED_VARIABLES`] variables, recorded in this order in each sample.
    pub variables: Vec<SampledVariable>,
    /// Servo periods between samples, ≥ 1 (HMC uiTime; NMC interval 0 means every period, so
    /// 0 reads as 1 here too).
    #[serde(default = "one")]
    pub interval: u32,
    /// Samples to record; the sampler is done when the buffer is full (HMC uiNum).
    pub points: u32,
    #[serde(default)]
    pub trigger: SamplingTrigger,
    /// Servo periods from the trigger to the first sample (NMC TCollectTrig startDelay); 0:
    /// the first sample is taken on the trigger's tick.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub delay: u32,
}

fn is_zero(n: &u32) -> bool {
    *n == 0
}

fn one() -> u32 {
    1
}

/// Arm a configured sampler (NMC CollectOnOff 1): it waits for its trigger, then records.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SamplingStart {
    pub sampler: SamplerId,
}

/// Fire a `command` trigger (HMC TriggerSample).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SamplingTriggerNow {
    pub sampler: SamplerId,
}

/// Stop recording; the data stay readable (NMC CollectOnOff 0, HMC DisableSample).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SamplingStop {
    pub sampler: SamplerId,
}

/// Read recorded samples `from` … `from + count` (all from `from` when `count` is absent). The
/// reply is [`super::Reply::Samples`]: the values row by row, one row per sample, the variables
/// in their configured order (HMC TV 34: sub-channel i of sample n is value n·k + i).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SamplingRead {
    pub sampler: SamplerId,
    #[serde(default)]
    pub from: u32,
    #[serde(default)]
    pub count: Option<u32>,
}

/// The sampling family.
#[derive(Clone, Debug, PartialEq)]
pub enum SamplingCommand {
    Configure(SamplingConfigure),
    Start(SamplingStart),
    Trigger(SamplingTriggerNow),
    Stop(SamplingStop),
    Read(SamplingRead),
}

command_from!(
    SamplingCommand,
    Sampling,
    [
        SamplingConfigure => Configure,
        SamplingStart => Start,
        SamplingTriggerNow => Trigger,
        SamplingStop => Stop,
        SamplingRead => Read,
    ]
);
