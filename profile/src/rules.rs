//! Vendor profile rules as options of the generic planner.
//!
//! Each controller's velocity-planning rules become a choice of [`Limits`], [`Options`] and an
//! end velocity for [`Profile::plan`](super::Profile::plan), plus a [`MovingAverage`]
//! window where the vendor smooths instead of limiting jerk. Units are SI (user units, /s,
//! /s², seconds); the dialects convert their own (NMC pulse/ms, CPU 226H Hz and ms) first.
//!
//! - **HMC trapezoid/triangle** (digest 000 §3.1): JerkMode 0 is a trapezoid with
//!   Accel/Speed/Decel, which the planner produces with `jerk = ∞`;
//!   [`hmc_trapezoid_duration`] is the manual's closed form, used to check it.
//! - **HMC S-curve** (digest 000 §3.2): JerkMode 1 is the 7-segment jerk-limited profile with
//!   `Accel`/`Decel` as the plateaus and `Jerk` as |da/dt|: [`hmc_limits`]. "The effective
//!   maximum acceleration is limited by Jerk" (§4.2.3.1 (4)) needs no rule: when the move is too
//!   short to reach the plateau the planner's triangular acceleration peaks at
//!   `sqrt(Jerk·Δv)` by itself.
//! - **NMC PTP** (digest 001 §2.5, §4.3): trapezoid with acc/dec, startVel (the velocity jumps
//!   to it), endVel (arrival velocity) and smoothCoef, a moving average of `smoothCoef` ms on the
//!   commanded position: [`nmc_ptp`], [`nmc_smooth_window`].
//! - **HIMC SMTime** (digest 004 §3.7): the same moving average, 0–500 ms:
//!   [`himc_smooth_window`].
//! - **CPU 226H** (digest 003 §2.0 tip 3, §2.9, §2.10): linear ramps between MIN_SPEED and
//!   MAX_SPEED whose acceleration comes from TA/TD or MC_SET_MAX_ACCELE:
//!   [`cpu226h_acceleration`], [`cpu226h_max_acceleration`], [`cpu226h_ramp`].

use super::smoothing::MAX_WINDOW_TICKS;
use super::{Limits, MovingAverage, Options, Overshoot};

/// A vendor rule's parameters that the rules refuse.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum RampError {
    /// CPU 226H App. B tip 3: TA (or TD) = 0 and no maximum acceleration set with
    /// MC_SET_MAX_ACCELE. The instruction reports a parameter fault (STATUS.Bit0).
    #[error("{name} = 0 and no maximum acceleration is set (MC_SET_MAX_ACCELE): parameter fault")]
    NoAcceleration { name: &'static str },
    /// The maximum speed is 0: on the CPU 226H that is the soft stop, not a ramp.
    #[error("maximum speed is 0")]
    ZeroSpeed,
    #[error("{name} = {value}: must be within {min}..={max}")]
    OutOfRange {
        name: &'static str,
        value: f64,
        min: f64,
        max: f64,
    },
    #[error("{name} = {value}: must be a positive number")]
    NotPositive { name: &'static str, value: f64 },
}

/// Limits, options and end velocity for one move under a vendor rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VendorMove {
    pub limits: Limits,
    pub options: Options,
    /// For [`Goal::Position`](super::Goal::Position).
    pub end_velocity: f64,
}

// ---- HMC (digest 000) ----

/// HMC_Move's test (digest 000 §3.1): a move longer than `Speed²/2·(1/Accel + 1/Decel)` is a
/// trapezoid, a shorter one a triangle.
pub fn hmc_is_trapezoid(distance: f64, speed: f64, accel: f64, decel: f64) -> bool {
    distance.abs() > speed * speed / 2.0 * (1.0 / accel + 1.0 / decel)
}

