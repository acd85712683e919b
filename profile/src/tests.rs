//! Properties of the planner (ARCHITECTURE §3.6): limits hold, targets are reached exactly,
//! segments join continuously, durations match the closed forms, nothing is ever NaN.
//!
//! Tolerances, relative to the problem's own scale (measured worst cases are far below):
//! - limits (each plus the boundary-time rounding below): |v| ≤ max(velocity, |v0|,
//!   |v_stop|)·(1 + 1e-9), where v_stop = v0 + a0|a0|/2j is
//!   the velocity the start state reaches before any planner can act; |a| ≤ the limit of the
//!   phase (acceleration while |v| grows, deceleration while it shrinks) or |a0|, ·(1 + 1e-9)
//!   (unless the start state reverses the motion by itself, then max(acceleration,
//!   deceleration, |a0|)); |j| ≤ jerk exactly;
//! - continuity: position 1e-9 of the profile's extent (max |p|, peak speed × duration),
//!   velocity 1e-9 of the peak speed, acceleration 1e-9 of the peak acceleration, each plus
//!   what rounding a boundary time to f64 seconds changes (4 ulp of the duration times the
//!   next derivative: at t = 1e7 s a boundary is only known to 2e-9 s);
//! - closed-form durations: 1e-9 relative.

use super::rules::hmc_trapezoid_duration;
use super::*;
use proptest::prelude::*;
use proptest::test_runner::Config;

pub(super) const TOL: f64 = 1e-9;

/// `cases`, or `PROPTEST_CASES` from the environment for a longer run.
pub(super) fn config(cases: u32) -> Config {
    Config {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(cases),
        failure_persistence: None,
        ..Config::default()
    }
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Problem {
    pub start: MotionState,
    pub goal: Goal,
    pub limits: Limits,
    pub options: Options,
}

impl Problem {
    fn plan(&self) -> Result<Profile, PlanError> {
        Profile::plan(self.start, self.goal, &self.limits, &self.options)
    }
}

pub(super) fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.log10()..hi.log10()).prop_map(|x| 10f64.powf(x))
}

fn unit() -> impl Strategy<Value = f64> {
    -1.0..1.0f64
}

/// Random problems: limits over `range` (each independently), start states inside and outside
/// the limits, both goal kinds, start/end velocities, both overshoot modes, trapezoids and
/// S-curves, equal and unequal acceleration/deceleration.
fn problems(range: (f64, f64)) -> impl Strategy<Value = Problem> {
    let (lo, hi) = range;
    (
        (
            log_uniform(lo, hi),
            log_uniform(lo, hi),
            log_uniform(lo, hi),
            prop_oneof![Just(1.0), log_uniform(0.1, 10.0)],
            0..4u8,
        ),
        (unit(), unit(), unit(), 0..3u8, 0..3u8),
        (
            unit(),
            -6.0..4.0f64,
            0..8u8,
            0.0..1.2f64,
            0.0..1.1f64,
            any::<bool>(),
        ),
    )
        .prop_map(
            |(
                (vel, acc, jerk, dec_ratio, jerk_kind),
                (fv, fa, fp, kv, ka),
                (fd, exp, goal_kind, fe, fs, jump),
            )| {
                let limits = Limits {
                    velocity: vel,
                    acceleration: acc,
                    deceleration: acc * dec_ratio,
                    jerk: if jerk_kind == 0 { f64::INFINITY } else { jerk },
                };
                let length = vel * vel / acc;
                let factor = |k: u8| [0.0, 1.0, 3.0][usize::from(k)];
                let start = MotionState {
                    p: fp * length * 100.0,
                    v: fv * vel * factor(kv),
                    a: fa * acc * factor(ka),
                };
                let distance = fd.signum() * length * 10f64.powf(exp);
                let goal = match goal_kind {
                    0 | 1 => Goal::Velocity {
                        target: fd * vel * 1.2,
                    },
                    2 => Goal::Position {
                        target: start.p,
                        end_velocity: 0.0,
                    },
                    3..=5 => Goal::Position {
                        target: start.p + distance,
                        end_velocity: 0.0,
                    },
                    _ => Goal::Position {
                        target: start.p + distance,
                        end_velocity: fe * vel,
                    },
                };
                let options = Options {
                    start_velocity: if goal_kind % 2 == 0 { 0.0 } else { fs * vel },
                    overshoot: if jump {
                        Overshoot::JumpToZeroAtTarget
                    } else {
                        Overshoot::Reverse
                    },
                };
                Problem {
                    start,
                    goal,
                    limits,
                    options,
                }
            },
        )
}

/// Times to sample: dense, plus every segment boundary.
fn sample_times(p: &Profile) -> Vec<f64> {
    let d = p.duration();
    let mut ts: Vec<f64> = (0..=200).map(|i| d * f64::from(i) / 200.0).collect();
    ts.extend(p.segment_times());
    ts
}

