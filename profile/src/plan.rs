//! The planner proper, in normalised units (velocity limit 1, acceleration limit 1, start at
//! position 0; `mod.rs` scales in and out).
//!
//! A position profile is ramp 1 `(v0, a0) → (vp, 0)`, an optional cruise at `vp`, and ramp 2
//! `(vp, 0) → (e, 0)`. The frame is chosen so that the target lies beyond the point where
//! braking now would stop (the final approach comes from that side, which also fixes the sign
//! of the end velocity `e`), and mirrored once more if the target is short of the direct ramp
//! `(v0, a0) → e` (the axis must dip below `e` or back up for run-up). Then the peak `vp` lies
//! in `[lo, vmax]` with `lo = max(v_stop, e)`, the distance `D(vp)` grows with `vp` (for
//! `vp ≥ 0`), and beyond `D(vmax)` the profile cruises at `vmax`.
//!
//! One family is not of this shape: when `a0` already brakes towards `e`
//! (`a0 < 0`, `v_stop > e`), distances between the direct ramp and `D(v_stop)` need the brake
//! partly released first (`a0 → a1 ∈ [a0, 0]` at full jerk, then the ramp to `e`): the
//! release branch. Arriving with a negative velocity, a release profile can also beat the
//! peak-velocity one beyond `D(v_stop)`; both are then planned and the faster kept. Together
//! these are Ruckig's UDDU/UDUD profile types for a target at rest acceleration, and the
//! durations agree with rsruckig to about 1e-11 (see `tests_ruckig`).
//!
//! `D(vp) = d` is solved by a safeguarded Newton iteration in `u = sqrt(vp − lo)` (the ramps
//! have square-root terms at `lo` that this makes smooth), started from the plateau model
//! (exact for trapezoids and long moves) or, for short moves, from the cubic of two triangular
//! ramps. `D` is evaluated in closed form from ramp symmetry where possible. The release
//! branch uses Brent's method. Every loop is bounded.

use super::ramp::{change, Change, Lim, Phase};

/// Ramp 1 (≤ 6 phases when split at v = 0) + cruise + ramp 2 (≤ 6).
pub(crate) const MAX_PHASES: usize = 13;

pub(super) const MAX_ITER: usize = 100;

/// A planned sequence of phases, from the start state.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plan {
    phases: [Phase; MAX_PHASES],
    len: usize,
    /// Velocity at the end, exactly where the plan knows it.
    end_v: f64,
}

impl Plan {
    pub fn new() -> Plan {
        Plan {
            phases: [Phase::default(); MAX_PHASES],
            len: 0,
            end_v: 0.0,
        }
    }

    pub(super) fn clear(&mut self) {
        self.len = 0;
        self.end_v = 0.0;
    }

    pub fn phases(&self) -> &[Phase] {
        self.phases.get(..self.len).unwrap_or(&[])
    }

    /// Appends a phase; empty phases are dropped. The capacity covers every plan shape.
    pub(super) fn push(&mut self, ph: Phase) {
        if ph.t > 0.0 {
            if let Some(slot) = self.phases.get_mut(self.len) {
                *slot = ph;
                self.len += 1;
            }
        }
    }

    /// Appends a velocity change that ends at `v1`.
    pub(super) fn push_change(&mut self, c: &Change, v1: f64) {
        for ph in c.phases() {
            self.push(*ph);
        }
        self.end_v = v1;
    }

    fn mirror(&mut self) {
        for ph in self.phases.iter_mut().take(self.len) {
            ph.v = -ph.v;
            ph.a = -ph.a;
            ph.j = -ph.j;
        }
        self.end_v = -self.end_v;
    }

    pub fn end_velocity(&self) -> f64 {
        self.end_v
    }

    /// Total duration.
    pub fn duration(&self) -> f64 {
        self.phases().iter().map(|p| p.t).sum()
    }

