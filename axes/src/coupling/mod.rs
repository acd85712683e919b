//! Couplings (issue 12 items 1–2, 9): gears and cams that make a slave axis follow a master;
//! superimposed motion (two masters) and the tangential axis (the two axes of a group's plane).
//!
//! Zero lag. The couplings do not run as stage-2 planners (those see the axes as the last tick
//! left them, so a slave would follow its master one servo period late). Instead stage 3 steps
//! the axes in the couplings' order: every master before its slaves, the uncoupled axes in
//! index order. Just before a slave steps, its coupling reads the master *as this tick left
//! it* (commanded, actual or encoder position) and feeds the slave its setpoint, which the
//! slave then runs through its own smoothing, output stage, plant and supervision like any fed
//! setpoint. The order is computed when a coupling is made or ends, never per tick; a coupling
//! whose master follows its slave (directly or down a chain) is refused (`CouplingLoop`).
//!
//! A slave that refuses its setpoint (fault, disable, stop, a limit) is decoupled: it keeps
//! doing what the refusal left it doing. A master's fault does not decouple: the master's stop
//! ramp is followed by the slave, so the two stay in ratio (decisions.md, issue 12 gear).

mod add_axis;
mod cam;
mod cam_event;
mod follow;
mod gantry;
mod gear;
mod handwheel;
mod link;
mod superimpose;
pub mod table;
mod tangential;
mod tangential_corner;
mod tangential_lift;

use std::collections::BTreeMap;
use std::sync::Arc;

use crate::axis::{Axis, Context, Feed};
use crate::command::{
    bounded, positive, AddAxisSet, AxisIndex, CamIn, CamTableDefine, CouplingCommand, EngineError,
    GearIn, MasterSource, Reply, SuperimposeIn, TangentialIn, HANDWHEEL_EXTERNAL_ENCODERS,
};
use crate::group::Groups;
use crate::param::ParamId;
use crate::profile::MotionState;
use crate::status::{CouplingKind, CouplingPhase, CouplingStatus};
pub use add_axis::AddLink;
pub use cam::{Cam, CamStart, CamStep};
use cam_event::cam_capture_start;
pub use follow::{FollowLink, FollowSlave};
pub use gantry::GantrySlave;
pub use gear::{Clutch, Gear};
pub use handwheel::Handwheel;
pub use superimpose::Superimpose;
pub use table::CamTable;
pub use tangential::{CornerMode, Tangential, TurnLimits};

/// Most cam tables defined at once.
pub const MAX_CAM_TABLES: usize = 256;

#[derive(Clone, Debug)]
enum Law {
    Gear(Gear),
    Cam(Cam),
    Superimpose(Superimpose),
    Tangential(Tangential),
    Gantry(GantrySlave),
    /// NMC Follow: the run is the slave's `FollowSlave` in `Couplings::follows`.
    Follow(FollowLink),
}

/// One slave and what it follows.
#[derive(Clone, Debug)]
struct Coupling {
    slave: AxisIndex,
    master: AxisIndex,
    source: MasterSource,
    law: Law,
    /// The master's position (per `source`) of the last tick.
    previous: f64,
    /// Superimposed and tangential couplings: the second master (followed by `source` too)
    /// and its position of the last tick.
    master2: Option<AxisIndex>,
    previous2: f64,
    /// Set when the coupling ended this tick; removed after the axes have stepped.
    ended: bool,
}

impl Coupling {
    fn status(&self) -> CouplingStatus {
        let (kind, ratio, table, table_index, cycle) = match &self.law {
            Law::Gear(g) => (CouplingKind::Gear, g.ratio(), None, 0, 0),
            Law::Gantry(_) => (CouplingKind::Gantry, 1.0, None, 0, 0),
            Law::Cam(cam) => (
                CouplingKind::Cam,
                0.0,
                Some(cam.table_id),
                cam.span(),
                cam.cycle(),
            ),
            Law::Superimpose(s) => (CouplingKind::Superimpose, s.ratios()[0], None, 0, 0),
            Law::Tangential(_) => (CouplingKind::Tangential, 0.0, None, 0, 0),
            Law::Follow(l) => (
                CouplingKind::Follow,
                0.0,
                None,
                l.segment(),
                i64::from(l.loops()),
            ),
        };
        let (ratio2, angle, deviation) = match &self.law {
            Law::Superimpose(s) => (s.ratios()[1], 0.0, 0.0),
            Law::Tangential(t) => (0.0, t.angle(), t.deviation()),
            _ => (0.0, 0.0, 0.0),
        };
        let corner_state = match &self.law {
            Law::Tangential(t) => t.corner_state(),
            _ => 0,
        };
        CouplingStatus {
            corner_state,
            master2: self.master2,
            ratio2,
            angle,
            deviation,
            slave: self.slave,
            master: self.master,
            kind,
            master_source: self.source,
            phase: self.phase(),
            ratio,
            table,
            table_index,
            cycle,
            gantry: match &self.law {
                Law::Gantry(g) => Some(g.status()),
                _ => None,
            },
            phase_offset: match &self.law {
                Law::Gear(g) => g.phase_offset(),
                _ => 0,
            },
        }
    }

