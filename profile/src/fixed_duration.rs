//! Fixed-duration position profiles: the move that takes exactly `T ≥` the time-optimal
//! duration, from the same start state to the same target (Ruckig's step 2, "time
//! synchronization"). Synchronized group moves (all axes of a line start and end together) and
//! PVT need it.
//!
//! The shape is the time-optimal one with a lower cruise: ramp 1 `(v0, a0) → (vc, 0)`, a cruise
//! at `vc` for `tc ≥ 0`, ramp 2 `(vc, 0) → (e, 0)`, each ramp time-optimal under the limits
//! (acceleration while |v| grows, deceleration while it shrinks; split at v = 0 when they
//! differ). With `T1(vc)`, `T2(vc)` the ramp durations and `D1`, `D2` their distances, `T` and
//! the distance `d` fix `vc`:
//!
//! ```text
//! tc = T − T1(vc) − T2(vc) ≥ 0,      g(vc) = D1 + D2 + vc·tc − d = 0.
//! ```
//!
//! On each interval of `vc` between the breakpoints `v_stop`, `e`, 0 and ±vmax (where a ramp
//! changes direction or limit), `T1 + T2` is concave (each ramp's duration is a concave function
//! of its velocity change: `2√(Δ/j)` as a triangle, `Δ/a + a/j` with a plateau, `Δ/a` for a
//! trapezoid), so `tc ≥ 0` holds on at most two sub-intervals, at its ends; and there
//! `g' = tc + Σ (τ − Δτ')/2 ≥ 0` (τ(Δ) a ramp's duration), so `g` is monotone and has at most one
//! root per sub-interval. Where several sub-intervals have one, the fastest cruise in the
//! direction of the target wins (the continuation of the time-optimal profile), a cruise the
//! other way (a reversal) only when there is none.
//!
//! Where the cruise has no solution and `v_stop ≠ e`, a second shape: bring `a0` to 0 (reaching
//! `v_stop`), cruise there, ramp to `e` at full limits, cruise at `e`. For a given `T` it covers,
//! linearly in the split of the two cruises, every distance between "cruise first" and "cruise
//! last", which is exactly where `T1 + T2` has a hump between `v_stop` and `e` (two full ramps
//! take longer than the one ramp between them, so a cruise in between does not fit).
//!
//! Which durations these cover (see [`DurationError::Blocked`] for the others):
//! - trapezoids: every duration Ruckig can synchronize to, and the same blocked intervals
//!   (tested against rsruckig). They occur when the start velocity points at a target too
//!   close to stop, wait and start again (e.g. arriving at speed): between the longest dip
//!   of the speed and the shortest reversal;
//! - S-curves from rest (with or without an end velocity): every duration ≥ the optimum
//!   (tested);
//! - other S-curves: a subset of Ruckig's durations. Ruckig also has profiles without a cruise
//!   whose acceleration does not return to 0 in between, which some durations need: just above
//!   the optimum when that is of the release kind (a start acceleration that already brakes
//!   towards `e`, see `plan`). Such durations are refused as blocked; a slightly longer one
//!   works. Over 100 000 random cases per kind inside Ruckig's input conditions, stretched by
//!   1 + 1e-6 … 1000 (`fixed_duration_coverage`), Ruckig plans 0.03 % (to rest) and 0.15 % (with
//!   an end velocity) of the durations this refuses, nearly all within 0.7 % above the
//!   optimum and all seen with a braking start acceleration; never the other way round.
//!   Trapezoids agree on every case.
//!
//! Work, once at planning time (never per tick): one time-optimal plan (for `T_opt` and the
//! direction of the end velocity), the second shape in closed form, and per interval of `vc`
//! (≤ 4):
//! - trapezoid: closed form (`T1 + T2` is linear and `g` quadratic in `vc` on an interval);
//! - S-curve: a golden-section search for the maximum of `T1 + T2` (≤ 100 steps), up to two
//!   Brent searches for its crossings with `T` and up to two for the root of `g` (≤ 100 steps
//!   each), each step evaluating two ramps in closed form: at most about 2000 ramp pairs.

use super::plan::{brent, golden_max, Plan};
use super::ramp::{change, Change, Lim, Phase};
use super::{Goal, Limits, MotionState, Options, PlanError, Profile, Scale};

/// Relative tolerance on the duration: a requested duration within it of the time-optimal one
/// gets the time-optimal profile, and a shorter one is refused.
pub const DURATION_TOL: f64 = 1e-9;

