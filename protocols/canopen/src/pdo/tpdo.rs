//! Transmit PDOs (CiA 301 §7.2.2.3, transmission types Table 71): synchronous acyclic (0),
//! every n-th SYNC (1–240) with a SYNC start value, RTR-only (252 synchronous, 253 event), and
//! event-driven (254/255: on change of a mapped value or on request, with inhibit time and
//! event timer).

use std::time::Duration;

use axes::od::{ObjectDictionary, PdoDirection};

use super::config::{comm_index, map_index};
use super::{Mapping, PdoComm};
use crate::frame::CanFrame;

#[derive(Debug, Default)]
pub(crate) struct Tpdo {
    /// 0-based number (0x1800 + n).
    pub n: u16,
    pub comm: PdoComm,
    pub map: Mapping,
    /// SYNCs counted towards the next transmission (types 1–240).
    syncs: u8,
    /// The SYNC start value was met (or none is used).
    started: bool,
    inhibit_until: Duration,
    event_due: Option<Duration>,
    /// The data last sent, for change detection.
    last: Option<([u8; 8], usize)>,
    /// An event happened (change, request, entering Operational) that is not yet sent.
    pending: bool,
    /// Type 252: data sampled at the last SYNC, sent on RTR.
    sampled: Option<([u8; 8], usize)>,
    pub(crate) sent: u64,
}

impl Tpdo {
    pub(crate) fn load(od: &ObjectDictionary, n: u16) -> Tpdo {
        Tpdo {
            n,
            comm: PdoComm::load(od, comm_index(PdoDirection::Transmit, n)),
            map: Mapping::load(
                od,
                map_index(PdoDirection::Transmit, n),
                PdoDirection::Transmit,
            ),
            ..Tpdo::default()
        }
    }

    /// Reload the parameters, keeping the run-time state.
    pub(crate) fn reload(&mut self, od: &ObjectDictionary, now: Duration) {
        let fresh = Tpdo::load(od, self.n);
        let changed = fresh.comm != self.comm || fresh.map != self.map;
        self.comm = fresh.comm;
        self.map = fresh.map;
        if changed {
            self.start(now);
        }
    }

    /// A TPDO with no mapped object is never sent.
    pub(crate) fn active(&self) -> bool {
        self.comm.valid() && !self.map.entries.is_empty()
    }

    fn event_driven(&self) -> bool {
        self.comm.ttype >= 254
    }

    /// Entering Operational (or a new configuration): event-driven TPDOs go out once.
    pub(crate) fn start(&mut self, now: Duration) {
        self.syncs = 0;
        self.started = false;
        self.last = None;
        self.sampled = None;
        self.pending = self.event_driven();
        self.event_due = self.timer(now);
    }

    fn timer(&self, now: Duration) -> Option<Duration> {
        (self.event_driven() && self.comm.event_ms > 0)
            .then(|| now.saturating_add(Duration::from_millis(u64::from(self.comm.event_ms))))
    }

    pub(crate) fn request(&mut self) {
        self.pending = true;
    }

    fn send(&mut self, data: ([u8; 8], usize), now: Duration, out: &mut Vec<CanFrame>) {
        out.push(CanFrame::short(self.comm.can_id(), data.0, data.1));
        self.sent += 1;
        self.last = Some(data);
        self.pending = false;
        self.inhibit_until =
            now.saturating_add(Duration::from_micros(100 * u64::from(self.comm.inhibit)));
        self.event_due = self.timer(now);
    }

    /// A SYNC was received (Operational).
    pub(crate) fn on_sync(
        &mut self,
        counter: Option<u8>,
        overflow: u8,
        od: &ObjectDictionary,
        now: Duration,
        out: &mut Vec<CanFrame>,
    ) {
        if !self.active() {
            return;
        }
        match self.comm.ttype {
            0 => {
                let data = self.map.pack(od);
                if self.pending || self.last != Some(data) {
                    self.send(data, now, out);
                }
            }
            t @ 1..=240 => {
                // §7.5.2.35 sub-index 6: with a counter, start at the SYNC whose counter
                // equals the start value.
                // Without one, the n-th SYNC after entering Operational is the first.
                if !self.started {
                    let start = self.comm.sync_start;
                    let with_start = overflow > 0 && start > 0;
                    if with_start && counter != Some(start) {
                        return;
                    }
                    self.started = true;
                    self.syncs = if with_start { t - 1 } else { 0 };
                }
                self.syncs += 1;
                if self.syncs >= t {
                    self.syncs = 0;
                    let data = self.map.pack(od);
                    self.send(data, now, out);
                }
            }
            252 => self.sampled = Some(self.map.pack(od)),
            _ => {}
        }
    }

    /// A remote request for this TPDO (Operational, RTR allowed).
    pub(crate) fn on_rtr(&mut self, od: &ObjectDictionary, now: Duration, out: &mut Vec<CanFrame>) {
        if !self.active() || !self.comm.rtr_allowed() {
            return;
        }
        let data = match self.comm.ttype {
            252 => match self.sampled {
                Some(d) => d,
                None => return,
            },
            _ => self.map.pack(od),
        };
        self.send(data, now, out);
    }

    /// Event-driven transmission: on change of a mapped value, request or event timer, once
    /// the inhibit time has passed. Type 0 only records that a change happened.
    pub(crate) fn on_tick(
        &mut self,
        od: &ObjectDictionary,
        now: Duration,
        out: &mut Vec<CanFrame>,
    ) {
        if !self.active() {
            return;
        }
        if !(self.event_driven() || self.comm.ttype == 0) {
            return;
        }
        let data = self.map.pack(od);
        if self.last.is_some_and(|l| l != data) {
            self.pending = true;
        }
        if !self.event_driven() {
            return;
        }
        let timer = self.event_due.is_some_and(|d| now >= d);
        if (self.pending || timer) && now >= self.inhibit_until {
            self.send(data, now, out);
        }
    }

    pub(crate) fn deadline(&self) -> Option<Duration> {
        if !self.active() || !self.event_driven() {
            return None;
        }
        let wake = if self.pending {
            Some(self.inhibit_until)
        } else {
            self.event_due
        };
        wake.map(|w| w.max(self.inhibit_until))
    }
}