/// Start velocity after the start-velocity jump.
fn jumped_start(pb: &Problem) -> MotionState {
    let mut s = pb.start;
    let sv = pb.options.start_velocity.min(pb.limits.velocity);
    let dir = match pb.goal {
        Goal::Position { target, .. } => target - pb.start.p,
        Goal::Velocity { target } => target,
    };
    if sv > 0.0 && dir != 0.0 && s.v.abs() < sv {
        s.v = match pb.goal {
            Goal::Velocity { target } => sv.min(target.abs()),
            Goal::Position { .. } => sv,
        }
        .copysign(dir);
        s.a = 0.0;
    }
    s
}

pub(super) fn check_profile(pb: &Problem, p: &Profile) -> Result<(), TestCaseError> {
    let lim = &pb.limits;
    let s0 = jumped_start(pb);
    let finite_jerk = lim.jerk.is_finite();
    let v_stop = if finite_jerk {
        s0.v + s0.a * s0.a.abs() / (2.0 * lim.jerk)
    } else {
        s0.v
    };
    let a0 = if finite_jerk { s0.a.abs() } else { 0.0 };
    let self_reversing = s0.v * v_stop < 0.0;
    let v_cap = lim.velocity.max(s0.v.abs()).max(v_stop.abs());
    let a_cap = lim.acceleration.max(lim.deceleration).max(a0);
    let d = p.duration();
    prop_assert!(d.is_finite() && d >= 0.0, "duration {d}");
    let end_p = p.final_state().p;
    let extent = pb.start.p.abs().max(end_p.abs()).max(v_cap * d);

    // Rounding a time to f64 seconds moves it by up to an ulp of the duration: near a
    // boundary the polynomial of the neighbouring segment may be evaluated that far.
    let dt_round = 4.0 * f64::EPSILON * d;
    let j_cap = if finite_jerk { lim.jerk } else { 0.0 };

    // Limits, densely and at the boundaries.
    for t in sample_times(p) {
        let s = p.sample(t);
        prop_assert!(
            s.p.is_finite() && s.v.is_finite() && s.a.is_finite() && s.j.is_finite(),
            "NaN/inf at {t}: {s:?}"
        );
        prop_assert!(
            s.v.abs() <= v_cap * (1.0 + TOL) + dt_round * a_cap,
            "|v| {} > {v_cap} at {t}",
            s.v
        );
        prop_assert!(s.j.abs() <= lim.jerk, "|j| {} > {} at {t}", s.j, lim.jerk);
        prop_assert!(
            s.a.abs() <= a_cap * (1.0 + TOL) + dt_round * j_cap,
            "|a| {} > {a_cap} at {t}",
            s.a
        );
        // Acceleration while |v| grows, deceleration while it shrinks (away from v = 0,
        // where the sign of v is rounding: of the arithmetic, and of the sample time by
        // `dt_round`, which on a long stretched profile is larger than `TOL * v_cap`). Not checked when the start state reverses the
        // motion by itself (v0 and v_stop on opposite sides of 0): the first ramp then uses the
        // limit of the direction it ends in throughout (docs/decisions.md, Profiles).
        if !self_reversing && s.v.abs() > TOL * v_cap + dt_round * a_cap {
            let limit = if s.v * s.a > 0.0 {
                lim.acceleration
            } else {
                lim.deceleration
            };
            prop_assert!(
                s.a.abs() <= limit.max(a0) * (1.0 + TOL) + dt_round * j_cap,
                "|a| {} > phase limit {limit} (v {}) at {t}",
                s.a,
                s.v
            );
        }
    }

    // Continuity across boundaries: the previous segment's polynomial at the boundary against
    // the next segment's start.
    let times: Vec<f64> = p.segment_times().collect();
    let segs: Vec<Segment> = p.segments().collect();
    let tol_v = TOL * v_cap + dt_round * a_cap;
    let tol_a = TOL * a_cap + dt_round * lim.jerk;
    for (i, &t) in times.iter().enumerate().skip(1) {
        let before = segs[i - 1];
        let dt = t - before.t;
        let left = Sample {
            p: before.p + dt * (before.v + dt * (0.5 * before.a + dt * before.j / 6.0)),
            v: before.v + dt * (before.a + 0.5 * dt * before.j),
            a: before.a + dt * before.j,
            j: before.j,
        };
        let right = segs[i];
        prop_assert!(
            (left.p - right.p).abs() <= TOL * extent,
            "p jumps by {} at {t}",
            left.p - right.p
        );
        prop_assert!(
            (left.v - right.v).abs() <= tol_v,
            "v jumps by {} at {t}",
            left.v - right.v
        );
        if finite_jerk {
            prop_assert!(
                (left.a - right.a).abs() <= tol_a,
                "a jumps by {} at {t}",
                left.a - right.a
            );
        }
    }

    // The end.
    let left_end = if let Some(last) = times.len().checked_sub(1) {
        let s = segs[last];
        let dt = d - s.t;
        Sample {
            p: s.p + dt * (s.v + dt * (0.5 * s.a + dt * s.j / 6.0)),
            v: s.v + dt * (s.a + 0.5 * dt * s.j),
            a: s.a + dt * s.j,
            j: s.j,
        }
    } else {
        let f = p.final_state();
        Sample {
            p: f.p,
            v: p.arrival_velocity(),
            a: 0.0,
            j: 0.0,
        }
    };
    match pb.goal {
        Goal::Position {
            target,
            end_velocity,
        } => {
            for t in [d, d * (1.0 + 1e-6) + 1e-9, d + 1.0, 2.0 * d + 1e6] {
                let s = p.sample(t);
                prop_assert_eq!(s.p.to_bits(), target.to_bits(), "p at {} of {}", t, d);
                prop_assert_eq!((s.v, s.a, s.j), (0.0, 0.0, 0.0));
            }
            prop_assert!(
                (left_end.p - target).abs() <= TOL * extent,
                "the motion ends {} from the target",
                left_end.p - target
            );
            prop_assert!((left_end.v - p.arrival_velocity()).abs() <= tol_v);
            // A jump to zero is a profile the Reverse mode would not plan.
            let reverse = Options {
                overshoot: Overshoot::Reverse,
                ..pb.options
            };
            let jumped = pb.options.overshoot == Overshoot::JumpToZeroAtTarget
                && Profile::plan(pb.start, pb.goal, lim, &reverse).ok() != Some(*p);
            if !jumped && !times.is_empty() {
                prop_assert!(
                    (p.arrival_velocity().abs() - end_velocity.min(lim.velocity)).abs()
                        <= TOL * v_cap,
                    "arrives at {}, wanted {}",
                    p.arrival_velocity(),
                    end_velocity
                );
                if finite_jerk {
                    prop_assert!(left_end.a.abs() <= tol_a, "a {} at the end", left_end.a);
                }
            }
        }
        Goal::Velocity { target } => {
            let vt = target.clamp(-lim.velocity, lim.velocity);
            prop_assert_eq!(p.sample(d).v, vt);
            prop_assert_eq!(p.sample(d + 1.0).v, vt);
            prop_assert_eq!(p.sample(d + 1.0).a, 0.0);
            prop_assert!(
                (left_end.v - vt).abs() <= tol_v,
                "v {} at the end",
                left_end.v
            );
            if finite_jerk {
                prop_assert!(left_end.a.abs() <= tol_a, "a {} at the end", left_end.a);
            }
            // The motion continues: p grows by vt per second.
            let (p1, p2) = (p.sample(d + 1.0).p, p.sample(d + 3.0).p);
            prop_assert!((p2 - p1 - 2.0 * vt).abs() <= TOL * (p1.abs() + p2.abs() + vt.abs()));
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(4000))]

    /// Moderate magnitudes (1e-2 … 1e4, independently per limit).
    #[test]
    fn invariants_hold(pb in problems((1e-2, 1e4))) {
        let p = pb.plan().map_err(|e| TestCaseError::fail(format!("{e} for {pb:?}")))?;
        check_profile(&pb, &p)?;
    }

    /// Pulse-sized and tiny numbers: every limit anywhere in 1e-6 … 1e10 (Ruckig issue #27).
    #[test]
    fn invariants_hold_at_extreme_magnitudes(pb in problems((1e-6, 1e10))) {
        let p = pb.plan().map_err(|e| TestCaseError::fail(format!("{e} for {pb:?}")))?;
        check_profile(&pb, &p)?;
    }
}

