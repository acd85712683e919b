//! Pulse/direction output (ARCHITECTURE §3.2): commanded motion → integer pulses. Counter
//! arithmetic wraps, as in the encoder.
//!
//! The counter tracks `round(position × pulses_per_unit)`, so the fraction of a pulse is carried
//! implicitly and never drifts. A command faster than `max_frequency` is clamped; the pulses owed
//! go out in later ticks (a stepper drive receives them late, it does not lose them).

/// Pulse output of one axis.
#[derive(Clone, Debug)]
pub struct PulseOutput {
    pulses_per_unit: f64,
    /// Largest number of pulses one tick may carry.
    max_per_tick: i64,
    period: f64,
    rate: f64,
    /// Pulses emitted since start (signed).
    count: i64,
    /// `count` target = round((position − origin) × pulses_per_unit) + base. Re-based when the
    /// scale changes so that a new `units` never causes a burst of pulses.
    origin: f64,
    base: i64,
    last: i32,
    direction: bool,
}

impl PulseOutput {
    pub fn new(pulses_per_unit: f64, max_frequency: f64, period: f64, position: f64) -> Self {
        let mut p = PulseOutput {
            pulses_per_unit,
            max_per_tick: 1,
            period,
            rate: 1.0 / period,
            count: 0,
            origin: position,
            base: 0,
            last: 0,
            direction: true,
        };
        p.set_max_frequency(max_frequency);
        p
    }

    pub fn set_max_frequency(&mut self, max_frequency: f64) {
        // At least one pulse per tick, so a clamped output still makes progress.
        self.max_per_tick = ((max_frequency * self.period).floor() as i64).max(1);
    }

    /// Change the scale; the current position keeps its pulse count.
    pub fn set_pulses_per_unit(&mut self, pulses_per_unit: f64, position: f64) {
        self.base = self.count;
        self.origin = position;
        self.pulses_per_unit = pulses_per_unit;
    }

    /// Emit the pulses that bring the output to `position` (physical, user units), within the
    /// frequency limit. Returns the pulses emitted this tick.
    pub fn update(&mut self, position: f64) -> i32 {
        // `as` saturates, so an absurd position gives a huge but finite target, never UB.
        let target = super::round_to_i64((position - self.origin) * self.pulses_per_unit);
        let target = target.wrapping_add(self.base);
        let emit = target
            .wrapping_sub(self.count)
            .clamp(-self.max_per_tick, self.max_per_tick);
        self.count = self.count.wrapping_add(emit);
        self.last = emit.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        if emit != 0 {
            self.direction = emit > 0;
        }
        self.last
    }

    /// The physical position the emitted pulses stand for.
    pub fn position(&self) -> f64 {
        self.count.wrapping_sub(self.base) as f64 / self.pulses_per_unit + self.origin
    }

    pub fn count(&self) -> i64 {
        self.count
    }

    pub fn last_tick(&self) -> i32 {
        self.last
    }

    /// Frequency of the last tick, Hz, signed.
    pub fn frequency(&self) -> f64 {
        self.last as f64 * self.rate
    }

    /// Direction level: true for positive motion (before any output inversion).
    pub fn direction(&self) -> bool {
        self.direction
    }

    /// Pulses commanded but not yet emitted because of the frequency clamp.
    pub fn owed(&self, position: f64) -> i64 {
        let target = super::round_to_i64((position - self.origin) * self.pulses_per_unit);
        target.wrapping_add(self.base).wrapping_sub(self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fractions_carry_without_drift() {
        // 3 pulses/unit, 0.1 unit per tick: 0.3 pulse per tick on average.
        let mut p = PulseOutput::new(3.0, 1e9, 1e-3, 0.0);
        let mut total = 0i64;
        for k in 1..=1000 {
            total += p.update(k as f64 * 0.1) as i64;
        }
        assert_eq!(total, 300);
        assert_eq!(p.count(), 300);
        assert!((p.position() - 100.0).abs() < 1e-12);
    }

    #[test]
    fn hmc_units_example_gives_50000_pulses() {
        // HMC §4.7.3: Units = 1000 lines/mm, HMC_Move(0, 50) ⇒ 50 000 pulses.
        let mut p = PulseOutput::new(1000.0, 2e6, 1e-3, 0.0);
        let mut pos: f64 = 0.0;
        while pos < 50.0 {
            pos = (pos + 0.7).min(50.0);
            p.update(pos);
        }
        assert_eq!(p.count(), 50_000);
    }

    #[test]
    fn frequency_clamp_delays_but_keeps_pulses() {
        // 200 kHz at 1 ms: at most 200 pulses per tick (CPU 226H).
        let mut p = PulseOutput::new(1.0, 200_000.0, 1e-3, 0.0);
        assert_eq!(p.update(1000.0), 200);
        assert_eq!(p.frequency(), 200_000.0);
        assert_eq!(p.owed(1000.0), 800);
        for _ in 0..4 {
            p.update(1000.0);
        }
        assert_eq!(p.count(), 1000);
        assert_eq!(p.update(1000.0), 0);
        assert_eq!(p.update(990.0), -10);
        assert!(!p.direction());
    }

    #[test]
    fn rescaling_does_not_burst() {
        let mut p = PulseOutput::new(10.0, 1e9, 1e-3, 0.0);
        p.update(5.0);
        assert_eq!(p.count(), 50);
        p.set_pulses_per_unit(100.0, 5.0);
        assert_eq!(p.update(5.0), 0);
        assert_eq!(p.update(6.0), 100);
        assert!((p.position() - 6.0).abs() < 1e-12);
    }

    #[test]
    fn absurd_positions_saturate_instead_of_panicking() {
        let mut p = PulseOutput::new(1e6, 1e6, 1e-3, 0.0);
        p.update(1e300);
        p.update(-1e300);
        p.update(f64::NAN);
    }
}
