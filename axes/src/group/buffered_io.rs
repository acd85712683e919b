//! A group's buffered I/O and stops beyond `group_set_output` (`group_pulse_output`,
//! `group_set_analog_output`, `group_stop_input`, `group_buffered_halt`; NMC
//! CrdBufDoBitPulseEnable / Disable, CrdBufOut, CrdAdvBufIoOnAfterLen / OffBeforeLen,
//! CrdBufSetEstopDI, CrdBufEstopDIExOnOff, CrdBufStopMtn, digest 001 §2.7).
//!
//! Inputs, in the order they come: [`Group::io_item`] checks a command into a queue item (from
//! `apply`); [`Group::reach_io`] acts on one when the path reaches its marker (a planner event
//! of `step`), or, for an output at a path distance, keeps it waiting; each tick
//! [`Group::watch_stop_inputs`] (before the path steps) reads the digital inputs the group
//! watches and [`Group::fire_distance_outputs`] (after it) acts on the waiting outputs whose
//! point the path has crossed (`PathState::travelled`). Outputs: digital outputs written at
//! once; pulse trains and analog writes as [`IoRequest`]s in `Env::io_requests`, which the
//! engine applies after the groups have stepped; halts in `Env::halts`, applied by
//! `Groups::step` after every group has stepped (a halt of another group); a watched input's
//! e-stop of the group. All of it bounded: [`MAX_DISTANCE_OUTPUTS`] waiting outputs,
//! [`STOP_INPUT_SLOTS`] watches.

use crate::command::{
    bounded, finite, CommandId, CommandState, EngineError, ErrorKind, GroupBufferedHalt,
    GroupPulseOutput, GroupSetAnalogOutput, GroupStopInput, PulseDigitalOutput,
};
use crate::status::{GroupFault, GroupState};

use super::queue::{IoAction, Item, PathPoint};
use super::{Env, Group};

/// Watches a group keeps (`group_stop_input` slots 0 … 63).
pub const STOP_INPUT_SLOTS: u16 = 64;
/// Outputs that may wait for their path distance at once; one more is refused (its command
/// ends with `queue_full`).
pub const MAX_DISTANCE_OUTPUTS: usize = 256;

/// A pulse train or an analog write a group asks the engine for (it owns the timed outputs and
/// the analog image).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum IoRequest {
    Pulse(PulseDigitalOutput),
    Analog { channel: u16, value: f64 },
}

/// An output waiting for the path to travel to `at` (`PathState::travelled`).
#[derive(Clone, Debug, PartialEq)]
struct DistanceOutput {
    id: CommandId,
    at: f64,
    /// Before the end: the distance, the marker's place, and the queue length `at` was
    /// worked out for (motion pushed or finished since moves the end, and `at` is worked out
    /// again: a program may push the motion after the marker was reached).
    before_end: Option<(f64, f64, usize)>,
    action: IoAction,
}

/// The group's waiting outputs and watched inputs.
#[derive(Clone, Debug, Default)]
pub(super) struct BufferedIo {
    /// In the order their markers were reached.
    waiting: Vec<DistanceOutput>,
    /// (slot, input, level), in slot order.
    stop_inputs: Vec<(u16, u16, bool)>,
}

/// A point the path has not reached while it stands at `x` (the fire check's tolerance is
/// half of this).
fn just_past(x: f64) -> f64 {
    x + 2e-9 * x.abs().max(1.0)
}

/// A time of a pulse train: seconds in [0, 1e6] (the timed outputs' range).
fn pulse_time(name: &'static str, v: f64) -> Result<f64, EngineError> {
    if v.is_finite() && (0.0..=1e6).contains(&v) {
        Ok(v)
    } else {
        Err(EngineError::InvalidArgument {
            name,
            value: v,
            reason: "a time in [0, 1e6] s",
        })
    }
}

/// A path distance: finite, ≥ 0, within the engine's magnitudes.
fn distance(name: &'static str, v: f64) -> Result<f64, EngineError> {
    let v = bounded(name, v)?;
    if v < 0.0 {
        return Err(EngineError::InvalidArgument {
            name,
            value: v,
            reason: "a path length ≥ 0",
        });
    }
    Ok(v)
}

fn digital_channel(env: &Env, channel: u16) -> Result<u16, EngineError> {
    if usize::from(channel) < env.outputs.len() {
        Ok(channel)
    } else {
        Err(EngineError::InvalidChannel {
            kind: "digital outputs",
            channel,
            count: env.outputs.len() as u16,
        })
    }
}

