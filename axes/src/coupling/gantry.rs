//! One gantry slave (issue 12 item 6): it receives its master's command plus the offset the
//! two had at `gantry_enable`, and the deviation between their actual positions is supervised
//! against a warning and a fault limit.
//!
//! Manuals: HMC_GantrySynchro (digest 000 §4.4: ≤ 7 slaves, alarm threshold → AxisStatus bit
//! 5, stop threshold → bit 6), NMC SetGantryMaster/SetGantrySlave and S-GANTRY (digest 001
//! §2.10/§5: open loop, "master & slaves get identical pulses", so each slave keeps its offset),
//! HIMC EnableGantryPair (digest 004 §2.6: Linear = (R + L)/2, Yaw = (R − L)/2, TV 36).
//!
//! Frames. The slave follows the master's commanded position in the motor frame, so a
//! `set_position` or the end of the master's homing moves no slave; such a redefinition of an
//! enabled master is passed on to the slaves' frames instead (HMC GantryInit: all axes are
//! redefined together), and the master's `homed` with it.

use super::{axis_ref, Coupling, Couplings, Env, Law};
use crate::axis::Axis;
use crate::axis::Context;
use crate::command::{
    bounded, nonnegative, AxisIndex, EngineError, GantryEnable, GantrySetPid, GantrySetPosition,
    MasterSource, Reply, MAX_GANTRY_SLAVES,
};
use crate::profile::MotionState;
use crate::status::{AxisFlags, GantryStatus};

/// What a gantry slave needs of its master this tick, read before the slave is borrowed.
#[derive(Clone, Copy, Debug)]
pub struct MasterView {
    /// Commanded state, position in the motor frame.
    motor: MotionState,
    /// User frame − motor frame of the commanded position.
    frame: f64,
    enabled: bool,
    homed: bool,
}

impl MasterView {
    pub fn enabled(&self) -> bool {
        self.enabled
    }

    pub fn read(master: &Axis) -> MasterView {
        let c = master.commanded();
        MasterView {
            motor: MotionState {
                p: master.commanded_motor_frame(),
                v: c.v,
                a: c.a,
            },
            frame: master.commanded_frame_offset(),
            enabled: master.is_enabled(),
            homed: master.live_flags().contains(AxisFlags::HOMED),
        }
    }
}

#[derive(Clone, Debug)]
pub struct GantrySlave {
    /// Slave − master commanded position (motor frames) at engagement.
    offset: f64,
    /// The same offset as read in the user frames at engagement (the status's `offset`).
    user_offset: f64,
    warning_limit: f64,
    fault_limit: f64,
    /// The master's frame shift and `homed` of the last tick: changes are passed on.
    master_frame: f64,
    master_homed: bool,
    /// The slave refused its setpoint (fault, disable): re-anchor when it follows again, rather
    /// than jump to the master.
    refused: bool,
    deviation: f64,
    warning: bool,
    linear: f64,
    yaw: f64,
    /// HMC GantrySynchro ucMode 1: the deviation correction below runs.
    closed_loop: bool,
    pid: Pid,
    period: f64,
}

/// A slave's deviation correction (HMC_SetGantryAxisPID, manual §4.4.11.3, defaults Kp 1,
/// Ki 0, Kd 0): the correction added to the slave's command moves at the rate
/// −(kp·e + ki·∫e dt + kd·de/dt), e the deviation after the last tick. A rate, not a position:
/// so kp alone takes a steady deviation to 0 (the manual's "消除偏差", eliminate it) and the
/// loop is stable for kp·period < 2 whatever the one-tick measuring delay; a positional P
/// (correction = −kp·e) would leave e/(1 + kp) and ring at kp = 1. Closed form, per tick.
#[derive(Clone, Copy, Debug)]
struct Pid {
    kp: f64,
    ki: f64,
    kd: f64,
    integral: f64,
    /// The deviation of the tick before (for the derivative); `None` until one was measured.
    last: Option<f64>,
    /// Added to the slave's command, motor frame.
    correction: f64,
    /// Its rate this tick, units/s (the setpoint's velocity feed-forward).
    rate: f64,
}

impl Pid {
    fn new() -> Pid {
        Pid {
            kp: 1.0,
            ki: 0.0,
            kd: 0.0,
            integral: 0.0,
            last: None,
            correction: 0.0,
            rate: 0.0,
        }
    }