    fn phase(&self) -> CouplingPhase {
        match &self.law {
            Law::Gear(g) => g.phase(),
            Law::Cam(c) => c.phase(),
            Law::Superimpose(_) => CouplingPhase::InSync,
            Law::Tangential(t) => t.phase(),
            Law::Gantry(_) => CouplingPhase::InSync,
            Law::Follow(l) => l.phase(),
        }
    }
}

/// The couplings and the cam tables. Cloned whole by atomic batches' checkpoints (the tables
/// are shared).
#[derive(Clone, Debug, Default)]
pub struct Couplings {
    /// By slave axis.
    list: Vec<Coupling>,
    tables: BTreeMap<u16, Arc<CamTable>>,
    /// Stage 3's order: each axis and the index in `list` of the coupling it is the slave of.
    /// Empty when there is no coupling (then the axes step in index order).
    order: Vec<(AxisIndex, Option<usize>)>,
    /// The handwheels (issue 12 item 7), by axis, and the external encoders' counts.
    handwheels: Vec<Handwheel>,
    external: [i64; HANDWHEEL_EXTERNAL_ENCODERS as usize],
    /// NMC Follow slaves' settings, FIFOs and runs (issue 12 item 2), by axis.
    follows: BTreeMap<AxisIndex, FollowSlave>,
    /// HMC add axes, by base axis: stage 3 steps each add axis before its base.
    adds: Vec<AddLink>,
}

/// What a coupling command may touch.
pub(crate) struct Env<'a, 'b> {
    pub axes: &'a mut [Axis],
    /// For `tangential_in`: the group whose path is tracked (and its corner stops).
    pub groups: &'a mut Groups,
    pub ctx: &'a mut Context<'b>,
    pub period: f64,
}

/// The master's value a coupling follows, this tick.
fn read_master(axis: &Axis, source: MasterSource, previous: f64, period: f64) -> MotionState {
    match source {
        MasterSource::Commanded => axis.commanded(),
        MasterSource::Actual => MotionState {
            p: axis.actual_position(),
            v: axis.actual_velocity(),
            a: 0.0,
        },
        MasterSource::Encoder => {
            let p = axis.encoder_position();
            MotionState {
                p,
                v: (p - previous) / period,
                a: 0.0,
            }
        }
    }
}

fn axis_ref(axes: &[Axis], index: AxisIndex) -> Result<&Axis, EngineError> {
    axes.get(index as usize).ok_or(EngineError::InvalidAxis {
        axis: u32::from(index),
        count: axes.len() as u32,
    })
}

impl Couplings {
    pub fn is_empty(&self) -> bool {
        self.list.is_empty() && self.handwheels.is_empty() && self.adds.is_empty()
    }

    /// The add axis of `base` (HMC_GetAddAxis), if it has one.
    pub fn add_axis_of(&self, base: AxisIndex) -> Option<AxisIndex> {
        self.find_add(base).map(|l| l.add)
    }

    fn find_add(&self, base: AxisIndex) -> Option<&AddLink> {
        self.adds
            .binary_search_by_key(&base, |l| l.base)
            .ok()
            .and_then(|i| self.adds.get(i))
    }

    /// `add_axis_set` (HMC_SetAddAxis): associate, replace or (without `add`) end the base's
    /// add axis. Ending keeps the base where it stands.
    fn add_axis_set(&mut self, env: &mut Env, c: &AddAxisSet) -> Result<Reply, EngineError> {
        axis_ref(env.axes, c.base)?;
        let at = self.adds.binary_search_by_key(&c.base, |l| l.base);
        let Some(add) = c.add else {
            if let Ok(i) = at {
                self.adds.remove(i);
            }
            if let Some(axis) = env.axes.get_mut(c.base as usize) {
                axis.set_add_axis(None);
            }
            self.reorder(env.axes.len());
            return Ok(Reply::Done);
        };
        let add_axis = axis_ref(env.axes, add)?;
        if add == c.base {
            return Err(EngineError::CoupledToItself { axis: c.base });
        }
        // Replacing the base's own link: the old one must not count as a path back to it.
        let old = at.ok().map(|i| self.adds.remove(i));
        if let Err(e) = self.check_no_loop(add, c.base) {
            if let Some(old) = old {
                let i = self.adds.partition_point(|l| l.base < old.base);
                self.adds.insert(i, old);
            }
            return Err(e);
        }
        let link = AddLink::new(c.base, add_axis, add);
        let i = self.adds.partition_point(|l| l.base < c.base);
        self.adds.insert(i, link);
        if let Some(axis) = env.axes.get_mut(c.base as usize) {
            axis.set_add_axis(Some(add));
        }
        self.reorder(env.axes.len());
        Ok(Reply::Done)
    }

