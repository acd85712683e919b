//! Data sampling (issue 12 item 9): bounded buffers of chosen variables, recorded every N
//! servo periods once a trigger fires (HMC sampling, digest 000 §4.4, TV 33–34; NMC data
//! collection, digest 001 §3.19, S-COLLECT). The buffer is allocated when the sampler is
//! configured; a tick appends at most one row per sampler and never allocates.

use serde::{Deserialize, Serialize};

use crate::command::{
    SampledVariable, SamplerId, SamplingConfigure, SamplingTrigger, MAX_SAMPLED_VARIABLES,
    MAX_SAMPLERS, MAX_SAMPLE_VALUES,
};
use crate::error::EngineError;

/// Where a sampler is in its run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SamplerState {
    /// Not configured, or configured and not started.
    #[default]
    Idle,
    /// Started, waiting for its trigger.
    Armed,
    /// Recording.
    Collecting,
    /// The buffer is full.
    Done,
    /// Stopped by `sampling_stop` before the buffer was full.
    Stopped,
}

/// A sampler as the snapshot shows it (the data are read with `sampling_read`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SamplerStatus {
    pub sampler: SamplerId,
    pub state: SamplerState,
    pub variables: Vec<SampledVariable>,
    pub interval: u32,
    /// Samples the buffer holds when full.
    pub capacity: u32,
    /// Samples recorded so far (HMC GetSampleNum counts values: `points × variables`).
    pub points: u32,
    /// The tick of the first sample, once triggered (the trigger's tick plus the delay).
    pub triggered_at: Option<u64>,
}

#[derive(Clone, Debug, Default)]
struct Sampler {
    config: Option<SamplingConfigure>,
    state: SamplerState,
    /// Row-major: one row of `variables.len()` values per sample.
    values: Vec<f64>,
    /// The trigger variable's value last tick (edges).
    previous: Option<f64>,
    /// Set by `sampling_trigger` for a `command` trigger.
    fired: bool,
    triggered_at: Option<u64>,
}

/// The engine's samplers.
#[derive(Clone, Debug)]
pub struct Samplers {
    samplers: Vec<Sampler>,
}

impl Default for Samplers {
    fn default() -> Samplers {
        Samplers {
            samplers: vec![Sampler::default(); MAX_SAMPLERS as usize],
        }
    }
}

fn invalid(sampler: SamplerId, reason: impl Into<String>) -> EngineError {
    EngineError::InvalidSampling {
        sampler,
        reason: reason.into(),
    }
}

impl Samplers {
    fn get_mut(&mut self, id: SamplerId) -> Result<&mut Sampler, EngineError> {
        self.samplers.get_mut(id as usize).ok_or_else(|| {
            invalid(
                id,
                format!("no such sampler (samplers are 0 to {})", MAX_SAMPLERS - 1),
            )
        })
    }

    fn get(&self, id: SamplerId) -> Result<&Sampler, EngineError> {
        self.samplers.get(id as usize).ok_or_else(|| {
            invalid(
                id,
                format!("no such sampler (samplers are 0 to {})", MAX_SAMPLERS - 1),
            )
        })
    }

    /// Check and install a configuration; `check` validates each variable against the machine.
    pub fn configure(
        &mut self,
        c: &SamplingConfigure,
        check: impl Fn(&SampledVariable) -> Result<(), EngineError>,
    ) -> Result<(), EngineError> {
        let id = c.sampler;
        self.get(id)?;
        let n = c.variables.len();
        if n == 0 || n > MAX_SAMPLED_VARIABLES {
            return Err(invalid(
                id,
                format!("1 to {MAX_SAMPLED_VARIABLES} variables per sampler, got {n}"),
            ));
        }
        for v in &c.variables {
            check(v)?;
        }
        match c.trigger {
            SamplingTrigger::Immediate | SamplingTrigger::Command => {}
            SamplingTrigger::Rising { variable, value }
            | SamplingTrigger::Falling { variable, value }
            | SamplingTrigger::Above { variable, value }
            | SamplingTrigger::Below { variable, value } => {
                check(&variable)?;
                if !value.is_finite() {
                    return Err(invalid(id, format!("trigger value {value} is not finite")));
                }
            }
        }
        if c.points == 0 {
            return Err(invalid(id, "points must be at least 1"));
        }
        let total = (c.points as usize).saturating_mul(n);
        if total > MAX_SAMPLE_VALUES {
            return Err(invalid(
                id,
                format!(
                    "{} points × {n} variables is more than {MAX_SAMPLE_VALUES} values",
                    c.points
                ),
            ));
        }
        let s = self.get_mut(id)?;
        let mut config = c.clone();
        config.interval = config.interval.max(1);
        s.values = Vec::with_capacity(total);
        s.config = Some(config);
        s.state = SamplerState::Idle;
        s.previous = None;
        s.fired = false;
        s.triggered_at = None;
        Ok(())
    }

