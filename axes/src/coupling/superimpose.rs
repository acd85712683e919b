//! Superimposed motion: slave travel = k1 · travel of master 1 + k2 · travel of master 2
//! (HMC_SuperimposeEx, digest 000 §4.4: `ΔDposS = (N0/D0)·ΔMposM0 + (N1/D1)·ΔMposM1`; TV 22–24).
//!
//! As the gear, positions are computed from anchors, never summed tick by tick:
//! slave = slave_anchor + Σ kᵢ · (masterᵢ − anchorᵢ), so the slave's travel is the combination of
//! the masters' travels to rounding however long it runs. The manual's law is on increments, so
//! engaging never moves the slave, and a ratio change (HMC_SetSuperimposeRatio) re-anchors where
//! the slave and masters stand: the new ratios apply to travel from then on, with no position
//! jump (TV 22: 3000 + 1·1000 + (−1)·(−1000) = 5000).

use crate::profile::MotionState;

#[derive(Clone, Debug)]
pub struct Superimpose {
    ratios: [f64; 2],
    /// The masters' positions and the slave's at the anchor.
    master_anchors: [f64; 2],
    slave_anchor: f64,
    /// The masters' positions of the last tick, and the slave's setpoint.
    masters: [f64; 2],
    last: f64,
}

impl Superimpose {
    /// Engaged where the masters stand at `masters` and the slave at `slave`.
    pub fn new(ratios: [f64; 2], masters: [f64; 2], slave: f64) -> Superimpose {
        Superimpose {
            ratios,
            master_anchors: masters,
            slave_anchor: slave,
            masters,
            last: slave,
        }
    }

    pub fn ratios(&self) -> [f64; 2] {
        self.ratios
    }

    /// New ratios from here on: re-anchored at the last tick's positions, so nothing jumps.
    pub fn set_ratios(&mut self, ratios: [f64; 2]) {
        self.ratios = ratios;
        self.master_anchors = self.masters;
        self.slave_anchor = self.last;
    }

    /// This tick's slave setpoint for the masters' states (already this tick's).
    pub fn step(&mut self, m1: MotionState, m2: MotionState) -> MotionState {
        let [k1, k2] = self.ratios;
        let [a1, a2] = self.master_anchors;
        self.masters = [m1.p, m2.p];
        let p = self.slave_anchor + k1 * (m1.p - a1) + k2 * (m2.p - a2);
        self.last = p;
        MotionState {
            p,
            v: k1 * m1.v + k2 * m2.v,
            a: k1 * m1.a + k2 * m2.a,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(p: f64) -> MotionState {
        MotionState { p, v: 0.0, a: 0.0 }
    }

    #[test]
    fn a_ratio_change_applies_to_travel_from_then_on_tv22() {
        // Digest 000 TV 22: SuperimposeEx(3, 0, 1, 1/1, 1/1); master 0 +1000, master 1 +2000
        // → 3000; ratios (1, −1); master 0 +1000, master 1 −1000 → 5000.
        let mut s = Superimpose::new([1.0, 1.0], [0.0, 0.0], 0.0);
        assert_eq!(s.step(at(1000.0), at(2000.0)).p, 3000.0);
        s.set_ratios([1.0, -1.0]);
        assert_eq!(s.step(at(1000.0), at(2000.0)).p, 3000.0, "no jump");
        assert_eq!(s.step(at(2000.0), at(1000.0)).p, 5000.0);
    }
}
