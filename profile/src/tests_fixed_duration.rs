//! Properties of the fixed-duration planner ([`Profile::plan_for_duration`]): the duration is
//! the one asked for (within [`DURATION_TOL`] relative), the target and end velocity are reached
//! exactly, the limits hold (the same checks, tolerances and dense sampling as the time-optimal
//! planner's, `tests::check_profile`), the time-optimal duration gives the time-optimal profile,
//! a longer duration never raises the peak velocity, and moves from rest are never blocked.

use super::tests::{check_profile, config, log_uniform, Problem, TOL};
use super::tests_ruckig::{feasible, ruckig_duration, Case};
use super::*;
use proptest::prelude::*;

impl Case {
    fn optimal(&self) -> Profile {
        Profile::plan(self.start, self.goal(), &self.limits, &Options::default())
            .unwrap_or_else(|e| panic!("{e} for {self:?}"))
    }

    fn goal(&self) -> Goal {
        Goal::Position {
            target: self.target,
            end_velocity: self.end_velocity,
        }
    }

    fn plan(&self, duration: f64) -> Result<Profile, DurationError> {
        Profile::plan_for_duration(
            self.start,
            self.target,
            self.end_velocity,
            &self.limits,
            duration,
        )
    }

    fn problem(&self) -> Problem {
        Problem {
            start: self.start,
            goal: self.goal(),
            limits: self.limits,
            options: Options::default(),
        }
    }
}

/// Stretch factors: exactly 1, just above 1, moderate, and very long.
fn stretches() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(1.0),
        2 => log_uniform(1e-9, 1e-2).prop_map(|x| 1.0 + x),
        4 => log_uniform(1.0, 10.0),
        1 => log_uniform(10.0, 1e6),
    ]
}

/// Random cases, with a stretch factor (requested / time-optimal duration): limits 1e-2 … 1e4 each, equal or unequal acceleration and deceleration,
/// trapezoids (`jerk_limited` false) or S-curves; starts at rest, inside and outside the
/// limits (`from_rest` keeps v0 = a0 = 0); distances from 1e-6 to 1e4 move lengths, or 0;
/// end velocities 0 or up to 1.2 × the limit (`to_rest` keeps 0).
pub(super) fn cases(
    jerk_limited: bool,
    from_rest: bool,
    to_rest: bool,
) -> impl Strategy<Value = (Case, f64)> {
    (
        (
            log_uniform(1e-2, 1e4),
            log_uniform(1e-2, 1e4),
            log_uniform(1e-2, 1e4),
            prop_oneof![Just(1.0), log_uniform(0.1, 10.0)],
        ),
        (-1.0..1.0f64, -1.0..1.0f64, 0..3u8, 0..3u8),
        (-1.0..1.0f64, -6.0..4.0f64, 0..6u8, 0.0..1.2f64),
        (-1e3..1e3f64, stretches()),
    )
        .prop_map(
            move |(
                (vel, acc, jerk, dec_ratio),
                (fv, fa, kv, ka),
                (fd, exp, kind, fe),
                (fp, stretch),
            )| {
                let limits = Limits {
                    velocity: vel,
                    acceleration: acc,
                    deceleration: acc * dec_ratio,
                    jerk: if jerk_limited { jerk } else { f64::INFINITY },
                };
                let length = vel * vel / acc;
                let factor = |k: u8| {
                    if from_rest {
                        0.0
                    } else {
                        [0.0, 1.0, 3.0][usize::from(k)]
                    }
                };
                let start = MotionState {
                    p: fp * length,
                    v: fv * vel * factor(kv),
                    a: fa * acc * factor(ka),
                };
                let distance = fd.signum() * length * 10f64.powf(exp);
                let (target, end_velocity) = match kind {
                    0 => (start.p, 0.0),
                    1..=3 => (start.p + distance, 0.0),
                    _ if to_rest => (start.p + distance, 0.0),
                    _ => (start.p + distance, fe * vel),
                };
                let case = Case {
                    start,
                    target,
                    end_velocity,
                    limits,
                };
                (case, stretch)
            },
        )
}

