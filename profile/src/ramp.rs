//! Velocity ramps, the building block of every profile.
//!
//! Everything here works in the planner's normalised units (velocity limit 1, acceleration
//! limit 1, positions relative to the start; see `plan`), so the few tolerances are absolute.

/// One phase of constant jerk `j` and duration `t`, with the velocity `v` and acceleration `a`
/// at its start. Stating them rather than integrating them lets a trapezoid jump in
/// acceleration, and puts reversals exactly at v = 0 and cruises exactly at the limit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Phase {
    pub v: f64,
    pub a: f64,
    pub j: f64,
    pub t: f64,
}

impl Phase {
    /// Position and velocity change over the whole phase.
    #[inline]
    pub fn advance(&self) -> (f64, f64) {
        self.advance_by(self.t)
    }

    /// Position and velocity change after `t` into the phase.
    #[inline]
    pub fn advance_by(&self, t: f64) -> (f64, f64) {
        let dp = t * (self.v + t * (0.5 * self.a + t * self.j * (1.0 / 6.0)));
        let dv = t * (self.a + 0.5 * t * self.j);
        (dp, dv)
    }
}

/// Normalised limits. `jerk` may be infinite (trapezoid). The inverses turn the divisions of
/// the hot path into multiplications.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lim {
    pub vmax: f64,
    pub acc: f64,
    pub dec: f64,
    pub jerk: f64,
    inv_acc: f64,
    inv_dec: f64,
    /// 1/jerk, 0 for a trapezoid.
    inv_jerk: f64,
}

impl Lim {
    pub fn new(vmax: f64, acc: f64, dec: f64, jerk: f64) -> Lim {
        Lim {
            vmax,
            acc,
            dec,
            jerk,
            inv_acc: 1.0 / acc,
            inv_dec: 1.0 / dec,
            inv_jerk: 1.0 / jerk,
        }
    }

    /// Velocity reached by bringing `a` to zero at full jerk (with infinite jerk `a` just
    /// vanishes).
    #[inline]
    pub fn v_stop(&self, v: f64, a: f64) -> f64 {
        v + 0.5 * a * a.abs() * self.inv_jerk
    }

    #[inline]
    pub fn inv_jerk(&self) -> f64 {
        self.inv_jerk
    }

    /// The plateau, and its inverse, of a ramp from `v_stop` to `v1`: acceleration while |v|
    /// grows, deceleration while it shrinks.
    #[inline]
    pub fn plateau(&self, v_stop: f64, v1: f64) -> (f64, f64) {
        if (v1 - v_stop) * v1 > 0.0 {
            (self.acc, self.inv_acc)
        } else {
            (self.dec, self.inv_dec)
        }
    }
}

/// The time-optimal move from `(v0, a0)` to `(v1, 0)` under one acceleration limit: raise (or
/// lower) the acceleration to the peak, hold it, bring it back to zero. Phases may have zero
/// length.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Ramp {
    pub phases: [Phase; 3],
    /// Magnitude of the acceleration plateau or triangle peak (0 when only `a0` is removed).
    pub peak: f64,
    /// +1 when the velocity rises towards `v1`, −1 when it falls, 0 when only `a0` is removed.
    pub dir: f64,
}

impl Ramp {
    /// Distance covered.
    #[inline]
    pub fn distance(&self) -> f64 {
        self.phases.iter().map(|ph| ph.advance().0).sum()
    }
}