/// Any finite input at all: the planner returns a profile or an error, never panics, and a
/// profile never samples to NaN.
fn any_finite() -> impl Strategy<Value = f64> {
    prop_oneof![
        any::<f64>().prop_filter("finite", |x| x.is_finite()),
        (-300.0..300.0f64, any::<bool>()).prop_map(|(e, neg)| {
            let x = 10f64.powf(e);
            if neg {
                -x
            } else {
                x
            }
        }),
        Just(0.0),
    ]
}

proptest! {
    #![proptest_config(config(4000))]

    #[test]
    fn any_finite_input_is_planned_or_refused_never_nan(
        (p, v, a, target, ev) in (any_finite(), any_finite(), any_finite(), any_finite(), any_finite()),
        (vel, acc, dec, jerk, sv) in (any_finite(), any_finite(), any_finite(), any_finite(), any_finite()),
        (velocity_goal, jump, trapezoid) in (any::<bool>(), any::<bool>(), any::<bool>()),
    ) {
        let goal = if velocity_goal {
            Goal::Velocity { target }
        } else {
            Goal::Position { target, end_velocity: ev.abs() }
        };
        let limits = Limits {
            velocity: vel,
            acceleration: acc,
            deceleration: dec,
            jerk: if trapezoid { f64::INFINITY } else { jerk },
        };
        let options = Options {
            start_velocity: sv.abs(),
            overshoot: if jump { Overshoot::JumpToZeroAtTarget } else { Overshoot::Reverse },
        };
        if let Ok(profile) = Profile::plan(MotionState { p, v, a }, goal, &limits, &options) {
            let d = profile.duration();
            prop_assert!(d.is_finite() && d >= 0.0);
            for t in [0.0, d / 3.0, d / 2.0, d, d + 1.0] {
                let s = profile.sample(t);
                prop_assert!(!(s.p.is_nan() || s.v.is_nan() || s.a.is_nan() || s.j.is_nan()),
                    "NaN at {t}: {s:?}");
            }
        }
    }
}

