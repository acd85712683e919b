//! The electronic gear: slave travel = ratio × master travel (digest 001 §2.16/§4.7, digest 000
//! §4.3 HMC_Gear, digest 004 §2.5 GearIn).
//!
//! Positions after the clutch are computed from anchors, never summed tick by tick:
//! slave = slave_anchor + ratio · (master − master_anchor), so the slave's travel is ratio × the
//! master's to rounding however long the gear runs. With a direction filter the master
//! coordinate is the sum of the master's moves in that direction instead of its position.

use crate::command::Direction;
use crate::profile::MotionState;
use crate::status::CouplingPhase;

/// How the gear engages, at `gear_in` and at each ratio change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Clutch {
    /// At once: NMC masterSlope 0, HMC, HIMC.
    Immediate,
    /// The ratio ramps linearly over this much master travel (NMC `masterSlope`: "master
    /// constant, slave uniformly accelerates"; TV 58).
    Distance(f64),
    /// The slave's velocity goes to ratio × master velocity with this acceleration; the
    /// positions lock when the velocities match (PLCopen MC_GearIn InGear).
    Acceleration(f64),
    /// As `Acceleration`, with `accel` while the slave's speed grows and `decel` while it
    /// shrinks: HMC_SetGearTransationSwitch = 1, "a smoothing transition with the axis's own
    /// Accel/Decel at gear start and on ratio changes" (digest 000 §4.3).
    Transition { accel: f64, decel: f64 },
}

#[derive(Clone, Debug)]
pub struct Gear {
    pub numerator: f64,
    pub denominator: f64,
    ratio: f64,
    clutch: Clutch,
    direction: Option<Direction>,
    phase: CouplingPhase,
    /// The ratio a distance clutch ramps from.
    from_ratio: f64,
    /// Master coordinate (position, or filtered travel) and slave position at the anchor.
    master_anchor: f64,
    slave_anchor: f64,
    /// The master coordinate of the last tick.
    master: f64,
    /// The slave's setpoint of the last tick.
    last: MotionState,
    /// HMC_SetGearPhaseOffset: the setpoints pass through this delay line.
    delay: Option<Delay>,
}

/// Most servo periods a gear's slave may run behind (HMC_SetGearPhaseOffset: 0~128).
pub const MAX_PHASE_OFFSET: u32 = 128;

/// A delay line of setpoints (HMC_SetGearPhaseOffset, digest 000 §4.3: "delays the slave
/// trajectory by 0~128 servo cycles"): each tick's setpoint comes out `len` ticks later; until
/// the first does, the slave holds where the gear found it. Allocated once at `gear_in`.
#[derive(Clone, Debug)]
struct Delay {
    ring: Box<[MotionState]>,
    head: usize,
}

impl Delay {
    fn pass(&mut self, next: MotionState) -> MotionState {
        let len = self.ring.len();
        match self.ring.get_mut(self.head) {
            Some(slot) => {
                self.head = (self.head + 1) % len;
                std::mem::replace(slot, next)
            }
            None => next,
        }
    }
}

impl Gear {
    /// A gear engaging from the slave's commanded state `slave` and the master's `master`.
    pub fn new(
        numerator: f64,
        denominator: f64,
        clutch: Clutch,
        direction: Option<Direction>,
        master: f64,
        slave: MotionState,
    ) -> Gear {
        let mut gear = Gear {
            numerator,
            denominator,
            ratio: numerator / denominator,
            clutch,
            direction,
            phase: CouplingPhase::Engaging,
            from_ratio: 0.0,
            master_anchor: master,
            slave_anchor: slave.p,
            master,
            last: slave,
            delay: None,
        };
        gear.engage(0.0);
        gear
    }

    /// Run the slave `ticks` servo periods behind (≤ [`MAX_PHASE_OFFSET`], checked by the
    /// caller); 0 is none.
    pub fn with_phase_offset(mut self, ticks: u32) -> Gear {
        if ticks > 0 {
            let rest = MotionState {
                p: self.last.p,
                v: 0.0,
                a: 0.0,
            };
            self.delay = Some(Delay {
                ring: vec![rest; ticks as usize].into_boxed_slice(),
                head: 0,
            });
        }
        self
    }

