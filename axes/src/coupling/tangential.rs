//! The tangential axis: an axis that tracks the tangent angle of a group's path in a plane
//! (HMC_MoveTang, digest 000 §4.4 "Tangential tracking", TV 62), e.g. a knife or a cutting head.
//!
//! The tangent is read from the plane's two member axes as stage 3 left them this tick (they
//! step before the tangential axis, so it has no lag): direction atan2(vy, vx), rate
//! (vx·ay − vy·ax)/(vx² + vy²). The angle is unwrapped (it runs on past a full turn), in the
//! axis's units (`units_per_turn` to a turn), plus the offset. The first direction is taken at
//! the turn nearest the axis's position; later jumps of the tangent (a corner) are taken the
//! shortest way (digest 000: "at jumps in the tangent it takes the shortest way"; exactly half
//! a turn counts as counter-clockwise).
//!
//! While the tangent turns within the axis's own limits (`speed` and `accel`/`decel`, HMC:
//! "within its own Accel/Decel/Speed") the axis follows it exactly (in sync). A jump beyond them
//! (a sharp corner, a blend tighter than the axis can turn) is chased: each tick the velocity
//! heads for the one that still stops on the angle (v = v_target ± √(2·decel·|error|)), clamped
//! to `speed` and changed by at most `accel`·dt; once the exact angle is reachable within the
//! limits again the axis is back in sync. While the path stands (at rest, or stopped at a
//! corner) the angle holds. Closed-form work per tick.
//!
//! Corner mode (HMC_MoveTangConfigCornerMode, manual §4.4.9.2): in `manual` mode the group
//! stops at every junction that turns by more than the angle limit (`group::corner`) and waits;
//! `follow_next` (HMC_MoveTangCornerFollowNextCmd) turns the axis, within its limits, to the
//! direction the next motion starts in, and the group's release (HMC_MoveTangCornerContinue)
//! lets the path go on. The engine tells the axis each tick whether its group stands at such a
//! stop (`set_corner_wait`).

use std::f64::consts::{PI, TAU};

use crate::command::GroupId;
use crate::profile::MotionState;
use crate::status::CouplingPhase;

/// The tangential axis's own limits for turning.
#[derive(Clone, Copy, Debug)]
pub struct TurnLimits {
    pub velocity: f64,
    pub acceleration: f64,
    pub deceleration: f64,
}

#[derive(Clone, Debug)]
pub struct Tangential {
    /// Axis units per radian.
    scale: f64,
    offset: f64,
    /// The path's last direction (radians); `None` until the path first moves.
    direction: Option<f64>,
    /// The tangent angle (units, unwrapped, offset included) and its rate.
    target: f64,
    target_velocity: f64,
    /// The axis's setpoint of the last tick.
    last: MotionState,
    phase: CouplingPhase,
    group: GroupId,
    plane: [u8; 2],
    /// The corner mode, and the next motion's direction while the group stands at a corner
    /// stop.
    corner: CornerMode,
    corner_wait: Option<f64>,
    /// The auto lift's Z axis and where its sequence stands (mode 2 only).
    lift: Option<super::tangential_lift::Lift>,
}

/// How the tangential axis handles corners (HMC_MoveTangConfigCornerMode `ucCornerMode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CornerMode {
    /// 0: no lift; a jump of the tangent is chased the shortest way.
    #[default]
    None,
    /// 1: manual lift: the path stops at corners above the angle limit and waits.
    Manual,
    /// 2: auto lift: the path stops at the same corners and `tangential_lift` lifts Z, turns
    /// the axis and lowers Z by itself.
    Auto,
}

/// `d` into (−π, π]: the shortest way round.
fn shortest(d: f64) -> f64 {
    let d = d.rem_euclid(TAU);
    if d > PI {
        d - TAU
    } else {
        d
    }
}

impl Tangential {
    /// Tracking from the axis's commanded state `axis`; it holds until the path moves.
    /// `group` and `plane` (its two coordinates) are the path tracked (for the corner mode).
    pub fn new(
        units_per_turn: f64,
        offset: f64,
        axis: MotionState,
        group: GroupId,
        plane: [u8; 2],
    ) -> Tangential {
        Tangential {
            group,
            plane,
            scale: units_per_turn / TAU,
            offset,
            direction: None,
            target: axis.p,
            target_velocity: 0.0,
            last: axis,
            phase: CouplingPhase::Waiting,
            corner: CornerMode::None,
            corner_wait: None,
            lift: None,
        }
    }

    pub fn group(&self) -> GroupId {
        self.group
    }

    pub fn plane(&self) -> [u8; 2] {
        self.plane
    }

    pub fn corner_mode(&self) -> CornerMode {
        self.corner
    }

    pub fn set_corner_mode(&mut self, mode: CornerMode) {
        self.corner = mode;
        if mode == CornerMode::None {
            self.corner_wait = None;
        }
    }

    /// The auto lift (with `CornerMode::Auto`).
    pub(super) fn set_lift(&mut self, lift: Option<super::tangential_lift::Lift>) {
        self.lift = lift;
    }

    pub(super) fn lift_mut(&mut self) -> Option<&mut super::tangential_lift::Lift> {
        self.lift.as_mut()
    }