/// Standard double-S duration from rest to rest with equal acceleration and deceleration
/// (Biagiotti & Melchiorri, "Trajectory Planning for Automatic Machines", §3.4).
fn double_s_duration(h: f64, vmax: f64, amax: f64, jmax: f64) -> f64 {
    let h = h.abs();
    // Acceleration phase to vmax: Tj jerk time, Ta total.
    let (tj, ta) = if vmax * jmax >= amax * amax {
        (amax / jmax, amax / jmax + vmax / amax)
    } else {
        let tj = (vmax / jmax).sqrt();
        (tj, 2.0 * tj)
    };
    let _ = tj;
    let tv = h / vmax - ta;
    if tv >= 0.0 {
        return 2.0 * ta + tv;
    }
    // vmax not reached.
    if h >= 2.0 * amax.powi(3) / (jmax * jmax) {
        let tj = amax / jmax;
        let ta = tj / 2.0 + ((tj / 2.0).powi(2) + h / amax).sqrt();
        2.0 * ta
    } else {
        let tj = (h / (2.0 * jmax)).cbrt();
        4.0 * tj
    }
}

proptest! {
    #![proptest_config(config(4000))]

    #[test]
    fn trapezoid_from_rest_lasts_the_hmc_closed_form(
        (vel, acc, dec) in (log_uniform(1e-3, 1e6), log_uniform(1e-3, 1e6), log_uniform(1e-3, 1e6)),
        (dist, p0) in (log_uniform(1e-3, 1e9), -1e6..1e6f64),
    ) {
        let limits = Limits { velocity: vel, acceleration: acc, deceleration: dec, jerk: f64::INFINITY };
        let target = p0 + dist;
        let p = Profile::plan(
            MotionState { p: p0, v: 0.0, a: 0.0 },
            Goal::Position { target, end_velocity: 0.0 },
            &limits,
            &Options::default(),
        ).unwrap();
        // The distance the planner sees, after rounding p0 + dist.
        let expected = hmc_trapezoid_duration(target - p0, vel, acc, dec).unwrap();
        prop_assert!((p.duration() - expected).abs() <= TOL * expected,
            "{} vs {expected}", p.duration());
    }

    #[test]
    fn s_curve_from_rest_lasts_the_double_s_closed_form(
        (vel, acc, jerk) in (log_uniform(1e-3, 1e6), log_uniform(1e-3, 1e6), log_uniform(1e-3, 1e9)),
        (dist, neg) in (log_uniform(1e-6, 1e9), any::<bool>()),
    ) {
        let limits = Limits { velocity: vel, acceleration: acc, deceleration: acc, jerk };
        let length = vel * vel / acc;
        let dist = if neg { -dist * length } else { dist * length };
        let p = Profile::plan(
            MotionState::default(),
            Goal::Position { target: dist, end_velocity: 0.0 },
            &limits,
            &Options::default(),
        ).unwrap();
        let expected = double_s_duration(dist, vel, acc, jerk);
        prop_assert!((p.duration() - expected).abs() <= TOL * expected,
            "{} vs {expected}", p.duration());
    }
}

#[test]
fn double_s_reference_numbers() {
    // Biagiotti & Melchiorri example 3.9 (rest to rest, h = 10, vmax 5, amax 10, jmax 30):
    // Tj = 1/3, Ta = 0.8333, Tv = 1.1667, T = 2.8333.
    assert!((double_s_duration(10.0, 5.0, 10.0, 30.0) - 2.8333).abs() < 1e-4);
}

#[test]
fn zero_distance_from_rest_is_a_zero_duration_profile() {
    let limits = Limits {
        velocity: 1.0,
        acceleration: 1.0,
        deceleration: 1.0,
        jerk: 1.0,
    };
    for (end_velocity, start_velocity) in [(0.0, 0.0), (0.5, 0.0), (0.5, 0.5)] {
        let p = Profile::plan(
            MotionState {
                p: 7.25,
                v: 0.0,
                a: 0.0,
            },
            Goal::Position {
                target: 7.25,
                end_velocity,
            },
            &limits,
            &Options {
                start_velocity,
                overshoot: Overshoot::Reverse,
            },
        )
        .unwrap();
        assert_eq!(p.duration(), 0.0);
        assert_eq!(p.segment_count(), 0);
        assert_eq!(p.sample(0.0).p, 7.25);
        assert_eq!(p.sample(5.0), p.sample(0.0));
    }
}