    /// A cam table by number.
    pub fn table(&self, id: u16) -> Option<&CamTable> {
        self.tables.get(&id).map(|t| t.as_ref())
    }

    /// Apply a coupling command.
    pub(crate) fn apply(
        &mut self,
        env: &mut Env,
        command: CouplingCommand,
    ) -> Result<Reply, EngineError> {
        match command {
            CouplingCommand::GearIn(c) => self.gear_in(env, &c),
            CouplingCommand::GearSetRatio(c) => {
                let ratio = check_ratio(c.numerator, c.denominator)?;
                let gear = self.gear_mut(c.slave)?;
                gear.set_ratio(ratio.0, ratio.1);
                Ok(Reply::Done)
            }
            CouplingCommand::GearOut(c) => self.decouple(env, c.slave, CouplingKind::Gear),
            CouplingCommand::CamTable(c) => self.define_table(c),
            CouplingCommand::CamIn(c) => self.cam_in(env, &c),
            CouplingCommand::CamOut(c) => self.decouple(env, c.slave, CouplingKind::Cam),
            CouplingCommand::SuperimposeIn(c) => self.superimpose_in(env, &c),
            CouplingCommand::SuperimposeSetRatios(c) => {
                let ratios = check_ratios(c.ratios)?;
                match self.find_mut(c.slave).map(|k| &mut k.law) {
                    Some(Law::Superimpose(s)) => {
                        s.set_ratios(ratios);
                        Ok(Reply::Done)
                    }
                    _ => Err(EngineError::NotCoupled {
                        axis: c.slave,
                        what: "the slave of a superimposed coupling",
                    }),
                }
            }
            CouplingCommand::SuperimposeOut(c) => {
                self.decouple(env, c.slave, CouplingKind::Superimpose)
            }
            CouplingCommand::TangentialIn(c) => self.tangential_in(env, &c),
            CouplingCommand::CamTableLink(c) => {
                let table = link::link_table(&c)?;
                self.install_table(c.table, table)
            }
            CouplingCommand::TangentialCornerMode(_)
            | CouplingCommand::TangentialCornerFollowNext(_)
            | CouplingCommand::TangentialCornerContinue(_) => self.tangential_corner(env, &command),
            CouplingCommand::TangentialOut(c) => {
                self.decouple(env, c.axis, CouplingKind::Tangential)
            }
            CouplingCommand::GantryEnable(c) => self.gantry_enable(env, &c),
            CouplingCommand::GantryDisable(c) => self.gantry_disable(env, c.master),
            CouplingCommand::HandwheelIn(c) => self.handwheel_in(env, &c),
            CouplingCommand::HandwheelOut(c) => self.handwheel_out(env, c.axis),
            CouplingCommand::HandwheelTurn(c) => self.handwheel_turn(&c),
            CouplingCommand::FollowConfig(c) => self.follow_config(env, &c),
            CouplingCommand::FollowPush(c) => self.follow_push(env, &c),
            CouplingCommand::FollowClear(c) => self.follow_clear(env, &c),
            CouplingCommand::FollowStart(c) => self.follow_start(env, &c),
            CouplingCommand::FollowSwitch(c) => self.follow_switch(env, &c),
            CouplingCommand::FollowOut(c) => self.decouple(env, c.axis, CouplingKind::Follow),
            CouplingCommand::HandwheelSetRatio(c) => self.handwheel_set_ratio(env, &c),
            CouplingCommand::GantrySetPosition(c) => self.gantry_set_position(env, &c),
            CouplingCommand::GantrySetPid(c) => self.gantry_set_pid(env, &c),
            CouplingCommand::AddAxisSet(c) => self.add_axis_set(env, &c),
        }
    }

    /// Check a new coupling of `slave` to `master`: both exist, they differ, the slave may be
    /// coupled and the master does not follow the slave down its chain.
    fn check_new(
        &self,
        axes: &[Axis],
        master: AxisIndex,
        slave: AxisIndex,
    ) -> Result<(), EngineError> {
        let s = axis_ref(axes, slave)?;
        axis_ref(axes, master)?;
        if master == slave {
            return Err(EngineError::CoupledToItself { axis: slave });
        }
        s.check_can_couple()?;
        self.check_no_loop(master, slave)
    }

