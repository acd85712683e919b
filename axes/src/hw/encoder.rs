//! Incremental encoder (ARCHITECTURE §3.2): physical motion → counts, A/B quadrature and an
//! index (Z) pulse once per revolution; optional noise from the seeded RNG; loss of feedback.

use crate::rng::Rng;
use serde::{Deserialize, Serialize};

/// Encoder of one axis.
#[derive(Clone, Debug)]
pub struct Encoder {
    counts_per_unit: f64,
    counts_per_rev: i64,
    index_width: i64,
    index_offset: i64,
    noise: f64,
    rng: Rng,
    /// Counts of the true motor position; `origin`/`base` as in the pulse output, so a change of
    /// scale never jumps.
    raw: i64,
    origin: f64,
    base: i64,
    /// What the controller reads: `raw − missed` plus noise. While the feedback is lost the
    /// counter freezes and the motion it misses is gone for good, as with a real incremental
    /// encoder (the axis has to be homed again).
    counts: i64,
    missed: i64,
    lost: bool,
    /// The index count at or below `raw`: the revolution the motor is in. Kept up to date
    /// incrementally so a tick needs no 64-bit division (~40 cycles each) unless it crosses
    /// a revolution boundary.
    index_below: i64,
}

/// What happened on the encoder during one tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EncoderTick {
    /// Physical position of an index pulse passed during the tick (the first one in the
    /// direction of travel).
    pub index_at: Option<f64>,
}

impl Encoder {
    pub fn new(config: &EncoderConfig, counts_per_unit: f64, position: f64, rng: Rng) -> Self {
        Encoder {
            counts_per_unit,
            counts_per_rev: config.counts_per_rev as i64,
            index_width: config.index_width.max(1) as i64,
            index_offset: config.index_offset as i64,
            noise: config.noise,
            rng,
            raw: 0,
            origin: position,
            base: 0,
            counts: 0,
            missed: 0,
            lost: false,
            index_below: 0,
        }
        .with_index_below()
    }

    /// Recompute `index_below` from scratch (construction, large jumps).
    fn with_index_below(mut self) -> Self {
        self.index_below = self.index_at_or_below(self.raw);
        self
    }

    fn index_at_or_below(&self, count: i64) -> i64 {
        if self.counts_per_rev > 0 {
            // In i128: an extreme counter must not overflow the arithmetic.
            let (c, o, r) = (
                i128::from(count),
                i128::from(self.index_offset),
                i128::from(self.counts_per_rev),
            );
            let k = (c - o).div_euclid(r) * r + o;
            k.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64
        } else {
            0
        }
    }

    pub fn set_counts_per_unit(&mut self, counts_per_unit: f64, position: f64) {
        self.base = self.raw;
        self.origin = position;
        self.counts_per_unit = counts_per_unit;
    }

    /// Feedback lost: the counter freezes while the motor may still move.
    pub fn set_lost(&mut self, lost: bool) {
        self.lost = lost;
    }

    fn counts_at(&self, position: f64) -> i64 {
        super::round_to_i64((position - self.origin) * self.counts_per_unit).wrapping_add(self.base)
    }

    fn position_of(&self, counts: i64) -> f64 {
        counts.wrapping_sub(self.base) as f64 / self.counts_per_unit + self.origin
    }

