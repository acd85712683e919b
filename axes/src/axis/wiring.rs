//! How the axis's logical inputs are wired: which physical input each one reads and whether the
//! controller inverts it (HMC_HwLimitConfig, NMC_MtSetLmtCfg, CPU 226H SIGNAL_TYPE). Derived from
//! the parameters when they change, so the per-tick path only follows it.

use crate::param::{ParamId, ParamSet, DEDICATED_INPUT};

/// Where a logical input comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Route {
    /// Not wired: the input never reads active.
    None,
    /// The axis's own simulated switch.
    Own,
    /// A general digital input of the machine.
    Di(usize),
}

impl Route {
    fn from_param(value: f64) -> Route {
        if value == DEDICATED_INPUT {
            Route::Own
        } else if value < 0.0 {
            Route::None
        } else {
            Route::Di(value as usize)
        }
    }

    /// The level on this route, before the controller's inversion; `None` when unwired.
    #[inline]
    pub(super) fn read(self, own: bool, di: &[bool]) -> Option<bool> {
        match self {
            Route::None => None,
            Route::Own => Some(own),
            Route::Di(n) => Some(di.get(n).copied().unwrap_or(false)),
        }
    }

    /// Whether the input exists at all, given whether the axis has its own switch.
    pub(super) fn exists(self, own: bool) -> bool {
        match self {
            Route::None => false,
            Route::Own => own,
            Route::Di(_) => true,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Wiring {
    pub limit_pos: Route,
    pub limit_neg: Route,
    pub home: Route,
    pub limit_pos_invert: bool,
    pub limit_neg_invert: bool,
    pub home_invert: bool,
    /// HMC_HoldConfig input.
    pub hold: Option<usize>,
    pub alarm_enabled: bool,
    pub alarm_invert: bool,
    /// Cyclic range of a rotary axis (HMC RepMode 1/2): positions wrap into
    /// `[low, low + length)`. `None` for finite travel.
    pub cyclic: Option<Cyclic>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Cyclic {
    pub low: f64,
    pub length: f64,
}

impl Cyclic {
    #[inline]
    pub(super) fn wrap(self, p: f64) -> f64 {
        (p - self.low).rem_euclid(self.length) + self.low
    }
}

impl Wiring {
    pub(super) fn from_params(p: &ParamSet) -> Wiring {
        let hold = p.get(ParamId::HoldIn);
        Wiring {
            limit_pos: Route::from_param(p.get(ParamId::FhLimitIn)),
            limit_neg: Route::from_param(p.get(ParamId::RhLimitIn)),
            home: Route::from_param(p.get(ParamId::HomeIn)),
            limit_pos_invert: p.flag(ParamId::LimitPosInvert),
            limit_neg_invert: p.flag(ParamId::LimitNegInvert),
            home_invert: p.flag(ParamId::HomeInvert),
            hold: (hold >= 0.0).then_some(hold as usize),
            alarm_enabled: p.flag(ParamId::DriveAlarmEnable),
            alarm_invert: p.flag(ParamId::DriveAlarmInvert),
            cyclic: {
                let dist = p.get(ParamId::RepDist);
                match p.get(ParamId::RepMode) as i64 {
                    1 => Some(Cyclic {
                        low: 0.0,
                        length: dist,
                    }),
                    2 => Some(Cyclic {
                        low: -dist,
                        length: 2.0 * dist,
                    }),
                    _ => None,
                }
            },
        }
    }
}
