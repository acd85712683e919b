//! HIMC group motion profiles (digest 004 §8.3.6 SetGrpMotionProfile, §8.3.7
//! SetGrpAngMotionProfile; TV 47–49): the vendor's ranges and defaults, the group error each
//! out-of-range value returns (Table 18.1.3.1, digest 004 §5.3), and the engine group
//! parameters a profile becomes. The engine itself only asks for positive, finite limits; the
//! HIMC's ranges are checked here, by the front-end that speaks HIMC.

use std::ops::RangeInclusive;

use axes::command::GroupParameter;

use super::{compose, GROUP_CLASS, SMOOTHING_MS};

/// Which of the group's two TCP profiles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Profile {
    /// SetGrpMotionProfile: X, Y, Z in mm/s, mm/s².
    Linear,
    /// SetGrpAngMotionProfile: A, B, C in deg/s, deg/s².
    Angular,
}

/// One profile as HMPL gives it: `max_velocity, max_acceleration, max_deceleration,
/// smooth_time` (the last in ms).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileValues {
    pub velocity: f64,
    pub acceleration: f64,
    pub deceleration: f64,
    pub smooth_ms: f64,
}

/// A group error of Table 18.1.3.1 that a profile setter returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GroupError {
    /// VVVV, the low word of the code.
    pub value: u16,
    /// The manual's name.
    pub name: &'static str,
}

impl GroupError {
    /// This error of group `group` as the functions return it: 0x82NNVVVV.
    pub const fn code(&self, group: u8) -> u32 {
        compose(GROUP_CLASS, group, self.value)
    }
}

/// The range of one value: `0 ~ max` (`open_at_zero`: `> 0 ~ max`, the manual's "cannot be 0").
#[derive(Clone, Debug, PartialEq)]
struct Range {
    values: RangeInclusive<f64>,
    open_at_zero: bool,
    error: GroupError,
}

impl Range {
    fn holds(&self, v: f64) -> bool {
        self.values.contains(&v) && !(self.open_at_zero && v == 0.0)
    }
}

const fn error(value: u16, name: &'static str) -> GroupError {
    GroupError { value, name }
}

/// The ranges of a profile, in HMPL order (velocity, acceleration, deceleration, smoothing).
fn ranges(profile: Profile) -> [Range; 4] {
    let (v, a, e) = match profile {
        // §8.3.6: vel 0 ~ 5000 mm/s; acc and dec > 0 ~ 50 000 mm/s²; smooth 0 ~ 500 ms.
        Profile::Linear => (
            5000.0,
            50_000.0,
            [
                error(0x00dc, "eERR_CRD_CMD_INVALID_LIN_VEL"),
                error(0x00e6, "eERR_CRD_CMD_INVALID_LIN_ACC"),
                error(0x00f0, "eERR_CRD_CMD_INVALID_LIN_DEC"),
                error(0x0104, "eERR_CRD_CMD_INVALID_LIN_SM_TIME"),
            ],
        ),
        // §8.3.7: 0 ~ 7200 deg/s; > 0 ~ 72 000 deg/s²; smooth 0 ~ 500 ms.
        Profile::Angular => (
            7200.0,
            72_000.0,
            [
                error(0x0140, "eERR_CRD_CMD_INVALID_ANG_VEL"),
                error(0x014a, "eERR_CRD_CMD_INVALID_ANG_ACC"),
                error(0x0154, "eERR_CRD_CMD_INVALID_ANG_DEC"),
                error(0x0168, "eERR_CRD_CMD_INVALID_ANG_SM_TIME"),
            ],
        ),
    };
    let [ev, ea, ed, es] = e;
    [
        Range {
            values: 0.0..=v,
            open_at_zero: false,
            error: ev,
        },
        Range {
            values: 0.0..=a,
            open_at_zero: true,
            error: ea,
        },
        Range {
            values: 0.0..=a,
            open_at_zero: true,
            error: ed,
        },
        Range {
            values: SMOOTHING_MS,
            open_at_zero: false,
            error: es,
        },
    ]
}

