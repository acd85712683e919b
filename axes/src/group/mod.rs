//! Axis groups (issue 11): 1–9 axes that move together on one path.
//!
//! The engine owns a [`Groups`] registry and runs every group in stage 2 of
//! [`crate::Engine::step`], before the other machine-level planners. A group owns a
//! [`PathPlanner`] (the `path` crate) and a mirror of its queue that remembers what each entry is
//! (a motion, or a buffered non-motion command) so that the planner's events become command
//! states, digital outputs, waits and single-axis moves.
//!
//! Inputs: group commands ([`Groups::apply`], between steps) and the axes as the previous tick
//! left them. Outputs, per tick ([`Groups::step`]): each moving group's members are fed this
//! tick's setpoint (axis position = group coordinate + origin offset), buffered outputs are
//! written, the ledger gets the finished commands. Queries: [`Groups::status_into`],
//! [`Groups::queued_state`]. Order: apply* → step → (status) → apply* → step …
//!
//! Files: `state` (the PLCopen Part 4 state machine and member checks), `queue` (the entries of
//! the group queue), `segment` (commands → path segments), `staging` (splines under
//! construction and the commands behind them), `commands` (each group command), `tick` (the
//! per-tick work), `merge` (HMC merge from the result axis).

use path::planner::{AxisLimits, PathLimits, PathPlanner, PlannerConfig};
use path::{Point, MAX_AXES};

use crate::axis::{Axis, Context, Ledger};
use crate::command::{AxisIndex, CommandId, CommandState, EngineError, GroupId};
use crate::config::GroupsConfig;
use crate::param::ParamId;
use crate::status::{
    AxisFlags, AxisStatus, GroupFault, GroupState, GroupStatus, InterferenceStatus,
};

mod buffered_io;
pub(crate) use buffered_io::IoRequest;
mod commands;
mod corner;
mod estop_break;
pub(crate) use corner::not_at_corner;
pub use corner::{CornerStop, CornerWait};
mod frames;
mod jog;
mod merge;
mod polar;
mod protection;
mod queue;
mod segment;
mod staging;
mod state;
mod tick;

use frames::GroupFrames;
use queue::{GroupQueue, Wait};
use segment::PendingMotion;

/// What the engine lends the groups for one command or one tick (split borrows of its fields).
pub(crate) struct Env<'a> {
    pub tick: u64,
    pub period: f64,
    pub axes: &'a mut [Axis],
    pub ledger: &'a mut Ledger,
    /// The machine's digital inputs (waits read them) and outputs (buffered outputs write them).
    pub di: &'a [bool],
    pub outputs: &'a mut [bool],
    /// Set when an output changed (the engine bumps its I/O version).
    pub outputs_changed: bool,
    /// Analog outputs of the machine (buffered analog writes are checked against it).
    pub analog_outputs: usize,
    /// Pulse trains and analog writes the groups ask for; the engine applies them after the
    /// groups, in order (`buffered_io`).
    pub io_requests: Vec<buffered_io::IoRequest>,
    /// Buffered halts (target, deceleration), applied by [`Groups::step`] after every group.
    pub halts: Vec<(GroupId, Option<f64>)>,
}

impl Env<'_> {
    /// An axis context for one call into an axis.
    fn context(&mut self) -> (Context<'_>, &mut [Axis]) {
        (
            Context {
                tick: self.tick,
                di: self.di,
                ledger: self.ledger,
            },
            self.axes,
        )
    }
}

/// HIMC SetGrpMotionProfile defaults (digest 004 §8.3.6): 100 mm/s, 5000 mm/s² up and down.
/// HIMC's fourth number is a 50 ms smoothing time; mcemu reads it as a jerk time, so the default
/// jerk is 5000 / 0.05 = 100 000 units/s³ (docs/decisions.md, "Axis groups").
pub const DEFAULT_PATH_LIMITS: PathLimits = PathLimits {
    velocity: 100.0,
    acceleration: 5000.0,
    deceleration: 5000.0,
    jerk: 100_000.0,
};