/// The largest |v| over the profile, sampled densely, at every segment start and on arrival.
fn peak_speed(p: &Profile) -> f64 {
    let d = p.duration();
    (0..=2000)
        .map(|i| d * f64::from(i) / 2000.0)
        .chain(p.segment_times())
        .map(|t| p.sample(t).v.abs())
        .fold(p.arrival_velocity().abs(), f64::max)
}

/// Checks a planned profile of requested duration `duration`.
fn check(c: &Case, duration: f64, p: &Profile) -> Result<(), TestCaseError> {
    prop_assert!(
        (p.duration() - duration).abs() <= DURATION_TOL * duration,
        "duration {} instead of {duration} for {c:?}",
        p.duration()
    );
    check_profile(&c.problem(), p)
}

/// Plans `c` at `stretch` × its optimal duration; Ok(None) when that is blocked.
fn plan_stretched(c: &Case, stretch: f64) -> Result<Option<(f64, Profile)>, TestCaseError> {
    let duration = c.optimal().duration() * stretch;
    match c.plan(duration) {
        Ok(p) => {
            check(c, duration, &p)?;
            Ok(Some((duration, p)))
        }
        Err(DurationError::Blocked { .. }) => Ok(None),
        Err(e) => Err(TestCaseError::fail(format!("{e} for {c:?}"))),
    }
}

/// From rest: planned at its stretch and at `more` times that, never blocked, and the longer
/// profile is never faster.
fn from_rest_and_longer(c: &Case, stretch: f64, more: f64) -> Result<(), TestCaseError> {
    let (duration, p) = plan_stretched(c, stretch)?
        .ok_or_else(|| TestCaseError::fail(format!("blocked: {c:?}")))?;
    let longer = c
        .plan(duration * more)
        .map_err(|e| TestCaseError::fail(format!("{e} for {c:?}")))?;
    check(c, duration * more, &longer)?;
    prop_assert!(
        peak_speed(&longer) <= peak_speed(&p) * (1.0 + TOL),
        "{} after {} for {c:?}",
        peak_speed(&longer),
        peak_speed(&p)
    );
    Ok(())
}

proptest! {
    #![proptest_config(config(4000))]

    /// Any start state: a profile of exactly the duration that meets every invariant, or a
    /// blocked duration; never another error.
    #[test]
    fn trapezoid_takes_the_duration_asked_for((c, stretch) in cases(false, false, false)) {
        plan_stretched(&c, stretch)?;
    }

    #[test]
    fn s_curve_takes_the_duration_asked_for((c, stretch) in cases(true, false, false)) {
        plan_stretched(&c, stretch)?;
    }

    #[test]
    fn s_curve_from_rest_is_never_blocked_and_slows_down(
        (c, stretch) in cases(true, true, false),
        more in log_uniform(1.0 + 1e-6, 100.0),
    ) {
        from_rest_and_longer(&c, stretch, more)?;
    }

    /// From rest, every duration ≥ the optimum is possible, and a longer one never moves
    /// faster.
    #[test]
    fn trapezoid_from_rest_is_never_blocked_and_slows_down(
        (c, stretch) in cases(false, true, false),
        more in log_uniform(1.0 + 1e-6, 100.0),
    ) {
        from_rest_and_longer(&c, stretch, more)?;
    }

    /// The time-optimal duration gives the time-optimal profile.
    #[test]
    fn optimal_duration_gives_the_optimal_profile(
        (c, _) in prop_oneof![cases(false, false, false), cases(true, false, false)],
    ) {
        let optimal = c.optimal();
        prop_assert_eq!(c.plan(optimal.duration()), Ok(optimal));
    }
}