    /// Arm: clear the data and wait for the trigger.
    pub fn start(&mut self, id: SamplerId) -> Result<(), EngineError> {
        let s = self.get_mut(id)?;
        if s.config.is_none() {
            return Err(invalid(id, "not configured (sampling_configure first)"));
        }
        s.values.clear();
        s.state = SamplerState::Armed;
        s.previous = None;
        s.fired = false;
        s.triggered_at = None;
        Ok(())
    }

    pub fn trigger(&mut self, id: SamplerId) -> Result<(), EngineError> {
        let s = self.get_mut(id)?;
        if s.state != SamplerState::Armed {
            return Err(invalid(id, "not armed (sampling_start first)"));
        }
        s.fired = true;
        Ok(())
    }

    pub fn stop(&mut self, id: SamplerId) -> Result<(), EngineError> {
        let s = self.get_mut(id)?;
        if matches!(s.state, SamplerState::Armed | SamplerState::Collecting) {
            s.state = SamplerState::Stopped;
        }
        Ok(())
    }

    /// Samples `from .. from + count` (to the end when `count` is None), row-major, and how
    /// many variables a row has.
    pub fn read(
        &self,
        id: SamplerId,
        from: u32,
        count: Option<u32>,
    ) -> Result<(usize, &[f64]), EngineError> {
        let s = self.get(id)?;
        let n = s.config.as_ref().map_or(0, |c| c.variables.len());
        if n == 0 {
            return Err(invalid(id, "not configured"));
        }
        let rows = s.values.len() / n;
        let start = (from as usize).min(rows);
        let end = count.map_or(rows, |c| start.saturating_add(c as usize).min(rows));
        Ok((n, s.values.get(start * n..end * n).unwrap_or(&[])))
    }

    /// Whether any sampler is armed or recording (the engine skips the stage otherwise).
    pub fn active(&self) -> bool {
        self.samplers
            .iter()
            .any(|s| matches!(s.state, SamplerState::Armed | SamplerState::Collecting))
    }

    /// One tick: triggers, then at most one row per recording sampler. `value` reads a variable
    /// as the tick left it.
    pub fn step(&mut self, tick: u64, value: impl Fn(&SampledVariable) -> f64) {
        for s in &mut self.samplers {
            let Some(c) = s.config.as_ref() else {
                continue;
            };
            if s.state == SamplerState::Armed {
                let fire = match c.trigger {
                    SamplingTrigger::Immediate => true,
                    SamplingTrigger::Command => s.fired,
                    SamplingTrigger::Rising { variable, value: v } => {
                        let now = value(&variable);
                        let hit = s.previous.is_some_and(|p| p < v) && now >= v;
                        s.previous = Some(now);
                        hit
                    }
                    SamplingTrigger::Falling { variable, value: v } => {
                        let now = value(&variable);
                        let hit = s.previous.is_some_and(|p| p > v) && now <= v;
                        s.previous = Some(now);
                        hit
                    }
                    SamplingTrigger::Above { variable, value: v } => value(&variable) >= v,
                    SamplingTrigger::Below { variable, value: v } => value(&variable) <= v,
                };
                if fire {
                    s.state = SamplerState::Collecting;
                    // The first sample's tick: `delay` periods after the trigger's.
                    s.triggered_at = Some(tick.saturating_add(u64::from(c.delay)));
                }
            }
            if s.state != SamplerState::Collecting {
                continue;
            }
            let first = s.triggered_at.unwrap_or(tick);
            if tick < first {
                continue;
            }
            let since = tick - first;
            if !since.is_multiple_of(u64::from(c.interval.max(1))) {
                continue;
            }
            // Capacity was reserved at configure time: this never reallocates.
            for v in &c.variables {
                s.values.push(value(v));
            }
            if s.values.len() >= (c.points as usize).saturating_mul(c.variables.len()) {
                s.state = SamplerState::Done;
            }
        }
    }

    /// The configured samplers, for the snapshot (`out` is reused).
    pub fn status_into(&self, out: &mut Vec<SamplerStatus>) {
        let mut k = 0;
        for (i, s) in self.samplers.iter().enumerate() {
            let Some(c) = s.config.as_ref() else {
                continue;
            };
            if out.len() <= k {
                out.push(SamplerStatus::default());
            }
            if let Some(o) = out.get_mut(k) {
                o.sampler = i as SamplerId;
                o.state = s.state;
                o.variables.clone_from(&c.variables);
                o.interval = c.interval;
                o.capacity = c.points;
                o.points = (s.values.len() / c.variables.len().max(1)) as u32;
                o.triggered_at = s.triggered_at;
            }
            k += 1;
        }
        out.truncate(k);
    }
}