impl Group {
    pub(super) fn pulse_output_item(
        &self,
        env: &Env,
        c: &GroupPulseOutput,
    ) -> Result<Item, EngineError> {
        let channel = digital_channel(env, c.channel)?;
        if c.toggles > 0 {
            if c.level.is_none() {
                return Err(EngineError::InvalidArgument {
                    name: "level",
                    value: f64::NAN,
                    reason: "a train (toggles > 0) starts at a level: give one",
                });
            }
            pulse_time("level_time", c.level_time)?;
            pulse_time("other_time", c.other_time)?;
        }
        let at = match (c.after_length, c.before_end) {
            (None, None) => PathPoint::Here,
            (Some(d), None) => PathPoint::After(distance("after_length", d)?),
            (None, Some(d)) => PathPoint::BeforeEnd(distance("before_end", d)?),
            (Some(_), Some(d)) => {
                return Err(EngineError::InvalidArgument {
                    name: "before_end",
                    value: d,
                    reason: "after_length or before_end, not both",
                })
            }
        };
        Ok(Item::Io {
            action: IoAction::Digital {
                channel,
                level: c.level,
                level_time: c.level_time,
                other_time: c.other_time,
                toggles: c.toggles,
            },
            at,
        })
    }

    pub(super) fn analog_output_item(
        &self,
        env: &Env,
        c: &GroupSetAnalogOutput,
    ) -> Result<Item, EngineError> {
        if usize::from(c.channel) >= env.analog_outputs {
            return Err(EngineError::InvalidChannel {
                kind: "analog outputs",
                channel: c.channel,
                count: env.analog_outputs as u16,
            });
        }
        Ok(Item::Io {
            action: IoAction::Analog {
                channel: c.channel,
                value: finite("value", c.value)?,
            },
            at: PathPoint::Here,
        })
    }

    pub(super) fn stop_input_item(
        &self,
        env: &Env,
        c: &GroupStopInput,
    ) -> Result<Item, EngineError> {
        if c.slot >= STOP_INPUT_SLOTS {
            return Err(EngineError::InvalidArgument {
                name: "slot",
                value: f64::from(c.slot),
                reason: "0 … 63",
            });
        }
        if let Some(ch) = c.channel.filter(|ch| usize::from(*ch) >= env.di.len()) {
            return Err(EngineError::InvalidChannel {
                kind: "digital inputs",
                channel: ch,
                count: env.di.len() as u16,
            });
        }
        Ok(Item::Io {
            action: IoAction::StopInput {
                slot: c.slot,
                watch: c.channel.map(|ch| (ch, c.level)),
            },
            at: PathPoint::Here,
        })
    }

    /// The target group is checked by `Groups::apply` (this group cannot see the others).
    pub(super) fn buffered_halt_item(&self, c: &GroupBufferedHalt) -> Result<Item, EngineError> {
        let deceleration = match c.deceleration {
            Some(d) => {
                let d = bounded("deceleration", d)?;
                if d <= 0.0 {
                    return Err(EngineError::InvalidArgument {
                        name: "deceleration",
                        value: d,
                        reason: "must be positive",
                    });
                }
                Some(d)
            }
            None => None,
        };
        Ok(Item::Io {
            action: IoAction::Halt {
                target: c.target,
                deceleration,
            },
            at: PathPoint::Here,
        })
    }

    /// The path reached buffered I/O marker `id`: act now, or wait for its path distance (the
    /// command stays active until it acts).
    pub(super) fn reach_io(
        &mut self,
        env: &mut Env,
        id: CommandId,
        action: IoAction,
        at: PathPoint,
    ) {
        // Where the marker is: the motion executing now began at it (its length covered so far
        // is how far this tick went past it), within the tick's travel.
        let travelled = self.planner.state().travelled;
        let marker = travelled - self.planner.executed_length();
        let (point, before_end) = match at {
            PathPoint::Here => (None, None),
            PathPoint::After(d) => (Some(marker + d / self.length_ratio), None),
            PathPoint::BeforeEnd(d) => {
                let d = d / self.length_ratio;
                let end = travelled + self.planner.remaining_length();
                // Never at the marker itself: the motion it is before may be pushed later.
                (
                    Some((end - d).max(just_past(marker))),
                    Some((d, marker, self.planner.queued())),
                )
            }
        };
        match point {
            Some(p) if p > travelled + 1e-9 * travelled.abs().max(1.0) => {
                if self.buffered_io.waiting.len() >= MAX_DISTANCE_OUTPUTS {
                    self.last_error = Some(ErrorKind::QueueFull);
                    env.ledger
                        .finish(id, CommandState::Error(ErrorKind::QueueFull));
                } else {
                    self.buffered_io.waiting.push(DistanceOutput {
                        id,
                        at: p,
                        before_end,
                        action,
                    });
                }
            }
            _ => {
                self.act(env, action);
                env.ledger.finish(id, CommandState::Done);
            }
        }
    }

