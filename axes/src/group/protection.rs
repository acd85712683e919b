//! Move protection between two groups (issue 11 item 1; NMC `NMC_SetMvProtect`,
//! `SetMvProtectMode01Para`, `GetMvProtectSts`, `TmvProtectPara`, digest 001 §2.5, §3.7, §4.4).
//!
//! Each tick, before the groups step, every protection looks at the two guarded coordinates
//! as the last tick left them: the distance `origin − Σ dir_k·position_k`, and for each group
//! how much closer its guarded coordinate would still come if stopped at the next check:
//! along its queued path (not the tangent) over
//! [`path::planner::PathPlanner::stopping_distance`] one period on, or along a jog's direction. If the
//! distance less those reserves would fall below the protection distance, the protection
//! acts:
//!
//! - `both_stop` (mode 0): both groups stop (`group_stop` with their deceleration);
//! - `retreat` (mode 1, NMC's "laser" mode): the stop group stops and, at rest, its guarded
//!   axis goes to `safe_wait_position`; the other group halts (its queue kept) and goes on
//!   once the retreat is done, halting again if the distance would still be violated.
//!
//! docs/decisions.md, "Group frames and move protection".

use super::segment;
use super::{Env, Group, Groups};
use crate::command::{
    bounded, nonnegative, positive, CommandId, EngineError, GroupId, MoveLinearAbsolute,
    MoveProtectionEnable, ProtectionMode, Reply,
};
use crate::status::{GroupState, InterferenceStatus};

/// One protection, checked.
#[derive(Clone, Debug)]
pub(crate) struct Protection {
    id: u16,
    groups: [GroupId; 2],
    axes: [usize; 2],
    direction: [f64; 2],
    origin_distance: f64,
    protection_distance: f64,
    mode: ProtectionMode,
    /// Index (0 or 1) of the group that retreats in `retreat` mode.
    stop_index: usize,
    safe_wait_position: f64,
    retreat_velocity: Option<f64>,
    retreat_acceleration: Option<f64>,
    /// The retreat is to be queued once the stop group is at rest.
    retreat_pending: bool,
    /// The queued retreat motion.
    retreat: Option<CommandId>,
    /// The other group was halted by the protection (retreat mode).
    halted_other: bool,
    /// A retreat ran to its end since the other group was halted: it may go on.
    retreat_done: bool,
    /// Acting, or an action not yet finished: reported as interference.
    latched: bool,
    distance: f64,
}

impl Protection {
    fn status(&self) -> InterferenceStatus {
        if self.latched {
            InterferenceStatus::Interference
        } else {
            InterferenceStatus::Clear
        }
    }
}

/// What one group shows the guard: its guarded coordinate, and how much closer to the other
/// group a stop issued at the next check would still bring that coordinate (its reserve,
/// ≥ 0). For a path: [`path::planner::PathPlanner::stopping_distance`] one period on (the
/// period travelled at the speed the path may reach by then, and its braking from there; the
/// speed gained in that period counts — without it a path accelerating hard toward a stop
/// braking gently decided a period late by a whole braking distance's growth) on the
/// queued path itself ([`path::planner::PathPlanner::advance_toward`]: a path that turns
/// toward the other group within its braking distance counts, one that turns away does not).
/// For a jog: the same length along its fixed direction, times the guarded coordinate's
/// share of it when that share closes.
fn guarded(g: &Group, env: &Env, axis: usize, direction: f64) -> (f64, f64) {
    let position = g
        .current_position(env.axes)
        .get(axis)
        .copied()
        .unwrap_or(0.0);
    let deceleration = g.defaults.deceleration;
    if let Some(jog) = &g.jog {
        let v = jog.velocity();
        let share = direction * jog.direction().get(axis).copied().unwrap_or(0.0) * v.signum();
        if share <= 0.0 || v == 0.0 {
            return (position, 0.0);
        }
        let length = jog.stopping_distance(env.period, deceleration);
        return (position, share * length);
    }
    let st = g.planner.state();
    let v = st.path_velocity.abs();
    if v <= 0.0 && st.path_acceleration <= 0.0 {
        return (position, 0.0);
    }
    // The stop comes at the earliest with the next check, one period on; its deceleration
    // over the counted coordinates, as `Group::stop` gives it to the planner.
    let length = g
        .planner
        .stopping_distance(env.period, deceleration / g.length_ratio);
    let mut unit = [0.0; path::MAX_AXES];
    if let Some(u) = unit.get_mut(axis) {
        *u = direction;
    }
    (position, g.planner.advance_toward(&unit, length))
}

