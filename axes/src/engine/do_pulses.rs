//! Timed digital outputs (NMC SetDOBitAutoReverse, DoBitPulseEnable, digest 001 §2.7, §2.8):
//! an output written now that toggles itself on the virtual clock, a whole number of ticks
//! after each change. At most one train per channel; a new write to the channel replaces it.

use crate::command::PulseDigitalOutput;
use crate::error::EngineError;

/// One running train.
#[derive(Clone, Debug, PartialEq)]
struct Train {
    channel: u16,
    /// Ticks the level it now shows still holds.
    left: u64,
    /// Ticks each level holds: [the level written first, the opposite].
    hold: [u64; 2],
    /// Which of `hold` the present level is.
    phase: usize,
    /// Toggles still to come (`u32::MAX`: forever).
    toggles: u32,
}

/// The trains, in the order they were started.
#[derive(Clone, Debug, Default)]
pub(super) struct DoPulses {
    trains: Vec<Train>,
}

/// Whole ticks of `seconds` (at least one: a toggle never happens in the tick it was asked).
fn ticks(name: &'static str, seconds: f64, period: f64) -> Result<u64, EngineError> {
    if !seconds.is_finite() || !(0.0..=1e6).contains(&seconds) {
        return Err(EngineError::InvalidArgument {
            name,
            value: seconds,
            reason: "a time in [0, 1e6] s",
        });
    }
    Ok(((seconds / period).round() as u64).max(1))
}

impl DoPulses {
    /// Check `c` against `outputs` (the channel exists), write its first level, and start its
    /// train; `toggles` 0 ends the channel's train and leaves the output as the train left it
    /// (in the tick the command arrives, so a stop never races a toggle).
    pub(super) fn start(
        &mut self,
        c: &PulseDigitalOutput,
        outputs: &mut [bool],
        period: f64,
    ) -> Result<(), EngineError> {
        let count = outputs.len() as u16;
        let out = outputs
            .get_mut(usize::from(c.channel))
            .ok_or(EngineError::InvalidChannel {
                kind: "digital outputs",
                channel: c.channel,
                count,
            })?;
        let hold = [
            ticks("level_time", c.level_time, period)?,
            ticks("other_time", c.other_time, period)?,
        ];
        self.stop(c.channel);
        if c.toggles > 0 {
            *out = c.level;
            self.trains.push(Train {
                channel: c.channel,
                left: hold[0],
                hold,
                phase: 0,
                toggles: c.toggles,
            });
        }
        Ok(())
    }

    /// End channel `channel`'s train, leaving the output as it is.
    pub(super) fn stop(&mut self, channel: u16) {
        self.trains.retain(|t| t.channel != channel);
    }

    /// One tick: toggle the outputs whose level has held its time, counting in `pulses` each
    /// hold of a train's first level that ends. Whether an output changed.
    pub(super) fn step(&mut self, outputs: &mut [bool], pulses: &mut [u32]) -> bool {
        if self.trains.is_empty() {
            return false;
        }
        let mut changed = false;
        for t in &mut self.trains {
            t.left = t.left.saturating_sub(1);
            if t.left > 0 {
                continue;
            }
            if let Some(o) = outputs.get_mut(usize::from(t.channel)) {
                *o = !*o;
                changed = true;
            }
            if t.phase == 0 {
                if let Some(n) = pulses.get_mut(usize::from(t.channel)) {
                    *n = n.wrapping_add(1);
                }
            }
            if t.toggles != u32::MAX {
                t.toggles -= 1;
            }
            t.phase = 1 - t.phase;
            t.left = t.hold.get(t.phase).copied().unwrap_or(1);
        }
        self.trains.retain(|t| t.toggles > 0);
        changed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_train_toggles_on_whole_ticks_and_ends() {
        let mut p = DoPulses::default();
        let mut out = vec![false; 2];
        let mut counts = vec![0u32; 2];
        let c = PulseDigitalOutput {
            channel: 1,
            level: true,
            level_time: 0.003,
            other_time: 0.001,
            toggles: 3,
        };
        p.start(&c, &mut out, 0.001).unwrap();
        let mut levels = Vec::new();
        for _ in 0..8 {
            p.step(&mut out, &mut counts);
            levels.push(out[1]);
        }
        assert_eq!(levels, [true, true, false, true, true, true, false, false]);
        // Two holds of the first level ended (toggles 1 and 3).
        assert_eq!(counts, [0, 2]);
        assert!(p.trains.is_empty());
        let bad = PulseDigitalOutput {
            channel: 2,
            ..c.clone()
        };
        assert!(p.start(&bad, &mut out, 0.001).is_err());
        // Toggles 0 ends a train where it stands, without writing.
        p.start(&c, &mut out, 0.001).unwrap();
        p.step(&mut out, &mut counts);
        p.step(&mut out, &mut counts);
        p.step(&mut out, &mut counts);
        assert!(!out[1]);
        let stop = PulseDigitalOutput {
            level: true,
            toggles: 0,
            ..c
        };
        p.start(&stop, &mut out, 0.001).unwrap();
        assert!(!out[1] && p.trains.is_empty());
    }
}
