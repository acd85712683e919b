//! EMCY producer (CiA 301 §7.2.7), error register 0x1001 and pre-defined error field 0x1003.

use std::collections::VecDeque;
use std::time::Duration;

use axes::od::ObjectDictionary;

use crate::device::{get_u32, get_u8, set_uint};
use crate::frame::CanFrame;
use crate::objects::idx;

/// Error register bits (CiA 301 §7.5.2.2).
pub mod register {
    pub const GENERIC: u8 = 0x01;
    pub const CURRENT: u8 = 0x02;
    pub const VOLTAGE: u8 = 0x04;
    pub const TEMPERATURE: u8 = 0x08;
    pub const COMMUNICATION: u8 = 0x10;
    pub const DEVICE_PROFILE: u8 = 0x20;
    pub const MANUFACTURER: u8 = 0x80;
}

/// Emergency error codes the node raises itself (CiA 301 Table 21).
pub mod code {
    pub const RESET: u16 = 0x0000;
    /// Life guard error or heartbeat error.
    pub const HEARTBEAT: u16 = 0x8130;
    /// PDO not processed due to length error.
    pub const PDO_LENGTH: u16 = 0x8210;
    /// PDO length exceeded.
    pub const PDO_LENGTH_EXCEEDED: u16 = 0x8220;
    /// RPDO timeout (event timer of an RPDO).
    pub const RPDO_TIMEOUT: u16 = 0x8250;
    /// Unexpected SYNC data length.
    pub const SYNC_LENGTH: u16 = 0x8240;
}

#[derive(Debug, Default)]
pub(crate) struct Emcy {
    /// Active errors: code and register bits.
    active: Vec<(u16, u8)>,
    queue: VecDeque<[u8; 8]>,
    next_allowed: Duration,
    pub(crate) capacity: usize,
    pub(crate) dropped: u64,
    pub(crate) sent: u64,
}

impl Emcy {
    pub(crate) fn register(&self) -> u8 {
        let bits = self.active.iter().fold(0, |r, (_, b)| r | b);
        if self.active.is_empty() {
            bits
        } else {
            bits | register::GENERIC
        }
    }

    pub(crate) fn is_active(&self, code: u16) -> bool {
        self.active.iter().any(|(c, _)| *c == code)
    }

    /// A new error: 0x1001 and 0x1003 updated and an EMCY queued. `false` if the code was
    /// already active (no repeated EMCY).
    pub(crate) fn raise(
        &mut self,
        od: &mut ObjectDictionary,
        code: u16,
        bits: u8,
        info: [u8; 5],
    ) -> bool {
        if code == code::RESET || self.is_active(code) {
            return false;
        }
        self.active.push((code, bits));
        let reg = self.register();
        set_uint(od, idx::ERROR_REGISTER, 0, u64::from(reg));
        push_history(
            od,
            u32::from(code) | u32::from(u16::from_le_bytes([info[0], info[1]])) << 16,
        );
        let c = code.to_le_bytes();
        self.enqueue([c[0], c[1], reg, info[0], info[1], info[2], info[3], info[4]]);
        true
    }

    /// An error went away: 0x1001 updated and an "error reset" EMCY (code 0) queued.
    pub(crate) fn clear(&mut self, od: &mut ObjectDictionary, code: u16) -> bool {
        let before = self.active.len();
        self.active.retain(|(c, _)| *c != code);
        if self.active.len() == before {
            return false;
        }
        let reg = self.register();
        set_uint(od, idx::ERROR_REGISTER, 0, u64::from(reg));
        self.enqueue([0, 0, reg, 0, 0, 0, 0, 0]);
        true
    }

    /// Power-on state: no active errors, empty history (reset node).
    pub(crate) fn reset(&mut self, od: &mut ObjectDictionary) {
        self.active.clear();
        self.queue.clear();
        set_uint(od, idx::ERROR_REGISTER, 0, 0);
        clear_history(od);
    }

    fn enqueue(&mut self, frame: [u8; 8]) {
        if self.queue.len() >= self.capacity.max(1) {
            self.queue.pop_front();
            self.dropped += 1;
        }
        self.queue.push_back(frame);
    }

    /// Send what the inhibit time (0x1015, 100 µs units) allows; `allowed` is false in states
    /// without EMCY, where queued messages are dropped (the history keeps them).
    pub(crate) fn flush(
        &mut self,
        od: &ObjectDictionary,
        now: Duration,
        allowed: bool,
        out: &mut Vec<CanFrame>,
    ) {
        let cob = get_u32(od, idx::COB_ID_EMCY, 0).unwrap_or(0x8000_0000);
        if !allowed || cob & 0x8000_0000 != 0 {
            self.dropped += self.queue.len() as u64;
            self.queue.clear();
            return;
        }
        let inhibit = Duration::from_micros(
            100 * u64::from(crate::device::get_u16(od, idx::EMCY_INHIBIT, 0).unwrap_or(0)),
        );
        while now >= self.next_allowed {
            let Some(frame) = self.queue.pop_front() else {
                break;
            };
            out.push(CanFrame::full((cob & 0x7FF) as u16, frame));
            self.sent += 1;
            self.next_allowed = now.saturating_add(inhibit);
        }
    }

    pub(crate) fn deadline(&self) -> Option<Duration> {
        (!self.queue.is_empty()).then_some(self.next_allowed)
    }
}

/// Newest error at sub-index 1; older ones move down; sub-index 0 counts them.
fn push_history(od: &mut ObjectDictionary, value: u32) {
    let capacity = (1..=254u8)
        .take_while(|&s| od.get(idx::ERROR_HISTORY, s).is_some())
        .count() as u8;
    if capacity == 0 {
        return;
    }
    for s in (2..=capacity).rev() {
        let older = get_u32(od, idx::ERROR_HISTORY, s - 1).unwrap_or(0);
        set_uint(od, idx::ERROR_HISTORY, s, u64::from(older));
    }
    set_uint(od, idx::ERROR_HISTORY, 1, u64::from(value));
    let count = get_u8(od, idx::ERROR_HISTORY, 0).unwrap_or(0);
    set_uint(
        od,
        idx::ERROR_HISTORY,
        0,
        u64::from(count.saturating_add(1).min(capacity)),
    );
}

/// 0x1003:00 = 0 (CiA 301 §7.5.2.4: writing 0 deletes the history).
pub(crate) fn clear_history(od: &mut ObjectDictionary) {
    for s in 1..=254u8 {
        if od.get(idx::ERROR_HISTORY, s).is_none() {
            break;
        }
        set_uint(od, idx::ERROR_HISTORY, s, 0);
    }
    set_uint(od, idx::ERROR_HISTORY, 0, 0);
}