#[test]
fn invalid_limits_are_refused() {
    let ok = Limits {
        velocity: 1.0,
        acceleration: 1.0,
        deceleration: 1.0,
        jerk: f64::INFINITY,
    };
    let goal = Goal::Position {
        target: 1.0,
        end_velocity: 0.0,
    };
    let plan =
        |limits: Limits| Profile::plan(MotionState::default(), goal, &limits, &Options::default());
    assert!(plan(ok).is_ok());
    for bad in [0.0, -1.0, f64::NAN] {
        assert!(matches!(
            plan(Limits {
                velocity: bad,
                ..ok
            }),
            Err(PlanError::InvalidLimit {
                name: "velocity",
                ..
            })
        ));
        assert!(plan(Limits {
            acceleration: bad,
            ..ok
        })
        .is_err());
        assert!(plan(Limits {
            deceleration: bad,
            ..ok
        })
        .is_err());
        assert!(plan(Limits { jerk: bad, ..ok }).is_err());
    }
    assert!(matches!(
        plan(Limits {
            velocity: f64::INFINITY,
            ..ok
        }),
        Err(PlanError::NotFinite { .. })
    ));
    let nan_start = Profile::plan(
        MotionState {
            p: f64::NAN,
            v: 0.0,
            a: 0.0,
        },
        goal,
        &ok,
        &Options::default(),
    );
    assert!(matches!(nan_start, Err(PlanError::NotFinite { .. })));
    let negative_end = Profile::plan(
        MotionState::default(),
        Goal::Position {
            target: 1.0,
            end_velocity: -1.0,
        },
        &ok,
        &Options::default(),
    );
    assert!(matches!(negative_end, Err(PlanError::Negative { .. })));
    // Finite but not representable once scaled.
    let absurd = Limits {
        velocity: 1e300,
        acceleration: 1e-300,
        deceleration: 1e-300,
        jerk: 1.0,
    };
    assert_eq!(plan(absurd), Err(PlanError::Unrepresentable));
}

fn scurve(v: f64, a: f64, d: f64, j: f64) -> Limits {
    Limits {
        velocity: v,
        acceleration: a,
        deceleration: d,
        jerk: j,
    }
}

fn to(target: f64) -> Goal {
    Goal::Position {
        target,
        end_velocity: 0.0,
    }
}

#[test]
fn moving_away_from_the_target_brakes_to_rest_then_reverses() {
    // HMC MoveModify case 1 (digest 000 §4.2, §8 vector 11), Accel ≠ Decel: the ramp through
    // zero is split at v = 0, where the acceleration is 0.
    let limits = scurve(1000.0, 2000.0, 4000.0, 1e5);
    let start = MotionState {
        p: 6000.0,
        v: 1000.0,
        a: 0.0,
    };
    let p = Profile::plan(start, to(5000.0), &limits, &Options::default()).unwrap();
    let stop = p
        .segments()
        .find(|s| s.v == 0.0)
        .expect("a segment starts at rest");
    assert_eq!(stop.a, 0.0);
    // Braking uses Decel, the way back Accel.
    let brake = p.sample(stop.t / 2.0);
    assert!((brake.a + 4000.0).abs() < 1e-6, "{brake:?}");
    let back = (0..1000)
        .map(|i| p.sample(stop.t + (p.duration() - stop.t) * f64::from(i) / 1000.0))
        .filter(|s| s.v * s.a > 0.0)
        .map(|s| s.a.abs())
        .fold(0.0, f64::max);
    assert!((back - 2000.0).abs() <= 2000.0 * TOL, "{back}");
    assert_eq!(p.sample(p.duration()).p, 5000.0);
    // With Accel = Decel the reversal is one continuous ramp: faster than the split one.
    let even = Profile::plan(
        start,
        to(5000.0),
        &scurve(1000.0, 4000.0, 4000.0, 1e5),
        &Options::default(),
    )
    .unwrap();
    assert!(even.segments().all(|s| s.v != 0.0 || s.t == 0.0));
}

#[test]
fn jump_to_zero_ends_where_braking_reaches_the_target() {
    // HMC §2.3.1: Decel lowered during the deceleration; the target comes before the stop.
    let limits = scurve(1000.0, 1000.0, 1000.0, f64::INFINITY);
    let start = MotionState {
        p: 0.0,
        v: 1000.0,
        a: 0.0,
    };
    // Braking from 1000 at 1000 takes 500 units; the target is 375 ahead.
    let opts = Options {
        start_velocity: 0.0,
        overshoot: Overshoot::JumpToZeroAtTarget,
    };
    let p = Profile::plan(start, to(375.0), &limits, &opts).unwrap();
    // 375 = 1000 t − 500 t² → t = 0.5; v = 500 jumps to 0.
    assert!((p.duration() - 0.5).abs() < 1e-12, "{}", p.duration());
    assert!((p.arrival_velocity() - 500.0).abs() < 1e-9);
    assert_eq!(p.sample(0.5).p, 375.0);
    assert_eq!(p.sample(0.5).v, 0.0);
    assert!((p.sample(0.25).a + 1000.0).abs() < 1e-12);
    // Reverse instead passes the target and comes back.
    let r = Profile::plan(start, to(375.0), &limits, &Options::default()).unwrap();
    assert!(r.duration() > 1.0);
    assert!(r.sample(1.0).p > 375.0);
    // A target beyond the stopping point is reached normally in both modes.
    let far = Profile::plan(start, to(2000.0), &limits, &opts).unwrap();
    let far_r = Profile::plan(start, to(2000.0), &limits, &Options::default()).unwrap();
    assert_eq!(far, far_r);
    // So is a target behind the axis: brake, then come back.
    let behind = Profile::plan(start, to(-100.0), &limits, &opts).unwrap();
    let behind_r = Profile::plan(start, to(-100.0), &limits, &Options::default()).unwrap();
    assert_eq!(behind, behind_r);
}

