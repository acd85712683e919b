//! Time-optimality against rsruckig, a Rust port of Ruckig (anchors §22).
//!
//! Ruckig's conditions: |v0| ≤ vmax, |a0| ≤ amax, |a0| ≤ sqrt(2 j (vmax − |v0|)), equal
//! acceleration and deceleration (Ruckig's limits are per sign of a, not per |v| growing), and
//! a target state with a = 0. Ruckig takes a signed target velocity; mcemu's end velocity is a
//! magnitude whose sign the planner picks (the side of the final approach), so each case asks
//! Ruckig for the arrival velocity mcemu chose. Ruckig supports infinite jerk (second-order
//! profiles), so trapezoids are compared too.
//!
//! Tolerance: |mcemu − ruckig| ≤ 1e-9 · ruckig. Over 2 million cases per kind
//! (`ruckig_sweep`, run with `--ignored` in release) the largest relative difference seen was
//! 1.2e-11, in either direction; both solve to about 1e-12 and round.

use super::*;
use proptest::prelude::*;
use rsruckig::prelude::{InputParameter, Ruckig, ThrowErrorHandler, Trajectory};

const REL_TOL: f64 = 1e-9;

/// Ruckig's duration, or None if it refuses the input. With `minimum`, Ruckig's step 2: the
/// shortest duration ≥ `minimum` it can synchronize to (longer than `minimum` only when that
/// is blocked).
pub(super) fn ruckig_duration(
    start: MotionState,
    target: f64,
    target_v: f64,
    limits: &Limits,
    minimum: Option<f64>,
) -> Option<f64> {
    let mut otg = Ruckig::<1, ThrowErrorHandler>::new(None, 0.001);
    let mut input = InputParameter::new(None);
    input.current_position[0] = start.p;
    input.current_velocity[0] = start.v;
    input.current_acceleration[0] = start.a;
    input.target_position[0] = target;
    input.target_velocity[0] = target_v;
    input.max_velocity[0] = limits.velocity;
    input.max_acceleration[0] = limits.acceleration;
    input.max_jerk[0] = limits.jerk;
    input.minimum_duration = minimum;
    let mut traj = Trajectory::new(None);
    otg.calculate(&input, &mut traj).ok()?;
    Some(traj.get_duration())
}

fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..hi.ln()).prop_map(f64::exp)
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Case {
    pub start: MotionState,
    pub target: f64,
    pub end_velocity: f64,
    pub limits: Limits,
}

/// A problem inside Ruckig's conditions; `end` adds an end velocity.
pub(super) fn feasible(jerk_limited: bool, end: bool) -> impl Strategy<Value = Case> {
    (
        (
            log_uniform(0.1, 10.0),
            log_uniform(0.1, 10.0),
            log_uniform(0.1, 100.0),
        ),
        (-1.0..1.0f64, -1.0..1.0f64, 0.0..1.0f64),
        (log_uniform(1e-6, 1000.0), any::<bool>(), 0..8u8),
    )
        .prop_map(
            move |((vmax, amax, jerk), (fv, fa, fe), (dist, neg, zeros))| {
                let jerk = if jerk_limited { jerk } else { f64::INFINITY };
                let v0 = if zeros & 1 == 0 { fv * vmax } else { 0.0 };
                let a_cap = amax.min((2.0 * jerk * (vmax - v0.abs())).sqrt());
                let a0 = if zeros & 2 == 0 && jerk_limited {
                    fa * a_cap
                } else {
                    0.0
                };
                let end_velocity = if end && zeros & 4 == 0 {
                    fe * vmax
                } else {
                    0.0
                };
                Case {
                    start: MotionState {
                        p: 0.0,
                        v: v0,
                        a: a0,
                    },
                    target: if neg { -dist } else { dist },
                    end_velocity,
                    limits: Limits {
                        velocity: vmax,
                        acceleration: amax,
                        deceleration: amax,
                        jerk,
                    },
                }
            },
        )
}

/// (mcemu, ruckig) durations, or None if Ruckig refuses the case.
fn durations(c: &Case) -> Option<(f64, f64)> {
    let profile = Profile::plan(
        c.start,
        Goal::Position {
            target: c.target,
            end_velocity: c.end_velocity,
        },
        &c.limits,
        &Options::default(),
    )
    .ok()?;
    let ve = c.end_velocity.copysign(profile.arrival_velocity());
    let theirs = ruckig_duration(c.start, c.target, ve, &c.limits, None)?;
    Some((profile.duration(), theirs))
}

fn check(c: &Case) -> Result<(), TestCaseError> {
    let (mine, theirs) = durations(c).ok_or_else(|| TestCaseError::fail("ruckig refused"))?;
    prop_assert!(
        (mine - theirs).abs() <= REL_TOL * theirs,
        "mcemu {mine} vs ruckig {theirs} (Δ {:e}) for {c:?}",
        mine - theirs
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 4000,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn s_curve_to_rest_is_as_fast_as_ruckig(c in feasible(true, false)) {
        check(&c)?;
    }

    #[test]
    fn s_curve_with_end_velocity_is_as_fast_as_ruckig(c in feasible(true, true)) {
        check(&c)?;
    }

    #[test]
    fn trapezoid_to_rest_is_as_fast_as_ruckig(c in feasible(false, false)) {
        check(&c)?;
    }

    #[test]
    fn trapezoid_with_end_velocity_is_as_fast_as_ruckig(c in feasible(false, true)) {
        check(&c)?;
    }
}

/// The case that needed the "release above D(lo)" candidate: braking hard through zero towards
/// a negative arrival velocity, slightly beyond the direct ramp's reach.
#[test]
fn release_candidate_beats_the_upper_branch() {
    let c = Case {
        start: MotionState {
            p: 0.0,
            v: 0.5455921572661216,
            a: -5.153734440161333,
        },
        target: 0.004531361309117528,
        end_velocity: 0.2562118070270172,
        limits: Limits {
            velocity: 5.502972202501305,
            acceleration: 6.234529164476569,
            deceleration: 6.234529164476569,
            jerk: 20.908149694159878,
        },
    };
    let (mine, theirs) = durations(&c).unwrap();
    assert!(
        (mine - theirs).abs() <= REL_TOL * theirs,
        "{mine} vs {theirs}"
    );
}

/// 2 million cases per kind; `cargo test --release -p axes ruckig_sweep -- --ignored`.
#[test]
#[ignore = "slow: a long sweep for the record, run in release"]
fn ruckig_sweep() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    for (jerk_limited, end) in [(true, false), (true, true), (false, false), (false, true)] {
        let strategy = feasible(jerk_limited, end);
        let mut worst = 0.0f64;
        for _ in 0..2_000_000 {
            let c = strategy.new_tree(&mut runner).unwrap().current();
            let (mine, theirs) = durations(&c).unwrap();
            let rel = (mine - theirs) / theirs;
            assert!(rel.abs() <= REL_TOL, "{mine} vs {theirs} for {c:?}");
            worst = if rel.abs() > worst.abs() { rel } else { worst };
        }
        println!("jerk limited {jerk_limited}, end velocity {end}: worst relative {worst:e}");
    }
}
