//! Capture channels and position-compare outputs (issue 12 items 4–5): the `Trigger` command
//! family's registry. The engine runs it once per tick after the axes have stepped
//! (`Engine::step` stage 3b), when each axis knows where it was at the start and the end of the
//! tick and when within it each of its signals changed (`axis/latch.rs`); and at once when a
//! command changes a digital input a capture watches.
//!
//! Both are bounded per tick: a capture checks one signal, a compare walks only the positions
//! the tick's motion crossed.

mod capture;
mod compare;
mod z_compare;

use crate::axis::{Axis, TriggerCounts};
use crate::command::{EngineError, Reply, TriggerCommand};
use crate::config::InputBinding;
use crate::status::{CaptureStatus, CompareStatus, ZCompareStatus};
use crate::types::AxisIndex;

use capture::Capture;
use compare::Compare;
use z_compare::ZCompare;
pub use z_compare::Z_COMPARE_CHANNELS;

/// Capture channels per axis (HMC has 8 on the machine, NMC 1 + 4 advanced, HIMC 2 touch
/// probes per axis).
pub const CAPTURE_CHANNELS: u8 = 8;
/// Compare channels on the machine (HMC NormalSwitch 0–7; NMC 2 modules).
pub const COMPARE_CHANNELS: u8 = 8;
/// Most positions one compare channel takes (NMC takes 32 896 per call).
pub const MAX_COMPARE_POSITIONS: usize = 65_536;
/// Most edges a repeated capture keeps (NMC `REPEAT_CAPT_MAX_NUM`, digest 001 §2.18).
pub const MAX_CAPTURE_REPEAT: u16 = 64;

/// What the engine lends the triggers for one tick or one command.
pub(crate) struct Env<'a> {
    /// The tick that just ran (a command: the tick whose end the machine stands at).
    pub tick: u64,
    pub period: f64,
    pub axes: &'a mut [Axis],
    /// Digital inputs forced by command: they change only by command, at the tick boundary.
    pub di_forced: &'a [Option<bool>],
    pub bindings: &'a [InputBinding],
    pub outputs: &'a mut [bool],
    pub outputs_changed: bool,
}

impl Env<'_> {
    fn axis(&self, axis: AxisIndex) -> Result<&Axis, EngineError> {
        let count = self.axes.len() as u32;
        self.axes
            .get(axis as usize)
            .ok_or(EngineError::InvalidAxis {
                axis: u32::from(axis),
                count,
            })
    }

    fn write_output(&mut self, channel: u16, value: bool) {
        if let Some(o) = self.outputs.get_mut(channel as usize) {
            if *o != value {
                *o = value;
                self.outputs_changed = true;
            }
        }
    }
}

/// The capture and compare channels of the machine.
#[derive(Clone, Debug, Default)]
pub struct Triggers {
    /// By axis, then channel.
    captures: Vec<Capture>,
    /// By channel.
    compares: Vec<Compare>,
    /// Z-phase compares (HMC SwitchTZ), by channel.
    z_compares: Vec<ZCompare>,
}

impl Triggers {
    pub(crate) fn apply(
        &mut self,
        env: &mut Env,
        command: TriggerCommand,
    ) -> Result<Reply, EngineError> {
        match command {
            TriggerCommand::CaptureArm(c) => {
                let capture = Capture::arm(env, &c)?;
                self.put_capture(env, capture);
            }
            TriggerCommand::CaptureArmThreshold(c) => {
                let capture = Capture::arm_threshold(env, &c)?;
                self.put_capture(env, capture);
            }
            TriggerCommand::CaptureClear(c) => {
                env.axis(c.axis)?;
                channel_in_range("capture", c.channel, CAPTURE_CHANNELS)?;
                self.captures.retain(|k| k.key() != (c.axis, c.channel));
                self.refresh_counts(env, c.axis);
            }
            TriggerCommand::CompareStart(c) => {
                let compare = Compare::start(env, &c)?;
                self.stop_compare(env, c.channel);
                let i = self.compares.partition_point(|k| k.channel() < c.channel);
                self.compares.insert(i, compare);
            }
            TriggerCommand::CompareStop(c) => {
                channel_in_range("compare", c.channel, COMPARE_CHANNELS)?;
                self.stop_compare(env, c.channel);
            }
            TriggerCommand::CompareFire(c) => {
                channel_in_range("compare", c.channel, COMPARE_CHANNELS)?;
                let compare = self
                    .compares
                    .iter_mut()
                    .find(|k| k.channel() == c.channel)
                    .ok_or_else(|| invalid("compare", c.channel, "not started"))?;
                compare.fire_now(env);
                let axis = compare.status().axis;
                self.refresh_counts(env, axis);
            }
            TriggerCommand::ZCompareStart(c) => {
                let others = self.z_compares.iter().filter(|k| k.channel() != c.channel);
                let z = ZCompare::start(env, &c, others)?;
                self.stop_z_compare(env, c.channel);
                let i = self.z_compares.partition_point(|k| k.channel() < c.channel);
                self.z_compares.insert(i, z);
            }
            TriggerCommand::ZCompareStop(c) => {
                channel_in_range("z_compare", c.channel, Z_COMPARE_CHANNELS)?;
                self.stop_z_compare(env, c.channel);
            }
        }
        Ok(Reply::Done)
    }

    /// Arm `capture`, replacing the channel's arm.
    fn put_capture(&mut self, env: &mut Env, capture: Capture) {
        let key = capture.key();
        match self.captures.binary_search_by_key(&key, Capture::key) {
            Ok(i) => {
                if let Some(slot) = self.captures.get_mut(i) {
                    *slot = capture;
                }
            }
            Err(i) => self.captures.insert(i, capture),
        }
        self.refresh_counts(env, key.0);
    }