impl Groups {
    pub(super) fn enable_protection(
        &mut self,
        c: MoveProtectionEnable,
    ) -> Result<Reply, EngineError> {
        let id = c.protection;
        let invalid = |reason: String| EngineError::InvalidProtection {
            protection: id,
            reason,
        };
        if c.groups[0] == c.groups[1] {
            return Err(invalid("guards two different groups".into()));
        }
        for (k, &group) in c.groups.iter().enumerate() {
            let g = self.get(group).ok_or(EngineError::UnknownGroup { group })?;
            let axis = c.axes[k];
            if axis >= g.dims() {
                return Err(invalid(format!(
                    "axes[{k}] = {axis}: group {group} has {} coordinates",
                    g.dims()
                )));
            }
            if !matches!(c.move_direction[k], 1 | -1) {
                return Err(invalid(format!(
                    "move_direction[{k}] is 1 or -1, not {}",
                    c.move_direction[k]
                )));
            }
        }
        let origin_distance = bounded("origin_distance", c.origin_distance)?;
        let protection_distance = nonnegative("protection_distance", c.protection_distance)?;
        let (stop_index, safe_wait_position) = match c.mode {
            ProtectionMode::BothStop => (0, 0.0),
            ProtectionMode::Retreat => {
                let stop = c.stop_group.ok_or_else(|| {
                    invalid("the retreat mode needs stop_group (NMC stopCrdNo)".into())
                })?;
                let index = c.groups.iter().position(|&g| g == stop).ok_or_else(|| {
                    invalid(format!("stop_group {stop} is not one of the two groups"))
                })?;
                let safe = c.safe_wait_position.ok_or_else(|| {
                    invalid("the retreat mode needs safe_wait_position (NMC safeWaitPos)".into())
                })?;
                (index, bounded("safe_wait_position", safe)?)
            }
        };
        let check = |name: &'static str, v: Option<f64>| {
            v.map(|v| positive(name, bounded(name, v)?)).transpose()
        };
        let p = Protection {
            id,
            groups: c.groups,
            axes: c.axes,
            direction: c.move_direction.map(f64::from),
            origin_distance,
            protection_distance,
            mode: c.mode,
            stop_index,
            safe_wait_position,
            retreat_velocity: check("retreat_velocity", c.retreat_velocity)?,
            retreat_acceleration: check("retreat_acceleration", c.retreat_acceleration)?,
            retreat_pending: false,
            retreat: None,
            halted_other: false,
            retreat_done: false,
            latched: false,
            distance: origin_distance,
        };
        self.protections.retain(|x| x.id != id);
        let at = self.protections.partition_point(|x| x.id < id);
        self.protections.insert(at, p);
        Ok(Reply::Done)
    }

    pub(super) fn disable_protection(&mut self, id: u16) -> Result<Reply, EngineError> {
        let before = self.protections.len();
        self.protections.retain(|x| x.id != id);
        if self.protections.len() == before {
            return Err(EngineError::InvalidProtection {
                protection: id,
                reason: "is not enabled".into(),
            });
        }
        for g in &mut self.groups {
            g.interference = (InterferenceStatus::NotEnabled, 0.0);
        }
        Ok(Reply::Done)
    }

    /// A deleted group's protections go with it.
    pub(super) fn forget_protections(&mut self, group: GroupId) {
        self.protections.retain(|p| !p.groups.contains(&group));
        for g in &mut self.groups {
            g.interference = (InterferenceStatus::NotEnabled, 0.0);
        }
    }

    fn index_of(&self, id: GroupId) -> Option<usize> {
        self.groups.iter().position(|g| g.id == id)
    }

    /// Every protection, in number order (see the module doc). Each group then reports the
    /// first protection it is in.
    pub(super) fn guard(&mut self, env: &mut Env) {
        if self.protections.is_empty() {
            return;
        }
        for g in &mut self.groups {
            g.interference = (InterferenceStatus::NotEnabled, 0.0);
        }
        let mut protections = std::mem::take(&mut self.protections);
        for p in &mut protections {
            self.guard_one(env, p);
        }
        for p in protections.iter().rev() {
            for id in p.groups {
                if let Some(i) = self.index_of(id) {
                    if let Some(g) = self.groups.get_mut(i) {
                        g.interference = (p.status(), p.distance);
                    }
                }
            }
        }
        self.protections = protections;
    }

    fn guard_one(&mut self, env: &mut Env, p: &mut Protection) {
        let (Some(i0), Some(i1)) = (self.index_of(p.groups[0]), self.index_of(p.groups[1])) else {
            return;
        };
        let index = [i0, i1];
        let mut position = [0.0; 2];
        let mut closing = [0.0; 2];
        for k in 0..2 {
            if let Some(g) = self.groups.get(index[k]) {
                (position[k], closing[k]) = guarded(g, env, p.axes[k], p.direction[k]);
            }
        }
        p.distance =
            p.origin_distance - p.direction[0] * position[0] - p.direction[1] * position[1];
        let need: f64 = closing.iter().sum();
        let danger = need > 0.0 && p.distance - need < p.protection_distance;
        let mut acting = danger;
        match p.mode {
            ProtectionMode::BothStop => {
                if danger {
                    for &i in &index {
                        if let Some(g) = self.groups.get_mut(i) {
                            g.protection_stop(env);
                        }
                    }
                }
            }
            ProtectionMode::Retreat => {
                let s = p.stop_index;
                let o = 1 - s;
                if danger {
                    if let Some(g) = self.groups.get_mut(index[s]) {
                        if matches!(g.state, GroupState::Moving | GroupState::Halted)
                            || p.retreat.is_none()
                        {
                            g.protection_stop(env);
                            p.retreat_pending = p.retreat.is_none();
                        }
                    }
                    if closing[o] > 0.0 {
                        if let Some(g) = self.groups.get_mut(index[o]) {
                            if g.state == GroupState::Moving {
                                let _ =
                                    g.halt(Some(g.defaults.deceleration), g.defaults.deceleration);
                                p.halted_other = true;
                                p.retreat_done = false;
                            }
                        }
                    }
                }
                acting |= self.retreat_step(env, p, index[s], index[o]);
            }
        }
        let stopping_now = index.iter().any(|&i| {
            self.groups
                .get(i)
                .is_some_and(|g| g.state == GroupState::Stopping)
        });
        p.latched = acting || (p.latched && stopping_now);
    }

    /// Retreat mode after the stop: queue the retreat once the stop group is at rest, and let
    /// the other group go on once the retreat is done. Returns whether anything is still
    /// under way.
    fn retreat_step(&mut self, env: &mut Env, p: &mut Protection, s: usize, o: usize) -> bool {
        let mut busy = false;
        if p.retreat_pending {
            busy = true;
            if let Some(g) = self.groups.get_mut(s) {
                match g.state {
                    GroupState::Standby if g.is_idle() => {
                        p.retreat_pending = false;
                        p.retreat = g.retreat(env, p);
                    }
                    GroupState::Disabled | GroupState::ErrorStop => p.retreat_pending = false,
                    _ => {}
                }
            }
        }
        if let Some(id) = p.retreat {
            match self.groups.get(s) {
                Some(g) if g.queued_state(id).is_some() => busy = true,
                _ => {
                    p.retreat = None;
                    p.retreat_done = true;
                }
            }
        }
        // The other group goes on only after a retreat made room; with the stop group already
        // waiting at its safe position it stays halted (a `group_continue` is the user's).
        if p.halted_other && !p.retreat_pending && p.retreat.is_none() && p.retreat_done {
            busy = true;
            if let Some(g) = self.groups.get_mut(o) {
                let _ = g.resume();
            }
            p.halted_other = false;
            p.retreat_done = false;
        }
        busy || p.halted_other
    }
}

