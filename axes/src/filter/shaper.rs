//! Input shapers (digest 004 §2.14 InShape): the output is a sum of delayed copies of the input,
//! weighted so that the residual vibration of a mode of `frequency` and `damping` cancels
//! (Singer & Seering ZV/ZVD; Singhose EI). Delays that fall between ticks read the input
//! linearly interpolated between its two neighbouring samples.

use super::ShaperType;
use crate::error::EngineError;

/// The longest shaper, in servo ticks (a ring buffer of this many past inputs at most).
pub const MAX_SHAPER_TICKS: usize = 1 << 16;

/// EI's tolerated residual vibration (5 %).
const EI_TOLERANCE: f64 = 0.05;

/// An input shaper on one axis's command.
#[derive(Clone, Debug, PartialEq)]
pub struct Shaper {
    shaper: ShaperType,
    frequency: f64,
    damping: f64,
    period: f64,
    /// (amplitude, delay in ticks), delays increasing; unused entries have amplitude 0.
    impulses: [(f64, f64); 3],
    count: usize,
    /// Past inputs, newest at `head`.
    history: Vec<f64>,
    head: usize,
    /// Ticks the input has not changed for (saturating at `span`).
    still: usize,
    /// The farthest tick back an impulse reads: the input unchanged this long means every
    /// impulse reads it, so the output is it.
    span: usize,
}

impl Shaper {
    /// A shaper for a mode of `frequency` Hz (undamped natural frequency) and damping ratio
    /// `damping` (0 ≤ ζ < 1), at rest at `position`.
    pub fn new(
        shaper: ShaperType,
        frequency: f64,
        damping: f64,
        period: f64,
        position: f64,
    ) -> Result<Self, EngineError> {
        if !frequency.is_finite() || frequency <= 0.0 {
            return Err(EngineError::InvalidArgument {
                name: "frequency",
                value: frequency,
                reason: "must be a finite number > 0 Hz",
            });
        }
        if frequency * period >= 0.5 {
            return Err(EngineError::InvalidArgument {
                name: "frequency",
                value: frequency,
                reason: "must be below half the servo rate",
            });
        }
        if !damping.is_finite() || !(0.0..1.0).contains(&damping) {
            return Err(EngineError::InvalidArgument {
                name: "damping",
                value: damping,
                reason: "must be within 0 <= damping < 1",
            });
        }
        let root = (1.0 - damping * damping).sqrt();
        let half = 0.5 / (frequency * root) / period;
        let k = (-damping * std::f64::consts::PI / root).exp();
        let (impulses, count) = match shaper {
            ShaperType::Zv => ([(1.0, 0.0), (k, half), (0.0, half)], 2),
            ShaperType::Zvd => ([(1.0, 0.0), (2.0 * k, half), (k * k, 2.0 * half)], 3),
            ShaperType::Ei => {
                let (outer, middle) = ((1.0 + EI_TOLERANCE) / 4.0, (1.0 - EI_TOLERANCE) / 2.0);
                ([(outer, 0.0), (middle, half), (outer, 2.0 * half)], 3)
            }
        };
        let last = impulses[count - 1].1;
        if last.ceil() >= MAX_SHAPER_TICKS as f64 {
            return Err(EngineError::InvalidArgument {
                name: "frequency",
                value: frequency,
                reason: "the shaper would be longer than 65536 servo ticks",
            });
        }
        let sum: f64 = impulses.iter().map(|(a, _)| a).sum();
        let impulses = impulses.map(|(a, d)| (a / sum, d));
        let span = last.ceil() as usize;
        let mut s = Shaper {
            shaper,
            frequency,
            damping,
            period,
            impulses,
            count,
            history: vec![position; span + 2],
            head: 0,
            still: span,
            span,
        };
        s.reset(position);
        Ok(s)
    }

    /// The input `ticks` ticks ago (0: this tick's), `ticks` < `history.len()`.
    fn past(&self, ticks: usize) -> f64 {
        let n = self.history.len();
        self.history[(self.head + n - ticks) % n]
    }

    pub fn next(&mut self, input: f64) -> f64 {
        let n = self.history.len();
        let previous = self.history[self.head];
        self.head = (self.head + 1) % n;
        self.history[self.head] = input;
        self.still = if input == previous {
            (self.still + 1).min(self.span)
        } else {
            0
        };
        if self.is_settled() {
            // Every impulse reads this same input: the output is it, exactly.
            return input;
        }
        let mut out = 0.0;
        for &(amplitude, delay) in &self.impulses[..self.count] {
            let whole = delay.floor();
            let fraction = delay - whole;
            let i = whole as usize;
            let newer = self.past(i);
            let sample = if fraction > 0.0 {
                newer + (self.past(i + 1) - newer) * fraction
            } else {
                newer
            };
            out += amplitude * sample;
        }
        out
    }

    pub fn is_settled(&self) -> bool {
        self.still >= self.span
    }

    pub fn reset(&mut self, position: f64) {
        self.history.fill(position);
        self.still = self.span;
    }

    pub fn shaper(&self) -> ShaperType {
        self.shaper
    }

    pub fn frequency(&self) -> f64 {
        self.frequency
    }

    pub fn damping(&self) -> f64 {
        self.damping
    }

    /// The last impulse's delay (s).
    pub fn delay(&self) -> f64 {
        self.impulses[self.count - 1].1 * self.period
    }

    /// (amplitude, delay in s) of each impulse.
    pub fn impulses(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.impulses[..self.count]
            .iter()
            .map(|&(a, d)| (a, d * self.period))
    }
}