/// HIMC SetGrpAngMotionProfile defaults (digest 004 §8.3.7, TV 49): 360 deg/s, 1800 deg/s² up
/// and down, the 50 ms smoothing time read as a jerk time (1800 / 0.05), as for the linear
/// profile.
pub const DEFAULT_ANGULAR_LIMITS: PathLimits = PathLimits {
    velocity: 360.0,
    acceleration: 1800.0,
    deceleration: 1800.0,
    jerk: 36_000.0,
};

/// HMC's result axis (合轴, digest 000 §4.3) of a group: an axis outside the group that the
/// group feeds the path length it travels (over each motion's counted coordinates) and whose
/// own limits are the path limits of motions that give none.
#[derive(Clone, Debug)]
struct ResultAxis {
    axis: AxisIndex,
    /// The commanded position fed last: its position when the path started from rest plus
    /// the counted path length travelled since.
    position: f64,
    /// The planner's `travelled` when `position` was last brought up to date.
    travelled: f64,
}

/// One group. See the module doc.
#[derive(Clone, Debug)]
pub struct Group {
    id: GroupId,
    members: Vec<AxisIndex>,
    result: Option<ResultAxis>,
    /// Counted path length per path length of the motion being executed (1: every
    /// coordinate counts; see `segment::length_ratio`).
    length_ratio: f64,
    /// The result axis's `speed` the running motion's velocity was taken from, if it was.
    speed_basis: Option<f64>,
    state: GroupState,
    planner: PathPlanner,
    queue: GroupQueue,
    origin: Point,
    /// HIMC's frame chain, NMC's transform and the selected coordinate system.
    frames: GroupFrames,
    /// NMC's polar machine: the plane's point fed as (θ, r) (`polar`).
    polar: Option<polar::PolarMachine>,
    /// Path limits of motions that give none (`group_set_parameter`).
    defaults: PathLimits,
    /// The orientation coordinates (HIMC A, B, C) and their angular profile (HIMC
    /// SetGrpAngMotionProfile); no coordinate: every one is linear.
    orientation: crate::command::CoordinateSet,
    angular: PathLimits,
    /// HMC's path stop after a member's trouble (`fault_deceleration`); None: the path is
    /// dropped (NMC, HIMC).
    fault_deceleration: Option<f64>,
    /// In ErrorStop, the path still decelerating by HMC's rule: which members have left it.
    fault_stop: Option<[bool; tick::FAULT_STOP_SLOTS]>,
    /// An e-stop kept the path (`estop_break`): frozen at the break, the members off it until
    /// a move back.
    off_path: bool,
    /// The last move back to the break (`estop_break`), which a second e-stop may cut.
    return_motion: Option<CommandId>,
    /// Every member limited to the smallest acceleration of the members (CPU 226H).
    smallest_acceleration: bool,
    override_factor: f64,
    /// The members were fed last tick (they are in SynchronizedMotion).
    feeding: bool,
    /// The motion being executed.
    running: Option<CommandId>,
    /// The last motion of a path that ended while a member's smoothed or filtered output was
    /// still on its way: done once every member has arrived (`tick::settle`).
    arriving: Option<CommandId>,
    segment: u64,
    user_segment: u32,
    /// The buffered wait the path stands at.
    waiting: Option<Wait>,
    /// An aborting motion waiting for the path to come to rest.
    pending: Option<PendingMotion>,
    /// The last motion queued is one HMC merges at its end (`merge`).
    last_mergeable: bool,
    /// Motions queued from now on may merge (`mergeable`, 0 for HMC_Move3D).
    merge_eligible: bool,
    /// A tangential axis's corner stops (`corner`), the plane direction the last queued
    /// motion ends in, and a release of the corner stop the path stands at.
    corner_stop: Option<corner::CornerStop>,
    last_direction: Option<f64>,
    corner_released: bool,
    /// A spline under construction and the commands after it (`staging`).
    staging: staging::Staging,
    /// A jog in progress (the planner is idle meanwhile).
    jog: Option<jog::Jog>,
    last_error: Option<crate::command::ErrorKind>,
    fault: Option<GroupFault>,
    /// Sum of the members' parameter versions when their limits were last given to the planner.
    params_version: u64,
    /// The planner's events of one step (reused).
    events: Vec<path::planner::PathEvent>,
    /// The move protection's view of this group, written by [`Groups::step`].
    interference: (InterferenceStatus, f64),
    /// Outputs waiting for a path distance, watched stop inputs (`buffered_io`).
    buffered_io: buffered_io::BufferedIo,
}