    /// Follow the motor to `position` (physical, user units).
    #[inline]
    pub fn update(&mut self, position: f64) -> EncoderTick {
        let previous = self.raw;
        self.raw = self.counts_at(position);
        let mut tick = EncoderTick::default();
        let cpr = self.counts_per_rev;
        if cpr > 0 && self.raw != previous {
            // The index sits at counts ≡ index_offset (mod counts_per_rev); `index_below` is the
            // one at or below `previous`. Report the first index crossed in the direction of
            // travel, whatever the speed.
            let below = self.index_below;
            if self.raw > previous {
                let next = below.wrapping_add(cpr);
                if self.raw >= next {
                    tick.index_at = Some(self.position_of(next));
                }
            } else if below < previous && self.raw <= below {
                tick.index_at = Some(self.position_of(below));
            } else if below == previous {
                // Starting on an index count, moving down first crosses the one before it.
                let prior = below.wrapping_sub(cpr);
                if self.raw <= prior {
                    tick.index_at = Some(self.position_of(prior));
                }
            }
            // Keep `index_below` the index count at or below `raw`: one revolution on is the
            // common case; anything farther is recomputed.
            if self.raw >= below.wrapping_add(cpr) {
                self.index_below = if self.raw < below.wrapping_add(2 * cpr) {
                    below.wrapping_add(cpr)
                } else {
                    self.index_at_or_below(self.raw)
                };
            } else if self.raw < below {
                self.index_below = if self.raw >= below.wrapping_sub(cpr) {
                    below.wrapping_sub(cpr)
                } else {
                    self.index_at_or_below(self.raw)
                };
            }
        }
        if self.lost {
            self.missed = self.missed.wrapping_add(self.raw.wrapping_sub(previous));
        } else {
            self.counts = self.raw.wrapping_sub(self.missed);
            if self.noise > 0.0 {
                self.counts = self
                    .counts
                    .wrapping_add(super::round_to_i64(self.noise * self.rng.next_signed()));
            }
        }
        tick
    }

    /// The counter a hardware latch reads when the motor passes `position` (physical) during
    /// this tick: that position's count less the counts missed while feedback was lost, or the
    /// frozen counter while it is lost. No noise: noise is a sample's, not the edge's.
    pub fn count_at(&self, position: f64) -> i64 {
        if self.lost {
            self.counts
        } else {
            self.counts_at(position).wrapping_sub(self.missed)
        }
    }

    /// The position a count stands for (physical frame, user units).
    pub fn position_of_count(&self, counts: i64) -> f64 {
        self.position_of(counts)
    }

    /// Counts of a distance (user units), rounded.
    pub fn counts_of(&self, distance: f64) -> i64 {
        super::round_to_i64(distance * self.counts_per_unit)
    }

    /// The counter the controller reads.
    pub fn counts(&self) -> i64 {
        self.counts
    }

    /// The position the counter stands for (physical frame, user units).
    pub fn position(&self) -> f64 {
        self.position_of(self.counts)
    }

    /// Index (Z) level: high for `index_width` counts once per revolution.
    pub fn index(&self) -> bool {
        self.counts_per_rev > 0 && self.raw.wrapping_sub(self.index_below) < self.index_width
    }

    /// A/B levels: bit 0 = A, bit 1 = B; counting up steps 00 → 01 → 11 → 10 (A leads B).
    pub fn quadrature(&self) -> u8 {
        const STATES: [u8; 4] = [0b00, 0b01, 0b11, 0b10];
        STATES[self.raw.rem_euclid(4) as usize]
    }

    /// Whether the encoder has an index pulse at all.
    pub fn has_index(&self) -> bool {
        self.counts_per_rev > 0
    }
}

/// Incremental encoder (ARCHITECTURE §3.2).
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderConfig {
    /// Counts per motor revolution: the index (Z) pulse comes once per revolution. 0 = no index.
    pub counts_per_rev: u32,
    /// Width of the index pulse, counts.
    pub index_width: u32,
    /// Count offset of the index pulse within a revolution.
    pub index_offset: u32,
    /// Peak amplitude of uniform noise added to the count, counts (0 = none).
    pub noise: f64,
}