/// Duration of an HMC JerkMode 0 move from rest to rest (digest 000 §3.1): trapezoid
/// `t = Speed/Accel + Speed/Decel + (D − d_acc − d_dec)/Speed`, or triangle with
/// `v_peak = sqrt(2·D·Accel·Decel/(Accel + Decel))`. `None` unless speed, accel and decel are
/// positive and everything is finite.
pub fn hmc_trapezoid_duration(distance: f64, speed: f64, accel: f64, decel: f64) -> Option<f64> {
    let usable = |x: f64| x.is_finite() && x > 0.0;
    if !(distance.is_finite() && usable(speed) && usable(accel) && usable(decel)) {
        return None;
    }
    let d = distance.abs();
    if hmc_is_trapezoid(d, speed, accel, decel) {
        let d_acc = speed * speed / (2.0 * accel);
        let d_dec = speed * speed / (2.0 * decel);
        Some(speed / accel + speed / decel + (d - d_acc - d_dec) / speed)
    } else {
        let v_peak = hmc_triangle_peak(d, accel, decel);
        Some(v_peak / accel + v_peak / decel)
    }
}

/// Peak speed of an HMC triangle move (digest 000 §3.1).
pub fn hmc_triangle_peak(distance: f64, accel: f64, decel: f64) -> f64 {
    (2.0 * distance.abs() * accel * decel / (accel + decel)).sqrt()
}

/// The HMC axis parameters as limits (digest 000 §3.1–3.2): JerkMode 0 (the default) is a
/// trapezoid (`jerk = ∞`), JerkMode 1 the S-curve with `Jerk`.
pub fn hmc_limits(speed: f64, accel: f64, decel: f64, jerk: f64, jerk_mode: bool) -> Limits {
    Limits {
        velocity: speed,
        acceleration: accel,
        deceleration: decel,
        jerk: if jerk_mode { jerk } else { f64::INFINITY },
    }
}

// ---- NMC (digest 001) and HIMC (digest 004) smoothing ----

/// Window of the moving average that realises a smoothing time, in servo ticks (at least 1:
/// no smoothing).
pub fn smoothing_window(smooth_time_s: f64, servo_period_s: f64) -> Result<usize, RampError> {
    if !(servo_period_s.is_finite() && servo_period_s > 0.0) {
        return Err(RampError::NotPositive {
            name: "servo period",
            value: servo_period_s,
        });
    }
    let max = MAX_WINDOW_TICKS as f64 * servo_period_s;
    if !(smooth_time_s.is_finite() && (0.0..=max).contains(&smooth_time_s)) {
        return Err(RampError::OutOfRange {
            name: "smoothing time",
            value: smooth_time_s,
            min: 0.0,
            max,
        });
    }
    // In range by the check above, so the cast neither saturates nor truncates a sign.
    Ok(((smooth_time_s / servo_period_s).round() as usize).clamp(1, MAX_WINDOW_TICKS))
}

/// NMC `smoothCoef` (TPtpPara/TJogPara, 0–199 ms; digest 001 §3.6, §4.3) → moving-average
/// window in ticks.
pub fn nmc_smooth_window(smooth_coef_ms: f64, servo_period_s: f64) -> Result<usize, RampError> {
    if !(0.0..=199.0).contains(&smooth_coef_ms) {
        return Err(RampError::OutOfRange {
            name: "smoothCoef",
            value: smooth_coef_ms,
            min: 0.0,
            max: 199.0,
        });
    }
    smoothing_window(smooth_coef_ms * 1e-3, servo_period_s)
}

/// HIMC `SetSMTime` (0–500 ms; digest 004 §3.7) → moving-average window in ticks.
pub fn himc_smooth_window(sm_time_ms: f64, servo_period_s: f64) -> Result<usize, RampError> {
    if !(0.0..=500.0).contains(&sm_time_ms) {
        return Err(RampError::OutOfRange {
            name: "SMTime",
            value: sm_time_ms,
            min: 0.0,
            max: 500.0,
        });
    }
    smoothing_window(sm_time_ms * 1e-3, servo_period_s)
}

