//! Limit and home switches computed from the motor's physical position (ARCHITECTURE §3.3
//! step 6), with debounce. Inversion (active-low wiring) is the controller's business and lives
//! in the axis, since the parameters that choose it are the controller's.

use serde::{Deserialize, Serialize};

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

    /// No change is pending: with a steady input, `update` changes nothing.
    pub fn settled(&self) -> bool {
        self.candidate == self.output
    }
}

/// A limit switch: active beyond `position` in its direction.
#[derive(Clone, Debug)]
pub struct LimitSwitch {
    position: f64,
    positive: bool,
    filter: Debounce,
    /// Raw level at the end of the last update.
    raw_level: bool,
}

impl LimitSwitch {
    pub fn new(config: &SwitchConfig, positive: bool, motor: f64) -> LimitSwitch {
        let mut s = LimitSwitch {
            position: config.position,
            positive,
            filter: Debounce::new(config.filter, false),
            raw_level: false,
        };
        let raw = s.raw(motor);
        s.filter = Debounce::new(config.filter, raw);
        s.raw_level = raw;
        s
    }

    fn raw(&self, motor: f64) -> bool {
        if self.positive {
            motor >= self.position
        } else {
            motor <= self.position
        }
    }

    /// Level after the motor moved to `to` (from where the last update left it), and the exact
    /// raw edge if one was crossed.
    pub fn update(&mut self, to: f64) -> (bool, Option<Edge>) {
        let (before, after) = (self.raw_level, self.raw(to));
        self.raw_level = after;
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

/// The levels and exact edges of an axis's switches after one tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SwitchTick {
    pub limit_pos: bool,
    pub limit_neg: bool,
    pub home: bool,
    pub limit_pos_edge: Option<Edge>,
    pub limit_neg_edge: Option<Edge>,
    pub home_edge: Option<Edge>,
}

/// All switches of one axis. Their levels change only where the motor crosses one of a few
/// boundary positions, so between two boundaries (and with every debounce settled) a tick
/// costs two comparisons instead of updating each switch.
#[derive(Clone, Debug)]
pub struct Switches {
    limit_pos: Option<LimitSwitch>,
    limit_neg: Option<LimitSwitch>,
    home: Option<HomeSwitch>,
    /// Open interval of motor positions around the last one in which no raw level changes.
    quiet: (f64, f64),
    last: SwitchTick,
}

impl Switches {
    pub fn new(config: &SwitchesConfig, motor: f64) -> Switches {
        let mut s = Switches {
            limit_pos: config
                .limit_pos
                .as_ref()
                .map(|c| LimitSwitch::new(c, true, motor)),
            limit_neg: config
                .limit_neg
                .as_ref()
                .map(|c| LimitSwitch::new(c, false, motor)),
            home: config.home.as_ref().map(|c| HomeSwitch::new(c, motor)),
            quiet: (motor, motor),
            last: SwitchTick::default(),
        };
        s.last = SwitchTick {
            limit_pos: s.limit_pos.as_ref().is_some_and(LimitSwitch::level),
            limit_neg: s.limit_neg.as_ref().is_some_and(LimitSwitch::level),
            home: s.home.as_ref().is_some_and(HomeSwitch::level),
            ..SwitchTick::default()
        };
        s.quiet = s.quiet_zone(motor);
        s
    }

    pub fn has_limit_pos(&self) -> bool {
        self.limit_pos.is_some()
    }

    pub fn has_limit_neg(&self) -> bool {
        self.limit_neg.is_some()
    }

    pub fn has_home(&self) -> bool {
        self.home.is_some()
    }

    /// The motor moved from `from` (where the last update left it) to `to`.
    #[inline]
    pub fn update(&mut self, from: f64, to: f64) -> SwitchTick {
        let (lo, hi) = self.quiet;
        if lo < to && to < hi {
            return SwitchTick {
                limit_pos_edge: None,
                limit_neg_edge: None,
                home_edge: None,
                ..self.last
            };
        }
        self.update_all(from, to)
    }

    #[inline(never)]
    fn update_all(&mut self, from: f64, to: f64) -> SwitchTick {
        let mut t = SwitchTick::default();
        if let Some(s) = self.limit_pos.as_mut() {
            (t.limit_pos, t.limit_pos_edge) = s.update(to);
        }
        if let Some(s) = self.limit_neg.as_mut() {
            (t.limit_neg, t.limit_neg_edge) = s.update(to);
        }
        if let Some(s) = self.home.as_mut() {
            (t.home, t.home_edge) = s.update(from, to);
        }
        self.last = t;
        self.quiet = self.quiet_zone(to);
        t
    }