/// Rest to rest, trapezoid: the peak is the smaller root of k·vp² − T·vp + d = 0,
/// k = 1/2a + 1/2d (ramps vp/a and vp/d, cruise (d − k·vp²)/vp).
/// A trapezoid stretched 38 000 times (CI's proptest found it): the end of its last ramp is
/// sampled at t ≈ 1.6e7 s, where rounding the time leaves a velocity of −3e-10 instead of 0;
/// the phase check must not take that sign for a reversal.
#[test]
fn a_very_long_trapezoid_meets_the_phase_limits() {
    let c = Case {
        start: MotionState {
            p: 0.0,
            v: 0.0,
            a: 0.0,
        },
        target: 11.07091242912458,
        end_velocity: 0.0,
        limits: Limits {
            velocity: 0.026532159312857462,
            acceleration: 0.4812768934877148,
            deceleration: 0.6728582991616205,
            jerk: f64::INFINITY,
        },
    };
    let planned = plan_stretched(&c, 38020.20642061043);
    assert!(matches!(planned, Ok(Some(_))), "{planned:?}");
}

#[test]
fn trapezoid_rest_to_rest_cruises_at_the_closed_form_velocity() {
    let limits = Limits {
        velocity: 10.0,
        acceleration: 4.0,
        deceleration: 2.0,
        jerk: f64::INFINITY,
    };
    // Optimal: 10 at 4 (2.5 s, 12.5) and 2 (5 s, 25), 62.5 at 10: 13.75 s.
    let start = MotionState {
        p: 5.0,
        v: 0.0,
        a: 0.0,
    };
    let optimal = Profile::plan(
        start,
        Goal::Position {
            target: 105.0,
            end_velocity: 0.0,
        },
        &limits,
        &Options::default(),
    )
    .unwrap();
    assert!((optimal.duration() - 13.75).abs() < 1e-12);
    let k = 1.0 / 8.0 + 1.0 / 4.0;
    for duration in [14.0, 20.0, 100.0, 1e6] {
        let p = Profile::plan_for_duration(start, 105.0, 0.0, &limits, duration).unwrap();
        let vp = 2.0 * 100.0 / (duration + (duration * duration - 4.0 * k * 100.0).sqrt());
        assert!(
            (p.sample(vp / 4.0).v - vp).abs() <= 1e-12 * vp,
            "{duration}"
        );
        assert!((p.duration() - duration).abs() <= 1e-12 * duration);
        assert_eq!(p.sample(duration).p, 105.0);
        assert_eq!(p.final_state().v, 0.0);
    }
}

#[test]
fn zero_distance_from_rest_stays_put_for_the_duration() {
    for jerk in [f64::INFINITY, 7.0] {
        let limits = Limits {
            velocity: 1.0,
            acceleration: 2.0,
            deceleration: 3.0,
            jerk,
        };
        let start = MotionState {
            p: -2.5,
            v: 0.0,
            a: 0.0,
        };
        assert_eq!(
            Profile::plan_for_duration(start, -2.5, 0.0, &limits, 0.0),
            Ok(Profile::hold(-2.5))
        );
        let p = Profile::plan_for_duration(start, -2.5, 0.0, &limits, 4.0).unwrap();
        assert_eq!(p.duration(), 4.0);
        for i in 0..=100 {
            let s = p.sample(0.05 * f64::from(i));
            assert_eq!((s.p, s.v, s.a, s.j), (-2.5, 0.0, 0.0, 0.0));
        }
    }
}

#[test]
fn too_short_and_invalid_durations_are_refused() {
    let limits = Limits {
        velocity: 1.0,
        acceleration: 1.0,
        deceleration: 1.0,
        jerk: f64::INFINITY,
    };
    let start = MotionState::default();
    // Optimal: 1 s up, 1 s cruise, 1 s down.
    let plan = |duration| Profile::plan_for_duration(start, 2.0, 0.0, &limits, duration);
    assert_eq!(
        plan(2.9),
        Err(DurationError::TooShort {
            duration: 2.9,
            minimum: 3.0
        })
    );
    for bad in [f64::NAN, -1.0, f64::INFINITY] {
        assert!(matches!(
            plan(bad),
            Err(DurationError::InvalidDuration { .. })
        ));
    }
    let bad_limits = Limits {
        velocity: 0.0,
        ..limits
    };
    assert!(matches!(
        Profile::plan_for_duration(start, 2.0, 0.0, &bad_limits, 5.0),
        Err(DurationError::Plan(PlanError::InvalidLimit { .. }))
    ));
}