#[test]
fn jump_to_zero_with_an_s_curve() {
    let limits = scurve(1000.0, 1000.0, 1000.0, 5000.0);
    let start = MotionState {
        p: 0.0,
        v: 1000.0,
        a: -500.0,
    };
    let opts = Options {
        start_velocity: 0.0,
        overshoot: Overshoot::JumpToZeroAtTarget,
    };
    let p = Profile::plan(start, to(300.0), &limits, &opts).unwrap();
    assert_eq!(p.sample(p.duration()).p, 300.0);
    assert!(p.arrival_velocity() > 0.0);
    // Pure braking: the acceleration never turns positive, jerk within the limit.
    for i in 0..=1000 {
        let s = p.sample(p.duration() * f64::from(i) / 1000.0);
        assert!(s.a <= 1e-9 && s.j.abs() <= 5000.0, "{s:?}");
        assert!(s.p <= 300.0 + 1e-9);
    }
}

#[test]
fn speed_above_the_limit_decelerates_to_it() {
    // HMC §2.4 fig. 7: Speed lowered mid-move.
    let limits = scurve(500.0, 1000.0, 1000.0, 2e4);
    let start = MotionState {
        p: 0.0,
        v: 1000.0,
        a: 0.0,
    };
    let p = Profile::plan(start, to(10_000.0), &limits, &Options::default()).unwrap();
    let mid = p.sample(p.duration() / 2.0);
    assert!((mid.v - 500.0).abs() < 1e-9, "{mid:?}");
    assert!(p.sample(0.1).v < 1000.0);
}

#[test]
fn acceleration_above_the_limit_is_brought_back_at_jerk() {
    // Accel lowered from 4000 to 1000 while accelerating at 4000.
    let limits = scurve(1000.0, 1000.0, 1000.0, 1e5);
    let start = MotionState {
        p: 0.0,
        v: 100.0,
        a: 4000.0,
    };
    let p = Profile::plan(start, to(10_000.0), &limits, &Options::default()).unwrap();
    assert_eq!(p.sample(0.0).j, -1e5);
    // 3000 / 1e5 = 30 ms to get back to the limit.
    let s = p.sample(0.03 + 1e-9);
    assert!((s.a - 1000.0).abs() < 1e-3, "{s:?}");
    assert_eq!(p.sample(p.duration()).p, 10_000.0);
}

#[test]
fn velocity_goal_with_start_velocity() {
    let limits = scurve(1e4, 1e5, 1e5, f64::INFINITY);
    let opts = Options {
        start_velocity: 500.0,
        overshoot: Overshoot::Reverse,
    };
    let p = Profile::plan(
        MotionState::default(),
        Goal::Velocity { target: -5000.0 },
        &limits,
        &opts,
    )
    .unwrap();
    assert_eq!(p.sample(0.0).v, -500.0);
    assert!((p.duration() - 0.045).abs() < 1e-12);
    assert_eq!(p.sample(1.0).v, -5000.0);
    // A target below the start velocity is jumped to directly.
    let slow = Profile::plan(
        MotionState::default(),
        Goal::Velocity { target: 200.0 },
        &limits,
        &opts,
    )
    .unwrap();
    assert_eq!(slow.duration(), 0.0);
    assert_eq!(slow.sample(2.0).p, 400.0);
    // Targets beyond the velocity limit are clamped to it.
    let fast = Profile::plan(
        MotionState::default(),
        Goal::Velocity { target: 2e4 },
        &limits,
        &Options::default(),
    )
    .unwrap();
    assert_eq!(fast.sample(1.0).v, 1e4);
    assert!(fast.is_velocity_goal());
    assert_eq!(fast.goal(), Goal::Velocity { target: 2e4 });
}

#[test]
fn pulse_sized_numbers() {
    // Ruckig issue #27 territory: jerk 1e10, acceleration 1e6, 1e5 pulses/s, 1e7 pulses.
    let limits = scurve(1e5, 1e6, 1e6, 1e10);
    let p = Profile::plan(
        MotionState {
            p: 123_456_789.0,
            v: 0.0,
            a: 0.0,
        },
        to(133_456_789.0),
        &limits,
        &Options::default(),
    )
    .unwrap();
    // 1e7/1e5 = 100 s cruise-equivalent + v/a + a/j = 0.1 + 1e-4.
    assert!(
        (p.duration() - (100.0 + 0.1 + 1e-4)).abs() < 1e-9,
        "{}",
        p.duration()
    );
    assert_eq!(p.sample(p.duration()).p, 133_456_789.0);
    // And a 1-pulse move with the same limits.
    let p = Profile::plan(
        MotionState::default(),
        to(1.0),
        &limits,
        &Options::default(),
    )
    .unwrap();
    assert!(p.duration() > 0.0 && p.duration() < 0.01);
    assert_eq!(p.sample(1.0).p, 1.0);
}