impl Group {
    pub fn id(&self) -> GroupId {
        self.id
    }

    pub fn members(&self) -> &[AxisIndex] {
        &self.members
    }

    /// The result axis, if the group has one.
    pub fn result_axis(&self) -> Option<AxisIndex> {
        self.result.as_ref().map(|r| r.axis)
    }

    /// The axes bound to the group: the members, then the result axis. Each is IN_GROUP, in
    /// SynchronizedMotion while the group feeds it, and its trouble stops the whole group.
    fn bound_axes(&self) -> impl Iterator<Item = AxisIndex> + '_ {
        self.members.iter().copied().chain(self.result_axis())
    }

    /// The path limits of a motion that gives none: the result axis's `speed`, `accel`,
    /// `decel` and `jerk` (jerk only in S-curve mode) when the group has one (HMC, digest 000
    /// §4.3), else the group parameters. A result-axis value that is not positive falls back
    /// to the group parameter.
    fn motion_defaults(&self, axes: &[Axis]) -> PathLimits {
        let Some(axis) = self.result_axis().and_then(|a| axes.get(a as usize)) else {
            return self.defaults;
        };
        let p = axis.params();
        let or_default = |v: f64, d: f64| if v > 0.0 && v.is_finite() { v } else { d };
        PathLimits {
            velocity: or_default(p.get(ParamId::Speed), self.defaults.velocity),
            acceleration: or_default(p.get(ParamId::Accel), self.defaults.acceleration),
            deceleration: or_default(p.get(ParamId::Decel), self.defaults.deceleration),
            jerk: if p.flag(ParamId::JerkMode) {
                or_default(p.get(ParamId::Jerk), self.defaults.jerk)
            } else {
                f64::INFINITY
            },
        }
    }

    /// The angular profile a motion of this group is held to, if it has orientation
    /// coordinates.
    fn angular_profile(&self) -> Option<segment::AngularProfile> {
        if self.orientation.is_empty() {
            return None;
        }
        let mut coordinates = [false; MAX_AXES];
        for k in self.orientation.iter() {
            if let Some(c) = coordinates.get_mut(k) {
                *c = true;
            }
        }
        Some(segment::AngularProfile {
            coordinates,
            limits: self.angular,
        })
    }

    /// The result axis's `speed`, if the group has a result axis and it is a positive number.
    fn result_speed(&self, axes: &[Axis]) -> Option<f64> {
        let axis = axes.get(self.result_axis()? as usize)?;
        let speed = axis.params().get(ParamId::Speed);
        (speed > 0.0 && speed.is_finite()).then_some(speed)
    }

    /// The planner's override: the group's, times the live change of the result axis's `speed`
    /// since the running motion took its velocity from it (HMC: the result axis's Speed is
    /// editable live, digest 000 §4.3, TV 3 for a single axis). Changes only when one of them
    /// does; the planner then re-plans the running motion from where it is.
    fn follow_live_speed(&mut self, axes: &[Axis]) {
        let live = match (self.speed_basis, self.result_speed(axes)) {
            (Some(basis), Some(now)) => now / basis,
            _ => 1.0,
        };
        let factor = (self.override_factor * live).min(commands::MAX_OVERRIDE);
        if factor != self.planner.override_factor() {
            self.planner.set_override(factor);
        }
    }

    pub fn state(&self) -> GroupState {
        self.state
    }

    /// Commanded velocity along the path; during a jog, the signed velocity along the jog
    /// coordinate.
    pub fn path_velocity(&self) -> f64 {
        self.path_motion().0
    }

    /// Path velocity and acceleration: the planner's, or a jog's along its coordinate.
    fn path_motion(&self) -> (f64, f64) {
        match &self.jog {
            Some(jog) => (jog.velocity(), jog.acceleration()),
            None => {
                let st = self.planner.state();
                (st.path_velocity, st.path_acceleration)
            }
        }
    }

    /// Ordinal of the motion being executed (counted from 1 since the group was created).
    pub fn segment(&self) -> u64 {
        self.segment
    }

    /// The `user_segment` of the motion being executed or last executed (NMC CrdGetUserSegNo).
    pub fn user_segment(&self) -> u32 {
        self.user_segment
    }

    /// The pose a frame link was set to, exactly (HIMC GetGrpCoordTrans, digest 004 TV 57);
    /// `None` for a selection that is not one link (`offset`, `wcs1`…`wcs15`, `pcs`).
    pub fn coordinate_transform(
        &self,
        frame: crate::command::CoordinateSystem,
    ) -> Option<[f64; 6]> {
        self.frames.link_pose(frame)
    }

    /// Number of group coordinates.
    fn dims(&self) -> usize {
        self.members.len()
    }

    /// The group coordinates of the members' commanded positions (minus the origin offset;
    /// under the polar transform the plane's Cartesian point).
    fn current_position(&self, axes: &[Axis]) -> Point {
        let mut p = [0.0; MAX_AXES];
        for (k, &a) in self.members.iter().enumerate() {
            if let (Some(out), Some(axis), Some(o)) =
                (p.get_mut(k), axes.get(a as usize), self.origin.get(k))
            {
                *out = axis.commanded().p - o;
            }
        }
        if let Some(polar) = self.polar {
            polar.cartesian_from_members(&mut p, &self.origin);
        }
        p
    }

    /// Coordinate `k` of [`Group::current_position`] (a sampler's `group_coordinate`), 0 past
    /// the last.
    pub(crate) fn sampled_coordinate(&self, axes: &[Axis], k: u8) -> f64 {
        self.current_position(axes)
            .get(usize::from(k))
            .copied()
            .unwrap_or(0.0)
    }

    /// The status record, each member's IN_POSITION from its status now.
    pub fn status(&self, axes: &[Axis]) -> GroupStatus {
        self.status_with(axes, |a| {
            axes.get(a as usize)
                .is_some_and(|x| x.status().flags.contains(AxisFlags::IN_POSITION))
        })
    }

    /// The status record, with `in_position(axis)` for each member (a snapshot passes the
    /// records it has just assembled).
    fn status_with(&self, axes: &[Axis], in_position: impl Fn(AxisIndex) -> bool) -> GroupStatus {
        let (path_velocity, path_acceleration) = self.path_motion();
        let mut members = [0; MAX_AXES];
        for (out, &a) in members.iter_mut().zip(&self.members) {
            *out = a;
        }
        let idle = self.is_idle();
        let all_in_position = self.members.iter().all(|&a| in_position(a));
        let used = self.queued() as u32;
        let coordinates = self.current_position(axes);
        GroupStatus {
            group: self.id,
            state: self.state,
            result_axis: self.result_axis(),
            axis_count: self.members.len() as u8,
            members,
            coordinates,
            origin: self.origin,
            coordinate_system: self.frames.selected(),
            frame_position: self.frames.position_in_selected(
                self.id,
                &coordinates,
                self.dims(),
                axes,
            ),
            interference: self.interference.0,
            interference_distance: self.interference.1,
            path_velocity,
            path_acceleration,
            current_command: self
                .running
                .or(self.arriving)
                .or(self.waiting.as_ref().map(|w| w.id))
                .or(self.jog.as_ref().map(|j| j.id)),
            segment: self.segment,
            user_segment: self.user_segment,
            queue_used: used,
            queue_free: self.queue.capacity().saturating_sub(used),
            remaining_length: self.planner.remaining_length(),
            in_position: idle && all_in_position,
            override_factor: self.override_factor,
            last_error: self.last_error,
            fault: self.fault,
            merge_speed_tolerance: self.planner.merge_rule().map_or(0.0, |r| r.speed_tolerance),
            mergeable: self.result.is_some() && self.merge_eligible,
            polar: self.polar.is_some(),
        }
    }

    /// Entries in the queue, the running one and a wait included.
    pub fn queued(&self) -> usize {
        self.queue.len()
            + self.staging.len()
            + usize::from(self.waiting.is_some())
            + usize::from(self.pending.is_some())
    }

    /// State of a command still owned by this group.
    fn queued_state(&self, id: CommandId) -> Option<CommandState> {
        if self.running == Some(id)
            || self.arriving == Some(id)
            || self.waiting.as_ref().is_some_and(|w| w.id == id)
            || self.jog.as_ref().is_some_and(|j| j.id == id)
            || self.waits_for_distance(id)
        {
            return Some(CommandState::Running);
        }
        if self.queue.contains(id)
            || self.staging.contains(id)
            || self.pending.as_ref().is_some_and(|p| p.id == id)
        {
            return Some(CommandState::Waiting);
        }
        None
    }
}