    /// One measurement `e` after a tick of `dt`: the correction the next tick applies.
    fn update(&mut self, e: f64, dt: f64) {
        self.integral += e * dt;
        let derivative = self.last.map_or(0.0, |l| (e - l) / dt);
        self.last = Some(e);
        let rate = -(self.kp * e + self.ki * self.integral + self.kd * derivative);
        // A non-finite rate (absurd gains overflowing) leaves the correction where it was.
        if rate.is_finite() && (self.correction + rate * dt).is_finite() {
            self.rate = rate;
            self.correction += rate * dt;
        } else {
            self.rate = 0.0;
        }
    }

    /// Start again from no correction (re-anchored, re-engaged).
    fn restart(&mut self) {
        *self = Pid {
            kp: self.kp,
            ki: self.ki,
            kd: self.kd,
            ..Pid::new()
        };
    }
}

/// What the deviation check found for one slave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Supervision {
    pub deviation: f64,
    pub warning: bool,
    pub fault: bool,
}

impl GantrySlave {
    /// A slave ganged to `master` where both stand now, with limits already checked (0 = none).
    pub fn new(
        master: &Axis,
        slave: &Axis,
        limits: [f64; 2],
        closed_loop: bool,
        period: f64,
    ) -> GantrySlave {
        let [warning_limit, fault_limit] = limits;
        let view = MasterView::read(master);
        GantrySlave {
            offset: slave.commanded_motor_frame() - view.motor.p,
            user_offset: slave.commanded().p - master.commanded().p,
            warning_limit,
            fault_limit,
            master_frame: view.frame,
            master_homed: view.homed,
            refused: false,
            deviation: 0.0,
            warning: false,
            linear: 0.0,
            yaw: 0.0,
            closed_loop,
            pid: Pid::new(),
            period,
        }
    }

    /// This tick's setpoint for `slave` (after passing on a redefinition of the master's
    /// frame).
    pub fn step(&mut self, master: MasterView, slave: &mut Axis) -> MotionState {
        let shift = master.frame - self.master_frame;
        let homed = master.homed && !self.master_homed;
        if master.enabled && (shift != 0.0 || homed) {
            slave.shift_frames(shift, homed);
        }
        self.master_frame = master.frame;
        self.master_homed = master.homed;
        if std::mem::take(&mut self.refused) {
            self.pid.restart();
            self.offset = slave.commanded_motor_frame() - master.motor.p;
        }
        let (correction, rate) = if self.closed_loop {
            (self.pid.correction, self.pid.rate)
        } else {
            (0.0, 0.0)
        };
        MotionState {
            p: master.motor.p + self.offset + correction + slave.commanded_frame_offset(),
            v: master.motor.v + rate,
            a: master.motor.a,
        }
    }

    /// The slave refused this tick's setpoint.
    pub fn refused(&mut self) {
        self.refused = true;
    }

    /// After both have stepped: the deviation (slave − master actual, less the offset) =
    /// master's following error − slave's + the correction, since the slave's command is the
    /// master's plus the offset and the correction; frame-free. A limit of 0 is none. A
    /// closed-loop gantry then updates the correction for the next tick.
    pub fn supervise(&mut self, master: &Axis, slave: &Axis) -> Supervision {
        let applied = if self.closed_loop {
            self.pid.correction
        } else {
            0.0
        };
        let deviation = master.following_error() - slave.following_error() + applied;
        if self.closed_loop && master.is_enabled() && slave.is_enabled() {
            self.pid.update(deviation, self.period);
        }
        let over = |limit: f64| limit > 0.0 && deviation.abs() > limit;
        self.deviation = deviation;
        self.warning = over(self.warning_limit);
        let (r, l) = (master.actual_position(), slave.actual_position());
        self.linear = (r + l) / 2.0;
        self.yaw = (r - l) / 2.0;
        Supervision {
            deviation,
            warning: self.warning,
            fault: over(self.fault_limit),
        }
    }

    pub fn status(&self) -> GantryStatus {
        GantryStatus {
            offset: self.user_offset,
            deviation: self.deviation,
            warning_limit: self.warning_limit,
            fault_limit: self.fault_limit,
            warning: self.warning,
            linear: self.linear,
            yaw: self.yaw,
            closed_loop: self.closed_loop,
            kp: self.pid.kp,
            ki: self.pid.ki,
            kd: self.pid.kd,
            correction: if self.closed_loop {
                self.pid.correction
            } else {
                0.0
            },
        }
    }

    /// New gains; the integral and the correction so far are kept.
    fn set_gains(&mut self, kp: f64, ki: f64, kd: f64) {
        self.pid.kp = kp;
        self.pid.ki = ki;
        self.pid.kd = kd;
    }