#[test]
fn end_velocity_arrives_in_the_direction_of_the_final_approach() {
    let limits = scurve(100.0, 1000.0, 1000.0, f64::INFINITY);
    let goal = Goal::Position {
        target: 100.0,
        end_velocity: 50.0,
    };
    // From rest: arrives moving forward.
    let p = Profile::plan(MotionState::default(), goal, &limits, &Options::default()).unwrap();
    assert!((p.arrival_velocity() - 50.0).abs() < 1e-9);
    // Moving fast towards a target it cannot stop before (braking ends at 102): the final
    // approach comes back.
    let start = MotionState {
        p: 97.0,
        v: 100.0,
        a: 0.0,
    };
    let p = Profile::plan(start, goal, &limits, &Options::default()).unwrap();
    assert!((p.arrival_velocity() + 50.0).abs() < 1e-9);
    assert_eq!(
        p.final_state(),
        MotionState {
            p: 100.0,
            v: 0.0,
            a: 0.0
        }
    );
}

/// The cases proptest once shrank to, when the release branch was not taken.
#[test]
fn release_branch_regressions() {
    let cases = [
        (
            MotionState {
                p: 0.0,
                v: 0.852997156377617,
                a: -0.38986961879539445,
            },
            0.8187427513362302,
            scurve(1.0, 1.0, 1.0, 1.0),
            1.9156703366229246,
        ),
        (
            MotionState {
                p: 0.0,
                v: -0.10021063330175074,
                a: 0.4871296437493519,
            },
            -0.013356158551974553,
            scurve(0.1855275193894238, 1.0, 1.0, 3.3796798741986622),
            f64::NAN,
        ),
    ];
    for (start, target, limits, ruckig) in cases {
        let p = Profile::plan(start, to(target), &limits, &Options::default()).unwrap();
        if ruckig.is_finite() {
            assert!(
                (p.duration() - ruckig).abs() < 1e-9 * ruckig,
                "{}",
                p.duration()
            );
        }
        assert_eq!(p.sample(p.duration()).p, target);
    }
}

#[test]
fn profile_is_small_and_copy() {
    fn copy<T: Copy>() {}
    copy::<Profile>();
    assert!(
        std::mem::size_of::<Profile>() <= 640,
        "{}",
        std::mem::size_of::<Profile>()
    );
}

// ---- MovingAverage (NMC smoothCoef, HIMC SMTime) ----

proptest! {
    #![proptest_config(config(300))]

    /// A trapezoid through the moving average: jerk-limited with jerk = acc/T_s, never faster,
    /// n − 1 ticks longer, and exactly on the target at the end.
    #[test]
    fn smoothing_turns_a_trapezoid_into_a_jerk_limited_curve(
        (vel, acc, dec) in (log_uniform(10.0, 1e4), log_uniform(1e4, 1e6), log_uniform(1e4, 1e6)),
        (seconds, p0, n) in (log_uniform(0.01, 2.0), -1e9..1e9f64, 1..200usize),
    ) {
        // At most about 4 s of ticks.
        let dist = vel * seconds;
        let period = 1e-3;
        let limits = Limits { velocity: vel, acceleration: acc, deceleration: dec, jerk: f64::INFINITY };
        let target = p0 + dist;
        let profile = Profile::plan(
            MotionState { p: p0, v: 0.0, a: 0.0 },
            Goal::Position { target, end_velocity: 0.0 },
            &limits,
            &Options::default(),
        ).unwrap();
        let mut filter = MovingAverage::new(n).unwrap();
        filter.reset(p0);
        let ticks = (profile.duration() / period).ceil() as usize + n + 3;
        let input: Vec<f64> = (0..=ticks).map(|k| profile.sample(k as f64 * period).p).collect();
        let output: Vec<f64> = input.iter().map(|&p| filter.next(p)).collect();
        let arrive_in = input.iter().position(|&p| p == target).unwrap();
        // Settled n − 1 ticks after the input (earlier only if an average rounds to it).
        let settled = arrive_in + n - 1;
        prop_assert!(output[settled..].iter().all(|&p| p == target));
        let last_moving = (output[settled - 1] - target).abs();
        prop_assert!(n == 1 || last_moving <= (target - input[arrive_in - 1]).abs());
        prop_assert!(filter.is_settled());
        // Rounding of positions around p0, differenced three times.
        let noise = 64.0 * f64::EPSILON * (p0.abs() + target.abs()) / period.powi(3);
        let jerk_bound = (acc + dec) / (n as f64 * period);
        for w in output.windows(4) {
            let jerk = (w[3] - 3.0 * w[2] + 3.0 * w[1] - w[0]) / period.powi(3);
            prop_assert!(jerk.abs() <= jerk_bound * (1.0 + 1e-6) + noise, "jerk {jerk} > {jerk_bound}");
        }
        for w in output.windows(2) {
            let v = (w[1] - w[0]) / period;
            prop_assert!(v <= vel * (1.0 + 1e-9) + noise * period * period);
        }
    }
}