    /// Refuse a coupling of `slave` to `master` when the master follows the slave down its
    /// chain.
    fn check_no_loop(&self, master: AxisIndex, slave: AxisIndex) -> Result<(), EngineError> {
        // Walk up from the master through every master of each coupling (two at most): with
        // no loop so far, each axis is reached at most once per path, and the paths end
        // within as many steps as there are couplings; the stack is bounded by twice that.
        let mut stack = vec![master];
        let mut visited = 0usize;
        while let Some(a) = stack.pop() {
            if a == slave {
                return Err(EngineError::CouplingLoop { slave, master });
            }
            visited += 1;
            let links = self.list.len() + self.adds.len() + 1;
            if visited > 4 * links * links {
                break;
            }
            if let Some(c) = self.find(a) {
                stack.push(c.master);
                stack.extend(c.master2);
            }
            // An add axis steps before its base as a master before its slave.
            if let Some(l) = self.find_add(a) {
                stack.push(l.add);
            }
        }
        Ok(())
    }

    fn gear_in(&mut self, env: &mut Env, c: &GearIn) -> Result<Reply, EngineError> {
        self.check_new(env.axes, c.master, c.slave)?;
        let (numerator, denominator) = check_ratio(c.numerator, c.denominator)?;
        let clutch = match (c.clutch_distance, c.acceleration) {
            (Some(_), _) | (_, Some(_)) if c.transition => {
                return Err(EngineError::InvalidArgument {
                    name: "transition",
                    value: 1.0,
                    reason: "the transition clutch uses the slave's accel and decel: give no clutch distance or acceleration with it",
                })
            }
            (None, None) if c.transition => {
                let p = axis_ref(env.axes, c.slave)?.params();
                Clutch::Transition {
                    accel: positive("accel", p.get(ParamId::Accel))?,
                    decel: positive("decel", p.get(ParamId::Decel))?,
                }
            }
            (Some(_), Some(_)) => {
                return Err(EngineError::InvalidArgument {
                    name: "clutch_distance",
                    value: c.clutch_distance.unwrap_or(0.0),
                    reason: "give a clutch distance or an acceleration, not both",
                })
            }
            (Some(d), None) => {
                let d = bounded("clutch_distance", d)?;
                if d > 0.0 {
                    Clutch::Distance(d)
                } else if d == 0.0 {
                    // NMC: "0 表示没有离合区".
                    Clutch::Immediate
                } else {
                    return Err(EngineError::InvalidArgument {
                        name: "clutch_distance",
                        value: d,
                        reason: "must be ≥ 0",
                    });
                }
            }
            (None, Some(a)) => Clutch::Acceleration(positive("acceleration", a)?),
            (None, None) => Clutch::Immediate,
        };
        let (m, slave) = positions(env, c.master, c.slave, c.master_source)?;
        if c.phase_offset > gear::MAX_PHASE_OFFSET {
            return Err(EngineError::InvalidArgument {
                name: "phase_offset",
                value: f64::from(c.phase_offset),
                reason: "0 to 128 servo periods (HMC_SetGearPhaseOffset)",
            });
        }
        let gear = Gear::new(numerator, denominator, clutch, c.direction, m, slave)
            .with_phase_offset(c.phase_offset);
        self.insert(
            env,
            (c.master, c.slave, c.master_source),
            Law::Gear(gear),
            m,
        );
        Ok(Reply::Done)
    }

    fn cam_in(&mut self, env: &mut Env, c: &CamIn) -> Result<Reply, EngineError> {
        self.check_new(env.axes, c.master, c.slave)?;
        let table = self
            .tables
            .get(&c.table)
            .cloned()
            .ok_or(EngineError::UnknownCamTable { table: c.table })?;
        for (name, v) in [
            ("master_offset", c.master_offset),
            ("slave_offset", c.slave_offset),
            ("slave_scaling", c.slave_scaling),
        ] {
            bounded(name, v)?;
        }
        positive("master_scaling", c.master_scaling)?;
        let start = match (c.start_position, c.start_input) {
            (Some(_), Some(_)) => {
                return Err(EngineError::InvalidArgument {
                    name: "start_position",
                    value: c.start_position.unwrap_or(0.0),
                    reason: "give a start position or a start input, not both",
                })
            }
            (Some(p), None) => {
                CamStart::MasterPosition(bounded("start_position", p)?, c.start_direction)
            }
            (None, Some(ch)) => {
                let count = env.ctx.di.len() as u16;
                if usize::from(ch) >= env.ctx.di.len() {
                    return Err(EngineError::InvalidChannel {
                        kind: "digital inputs",
                        channel: ch,
                        count,
                    });
                }
                CamStart::Input(ch)
            }
            (None, None) => match c.start_capture {
                Some(ch) => cam_capture_start(ch)?,
                None => CamStart::Immediate,
            },
        };
        if c.start_capture.is_some() && !matches!(start, CamStart::Capture(_)) {
            return Err(EngineError::InvalidArgument {
                name: "start_capture",
                value: c.start_capture.map_or(0.0, f64::from),
                reason: "give one start: a position, an input or a capture channel",
            });
        }
        let (m, slave) = positions(env, c.master, c.slave, c.master_source)?;
        let mut cam = Cam::new(c, table, start);
        cam.start_if_immediate(m, slave.p);
        self.insert(env, (c.master, c.slave, c.master_source), Law::Cam(cam), m);
        Ok(Reply::Done)
    }

