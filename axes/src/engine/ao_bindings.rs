//! Analog outputs that follow an axis variable every tick (`bind_analog_output`; issue 14,
//! HIMC SetSlvAOMonitor with SetSlvAOParam `ao_en_bind` 1, digest 004 §10.4: "AO = variable ×
//! scale + offset"). Written after the axes step (stage 3b), so an output shows this tick's
//! value; a `write_analog_output` to a bound channel lasts until then.

use crate::axis::Axis;
use crate::command::{AnalogSource, BindAnalogOutput, EngineError};

#[derive(Clone, Debug, PartialEq)]
struct Binding {
    channel: u16,
    axis: u16,
    source: AnalogSource,
    scale: f64,
    offset: f64,
    min: f64,
    max: f64,
    /// The axis's actual velocity last tick (`act_acc` is its change per second).
    last_velocity: f64,
}

/// The bound analog outputs, at most one binding per channel.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct AoBindings {
    bindings: Vec<Binding>,
}

impl AoBindings {
    /// Bind `c.channel` to `c.source` of `c.axis` (replacing its binding), or release it
    /// without an axis. The channel and the axis exist; scale and offset are finite.
    pub(super) fn bind(
        &mut self,
        c: &BindAnalogOutput,
        outputs: usize,
        axes: &[Axis],
    ) -> Result<(), EngineError> {
        if usize::from(c.channel) >= outputs {
            return Err(EngineError::InvalidChannel {
                kind: "analog outputs",
                channel: c.channel,
                count: outputs as u16,
            });
        }
        for (name, value) in [("scale", c.scale), ("offset", c.offset)] {
            if !value.is_finite() {
                return Err(EngineError::InvalidArgument {
                    name,
                    value,
                    reason: "must be finite",
                });
            }
        }
        let (min, max) = (
            c.min.unwrap_or(f64::NEG_INFINITY),
            c.max.unwrap_or(f64::INFINITY),
        );
        if min.is_nan() || max.is_nan() || min > max {
            return Err(EngineError::InvalidArgument {
                name: "min",
                value: min,
                reason: "must be a number at most max",
            });
        }
        self.bindings.retain(|b| b.channel != c.channel);
        let Some(axis) = c.axis else {
            return Ok(());
        };
        let a = axes
            .get(usize::from(axis))
            .ok_or(EngineError::InvalidAxis {
                axis: u32::from(axis),
                count: axes.len() as u32,
            })?;
        self.bindings.push(Binding {
            channel: c.channel,
            axis,
            source: c.source,
            scale: c.scale,
            offset: c.offset,
            min,
            max,
            last_velocity: a.actual_velocity(),
        });
        Ok(())
    }

    /// Write every bound output from the axes as they stand; whether one changed.
    pub(super) fn step(&mut self, axes: &[Axis], period: f64, outputs: &mut [f64]) -> bool {
        let mut changed = false;
        for b in &mut self.bindings {
            let (Some(axis), Some(out)) = (
                axes.get(usize::from(b.axis)),
                outputs.get_mut(usize::from(b.channel)),
            ) else {
                continue;
            };
            let velocity = axis.actual_velocity();
            let cmd = axis.commanded_output();
            let value = match b.source {
                AnalogSource::CmdPos => cmd.p,
                AnalogSource::CmdVel => cmd.v,
                AnalogSource::CmdAcc => cmd.a,
                AnalogSource::ActPos => axis.actual_position_shown(),
                AnalogSource::ActVel => velocity,
                AnalogSource::ActAcc => (velocity - b.last_velocity) / period,
                AnalogSource::Torque => axis.torque(),
            };
            b.last_velocity = velocity;
            let value = (value * b.scale + b.offset).clamp(b.min, b.max);
            if *out != value {
                *out = value;
                changed = true;
            }
        }
        changed
    }

    pub(super) fn is_empty(&self) -> bool {
        self.bindings.is_empty()
    }
}