    /// Position at the end.
    pub fn end_position(&self) -> f64 {
        self.phases().iter().map(|ph| ph.advance().0).sum()
    }
}

/// Velocity goal: one velocity change.
pub(crate) fn velocity(v0: f64, a0: f64, target: f64, lim: &Lim, out: &mut Plan) {
    out.clear();
    out.push_change(&change(v0, a0, target, lim), target);
}

/// Position goal at distance `d`, arriving with speed `e ≥ 0` in the direction of the final
/// approach. With `jump_to_zero`, a target that braking would pass ends the plan where the
/// braking profile reaches it (HMC §2.3.1).
#[allow(clippy::too_many_arguments)]
pub(crate) fn position(
    v0: f64,
    a0: f64,
    d: f64,
    e: f64,
    lim: &Lim,
    jump_to_zero: bool,
    forward: bool,
    out: &mut Plan,
) {
    out.clear();
    let brake = change(v0, a0, 0.0, lim);
    let d_brake = brake.distance();
    // The final approach comes from the side of the stopping point: the frame `sigma` makes
    // the target lie ahead of it. `forward` (Profile::plan_passing): from the start's side
    // whenever the end velocity is not 0.
    let below = if forward && e != 0.0 {
        d < 0.0
    } else {
        d < d_brake || (d == d_brake && lim.v_stop(v0, a0) < 0.0)
    };
    let sigma = if below { -1.0 } else { 1.0 };
    if jump_to_zero && sigma * d < 0.0 && sigma * d_brake < sigma * d {
        // Braking passes the target (it lies between here and the stopping point).
        truncated(&brake, d, out);
        return;
    }
    let (v0, a0, d) = (sigma * v0, sigma * a0, sigma * d);
    let d_direct = if e == 0.0 {
        // The planner is symmetric: negating the state negates the distance exactly.
        sigma * d_brake
    } else {
        change(v0, a0, e, lim).distance()
    };
    let m = if d < d_direct { -1.0 } else { 1.0 };
    Branch {
        v0: m * v0,
        a0: m * a0,
        e: m * e,
        d_direct: m * d_direct,
        lim: *lim,
    }
    .plan(m * d, out);
    if sigma * m < 0.0 {
        out.mirror();
    }
}

