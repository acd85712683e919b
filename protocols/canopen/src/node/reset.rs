//! NMT reset node / reset communication and power-on (CiA 301 §7.3.2.2.1): areas back to
//! their power-on values (defaults, then the stored image), node-id-dependent COB-IDs, caches
//! reloaded, boot-up message.

use std::ops::RangeInclusive;
use std::time::Duration;

use axes::od::{ObjectDictionary, PdoDirection, Value};

use super::Node;
use crate::device::{get_u16, get_u32, set_uint, Device};
use crate::events::NodeEvent;
use crate::frame::CanFrame;
use crate::nmt::NmtState;
use crate::objects::{idx, valid_node_id, NODE_ID_COBS, UNCONFIGURED};
use crate::pdo::rpdo::Rpdo;
use crate::pdo::tpdo::Tpdo;
use crate::store::{self, ParameterGroup};

const COMMUNICATION_AREA: RangeInclusive<u16> = 0x1000..=0x1FFF;
const APPLICATION_AREA: RangeInclusive<u16> = 0x2000..=0x9FFF;

/// Entries of `area` back to their defaults; the error register and history (not parameters,
/// kept by the EMCY producer) are left alone.
fn restore_defaults(od: &mut ObjectDictionary, area: RangeInclusive<u16>) {
    let defaults: Vec<(u16, u8, Value)> = od
        .entries()
        .filter(|e| area.contains(&e.def.index))
        .filter(|e| !matches!(e.def.index, idx::ERROR_REGISTER | idx::ERROR_HISTORY))
        .filter(|e| e.value != e.def.default)
        .map(|e| (e.def.index, e.def.subindex, e.def.default.clone()))
        .collect();
    for (index, subindex, value) in defaults {
        let _ = od.set(index, subindex, value);
    }
}

impl<D: Device> Node<D> {
    /// Apply the stored image's `group` to the dictionary (a damaged image is ignored: the
    /// defaults stay).
    pub(super) fn apply_stored(&mut self, group: ParameterGroup) {
        if let Some(image) = &self.stored {
            let _ = store::load(self.device.od_mut(), image, group);
        }
    }

    pub(super) fn reset_node(&mut self, now: Duration, out: &mut Vec<CanFrame>) {
        self.enter_initialising();
        restore_defaults(self.device.od_mut(), APPLICATION_AREA);
        self.apply_stored(ParameterGroup::Application);
        self.emcy.reset(self.device.od_mut());
        self.event(NodeEvent::ResetNode);
        self.reset_communication_inner(now, out);
    }

    pub(super) fn reset_communication(&mut self, now: Duration, out: &mut Vec<CanFrame>) {
        self.enter_initialising();
        self.reset_communication_inner(now, out);
    }

    fn reset_communication_inner(&mut self, now: Duration, out: &mut Vec<CanFrame>) {
        restore_defaults(self.device.od_mut(), COMMUNICATION_AREA);
        self.apply_stored(ParameterGroup::Communication);
        self.event(NodeEvent::ResetCommunication);
        self.initialise_communication(now, out);
    }

    fn enter_initialising(&mut self) {
        let from = self.nmt;
        if from != NmtState::Initialising {
            self.nmt = NmtState::Initialising;
            self.event(NodeEvent::NmtStateChanged {
                from,
                to: NmtState::Initialising,
            });
        }
    }

    /// Take the LSS node id, fix node-id-dependent COB-IDs, reload every cache, send the
    /// boot-up message and enter Pre-operational.
    pub(super) fn initialise_communication(&mut self, now: Duration, out: &mut Vec<CanFrame>) {
        let pending = self.lss.pending_id;
        if valid_node_id(pending) || pending == UNCONFIGURED {
            self.node_id = pending;
        }
        self.sdo.reset();
        self.consumers.reset();
        self.guarding.reset();
        if self.node_id == UNCONFIGURED {
            self.nmt = NmtState::Initialising;
            return;
        }
        fix_node_id_cobs(self.device.od_mut(), self.node_id);
        self.reload_all(now);
        out.push(CanFrame::short(0x700 + u16::from(self.node_id), [0; 8], 1));
        let from = self.nmt;
        self.nmt = NmtState::PreOperational;
        self.event(NodeEvent::NmtStateChanged {
            from,
            to: NmtState::PreOperational,
        });
    }

    /// Rebuild the run-time state of every service from the dictionary.
    pub(super) fn reload_all(&mut self, now: Duration) {
        let od = self.device.od();
        self.sdo.tx_id = get_u32(od, idx::SDO_SERVER, 2)
            .map(|c| (c & 0x7FF) as u16)
            .unwrap_or(0x580 + u16::from(self.node_id));
        self.producer.load(od, now, None);
        self.consumers.load(od);
        self.guarding.load(od);
        self.sync.load(od);
        // Every PDO the dictionary has: a user EDS may number them sparsely (0x1400, 0x1402).
        let numbers =
            |base: u16| (0..idx::PDO_RANGE).filter(move |&n| od.contains_object(base + n));
        self.rpdos = numbers(idx::RPDO_COMM).map(|n| Rpdo::load(od, n)).collect();
        self.tpdos = numbers(idx::TPDO_COMM).map(|n| Tpdo::load(od, n)).collect();
    }

    /// Reload what a write to `index` changed.
    pub(super) fn reload_after_write(&mut self, index: u16, now: Duration) {
        let od = self.device.od();
        match index {
            idx::PRODUCER_HEARTBEAT => {
                // A new producer time starts at once.
                let at = (get_u16(od, idx::PRODUCER_HEARTBEAT, 0).unwrap_or(0) > 0).then_some(now);
                self.producer.load(od, now, at);
            }
            idx::CONSUMER_HEARTBEAT => self.consumers.load(od),
            idx::GUARD_TIME | idx::LIFE_TIME_FACTOR => self.guarding.load(od),
            idx::COB_ID_SYNC | idx::SYNC_OVERFLOW => self.sync.load(od),
            _ => match crate::pdo::config::PdoObject::of(index) {
                Some(
                    crate::pdo::config::PdoObject::Comm(PdoDirection::Receive, n)
                    | crate::pdo::config::PdoObject::Map(PdoDirection::Receive, n),
                ) => {
                    if let Some(r) = self.rpdos.iter_mut().find(|r| r.n == n) {
                        *r = Rpdo::load(od, n);
                    }
                }
                Some(
                    crate::pdo::config::PdoObject::Comm(PdoDirection::Transmit, n)
                    | crate::pdo::config::PdoObject::Map(PdoDirection::Transmit, n),
                ) => {
                    if let Some(t) = self.tpdos.iter_mut().find(|t| t.n == n) {
                        t.reload(od, now);
                    }
                }
                None => {}
            },
        }
    }
}

/// COB-IDs of the pre-defined connection set follow the node id: a value within
/// base..=base+0x7F becomes base + node id, flags kept.
fn fix_node_id_cobs(od: &mut ObjectDictionary, node_id: u8) {
    for (index, subindex, base) in NODE_ID_COBS {
        if let Some(v) = get_u32(od, index, subindex) {
            if (base..=base + 0x7F).contains(&(v & 0x7FF)) {
                set_uint(
                    od,
                    index,
                    subindex,
                    u64::from((v & !0x7FF) | (base + u32::from(node_id))),
                );
            }
        }
    }
}
