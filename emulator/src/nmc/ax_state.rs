//! What the axis-level additions (id family 0x13xx) keep between calls, and the two guards
//! that act without a call: the communication watchdog (`NMC_SetWatchDog`, digest 001 §2.20,
//! TV71) and the E-stop inputs (`NMC_MtSetEstopDI`, `NMC_SetEstopDIEx`, §2.3).
//!
//! Both are judged on the engine's virtual clock (`Snapshot::tick` × `period`): [`AxState::due`]
//! takes a snapshot and returns the engine commands to apply now; `ax_watch` calls it every
//! millisecond or two while a guard is armed. Every request the device serves records its
//! tick ([`AxState::heard`]), which is what keeps the watchdog quiet.

use axes::command::{
    BufferMode, Command, MoveAbsolute, MoveVelocity, Stop, StopMode, WriteDigitalOutput,
};
use axes::status::Snapshot;
use axes::AxisFlags;
use mcemu_dialects::nmc::{acceleration_to_engine, velocity_to_engine};
use mcemu_nmc::ax_structs::{DacMotor, EstopExParam, PidPara, ESTOP_DI_EX_CH_NUM};

use mcemu_dialects::PulseScale;

/// `NMC_SetWatchDog`: after `timeout` seconds without a request, stop the axes (abruptly for
/// stopMode 1, with their stop deceleration for 0) and write `do_value` to DO group `group`
/// (its first output channel `do_start`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Watchdog {
    pub timeout: f64,
    pub stop_mode: i16,
    pub do_start: usize,
    pub do_value: i64,
    /// Fired since the last request: fires once per silence.
    pub fired: bool,
}

/// One axis's `NMC_MtSetEstopDI`: general input `gpi` at level `sense` (0 low, 1 high) stops it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EstopDi {
    pub gpi: i16,
    pub sense: i16,
    /// At its level when last looked at (the edge into it stops the axis even when still).
    pub active: bool,
}

/// One armed `NMC_SetEstopDIEx` group and since when (seconds) its input has been at the
/// triggering level (`None`: not at it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EstopEx {
    pub param: EstopExParam,
    pub active_since: Option<f64>,
    /// Its level has held for the filter time since it last came.
    pub fired: bool,
}

/// What a passed PTP compare needs of its axis's move (from the service's settings): a jog
/// (keeps its direction) or a PTP move to `target` pulses; its acceleration and deceleration
/// (pulse/ms²); the axis's pulse scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveSettings {
    pub jog: bool,
    pub target: i64,
    pub acc: f64,
    pub dec: f64,
    pub scale: PulseScale,
}

/// `NMC_MtSetPtpComparePara`: when the axis's planned position passes `pos` (pulses) moving
/// positive (`dir` 1) or negative (0), its move continues at `vel` pulse/ms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PtpCompare {
    pub dir: i16,
    pub pos: i64,
    pub vel: f64,
    /// Armed, not yet passed.
    pub active: bool,
    /// Passed: the velocity was changed.
    pub out: bool,
}

/// How `NMC_MtGetEncPos` reports an axis's encoder counts: times `coe` (`NMC_MtSetEncCoe`,
/// default 1), plus `offset` (`NMC_MtSetEncPos`, `MtZeroPos`), in pulses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EncReport {
    pub coe: f64,
    pub offset: i64,
}

impl Default for EncReport {
    fn default() -> EncReport {
        EncReport {
            coe: 1.0,
            offset: 0,
        }
    }
}

impl EncReport {
    /// The reported position of raw `counts`.
    pub fn position(&self, counts: i64) -> i64 {
        let scaled = (counts as f64 * self.coe).round();
        (scaled.clamp(i64::MIN as f64, i64::MAX as f64) as i64).saturating_add(self.offset)
    }