/// See [`Ramp`]. `amax > 0` with its inverse `inv_amax`; the jerk comes from `lim`.
#[inline(always)]
pub(crate) fn ramp(v0: f64, a0: f64, v1: f64, amax: f64, inv_amax: f64, lim: &Lim) -> Ramp {
    let (jerk, inv_jerk) = (lim.jerk, lim.inv_jerk);
    const NONE: Phase = Phase {
        v: 0.0,
        a: 0.0,
        j: 0.0,
        t: 0.0,
    };
    if !jerk.is_finite() {
        // Trapezoid: the acceleration jumps, so `a0` does not matter.
        let dv = v1 - v0;
        let dir = if dv > 0.0 {
            1.0
        } else if dv < 0.0 {
            -1.0
        } else {
            0.0
        };
        return Ramp {
            phases: [
                Phase {
                    v: v0,
                    a: dir * amax,
                    j: 0.0,
                    t: dv.abs() * inv_amax,
                },
                NONE,
                NONE,
            ],
            peak: amax,
            dir,
        };
    }
    let v_stop = v0 + 0.5 * a0 * a0.abs() * inv_jerk;
    let gap = v1 - v_stop;
    if gap == 0.0 || !gap.is_finite() {
        // Removing a0 lands exactly on v1 (or the input is unusable: a NaN phase is caught by
        // the caller's finiteness check).
        let j = if a0 > 0.0 { -jerk } else { jerk };
        return Ramp {
            phases: [
                Phase {
                    v: v0,
                    a: a0,
                    j,
                    t: a0.abs() * inv_jerk,
                },
                NONE,
                NONE,
            ],
            peak: 0.0,
            dir: 0.0,
        };
    }
    // Work in the ramp's direction: the velocity rises by `dvu` and the acceleration starts
    // at `au`; v1 lies beyond v_stop, so the peak is at least max(au, 0).
    let s = if gap > 0.0 { 1.0 } else { -1.0 };
    let au = s * a0;
    let dvu = s * (v1 - v0);
    let (ap, t1, j1, plateau) = if au >= amax {
        // Beyond the limit (lowered mid-move): come back to it at full jerk first.
        (amax, (au - amax) * inv_jerk, -1.0, true)
    } else {
        let tri = (jerk * dvu + 0.5 * au * au).max(0.0).sqrt();
        if tri < amax {
            (tri, (tri - au) * inv_jerk, 1.0, false)
        } else {
            (amax, (amax - au) * inv_jerk, 1.0, true)
        }
    };
    let t3 = ap * inv_jerk;
    let dv1 = 0.5 * (au + ap) * t1;
    let dv3 = 0.5 * ap * t3;
    let t2 = if plateau {
        ((dvu - dv1 - dv3) * inv_amax).max(0.0)
    } else {
        0.0
    };
    Ramp {
        phases: [
            Phase {
                v: v0,
                a: a0,
                j: s * j1 * jerk,
                t: t1,
            },
            Phase {
                v: v0 + s * dv1,
                a: s * ap,
                j: 0.0,
                t: t2,
            },
            Phase {
                // Counted back from v1, so that the ramp ends on it.
                v: v1 - s * dv3,
                a: s * ap,
                j: -s * jerk,
                t: t3,
            },
        ],
        peak: ap,
        dir: s,
    }
}

/// A velocity change with the vendor rule for acceleration vs deceleration: the acceleration
/// limit applies while |v| grows and the deceleration limit while it shrinks. A change through
/// v = 0 with different limits is split at v = 0 (brake to rest, then accelerate: HMC
/// MoveModify "decelerate to a stop, then reverse", digest 000 §4.2); with equal limits it is
/// one time-optimal ramp through zero.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Change {
    pub ramps: [Ramp; 2],
    pub split: bool,
}

impl Change {
    /// The ramp whose end velocity is the change's end velocity.
    #[inline]
    pub fn last(&self) -> &Ramp {
        if self.split {
            &self.ramps[1]
        } else {
            &self.ramps[0]
        }
    }

    /// The ramp that starts at the change's start state.
    #[inline]
    pub fn first(&self) -> &Ramp {
        &self.ramps[0]
    }

    /// Distance covered.
    #[inline]
    pub fn distance(&self) -> f64 {
        let d = self.ramps[0].distance();
        if self.split {
            d + self.ramps[1].distance()
        } else {
            d
        }
    }

    /// The phases in order.
    pub fn phases(&self) -> impl Iterator<Item = &Phase> {
        let n = if self.split { 2 } else { 1 };
        self.ramps[..n].iter().flat_map(|r| r.phases.iter())
    }
}