/// The braking profile cut where it reaches `d`.
fn truncated(brake: &Change, d: f64, out: &mut Plan) {
    let s = if d < 0.0 { -1.0 } else { 1.0 };
    let mut p = 0.0;
    for ph in brake.phases() {
        if ph.t <= 0.0 {
            continue;
        }
        let (dp, _) = ph.advance();
        if s * (p + dp - d) >= 0.0 {
            // First phase that reaches d: p − d changes sign once in it (the velocity reverses
            // at most once while braking), so bisection finds the crossing.
            let (mut lo, mut hi) = (0.0, ph.t);
            for _ in 0..MAX_ITER {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if s * (p + ph.advance_by(mid).0 - d) >= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            out.push(Phase { t: hi, ..*ph });
            out.end_v = ph.v + ph.advance_by(hi).1;
            return;
        }
        out.push(*ph);
        p += dp;
    }
}

/// The position problem in a frame where `d ≥` the direct-ramp distance.
struct Branch {
    v0: f64,
    a0: f64,
    e: f64,
    /// Distance of the direct ramp (v0, a0) → e.
    d_direct: f64,
    lim: Lim,
}

/// D(vp) and its slope in u (vp = lo + u²).
struct Measure {
    d: f64,
    /// Sum of the magnitudes added up in `d` (for the achievable precision).
    mag: f64,
    /// ∂D/∂u.
    du: f64,
}

impl Branch {
    /// D(vp) and ∂D/∂u at vp = lo + u².
    #[inline]
    fn measure(&self, vp: f64, u: f64) -> Measure {
        if let Some(m) = self.measure_symmetric(vp, u) {
            return m;
        }
        let lim = &self.lim;
        let c1 = change(self.v0, self.a0, vp, lim);
        let c2 = change(vp, 0.0, self.e, lim);
        let d1 = c1.distance();
        let d2 = c2.distance();
        let (r1, r2) = (c1.last(), c2.first());
        Measure {
            d: d1 + d2,
            mag: d1.abs() + d2.abs(),
            du: slope_u((r1.peak, r1.dir), vp, u, 1.0, lim)
                + slope_u((r2.peak, r2.dir), vp, u, -1.0, lim),
        }
    }

    /// The same from the symmetry of ramps that start and end at a = 0, without building
    /// them: such a ramp covers (v_from + v_to)/2 × its duration. Ramp 1 is one of them after
    /// removing a0 (a0 against the ramp) or before a virtual rise of a from 0 to a0 (a0 along
    /// it). None where that does not hold (split reversals, a0 beyond the plateau, trapezoids).
    #[inline]
    fn measure_symmetric(&self, vp: f64, u: f64) -> Option<Measure> {
        let lim = &self.lim;
        let (v0, a0, e) = (self.v0, self.a0, self.e);
        let v_stop = lim.v_stop(v0, a0);
        if lim.acc != lim.dec && (v_stop * vp < 0.0 || vp * e < 0.0) {
            return None;
        }
        let s1 = if vp >= v_stop { 1.0 } else { -1.0 };
        let plateau1 = lim.plateau(v_stop, vp);
        let au = s1 * a0;
        let (d1, du1, mag1) = if !lim.jerk.is_finite() {
            // Trapezoid: a0 does not matter.
            let (ds, dds) = symmetric(v0, vp, plateau1, u, lim);
            (ds, dds, ds.abs())
        } else if au <= 0.0 {
            // a0 → 0 at jerk s1·j, then the symmetric ramp from v_stop.
            let t = a0.abs() * lim.inv_jerk();
            let da = t * (v0 + t * (0.5 * a0 + t * s1 * lim.jerk / 6.0));
            let (ds, dds) = symmetric(v_stop, vp, plateau1, u, lim);
            (da + ds, dds, da.abs() + ds.abs())
        } else if au <= plateau1.0 {
            // The symmetric ramp from w, where a would have been 0, less that virtual rise.
            let tau = au * lim.inv_jerk();
            let w = v0 - 0.5 * s1 * a0 * a0 * lim.inv_jerk();
            let dv = tau * (w + s1 * lim.jerk * tau * tau / 6.0);
            let (ds, dds) = symmetric(w, vp, plateau1, u, lim);
            (ds - dv, dds, ds.abs() + dv.abs())
        } else {
            return None;
        };
        let (d2, du2) = symmetric(e, vp, lim.plateau(vp, e), u, lim);
        Some(Measure {
            d: d1 + d2,
            mag: mag1 + d2.abs(),
            du: du1 + du2,
        })
    }

    #[inline]
    fn distance(&self, vp: f64) -> f64 {
        self.measure(vp, 0.0).d
    }

    fn plan(&self, d: f64, out: &mut Plan) {
        let lim = &self.lim;
        let v_stop = lim.v_stop(self.v0, self.a0);
        let mut lo = if v_stop <= lim.vmax {
            v_stop.max(self.e)
        } else {
            // Faster than the limit: ramp 1 brakes down to vp ≤ vmax.
            self.e
        };
        // With lo = e, ramp 1 is the direct ramp and ramp 2 is empty.
        let mut d_lo = if lo == self.e {
            self.d_direct
        } else {
            self.distance(lo)
        };
        // The release family exists when a0 already brakes towards e.
        let release = lim.jerk.is_finite() && self.a0 < 0.0 && lo == v_stop && v_stop > self.e;
        if d < d_lo {
            if release {
                self.release(d, self.a0, 0.0, d_lo, out);
            } else {
                // Only rounding puts d below D(lo) otherwise: D(lo) is the direct ramp.
                self.build(lo, 0.0, d, out);
            }
            return;
        }
        if lo < 0.0 {
            // D grows with vp for vp ≥ 0 (and for vp below the start of ramp 1); between a
            // negative lo and 0 it need not. Search there only if the root is there.
            let d0 = self.distance(0.0);
            if d0 <= d {
                lo = 0.0;
                d_lo = d0;
            }
        }
        let d_hi = self.distance(lim.vmax);
        if d_hi <= d {
            self.build(lim.vmax, (d - d_hi) / lim.vmax, d, out);
        } else {
            let vp = self.solve(lo, d_lo, d, d_hi);
            self.build(vp, 0.0, d, out);
        }
        if release && self.e < 0.0 {
            // Arriving with a negative velocity, easing the brake can first gain distance and
            // then lose it (lengthening the profile costs |e| per second), so D_release may
            // exceed D(lo) in between: such a release profile can beat the upper one.
            let mut alt = Plan::new();
            if self.release_above(d, &mut alt) && alt.duration() < out.duration() {
                *out = alt;
            }
        }
    }

    /// The phases for peak `vp` and cruise time `cruise`; a cruise absorbs the rounding of
    /// the ramps so that the plan ends at `d`.
    fn build(&self, vp: f64, cruise: f64, d: f64, out: &mut Plan) {
        out.clear();
        out.push_change(&change(self.v0, self.a0, vp, &self.lim), vp);
        let at = out.len;
        out.push(Phase {
            v: vp,
            a: 0.0,
            j: 0.0,
            t: cruise,
        });
        let has_cruise = out.len > at;
        out.push_change(&change(vp, 0.0, self.e, &self.lim), self.e);
        if has_cruise && vp != 0.0 {
            let p_end = out.end_position();
            if let Some(ph) = out.phases.get_mut(at) {
                ph.t = (ph.t + (d - p_end) / vp).max(0.0);
            }
        }
    }

    /// Solves D(vp) = d for vp in [lo, vmax], given D(lo) = d_lo ≤ d < D(vmax) = d_hi.
    fn solve(&self, lo: f64, d_lo: f64, d: f64, d_hi: f64) -> f64 {
        let lim = &self.lim;
        // Where D would reach d if both ramps kept their acceleration plateaus A all the way
        // down from vmax: there dD/dvp = Σ (vp + A²/2j)/A, so
        // D(vmax) − D(vp) = k (vmax² − vp²) + c (vmax − vp) with k = Σ 1/2A, c = Σ A/2j.
        let k = 0.5 / lim.acc + 0.5 / lim.dec;
        if !lim.jerk.is_finite() && lo >= 0.0 {
            // Trapezoid: D(vp) = D(lo) + k (vp² − lo²) exactly on [lo, vmax]; counted from lo
            // so that short moves do not cancel.
            return (lo * lo + (d - d_lo).max(0.0) / k).sqrt().min(lim.vmax);
        }
        let ij = lim.inv_jerk();
        let c = 0.5 * (lim.acc + lim.dec) * ij;
        let b = 2.0 * k * lim.vmax + c;
        let excess = d_hi - d;
        let disc = b * b - 4.0 * k * excess;
        let back = if disc >= 0.0 {
            2.0 * excess / (b + disc.sqrt())
        } else {
            lim.vmax - lo
        };
        let guess = lim.vmax - back;
        // That model holds once both ramps reach their plateaus: ramp 2 from e + dec²/j on,
        // ramp 1 from (its symmetric start, see `measure_symmetric`) + acc²/j on.
        let plateau1 = if self.a0 >= lim.acc {
            f64::NEG_INFINITY
        } else if self.a0 <= 0.0 {
            lim.v_stop(self.v0, self.a0) + lim.acc * lim.acc * ij
        } else {
            self.v0 + (lim.acc * lim.acc - 0.5 * self.a0 * self.a0) * ij
        };
        let plateau2 = self.e + lim.dec * lim.dec * ij;
        let (mut ul, mut uh) = (0.0, (lim.vmax - lo).max(0.0).sqrt());
        let mut u = if guess >= plateau1.max(plateau2) {
            (guess - lo).max(0.0).sqrt()
        } else {
            // Shorter moves: as if both ramps were triangles starting at lo, where
            // D − D(lo) = (2/√j)(u³ + 2·lo·u); the one real root of that cubic (Cardano).
            let p = 2.0 * lo.max(0.0);
            let q = 0.5 * (d - d_lo).max(0.0) * lim.jerk.sqrt();
            let r = (0.25 * q * q + p * p * p / 27.0).sqrt();
            let cr = (0.5 * q + r).cbrt();
            if cr > 0.0 {
                cr - p / (3.0 * cr)
            } else {
                0.0
            }
        }
        .clamp(ul, uh);
        for _ in 0..MAX_ITER {
            let vp = lo + u * u;
            let m = self.measure(vp, u);
            let f = m.d - d;
            if f == 0.0 || f.abs() <= 2.0 * f64::EPSILON * m.mag {
                break;
            }
            if f < 0.0 {
                ul = u;
            } else {
                uh = u;
            }
            let mut next = u - f / m.du;
            if !(next > ul && next < uh) {
                next = 0.5 * (ul + uh);
            }
            if (next - u).abs() <= 2.0 * f64::EPSILON * next || uh - ul <= 2.0 * f64::EPSILON * uh {
                u = next;
                break;
            }
            u = next;
        }
        lo + u * u
    }

    /// Release family: a0 < 0 brakes towards e; the brake is eased to a1 ∈ [a0, 0] at full
    /// jerk, then the ramp to e follows. a1 = a0 is the direct ramp, a1 = 0 the upper branch
    /// at vp = v_stop.
    fn release_eval(&self, a1: f64) -> (Phase, Change, f64) {
        let (v0, a0, lim) = (self.v0, self.a0, &self.lim);
        let first = Phase {
            v: v0,
            a: a0,
            j: lim.jerk,
            t: ((a1 - a0) * lim.inv_jerk()).max(0.0),
        };
        let (dp, dv) = first.advance();
        let rest = change(v0 + dv, a1, self.e, lim);
        (first, rest, dp + rest.distance())
    }

    /// The release profile with D = d for a1 in [lo, hi], given D(lo) ≤ d ≤ D(hi) = d_hi.
    fn release(&self, d: f64, lo: f64, hi: f64, d_hi: f64, out: &mut Plan) {
        let f_lo = self.release_eval(lo).2 - d;
        let a1 = brent(|a1| self.release_eval(a1).2 - d, lo, hi, f_lo, d_hi - d);
        let (first, rest, _) = self.release_eval(a1);
        out.clear();
        out.push(first);
        out.push_change(&rest, self.e);
    }

    /// The least-released profile with D = d when D_release rises above d somewhere in
    /// [a0, 0] (it starts at the direct-ramp distance ≤ d and is unimodal): golden-section
    /// search for a point at or above d, then the root before it. False if there is none.
    fn release_above(&self, d: f64, out: &mut Plan) -> bool {
        let f = |a1: f64| self.release_eval(a1).2;
        let width = 4.0 * f64::EPSILON * self.a0.abs();
        let (a1, f1) = golden_max(f, self.a0, 0.0, width, |f1| f1 >= d);
        if f1 >= d {
            self.release(d, self.a0, a1, f1, out);
            true
        } else {
            false
        }
    }
}

/// ∂D/∂u of the ramp (peak, direction) that depends on vp, with vp = lo + u². `sign` is +1 for ramp 1
/// (ending at vp) and −1 for ramp 2 (starting at vp).
///
/// For a ramp ending at vp with a = 0, peak acceleration ap and direction s,
/// ∂D/∂vp = (ap²/2j + s·vp)/ap; a ramp starting at vp with a = 0 is its time reverse, which
/// flips s. The factor 2u/ap stays finite where ap → 0 (ap ≈ √j·u there).
#[inline]
fn slope_u((peak, dir): (f64, f64), vp: f64, u: f64, sign: f64, lim: &Lim) -> f64 {
    let s = if dir != 0.0 { sign * dir } else { 1.0 };
    let num = 0.5 * peak * peak * lim.inv_jerk() + s * vp;
    if peak > 0.0 {
        2.0 * u * num / peak
    } else {
        // Only with a finite jerk: a trapezoid's peak is its plateau.
        2.0 * num * lim.inv_jerk().sqrt()
    }
}

/// Distance and ∂/∂u (vp = lo + u²) of the ramp (w, 0) → (vp, 0) with plateau `a`: its
/// acceleration is symmetric in time, so it covers (w + vp)/2 × its duration, which is
/// 2·sqrt(Δ/j) as a triangle and Δ/a + a/j with a plateau (Δ = |vp − w|).
#[inline]
fn symmetric(w: f64, vp: f64, (a, inv_a): (f64, f64), u: f64, lim: &Lim) -> (f64, f64) {
    let ij = lim.inv_jerk();
    let delta = (vp - w).abs();
    let s = if vp >= w { 1.0 } else { -1.0 };
    let sum = w + vp;
    // With infinite jerk, ij = 0 and the ramp is its plateau.
    if delta * lim.jerk <= a * a {
        let half = (delta * ij).sqrt();
        // 2u·∂/∂vp of sum·half; u/half stays finite where the ramp vanishes at lo (Δ = u²).
        let ratio = if half > 0.0 {
            u / half
        } else {
            lim.jerk.sqrt()
        };
        (sum * half, 2.0 * u * half + sum * s * ij * ratio)
    } else {
        let t = delta * inv_a + a * ij;
        (0.5 * sum * t, u * (t + sum * s * inv_a))
    }
}

/// Golden-section search for the maximum of a unimodal `f` on `[a, b]`, until the bracket is
/// `width` wide or after `MAX_ITER` steps: the first probe `x` whose `f(x)` is `enough`, or else
/// the higher of the last two probes, with its value.
pub(super) fn golden_max(
    f: impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    width: f64,
    enough: impl Fn(f64) -> bool,
) -> (f64, f64) {
    const G: f64 = 0.618_033_988_749_894_8;
    let (mut a, mut b) = (a, b);
    let mut x1 = b - G * (b - a);
    let mut x2 = a + G * (b - a);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..MAX_ITER {
        if enough(f1) {
            return (x1, f1);
        }
        if enough(f2) {
            return (x2, f2);
        }
        if b - a <= width {
            break;
        }
        if f1 < f2 {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + G * (b - a);
            f2 = f(x2);
        } else {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - G * (b - a);
            f1 = f(x1);
        }
    }
    if f1 >= f2 {
        (x1, f1)
    } else {
        (x2, f2)
    }
}

/// Brent's method on [a, b] with f(a), f(b) of opposite signs (or one zero).
pub(super) fn brent(mut f: impl FnMut(f64) -> f64, a: f64, b: f64, fa: f64, fb: f64) -> f64 {
    let (mut a, mut b, mut fa, mut fb) = (a, b, fa, fb);
    if fa == 0.0 {
        return a;
    }
    if fb == 0.0 || fa * fb > 0.0 {
        return b;
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..MAX_ITER {
        if fb * fc > 0.0 {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + f64::MIN_POSITIVE;
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            return b;
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qa = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qa * (qa - r) - (b - a) * (r - 1.0));
                q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol {
            d
        } else if m > 0.0 {
            tol
        } else {
            -tol
        };
        fb = f(b);
        if !fb.is_finite() {
            return b;
        }
    }
    b
}