    /// The phase offset in servo periods.
    pub fn phase_offset(&self) -> u32 {
        self.delay
            .as_ref()
            .map_or(0, |d| u32::try_from(d.ring.len()).unwrap_or(u32::MAX))
    }

    /// The ratio it runs at (or engages to).
    pub fn ratio(&self) -> f64 {
        self.ratio
    }

    pub fn phase(&self) -> CouplingPhase {
        self.phase
    }

    /// Change the ratio from where the slave is, through the clutch (HMC_SetGearRatio).
    pub fn set_ratio(&mut self, numerator: f64, denominator: f64) {
        let from = match self.phase {
            CouplingPhase::InSync => self.ratio,
            // Mid-clutch: ramp on from the ratio the slave has reached.
            _ => self.current_ratio(),
        };
        self.numerator = numerator;
        self.denominator = denominator;
        self.ratio = numerator / denominator;
        self.master_anchor = self.master;
        self.slave_anchor = self.last.p;
        self.engage(from);
    }

    fn engage(&mut self, from: f64) {
        self.from_ratio = from;
        self.phase = match self.clutch {
            Clutch::Immediate => CouplingPhase::InSync,
            Clutch::Distance(_) | Clutch::Acceleration(_) | Clutch::Transition { .. } => {
                CouplingPhase::Engaging
            }
        };
    }

    /// The slave's velocity ratio now, as a distance clutch sees it.
    fn current_ratio(&self) -> f64 {
        match self.clutch {
            Clutch::Distance(d) => {
                let u = (self.master - self.master_anchor).abs();
                self.from_ratio + (self.ratio - self.from_ratio) * (u / d).min(1.0)
            }
            _ => self.ratio,
        }
    }

    /// The master coordinate and its velocity and acceleration through the direction filter
    /// (NMC MtGearSetDir: >0 follow positive master motion only, <0 negative only).
    fn filter(&self, master: MotionState, previous: f64, raw_previous: f64) -> MotionState {
        let Some(direction) = self.direction else {
            return master;
        };
        let passes = |d: f64| match direction {
            Direction::Positive => d > 0.0,
            Direction::Negative => d < 0.0,
        };
        let step = master.p - raw_previous;
        MotionState {
            p: previous + if passes(step) { step } else { 0.0 },
            v: if passes(master.v) { master.v } else { 0.0 },
            a: if passes(master.v) { master.a } else { 0.0 },
        }
    }

    /// This tick's slave setpoint for the master's state `master` (already this tick's) and the
    /// master's raw position of the last tick `raw_previous`.
    pub fn step(&mut self, master: MotionState, raw_previous: f64, dt: f64) -> MotionState {
        let next = self.advance(master, raw_previous, dt);
        match &mut self.delay {
            Some(delay) => delay.pass(next),
            None => next,
        }
    }

    /// [`Gear::step`] before the phase offset.
    fn advance(&mut self, master: MotionState, raw_previous: f64, dt: f64) -> MotionState {
        let m = self.filter(master, self.master, raw_previous);
        self.master = m.p;
        let r = self.ratio;
        let next = match (self.phase, self.clutch) {
            (CouplingPhase::Engaging, Clutch::Distance(d)) => {
                let u = m.p - self.master_anchor;
                let dr = r - self.from_ratio;
                if u.abs() >= d {
                    // Clutch done: anchor where the ramp ended, in the direction travelled.
                    let s = u.signum() * d;
                    self.slave_anchor += self.from_ratio * s + dr * s / 2.0;
                    self.master_anchor += s;
                    self.phase = CouplingPhase::InSync;
                    self.in_gear(m)
                } else {
                    let k = u.abs() / d;
                    MotionState {
                        p: self.slave_anchor + self.from_ratio * u + dr * u * u.abs() / (2.0 * d),
                        v: (self.from_ratio + dr * k) * m.v,
                        a: (self.from_ratio + dr * k) * m.a + dr * u.signum() * m.v * m.v / d,
                    }
                }
            }
            (CouplingPhase::Engaging, Clutch::Acceleration(_) | Clutch::Transition { .. }) => {
                let target = r * m.v;
                let dv = target - self.last.v;
                let acc = match self.clutch {
                    // Speeding up (or through zero) with accel, slowing down with decel.
                    Clutch::Transition { accel, decel } => {
                        if target.abs() >= self.last.v.abs() || target * self.last.v < 0.0 {
                            accel
                        } else {
                            decel
                        }
                    }
                    Clutch::Acceleration(acc) => acc,
                    _ => f64::INFINITY,
                };
                let step = dv.clamp(-acc * dt, acc * dt);
                let v = self.last.v + step;
                let p = self.last.p + (self.last.v + v) * 0.5 * dt;
                if step == dv {
                    // Velocities match: lock the positions from here (PLCopen InGear).
                    self.slave_anchor = p;
                    self.master_anchor = m.p;
                    self.phase = CouplingPhase::InSync;
                }
                MotionState { p, v, a: step / dt }
            }
            _ => self.in_gear(m),
        };
        self.last = next;
        next
    }