/// Why no profile of the requested duration was planned.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum DurationError {
    #[error(transparent)]
    Plan(#[from] PlanError),
    #[error("duration {duration}: must be a finite number ≥ 0")]
    InvalidDuration { duration: f64 },
    #[error("duration {duration} s is shorter than the time-optimal {minimum} s")]
    TooShort { duration: f64, minimum: f64 },
    /// No profile of the two shapes takes exactly this long: Ruckig's blocked intervals (a
    /// start velocity towards a target too close to stop, wait and start again: a longer
    /// duration works again with a reversal), and for S-curves also some durations only
    /// profiles without a cruise reach (see the module doc). The caller picks another
    /// duration (a synchronized group: the next one every axis can take).
    #[error(
        "no profile takes exactly {duration} s (time-optimal {minimum} s): a blocked duration"
    )]
    Blocked { duration: f64, minimum: f64 },
}

impl Profile {
    /// Plan from `start` to `target`, arriving at `end_velocity` (a magnitude, in the direction
    /// the time-optimal profile arrives from, see [`Goal::Position`]), taking exactly `duration`
    /// seconds within `limits`.
    ///
    /// The result is sampled like any other profile. Its duration is `duration` within
    /// [`DURATION_TOL`] (relative; in practice a few ulps: the sum of its phases), and from
    /// `duration()` on it samples to exactly the target. `duration` within `DURATION_TOL` of
    /// the time-optimal duration returns the time-optimal profile itself.
    /// A zero-distance move from rest stays put for `duration`.
    ///
    /// No start-velocity jump and no jump to zero at the target: the options are the defaults
    /// (`Options::default()`).
    pub fn plan_for_duration(
        start: MotionState,
        target: f64,
        end_velocity: f64,
        limits: &Limits,
        duration: f64,
    ) -> Result<Profile, DurationError> {
        let goal = Goal::Position {
            target,
            end_velocity,
        };
        let optimal = Profile::plan(start, goal, limits, &Options::default())?;
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(DurationError::InvalidDuration { duration });
        }
        let minimum = optimal.duration();
        if duration < minimum * (1.0 - DURATION_TOL) {
            return Err(DurationError::TooShort { duration, minimum });
        }
        if duration <= minimum * (1.0 + DURATION_TOL) {
            return Ok(optimal);
        }
        let scale = Scale::new(limits)?;
        // The end velocity points where the time-optimal profile arrives from.
        let e = (end_velocity / scale.v).min(1.0);
        let e = if optimal.arrival_velocity() < 0.0 {
            -e
        } else {
            e
        };
        let family = Family {
            v0: start.v / scale.v,
            a0: if limits.jerk.is_finite() {
                start.a / scale.a
            } else {
                0.0
            },
            e,
            d: (target - start.p) / scale.p,
            tf: duration / scale.t,
            lim: scale.lim,
        };
        let shape = family
            .solve()
            .or_else(|| family.two_cruises())
            .ok_or(DurationError::Blocked { duration, minimum })?;
        let mut plan = Plan::new();
        family.build(shape, &mut plan);
        Ok(Profile::assemble(
            start.p,
            goal,
            &plan,
            &scale,
            limits,
            Some(target),
        )?)
    }
}

/// The problem in the planner's normalised units (see `plan`): start `(v0, a0)`, signed end
/// velocity `e`, distance `d`, duration `tf`.
struct Family {
    v0: f64,
    a0: f64,
    e: f64,
    d: f64,
    tf: f64,
    lim: Lim,
}

/// A solution: which shape, with its free values.
#[derive(Clone, Copy, Debug)]
enum Shape {
    /// Ramp to `vc`, cruise, ramp to `e`.
    Cruise(f64),
    /// Bring `a0` to 0 (reaching `v_stop`), cruise there for `before`, ramp to `e`, cruise at
    /// `e` for `after`.
    TwoCruises { before: f64, after: f64 },
}

/// The two ramps through cruise velocity `vc`, with their total duration and distance.
struct Ramps {
    first: Change,
    second: Change,
    time: f64,
    distance: f64,
}

fn duration_of(c: &Change) -> f64 {
    c.phases().map(|ph| ph.t).sum()
}

impl Family {
    fn ramps(&self, vc: f64) -> Ramps {
        let first = change(self.v0, self.a0, vc, &self.lim);
        let second = change(vc, 0.0, self.e, &self.lim);
        Ramps {
            time: duration_of(&first) + duration_of(&second),
            distance: first.distance() + second.distance(),
            first,
            second,
        }
    }

