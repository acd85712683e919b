//! One Z-phase compare channel (HMC `HMC_SwitchTZConfig`, manual §4.4.3.4–4.4.3.8, digest 000
//! §4.4; HMC `HMC_SwitchConfig` ucOutputMode 1): positions of a trigger axis in order, each
//! driving the Z-phase output of an output axis when passed.
//!
//! A position is passed as by a 1-D compare ([`super::compare::passed_1d`]: "the first sample
//! past the target", digest 000 §4.4). The output is not a DO of the I/O image but the output
//! axis's own Z line (`AxisStatus::z_output`). Toggle mode (ucTimeMode 0) toggles at each
//! position, to `level` at the first. Pulse mode (ucTimeMode 1) holds `level` for `pulse_width`
//! seconds from the moment of the crossing, found within the tick from the straight travel (the
//! FPGA outputs "at" the position, not at the next servo tick), so a pulse may be far shorter
//! than a period: the status shows it high at the end of every tick it overlaps. A position
//! crossed while a pulse is on is not answered (note 5: "S1 − S0 > V·T, otherwise the module
//! does not respond"): it is `missed`, and the channel goes on to the next.

use super::compare::passed_1d;
use super::{channel_in_range, invalid, Env, MAX_COMPARE_POSITIONS};
use crate::command::{bounded, positive, EngineError, ZCompareStart};
use crate::status::{CompareOutputMode, CompareState, ZCompareStatus};

/// Z-phase compare channels on the machine (HMC MC1008: SwitchTZ 0–1 and Switch 0–3 with a
/// Z-phase output; a front-end maps its numbering onto these).
pub const Z_COMPARE_CHANNELS: u8 = 8;

#[derive(Clone, Debug)]
pub(super) struct ZCompare {
    status: ZCompareStatus,
    positions: Vec<f64>,
    level: bool,
    /// Seconds (pulse mode).
    pulse_width: f64,
    /// When the current pulse ends, seconds of engine time.
    pulse_end: Option<f64>,
    /// The level the next toggle writes.
    toggle_level: bool,
}

impl ZCompare {
    /// A channel started as `c` asks, or why it cannot be. `others`: the channels running,
    /// this one's old self excepted (an output axis takes one channel). In pulse mode the
    /// output goes to its idle level at once.
    pub(super) fn start<'a>(
        env: &mut Env,
        c: &ZCompareStart,
        mut others: impl Iterator<Item = &'a ZCompare>,
    ) -> Result<ZCompare, EngineError> {
        let channel = c.channel;
        channel_in_range("z_compare", channel, Z_COMPARE_CHANNELS)?;
        env.axis(c.axis)?;
        env.axis(c.output_axis)?;
        if others.any(|o| o.status.output_axis == c.output_axis) {
            // HMC 1553: "Z output already used".
            return Err(invalid(
                "z_compare",
                channel,
                format!(
                    "the Z-phase output of axis {} is driven by another channel",
                    c.output_axis
                ),
            ));
        }
        if c.positions.is_empty() {
            return Err(invalid("z_compare", channel, "no positions"));
        }
        if c.positions.len() > MAX_COMPARE_POSITIONS {
            return Err(invalid(
                "z_compare",
                channel,
                format!("more than {MAX_COMPARE_POSITIONS} positions"),
            ));
        }
        for p in &c.positions {
            bounded("positions", *p)?;
        }
        let pulse_width = match c.mode {
            CompareOutputMode::Pulse => {
                positive("pulse_width", bounded("pulse_width", c.pulse_width)?)?
            }
            CompareOutputMode::Toggle => 0.0,
        };
        let total = c.positions.len() as u32;
        let z = ZCompare {
            status: ZCompareStatus {
                channel,
                axis: c.axis,
                source: c.source,
                output_axis: c.output_axis,
                mode: c.mode,
                state: CompareState::Running,
                count: 0,
                missed: 0,
                remaining: total,
                total,
            },
            positions: c.positions.clone(),
            level: c.level,
            pulse_width,
            pulse_end: None,
            toggle_level: c.level,
        };
        if c.mode == CompareOutputMode::Pulse {
            z.write(env, !c.level);
        }
        Ok(z)
    }

    pub(super) fn channel(&self) -> u8 {
        self.status.channel
    }

    pub(super) fn status(&self) -> &ZCompareStatus {
        &self.status
    }

    /// Dropped: a pulse in progress ends.
    pub(super) fn stop(self, env: &mut Env) {
        if self.pulse_end.is_some() {
            self.write(env, !self.level);
        }
    }

    fn write(&self, env: &mut Env, level: bool) {
        if let Some(a) = env.axes.get_mut(self.status.output_axis as usize) {
            a.set_z_output(level);
        }
    }

    /// One tick: the positions the tick's travel passed, each at its moment within the tick.
    pub(super) fn step(&mut self, env: &mut Env) {
        let s = &self.status;
        let next = s.total - s.remaining;
        let Some(axis) = env.axes.get(s.axis as usize) else {
            return;
        };
        let [x0, x1] = axis.swept(s.source);
        let passed = passed_1d(|k| self.positions.get(k as usize).copied(), next, [x0, x1]);
        // The tick ran from `start` to `end`, seconds of engine time.
        let end = env.tick as f64 * env.period;
        let start = end - env.period;
        for k in next..next.saturating_add(passed) {
            let p = self.positions.get(k as usize).copied().unwrap_or(x1);
            let f = (p - x0) / (x1 - x0);
            let at = start
                + if f.is_finite() {
                    f.clamp(0.0, 1.0)
                } else {
                    1.0
                } * env.period;
            self.pass(env, at);
        }
        self.status.remaining -= passed.min(self.status.remaining);
        if self.status.mode == CompareOutputMode::Pulse {
            // High at the end of every tick the pulse overlapped, then back to idle.
            let on = self.pulse_end.is_some_and(|e| e > start);
            if !self.pulse_end.is_some_and(|e| e > end) {
                self.pulse_end = None;
            }
            self.write(env, if on { self.level } else { !self.level });
        }
        if self.status.remaining == 0 {
            self.status.state = CompareState::Done;
        }
    }

    /// A position passed at `at` seconds.
    fn pass(&mut self, env: &mut Env, at: f64) {
        match self.status.mode {
            CompareOutputMode::Toggle => {
                let level = self.toggle_level;
                self.write(env, level);
                self.toggle_level = !level;
            }
            CompareOutputMode::Pulse => {
                if self.pulse_end.is_some_and(|e| at < e) {
                    self.status.missed = self.status.missed.saturating_add(1);
                    return;
                }
                self.pulse_end = Some(at + self.pulse_width);
            }
        }
        self.status.count = self.status.count.saturating_add(1);
    }
}