    /// The offset that makes raw `counts` read `wanted`.
    pub fn offset_for(&self, counts: i64, wanted: i64) -> i64 {
        wanted.saturating_sub(EncReport { offset: 0, ..*self }.position(counts))
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
    /// `NMC_MtPrfConfig`: mapped axis, port, and the offset axisPos = prfPos + startPos.
    pub map_axis: i16,
    pub port: i16,
    pub start_pos: i64,
    /// `NMC_MtSetPrfCoe` (0, 1].
    pub prf_coe: f64,
}

impl AxisLoop {
    pub fn fresh(axis: usize) -> AxisLoop {
        AxisLoop {
            ctrl_mode: 0,
            pid: [PidPara::default(); 3],
            pid_index: 0,
            dac: DacMotor {
                inverse: 0,
                bias: 0,
                dac_lmt: i16::MAX,
            },
            map_axis: i16::try_from(axis).unwrap_or(i16::MAX),
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
    /// Seconds on the virtual clock of the last request.
    pub last_heard: f64,
    /// By axis.
    pub estop_di: std::collections::BTreeMap<usize, EstopDi>,
    pub estop_ex: [Option<EstopEx>; ESTOP_DI_EX_CH_NUM],
    /// `NMC_MtSetSvClr` levels by axis (1 inactive, the default).
    pub sv_clr: std::collections::BTreeMap<usize, i16>,
    /// By axis.
    pub enc: std::collections::BTreeMap<usize, EncReport>,
    /// By axis (`AxisLoop::fresh` until written).
    pub loops: std::collections::BTreeMap<usize, AxisLoop>,
    /// By axis.
    pub ptp_compare: std::collections::BTreeMap<usize, PtpCompare>,
    /// `NMC_MtSetAxisDampCompParam` by axis: enable, param1, param2 (kept only).
    pub damp_comp: std::collections::BTreeMap<usize, (i16, i16, i16)>,
}

/// The virtual time of a snapshot, seconds.
pub fn seconds(s: &Snapshot) -> f64 {
    s.time()
}

impl AxState {
    /// Whether a guard needs watching.
    pub fn armed(&self) -> bool {
        self.watchdog.is_some()
            || !self.estop_di.is_empty()
            || self.estop_ex.iter().any(Option::is_some)
            || self.ptp_compare.values().any(|p| p.active)
    }

    /// Axis `axis`'s closed-loop and profile configuration.
    pub fn axis_loop(&self, axis: usize) -> AxisLoop {
        self.loops
            .get(&axis)
            .copied()
            .unwrap_or_else(|| AxisLoop::fresh(axis))
    }

    pub fn axis_loop_mut(&mut self, axis: usize) -> &mut AxisLoop {
        self.loops
            .entry(axis)
            .or_insert_with(|| AxisLoop::fresh(axis))
    }

    /// Axis `axis`'s encoder position from its raw `counts`.
    pub fn enc_pos(&self, axis: usize, counts: i64) -> i64 {
        self.enc
            .get(&axis)
            .copied()
            .unwrap_or_default()
            .position(counts)
    }

    /// A request arrived at virtual time `now`.
    pub fn heard(&mut self, now: f64) {
        self.last_heard = now;
        if let Some(w) = &mut self.watchdog {
            w.fired = false;
        }
    }

    /// The commands the guards call for in snapshot `s` (empty: nothing to do). An E-stop
    /// input reaching its level stops its axes (latching BIT_AXIS_ESTP); while it stays there,
    /// a move started anyway is stopped too.
    /// `moves`: each axis's move (what a passed PTP compare changes).
    pub fn due(&mut self, s: &Snapshot, moves: &[MoveSettings]) -> Vec<Command> {
        let now = seconds(s);
        let mut out = Vec::new();
        self.ptp_compares_due(s, moves, &mut out);
        // Per axis: held at an E-stop level; reached it just now.
        let mut estop = vec![false; s.axes.len()];
        let mut edge = vec![false; s.axes.len()];
        for (&axis, e) in &mut self.estop_di {
            let level = usize::try_from(e.gpi)
                .ok()
                .and_then(|i| s.io.di.get(i))
                .copied();
            let active = level == Some(e.sense == 1);
            if let (Some(held), Some(new)) = (estop.get_mut(axis), edge.get_mut(axis)) {
                *held |= active;
                *new |= active && !e.active;
            }
            e.active = active;
        }
        for e in self.estop_ex.iter_mut().flatten() {
            let level = input_level(s, &e.param);
            if level == Some(e.param.di_sense == 1) {
                let since = *e.active_since.get_or_insert(now);
                // filter: how long the level must hold, in ms (digest 001 §3.6 gives no unit).
                if now - since + 1e-9 >= f64::from(e.param.filter) / 1e3 {
                    for axis in 0..estop.len().min(16) {
                        if e.param.ax_mask & (1 << axis) != 0 {
                            if let (Some(held), Some(new)) =
                                (estop.get_mut(axis), edge.get_mut(axis))
                            {
                                *held = true;
                                *new |= !e.fired;
                            }
                        }
                    }
                    e.fired = true;
                }
            } else {
                (e.active_since, e.fired) = (None, false);
            }
        }
        for (axis, (held, new)) in estop.iter().zip(&edge).enumerate() {
            // Moving and not already in an E-stop (which is MOVING until it has stopped).
            let moving = s.axes.get(axis).is_some_and(|a| {
                a.flags.contains(AxisFlags::MOVING) && !a.latched.contains(AxisFlags::ESTOP)
            });
            if *new || (*held && moving) {
                out.push(
                    Stop {
                        axis: axis as u16,
                        mode: StopMode::Emergency,
                        deceleration: None,
                    }
                    .into(),
                );
            }
        }
        if let Some(w) = &mut self.watchdog {
            if !w.fired && now - self.last_heard >= w.timeout {
                w.fired = true;
                let mode = if w.stop_mode == 1 {
                    StopMode::Abrupt
                } else {
                    StopMode::Smooth
                };
                for axis in 0..s.axes.len() {
                    out.push(
                        Stop {
                            axis: axis as u16,
                            mode,
                            deceleration: None,
                        }
                        .into(),
                    );
                }
                let count = s.io.do_.len().saturating_sub(w.do_start).min(32);
                for i in 0..count {
                    out.push(
                        WriteDigitalOutput {
                            channel: (w.do_start + i) as u16,
                            value: w.do_value & (1 << i) != 0,
                        }
                        .into(),
                    );
                }
            }
        }
        out
    }
}

impl AxState {
    /// The PTP compares whose position the moving axis has passed: the move goes on at the new
    /// velocity (a jog keeps its direction), from the tick the watcher sees it.
    fn ptp_compares_due(&mut self, s: &Snapshot, moves: &[MoveSettings], out: &mut Vec<Command>) {
        for (&axis, p) in &mut self.ptp_compare {
            let (Some(a), Some(m)) = (s.axes.get(axis), moves.get(axis)) else {
                continue;
            };
            if !p.active || !a.flags.contains(AxisFlags::MOVING) {
                continue;
            }
            let here = m.scale.from_engine(a.cmd_pos);
            let passed = if p.dir == 1 {
                here >= p.pos as f64
            } else {
                here <= p.pos as f64
            };
            if !passed {
                continue;
            }
            (p.active, p.out) = (false, true);
            let (axis, scale) = (axis as u16, m.scale);
            let (acc, dec) = (
                Some(acceleration_to_engine(scale, m.acc)),
                Some(acceleration_to_engine(scale, m.dec)),
            );
            let command: Command = if m.jog {
                MoveVelocity {
                    axis,
                    velocity: velocity_to_engine(scale, p.vel).copysign(a.cmd_vel),
                    acceleration: acc,
                    deceleration: dec,
                    jerk: None,
                    buffer_mode: BufferMode::Aborting,
                }
                .into()
            } else {
                MoveAbsolute {
                    axis,
                    position: scale.to_engine(m.target as f64),
                    velocity: Some(velocity_to_engine(scale, p.vel)),
                    acceleration: acc,
                    deceleration: dec,
                    jerk: None,
                    buffer_mode: BufferMode::Aborting,
                }
                .into()
            };
            out.push(command);
        }
    }
}

/// The level of the input an advanced E-stop group watches: a general input, or a dedicated
/// one of axis `di_index` (1 negative limit, 2 positive limit, 3 home, 4 index).
pub fn input_level(s: &Snapshot, p: &EstopExParam) -> Option<bool> {
    let index = usize::try_from(p.di_index).ok()?;
    let flag = match p.di_type {
        0 => return s.io.di.get(index).copied(),
        1 => AxisFlags::HW_LIMIT_NEG,
        2 => AxisFlags::HW_LIMIT_POS,
        3 => AxisFlags::HOME_SWITCH,
        4 => AxisFlags::INDEX,
        _ => return None,
    };
    s.axes.get(index).map(|a| a.flags.contains(flag))
}

#[cfg(test)]
mod tests {
    use axes::status::{AxisStatus, Snapshot};
    use axes::AxisFlags;

    use super::*;

    /// A snapshot at tick `tick` (1 ms period) of two axes, axis 1 `moving`, DI2 at `di2`.
    fn snapshot(tick: u64, moving: bool, di2: bool) -> Snapshot {
        let mut s = Snapshot {
            tick,
            period: 1e-3,
            ..Snapshot::default()
        };
        let mut a = AxisStatus::default();
        a.flags.put(AxisFlags::MOVING, moving);
        s.axes = vec![AxisStatus::default(), a];
        s.io.di = vec![false, false, di2];
        s.io.do_ = vec![true; 8];
        s
    }

    fn stops(c: &[Command]) -> usize {
        c.iter()
            .filter(|c| matches!(c, Command::Axis(axes::command::AxisCommand::Stop(_))))
            .count()
    }

    /// TV71 on the virtual clock: quiet until 500 ms after the last request, then both axes
    /// stop and DO group 0 is written, once; a request re-arms it.
    #[test]
    fn the_watchdog_fires_once_per_silence_on_the_virtual_clock() {
        let mut st = AxState {
            watchdog: Some(Watchdog {
                timeout: 0.5,
                stop_mode: 1,
                do_start: 0,
                do_value: 0,
                fired: false,
            }),
            ..AxState::default()
        };
        st.heard(0.1);
        assert!(st.due(&snapshot(599, true, false), &[]).is_empty());
        let fired = st.due(&snapshot(600, true, false), &[]);
        assert_eq!(stops(&fired), 2);
        assert_eq!(fired.len(), 2 + 8, "8 outputs of group 0 written");
        assert!(st.due(&snapshot(2000, true, false), &[]).is_empty());
        st.heard(2.0);
        assert!(st.due(&snapshot(2499, true, false), &[]).is_empty());
        assert_eq!(stops(&st.due(&snapshot(2500, true, false), &[])), 2);
    }

    /// An advanced E-stop group: DI2 high for the filter's 5 ms stops axis 1 (still or not,
    /// once at the edge); while it stays high only a moving axis is stopped again.
    #[test]
    fn an_estop_group_fires_after_its_filter_time() {
        let mut st = AxState::default();
        st.estop_ex[0] = Some(EstopEx {
            param: EstopExParam {
                ax_mask: 0b10,
                di_type: 0,
                di_index: 2,
                filter: 5,
                di_sense: 1,
            },
            active_since: None,
            fired: false,
        });
        assert!(st.armed());
        assert!(st.due(&snapshot(10, false, true), &[]).is_empty());
        assert!(st.due(&snapshot(14, false, true), &[]).is_empty());
        assert_eq!(stops(&st.due(&snapshot(15, false, true), &[])), 1);
        assert!(st.due(&snapshot(16, false, true), &[]).is_empty());
        assert_eq!(stops(&st.due(&snapshot(17, true, true), &[])), 1);
        assert!(st.due(&snapshot(18, true, false), &[]).is_empty());
    }
}