    /// Every axis of the gantry was redefined (`gantry_set_position`): the master's frame moved
    /// by `master_shift` (not to be passed on again) and the slave's user offset is now 0.
    fn redefined(&mut self, master_shift: f64) {
        self.master_frame += master_shift;
        self.user_offset = 0.0;
    }
}

// The registry's side: `gantry_enable`, `gantry_disable` and the supervision after stage 3.

impl Couplings {
    /// `gantry_enable`: all slaves ganged or none.
    pub(super) fn gantry_enable(
        &mut self,
        env: &mut Env,
        c: &GantryEnable,
    ) -> Result<Reply, EngineError> {
        let master = c.master;
        axis_ref(env.axes, master)?;
        let invalid = |reason| EngineError::InvalidGantry { master, reason };
        if c.slaves.is_empty() {
            return Err(invalid("give at least one slave"));
        }
        if c.slaves.len() > MAX_GANTRY_SLAVES {
            return Err(invalid("at most 7 slaves (HMC_GantrySynchro)"));
        }
        let warning_limit =
            nonnegative("warning_limit", bounded("warning_limit", c.warning_limit)?)?;
        let fault_limit = nonnegative("fault_limit", bounded("fault_limit", c.fault_limit)?)?;
        if warning_limit > 0.0 && fault_limit > 0.0 && warning_limit > fault_limit {
            return Err(invalid("the warning limit must not exceed the fault limit"));
        }
        if self.gantry_slaves(master).next().is_some() {
            return Err(EngineError::GantryExists { master });
        }
        if c.require_disabled {
            // HIMC EnableGantryPair (digest 004 §2.6, TV 38): both axes must be disabled.
            for &a in std::iter::once(&master).chain(&c.slaves) {
                let axis = axis_ref(env.axes, a)?;
                if axis.is_enabled() {
                    return Err(invalid(
                        "every axis of the pair must be disabled (HIMC EnableGantryPair)",
                    ));
                }
                if !axis.can_move() {
                    return Err(invalid("every axis of the pair must be able to move"));
                }
            }
        }
        for (i, &slave) in c.slaves.iter().enumerate() {
            if c.slaves.iter().take(i).any(|&s| s == slave) {
                return Err(invalid("a slave is listed twice"));
            }
            if c.require_disabled {
                if slave == master {
                    return Err(EngineError::CoupledToItself { axis: slave });
                }
                axis_ref(env.axes, slave)?.check_unclaimed()?;
                self.check_no_loop(master, slave)?;
            } else {
                self.check_new(env.axes, master, slave)?;
            }
        }
        for &slave in &c.slaves {
            let law = GantrySlave::new(
                axis_ref(env.axes, master)?,
                axis_ref(env.axes, slave)?,
                [warning_limit, fault_limit],
                c.closed_loop,
                env.period,
            );
            self.insert(
                env,
                (master, slave, MasterSource::Commanded),
                Law::Gantry(law),
                0.0,
            );
        }
        Ok(Reply::Done)
    }

    /// `gantry_disable`: the slaves decelerate to rest with their `decel` from the velocity
    /// they have (as `gear_out`) and are free again.
    pub(super) fn gantry_disable(
        &mut self,
        env: &mut Env,
        master: AxisIndex,
    ) -> Result<Reply, EngineError> {
        axis_ref(env.axes, master)?;
        let slaves = self.slaves_of_master(master)?;
        self.list
            .retain(|c| !(c.master == master && matches!(c.law, Law::Gantry(_))));
        for slave in slaves {
            if let Some(axis) = env.axes.get_mut(slave as usize) {
                axis.set_coupled(None, false);
                axis.set_gantry(0.0, false, false);
                let _ = axis.feed(env.ctx, crate::axis::Feed::Release);
            }
        }
        if let Some(axis) = env.axes.get_mut(master as usize) {
            axis.set_gantry(0.0, false, false);
        }
        self.reorder(env.axes.len());
        Ok(Reply::Done)
    }

    /// `gantry_set_position` (HMC_GantryGroupDefPos): every axis of the gantry reads
    /// `position`, its actual position shifted with it; the master's shift is not passed on
    /// again by the slaves' next step.
    pub(super) fn gantry_set_position(
        &mut self,
        env: &mut Env,
        c: &GantrySetPosition,
    ) -> Result<Reply, EngineError> {
        let master = c.master;
        axis_ref(env.axes, master)?;
        let position = bounded("position", c.position)?;
        // HMC: "当前指令不为龙门同步指令时，返回错误".
        let slaves = self.slaves_of_master(master)?;
        let mut master_shift = 0.0;
        for &a in std::iter::once(&master).chain(&slaves) {
            if let Some(axis) = env.axes.get_mut(a as usize) {
                let shift = position - axis.commanded().p;
                axis.shift_frames(shift, false);
                if a == master {
                    master_shift = shift;
                }
            }
        }
        for k in self.list.iter_mut().filter(|k| k.master == master) {
            if let Law::Gantry(g) = &mut k.law {
                g.redefined(master_shift);
            }
        }
        Ok(Reply::Done)
    }