    fn stop_compare(&mut self, env: &mut Env, channel: u8) {
        if let Some(i) = self.compares.iter().position(|k| k.channel() == channel) {
            let compare = self.compares.remove(i);
            let axis = compare.status().axis;
            compare.stop(env);
            self.refresh_counts(env, axis);
        }
    }

    fn stop_z_compare(&mut self, env: &mut Env, channel: u8) {
        if let Some(i) = self.z_compares.iter().position(|k| k.channel() == channel) {
            self.z_compares.remove(i).stop(env);
        }
    }

    /// What the axis's status shows of its channels: latches (> 0 is NMC `BIT_AXIS_CAPTSET`),
    /// the newest latch's actual position, and the outputs its compare channels fired.
    fn refresh_counts(&self, env: &mut Env, axis: AxisIndex) {
        let mut counts = TriggerCounts::default();
        let mut newest = None;
        for c in self.captures.iter().map(Capture::status) {
            if c.axis != axis {
                continue;
            }
            counts.captures = counts.captures.saturating_add(c.count);
            if let Some(l) = c.latches.last() {
                if newest.is_none_or(|t| l.tick >= t) {
                    newest = Some(l.tick);
                    counts.capture_position = l.act_pos;
                }
            }
        }
        counts.compare_outputs = self
            .compares
            .iter()
            .map(Compare::status)
            .filter(|c| c.axis == axis)
            .fold(0u32, |n, c| n.saturating_add(c.count));
        if let Some(a) = env.axes.get_mut(axis as usize) {
            a.set_trigger_counts(counts);
        }
    }

    /// After the axes stepped: latch the edges of this tick, then fire the compare outputs.
    pub(crate) fn step(&mut self, env: &mut Env) {
        for i in 0..self.captures.len() {
            let latched = self.captures.get_mut(i).is_some_and(|c| c.step(env));
            if latched {
                if let Some(axis) = self.captures.get(i).map(|c| c.key().0) {
                    self.refresh_counts(env, axis);
                }
            }
        }
        for i in 0..self.compares.len() {
            let fired = self.compares.get_mut(i).is_some_and(|c| c.step(env));
            if fired {
                if let Some(axis) = self.compares.get(i).map(|c| c.status().axis) {
                    self.refresh_counts(env, axis);
                }
            }
        }
        for z in &mut self.z_compares {
            z.step(env);
        }
    }

    /// A command changed digital input `channel` to `level`: the edge happens at the tick
    /// boundary, where the machine stands.
    pub(crate) fn input_changed(&mut self, env: &mut Env, channel: u16, level: bool) {
        for i in 0..self.captures.len() {
            let latched = self
                .captures
                .get_mut(i)
                .is_some_and(|c| c.input_changed(env, channel, level));
            if latched {
                if let Some(axis) = self.captures.get(i).map(|c| c.key().0) {
                    self.refresh_counts(env, axis);
                }
            }
        }
    }

    /// Whether any capture watches a digital input (the engine then looks for command edges).
    pub(crate) fn watches_inputs(&self) -> bool {
        self.captures.iter().any(Capture::watches_input)
    }

    /// The capture channels' records, by axis and channel.
    pub fn captures(&self) -> impl Iterator<Item = &CaptureStatus> {
        self.captures.iter().map(Capture::status)
    }

    /// Channel `channel` of `axis`, if armed (or done).
    pub fn capture(&self, axis: AxisIndex, channel: u8) -> Option<&CaptureStatus> {
        self.captures
            .binary_search_by_key(&(axis, channel), Capture::key)
            .ok()
            .and_then(|i| self.captures.get(i))
            .map(Capture::status)
    }

    /// The compare channels' records, by channel.
    pub fn compares(&self) -> impl Iterator<Item = &CompareStatus> {
        self.compares.iter().map(Compare::status)
    }

    pub fn compare(&self, channel: u8) -> Option<&CompareStatus> {
        self.compares().find(|c| c.channel == channel)
    }

    /// The Z-phase compare channels' records, by channel.
    pub fn z_compares(&self) -> impl Iterator<Item = &ZCompareStatus> {
        self.z_compares.iter().map(ZCompare::status)
    }

    /// Copy the records into a snapshot's lists, reusing their allocations.
    pub(crate) fn status_into(
        &self,
        captures: &mut Vec<CaptureStatus>,
        compares: &mut Vec<CompareStatus>,
        z_compares: &mut Vec<ZCompareStatus>,
    ) {
        z_compares.clear();
        z_compares.extend(self.z_compares().cloned());
        captures.truncate(self.captures.len());
        for (i, c) in self.captures.iter().enumerate() {
            match captures.get_mut(i) {
                Some(out) => out.clone_from(c.status()),
                None => captures.push(c.status().clone()),
            }
        }
        compares.clear();
        compares.extend(self.compares.iter().map(|c| c.status().clone()));
    }
}

fn channel_in_range(trigger: &'static str, channel: u8, count: u8) -> Result<(), EngineError> {
    if channel < count {
        Ok(())
    } else {
        Err(EngineError::InvalidTrigger {
            trigger,
            channel,
            reason: format!("channels are 0 to {}", count - 1),
        })
    }
}

fn invalid(trigger: &'static str, channel: u8, reason: impl Into<String>) -> EngineError {
    EngineError::InvalidTrigger {
        trigger,
        channel,
        reason: reason.into(),
    }
}