impl Default for EncoderConfig {
    fn default() -> Self {
        EncoderConfig {
            counts_per_rev: 10_000,
            index_width: 1,
            index_offset: 0,
            noise: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn encoder(cpr: u32, cpu: f64) -> Encoder {
        let config = EncoderConfig {
            counts_per_rev: cpr,
            index_width: 1,
            index_offset: 0,
            noise: 0.0,
        };
        Encoder::new(&config, cpu, 0.0, Rng::new(1))
    }

    #[test]
    fn hmc_ke_example_counts_to_degrees() {
        // HMC §4.7.5: Ke = 360/8192 with Units = 1 ⇒ 8192 counts per 360 degrees.
        let mut e = encoder(8192, 8192.0 / 360.0);
        e.update(360.0);
        assert_eq!(e.counts(), 8192);
        assert!((e.position() - 360.0).abs() < 1e-12);
    }

    #[test]
    fn index_found_at_every_revolution_even_when_fast() {
        let mut e = encoder(1000, 1000.0); // one revolution per unit
        assert_eq!(e.update(0.5).index_at, None);
        assert_eq!(e.update(1.2).index_at, Some(1.0));
        // Several revolutions in one tick: the first one crossed is reported.
        assert_eq!(e.update(4.7).index_at, Some(2.0));
        // Backwards.
        assert_eq!(e.update(3.5).index_at, Some(4.0));
        assert_eq!(e.update(3.2).index_at, None);
        assert_eq!(e.update(-0.2).index_at, Some(3.0));
        e.update(0.0);
        assert!(e.index());
        e.update(0.0005);
        assert!(!e.index());
    }

    #[test]
    fn incremental_index_tracking_matches_the_arithmetic() {
        // Random walks with steps from sub-revolution to many revolutions, both directions,
        // against the closed form of "first index count crossed".
        let config = EncoderConfig {
            counts_per_rev: 37,
            index_width: 3,
            index_offset: 5,
            noise: 0.0,
        };
        let mut r = Rng::new(11);
        let mut e = Encoder::new(&config, 1.0, 0.0, Rng::new(1));
        let mut prev: i64 = 0;
        for _ in 0..200_000 {
            let step = match r.next_u64() % 4 {
                0 => (r.next_signed() * 3.0) as i64,
                1 => (r.next_signed() * 40.0) as i64,
                2 => (r.next_signed() * 400.0) as i64,
                _ => 0,
            };
            let next = prev + step;
            let got = e.update(next as f64).index_at;
            let expect = if next > prev {
                let k = (prev - 5).div_euclid(37) * 37 + 5 + 37;
                (k <= next).then_some(k as f64)
            } else if next < prev {
                let k = (prev - 1 - 5).div_euclid(37) * 37 + 5;
                (k >= next).then_some(k as f64)
            } else {
                None
            };
            assert_eq!(got, expect, "{prev} → {next}");
            assert_eq!(e.index(), (next - 5).rem_euclid(37) < 3, "level at {next}");
            prev = next;
        }
    }

    #[test]
    fn quadrature_sequence_and_direction() {
        let mut e = encoder(0, 1.0);
        let mut seq = vec![];
        for k in 0..5 {
            e.update(k as f64);
            seq.push(e.quadrature());
        }
        assert_eq!(seq, vec![0b00, 0b01, 0b11, 0b10, 0b00]);
        e.update(-1.0);
        assert_eq!(e.quadrature(), 0b10);
    }

    #[test]
    fn loss_freezes_counts_and_noise_is_seeded() {
        let mut e = encoder(0, 1.0);
        e.update(10.0);
        e.set_lost(true);
        e.update(20.0);
        assert_eq!(e.counts(), 10);
        e.set_lost(false);
        e.update(25.0);
        assert_eq!(
            e.counts(),
            15,
            "the 10 counts moved while lost are missing for good"
        );

        let noisy = EncoderConfig {
            noise: 2.0,
            ..EncoderConfig::default()
        };
        let run = |seed| {
            let mut e = Encoder::new(&noisy, 1.0, 0.0, Rng::new(seed));
            (0..100)
                .map(|_| {
                    e.update(50.0);
                    e.counts()
                })
                .collect::<Vec<_>>()
        };
        let a = run(3);
        assert_eq!(a, run(3));
        assert!(a.iter().all(|c| (48..=52).contains(c)));
        assert!(a.iter().any(|c| *c != 50));
    }
}