    /// `superimpose_in`: two different masters, neither the slave nor following it.
    fn superimpose_in(&mut self, env: &mut Env, c: &SuperimposeIn) -> Result<Reply, EngineError> {
        let [m1, m2] = c.masters;
        self.check_new(env.axes, m1, c.slave)?;
        self.check_new(env.axes, m2, c.slave)?;
        if m1 == m2 {
            return Err(EngineError::InvalidArgument {
                name: "masters",
                value: f64::from(m1),
                reason: "the two masters must be different axes",
            });
        }
        let ratios = check_ratios(c.ratios)?;
        let (p1, slave) = positions(env, m1, c.slave, c.master_source)?;
        let (p2, _) = positions(env, m2, c.slave, c.master_source)?;
        let law = Law::Superimpose(Superimpose::new(ratios, [p1, p2], slave.p));
        self.insert_two(env, c.slave, [m1, m2], c.master_source, law, [p1, p2]);
        Ok(Reply::Done)
    }

    /// `tangential_in`: the plane's two member axes of the group are the masters.
    fn tangential_in(&mut self, env: &mut Env, c: &TangentialIn) -> Result<Reply, EngineError> {
        let group = env
            .groups
            .get(c.group)
            .ok_or(EngineError::UnknownGroup { group: c.group })?;
        let [i, j] = c.coordinates;
        if i == j {
            return Err(EngineError::InvalidArgument {
                name: "coordinates",
                value: f64::from(i),
                reason: "the plane needs two different coordinates",
            });
        }
        let member =
            |k: u8| {
                group.members().get(usize::from(k)).copied().ok_or_else(|| {
                    EngineError::InvalidGroup {
                        group: c.group,
                        reason: format!(
                            "has {} coordinates: no coordinate {k}",
                            group.members().len()
                        ),
                    }
                })
            };
        let (x, y) = (member(i)?, member(j)?);
        self.check_new(env.axes, x, c.axis)?;
        self.check_new(env.axes, y, c.axis)?;
        let offset = bounded("offset", c.offset)?;
        let turn = positive("units_per_turn", c.units_per_turn)?;
        let source = MasterSource::Commanded;
        let (px, axis) = positions(env, x, c.axis, source)?;
        let (py, _) = positions(env, y, c.axis, source)?;
        let law = Law::Tangential(Tangential::new(turn, offset, axis, c.group, c.coordinates));
        self.insert_two(env, c.axis, [x, y], source, law, [px, py]);
        Ok(Reply::Done)
    }

    /// Add a coupling of `slave` to two masters (by `source`, whose values are `m` now).
    fn insert_two(
        &mut self,
        env: &mut Env,
        slave: AxisIndex,
        [master, master2]: [AxisIndex; 2],
        source: MasterSource,
        law: Law,
        [m1, m2]: [f64; 2],
    ) {
        let coupling = Coupling {
            slave,
            master,
            source,
            law,
            previous: m1,
            master2: Some(master2),
            previous2: m2,
            ended: false,
        };
        self.insert_coupling(env, coupling);
    }

    /// Define (or replace) a cam table: `cam_table`, and the config's `[[cam_tables]]`.
    pub(crate) fn define_table(&mut self, c: CamTableDefine) -> Result<Reply, EngineError> {
        let table = CamTable::new(c.table, &c.points, c.interpolation)?;
        self.install_table(c.table, table)
    }

    /// Put `table` under number `id` unless a running cam uses that number or there is no room.
    fn install_table(&mut self, id: u16, table: CamTable) -> Result<Reply, EngineError> {
        if let Some(user) = self
            .list
            .iter()
            .find(|k| matches!(&k.law, Law::Cam(cam) if cam.table_id == id))
        {
            return Err(EngineError::CamTableInUse {
                table: id,
                slave: user.slave,
            });
        }
        if !self.tables.contains_key(&id) && self.tables.len() >= MAX_CAM_TABLES {
            return Err(EngineError::InvalidCamTable {
                table: id,
                reason: format!("no room: at most {MAX_CAM_TABLES} tables"),
            });
        }
        self.tables.insert(id, Arc::new(table));
        Ok(Reply::Done)
    }