    /// `gantry_set_pid` (HMC_SetGantryAxisPID): gains of a gantry slave's correction.
    pub(super) fn gantry_set_pid(
        &mut self,
        env: &mut Env,
        c: &GantrySetPid,
    ) -> Result<Reply, EngineError> {
        axis_ref(env.axes, c.axis)?;
        let kp = nonnegative("kp", bounded("kp", c.kp)?)?;
        let ki = nonnegative("ki", bounded("ki", c.ki)?)?;
        let kd = nonnegative("kd", bounded("kd", c.kd)?)?;
        let slave = self
            .list
            .iter_mut()
            .filter(|k| k.slave == c.axis)
            .find_map(|k| match &mut k.law {
                Law::Gantry(g) => Some(g),
                _ => None,
            })
            .ok_or(EngineError::NotCoupled {
                axis: c.axis,
                what: "a gantry slave",
            })?;
        slave.set_gains(kp, ki, kd);
        Ok(Reply::Done)
    }

    /// The slaves of `master`'s gantry, if it is a gantry master: a power command on the
    /// master (`enable`, `disable`) applies to them too (HIMC §7.1.1, TV 39: enabling the RHS
    /// enables both).
    pub(crate) fn gantry_power_gang(&self, master: AxisIndex) -> Vec<AxisIndex> {
        self.gantry_slaves(master).collect()
    }

    /// The slaves of `master`'s gantry, or `not_coupled` when it is no gantry's master.
    fn slaves_of_master(&self, master: AxisIndex) -> Result<Vec<AxisIndex>, EngineError> {
        let slaves: Vec<AxisIndex> = self.gantry_slaves(master).collect();
        if slaves.is_empty() {
            return Err(EngineError::NotCoupled {
                axis: master,
                what: "the master of a gantry",
            });
        }
        Ok(slaves)
    }

    fn gantry_slaves(&self, master: AxisIndex) -> impl Iterator<Item = AxisIndex> + '_ {
        self.list
            .iter()
            .filter(move |c| c.master == master && matches!(c.law, Law::Gantry(_)))
            .map(|c| c.slave)
    }

    /// After stage 3: each gantry slave's deviation against its limits; a fault latches on
    /// the master. The master shows the largest deviation of its slaves and any warning.
    /// Only when there are gantries: a scan of the couplings otherwise.
    pub(super) fn supervise_gantries(&mut self, axes: &mut [Axis], ctx: &mut Context) {
        for c in self.list.iter_mut() {
            let Law::Gantry(g) = &mut c.law else { continue };
            let (Some(master), Some(slave)) =
                (axes.get(c.master as usize), axes.get(c.slave as usize))
            else {
                continue;
            };
            let found = g.supervise(master, slave);
            if found.fault {
                if let Some(m) = axes.get_mut(c.master as usize) {
                    m.gantry_fault(ctx);
                }
            }
        }
        // The slaves' flags once every fault of this tick is latched.
        for c in self.list.iter() {
            let Law::Gantry(g) = &c.law else { continue };
            let shown = axes
                .get(c.master as usize)
                .is_some_and(|m| m.latched().contains(AxisFlags::GANTRY_FAULT));
            if let Some(s) = axes.get_mut(c.slave as usize) {
                s.set_gantry(g.deviation, g.warning, shown);
            }
        }
        // The masters, each once (the list is by slave; a master appears once per slave).
        for (i, c) in self.list.iter().enumerate() {
            let master = c.master;
            let gantry = |k: &Coupling| k.master == master && matches!(k.law, Law::Gantry(_));
            if !gantry(c) || self.list.iter().take(i).any(gantry) {
                continue;
            }
            let mut worst = 0.0f64;
            let mut warning = false;
            for k in self.list.iter().filter(|k| gantry(k)) {
                if let Law::Gantry(g) = &k.law {
                    if g.deviation.abs() > worst.abs() {
                        worst = g.deviation;
                    }
                    warning |= g.warning;
                }
            }
            if let Some(m) = axes.get_mut(master as usize) {
                m.set_gantry(worst, warning, false);
            }
        }
    }

    pub(super) fn has_gantry(&self) -> bool {
        self.list.iter().any(|c| matches!(c.law, Law::Gantry(_)))
    }
}