    /// `T1 + T2 − T`: feasible (a cruise of `tc ≥ 0`) where ≤ 0.
    fn overtime(&self, vc: f64) -> f64 {
        self.ramps(vc).time - self.tf
    }

    /// `g(vc)`: the distance the profile through `vc` covers in `T`, less `d`.
    fn excess(&self, vc: f64) -> f64 {
        let r = self.ramps(vc);
        r.distance + vc * (self.tf - r.time) - self.d
    }

    /// The cruise velocity, or None if no profile of the family takes `tf`.
    fn solve(&self) -> Option<Shape> {
        let lim = &self.lim;
        // Breakpoints: where ramp 1 or ramp 2 changes direction, and v = 0 (limits switch).
        let v_stop = lim.v_stop(self.v0, self.a0);
        let mut points = [-lim.vmax, lim.vmax, 0.0, v_stop, self.e];
        for x in &mut points {
            *x = x.clamp(-lim.vmax, lim.vmax);
        }
        points.sort_by(f64::total_cmp);
        // The direction of travel is preferred: the fastest cruise towards the target that
        // takes `tf` (the continuation of the time-optimal profile); a cruise the other way
        // (a reversal) only when there is none.
        let s = if self.d != 0.0 {
            self.d.signum()
        } else if self.e != 0.0 {
            self.e.signum()
        } else {
            1.0
        };
        let rank = |vc: f64| (s * vc >= 0.0, (s * vc).abs());
        let mut best: Option<f64> = None;
        for w in points.windows(2) {
            let (p, q) = (w[0], w[1]);
            if q <= p {
                continue;
            }
            let roots = if lim.jerk.is_finite() {
                self.roots_numeric(p, q)
            } else {
                self.roots_trapezoid(p, q)
            };
            for vc in roots.into_iter().flatten() {
                if best.is_none_or(|b| rank(vc) > rank(b)) {
                    best = Some(vc);
                }
            }
        }
        best.map(Shape::Cruise)
    }

    /// The velocity change `v_stop → e` at full limits between a cruise at `v_stop` and one at
    /// `e`: for a given `T` it covers every distance between cruising first and cruising last,
    /// which is where the S-curve's `T1 + T2` has its hump (see the module doc). With `R` the
    /// time and `Q` the distance the two cruises share: `before + after = R`,
    /// `v_stop·before + e·after = Q`.
    fn two_cruises(&self) -> Option<Shape> {
        let lim = &self.lim;
        let v_stop = lim.v_stop(self.v0, self.a0);
        if v_stop == self.e || v_stop.abs() > lim.vmax {
            return None;
        }
        let removal = change(self.v0, self.a0, v_stop, lim);
        let ramp = change(v_stop, 0.0, self.e, lim);
        let r = self.tf - duration_of(&removal) - duration_of(&ramp);
        let q = self.d - removal.distance() - ramp.distance();
        let after = (q - v_stop * r) / (self.e - v_stop);
        let before = r - after;
        // Rounding: a share a hair below 0 is 0.
        let slack = 1e-12 * self.tf;
        (after >= -slack && before >= -slack).then_some(Shape::TwoCruises {
            before: before.max(0.0),
            after: after.max(0.0),
        })
    }

    /// Trapezoid on `[p, q]`: the ramps' rates are constant there, so with `r1` the rate of
    /// ramp 1's last part and `r2` that of ramp 2's first part (signed), `T1 + T2` is linear
    /// with slope `w = 1/r1 − 1/r2` and `D1 + D2` quadratic with `w/2` as the coefficient of
    /// `vc²`: `g = −(w/2) vc² + (T − S + m·w) vc + (D(m) − m² w/2 − d)` around the midpoint `m`
    /// with `S = T1 + T2` there.
    fn roots_trapezoid(&self, p: f64, q: f64) -> [Option<f64>; 2] {
        let m = 0.5 * (p + q);
        let r = self.ramps(m);
        let (Some(r1), Some(r2)) = (rate(r.first.last()), rate(r.second.first())) else {
            return [None, None];
        };
        let w = 1.0 / r1 - 1.0 / r2;
        let time = r.time;
        // Feasible part: S + (vc − m)·w ≤ T.
        let (l, h) = if w == 0.0 {
            if time <= self.tf {
                (p, q)
            } else {
                return [None, None];
            }
        } else {
            let edge = m + (self.tf - time) / w;
            if w > 0.0 {
                (p, edge.min(q))
            } else {
                (edge.max(p), q)
            }
        };
        if l > h {
            return [None, None];
        }
        let a = -0.5 * w;
        let b = self.tf - time + m * w;
        let c = r.distance - 0.5 * m * m * w - self.d;
        let g = |x: f64| (a * x + b) * x + c;
        [quadratic_root_in(a, b, c, l, h, g(l), g(h)), None]
    }

