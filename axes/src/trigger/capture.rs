//! One capture channel: the axis whose positions it latches, the signal it watches and its
//! latches (NMC capture, repeat and advanced capture, digest 001 §2.18, §4.6; HMC
//! `HMC_CaptureConfig` with its window and states, digest 000 §4.4; HIMC touch probe, digest 004
//! §2.12).

use super::{channel_in_range, invalid, Env, CAPTURE_CHANNELS, MAX_CAPTURE_REPEAT};
use crate::axis::SignalEdge;
use crate::command::{bounded, CaptureArm, CaptureArmThreshold, EngineError};
use crate::config::AxisSignal;
use crate::status::{CaptureSource, CaptureState, CaptureStatus, Latch, PositionSource};
use crate::types::AxisIndex;

#[derive(Clone, Debug)]
pub(super) struct Capture {
    status: CaptureStatus,
    /// The position a `commanded_position`/`actual_position` source crosses.
    threshold: Option<f64>,
}

impl Capture {
    /// A channel armed as `c` asks, or why it cannot be.
    pub(super) fn arm(env: &Env, c: &CaptureArm) -> Result<Capture, EngineError> {
        Capture::arm_with(env, c, None)
    }

    /// A channel latching where a position crosses a threshold (NMC advanced capture sources
    /// PRFPOS/ENCPOS, digest 001 §3.15).
    pub(super) fn arm_threshold(
        env: &Env,
        c: &CaptureArmThreshold,
    ) -> Result<Capture, EngineError> {
        let arm = CaptureArm {
            axis: c.axis,
            channel: c.channel,
            source: match c.source {
                PositionSource::Commanded => CaptureSource::CommandedPosition,
                PositionSource::Actual => CaptureSource::ActualPosition,
            },
            input: None,
            source_axis: c.source_axis,
            edge: c.edge,
            repeat: c.repeat,
            continuous: c.continuous,
            window: None,
        };
        Capture::arm_with(env, &arm, Some(bounded("threshold", c.threshold)?))
    }

    fn arm_with(env: &Env, c: &CaptureArm, threshold: Option<f64>) -> Result<Capture, EngineError> {
        let channel = c.channel;
        let by_threshold = matches!(
            c.source,
            CaptureSource::CommandedPosition | CaptureSource::ActualPosition
        );
        if by_threshold && threshold.is_none() {
            return Err(invalid(
                "capture",
                channel,
                "a position source needs a threshold: use capture_arm_threshold",
            ));
        }
        env.axis(c.axis)?;
        channel_in_range("capture", channel, CAPTURE_CHANNELS)?;
        let source_axis = c.source_axis.unwrap_or(c.axis);
        env.axis(source_axis)?;
        match (c.source, c.input) {
            (CaptureSource::Di, None) => {
                return Err(invalid("capture", channel, "source `di` needs an `input`"))
            }
            (CaptureSource::Di, Some(input)) => {
                let count = env.di_forced.len() as u16;
                if input >= count {
                    return Err(EngineError::InvalidChannel {
                        kind: "digital inputs",
                        channel: input,
                        count,
                    });
                }
            }
            (_, Some(_)) => {
                return Err(invalid(
                    "capture",
                    channel,
                    "`input` is for source `di` only",
                ))
            }
            (_, None) => {}
        }
        // TV 62: MtSetCaptRepeat(ax, 65) is refused.
        if !(1..=MAX_CAPTURE_REPEAT).contains(&c.repeat) {
            return Err(EngineError::InvalidArgument {
                name: "repeat",
                value: f64::from(c.repeat),
                reason: "must be 1 to 64 (NMC REPEAT_CAPT_MAX_NUM)",
            });
        }
        if let Some(w) = &c.window {
            bounded("window.low", w.low)?;
            bounded("window.high", w.high)?;
            if w.low > w.high {
                return Err(invalid(
                    "capture",
                    channel,
                    format!("window low {} is above high {}", w.low, w.high),
                ));
            }
        }
        let mut capture = Capture {
            status: CaptureStatus {
                axis: c.axis,
                channel,
                source: c.source,
                source_axis,
                input: c.input,
                edge: c.edge,
                repeat: c.repeat,
                continuous: c.continuous,
                window: c.window,
                state: CaptureState::Waiting,
                count: 0,
                latches: Vec::with_capacity(usize::from(c.repeat)),
            },
            threshold,
        };
        capture.refresh_window(env);
        Ok(capture)
    }

    pub(super) fn key(&self) -> (AxisIndex, u8) {
        (self.status.axis, self.status.channel)
    }

    pub(super) fn status(&self) -> &CaptureStatus {
        &self.status
    }

    pub(super) fn watches_input(&self) -> bool {
        self.status.source == CaptureSource::Di
    }