/// The defaults of a fresh group (TV 48: [100, 5000, 5000, 50]; TV 49: [360, 1800, 1800, 50]).
pub const fn defaults(profile: Profile) -> ProfileValues {
    match profile {
        Profile::Linear => ProfileValues {
            velocity: 100.0,
            acceleration: 5000.0,
            deceleration: 5000.0,
            smooth_ms: 50.0,
        },
        Profile::Angular => ProfileValues {
            velocity: 360.0,
            acceleration: 1800.0,
            deceleration: 1800.0,
            smooth_ms: 50.0,
        },
    }
}

/// Check a profile against the HIMC's ranges: the first value out of range (NaN included)
/// gives its group error, as the HMPL call returns it (TV 47, TV 49).
pub fn check(profile: Profile, values: &ProfileValues) -> Result<(), GroupError> {
    let given = [
        values.velocity,
        values.acceleration,
        values.deceleration,
        values.smooth_ms,
    ];
    match ranges(profile)
        .into_iter()
        .zip(given)
        .find(|(r, v)| !r.holds(*v))
    {
        Some((r, _)) => Err(r.error),
        None => Ok(()),
    }
}

/// The largest velocity, acceleration and deceleration a profile may have (§8.3.6, §8.3.7):
/// the group limits' values until `SetConfigVar` lowers them (`HCV_ID_grp_lin_vel_lim` …).
pub fn maxima(profile: Profile) -> [f64; 3] {
    let [v, a, d, _] = ranges(profile);
    [*v.values.end(), *a.values.end(), *d.values.end()]
}

/// [`check`], then the velocity, acceleration and deceleration against the group's `limits`
/// (each at most its [`maxima`]): over a limit is the value's range error.
pub fn check_within(
    profile: Profile,
    values: &ProfileValues,
    limits: [f64; 3],
) -> Result<(), GroupError> {
    check(profile, values)?;
    let given = [values.velocity, values.acceleration, values.deceleration];
    match ranges(profile)
        .into_iter()
        .zip(given.into_iter().zip(limits))
        .find(|(_, (v, limit))| v > limit)
    {
        Some((r, _)) => Err(r.error),
        None => Ok(()),
    }
}