/// One axis's own limits as the path planner sees them: `max_velocity` (else `speed`),
/// `max_accel` (else `accel`), and `jerk` in S-curve mode (else none).
fn axis_limits(axis: &Axis) -> AxisLimits {
    let p = axis.params();
    let positive_or = |v: f64, fallback: f64| if v > 0.0 { v } else { fallback };
    AxisLimits {
        velocity: positive_or(p.get(ParamId::MaxVelocity), p.get(ParamId::Speed)),
        acceleration: positive_or(p.get(ParamId::MaxAccel), p.get(ParamId::Accel)),
        jerk: if p.flag(ParamId::JerkMode) {
            p.get(ParamId::Jerk)
        } else {
            f64::INFINITY
        },
    }
}

/// The planner configuration of a group of `members`.
fn planner_config(
    members: &[AxisIndex],
    axes: &[Axis],
    period: f64,
    capacity: u32,
    lookahead: u32,
) -> PlannerConfig {
    let unlimited = AxisLimits {
        velocity: f64::INFINITY,
        acceleration: f64::INFINITY,
        jerk: f64::INFINITY,
    };
    let mut limits = [unlimited; MAX_AXES];
    for (out, &a) in limits.iter_mut().zip(members) {
        if let Some(axis) = axes.get(a as usize) {
            *out = axis_limits(axis);
        }
    }
    PlannerConfig {
        dims: members.len(),
        axes: limits,
        period,
        lookahead: lookahead as usize,
        capacity: capacity as usize,
    }
}