    /// Add the coupling of `slave` to `master` (by `source`, whose value is `m` now).
    fn insert(
        &mut self,
        env: &mut Env,
        (master, slave, source): (AxisIndex, AxisIndex, MasterSource),
        law: Law,
        m: f64,
    ) {
        let coupling = Coupling {
            slave,
            master,
            source,
            law,
            previous: m,
            master2: None,
            previous2: 0.0,
            ended: false,
        };
        self.insert_coupling(env, coupling);
    }

    /// Add `coupling` (its slave not yet coupled) and recompute stage 3's order.
    fn insert_coupling(&mut self, env: &mut Env, coupling: Coupling) {
        if let Some(axis) = env.axes.get_mut(coupling.slave as usize) {
            axis.set_coupled(
                Some(coupling.master),
                coupling.phase() == CouplingPhase::InSync,
            );
            axis.set_coupling_kind(coupling.status().kind);
        }
        let at = self.list.partition_point(|c| c.slave < coupling.slave);
        self.list.insert(at, coupling);
        self.reorder(env.axes.len());
    }

    fn find(&self, slave: AxisIndex) -> Option<&Coupling> {
        self.list
            .binary_search_by_key(&slave, |c| c.slave)
            .ok()
            .and_then(|i| self.list.get(i))
    }

    fn find_mut(&mut self, slave: AxisIndex) -> Option<&mut Coupling> {
        let i = self.list.binary_search_by_key(&slave, |c| c.slave).ok()?;
        self.list.get_mut(i)
    }

    fn gear_mut(&mut self, slave: AxisIndex) -> Result<&mut Gear, EngineError> {
        let not = EngineError::NotCoupled {
            axis: slave,
            what: "the slave of a gear",
        };
        let i = self
            .list
            .binary_search_by_key(&slave, |c| c.slave)
            .map_err(|_| not.clone())?;
        match self.list.get_mut(i).map(|c| &mut c.law) {
            Some(Law::Gear(g)) => Ok(g),
            _ => Err(not),
        }
    }

    /// `gear_out`/`cam_out`: the slave keeps its velocity and decelerates to rest with its
    /// `decel` (PLCopen MC_GearOut: the slave continues with the velocity it has).
    fn decouple(
        &mut self,
        env: &mut Env,
        slave: AxisIndex,
        kind: CouplingKind,
    ) -> Result<Reply, EngineError> {
        let what = match kind {
            CouplingKind::Gear => "the slave of a gear",
            CouplingKind::Cam => "the slave of a cam",
            CouplingKind::Superimpose => "the slave of a superimposed coupling",
            CouplingKind::Tangential => "a tangential axis",
            CouplingKind::Gantry => "the slave of a gantry",
            CouplingKind::Follow => "a Follow slave",
        };
        let i = self
            .list
            .binary_search_by_key(&slave, |c| c.slave)
            .map_err(|_| EngineError::NotCoupled { axis: slave, what })?;
        let matches = match self.list.get(i).map(|c| &c.law) {
            Some(Law::Gear(_)) => kind == CouplingKind::Gear,
            Some(Law::Cam(_)) => kind == CouplingKind::Cam,
            Some(Law::Superimpose(_)) => kind == CouplingKind::Superimpose,
            Some(Law::Tangential(_)) => kind == CouplingKind::Tangential,
            Some(Law::Follow(_)) => kind == CouplingKind::Follow,
            Some(Law::Gantry(_)) | None => false,
        };
        if !matches {
            return Err(EngineError::NotCoupled { axis: slave, what });
        }
        if let Some(Law::Tangential(t)) = self.list.get(i).map(|c| &c.law) {
            Self::clear_corner_stop(env.groups, t);
        }
        self.list.remove(i);
        if kind == CouplingKind::Follow {
            self.follow_ended(slave);
        }
        if let Some(axis) = env.axes.get_mut(slave as usize) {
            axis.set_coupled(None, false);
            // Not fed (a cam that never started): nothing to release.
            let _ = axis.feed(env.ctx, Feed::Release);
        }
        self.reorder(env.axes.len());
        Ok(Reply::Done)
    }