/// An NMC PTP move (digest 001 §2.5, §4.3) in per-second units: a trapezoid (the S shape comes
/// from the smoothCoef moving average, [`nmc_smooth_window`]), starting at `start_vel` and
/// arriving at `end_vel`.
pub fn nmc_ptp(acc: f64, dec: f64, start_vel: f64, end_vel: f64, max_vel: f64) -> VendorMove {
    VendorMove {
        limits: Limits {
            velocity: max_vel,
            acceleration: acc,
            deceleration: dec,
            jerk: f64::INFINITY,
        },
        options: Options {
            start_velocity: start_vel,
            overshoot: Overshoot::Reverse,
        },
        end_velocity: end_vel,
    }
}

/// A moving average for an NMC smoothCoef; see [`nmc_smooth_window`].
pub fn nmc_smoothing(smooth_coef_ms: f64, servo_period_s: f64) -> Result<MovingAverage, RampError> {
    let n = nmc_smooth_window(smooth_coef_ms, servo_period_s)?;
    // The window is within MAX_WINDOW_TICKS by construction.
    MovingAverage::new(n).map_err(|_| RampError::OutOfRange {
        name: "smoothCoef",
        value: smooth_coef_ms,
        min: 0.0,
        max: 199.0,
    })
}

// ---- CPU 226H (digest 003) ----

/// Highest pulse frequency of a CPU 226H axis (Hz): speeds are `DWORD 0~200000`.
pub const CPU226H_MAX_SPEED: f64 = 200_000.0;
/// Longest TA/TD (s): times are `DWORD 0~10000` ms.
pub const CPU226H_MAX_RAMP_TIME: f64 = 10.0;

/// The maximum acceleration set by MC_SET_MAX_ACCELE (digest 003 §2.7): `MAX_SPEED/TA`, or none
/// when TA = 0 ("treated as no max accel set").
pub fn cpu226h_max_acceleration(max_speed: f64, ta_s: f64) -> Option<f64> {
    let max_speed = clamp_speed(max_speed);
    let ta = clamp_time(ta_s);
    (ta > 0.0 && max_speed > 0.0).then(|| max_speed / ta)
}

/// Acceleration of a CPU 226H ramp (App. B tip 3, digest 003 §2.0): TA ≠ 0 →
/// `(MAX_SPEED − MIN_SPEED)/TA`, capped by the maximum acceleration if one is set; TA = 0 → the
/// maximum acceleration; TA = 0 without one → parameter fault. The same rule gives the
/// deceleration from TD. Speeds in Hz, TA in seconds, result in Hz/s.
///
/// Speeds and times out of range are clamped ("not errors; silently set to the nearest
/// reasonable value"), MIN_SPEED above MAX_SPEED is lowered to it. When MIN_SPEED = MAX_SPEED
/// there is nothing to ramp (the move runs at that speed); the acceleration is then only used
/// to brake a move that has to reverse, and is `MAX_SPEED/TA` (capped likewise).
pub fn cpu226h_acceleration(
    min_speed: f64,
    max_speed: f64,
    ta_s: f64,
    max_accel: Option<f64>,
) -> Result<f64, RampError> {
    ramp_acceleration("TA", min_speed, max_speed, ta_s, max_accel)
}

fn ramp_acceleration(
    name: &'static str,
    min_speed: f64,
    max_speed: f64,
    time_s: f64,
    max_accel: Option<f64>,
) -> Result<f64, RampError> {
    let max_speed = clamp_speed(max_speed);
    if max_speed <= 0.0 {
        return Err(RampError::ZeroSpeed);
    }
    let min_speed = clamp_speed(min_speed).min(max_speed);
    let max_accel = max_accel.filter(|a| a.is_finite() && *a > 0.0);
    let time = clamp_time(time_s);
    if time == 0.0 {
        return max_accel.ok_or(RampError::NoAcceleration { name });
    }
    let rise = if max_speed > min_speed {
        max_speed - min_speed
    } else {
        max_speed
    };
    let a = rise / time;
    Ok(max_accel.map_or(a, |m| a.min(m)))
}