    fn in_gear(&self, m: MotionState) -> MotionState {
        let r = self.ratio;
        MotionState {
            p: self.slave_anchor + r * (m.p - self.master_anchor),
            v: r * m.v,
            a: r * m.a,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(p: f64, v: f64) -> MotionState {
        MotionState { p, v, a: 0.0 }
    }

    #[test]
    fn a_distance_clutch_loses_half_the_clutch_travel_tv58() {
        // Digest 001 TV 58: ratio 4/5, clutch 2000, master +10000 → slave 8000 − 800.
        let mut g = Gear::new(
            4.0,
            5.0,
            Clutch::Distance(2000.0),
            None,
            0.0,
            MotionState::default(),
        );
        let mut prev = 0.0;
        let mut s = MotionState::default();
        for i in 1..=1000 {
            let m = i as f64 * 10.0;
            s = g.step(at(m, 10.0), prev, 1.0);
            prev = m;
        }
        assert_eq!(g.phase(), CouplingPhase::InSync);
        assert!((s.p - 7200.0).abs() < 1e-9, "{}", s.p);
    }

    #[test]
    fn a_transition_speeds_up_with_accel_and_slows_down_with_decel() {
        // HMC_SetGearTransationSwitch (digest 000 §4.3): accel 10 up to ratio 2 × master 5.
        let clutch = Clutch::Transition {
            accel: 10.0,
            decel: 2.0,
        };
        let mut g = Gear::new(2.0, 1.0, clutch, None, 0.0, MotionState::default());
        let dt = 0.01;
        let (mut m, mut prev) = (0.0, 0.0);
        let mut until_in_sync = |g: &mut Gear| {
            for tick in 1..1000 {
                m += 5.0 * dt;
                let s = g.step(at(m, 5.0), prev, dt);
                prev = m;
                if g.phase() == CouplingPhase::InSync {
                    return (tick, s.v);
                }
            }
            (0, 0.0)
        };
        // 0 → 10 at accel 10: 1 s, 100 ticks (one more where rounding leaves a last ulp).
        let (ticks, v) = until_in_sync(&mut g);
        assert!((100..=101).contains(&ticks), "{ticks}");
        assert!((v - 10.0).abs() < 1e-9, "{v}");
        // Ratio 1: 10 → 5 at decel 2 takes 2.5 s.
        g.set_ratio(1.0, 1.0);
        assert_eq!(g.phase(), CouplingPhase::Engaging);
        let (ticks, v) = until_in_sync(&mut g);
        assert!((250..=251).contains(&ticks), "{ticks}");
        assert!((v - 5.0).abs() < 1e-9, "{v}");
    }

    #[test]
    fn the_direction_filter_ignores_master_travel_the_other_way() {
        let mut g = Gear::new(
            2.0,
            1.0,
            Clutch::Immediate,
            Some(Direction::Positive),
            0.0,
            MotionState::default(),
        );
        let mut prev = 0.0;
        let mut s = MotionState::default();
        for m in [1.0, 2.0, 1.0, 0.0, 1.0] {
            s = g.step(at(m, 0.0), prev, 1.0);
            prev = m;
        }
        assert_eq!(s.p, 6.0);
    }
}
