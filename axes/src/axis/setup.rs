//! The per-tick view of an axis's parameters: how its inputs are wired (which physical input each
//! logical input reads and whether the controller inverts it: HMC_HwLimitConfig,
//! NMC_MtSetLmtCfg, CPU 226H SIGNAL_TYPE), its travel (finite or cyclic), and the thresholds
//! supervision checks every tick. Derived from the parameters when one changes, and compact, so
//! the tick reads one or two cache lines instead of a dozen scattered parameters.

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
pub(super) struct Setup {
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
    /// `[low, low + length)`. `None` for finite travel, where limits apply.
    pub cyclic: Option<Cyclic>,
    pub ignore_hw_limits: bool,
    pub limit_latch: bool,
    /// Positive and negative soft limits, `None` while ignored.
    pub soft_limits: Option<(f64, f64)>,
    /// 0 disables the following-error check.
    pub fe_limit: f64,
    pub fe_fault_cycles: u32,
    pub fe_warning_clear_cycles: u32,
    pub axis_err_mask: u32,
    pub in_position_window: f64,
    /// The largest |compensation| output; 0 unlimited (digest 004 §2.13, HCV max_comp_lim).
    pub compensation_limit: f64,
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

impl Setup {
    pub(super) fn from_params(p: &ParamSet) -> Setup {
        let hold = p.get(ParamId::HoldIn);
        Setup {
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
            ignore_hw_limits: p.flag(ParamId::IgnoreHwLimits),
            limit_latch: p.flag(ParamId::LimitLatch),
            soft_limits: (!p.flag(ParamId::IgnoreSwLimits))
                .then(|| (p.get(ParamId::FsLimit), p.get(ParamId::RsLimit))),
            fe_limit: p.get(ParamId::FeLimit),
            fe_fault_cycles: p.get(ParamId::FeFaultCycles) as u32,
            fe_warning_clear_cycles: p.get(ParamId::FeWarningClearCycles) as u32,
            axis_err_mask: p.get(ParamId::AxisErrMask) as u32,
            compensation_limit: p.get(ParamId::CompensationLimit),
            in_position_window: p.get(ParamId::InPositionWindow),
        }
    }
}
