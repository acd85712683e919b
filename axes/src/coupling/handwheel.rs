//! A handwheel (MPG) driving an axis (issue 12 item 7; NMC SetHandWheel, S-HANDWHEEL, digest
//! 001 §2.9): the axis follows its position at `handwheel_in` plus (counts − counts then) ×
//! ratio, never faster than `velocity` nor with more than `acceleration`.
//!
//! The follower is closed form per tick: it lands on the target when that is within both
//! limits; otherwise the velocity it aims for is the wheel's plus the fastest from which it
//! can still stop at the target with `acceleration`, clamped to `velocity`, and its velocity
//! moves toward that by at most a·dt. So it never exceeds either
//! limit and follows a steadily turning wheel with no steady lag. Wheel travel it cannot
//! follow is caught up (`catch_up`) or, with `drop`, cut to velocity × period per tick and
//! forgotten, as MPG modes that discard excess pulses do.

use super::{axis_ref, Couplings, Env};
use crate::axis::{Axis, Context, Feed};
use crate::command::HandwheelExcess;
use crate::command::{
    positive, EngineError, HandwheelIn, HandwheelSetRatio, HandwheelTurn, Reply,
    HANDWHEEL_EXTERNAL_BASE, HANDWHEEL_EXTERNAL_ENCODERS,
};
use crate::profile::MotionState;
use crate::status::HandwheelStatus;
use crate::types::AxisIndex;

#[derive(Clone, Debug)]
pub struct Handwheel {
    pub axis: AxisIndex,
    pub input: u16,
    ratio: f64,
    velocity: f64,
    acceleration: f64,
    excess: HandwheelExcess,
    /// Target = `base` + ratio × (counts − `base_counts`) − `dropped`.
    base: f64,
    base_counts: i64,
    counts: i64,
    dropped: f64,
    target: f64,
    /// The setpoint fed last tick.
    state: MotionState,
    /// The axis's commanded frame shift of the last tick: a `set_position` moves the wheel's
    /// frame with it.
    frame: f64,
    /// The axis refused its setpoint this tick: removed after the feed.
    ended: bool,
}

/// What a new handwheel starts from.
pub struct Start {
    pub axis: AxisIndex,
    pub input: u16,
    pub ratio: f64,
    pub velocity: f64,
    pub acceleration: f64,
    pub excess: HandwheelExcess,
    pub counts: i64,
    pub state: MotionState,
    pub frame: f64,
}

impl Handwheel {
    pub fn new(s: Start) -> Handwheel {
        Handwheel {
            axis: s.axis,
            input: s.input,
            ratio: s.ratio,
            velocity: s.velocity,
            acceleration: s.acceleration,
            excess: s.excess,
            base: s.state.p,
            base_counts: s.counts,
            counts: s.counts,
            dropped: 0.0,
            target: s.state.p,
            state: s.state,
            frame: s.frame,
            ended: false,
        }
    }

    /// This tick's setpoint for the input's `counts` and the axis's frame shift `frame`.
    pub fn step(&mut self, counts: i64, frame: f64, dt: f64) -> MotionState {
        let shift = frame - self.frame;
        if shift != 0.0 {
            self.frame = frame;
            self.base += shift;
            self.state.p += shift;
            self.target += shift;
        }
        let previous = self.target;
        let mut target = self.base + self.ratio * (counts - self.base_counts) as f64 - self.dropped;
        if self.excess == HandwheelExcess::Drop {
            let most = self.velocity * dt;
            let step = target - previous;
            let kept = step.clamp(-most, most);
            self.dropped += step - kept;
            target = previous + kept;
        }
        self.counts = counts;
        self.target = target;
        let wheel_v = (target - previous) / dt;
        self.state = follow(
            self.state,
            target,
            wheel_v,
            self.velocity,
            self.acceleration,
            dt,
        );
        self.state
    }

    /// A new ratio from here on (NMC SetHandWheelRatio): the target stays where it is and
    /// only the counts after this moment use the new ratio, so nothing jumps.
    pub fn set_ratio(&mut self, ratio: f64) {
        self.base = self.target;
        self.base_counts = self.counts;
        self.dropped = 0.0;
        self.ratio = ratio;
    }

    pub fn status(&self) -> HandwheelStatus {
        HandwheelStatus {
            axis: self.axis,
            input: self.input,
            ratio: self.ratio,
            counts: self.counts,
            target: self.target,
            lag: self.target - self.state.p,
            dropped: self.dropped,
        }
    }
}