/// Moving at full speed towards a target it is to pass at full speed: slower arrivals dip to
/// a lower speed vc and back, covering 1 − vc² + vc·tc in 2(1 − vc) + tc (units 1). The
/// longest of them, with no cruise, lasts 2(1 − √0.2) ≈ 1.106 s; a reversal (vc < 0) first
/// fits at 2(1 + √0.2) ≈ 2.894 s. Between, the durations are blocked.
#[test]
fn durations_between_the_longest_dip_and_the_shortest_reversal_are_blocked() {
    let limits = Limits {
        velocity: 1.0,
        acceleration: 1.0,
        deceleration: 1.0,
        jerk: f64::INFINITY,
    };
    let start = MotionState {
        p: 0.0,
        v: 1.0,
        a: 0.0,
    };
    let plan = |duration| Profile::plan_for_duration(start, 0.8, 1.0, &limits, duration);
    assert_eq!(plan(0.8).unwrap().duration(), 0.8);
    // vc² + (T − 2)·vc + 0.2 = 0 with tc = T − 2(1 − vc) ≥ 0.
    let p = plan(1.0).unwrap();
    let vc = (1.0 + 0.2f64.sqrt()) / 2.0;
    assert!((p.sample(0.5).v - vc).abs() < 1e-12, "{:?}", p.sample(0.5));
    assert!((p.duration() - 1.0).abs() < 1e-15);
    for blocked in [1.2, 2.0, 2.8] {
        assert_eq!(
            plan(blocked),
            Err(DurationError::Blocked {
                duration: blocked,
                minimum: 0.8
            })
        );
    }
    let p = plan(3.0).unwrap();
    let vc = (-1.0 + 0.2f64.sqrt()) / 2.0;
    assert!((p.sample(1.5).v - vc).abs() < 1e-12, "{:?}", p.sample(1.5));
    assert_eq!(p.sample(3.0).p, 0.8);
    assert!((p.arrival_velocity() - 1.0).abs() < 1e-12);
}

// ---- Against Ruckig's step 2 (rsruckig with `minimum_duration`) ----

/// (ours, Ruckig's): whether each plans exactly `stretch` × the optimal duration; Ruckig
/// answers with a longer duration when that one is blocked, and None when it refuses (seen
/// with stretches of a few hundred and a low jerk). Cases inside Ruckig's input conditions
/// (`tests_ruckig::feasible`).
fn both_plan(c: &Case, stretch: f64) -> Result<(bool, Option<bool>), TestCaseError> {
    let optimal = c.optimal();
    let duration = optimal.duration() * stretch;
    let ours = match c.plan(duration) {
        Ok(p) => {
            check(c, duration, &p)?;
            true
        }
        Err(DurationError::Blocked { .. }) => false,
        Err(e) => return Err(TestCaseError::fail(format!("{e} for {c:?}"))),
    };
    let ve = c.end_velocity.copysign(optimal.arrival_velocity());
    let theirs = ruckig_duration(c.start, c.target, ve, &c.limits, Some(duration));
    Ok((
        ours,
        theirs.map(|t| (t - duration).abs() <= 1e-8 * duration),
    ))
}

fn ruckig_stretches() -> impl Strategy<Value = f64> {
    prop_oneof![
        log_uniform(1e-6, 1e-2).prop_map(|x| 1.0 + x),
        log_uniform(1.0, 10.0),
        log_uniform(10.0, 1e3),
    ]
}

