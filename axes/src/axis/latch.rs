//! What a hardware latch on this axis sees (issue 12 item 4, digest 000 §9 item 34): where the
//! axis was at the start and the end of the last tick, when within the tick each of its signals
//! changed, and the axis's positions at such a moment. The motor is taken to move in a straight
//! line through the tick, so a switch at a fixed position is crossed at the fraction of the tick
//! found from the motor's positions before and after it.

use super::setup::Route;
use super::{Axis, Inputs};
use crate::config::AxisSignal;
use crate::hw::AxisClass;
use crate::status::{Latch, PositionSource};

/// The last tick's start and end, and the inputs as the tick before left them.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Sweep {
    /// Physical motor position.
    pub motor: [f64; 2],
    /// Commanded position, user frame, unwrapped.
    pub cmd: [f64; 2],
    /// Actual position, user frame, unwrapped.
    pub act: [f64; 2],
    /// The inputs as the tick before left them, kept only by a tick that may have changed
    /// their levels (`levels_changed`): the common tick, which changes none, copies nothing.
    pub before: Inputs,
    pub levels_changed: bool,
}

/// The capture and compare channels' part of the axis's status (see `AxisStatus::captures`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TriggerCounts {
    /// Latches of the axis's channels; > 0 is NMC `BIT_AXIS_CAPTSET`.
    pub captures: u32,
    pub capture_position: f64,
    pub compare_outputs: u32,
    /// The Z-phase output's level (`AxisStatus::z_output`).
    pub z_output: bool,
}

/// A change of one of the axis's signals during the last tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SignalEdge {
    /// The new level; `None` for an index pulse, one count wide: both edges at once.
    pub rising: Option<bool>,
    /// When: 0 = the tick's start (a change made by a command between ticks), 1 = its end.
    pub fraction: f64,
    /// Where the motor was at the edge (physical frame), when the axis's own motion made it.
    pub motor: Option<f64>,
}

impl SignalEdge {
    fn level_change(now: bool, then: bool) -> Option<SignalEdge> {
        (now != then).then_some(SignalEdge {
            rising: Some(now),
            fraction: 0.0,
            motor: None,
        })
    }
}

impl Inputs {
    /// The level of `signal`: at the connector (`electrical`) or as the controller reads it.
    fn level(&self, signal: AxisSignal, electrical: bool) -> bool {
        match (signal, electrical) {
            (AxisSignal::Home, true) => self.sensor_home,
            (AxisSignal::Home, false) => self.home,
            (AxisSignal::LimitPos, true) => self.sensor_limit_pos,
            (AxisSignal::LimitPos, false) => self.limit_pos,
            (AxisSignal::LimitNeg, true) => self.sensor_limit_neg,
            (AxisSignal::LimitNeg, false) => self.limit_neg,
            (AxisSignal::Index, _) => self.index,
            (AxisSignal::DriveAlarm, true) => self.sensor_alarm,
            (AxisSignal::DriveAlarm, false) => self.drive_alarm,
        }
    }
}

fn lerp(pair: [f64; 2], f: f64) -> f64 {
    pair[0] + (pair[1] - pair[0]) * f
}

impl Axis {
    /// The edge of `signal` during the last tick, if it changed. `electrical`: the level at the
    /// connector, as a general input wired to the sensor reads it; otherwise the input as the
    /// controller reads it (routing, inversion). An unforced switch of the axis's own changes
    /// where the motor crosses it, exactly (a narrow cam crossed within one tick still gives its
    /// first edge, and a debounce does not delay it: latches sit before the filter); a forced or
    /// routed input changes when the command or the general input did, at the tick's start.
    pub(crate) fn signal_edge(&self, signal: AxisSignal, electrical: bool) -> Option<SignalEdge> {
        let then = if self.sweep.levels_changed {
            &self.sweep.before
        } else {
            &self.inputs
        };
        let (now, f, w) = (&self.inputs, &self.forces, &self.setup);
        // A switch: its exact edge, whether it is forced, its route, wiring and inversion.
        let switch = match signal {
            AxisSignal::Home => Some((
                now.home_edge,
                f.home.is_some(),
                w.home,
                self.home_active_low,
                w.home_invert,
            )),
            AxisSignal::LimitPos => Some((
                now.limit_pos_edge,
                f.limit_pos.is_some(),
                w.limit_pos,
                self.limit_pos_active_low,
                w.limit_pos_invert,
            )),
            AxisSignal::LimitNeg => Some((
                now.limit_neg_edge,
                f.limit_neg.is_some(),
                w.limit_neg,
                self.limit_neg_active_low,
                w.limit_neg_invert,
            )),
            AxisSignal::Index | AxisSignal::DriveAlarm => None,
        };
        if let Some((edge, forced, route, active_low, invert)) = switch {
            if !forced && (electrical || route == Route::Own) {
                return edge.map(|e| SignalEdge {
                    rising: Some(e.rising ^ active_low ^ (invert && !electrical)),
                    fraction: self.fraction_at(e.position),
                    motor: Some(e.position),
                });
            }
        }
        if signal == AxisSignal::Index && f.index.is_none() {
            return now.index_at.map(|p| SignalEdge {
                rising: None,
                fraction: self.fraction_at(p),
                motor: Some(p),
            });
        }
        SignalEdge::level_change(
            now.level(signal, electrical),
            then.level(signal, electrical),
        )
    }

    /// When in the last tick the motor was at `motor` (physical).
    fn fraction_at(&self, motor: f64) -> f64 {
        let [m0, m1] = self.sweep.motor;
        let f = (motor - m0) / (m1 - m0);
        if f.is_finite() {
            f.clamp(0.0, 1.0)
        } else {
            1.0
        }
    }

    /// The axis at `fraction` of the last tick, as a latch reads it: the commanded position
    /// interpolated, the encoder counter of the motor position there (`motor` when the edge
    /// gave it exactly), and the actual position that count stands for.
    pub(crate) fn latch(
        &self,
        tick: u64,
        fraction: f64,
        motor: Option<f64>,
        rising: bool,
    ) -> Latch {
        let s = &self.sweep;
        let m = motor.unwrap_or_else(|| lerp(s.motor, fraction));
        let counts = self.encoder.count_at(m);
        let act = match self.class {
            AxisClass::Virtual => m + self.act_offset + self.injected_fe_sign(),
            AxisClass::Unused => lerp(s.act, fraction),
            _ => self.encoder.position_of_count(counts) + self.act_offset + self.injected_fe_sign(),
        };
        Latch {
            tick,
            rising,
            cmd_pos: self.wrap(lerp(s.cmd, fraction)),
            act_pos: self.wrap(act),
            encoder_counts: counts,
        }
    }

    /// The commanded or actual position at the start and the end of the last tick (user frame,
    /// unwrapped): what a position compare watches.
    pub(crate) fn swept(&self, source: PositionSource) -> [f64; 2] {
        match source {
            PositionSource::Commanded => self.sweep.cmd,
            PositionSource::Actual => self.sweep.act,
        }
    }

    /// The actual position as the status shows it (wrapped on a cyclic axis).
    pub(crate) fn actual_position_wrapped(&self) -> f64 {
        self.wrap(self.act_pos)
    }

    /// What the capture and compare channels on this axis report in its status.
    pub(crate) fn set_trigger_counts(&mut self, counts: TriggerCounts) {
        self.triggers = TriggerCounts {
            z_output: self.triggers.z_output,
            ..counts
        };
    }

    /// Drive the axis's Z-phase output (a `z_compare` channel).
    pub(crate) fn set_z_output(&mut self, level: bool) {
        self.triggers.z_output = level;
    }
}