/// A CPU 226H move (MC_PTP_R/A, MC_SPEED_CTL; digest 003 §2.9–2.10): the pulse train starts at
/// MIN_SPEED, ramps linearly to MAX_SPEED (SET_SPEED), and ramps back down to MIN_SPEED at the
/// target, where the pulses stop. PTP uses TA for both ramps (pass `td_s = ta_s`); SPEED_CTL
/// has its own TD. Plan position moves with `Goal::Position { end_velocity }` and speed control
/// with `Goal::Velocity`.
pub fn cpu226h_ramp(
    min_speed: f64,
    max_speed: f64,
    ta_s: f64,
    td_s: f64,
    max_accel: Option<f64>,
) -> Result<VendorMove, RampError> {
    let acceleration = ramp_acceleration("TA", min_speed, max_speed, ta_s, max_accel)?;
    let deceleration = ramp_acceleration("TD", min_speed, max_speed, td_s, max_accel)?;
    let max_speed = clamp_speed(max_speed);
    let min_speed = clamp_speed(min_speed).min(max_speed);
    Ok(VendorMove {
        limits: Limits {
            velocity: max_speed,
            acceleration,
            deceleration,
            jerk: f64::INFINITY,
        },
        options: Options {
            start_velocity: min_speed,
            overshoot: Overshoot::Reverse,
        },
        end_velocity: min_speed,
    })
}

fn clamp_speed(hz: f64) -> f64 {
    if hz.is_nan() {
        0.0
    } else {
        hz.clamp(0.0, CPU226H_MAX_SPEED)
    }
}

