//! Moving-average smoothing of the commanded position (placeholder until the profile work lands).

/// Moving average over `n` ticks.
#[derive(Clone, Debug)]
pub struct MovingAverage {
    value: f64,
}

impl MovingAverage {
    pub fn new(_n: usize) -> MovingAverage {
        MovingAverage { value: 0.0 }
    }
    pub fn reset(&mut self, p: f64) {
        self.value = p;
    }
    pub fn next(&mut self, p: f64) -> f64 {
        self.value = p;
        p
    }
    pub fn is_settled(&self) -> bool {
        true
    }
}