/// One tick of a follower at `s` toward `target` moving at `target_v`, within `vmax` and `amax`
/// (positions advance by the new velocity × dt, so the velocity a tick reports is the one that
/// moved it).
fn follow(
    s: MotionState,
    target: f64,
    target_v: f64,
    vmax: f64,
    amax: f64,
    dt: f64,
) -> MotionState {
    let e = target - s.p;
    let dv = amax * dt;
    let exact = e / dt;
    // Reaching the target this tick is within both limits: lock on.
    if (exact - s.v).abs() <= dv && exact.abs() <= vmax {
        return MotionState {
            p: target,
            v: exact,
            a: (exact - s.v) / dt,
        };
    }
    // The lag behind a target that keeps its pace, and the fastest velocity relative to the
    // target from which steps of dv close it (dt·v·(v/dv + 1)/2 = |lag|).
    let lag = e - target_v * dt;
    let brake = ((1.0 + 8.0 * lag.abs() / (dv * dt)).sqrt() - 1.0) * dv / 2.0;
    let wanted = (target_v + lag.signum() * brake).clamp(-vmax, vmax);
    let v = s.v + (wanted - s.v).clamp(-dv, dv);
    MotionState {
        p: s.p + v * dt,
        v,
        a: (v - s.v) / dt,
    }
}

// The registry's side: `handwheel_in`, `handwheel_out`, `handwheel_turn` and the feed before
// stage 3 steps the axes.

impl Couplings {
    pub(super) fn handwheel_in(
        &mut self,
        env: &mut Env,
        c: &HandwheelIn,
    ) -> Result<Reply, EngineError> {
        let axis = axis_ref(env.axes, c.axis)?;
        let (numerator, denominator) = super::check_ratio(c.numerator, c.denominator)?;
        if numerator == 0.0 {
            return Err(EngineError::InvalidArgument {
                name: "numerator",
                value: numerator,
                reason: "must not be zero (NMC SetHandWheel: ratio > 0)",
            });
        }
        let velocity = positive("velocity", c.velocity)?;
        let acceleration = positive("acceleration", c.acceleration)?;
        if c.input == c.axis {
            return Err(EngineError::InvalidArgument {
                name: "input",
                value: f64::from(c.input),
                reason: "an axis cannot follow its own encoder",
            });
        }
        let counts = self.input_counts(env.axes, c.input)?;
        axis.check_can_couple()?;
        if self.handwheels.iter().any(|h| h.axis == c.axis) {
            return Err(EngineError::AxisOnHandwheel { axis: c.axis });
        }
        let wheel = Handwheel::new(Start {
            axis: c.axis,
            input: c.input,
            ratio: numerator / denominator,
            velocity,
            acceleration,
            excess: c.excess,
            counts,
            state: axis.commanded(),
            frame: axis.commanded_frame_offset(),
        });
        let at = self.handwheels.partition_point(|h| h.axis < c.axis);
        self.handwheels.insert(at, wheel);
        if let Some(a) = env.axes.get_mut(c.axis as usize) {
            a.set_handwheel(true);
        }
        Ok(Reply::Done)
    }

    /// `handwheel_out`: the axis ramps to rest with its `decel` from the velocity it has.
    pub(super) fn handwheel_out(
        &mut self,
        env: &mut Env,
        axis: AxisIndex,
    ) -> Result<Reply, EngineError> {
        axis_ref(env.axes, axis)?;
        let i =
            self.handwheels
                .iter()
                .position(|h| h.axis == axis)
                .ok_or(EngineError::NotCoupled {
                    axis,
                    what: "driven by a handwheel",
                })?;
        self.handwheels.remove(i);
        if let Some(a) = env.axes.get_mut(axis as usize) {
            a.set_handwheel(false);
            let _ = a.feed(env.ctx, Feed::Release);
        }
        Ok(Reply::Done)
    }

    /// `handwheel_set_ratio`: the named axis's handwheel, or without `axis` every handwheel.
    pub(super) fn handwheel_set_ratio(
        &mut self,
        env: &mut Env,
        c: &HandwheelSetRatio,
    ) -> Result<Reply, EngineError> {
        let (numerator, denominator) = super::check_ratio(c.numerator, c.denominator)?;
        let none = |axis: AxisIndex| EngineError::NotCoupled {
            axis,
            what: "driven by a handwheel",
        };
        match c.axis {
            Some(axis) => {
                axis_ref(env.axes, axis)?;
                let wheel = self
                    .handwheels
                    .iter_mut()
                    .find(|h| h.axis == axis)
                    .ok_or(none(axis))?;
                wheel.set_ratio(numerator / denominator);
            }
            None if self.handwheels.is_empty() => return Err(none(0)),
            None => {
                for wheel in &mut self.handwheels {
                    wheel.set_ratio(numerator / denominator);
                }
            }
        }
        Ok(Reply::Done)
    }

    /// `handwheel_turn`: an operator turns an external encoder.
    pub(super) fn handwheel_turn(&mut self, c: &HandwheelTurn) -> Result<Reply, EngineError> {
        let slot = self.external_slot(c.input)?;
        if let Some(n) = self.external.get_mut(slot) {
            *n = n.wrapping_add(c.counts);
        }
        Ok(Reply::Done)
    }

