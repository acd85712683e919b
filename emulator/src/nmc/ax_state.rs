//! What the axis-level additions (id family 0x13xx) keep between calls. The watchdog
//! (`NMC_SetWatchDog`, digest 001 §2.20, TV71), the E-stop inputs (`NMC_MtSetEstopDI`,
//! `NMC_SetEstopDIEx`, §2.3) and the PTP compares (`NMC_MtSetPtpComparePara`, §2.5) are the
//! engine's guards (`axes::guard`, judged on the tick); what is kept here is what the handlers
//! read back, and the watchdog's period in ticks, which every request turns into a new
//! deadline ([`AxState::heard`]).

use axes::command::WatchdogKick;
use axes::AxisStatus;
use mcemu_nmc::ax_structs::{DacMotor, EstopExParam, PidPara, ESTOP_DI_EX_CH_NUM};

/// `NMC_SetWatchDog`, armed in the engine: its timeout in servo periods.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Watchdog {
    pub ticks: u64,
}

/// One axis's `NMC_MtSetEstopDI`: general input `gpi` at level `sense` (0 low, 1 high) stops it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EstopDi {
    pub gpi: i16,
    pub sense: i16,
}

/// One armed `NMC_SetEstopDIEx` group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EstopEx {
    pub param: EstopExParam,
}

/// How the NMC reads an axis's encoder (`NMC_MtGetEncPos`, `NMC_GetEncPos`, the packs, the
/// captures): the engine's counter in the user frame (`encoder_counts + encoder_offset`, which
/// homing and the actual-position redefinitions move: the card clears its encoder with the
/// position on homing, digest 001 §2.6, §4.1, and a bus drive's homing redefines its 0x6064), times
/// `coe` (`NMC_MtSetEncCoe`, default 1), plus `offset` (`NMC_MtSetEncPos`) while the frame it
/// was set in holds: a later redefinition (homing, `NMC_MtZeroPos`) supersedes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EncReport {
    pub coe: f64,
    offset: i64,
    /// The `encoder_offset` `offset` was set in.
    frame: i64,
}

impl Default for EncReport {
    fn default() -> EncReport {
        EncReport {
            coe: 1.0,
            offset: 0,
            frame: 0,
        }
    }
}

impl EncReport {
    /// The reading of raw `counts` (now, or latched) in the frame of `status`.
    pub fn reading(&self, counts: i64, status: &AxisStatus) -> i64 {
        let user = counts.wrapping_add(status.encoder_offset);
        let scaled = (user as f64 * self.coe).round();
        let offset = if status.encoder_offset == self.frame {
            self.offset
        } else {
            0
        };
        (scaled.clamp(i64::MIN as f64, i64::MAX as f64) as i64).saturating_add(offset)
    }

    /// The encoder's reading now.
    pub fn position(&self, status: &AxisStatus) -> i64 {
        self.reading(status.encoder_counts, status)
    }

    /// Make the encoder read `wanted` now.
    pub fn set_position(&mut self, status: &AxisStatus, wanted: i64) {
        self.offset = 0;
        self.frame = status.encoder_offset;
        self.offset = wanted.saturating_sub(self.position(status));
    }

    /// Scale the counts by `coe` from now on, the reading continuous.
    pub fn set_coe(&mut self, status: &AxisStatus, coe: f64) {
        let now = self.position(status);
        self.coe = coe;
        self.set_position(status, now);
    }

    /// Forget `NMC_MtSetEncPos`: the counts as they are (`NMC_MtZeroPos`, which zeroes them).
    pub fn clear_offset(&mut self) {
        self.offset = 0;
    }
}