    /// Recompute stage 3's order: masters before slaves (depth in the master chain, then
    /// index). Loops were refused when the couplings were made, so depths are bounded.
    fn reorder(&mut self, axes: usize) {
        self.order.clear();
        if self.list.is_empty() && self.adds.is_empty() {
            return;
        }
        // A slave's depth is one more than its deepest master's: relaxed once per coupling
        // (a chain is at most that long), so bounded without recursion.
        let mut depths = vec![0usize; axes];
        let edges = self.adds.iter().map(|l| (l.add, l.base));
        let edges: Vec<(AxisIndex, AxisIndex)> = edges.collect();
        for _ in 0..self.list.len() + edges.len() {
            let mut changed = false;
            for &(add, base) in &edges {
                let deepest = depths.get(add as usize).copied().unwrap_or(0);
                if let Some(d) = depths.get_mut(base as usize) {
                    if *d < deepest + 1 {
                        *d = deepest + 1;
                        changed = true;
                    }
                }
            }
            for c in &self.list {
                let deepest = [Some(c.master), c.master2]
                    .into_iter()
                    .flatten()
                    .filter_map(|m| depths.get(m as usize).copied())
                    .max()
                    .unwrap_or(0);
                if let Some(d) = depths.get_mut(c.slave as usize) {
                    if *d < deepest + 1 {
                        *d = deepest + 1;
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        let mut order: Vec<(usize, AxisIndex)> = depths
            .iter()
            .enumerate()
            .map(|(i, &d)| (d, i as AxisIndex))
            .collect();
        order.sort_unstable();
        let slots: Vec<(AxisIndex, Option<usize>)> = order
            .into_iter()
            .map(|(_, a)| {
                let slot = self.list.binary_search_by_key(&a, |c| c.slave).ok();
                (a, slot)
            })
            .collect();
        self.order = slots;
    }

    /// Stage 3: every axis steps, in index order without couplings, else in the couplings' order
    /// with each slave fed from its master just before it steps; then the couplings that ended
    /// are dropped.
    pub(crate) fn step_axes(&mut self, env: &mut Env) {
        self.refresh_corner_waits(env.groups);
        self.run_auto_lifts(env);
        let Env {
            axes, ctx, period, ..
        } = env;
        if !self.handwheels.is_empty() {
            self.drive_handwheels(axes, ctx, *period);
        }
        if self.list.is_empty() && self.adds.is_empty() {
            for axis in axes.iter_mut() {
                axis.step(ctx);
            }
            return;
        }
        for i in 0..self.order.len() {
            let Some(&(index, slot)) = self.order.get(i) else {
                break;
            };
            if let Some(slot) = slot {
                self.drive_slave(slot, axes, ctx, *period);
            }
            if !self.adds.is_empty() {
                self.add_travel(index, axes);
            }
            if let Some(axis) = axes.get_mut(index as usize) {
                axis.step(ctx);
            }
        }
        if self.has_gantry() {
            self.supervise_gantries(axes, ctx);
        }
        self.sweep(axes, ctx);
    }

    /// Stage 3, just before slave `slot`'s axis steps: read its master as this tick left it
    /// and feed the slave. A refused setpoint ends the coupling.
    fn drive_slave(&mut self, slot: usize, axes: &mut [Axis], ctx: &mut Context, period: f64) {
        let Some(c) = self.list.get_mut(slot) else {
            return;
        };
        let Some(master_axis) = axes.get(c.master as usize) else {
            return;
        };
        let master = read_master(master_axis, c.source, c.previous, period);
        let gantry_master = match c.law {
            Law::Gantry(_) => Some(gantry::MasterView::read(master_axis)),
            _ => None,
        };
        let previous = std::mem::replace(&mut c.previous, master.p);
        // The second master (superimposed, tangential); its velocity comes with its state.
        let master2 = c
            .master2
            .and_then(|m| axes.get(m as usize))
            .map(|a| read_master(a, c.source, c.previous2, period));
        if let Some(m2) = master2 {
            c.previous2 = m2.p;
        }
        let Some(slave) = axes.get_mut(c.slave as usize) else {
            return;
        };
        let (feed, end) = match &mut c.law {
            Law::Gear(g) => (Some(g.step(master, previous, period)), false),
            Law::Superimpose(s) => (master2.map(|m2| s.step(master, m2)), false),
            Law::Tangential(t) => {
                let limits = turn_limits(slave);
                (master2.map(|y| t.step(master, y, limits, period)), false)
            }
            Law::Cam(cam) => {
                let input = match cam.start_input() {
                    Some(ch) => ctx.di.get(usize::from(ch)).copied().unwrap_or(false),
                    None => false,
                };
                cam.check_start(previous, master.p, input, slave.commanded().p);
                match cam.step(master) {
                    CamStep::Wait => (None, false),
                    CamStep::Follow(s) => (Some(s), false),
                    CamStep::End(s) => (Some(s), true),
                }
            }
            Law::Gantry(g) => match gantry_master {
                // Both sides off (a HIMC pair made at rest, TV 39): nothing to follow; the
                // slave is re-anchored when the pair is enabled.
                Some(view) if !view.enabled() && !slave.is_enabled() => {
                    g.refused();
                    (None, false)
                }
                Some(view) => (Some(g.step(view, slave)), false),
                None => (None, false),
            },
            Law::Follow(link) => {
                match link.step(self.follows.get_mut(&c.slave), master, previous) {
                    CamStep::Wait => (None, false),
                    CamStep::Follow(s) => (Some(s), false),
                    CamStep::End(s) => (Some(s), true),
                }
            }
        };
        let in_sync = c.phase() == CouplingPhase::InSync;
        let Some(setpoint) = feed else {
            return;
        };
        if let Law::Gantry(g) = &mut c.law {
            // A gantry stays ganged when a slave cannot follow: an enabled master stops with a
            // gantry fault (the slave's own fault or disable stops the slave; a disabled master
            // has nothing to stop, as after `disable_all`), and the slave is re-anchored when
            // it follows again.
            if slave.feed(ctx, Feed::Follow(setpoint)).is_err() {
                g.refused();
                if let Some(m) = axes.get_mut(c.master as usize) {
                    if m.is_enabled() {
                        m.gantry_fault(ctx);
                    }
                }
            }
            return;
        }
        if slave.feed(ctx, Feed::Follow(setpoint)).is_err() || end {
            // Refused (fault, disable, stop, limit): decoupled, the slave keeps what the
            // refusal left it doing. Ended: it stands at the end and is free from next tick.
            c.ended = true;
            slave.set_coupled(None, false);
            if let (Law::Follow(_), Some(f)) = (&c.law, self.follows.get_mut(&c.slave)) {
                f.end();
            }
        } else {
            slave.set_coupled(Some(c.master), in_sync);
        }
    }

    /// Stage 3, just before `base` steps: lay its add axis's travel of this tick on it.
    fn add_travel(&mut self, base: AxisIndex, axes: &mut [Axis]) {
        let Ok(i) = self.adds.binary_search_by_key(&base, |l| l.base) else {
            return;
        };
        let Some(link) = self.adds.get_mut(i) else {
            return;
        };
        let Some(add) = axes.get(link.add as usize) else {
            return;
        };
        let travel = link.travel(add);
        if let Some(axis) = axes.get_mut(base as usize) {
            axis.add_displacement(travel);
        }
    }

    /// After stage 3: drop the couplings that ended this tick and let their slaves go (a
    /// slave still fed ramps down with its `decel`; one that ended at rest simply stops being
    /// fed). Rare: no work otherwise.
    fn sweep(&mut self, axes: &mut [Axis], ctx: &mut Context) {
        if !self.list.iter().any(|c| c.ended) {
            return;
        }
        for c in self.list.iter().filter(|c| c.ended) {
            if let Some(axis) = axes.get_mut(c.slave as usize) {
                let _ = axis.feed(ctx, Feed::Release);
            }
        }
        self.list.retain(|c| !c.ended);
        self.reorder(axes.len());
    }

    /// The couplings' records, by slave.
    pub fn status_into(&self, out: &mut Vec<CouplingStatus>) {
        out.clear();
        out.extend(self.list.iter().map(Coupling::status));
    }

    /// The coupling record of `slave`, if it is one.
    pub fn status_of(&self, slave: AxisIndex) -> Option<CouplingStatus> {
        self.find(slave).map(Coupling::status)
    }
}

/// The master's value (by `source`) and the slave's commanded state, as a new coupling starts
/// from them.
fn positions(
    env: &Env,
    master: AxisIndex,
    slave: AxisIndex,
    source: MasterSource,
) -> Result<(f64, MotionState), EngineError> {
    let m = read_master(axis_ref(env.axes, master)?, source, 0.0, env.period).p;
    Ok((m, axis_ref(env.axes, slave)?.commanded()))
}

/// numerator / denominator of a gear: finite, within bounds, denominator ≠ 0.
fn check_ratio(numerator: f64, denominator: f64) -> Result<(f64, f64), EngineError> {
    let n = bounded("numerator", numerator)?;
    let d = bounded("denominator", denominator)?;
    if d == 0.0 {
        return Err(EngineError::InvalidArgument {
            name: "denominator",
            value: d,
            reason: "must not be zero",
        });
    }
    Ok((n, d))
}

/// The ratios of a superimposed coupling: finite, within bounds.
fn check_ratios([k1, k2]: [f64; 2]) -> Result<[f64; 2], EngineError> {
    Ok([bounded("ratios[0]", k1)?, bounded("ratios[1]", k2)?])
}

/// A tangential axis turns within its own `speed` (else `max_velocity`), `accel` and `decel`
/// (digest 000 §4.4 MoveTang); a limit of 0 means none.
fn turn_limits(axis: &Axis) -> TurnLimits {
    let p = axis.params();
    let or_none = |v: f64| if v > 0.0 { v } else { f64::INFINITY };
    let speed = p.get(ParamId::Speed);
    TurnLimits {
        velocity: or_none(if speed > 0.0 {
            speed
        } else {
            p.get(ParamId::MaxVelocity)
        }),
        acceleration: or_none(p.get(ParamId::Accel)),
        deceleration: or_none(p.get(ParamId::Decel)),
    }
}
