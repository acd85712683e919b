//! Receive PDOs (CiA 301 §7.2.2.2): immediate (254/255) or applied at the next SYNC (0–240),
//! length checks (EMCY 0x8210/0x8220) and deadline monitoring by the event timer (0x8250).

use std::time::Duration;

use axes::od::{ObjectDictionary, PdoDirection};

use super::config::{comm_index, map_index};
use super::{Mapping, PdoComm};

#[derive(Debug, Default)]
pub(crate) struct Rpdo {
    /// 0-based number (0x1400 + n).
    pub n: u16,
    pub comm: PdoComm,
    pub map: Mapping,
    /// Data of a synchronous RPDO waiting for the next SYNC.
    pub buffered: Option<([u8; 8], usize)>,
    pub deadline: Option<Duration>,
}

/// What to do with a received RPDO.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Received {
    /// Write the mapped objects now; `too_long` when the frame had extra bytes (processed,
    /// EMCY 0x8220).
    Apply { too_long: bool },
    /// Kept for the next SYNC.
    Buffered { too_long: bool },
    /// Shorter than the mapping: not processed (EMCY 0x8210).
    TooShort,
}

impl Rpdo {
    pub(crate) fn load(od: &ObjectDictionary, n: u16) -> Rpdo {
        Rpdo {
            n,
            comm: PdoComm::load(od, comm_index(PdoDirection::Receive, n)),
            map: Mapping::load(
                od,
                map_index(PdoDirection::Receive, n),
                PdoDirection::Receive,
            ),
            buffered: None,
            deadline: None,
        }
    }

    pub(crate) fn active(&self) -> bool {
        self.comm.valid()
    }

    pub(crate) fn synchronous(&self) -> bool {
        self.comm.ttype <= 240
    }

    pub(crate) fn on_frame(&mut self, data: &[u8], now: Duration) -> Received {
        if data.len() < self.map.len {
            return Received::TooShort;
        }
        if self.comm.event_ms > 0 {
            self.deadline =
                Some(now.saturating_add(Duration::from_millis(u64::from(self.comm.event_ms))));
        }
        let too_long = data.len() > self.map.len;
        if self.synchronous() {
            let mut buf = [0u8; 8];
            for (slot, b) in buf.iter_mut().zip(data) {
                *slot = *b;
            }
            self.buffered = Some((buf, data.len()));
            Received::Buffered { too_long }
        } else {
            Received::Apply { too_long }
        }
    }

    /// Whether the event timer ran out since the last reception (reported once).
    pub(crate) fn expired(&mut self, now: Duration) -> bool {
        if self.deadline.is_some_and(|d| now > d) {
            self.deadline = None;
            return true;
        }
        false
    }
}