/// One axis's closed-loop and profile configuration (digest 001 §2.15, §2.20).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisLoop {
    /// `NMC_MtSetCtrlMode`: 0 pulse (open loop), 1 DA closed loop.
    pub ctrl_mode: i16,
    /// The three PID sets and the active one.
    pub pid: [PidPara; 3],
    pub pid_index: i16,
    pub dac: DacMotor,
    /// `NMC_MtPrfConfig`: mapped axis (None until written: the axis's own NMC number, which
    /// the handler knows from the bus map), port, and the offset axisPos = prfPos + startPos.
    pub map_axis: Option<i16>,
    pub port: i16,
    pub start_pos: i64,
    /// `NMC_MtSetPrfCoe` (0, 1].
    pub prf_coe: f64,
}

impl AxisLoop {
    pub fn fresh() -> AxisLoop {
        AxisLoop {
            ctrl_mode: 0,
            pid: [PidPara::default(); 3],
            pid_index: 0,
            dac: DacMotor {
                inverse: 0,
                bias: 0,
                dac_lmt: i16::MAX,
            },
            map_axis: None,
            port: 0,
            start_pos: 0,
            prf_coe: 1.0,
        }
    }
}

/// The device's axis-level settings.
#[derive(Clone, Debug, Default)]
pub struct AxState {
    /// `NMC_SetProfilePeriod` µs (None: never set; the engine's period is read).
    pub profile_period: Option<i16>,
    pub watchdog: Option<Watchdog>,
    /// The tick of the last request that moved the watchdog's deadline.
    pub last_kick: u64,
    /// By axis.
    pub estop_di: std::collections::BTreeMap<usize, EstopDi>,
    pub estop_ex: [Option<EstopEx>; ESTOP_DI_EX_CH_NUM],
    /// `NMC_MtSetSvClr` levels by axis (1 inactive, the default).
    pub sv_clr: std::collections::BTreeMap<usize, i16>,
    /// By axis.
    pub enc: std::collections::BTreeMap<usize, EncReport>,
    /// By axis (`AxisLoop::fresh` until written).
    pub loops: std::collections::BTreeMap<usize, AxisLoop>,
    /// `NMC_MtSetAxisDampCompParam` by axis: enable, param1, param2 (kept only).
    pub damp_comp: std::collections::BTreeMap<usize, (i16, i16, i16)>,
}

impl AxState {
    /// Axis `axis`'s closed-loop and profile configuration.
    pub fn axis_loop(&self, axis: usize) -> AxisLoop {
        self.loops
            .get(&axis)
            .copied()
            .unwrap_or_else(AxisLoop::fresh)
    }

    pub fn axis_loop_mut(&mut self, axis: usize) -> &mut AxisLoop {
        self.loops.entry(axis).or_insert_with(AxisLoop::fresh)
    }

    /// Axis `axis`'s encoder reading now (`status` is the axis's).
    pub fn enc_pos(&self, axis: usize, status: &AxisStatus) -> i64 {
        self.enc_reading(axis, status.encoder_counts, status)
    }

    /// Axis `axis`'s encoder reading of raw `counts` (a latch).
    pub fn enc_reading(&self, axis: usize, counts: i64, status: &AxisStatus) -> i64 {
        self.enc
            .get(&axis)
            .copied()
            .unwrap_or_default()
            .reading(counts, status)
    }

    /// A request arrived at tick `tick`: the watchdog's new deadline for the engine, once per
    /// tick (requests within one tick give the same deadline).
    pub fn heard(&mut self, tick: u64) -> Option<WatchdogKick> {
        let w = self.watchdog?;
        if tick == self.last_kick {
            return None;
        }
        self.last_kick = tick;
        Some(WatchdogKick {
            deadline: tick.saturating_add(w.ticks),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One deadline per tick: a second request in the same tick moves nothing.
    #[test]
    fn requests_move_the_watchdog_deadline_once_per_tick() {
        let mut st = AxState::default();
        assert_eq!(st.heard(5), None, "no watchdog armed");
        st.watchdog = Some(Watchdog { ticks: 500 });
        assert_eq!(st.heard(5), Some(WatchdogKick { deadline: 505 }));
        assert_eq!(st.heard(5), None);
        assert_eq!(st.heard(9), Some(WatchdogKick { deadline: 509 }));
    }
}