proptest! {
    #![proptest_config(config(500))]

    /// Trapezoids: the same durations are possible and the same are blocked.
    #[test]
    fn trapezoid_durations_are_blocked_exactly_where_ruckig_blocks_them(
        c in prop_oneof![feasible(false, false), feasible(false, true)],
        stretch in ruckig_stretches(),
    ) {
        let (ours, theirs) = both_plan(&c, stretch)?;
        let theirs = theirs.ok_or_else(|| TestCaseError::reject("ruckig refused"))?;
        prop_assert_eq!(ours, theirs, "mcemu planned {}, ruckig {} for {:?} × {}", ours, theirs, c, stretch);
    }

    /// S-curves: a duration planned here is one Ruckig can synchronize to (this family is a
    /// subset of Ruckig's profiles, so not the other way round), and rest to rest both plan
    /// every duration.
    #[test]
    fn s_curve_durations_are_a_subset_of_ruckigs(
        c in prop_oneof![feasible(true, false), feasible(true, true)],
        stretch in ruckig_stretches(),
    ) {
        let (ours, theirs) = both_plan(&c, stretch)?;
        let theirs = theirs.ok_or_else(|| TestCaseError::reject("ruckig refused"))?;
        prop_assert!(!ours || theirs, "mcemu planned a duration ruckig blocks: {:?} × {}", c, stretch);
        if c.start == MotionState::default() && c.end_velocity == 0.0 {
            prop_assert!(ours && theirs, "rest to rest: mcemu {}, ruckig {}", ours, theirs);
        }
    }
}

/// How often each blocks, over many random cases: `cargo test --release -p axes
/// fixed_duration_coverage -- --ignored --nocapture`.
#[test]
#[ignore = "slow: statistics for the record, run in release"]
fn fixed_duration_coverage() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    for (jerk_limited, end) in [(true, false), (true, true), (false, false), (false, true)] {
        let strategy = (feasible(jerk_limited, end), ruckig_stretches());
        let mut counts = [[0u32; 2]; 2];
        let mut refused = 0;
        for _ in 0..100_000 {
            let (c, stretch) = strategy.new_tree(&mut runner).unwrap().current();
            match both_plan(&c, stretch).unwrap() {
                (ours, Some(theirs)) => counts[usize::from(ours)][usize::from(theirs)] += 1,
                (_, None) => refused += 1,
            }
        }
        println!(
            "jerk limited {jerk_limited}, end velocity {end}: both plan {}, only ruckig {}, \
             only mcemu {}, both blocked {}, ruckig refused {refused}",
            counts[1][1], counts[0][1], counts[1][0], counts[0][0]
        );
    }
}

/// S-curve from rest to speed 1 (limits 1): the ramp takes 2 s and covers 1. For 1.2 in 2.4 s
/// a cruise at vc between 0 and 1 does not fit (two ramps through vc take 2√vc + 2√(1 − vc),
/// over 2.4 for vc in 0.051 … 0.949, and outside that they cover too little or too much), so
/// the profile waits 0.2 s, ramps, and cruises at 1 for 0.2 s.
#[test]
fn s_curve_between_start_and_end_velocity_cruises_at_both() {
    let limits = Limits {
        velocity: 1.0,
        acceleration: 1.0,
        deceleration: 1.0,
        jerk: 1.0,
    };
    let start = MotionState::default();
    let p = Profile::plan_for_duration(start, 1.2, 1.0, &limits, 2.4).unwrap();
    assert!((p.duration() - 2.4).abs() < 1e-15);
    assert_eq!(p.sample(0.19), Sample::default());
    let ramp_end = p.sample(2.2);
    assert!((ramp_end.v - 1.0).abs() < 1e-12 && (ramp_end.p - 1.0).abs() < 1e-12);
    assert!((p.sample(2.3).p - 1.1).abs() < 1e-12);
    assert_eq!(p.sample(p.duration()).p, 1.2);
    assert!((p.arrival_velocity() - 1.0).abs() < 1e-15);
}
