//! The tangential axis's corner mode (HMC_MoveTangConfigCornerMode, MoveTangCornerFollowNextCmd,
//! MoveTangCornerContinue; manual §4.4.9.2–4.4.9.5, digest 000 §4.4, TV 62): the commands, which
//! set the tracked group's corner stops (`group::corner`), and the per-tick view of whether
//! that group stands at one.

use super::tangential_lift::Lift;
use super::{Couplings, Env, Law, Tangential};
use crate::command::{
    bounded, AxisIndex, CouplingCommand, EngineError, Reply, TangentialCornerMode,
    TangentialCornerModeKind,
};
use crate::coupling::CornerMode;
use crate::group::{not_at_corner, CornerStop, Groups};

/// The auto lift of `tangential_corner_mode` `auto`: a Z axis that exists, is not the
/// tangential axis and not a member of the tracked group (whose path it would leave), and a
/// finite safe position.
fn auto_lift(
    c: &TangentialCornerMode,
    axes: usize,
    members: &[AxisIndex],
) -> Result<Lift, EngineError> {
    let z = c.z_axis.ok_or(EngineError::InvalidArgument {
        name: "z_axis",
        value: 255.0,
        reason: "the auto lift needs the axis that lifts",
    })?;
    if usize::from(z) >= axes {
        return Err(EngineError::InvalidAxis {
            axis: u32::from(z),
            count: axes as u32,
        });
    }
    if z == c.axis || members.contains(&z) {
        return Err(EngineError::InvalidArgument {
            name: "z_axis",
            value: f64::from(z),
            reason:
                "the lifting axis must be neither the tangential axis nor a member of its group",
        });
    }
    let safe = bounded("safe_z", c.safe_z)?;
    Ok(Lift::new(z, safe, c.safe_z_mode))
}

impl Couplings {
    /// `tangential_corner_mode`, `_follow_next`, `_continue`.
    pub(super) fn tangential_corner(
        &mut self,
        env: &mut Env,
        command: &CouplingCommand,
    ) -> Result<Reply, EngineError> {
        match command {
            CouplingCommand::TangentialCornerMode(c) => {
                let mode = match c.mode {
                    TangentialCornerModeKind::None => CornerMode::None,
                    TangentialCornerModeKind::Manual => CornerMode::Manual,
                    TangentialCornerModeKind::Auto => CornerMode::Auto,
                };
                // NaN fails the range check too.
                if !(0.0..=std::f64::consts::PI).contains(&c.angle_limit) {
                    return Err(EngineError::InvalidArgument {
                        name: "angle_limit",
                        value: c.angle_limit,
                        reason: "the corner angle limit is 0 to π radians",
                    });
                }
                let t = self.tangential_mut(c.axis)?;
                let (group, plane) = (t.group(), t.plane());
                let g = env
                    .groups
                    .group_mut(group)
                    .ok_or(EngineError::UnknownGroup { group })?;
                let lift = match mode {
                    CornerMode::Auto => Some(auto_lift(c, env.axes.len(), g.members())?),
                    _ => None,
                };
                g.set_corner_stop((mode != CornerMode::None).then_some(CornerStop {
                    plane: plane.map(usize::from),
                    angle_limit: c.angle_limit,
                }));
                let t = self.tangential_mut(c.axis)?;
                t.set_corner_mode(mode);
                t.set_lift(lift);
                t.set_corner_wait(g.corner_wait().map(|w| w.next_direction));
                Ok(Reply::Done)
            }
            CouplingCommand::TangentialCornerFollowNext(c) => {
                let t = self.manual_tangential(c.axis)?;
                if !t.follow_next() {
                    return Err(not_at_corner(t.group()));
                }
                Ok(Reply::Done)
            }
            CouplingCommand::TangentialCornerContinue(c) => {
                let group = self.manual_tangential(c.axis)?.group();
                env.groups
                    .group_mut(group)
                    .ok_or(EngineError::UnknownGroup { group })?
                    .release_corner()?;
                Ok(Reply::Done)
            }
            _ => Ok(Reply::Done),
        }
    }

    /// Stage 3, before the axes step: each tangential axis with a corner mode learns whether
    /// its group stands at a corner stop (stage 2 of this tick put it there).
    pub(super) fn refresh_corner_waits(&mut self, groups: &Groups) {
        for c in &mut self.list {
            if let Law::Tangential(t) = &mut c.law {
                if t.corner_mode() != CornerMode::None {
                    let wait = groups.get(t.group()).and_then(|g| g.corner_wait());
                    t.set_corner_wait(wait.map(|w| w.next_direction));
                }
            }
        }
    }

    /// A tangential axis is decoupled: its group no longer stops at corners for it.
    pub(super) fn clear_corner_stop(groups: &mut Groups, t: &Tangential) {
        if t.corner_mode() != CornerMode::None {
            if let Some(g) = groups.group_mut(t.group()) {
                g.set_corner_stop(None);
            }
        }
    }

    fn tangential_mut(&mut self, axis: AxisIndex) -> Result<&mut Tangential, EngineError> {
        let found = self
            .list
            .binary_search_by_key(&axis, |c| c.slave)
            .ok()
            .and_then(|i| self.list.get_mut(i));
        match found.map(|c| &mut c.law) {
            Some(Law::Tangential(t)) => Ok(t),
            _ => Err(EngineError::NotCoupled {
                axis,
                what: "a tangential axis",
            }),
        }
    }

    /// The tangential axis `axis` in manual corner mode.
    fn manual_tangential(&mut self, axis: AxisIndex) -> Result<&mut Tangential, EngineError> {
        let t = self.tangential_mut(axis)?;
        if t.corner_mode() != CornerMode::Manual {
            return Err(EngineError::InvalidArgument {
                name: "axis",
                value: f64::from(axis),
                reason: "the tangential axis is not in manual corner mode",
            });
        }
        Ok(t)
    }
}