/// The engine group parameters a checked profile sets (`group_set_parameter`): the velocity
/// and accelerations as they are, the smoothing time as a jerk time, jerk = acceleration / Ts
/// (digest 004 §5.1; 0 ms: none, a trapezoid). A velocity of 0, which the HIMC takes, is
/// refused by the engine (a path at 0 never ends).
pub fn parameters(profile: Profile, values: &ProfileValues) -> [(GroupParameter, f64); 4] {
    let names = match profile {
        Profile::Linear => [
            GroupParameter::Velocity,
            GroupParameter::Acceleration,
            GroupParameter::Deceleration,
            GroupParameter::Jerk,
        ],
        Profile::Angular => [
            GroupParameter::AngularVelocity,
            GroupParameter::AngularAcceleration,
            GroupParameter::AngularDeceleration,
            GroupParameter::AngularJerk,
        ],
    };
    let jerk = if values.smooth_ms > 0.0 {
        values.acceleration / super::ms_to_seconds(values.smooth_ms)
    } else {
        0.0
    };
    let [v, a, d, j] = names;
    [
        (v, values.velocity),
        (a, values.acceleration),
        (d, values.deceleration),
        (j, jerk),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use axes::group::{DEFAULT_ANGULAR_LIMITS, DEFAULT_PATH_LIMITS};

    fn values(v: [f64; 4]) -> ProfileValues {
        ProfileValues {
            velocity: v[0],
            acceleration: v[1],
            deceleration: v[2],
            smooth_ms: v[3],
        }
    }

    #[test]
    fn limits_below_the_ranges_refuse_what_exceeds_them() {
        assert_eq!(maxima(Profile::Linear), [5000.0, 50_000.0, 50_000.0]);
        assert_eq!(maxima(Profile::Angular), [7200.0, 72_000.0, 72_000.0]);
        let v = values([200.0, 5000.0, 5000.0, 50.0]);
        assert_eq!(
            check_within(Profile::Linear, &v, [200.0, 5000.0, 5000.0]),
            Ok(())
        );
        let over = |limits| check_within(Profile::Linear, &v, limits).unwrap_err().name;
        assert_eq!(
            over([199.0, 5000.0, 5000.0]),
            "eERR_CRD_CMD_INVALID_LIN_VEL"
        );
        assert_eq!(
            over([200.0, 5000.0, 4999.0]),
            "eERR_CRD_CMD_INVALID_LIN_DEC"
        );
    }

    #[test]
    fn tv47_linear_profiles_out_of_range_return_their_group_errors() {
        // SetGrpMotionProfile(0, 5001, 5000, 5000, 50); (0, 100, 0, 5000, 50);
        // (0, 100, 5000, 5000, 501): each ≠ 0.
        for (v, name) in [
            (
                [5001.0, 5000.0, 5000.0, 50.0],
                "eERR_CRD_CMD_INVALID_LIN_VEL",
            ),
            ([100.0, 0.0, 5000.0, 50.0], "eERR_CRD_CMD_INVALID_LIN_ACC"),
            (
                [100.0, 5000.0, 5000.0, 501.0],
                "eERR_CRD_CMD_INVALID_LIN_SM_TIME",
            ),
            (
                [100.0, 5000.0, 50_001.0, 50.0],
                "eERR_CRD_CMD_INVALID_LIN_DEC",
            ),
            (
                [f64::NAN, 5000.0, 5000.0, 50.0],
                "eERR_CRD_CMD_INVALID_LIN_VEL",
            ),
            ([-1.0, 5000.0, 5000.0, 50.0], "eERR_CRD_CMD_INVALID_LIN_VEL"),
        ] {
            let e = check(Profile::Linear, &values(v)).unwrap_err();
            assert_eq!(e.name, name, "{v:?}");
        }
        assert_eq!(
            check(Profile::Linear, &values([100.0, 0.0, 5000.0, 50.0]))
                .unwrap_err()
                .code(0),
            0x8200_00e6
        );
        // The edges are in range: 0 and 5000 mm/s, 50 000 mm/s², 0 and 500 ms.
        for v in [[0.0, 50_000.0, 50_000.0, 0.0], [5000.0, 1e-9, 1e-9, 500.0]] {
            assert_eq!(check(Profile::Linear, &values(v)), Ok(()), "{v:?}");
        }
    }

    #[test]
    fn tv49_angular_profiles_out_of_range_return_their_group_errors() {
        // SetGrpAngMotionProfile(0, 7201, 1800, 1800, 50) ≠ 0.
        let e = check(Profile::Angular, &values([7201.0, 1800.0, 1800.0, 50.0])).unwrap_err();
        assert_eq!(e.name, "eERR_CRD_CMD_INVALID_ANG_VEL");
        assert_eq!(e.code(2), 0x8202_0140);
        for (v, name) in [
            (
                [360.0, 72_001.0, 1800.0, 50.0],
                "eERR_CRD_CMD_INVALID_ANG_ACC",
            ),
            ([360.0, 1800.0, 0.0, 50.0], "eERR_CRD_CMD_INVALID_ANG_DEC"),
            (
                [360.0, 1800.0, 1800.0, 500.5],
                "eERR_CRD_CMD_INVALID_ANG_SM_TIME",
            ),
        ] {
            assert_eq!(check(Profile::Angular, &values(v)).unwrap_err().name, name);
        }
        assert_eq!(
            check(
                Profile::Angular,
                &values([7200.0, 72_000.0, 72_000.0, 500.0])
            ),
            Ok(())
        );
    }

    #[test]
    fn tv48_tv49_the_defaults_are_in_range_and_are_the_engines() {
        for (profile, engine) in [
            (Profile::Linear, DEFAULT_PATH_LIMITS),
            (Profile::Angular, DEFAULT_ANGULAR_LIMITS),
        ] {
            let d = defaults(profile);
            assert_eq!(check(profile, &d), Ok(()));
            let p = parameters(profile, &d);
            assert_eq!(
                [p[0].1, p[1].1, p[2].1, p[3].1],
                [
                    engine.velocity,
                    engine.acceleration,
                    engine.deceleration,
                    engine.jerk
                ],
                "{profile:?}"
            );
        }
        assert_eq!(defaults(Profile::Linear).smooth_ms, 50.0);
        let no_smoothing = parameters(Profile::Angular, &values([360.0, 1800.0, 1800.0, 0.0]));
        assert_eq!(no_smoothing[3], (GroupParameter::AngularJerk, 0.0));
    }
}
