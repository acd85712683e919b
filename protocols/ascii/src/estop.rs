//! The controller's E-stop input (digest 004 §1.10, §2.8, §9.2.6 `BindEMO`): a rising edge of
//! the bound GPI (8 unless `BindEMO` chose another, 0 = none) stops every axis at once, as
//! `EStop` does, and latches `eERR_EMERGENCY_STOP`.
//!
//! The engine watches the input (`set_estop_input`): the tick that reads the edge is the tick
//! the axes stop. This module is the front-end's side of it, sans-IO:
//! - [`EstopSent`]: the binding the engine holds, so that a line that changed the registers'
//!   binding (`BindEMO`, `SetGPIInvert` of the bound pin) sends the new one before its reply;
//! - [`EstopTrips`]: the engine's count of trips, which an engine observer publishes after every
//!   tick, so that the next line latches the code.

use std::sync::atomic::{AtomicU64, Ordering};

use axes::command::{Command, SetEstopInput};

/// The binding registers ask for: (channel, inverted), or none.
pub type Binding = Option<(usize, bool)>;

/// The engine command that binds `binding`: an inverted input is active low (the E-stop sees
/// the input as every HMPL reader does).
pub fn command(binding: Binding) -> Command {
    let bound = binding.and_then(|(c, inverted)| Some((u16::try_from(c).ok()?, inverted)));
    Command::from(SetEstopInput {
        channel: bound.map(|(c, _)| c),
        level: !bound.is_some_and(|(_, inverted)| inverted),
    })
}

/// The binding last sent to the engine, as one word (`u64::MAX`: none sent yet; 0: none
/// bound; else channel + 1, bit 32 set when inverted), so every line compares it without a
/// lock.
#[derive(Debug)]
pub struct EstopSent(AtomicU64);

const NOT_SENT: u64 = u64::MAX;
const INVERTED: u64 = 1 << 32;

fn word(binding: Binding) -> u64 {
    match binding.and_then(|(c, inv)| Some((u32::try_from(c).ok()?, inv))) {
        Some((c, inverted)) => (u64::from(c) + 1) | if inverted { INVERTED } else { 0 },
        None => 0,
    }
}

impl EstopSent {
    pub fn new() -> EstopSent {
        EstopSent(AtomicU64::new(NOT_SENT))
    }

    /// Whether the engine holds `binding` already.
    pub fn holds(&self, binding: Binding) -> bool {
        self.0.load(Ordering::Acquire) == word(binding)
    }

    /// The engine was sent `binding`.
    pub fn sent(&self, binding: Binding) {
        self.0.store(word(binding), Ordering::Release);
    }
}

impl Default for EstopSent {
    fn default() -> Self {
        EstopSent::new()
    }
}

/// The engine's E-stop input trips, as the observer saw them and as the lines latched them.
#[derive(Debug, Default)]
pub struct EstopTrips {
    published: AtomicU64,
    latched: AtomicU64,
}

impl EstopTrips {
    /// After a tick: the engine's count (`Engine::estop_input_trips`).
    pub fn publish(&self, trips: u64) {
        self.published.store(trips, Ordering::Release);
    }

    /// Whether the input fired since the last call (the code is then to be latched).
    pub fn take_tripped(&self) -> bool {
        let now = self.published.load(Ordering::Acquire);
        // A plain load first: the common case (nothing fired) writes nothing.
        self.latched.load(Ordering::Relaxed) != now
            && self.latched.swap(now, Ordering::AcqRel) != now
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_inverted_input_is_active_low() {
        let c = |b| serde_json::to_value(command(b)).unwrap();
        assert_eq!(
            c(Some((7, false))),
            serde_json::json!({"type": "set_estop_input", "channel": 7, "level": true})
        );
        assert_eq!(c(Some((2, true)))["level"], false);
        assert_eq!(c(None)["channel"], serde_json::Value::Null);
    }

    #[test]
    fn a_binding_is_sent_once() {
        let s = EstopSent::new();
        assert!(!s.holds(Some((7, false))));
        assert!(!s.holds(None), "nothing sent yet: not even none");
        s.sent(Some((7, false)));
        assert!(s.holds(Some((7, false))));
        assert!(!s.holds(Some((7, true))));
        s.sent(None);
        assert!(s.holds(None));
    }

    #[test]
    fn each_trip_is_latched_once() {
        let t = EstopTrips::default();
        assert!(!t.take_tripped());
        t.publish(1);
        assert!(t.take_tripped());
        assert!(!t.take_tripped());
        t.publish(1);
        assert!(!t.take_tripped(), "the same count: no new trip");
        t.publish(3);
        assert!(t.take_tripped());
    }
}
