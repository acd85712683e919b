//! The controller's E-stop input (digest 004 §1.10, §2.8, §9.2.6 `BindEMO`): a rising edge of
//! the bound GPI (8 unless `BindEMO` chose another, 0 = none) stops every axis at once, as
//! `EStop` does, and latches `eERR_EMERGENCY_STOP`.
//!
//! Sans-IO. [`EstopBinding`] is shared between the Native ASCII server, which publishes the
//! binding its registers hold after every line ([`EstopBinding::publish`]), and an
//! [`EstopInput`], which the transport runs after every servo tick (an engine observer) with
//! the digital inputs of that tick: [`EstopInput::tick`] says whether the E-stop fires now.
//! The server then reads [`EstopBinding::take_tripped`] before each line to latch the code.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// The bound input as the server last published it: 0 = none, else (channel + 1) with bit 32
/// set when the input is inverted (`SetGPIInvert`, which the E-stop sees as every reader does).
#[derive(Debug)]
pub struct EstopBinding {
    bound: AtomicU64,
    tripped: AtomicBool,
}

const INVERTED: u64 = 1 << 32;

impl EstopBinding {
    /// GPI 8 (channel 7), not inverted: the controller's default.
    pub fn new() -> EstopBinding {
        let b = EstopBinding {
            bound: AtomicU64::new(0),
            tripped: AtomicBool::new(false),
        };
        b.publish(Some(7), false);
        b
    }

    /// The binding now: input `channel` (0-based), inverted or not; `None`: no E-stop input.
    pub fn publish(&self, channel: Option<usize>, inverted: bool) {
        let word = match channel.and_then(|c| u32::try_from(c).ok()) {
            Some(c) => (u64::from(c) + 1) | if inverted { INVERTED } else { 0 },
            None => 0,
        };
        self.bound.store(word, Ordering::Relaxed);
    }

    fn load(&self) -> Option<(usize, bool)> {
        let word = self.bound.load(Ordering::Relaxed);
        let channel = (word & u64::from(u32::MAX)).checked_sub(1)?;
        Some((usize::try_from(channel).ok()?, word & INVERTED != 0))
    }

    /// Whether the E-stop fired since the last call (the code is then to be latched).
    pub fn take_tripped(&self) -> bool {
        // A plain load first: the common case (nothing fired) writes nothing.
        self.tripped.load(Ordering::Relaxed) && self.tripped.swap(false, Ordering::AcqRel)
    }
}

impl Default for EstopBinding {
    fn default() -> Self {
        EstopBinding::new()
    }
}

/// The edge detector, one per machine: call [`EstopInput::tick`] once per servo tick.
#[derive(Debug, Default)]
pub struct EstopInput {
    /// The binding and its level at the last tick.
    last: Option<((usize, bool), bool)>,
}

impl EstopInput {
    /// The digital inputs `di` of this tick; true when the bound input rose (after inversion)
    /// since the last tick, and `binding` records that it fired. A new binding starts from the
    /// input's level: binding an input that is already on fires nothing.
    pub fn tick(&mut self, binding: &EstopBinding, di: &[bool]) -> bool {
        let Some(bound) = binding.load() else {
            self.last = None;
            return false;
        };
        let (channel, inverted) = bound;
        let level = di.get(channel).is_some_and(|&on| on != inverted);
        let rose = matches!(self.last, Some((was, false)) if was == bound) && level;
        self.last = Some((bound, level));
        if rose {
            binding.tripped.store(true, Ordering::Release);
        }
        rose
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rising_edge_of_the_bound_input_fires_once() {
        let b = EstopBinding::new();
        let mut e = EstopInput::default();
        let mut di = [false; 8];
        assert!(!e.tick(&b, &di));
        di[7] = true;
        assert!(e.tick(&b, &di));
        assert!(!e.tick(&b, &di), "held high: no new edge");
        assert!(b.take_tripped());
        assert!(!b.take_tripped());
        di[7] = false;
        assert!(!e.tick(&b, &di));
        di[3] = true;
        assert!(!e.tick(&b, &di), "another input");
    }

    #[test]
    fn unbound_rebound_and_inverted() {
        let b = EstopBinding::new();
        let mut e = EstopInput::default();
        let mut di = [false; 8];
        b.publish(None, false);
        e.tick(&b, &di);
        di[7] = true;
        assert!(!e.tick(&b, &di), "BindEMO(0): TV 7, no reaction");
        // Bound to an input that is already on: no edge until it falls and rises again.
        b.publish(Some(7), false);
        assert!(!e.tick(&b, &di));
        // Inverted: the input reads off while it is on; switching it off is the rising edge.
        b.publish(Some(7), true);
        assert!(!e.tick(&b, &di));
        di[7] = false;
        assert!(e.tick(&b, &di));
        // A channel the machine does not have reads off.
        b.publish(Some(40), false);
        assert!(!e.tick(&b, &di));
    }
}