impl Group {
    /// The protection's stop: a moving or halted path decelerates and drops its queue.
    fn protection_stop(&mut self, env: &mut Env) {
        if matches!(self.state, GroupState::Moving | GroupState::Halted) {
            let _ = self.stop(env, self.defaults.deceleration);
        }
    }

    /// The retreat line: the guarded coordinate to the safe position, the others where they
    /// are (group coordinates). `None` when already there or refused.
    fn retreat(&mut self, env: &mut Env, p: &Protection) -> Option<CommandId> {
        let k = p.axes.get(p.stop_index).copied()?;
        let mut position: Vec<f64> = self.current_position(env.axes).get(..self.dims())?.to_vec();
        let here = position.get_mut(k)?;
        if (*here - p.safe_wait_position).abs() <= 1e-9 {
            return None;
        }
        *here = p.safe_wait_position;
        let c = MoveLinearAbsolute {
            group: self.id,
            position,
            velocity: p.retreat_velocity,
            acceleration: p.retreat_acceleration,
            deceleration: p.retreat_acceleration,
            jerk: None,
            buffer_mode: Default::default(),
            transition: Default::default(),
            user_segment: None,
            independent: Default::default(),
            coordinate_system: None,
        };
        let defaults = self.motion_defaults(env.axes);
        let r = segment::linear_absolute(self.id, self.dims(), &c, &defaults).ok()?;
        match self.submit(env, r) {
            Ok(Reply::Accepted { id }) => Some(id),
            _ => None,
        }
    }
}