#[test]
fn smoothing_jerk_is_acc_over_ts() {
    // NMC TV12 trapezoid (acc 5e5, vel 1e4, 10000 pulses) with smoothCoef 20 ms at 1 ms:
    // jerk = 5e5 / 0.02 = 2.5e7 pulse/s³, and the move lasts 19 ms longer.
    let limits = Limits {
        velocity: 1e4,
        acceleration: 5e5,
        deceleration: 5e5,
        jerk: f64::INFINITY,
    };
    let profile = Profile::plan(
        MotionState::default(),
        to(10_000.0),
        &limits,
        &Options::default(),
    )
    .unwrap();
    let mut filter = super::rules::nmc_smoothing(20.0, 1e-3).unwrap();
    let out: Vec<f64> = (0..1100)
        .map(|k| filter.next(profile.sample(f64::from(k) * 1e-3).p))
        .collect();
    let peak_jerk = out
        .windows(4)
        .map(|w| ((w[3] - 3.0 * w[2] + 3.0 * w[1] - w[0]) / 1e-9).abs())
        .fold(0.0, f64::max);
    assert!((peak_jerk - 2.5e7).abs() < 1.0, "{peak_jerk}");
    assert_eq!(out.iter().position(|&p| p == 10_000.0), Some(1020 + 19));
}

proptest! {
    #![proptest_config(config(200))]

    /// The running sum matches a fresh sum over the window, also after many windows.
    #[test]
    fn moving_average_matches_the_window_mean(
        n in 1..64usize,
        offset in -1e9..1e9f64,
        steps in proptest::collection::vec(-10.0..10.0f64, 1..2000),
    ) {
        let mut filter = MovingAverage::new(n).unwrap();
        filter.reset(offset);
        let mut history = vec![offset; n];
        let mut x = offset;
        for step in steps {
            x += step;
            history.push(x);
            let got = filter.next(x);
            let window = &history[history.len() - n..];
            let want = offset + window.iter().map(|p| p - offset).sum::<f64>() / n as f64;
            prop_assert!((got - want).abs() <= 1e-9 * (1.0 + offset.abs()), "{got} vs {want}");
        }
    }
}

#[test]
fn moving_average_is_exact_after_a_long_run() {
    let mut filter = MovingAverage::new(8000).unwrap();
    filter.reset(1e9);
    let mut x = 1e9;
    for k in 0..200_000u32 {
        x += f64::from(k % 97) * 0.013 - 0.6;
        filter.next(x);
    }
    let last = x + 0.1;
    for _ in 0..7999 {
        assert_ne!(filter.next(last), last);
    }
    assert_eq!(filter.next(last), last);
    assert!(filter.is_settled());
}

#[test]
fn sample_from_matches_sample_bit_for_bit() {
    let limits = Limits {
        velocity: 3.0,
        acceleration: 7.0,
        deceleration: 5.0,
        jerk: 40.0,
    };
    let start = MotionState {
        p: -1.0,
        v: 2.5,
        a: -3.0,
    };
    for target in [-20.0, -0.5, 0.0, 0.7, 12.0] {
        let goal = Goal::Position {
            target,
            end_velocity: 0.0,
        };
        let profile = Profile::plan(start, goal, &limits, &Options::default()).unwrap();
        let mut hint = 0;
        let n = 5000;
        for k in 0..=n {
            let t = profile.duration() * 1.1 * k as f64 / n as f64;
            assert_eq!(
                profile.sample_from(t, &mut hint),
                profile.sample(t),
                "t = {t}"
            );
        }
        // A stale or absurd hint, and time going backwards, are still right.
        for (t, mut h) in [(0.0, 12), (profile.duration() / 3.0, 99), (0.01, 5)] {
            assert_eq!(profile.sample_from(t, &mut h), profile.sample(t));
        }
    }
}

#[test]
fn plan_passing_passes_a_target_nearer_than_the_braking_distance_without_turning_back() {
    let limits = Limits {
        velocity: 69.54,
        acceleration: 1237.0,
        deceleration: 1237.0,
        jerk: f64::INFINITY,
    };
    let start = MotionState {
        p: 0.0,
        v: 69.54,
        a: 0.0,
    };
    // Braking from 69.54 takes 1.95: `plan` approaches 1.8 from beyond; `plan_passing` cruises.
    let back = Profile::plan(
        start,
        Goal::Position {
            target: 1.8,
            end_velocity: 69.54,
        },
        &limits,
        &Options::default(),
    )
    .unwrap();
    assert!(back.duration() > 0.1);
    for jerk in [f64::INFINITY, 200_000.0] {
        let limits = Limits { jerk, ..limits };
        let p = Profile::plan_passing(start, 1.8, 60.0, &limits).unwrap();
        assert!(p.duration() < 0.035, "{}", p.duration());
        let mut t = 0.0;
        while t < p.duration() {
            let s = p.sample(t);
            assert!(s.v > 0.0 && s.p <= 1.8 + 1e-12, "{t}: {s:?}");
            t += 1e-4;
        }
        assert_eq!(p.sample(p.duration()).p, 1.8);
        assert!((p.arrival_velocity() - 60.0).abs() < 1e-9);
    }
}