/// Every group of the machine, by group number. `Clone` for the atomic batches' checkpoint.
#[derive(Clone, Debug)]
pub struct Groups {
    config: GroupsConfig,
    /// Sorted by group number (deterministic order, no hash map).
    groups: Vec<Group>,
    /// Move protections between two groups, sorted by number.
    protections: Vec<protection::Protection>,
}

impl Groups {
    pub fn new(config: GroupsConfig) -> Groups {
        Groups {
            config,
            groups: Vec::new(),
            protections: Vec::new(),
        }
    }

    pub fn iter(&self) -> impl Iterator<Item = &Group> {
        self.groups.iter()
    }

    pub fn get(&self, id: GroupId) -> Option<&Group> {
        self.groups.iter().find(|g| g.id == id)
    }

    fn get_mut(&mut self, id: GroupId) -> Result<&mut Group, EngineError> {
        self.groups
            .iter_mut()
            .find(|g| g.id == id)
            .ok_or(EngineError::UnknownGroup { group: id })
    }

    /// Stage 2, first part: every group in group-number order. See [`Group::step`].
    pub(crate) fn step(&mut self, env: &mut Env) {
        self.guard(env);
        for g in &mut self.groups {
            g.step(env);
        }
        // Buffered halts (NMC CrdBufStopMtn) after every group, so one may halt another: a
        // target that cannot halt now (stopping, in error) is left as it is.
        for (target, deceleration) in std::mem::take(&mut env.halts) {
            if let Ok(g) = self.get_mut(target) {
                let defaults = g.motion_defaults(env.axes).deceleration;
                let _ = g.halt(deceleration, defaults);
            }
        }
    }