    /// The open interval around `p` free of switch boundaries, or an empty one while a
    /// debounce is still counting (every tick must then reach it).
    fn quiet_zone(&self, p: f64) -> (f64, f64) {
        let settled = self.limit_pos.as_ref().is_none_or(|s| s.filter.settled())
            && self.limit_neg.as_ref().is_none_or(|s| s.filter.settled())
            && self.home.as_ref().is_none_or(|s| s.filter.settled());
        if !settled {
            return (p, p);
        }
        let mut lo = f64::NEG_INFINITY;
        let mut hi = f64::INFINITY;
        let bounds = [
            self.limit_pos.as_ref().map(|s| s.position),
            self.limit_neg.as_ref().map(|s| s.position),
            self.home.as_ref().map(|s| s.low),
            self.home.as_ref().map(|s| s.high),
        ];
        for b in bounds.into_iter().flatten() {
            if b <= p && b > lo {
                lo = b;
            }
            if b >= p && b < hi {
                hi = b;
            }
        }
        (lo, hi)
    }
}

/// Limit and home switches, computed from the actual position.
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SwitchesConfig {
    /// Positive limit: active for actual position ≥ `position`.
    pub limit_pos: Option<SwitchConfig>,
    /// Negative limit: active for actual position ≤ `position`.
    pub limit_neg: Option<SwitchConfig>,
    /// Home switch (a cam): active for actual position in `[low, high]`.
    pub home: Option<HomeSwitchConfig>,
}

#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SwitchConfig {
    /// Actual position (user units) where the switch becomes active.
    pub position: f64,
    /// The sensor outputs low while actuated (normally-closed wiring). The controller's
    /// `*_invert` parameter must match, or the input reads inverted — as on a real machine.
    #[serde(default)]
    pub active_low: bool,
    /// Ticks the raw level must be stable before the input follows it (debounce).
    #[serde(default)]
    pub filter: u32,
}

/// A home switch active on `[low, high]` (a cam). Leave one bound out for a switch that stays
/// active to that side (CiA 402 "positive/negative home switch").
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HomeSwitchConfig {
    /// Lower end of the active range, user units; omitted: unbounded (active to −∞).
    #[serde(default = "neg_inf")]
    pub low: f64,
    /// Upper end of the active range, user units; omitted: unbounded (active to +∞).
    #[serde(default = "pos_inf")]
    pub high: f64,
    /// The sensor outputs low while actuated; `home_invert` must match.
    #[serde(default)]
    pub active_low: bool,
    /// Ticks the raw level must be stable before the input follows it (debounce).
    #[serde(default)]
    pub filter: u32,
}

fn neg_inf() -> f64 {
    f64::NEG_INFINITY
}
fn pos_inf() -> f64 {
    f64::INFINITY
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
        assert_eq!(s.update(99.0), (false, None));
        let (level, edge) = s.update(101.0);
        assert!(level);
        assert_eq!(
            edge,
            Some(Edge {
                position: 100.0,
                rising: true
            })
        );
        let (level, edge) = s.update(98.0);
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
        assert!(!n.update(0.0).0);
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

#[cfg(test)]
mod quiet_zone_tests {
    use super::*;
    use crate::rng::Rng;

    /// The shortcut must never change what the switches report: compare against updating
    /// every switch every tick, on random walks across all boundaries, with debounce.
    #[test]
    fn the_quiet_zone_never_changes_levels_or_edges() {
        let config = SwitchesConfig {
            limit_pos: Some(SwitchConfig {
                position: 50.0,
                filter: 2,
                active_low: false,
            }),
            limit_neg: Some(SwitchConfig {
                position: -50.0,
                filter: 0,
                active_low: false,
            }),
            home: Some(HomeSwitchConfig {
                low: 10.0,
                high: 12.0,
                filter: 3,
                active_low: false,
            }),
        };
        let mut fast = Switches::new(&config, 0.0);
        let mut slow = Switches::new(&config, 0.0);
        let mut r = Rng::new(5);
        let mut p = 0.0;
        for _ in 0..200_000 {
            let step = match r.next_u64() % 3 {
                0 => r.next_signed() * 0.3,
                1 => r.next_signed() * 3.0,
                _ => 0.0,
            };
            let next = (p + step).clamp(-70.0, 70.0);
            let a = fast.update(p, next);
            let b = slow.update_all(p, next);
            assert_eq!(a, b, "{p} → {next}");
            p = next;
        }
    }
}