    fn external_slot(&self, input: u16) -> Result<usize, EngineError> {
        input
            .checked_sub(HANDWHEEL_EXTERNAL_BASE)
            .filter(|k| *k < HANDWHEEL_EXTERNAL_ENCODERS)
            .map(usize::from)
            .ok_or(EngineError::UnknownHandwheelInput {
                input,
                axes: 0,
                external_end: HANDWHEEL_EXTERNAL_BASE + HANDWHEEL_EXTERNAL_ENCODERS,
            })
    }

    /// The count of handwheel input `input`: an axis's encoder or an external encoder.
    fn input_counts(&self, axes: &[Axis], input: u16) -> Result<i64, EngineError> {
        let unknown = EngineError::UnknownHandwheelInput {
            input,
            axes: axes.len() as u32,
            external_end: HANDWHEEL_EXTERNAL_BASE + HANDWHEEL_EXTERNAL_ENCODERS,
        };
        if input < HANDWHEEL_EXTERNAL_BASE {
            return axes
                .get(usize::from(input))
                .map(Axis::encoder_counts)
                .ok_or(unknown);
        }
        let slot = self.external_slot(input).map_err(|_| unknown)?;
        Ok(self.external.get(slot).copied().unwrap_or(0))
    }

    /// Stage 3, before the axes step: feed each handwheel's axis. An axis encoder as input is
    /// read as the last tick left it (one tick late; external encoders change between ticks).
    /// A refused setpoint (fault, disable, stop, a limit) ends the handwheel, as it ends a
    /// coupling.
    pub(super) fn drive_handwheels(&mut self, axes: &mut [Axis], ctx: &mut Context, period: f64) {
        let mut ended = false;
        for i in 0..self.handwheels.len() {
            let Some(input) = self.handwheels.get(i).map(|h| h.input) else {
                break;
            };
            let counts = self.input_counts(axes, input).unwrap_or(0);
            let Some(h) = self.handwheels.get_mut(i) else {
                break;
            };
            let Some(axis) = axes.get_mut(h.axis as usize) else {
                continue;
            };
            let setpoint = h.step(counts, axis.commanded_frame_offset(), period);
            if axis.feed(ctx, Feed::Follow(setpoint)).is_err() {
                axis.set_handwheel(false);
                let _ = axis.feed(ctx, Feed::Release);
                h.ended = true;
                ended = true;
            }
        }
        if ended {
            self.handwheels.retain(|h| !h.ended);
        }
    }

    /// The handwheels' records, by axis.
    pub fn handwheels_into(&self, out: &mut Vec<HandwheelStatus>) {
        out.clear();
        out.extend(self.handwheels.iter().map(Handwheel::status));
    }

    /// The external encoders' counts (256, 257), in input order (NMC_GetEncPos).
    pub fn external_encoders(&self) -> [i64; HANDWHEEL_EXTERNAL_ENCODERS as usize] {
        self.external
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wheel(excess: HandwheelExcess) -> Handwheel {
        Handwheel::new(start(excess))
    }

    fn start(excess: HandwheelExcess) -> Start {
        Start {
            axis: 0,
            input: 256,
            ratio: 0.01,
            velocity: 10.0,
            acceleration: 100.0,
            excess,
            counts: 0,
            state: MotionState::default(),
            frame: 0.0,
        }
    }

    #[test]
    fn a_fast_turn_is_caught_up_within_the_limits() {
        let mut h = wheel(HandwheelExcess::CatchUp);
        let dt = 0.001;
        // 1000 counts = 10 units at once: far faster than 10 units/s.
        let mut s = MotionState::default();
        let mut last_v = 0.0;
        for _ in 0..3000 {
            s = h.step(1000, 0.0, dt);
            assert!(s.v.abs() <= 10.0 + 1e-9, "{}", s.v);
            assert!((s.v - last_v).abs() <= 100.0 * dt + 1e-9);
            last_v = s.v;
        }
        assert_eq!(s.p, 10.0);
        assert_eq!(s.v, 0.0);
    }

    #[test]
    fn a_fast_turn_with_drop_forgets_what_the_velocity_cannot_follow() {
        let mut h = wheel(HandwheelExcess::Drop);
        let dt = 0.001;
        let mut s = MotionState::default();
        for _ in 0..3000 {
            s = h.step(1000, 0.0, dt);
        }
        // One tick at most velocity × dt of the 10 units was kept.
        assert!((s.p - 0.01).abs() < 1e-12, "{}", s.p);
        assert!((h.status().dropped - 9.99).abs() < 1e-9);
    }

    #[test]
    fn a_steady_wheel_is_followed_with_no_steady_lag() {
        let mut h = Handwheel::new(Start {
            ratio: 0.005,
            ..start(HandwheelExcess::CatchUp)
        });
        let dt = 0.001;
        let mut s = MotionState::default();
        // 1 count per tick = 5 units/s, half the velocity limit: the start's lag is caught up.
        for i in 1..=2000 {
            s = h.step(i, 0.0, dt);
        }
        assert!((s.v - 5.0).abs() < 1e-9, "{}", s.v);
        assert!(h.status().lag.abs() < 1e-9, "{}", h.status().lag);
    }
}