    /// After the path stepped: the waiting outputs whose point it has crossed, in order.
    pub(super) fn fire_distance_outputs(&mut self, env: &mut Env) {
        if self.buffered_io.waiting.is_empty() {
            return;
        }
        let travelled = self.planner.state().travelled;
        let queued = self.planner.queued();
        let mut waiting = std::mem::take(&mut self.buffered_io.waiting);
        for w in &mut waiting {
            if let Some((d, marker, counted)) = &mut w.before_end {
                if *counted != queued {
                    // O(queue), only on a tick the queue changed.
                    let end = travelled + self.planner.remaining_length();
                    w.at = (end - *d).max(just_past(*marker));
                    *counted = queued;
                }
            }
        }
        // A point the path stands on is crossed (the sums behind `at` round).
        let reach = travelled + 1e-9 * travelled.abs().max(1.0);
        let (due, left): (Vec<_>, Vec<_>) = waiting.into_iter().partition(|w| w.at <= reach);
        self.buffered_io.waiting = left;
        for w in due {
            self.act(env, w.action);
            env.ledger.finish(w.id, CommandState::Done);
        }
    }

    /// Before the path steps: a watched input at its level e-stops the group (as
    /// `group_emergency_stop`). Whether it did.
    pub(super) fn watch_stop_inputs(&mut self, env: &mut Env) -> bool {
        let hit = self
            .buffered_io
            .stop_inputs
            .iter()
            .any(|(_, ch, level)| env.di.get(usize::from(*ch)) == Some(level));
        if hit && self.state != GroupState::Disabled {
            self.fault(env, GroupFault::EmergencyStop);
            self.emergency_stop_members(env);
        }
        hit
    }

    /// The waiting outputs end `state` (the group stopped, faulted or was reset).
    pub(super) fn drop_distance_outputs(&mut self, env: &mut Env, state: CommandState) {
        for w in self.buffered_io.waiting.drain(..) {
            env.ledger.finish(w.id, state);
        }
    }

    /// Whether output `id` waits for its path distance.
    pub(super) fn waits_for_distance(&self, id: CommandId) -> bool {
        self.buffered_io.waiting.iter().any(|w| w.id == id)
    }

    /// A reset ends every watch.
    pub(super) fn clear_stop_inputs(&mut self) {
        self.buffered_io.stop_inputs.clear();
    }

    fn act(&mut self, env: &mut Env, action: IoAction) {
        match action {
            IoAction::Digital {
                channel,
                level,
                level_time,
                other_time,
                toggles,
            } => {
                if toggles == 0 {
                    if let (Some(v), Some(out)) = (level, env.outputs.get_mut(usize::from(channel)))
                    {
                        if *out != v {
                            *out = v;
                            env.outputs_changed = true;
                        }
                    }
                }
                // toggles 0: the request only ends a running train (it writes nothing).
                env.io_requests.push(IoRequest::Pulse(PulseDigitalOutput {
                    channel,
                    level: level.unwrap_or(false),
                    level_time,
                    other_time,
                    toggles,
                }));
            }
            IoAction::Analog { channel, value } => {
                env.io_requests.push(IoRequest::Analog { channel, value });
            }
            IoAction::StopInput { slot, watch } => {
                let inputs = &mut self.buffered_io.stop_inputs;
                inputs.retain(|(s, _, _)| *s != slot);
                if let Some((ch, level)) = watch {
                    let at = inputs.partition_point(|(s, _, _)| *s < slot);
                    inputs.insert(at, (slot, ch, level));
                }
            }
            IoAction::Halt {
                target,
                deceleration,
            } => env.halts.push((target, deceleration)),
        }
    }

    /// The watches in slot order: (slot, input, level).
    pub fn stop_inputs(&self) -> impl Iterator<Item = (u16, u16, bool)> + '_ {
        self.buffered_io.stop_inputs.iter().copied()
    }

    /// Outputs waiting for their path distance.
    pub fn distance_outputs_waiting(&self) -> usize {
        self.buffered_io.waiting.len()
    }
}