    /// Whether the group stands at a corner stop.
    pub(super) fn at_corner(&self) -> bool {
        self.corner_wait.is_some()
    }

    /// Whether the group stands at a corner stop, and the next motion's direction (radians).
    pub fn set_corner_wait(&mut self, next_direction: Option<f64>) {
        self.corner_wait = next_direction;
    }

    /// HMC_GetMoveTangCornerState: 0 no lift, 1 manual and the path running, 2 manual and the
    /// path standing at a corner, 3 auto and running, 4 auto and lifting (the path standing
    /// at a corner while Z lifts, the axis turns and Z comes back), 255 an auto lift that
    /// could not move Z.
    pub fn corner_state(&self) -> u8 {
        match (self.corner, self.corner_wait) {
            (CornerMode::None, _) => 0,
            (CornerMode::Manual, None) => 1,
            (CornerMode::Manual, Some(_)) => 2,
            (CornerMode::Auto, _) => self.lift.as_ref().map_or(3, |l| l.corner_state()),
        }
    }

    /// HMC_MoveTangCornerFollowNextCmd: track the direction the next motion starts in (the
    /// shortest way round from the last one); the axis turns to it within its limits while
    /// the path stands. Refused (`false`) unless the group stands at a corner stop.
    pub fn follow_next(&mut self) -> bool {
        let Some(next) = self.corner_wait else {
            return false;
        };
        self.target = self.angle_toward(next);
        self.direction = Some(next);
        self.target_velocity = 0.0;
        true
    }

    pub fn phase(&self) -> CouplingPhase {
        self.phase
    }

    /// The tangent angle the axis tracks (HMC_GetMoveTangDestDirection), in its units.
    pub fn angle(&self) -> f64 {
        self.target
    }

    /// How far the axis is from the tangent angle (HMC_GetMoveTangDeviation).
    pub fn deviation(&self) -> f64 {
        self.target - self.last.p
    }

    /// This tick's setpoint from the plane's axes `x` and `y` (this tick's states).
    pub fn step(
        &mut self,
        x: MotionState,
        y: MotionState,
        limits: TurnLimits,
        dt: f64,
    ) -> MotionState {
        self.track(x, y, dt);
        let last = self.last;
        let implied = (self.target - last.p) / dt;
        let slack = 1.0 + 1e-9;
        let fits = implied.abs() <= limits.velocity * slack
            && (implied - last.v).abs()
                <= limits.acceleration.max(limits.deceleration) * dt * slack;
        let next = if fits {
            if self.direction.is_some() {
                self.phase = CouplingPhase::InSync;
            }
            MotionState {
                p: self.target,
                v: self.target_velocity,
                a: (self.target_velocity - last.v) / dt,
            }
        } else {
            self.phase = CouplingPhase::Engaging;
            self.chase(limits, dt)
        };
        self.last = next;
        next
    }

    /// Update the tangent angle and its rate from the plane's axes.
    fn track(&mut self, x: MotionState, y: MotionState, dt: f64) {
        let speed2 = x.v * x.v + y.v * y.v;
        // Below rounding of the positions the direction is noise: the path stands.
        let floor = 1e-12 * (1.0 + x.p.abs() + y.p.abs());
        let moving = speed2.sqrt() * dt > floor;
        if !moving {
            self.target_velocity = 0.0;
            return;
        }
        let direction = y.v.atan2(x.v);
        let rate = (x.v * y.a - y.v * x.a) / speed2;
        self.target = self.angle_toward(direction);
        self.direction = Some(direction);
        self.target_velocity = if rate.is_finite() {
            rate * self.scale
        } else {
            0.0
        };
    }

    /// The unwrapped angle (units) for the path direction `direction` (radians): the shortest
    /// way from the last direction, or the first one at the turn nearest the axis.
    fn angle_toward(&self, direction: f64) -> f64 {
        match self.direction {
            Some(previous) => self.target + shortest(direction - previous) * self.scale,
            None => {
                let angle = direction * self.scale + self.offset;
                let turn = TAU * self.scale;
                angle + ((self.last.p - angle) / turn).round() * turn
            }
        }
    }

    /// One tick toward the angle within the limits (see the module doc).
    fn chase(&self, limits: TurnLimits, dt: f64) -> MotionState {
        let last = self.last;
        let error = self.target - last.p;
        let braking = (2.0 * limits.deceleration * error.abs()).sqrt();
        let wanted = (self.target_velocity + error.signum() * braking)
            .clamp(-limits.velocity, limits.velocity);
        let step = limits.acceleration.max(limits.deceleration) * dt;
        let v = last.v + (wanted - last.v).clamp(-step, step);
        MotionState {
            p: last.p + (last.v + v) * 0.5 * dt,
            v,
            a: (v - last.v) / dt,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shortest_way_round() {
        assert!((shortest(1.5 * PI) + 0.5 * PI).abs() < 1e-12);
        assert!((shortest(-1.5 * PI) - 0.5 * PI).abs() < 1e-12);
        assert_eq!(shortest(PI), PI);
        assert_eq!(shortest(-PI), PI);
    }
}
