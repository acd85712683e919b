//! Moving-average smoothing of the commanded position: NMC smoothCoef (digest 001 §4.3) and
//! HIMC SMTime (digest 004 §3.7, "Jerk = acc/Ts").
//!
//! Averaging the last `n` commanded positions is the same as averaging the last `n` velocity
//! samples, so a trapezoid (piecewise constant acceleration) comes out with linear
//! acceleration ramps of `n` ticks: jerk = acc / (n·period). The last input change reaches the
//! output `n − 1` ticks later, which is how much the move lengthens.

/// Longest window: 0.5 s (HIMC SMTime maximum) at the shortest servo period, 62.5 µs.
pub const MAX_WINDOW_TICKS: usize = 8000;

#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SmoothingError {
    #[error("smoothing window of {ticks} ticks exceeds the maximum of {max}")]
    WindowTooLong { ticks: usize, max: usize },
}

/// Moving average over a fixed number of servo ticks. Allocates once, in [`MovingAverage::new`].
#[derive(Clone, Debug)]
pub struct MovingAverage {
    /// The last `n` inputs, relative to `base`, as a ring.
    buf: Box<[f64]>,
    idx: usize,
    /// Sum of `buf`.
    sum: f64,
    /// Sum of the inputs written since `idx` last wrapped to 0. When it wraps, those are
    /// exactly the window, so `sum` restarts from it: rounding cannot build up over time.
    fresh: f64,
    base: f64,
    last: f64,
    /// Consecutive inputs equal to `last`, capped at `n`.
    same: usize,
}

impl MovingAverage {
    /// A window of `n_ticks` servo ticks, holding 0. `n_ticks` 0 and 1 both mean no smoothing.
    pub fn new(n_ticks: usize) -> Result<MovingAverage, SmoothingError> {
        let n = n_ticks.max(1);
        if n > MAX_WINDOW_TICKS {
            return Err(SmoothingError::WindowTooLong {
                ticks: n_ticks,
                max: MAX_WINDOW_TICKS,
            });
        }
        Ok(MovingAverage {
            buf: vec![0.0; n].into_boxed_slice(),
            idx: 0,
            sum: 0.0,
            fresh: 0.0,
            base: 0.0,
            last: 0.0,
            same: n,
        })
    }

    /// Window length in ticks.
    pub fn window(&self) -> usize {
        self.buf.len()
    }

    /// Forget the history: the output is `p` and settled.
    pub fn reset(&mut self, p: f64) {
        self.buf.fill(0.0);
        self.idx = 0;
        self.sum = 0.0;
        self.fresh = 0.0;
        self.base = p;
        self.last = p;
        self.same = self.buf.len();
    }

    /// Feed this tick's input; returns the smoothed value. Once the input has been constant for
    /// a whole window the output is exactly the input, so a move still ends on its target.
    #[inline]
    pub fn next(&mut self, p: f64) -> f64 {
        let n = self.buf.len();
        let x = p - self.base;
        if let Some(slot) = self.buf.get_mut(self.idx) {
            self.sum += x - *slot;
            *slot = x;
        }
        self.fresh += x;
        self.idx += 1;
        if self.idx >= n {
            self.idx = 0;
            self.sum = self.fresh;
            self.fresh = 0.0;
        }
        if p == self.last {
            self.same = (self.same + 1).min(n);
        } else {
            self.last = p;
            self.same = 1;
        }
        if self.same >= n {
            p
        } else {
            self.base + self.sum / n as f64
        }
    }

    /// Whether the last `window()` inputs were equal, i.e. the output equals the input.
    pub fn is_settled(&self) -> bool {
        self.same >= self.buf.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_one_is_the_identity() {
        let mut f = MovingAverage::new(0).unwrap();
        assert_eq!(f.window(), 1);
        for x in [1.0, 2.5, -3.0, 1e12 + 0.3] {
            assert_eq!(f.next(x), x);
            assert!(f.is_settled());
        }
    }

    #[test]
    fn too_long_a_window_is_refused() {
        assert!(MovingAverage::new(MAX_WINDOW_TICKS).is_ok());
        assert_eq!(
            MovingAverage::new(MAX_WINDOW_TICKS + 1).unwrap_err(),
            SmoothingError::WindowTooLong {
                ticks: MAX_WINDOW_TICKS + 1,
                max: MAX_WINDOW_TICKS
            }
        );
    }

    #[test]
    fn step_becomes_a_ramp_and_settles_exactly() {
        let mut f = MovingAverage::new(4).unwrap();
        f.reset(10.0);
        let out: Vec<f64> = (0..6).map(|_| f.next(0.1 + 0.2)).collect();
        let target = 0.1 + 0.2;
        assert_eq!(out[0], 10.0 + (target - 10.0) / 4.0);
        assert!(!f.is_settled() || out[3] == target);
        assert_eq!(out[3], target);
        assert_eq!(out[5], target);
        assert!(f.is_settled());
    }
}