    /// S-curve on `[p, q]`: `T1 + T2 − T` is concave there, so it is ≤ 0 on `[p, q]` or on
    /// up to two end parts, split off at its maximum (golden section) by Brent; on each part
    /// `g` is monotone and Brent finds its root if the ends bracket one.
    fn roots_numeric(&self, p: f64, q: f64) -> [Option<f64>; 2] {
        let h = |x: f64| self.overtime(x);
        let (hp, hq) = (h(p), h(q));
        let (m, hm) = concave_max(h, p, q, hp, hq);
        let parts = if hm <= 0.0 {
            [Some((p, q)), None]
        } else {
            [
                (hp <= 0.0).then(|| (p, brent(h, p, m, hp, hm))),
                (hq <= 0.0).then(|| (brent(h, m, q, hm, hq), q)),
            ]
        };
        parts.map(|part| {
            let (l, r) = part?;
            let (gl, gr) = (self.excess(l), self.excess(r));
            if gl > 0.0 || gr < 0.0 {
                return None;
            }
            Some(brent(|x| self.excess(x), l, r, gl, gr))
        })
    }

    /// The phases of `shape`; a cruise takes what the ramps leave of `tf`.
    fn build(&self, shape: Shape, out: &mut Plan) {
        out.clear();
        let cruise = |v: f64, t: f64| Phase {
            v,
            a: 0.0,
            j: 0.0,
            t: t.max(0.0),
        };
        match shape {
            Shape::Cruise(vc) => {
                let r = self.ramps(vc);
                out.push_change(&r.first, vc);
                out.push(cruise(vc, self.tf - r.time));
                out.push_change(&r.second, self.e);
            }
            Shape::TwoCruises { before, after } => {
                let v_stop = self.lim.v_stop(self.v0, self.a0);
                out.push_change(&change(self.v0, self.a0, v_stop, &self.lim), v_stop);
                out.push(cruise(v_stop, before));
                out.push_change(&change(v_stop, 0.0, self.e, &self.lim), self.e);
                out.push(cruise(self.e, after));
            }
        }
    }
}

/// The maximum of a concave `f` on `[a, b]` (with `f(a)`, `f(b)` given) and where it is.
fn concave_max(f: impl Fn(f64) -> f64, a: f64, b: f64, fa: f64, fb: f64) -> (f64, f64) {
    let width = 4.0 * f64::EPSILON * a.abs().max(b.abs());
    let inner = golden_max(f, a, b, width, |_| false);
    [(a, fa), (b, fb)]
        .into_iter()
        .fold(inner, |best, end| if end.1 > best.1 { end } else { best })
}

/// The signed acceleration of a trapezoid ramp, None for an empty one.
fn rate(r: &super::ramp::Ramp) -> Option<f64> {
    let a = r.phases[0].a;
    (a != 0.0).then_some(a)
}

/// The root of `a x² + b x + c` in `[l, h]`, given its values `gl ≤ 0 ≤ gh` at the ends (None
/// if they do not bracket one). The polynomial is monotone there, so there is one root (or
/// an interval of them when it vanishes; then `l`).
fn quadratic_root_in(a: f64, b: f64, c: f64, l: f64, h: f64, gl: f64, gh: f64) -> Option<f64> {
    if gl > 0.0 || gh < 0.0 {
        return None;
    }
    if gl == 0.0 {
        return Some(l);
    }
    if gh == 0.0 {
        return Some(h);
    }
    let candidates = if a == 0.0 {
        [-c / b, f64::NAN]
    } else {
        // Without cancellation: q = −(b + sign(b)·√disc)/2, roots q/a and c/q.
        let disc = (b * b - 4.0 * a * c).max(0.0);
        let q = -0.5 * (b + disc.sqrt().copysign(b));
        [q / a, c / q]
    };
    // The root in [l, h]; rounding may put it just outside, so the nearest one, clamped.
    let distance = |x: f64| {
        if x.is_nan() {
            f64::INFINITY
        } else {
            (l - x).max(x - h).max(0.0)
        }
    };
    let x = if distance(candidates[0]) <= distance(candidates[1]) {
        candidates[0]
    } else {
        candidates[1]
    };
    x.is_finite().then(|| x.clamp(l, h))
}