/// See [`Change`].
#[inline(always)]
pub(crate) fn change(v0: f64, a0: f64, v1: f64, lim: &Lim) -> Change {
    let v_stop = lim.v_stop(v0, a0);
    if lim.acc != lim.dec && v_stop * v1 < 0.0 {
        Change {
            ramps: [
                ramp(v0, a0, 0.0, lim.dec, lim.inv_dec, lim),
                ramp(0.0, 0.0, v1, lim.acc, lim.inv_acc, lim),
            ],
            split: true,
        }
    } else {
        // |v| grows on the way from v_stop to v1 iff v1 lies beyond v_stop, away from zero.
        let (amax, inv) = lim.plateau(v_stop, v1);
        Change {
            ramps: [ramp(v0, a0, v1, amax, inv, lim), Ramp::default()],
            split: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn end_state(r: &Ramp) -> (f64, f64) {
        let mut v = r.phases[0].v;
        let mut a = r.phases[0].a;
        for ph in &r.phases {
            assert!((ph.v - v).abs() < 1e-12, "{ph:?} starts at {v}");
            v = ph.v + ph.advance().1;
            a = ph.a + ph.j * ph.t;
        }
        (v, a)
    }

    #[test]
    fn ramps_end_at_the_target_velocity_with_zero_acceleration() {
        let cases = [
            (0.0, 0.0, 1.0, 1.0, 10.0),
            (0.0, 0.0, 1.0, 1.0, 0.5),
            (1.0, 0.5, -1.0, 0.7, 3.0),
            (0.3, -2.0, 1.0, 1.0, 3.0),
            (0.3, 2.0, 0.0, 1.0, 3.0),
            (0.0, 3.0, 0.5, 1.0, 2.0),
        ];
        for (v0, a0, v1, amax, j) in cases {
            let r = ramp(v0, a0, v1, amax, 1.0 / amax, &Lim::new(1.0, amax, amax, j));
            let (v, a) = end_state(&r);
            assert!((v - v1).abs() < 1e-12, "{v0} {a0} {v1}: v = {v}");
            assert!(a.abs() < 1e-12, "{v0} {a0} {v1}: a = {a}");
            assert!(r.phases.iter().all(|p| p.t >= 0.0));
        }
    }

    #[test]
    fn triangle_and_trapezoid_ramps_from_rest() {
        // Plateau: 0 → 2 with a = 1, j = 10: t1 = t3 = 0.1, t2 = 1.9.
        let lim = Lim::new(1.0, 1.0, 1.0, 10.0);
        let r = ramp(0.0, 0.0, 2.0, 1.0, 1.0, &lim);
        assert!((r.phases[1].t - 1.9).abs() < 1e-12);
        // Triangle: 0 → 0.01 with a = 1, j = 10: peak sqrt(0.1).
        let r = ramp(0.0, 0.0, 0.01, 1.0, 1.0, &lim);
        assert!((r.peak - 0.1f64.sqrt()).abs() < 1e-12);
        assert_eq!(r.phases[1].t, 0.0);
    }

    #[test]
    fn reversal_is_split_only_when_limits_differ() {
        let equal = Lim::new(1.0, 1.0, 1.0, f64::INFINITY);
        assert!(!change(0.5, 0.0, -0.5, &equal).split);
        let unequal = Lim::new(1.0, 1.0, 2.0, f64::INFINITY);
        let c = change(0.5, 0.0, -0.5, &unequal);
        assert!(c.split);
        // Brake 0.5 at 2 (0.25 s), accelerate 0.5 at 1 (0.5 s).
        assert_eq!(c.ramps[0].phases[0].t, 0.25);
        assert_eq!(c.ramps[1].phases[0].t, 0.5);
        assert_eq!(c.distance(), 0.0625 - 0.125);
        assert_eq!(c.ramps[1].phases[0].v, 0.0);
    }
}