    /// Machine-wide `stop_all` (issue 11 item 6): every moving group's path is dropped and the
    /// group stays enabled (Standby); the machine command stops the members themselves.
    pub(crate) fn drop_paths(&mut self, env: &mut Env) {
        for g in &mut self.groups {
            if matches!(
                g.state,
                GroupState::Moving | GroupState::Halted | GroupState::Stopping
            ) {
                g.drop_all(env, CommandState::Aborted);
                g.state = GroupState::Standby;
            }
        }
    }

    /// Machine-wide `enable_all`, after the axes: every Disabled group whose members are all
    /// enabled and at rest goes to Standby (`group_enable`'s rule); a group in ErrorStop waits
    /// for a reset.
    pub(crate) fn enable_all(&mut self, env: &Env) {
        for g in &mut self.groups {
            if g.state == GroupState::Disabled {
                // A group with a member not ready stays Disabled: not an error of enable_all.
                let _ = g.enable(env);
            }
        }
    }

    /// Machine-wide `disable_all`: every group is disabled, its path dropped.
    pub(crate) fn disable_all(&mut self, env: &mut Env) {
        for g in &mut self.groups {
            g.drop_all(env, CommandState::Aborted);
            g.state = GroupState::Disabled;
            g.fault = None;
        }
    }

    /// Machine-wide `emergency_stop_all`: every enabled group goes to ErrorStop
    /// (`emergency_stop`); the machine command stops the members themselves.
    pub(crate) fn emergency_stop_all(&mut self, env: &mut Env) {
        for g in &mut self.groups {
            if g.state != GroupState::Disabled {
                g.fault(env, GroupFault::EmergencyStop);
            }
        }
    }

    /// Machine-wide `reset_all`, after the axes: each group in ErrorStop is reset as by
    /// `group_reset` (Standby, or Disabled when its members are all disabled); one whose cause
    /// remains stays in ErrorStop (its members' errors are the ones reported).
    pub(crate) fn reset_all(&mut self, env: &mut Env) {
        for g in &mut self.groups {
            let _ = g.reset(env);
        }
    }

    /// State of a command a group still holds.
    pub(crate) fn queued_state(&self, id: CommandId) -> Option<CommandState> {
        self.groups.iter().find_map(|g| g.queued_state(id))
    }

    /// Every group's status record, reusing `out`; `statuses` are the axes' records of the
    /// same tick (for the members' IN_POSITION).
    pub fn status_into(&self, axes: &[Axis], statuses: &[AxisStatus], out: &mut Vec<GroupStatus>) {
        let in_position = |a: AxisIndex| {
            statuses
                .get(a as usize)
                .is_some_and(|s| s.flags.contains(AxisFlags::IN_POSITION))
        };
        out.clear();
        out.extend(self.groups.iter().map(|g| g.status_with(axes, in_position)));
    }
}
