//! The engine's side of data sampling (issue 12 item 9): the commands, and stage 5, which
//! records after the axes and drives have stepped.

use super::Engine;
use crate::command::{
    EngineError, Reply, SampledVariable, SamplingCommand, SamplingConfigure, SamplingRead,
    SamplingStart, SamplingStop, SamplingTriggerNow,
};

impl Engine {
    pub(super) fn apply_sampling_command(
        &mut self,
        command: SamplingCommand,
    ) -> Result<Reply, EngineError> {
        match command {
            SamplingCommand::Configure(c) => self.configure_sampler(&c)?,
            SamplingCommand::Start(SamplingStart { sampler }) => self.samplers.start(sampler)?,
            SamplingCommand::Trigger(SamplingTriggerNow { sampler }) => {
                self.samplers.trigger(sampler)?
            }
            SamplingCommand::Stop(SamplingStop { sampler }) => self.samplers.stop(sampler)?,
            SamplingCommand::Read(SamplingRead {
                sampler,
                from,
                count,
            }) => {
                let (variables, values) = self.samplers.read(sampler, from, count)?;
                return Ok(Reply::Samples {
                    sampler,
                    from,
                    variables: variables as u32,
                    values: values.to_vec(),
                });
            }
        }
        Ok(Reply::Done)
    }

    fn configure_sampler(&mut self, c: &SamplingConfigure) -> Result<(), EngineError> {
        let axes = self.axes.len() as u32;
        let di = self.io.image.di.len() as u16;
        let do_ = self.io.image.do_.len() as u16;
        self.samplers.configure(c, |v| match *v {
            SampledVariable::DigitalInput { channel } if channel >= di => {
                Err(EngineError::InvalidChannel {
                    kind: "digital inputs",
                    channel,
                    count: di,
                })
            }
            SampledVariable::DigitalOutput { channel } if channel >= do_ => {
                Err(EngineError::InvalidChannel {
                    kind: "digital outputs",
                    channel,
                    count: do_,
                })
            }
            SampledVariable::GroupCoordinate { group, coordinate } => {
                let g = self
                    .groups
                    .get(group)
                    .ok_or(EngineError::UnknownGroup { group })?;
                if usize::from(coordinate) >= g.members().len() {
                    return Err(EngineError::InvalidGroup {
                        group,
                        reason: format!(
                            "coordinate {coordinate}: the group has {} coordinates",
                            g.members().len()
                        ),
                    });
                }
                Ok(())
            }
            SampledVariable::GroupVelocity { group } => self
                .groups
                .get(group)
                .map(|_| ())
                .ok_or(EngineError::UnknownGroup { group }),
            _ => match v.axis() {
                Some(axis) if u32::from(axis) >= axes => Err(EngineError::InvalidAxis {
                    axis: u32::from(axis),
                    count: axes,
                }),
                _ => Ok(()),
            },
        })
    }

    /// Stage 5: every armed or recording sampler reads the machine as this tick left it.
    pub(super) fn sample(&mut self) {
        if !self.samplers.active() {
            return;
        }
        let Engine {
            axes,
            io,
            groups,
            samplers,
            tick,
            ..
        } = self;
        samplers.step(*tick, |v| match *v {
            SampledVariable::DigitalInput { channel } => bit(&io.image.di, channel),
            SampledVariable::DigitalOutput { channel } => bit(&io.image.do_, channel),
            SampledVariable::GroupCoordinate { group, coordinate } => groups
                .get(group)
                .map_or(0.0, |g| g.sampled_coordinate(axes, coordinate)),
            SampledVariable::GroupVelocity { group } => {
                groups.get(group).map_or(0.0, |g| g.path_velocity())
            }
            _ => v
                .axis()
                .and_then(|axis| axes.get(axis as usize))
                .map_or(0.0, |a| a.sampled(v)),
        });
    }
}

fn bit(bits: &[bool], channel: u16) -> f64 {
    f64::from(u8::from(
        bits.get(channel as usize).copied().unwrap_or(false),
    ))
}
