//! Limit and home switches computed from the motor's physical position (ARCHITECTURE §3.3
//! step 6), with debounce. Inversion (active-low wiring) is the controller's business and lives
//! in the axis, since the parameters that choose it are the controller's.

use crate::config::{HomeSwitchConfig, SwitchConfig};

/// Where a switch changed level during a tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge {
    /// Physical position of the change (exact, as an FPGA capture would latch it).
    pub position: f64,
    /// true: became active.
    pub rising: bool,
}

/// Debounce: the output follows the input only after it has been stable for `ticks` ticks.
#[derive(Clone, Copy, Debug, Default)]
pub struct Debounce {
    ticks: u32,
    output: bool,
    candidate: bool,
    stable_for: u32,
}

impl Debounce {
    pub fn new(ticks: u32, initial: bool) -> Debounce {
        Debounce {
            ticks,
            output: initial,
            candidate: initial,
            stable_for: 0,
        }
    }

    pub fn update(&mut self, input: bool) -> bool {
        if self.ticks == 0 {
            self.output = input;
            return input;
        }
        if input != self.candidate {
            self.candidate = input;
            self.stable_for = 0;
        }
        if self.candidate != self.output {
            self.stable_for += 1;
            if self.stable_for >= self.ticks {
                self.output = self.candidate;
            }
        }
        self.output
    }

    pub fn output(&self) -> bool {
        self.output
    }
}

/// A limit switch: active beyond `position` in its direction.
#[derive(Clone, Debug)]
pub struct LimitSwitch {
    position: f64,
    positive: bool,
    filter: Debounce,
}

impl LimitSwitch {
    pub fn new(config: &SwitchConfig, positive: bool, motor: f64) -> LimitSwitch {
        let mut s = LimitSwitch {
            position: config.position,
            positive,
            filter: Debounce::new(config.filter, false),
        };
        let raw = s.raw(motor);
        s.filter = Debounce::new(config.filter, raw);
        s
    }

    fn raw(&self, motor: f64) -> bool {
        if self.positive {
            motor >= self.position
        } else {
            motor <= self.position
        }
    }

    /// Level after the motor moved from `from` to `to`, and the exact raw edge if it was crossed.
    pub fn update(&mut self, from: f64, to: f64) -> (bool, Option<Edge>) {
        let (before, after) = (self.raw(from), self.raw(to));
        let edge = (before != after).then_some(Edge {
            position: self.position,
            rising: after,
        });
        (self.filter.update(after), edge)
    }

    pub fn level(&self) -> bool {
        self.filter.output()
    }
}

/// A home switch active on `[low, high]`.
#[derive(Clone, Debug)]
pub struct HomeSwitch {
    low: f64,
    high: f64,
    filter: Debounce,
}

impl HomeSwitch {
    pub fn new(config: &HomeSwitchConfig, motor: f64) -> HomeSwitch {
        let mut s = HomeSwitch {
            low: config.low,
            high: config.high,
            filter: Debounce::new(config.filter, false),
        };
        let raw = s.raw(motor);
        s.filter = Debounce::new(config.filter, raw);
        s
    }

    fn raw(&self, motor: f64) -> bool {
        self.low <= motor && motor <= self.high
    }

    /// Level after the motor moved from `from` to `to`, and the first raw edge crossed in the
    /// direction of travel (a narrow cam can be crossed entirely within one tick).
    pub fn update(&mut self, from: f64, to: f64) -> (bool, Option<Edge>) {
        // Active on [low, high]: entering moving up happens at `low`, leaving at just past `high`.
        let edge = if to > from {
            if from < self.low && self.low <= to {
                Some(Edge {
                    position: self.low,
                    rising: true,
                })
            } else if from <= self.high && self.high < to {
                Some(Edge {
                    position: self.high,
                    rising: false,
                })
            } else {
                None
            }
        } else if to < from {
            if to <= self.high && self.high < from {
                Some(Edge {
                    position: self.high,
                    rising: true,
                })
            } else if to < self.low && self.low <= from {
                Some(Edge {
                    position: self.low,
                    rising: false,
                })
            } else {
                None
            }
        } else {
            None
        };
        (self.filter.update(self.raw(to)), edge)
    }

    pub fn level(&self) -> bool {
        self.filter.output()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn debounce_needs_stable_ticks() {
        let mut d = Debounce::new(3, false);
        assert!(!d.update(true));
        assert!(!d.update(true));
        assert!(d.update(true));
        assert!(d.update(false)); // one glitch does not pass
        assert!(d.update(true));
        assert!(d.update(false));
        assert!(d.update(false));
        assert!(!d.update(false));
    }

    #[test]
    fn limit_edges_and_levels() {
        let cfg = SwitchConfig {
            position: 100.0,
            filter: 0,
            active_low: false,
        };
        let mut s = LimitSwitch::new(&cfg, true, 0.0);
        assert!(!s.level());
        assert_eq!(s.update(0.0, 99.0), (false, None));
        let (level, edge) = s.update(99.0, 101.0);
        assert!(level);
        assert_eq!(
            edge,
            Some(Edge {
                position: 100.0,
                rising: true
            })
        );
        let (level, edge) = s.update(101.0, 98.0);
        assert!(!level);
        assert!(!edge.unwrap().rising);
        let mut n = LimitSwitch::new(
            &SwitchConfig {
                position: -5.0,
                filter: 0,
                active_low: false,
            },
            false,
            -6.0,
        );
        assert!(n.level());
        assert!(!n.update(-6.0, 0.0).0);
    }

    #[test]
    fn home_cam_edges_in_both_directions() {
        let cfg = HomeSwitchConfig {
            low: 10.0,
            high: 20.0,
            filter: 0,
            active_low: false,
        };
        let mut h = HomeSwitch::new(&cfg, 0.0);
        let (l, e) = h.update(0.0, 12.0);
        assert!(l);
        assert_eq!(
            e,
            Some(Edge {
                position: 10.0,
                rising: true
            })
        );
        let (l, e) = h.update(12.0, 25.0);
        assert!(!l);
        assert_eq!(
            e,
            Some(Edge {
                position: 20.0,
                rising: false
            })
        );
        let (_, e) = h.update(25.0, 15.0);
        assert_eq!(
            e,
            Some(Edge {
                position: 20.0,
                rising: true
            })
        );
        // Crossing the whole cam in one tick reports the near edge.
        let (l, e) = h.update(15.0, 0.0);
        assert!(!l);
        assert_eq!(
            e,
            Some(Edge {
                position: 10.0,
                rising: false
            })
        );
        let (l, e) = h.update(0.0, 30.0);
        assert!(!l);
        assert_eq!(
            e,
            Some(Edge {
                position: 10.0,
                rising: true
            })
        );
    }

    #[test]
    fn one_sided_home_switch() {
        let cfg = HomeSwitchConfig {
            low: 50.0,
            high: f64::INFINITY,
            filter: 0,
            active_low: false,
        };
        let mut h = HomeSwitch::new(&cfg, 100.0);
        assert!(h.level());
        let (l, e) = h.update(100.0, 40.0);
        assert!(!l);
        assert_eq!(
            e,
            Some(Edge {
                position: 50.0,
                rising: false
            })
        );
    }
}
