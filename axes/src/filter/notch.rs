//! The vibration suppression filter (digest 004 §2.14 VSF): a notch at `frequency` whose width
//! the damping ratio sets, H(s) = (s² + ω²) / (s² + 2ζωs + ω²), discretised by the bilinear
//! transform with the notch frequency prewarped (the RBJ cookbook notch, Q = 1 / 2ζ). Its DC
//! gain is exactly 1, so a held command is reached; once within a hair of it the output snaps
//! to it and the filter is settled.

use crate::error::EngineError;

/// The output counts as arrived within this much (relative to max(1, |input|)).
const SETTLE_TOLERANCE: f64 = 1e-9;

#[derive(Clone, Debug, PartialEq)]
pub struct Notch {
    frequency: f64,
    damping: f64,
    /// Normalised coefficients: b0, b1, b2, a1, a2 (a0 = 1).
    b: [f64; 3],
    a: [f64; 2],
    /// Past inputs and outputs: x[n-1], x[n-2], y[n-1], y[n-2].
    x: [f64; 2],
    y: [f64; 2],
    settled: bool,
}

impl Notch {
    pub fn new(
        frequency: f64,
        damping: f64,
        period: f64,
        position: f64,
    ) -> Result<Self, EngineError> {
        if !frequency.is_finite() || frequency <= 0.0 || frequency * period >= 0.5 {
            return Err(EngineError::InvalidArgument {
                name: "frequency",
                value: frequency,
                reason: "must be a finite number > 0 Hz and below half the servo rate",
            });
        }
        if !damping.is_finite() || damping <= 0.0 || damping > 10.0 {
            return Err(EngineError::InvalidArgument {
                name: "damping",
                value: damping,
                reason: "must be within 0 < damping <= 10",
            });
        }
        let w = 2.0 * std::f64::consts::PI * frequency * period;
        let alpha = w.sin() * damping;
        let cos = w.cos();
        let a0 = 1.0 + alpha;
        let mut n = Notch {
            frequency,
            damping,
            b: [1.0 / a0, -2.0 * cos / a0, 1.0 / a0],
            a: [-2.0 * cos / a0, (1.0 - alpha) / a0],
            x: [position; 2],
            y: [position; 2],
            settled: true,
        };
        n.reset(position);
        Ok(n)
    }

    pub fn next(&mut self, input: f64) -> f64 {
        if self.settled && input == self.x[0] {
            return input;
        }
        let y = self.b[0] * input + self.b[1] * self.x[0] + self.b[2] * self.x[1]
            - self.a[0] * self.y[0]
            - self.a[1] * self.y[1];
        let tolerance = SETTLE_TOLERANCE * input.abs().max(1.0);
        let arrived = input == self.x[0]
            && input == self.x[1]
            && (y - input).abs() <= tolerance
            && (self.y[0] - input).abs() <= tolerance;
        if arrived {
            self.reset(input);
            return input;
        }
        self.settled = false;
        self.x = [input, self.x[0]];
        self.y = [y, self.y[0]];
        y
    }

    pub fn is_settled(&self) -> bool {
        self.settled
    }

    pub fn reset(&mut self, position: f64) {
        self.x = [position; 2];
        self.y = [position; 2];
        self.settled = true;
    }

    pub fn frequency(&self) -> f64 {
        self.frequency
    }

    pub fn damping(&self) -> f64 {
        self.damping
    }
}