fn clamp_time(s: f64) -> f64 {
    if s.is_nan() {
        0.0
    } else {
        s.clamp(0.0, CPU226H_MAX_RAMP_TIME)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Goal, MotionState, Profile};

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * a.abs().max(b.abs()).max(1e-300)
    }

    fn plan_from_rest(distance: f64, m: &VendorMove) -> Profile {
        Profile::plan(
            MotionState::default(),
            Goal::Position {
                target: distance,
                end_velocity: m.end_velocity,
            },
            &m.limits,
            &m.options,
        )
        .unwrap()
    }

    #[test]
    fn hmc_example_1_trapezoid() {
        // Digest 000 §8 vector 1: Speed 1000, Accel = Decel = 2000, Move 4000 → 4.5 s.
        assert!(hmc_is_trapezoid(4000.0, 1000.0, 2000.0, 2000.0));
        assert_eq!(
            hmc_trapezoid_duration(4000.0, 1000.0, 2000.0, 2000.0),
            Some(4.5)
        );
        let limits = hmc_limits(1000.0, 2000.0, 2000.0, 5e9, false);
        let p = Profile::plan(
            MotionState::default(),
            Goal::Position {
                target: 4000.0,
                end_velocity: 0.0,
            },
            &limits,
            &Options::default(),
        )
        .unwrap();
        assert!(close(p.duration(), 4.5, 1e-12), "{}", p.duration());
        assert!(close(p.sample(0.5).p, 250.0, 1e-12));
        assert!(close(p.sample(2.0).v, 1000.0, 1e-12));
        assert_eq!(p.sample(4.5).p, 4000.0);
    }

    #[test]
    fn hmc_example_2_triangle() {
        // Vector 2: Speed 2000, Accel = Decel = 1000, Move 1000 → triangle, peak 1000, 2.0 s.
        assert!(!hmc_is_trapezoid(1000.0, 2000.0, 1000.0, 1000.0));
        assert_eq!(hmc_triangle_peak(1000.0, 1000.0, 1000.0), 1000.0);
        assert_eq!(
            hmc_trapezoid_duration(1000.0, 2000.0, 1000.0, 1000.0),
            Some(2.0)
        );
        let limits = hmc_limits(2000.0, 1000.0, 1000.0, 5e9, false);
        let p = Profile::plan(
            MotionState::default(),
            Goal::Position {
                target: 1000.0,
                end_velocity: 0.0,
            },
            &limits,
            &Options::default(),
        )
        .unwrap();
        assert!(close(p.duration(), 2.0, 1e-12));
        assert!(close(p.sample(1.0).v, 1000.0, 1e-12));
    }

    #[test]
    fn hmc_example_3_live_speed_change() {
        // Vector 3: Speed 1000, Accel = Decel = 1000, Move 3000; at t = 2 s Speed := 500.
        // At 2 s: p = 500 + 1000 = 1500, v = 1000. Re-planned: 0.5 s down to 500 (375),
        // 2.0 s at 500 (1000), 0.5 s down (125): ends at 5.0 s, at 3000.
        let limits = hmc_limits(500.0, 1000.0, 1000.0, 5e9, false);
        let p = Profile::plan(
            MotionState {
                p: 1500.0,
                v: 1000.0,
                a: 0.0,
            },
            Goal::Position {
                target: 3000.0,
                end_velocity: 0.0,
            },
            &limits,
            &Options::default(),
        )
        .unwrap();
        assert!(close(2.0 + p.duration(), 5.0, 1e-12), "{}", p.duration());
        assert!(close(p.sample(0.5).p, 1875.0, 1e-12));
        assert!(close(p.sample(1.5).v, 500.0, 1e-12));
    }

    #[test]
    fn hmc_cancel_of_forward_numbers() {
        // Vector 7: Speed = Accel = Decel = 100000: 1 s and 50000 units to full speed.
        let limits = hmc_limits(1e5, 1e5, 1e5, 5e9, false);
        let p = Profile::plan(
            MotionState::default(),
            Goal::Velocity { target: 1e5 },
            &limits,
            &Options::default(),
        )
        .unwrap();
        assert!(close(p.duration(), 1.0, 1e-12));
        assert!(close(p.final_state().p, 50_000.0, 1e-12));
        assert!(close(p.sample(10.0).p, 950_000.0, 1e-12));
    }

    #[test]
    fn hmc_jerk_mode_limits_the_acceleration_of_short_moves() {
        // §4.2.3.1 (4): with JerkMode 1 a short move does not reach Accel.
        let limits = hmc_limits(2000.0, 200_000.0, 200_000.0, 5e6, true);
        let p = Profile::plan(
            MotionState::default(),
            Goal::Position {
                target: 10.0,
                end_velocity: 0.0,
            },
            &limits,
            &Options::default(),
        )
        .unwrap();
        let peak = (0..1000)
            .map(|i| p.sample(p.duration() * i as f64 / 1000.0).a.abs())
            .fold(0.0, f64::max);
        assert!(peak < 200_000.0 * 0.9, "{peak}");
        // Symmetric rest-to-rest triangle: D = 2 a³/j² → a = (D j²/2)^(1/3).
        assert!(close(peak, (10.0 * 5e6f64.powi(2) / 2.0).cbrt(), 1e-2));
    }

    #[test]
    fn nmc_tv12_trapezoid_lasts_1020_ms() {
        // Digest 001 TV12: acc 0.5 pulse/ms², maxVel 10 pulse/ms, 10000 pulses → 1020 ms.
        let m = nmc_ptp(5e5, 5e5, 0.0, 0.0, 1e4);
        let p = plan_from_rest(10_000.0, &m);
        assert!(close(p.duration(), 1.020, 1e-12), "{}", p.duration());
        assert!(close(p.sample(0.5).v, 1e4, 1e-12));
        assert_eq!(p.sample(1.020).p, 10_000.0);
        // TV13: then 10010 more → 20010.
        let p2 = Profile::plan(
            p.final_state(),
            Goal::Position {
                target: 20_010.0,
                end_velocity: 0.0,
            },
            &m.limits,
            &m.options,
        )
        .unwrap();
        assert_eq!(p2.sample(p2.duration()).p, 20_010.0);
    }

    #[test]
    fn nmc_tv14_speed_raised_in_motion() {
        // TV14: PTP at 1 pulse/ms; at 2000 pulses vel := 5 → ramps up in 8 ms, ends at 10000.
        let m = nmc_ptp(5e5, 5e5, 0.0, 0.0, 5e3);
        let p = Profile::plan(
            MotionState {
                p: 2000.0,
                v: 1e3,
                a: 0.0,
            },
            Goal::Position {
                target: 10_000.0,
                end_velocity: 0.0,
            },
            &m.limits,
            &m.options,
        )
        .unwrap();
        assert!(close(p.sample(0.008).v, 5e3, 1e-9));
        assert!(p.sample(0.007).v < 5e3);
        assert_eq!(p.sample(p.duration()).p, 10_000.0);
    }

    #[test]
    fn nmc_tv16_tv18_jog_and_stop() {
        // TV16: jog acc 0.5, vel 5 pulse/ms → full speed after 10 ms, 475 pulses at 100 ms.
        let limits = nmc_ptp(5e5, 5e5, 0.0, 0.0, 5e3).limits;
        let jog = Profile::plan(
            MotionState::default(),
            Goal::Velocity { target: 5e3 },
            &limits,
            &Options::default(),
        )
        .unwrap();
        assert!(close(jog.duration(), 0.010, 1e-12));
        let at = jog.sample(0.1);
        assert!(close(at.p, 475.0, 1e-12), "{}", at.p);
        // TV18: MtStop with dec 0.5 → stops within 10 ms, 25 pulses further.
        let stop = Profile::plan(
            MotionState {
                p: at.p,
                v: at.v,
                a: at.a,
            },
            Goal::Velocity { target: 0.0 },
            &limits,
            &Options::default(),
        )
        .unwrap();
        assert!(close(stop.duration(), 0.010, 1e-12));
        assert!(close(stop.final_state().p, 500.0, 1e-12));
        // TV17: negative jog.
        let neg = Profile::plan(
            MotionState::default(),
            Goal::Velocity { target: -5e3 },
            &limits,
            &Options::default(),
        )
        .unwrap();
        assert_eq!(neg.sample(1.0).v, -5e3);
    }

    #[test]
    fn nmc_start_and_end_velocity() {
        // startVel 1 pulse/ms, endVel 2 pulse/ms: the profile starts at 1000/s and arrives at
        // 2000/s; the pulses then stop.
        let m = nmc_ptp(5e5, 5e5, 1e3, 2e3, 1e4);
        let p = plan_from_rest(10_000.0, &m);
        assert_eq!(p.sample(0.0).v, 1e3);
        assert!(close(p.arrival_velocity(), 2e3, 1e-12));
        let d_up = (1e8 - 1e6) / 1e6;
        let d_down = (1e8 - 4e6) / 1e6;
        let expected = (1e4 - 1e3) / 5e5 + (1e4 - 2e3) / 5e5 + (1e4 - d_up - d_down) / 1e4;
        assert!(close(p.duration(), expected, 1e-12));
    }

    #[test]
    fn smoothing_windows() {
        assert_eq!(nmc_smooth_window(0.0, 1e-3), Ok(1));
        assert_eq!(nmc_smooth_window(50.0, 1e-3), Ok(50));
        assert_eq!(nmc_smooth_window(199.0, 62.5e-6), Ok(3184));
        assert!(nmc_smooth_window(200.0, 1e-3).is_err());
        assert!(nmc_smooth_window(-1.0, 1e-3).is_err());
        assert!(nmc_smooth_window(f64::NAN, 1e-3).is_err());
        assert!(nmc_smooth_window(10.0, 0.0).is_err());
        assert_eq!(himc_smooth_window(500.0, 62.5e-6), Ok(8000));
        assert_eq!(himc_smooth_window(50.0, 1e-3), Ok(50));
        assert!(himc_smooth_window(501.0, 1e-3).is_err());
        assert_eq!(nmc_smoothing(20.0, 1e-3).unwrap().window(), 20);
    }

    #[test]
    fn cpu226h_tv11_acceleration_from_ta() {
        // TV-11: MIN 500, MAX 10500, TA 100 ms, no max accel → 100 Hz/ms, ramp 100 ms, 550
        // pulses each way.
        assert_eq!(cpu226h_acceleration(500.0, 10_500.0, 0.1, None), Ok(1e5));
        let m = cpu226h_ramp(500.0, 10_500.0, 0.1, 0.1, None).unwrap();
        assert_eq!(m.options.start_velocity, 500.0);
        assert_eq!(m.end_velocity, 500.0);
        assert_eq!(m.limits.jerk, f64::INFINITY);
        // 2000 pulses: trapezoid, 0.1 + 900/10500 + 0.1 s.
        let p = plan_from_rest(2000.0, &m);
        assert!(close(p.duration(), 0.2 + 900.0 / 10_500.0, 1e-12));
        assert_eq!(p.sample(0.0).v, 500.0);
        assert!(close(p.sample(0.1).p, 550.0, 1e-12));
        assert!(close(p.arrival_velocity(), 500.0, 1e-12));
        // 1000 < 1100 pulses: triangle, peak sqrt(500² + 1e5·1000).
        let p = plan_from_rest(1000.0, &m);
        let peak = (500.0f64 * 500.0 + 1e5 * 1000.0).sqrt();
        assert!(close(p.sample(p.duration() / 2.0).v, peak, 1e-9));
        assert_eq!(p.sample(p.duration()).p, 1000.0);
    }

    #[test]
    fn cpu226h_tv12_no_acceleration_is_a_parameter_fault() {
        assert_eq!(
            cpu226h_acceleration(500.0, 10_500.0, 0.0, None),
            Err(RampError::NoAcceleration { name: "TA" })
        );
        // MC_SET_MAX_ACCELE with TA = 0 means "none set".
        let none = cpu226h_max_acceleration(20_000.0, 0.0);
        assert_eq!(none, None);
        assert!(cpu226h_acceleration(500.0, 10_500.0, 0.0, none).is_err());
        assert_eq!(
            cpu226h_ramp(500.0, 10_500.0, 0.1, 0.0, None),
            Err(RampError::NoAcceleration { name: "TD" })
        );
    }

    #[test]
    fn cpu226h_tv13_tv14_maximum_acceleration() {
        // TV-13: MC_SET_MAX_ACCELE(MAX 20000, TA 200 ms) → 100 Hz/ms; PTP with TA = 0 uses it.
        let max = cpu226h_max_acceleration(20_000.0, 0.2);
        assert_eq!(max, Some(1e5));
        assert_eq!(cpu226h_acceleration(500.0, 10_500.0, 0.0, max), Ok(1e5));
        // TV-14: MIN 1000, MAX 11000, TA 50 ms asks for 200 Hz/ms → capped at 100: 100 ms ramp.
        let a = cpu226h_acceleration(1000.0, 11_000.0, 0.05, max).unwrap();
        assert_eq!(a, 1e5);
        let m = cpu226h_ramp(1000.0, 11_000.0, 0.05, 0.05, max).unwrap();
        let p = plan_from_rest(100_000.0, &m);
        assert!(p.sample(0.099).v < 11_000.0);
        assert!(close(p.sample(0.1).v, 11_000.0, 1e-12));
    }

    #[test]
    fn cpu226h_clamps() {
        // Out-of-range speeds and times are clamped, not refused.
        let m = cpu226h_ramp(500.0, 1e6, 20.0, 20.0, None).unwrap();
        assert_eq!(m.limits.velocity, CPU226H_MAX_SPEED);
        assert_eq!(m.limits.acceleration, (CPU226H_MAX_SPEED - 500.0) / 10.0);
        // MIN above MAX: lowered to MAX, a constant-speed run.
        let m = cpu226h_ramp(5000.0, 3000.0, 0.1, 0.1, None).unwrap();
        assert_eq!(m.options.start_velocity, 3000.0);
        assert_eq!(m.limits.acceleration, 30_000.0);
        let p = plan_from_rest(3000.0, &m);
        assert!(close(p.duration(), 1.0, 1e-12));
        assert_eq!(
            cpu226h_acceleration(0.0, 0.0, 0.1, None),
            Err(RampError::ZeroSpeed)
        );
    }
}