    fn armed(&self) -> bool {
        self.status.state != CaptureState::Done
    }

    /// This tick's edge of the watched signal, if any; whether it latched.
    pub(super) fn step(&mut self, env: &Env) -> bool {
        if !self.armed() {
            return false;
        }
        let edge = self.edge(env);
        let latched = match edge {
            Some((e, exact)) if self.status.edge.accepts(e.rising) => {
                self.latch(env, e.fraction, e.motor.filter(|_| exact), e.rising)
            }
            _ => false,
        };
        self.refresh_window(env);
        latched
    }

    /// The watched signal's edge in the last tick, and whether it came from the capture axis's
    /// own motion (its motor position at the edge is then exact).
    fn edge(&self, env: &Env) -> Option<(SignalEdge, bool)> {
        let s = &self.status;
        let (axis, signal, electrical) = match s.source {
            CaptureSource::Index => (s.source_axis, AxisSignal::Index, false),
            CaptureSource::Home => (s.source_axis, AxisSignal::Home, false),
            CaptureSource::LimitPos => (s.source_axis, AxisSignal::LimitPos, false),
            CaptureSource::LimitNeg => (s.source_axis, AxisSignal::LimitNeg, false),
            CaptureSource::CommandedPosition => {
                return self.crossing(env, PositionSource::Commanded)
            }
            CaptureSource::ActualPosition => return self.crossing(env, PositionSource::Actual),
            CaptureSource::Di => {
                let input = s.input?;
                // A forced or unwired input changes only by command (`input_changed`); a wired
                // one follows its sensor's electrical level, the last binding winning as in
                // the engine's stage 1.
                if env
                    .di_forced
                    .get(input as usize)
                    .copied()
                    .flatten()
                    .is_some()
                {
                    return None;
                }
                let b = env.bindings.iter().rev().find(|b| b.channel == input)?;
                (b.axis, b.signal, true)
            }
        };
        let edge = env
            .axes
            .get(axis as usize)?
            .signal_edge(signal, electrical)?;
        Some((edge, axis == s.axis))
    }

    /// Where the source axis's `source` position crossed the threshold in the last tick (up:
    /// rising), at the fraction of the tick its straight travel gives.
    fn crossing(&self, env: &Env, source: PositionSource) -> Option<(SignalEdge, bool)> {
        let t = self.threshold?;
        let [a, b] = env
            .axes
            .get(self.status.source_axis as usize)?
            .swept(source);
        let up = a < t && t <= b;
        let down = a > t && t >= b;
        if !(up || down) {
            return None;
        }
        let edge = SignalEdge {
            rising: Some(up),
            fraction: ((t - a) / (b - a)).clamp(0.0, 1.0),
            motor: None,
        };
        Some((edge, false))
    }

    /// A command changed digital input `channel` to `level`; whether it latched.
    pub(super) fn input_changed(&mut self, env: &Env, channel: u16, level: bool) -> bool {
        let s = &self.status;
        if !self.armed()
            || s.source != CaptureSource::Di
            || s.input != Some(channel)
            || !s.edge.accepts(Some(level))
        {
            return false;
        }
        // The tick boundary: the end of the last tick.
        self.latch(env, 1.0, None, Some(level))
    }

    /// Latch the capture axis at `fraction` of the last tick, if the window admits it.
    fn latch(
        &mut self,
        env: &Env,
        fraction: f64,
        motor: Option<f64>,
        rising: Option<bool>,
    ) -> bool {
        let s = &mut self.status;
        let Some(axis) = env.axes.get(s.axis as usize) else {
            return false;
        };
        let latch: Latch = axis.latch(env.tick, fraction, motor, rising.unwrap_or(true));
        // HMC window: on the capture axis's MPos at the edge (digest 000 §8 vector 31).
        if s.window.is_some_and(|w| !w.admits(latch.act_pos)) {
            return false;
        }
        if s.latches.len() >= usize::from(s.repeat) {
            // Continuous: keep the newest `repeat`.
            s.latches.remove(0);
        }
        s.latches.push(latch);
        s.count = s.count.saturating_add(1);
        if !s.continuous && s.count >= u32::from(s.repeat) {
            s.state = CaptureState::Done;
        }
        true
    }

    /// HMC states 1 and 2: whether the capture axis is in its window now.
    fn refresh_window(&mut self, env: &Env) {
        let s = &mut self.status;
        if s.state == CaptureState::Done {
            return;
        }
        let outside = match (s.window, env.axes.get(s.axis as usize)) {
            (Some(w), Some(axis)) => !w.admits(axis.actual_position_wrapped()),
            _ => false,
        };
        s.state = if outside {
            CaptureState::OutsideWindow
        } else {
            CaptureState::Waiting
        };
    }
}
