//! The CiA 301 slave node: a sans-IO state machine. The transport feeds it received frames
//! ([`Node::on_frame`]) and the time ([`Node::on_tick`], at least at [`Node::next_deadline`]);
//! it returns the frames to send and queues [`NodeEvent`]s for the application.
//!
//! Time is a [`Duration`] since an epoch the caller chooses (the engine's virtual clock); the
//! node never reads a clock.

mod access;
mod reset;

use std::collections::VecDeque;
use std::time::Duration;

use axes::od::{ObjectDictionary, Value};

use crate::device::{get_u8, Device};
use crate::emcy::{self, register, Emcy};
use crate::events::{LossCause, NodeEvent};
use crate::frame::CanFrame;
use crate::heartbeat::{ConsumerEvent, Consumers, Guarding, Producer};
use crate::lss::{LssEffect, LssSlave, LSS_RX_ID, LSS_TX_ID};
use crate::nmt::{NmtCommand, NmtState, Service};
use crate::objects::{
    add_missing, communication_objects, idx, valid_node_id, ErrorBehaviour, NodeConfig,
    UNCONFIGURED,
};
use crate::pdo::rpdo::{Received, Rpdo};
use crate::pdo::tpdo::Tpdo;
use crate::sdo::{SdoCounters, SdoServer};
use crate::sync::SyncConsumer;

/// Events held for the application; older ones are dropped (and counted) beyond this.
const EVENT_CAPACITY: usize = 4096;

/// Counters of what the node received and did, for metrics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct NodeCounters {
    pub frames_in: u64,
    pub frames_out: u64,
    /// Frames for other nodes or services the present state does not run.
    pub ignored: u64,
    pub nmt_commands: u64,
    pub sync: u64,
    pub sync_length_errors: u64,
    pub rpdos: u64,
    pub rpdo_length_errors: u64,
    /// Mapped values an RPDO carried that the device refused.
    pub rpdo_write_errors: u64,
    pub lss_requests: u64,
    pub error_frames: u64,
    pub emcy_sent: u64,
    pub emcy_dropped: u64,
    pub events_dropped: u64,
    pub sdo: SdoCounters,
}

/// A node that cannot be built.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NodeError {
    #[error("node id {0} is invalid: use 1–127, or 255 for an unconfigured LSS slave")]
    NodeId(u8),
}

/// A CiA 301 slave node serving the dictionary of a [`Device`].
#[derive(Debug)]
pub struct Node<D: Device = ObjectDictionary> {
    config: NodeConfig,
    device: D,
    node_id: u8,
    nmt: NmtState,
    now: Duration,
    sdo: SdoServer,
    producer: Producer,
    consumers: Consumers,
    guarding: Guarding,
    sync: SyncConsumer,
    rpdos: Vec<Rpdo>,
    tpdos: Vec<Tpdo>,
    emcy: Emcy,
    lss: LssSlave,
    /// The persisted parameter image (power-on values over the defaults).
    stored: Option<Vec<u8>>,
    /// The image a store/restore is writing, until the transport confirms.
    persisting: Option<Vec<u8>>,
    local_control: bool,
    events: VecDeque<NodeEvent>,
    counters: NodeCounters,
}

impl<D: Device> Node<D> {
    /// A node in Initialising. The communication objects the device lacks are added to its
    /// dictionary ([`communication_objects`]); call [`start`](Self::start) to boot.
    pub fn new(config: NodeConfig, mut device: D) -> Result<Node<D>, NodeError> {
        let id = config.node_id;
        if !(valid_node_id(id) || id == UNCONFIGURED) {
            return Err(NodeError::NodeId(id));
        }
        add_missing(device.od_mut(), communication_objects(&config, id));
        let mut emcy = Emcy::default();
        emcy.capacity = config.emcy_queue;
        Ok(Node {
            sdo: SdoServer::new(
                config.sdo_timeout,
                config.sdo_block_size,
                config.sdo_max_len,
            ),
            lss: LssSlave::new(id, config.bit_timing),
            node_id: id,
            config,
            device,
            nmt: NmtState::Initialising,
            now: Duration::ZERO,
            producer: Producer::default(),
            consumers: Consumers::default(),
            guarding: Guarding::default(),
            sync: SyncConsumer::default(),
            rpdos: Vec::new(),
            tpdos: Vec::new(),
            emcy,
            stored: None,
            persisting: None,
            local_control: false,
            events: VecDeque::new(),
            counters: NodeCounters::default(),
        })
    }

    /// The persisted parameter image to use as power-on values (call before `start`; the
    /// transport reads it from disk). Applied at start and at every reset.
    pub fn set_stored_image(&mut self, image: Option<Vec<u8>>) {
        self.stored = image;
    }

    /// The parameter image last persisted, if any.
    pub fn stored_image(&self) -> Option<&[u8]> {
        self.stored.as_deref()
    }

    /// Power on: apply the stored image, initialise communication, send the boot-up message
    /// and enter Pre-operational. An unconfigured node (id 0xFF) stays in Initialising and
    /// answers LSS only.
    pub fn start(&mut self, now: Duration) -> Vec<CanFrame> {
        let mut out = Vec::new();
        self.now = now;
        self.apply_stored(crate::store::ParameterGroup::All);
        self.initialise_communication(now, &mut out);
        self.counters.frames_out += out.len() as u64;
        out
    }

    pub fn node_id(&self) -> u8 {
        self.node_id
    }

    pub fn nmt_state(&self) -> NmtState {
        self.nmt
    }

    pub fn config(&self) -> &NodeConfig {
        &self.config
    }

    pub fn device(&self) -> &D {
        &self.device
    }

    /// The device, for the application between calls (a drive's servo tick writes its
    /// statusword here; event-driven TPDOs notice the change at the next tick).
    pub fn device_mut(&mut self) -> &mut D {
        &mut self.device
    }

    pub fn od(&self) -> &ObjectDictionary {
        self.device.od()
    }

    pub fn counters(&self) -> NodeCounters {
        NodeCounters {
            sdo: self.sdo.counters,
            emcy_sent: self.emcy.sent,
            emcy_dropped: self.emcy.dropped,
            ..self.counters
        }
    }

    /// While on, SDO downloads are refused with 0x08000021 (the application holds local
    /// control of its parameters).
    pub fn set_local_control(&mut self, on: bool) {
        self.local_control = on;
    }

    /// The transport saw a CAN error frame (counted; the node keeps running).
    pub fn note_error_frame(&mut self) {
        self.counters.error_frames += 1;
    }

    /// The next event for the application.
    pub fn poll_event(&mut self) -> Option<NodeEvent> {
        self.events.pop_front()
    }

    /// Every pending event.
    pub fn drain_events(&mut self) -> impl Iterator<Item = NodeEvent> + '_ {
        self.events.drain(..)
    }

    fn event(&mut self, e: NodeEvent) {
        if self.events.len() >= EVENT_CAPACITY {
            self.events.pop_front();
            self.counters.events_dropped += 1;
        }
        self.events.push_back(e);
    }

    // ---- frames in ----

    /// A received frame; returns the frames to send.
    pub fn on_frame(&mut self, frame: &CanFrame, now: Duration) -> Vec<CanFrame> {
        let mut out = Vec::new();
        self.on_frame_into(frame, now, &mut out);
        out
    }

    /// [`on_frame`](Self::on_frame) appending to `out` (no allocation per frame).
    pub fn on_frame_into(&mut self, frame: &CanFrame, now: Duration, out: &mut Vec<CanFrame>) {
        let before = out.len();
        self.now = now;
        self.counters.frames_in += 1;
        if !self.route(frame, now, out) {
            self.counters.ignored += 1;
        }
        // A producer time written just now starts at once.
        if self.nmt != NmtState::Initialising && self.producer.due(now) {
            self.send_heartbeat(out);
        }
        self.emcy
            .flush(self.device.od(), now, self.nmt.allows(Service::Emcy), out);
        self.counters.frames_out += (out.len() - before) as u64;
    }

    /// Whether [`route`](Self::route) could take `frame` (a cheap check with no effect): a
    /// bus of many nodes hands each frame only to the nodes it concerns, and counts it
    /// [`ignored`](Self::note_ignored) on the rest.
    pub fn accepts(&self, frame: &CanFrame) -> bool {
        let id = frame.id();
        if (id == 0 || id == LSS_RX_ID) && !frame.is_rtr() {
            return true;
        }
        if self.nmt == NmtState::Initialising {
            return false;
        }
        let own = u16::from(self.node_id);
        if frame.is_rtr() {
            return id == 0x700 + own
                || self
                    .tpdos
                    .iter()
                    .any(|t| t.active() && t.comm.can_id() == id);
        }
        id == 0x600 + own
            || self.sync.can_id == Some(id)
            || ((0x701..=0x77F).contains(&id) && self.consumers.monitors((id - 0x700) as u8))
            || self
                .rpdos
                .iter()
                .any(|r| r.active() && r.comm.can_id() == id)
    }

    /// A frame this node was not handed because it does not [`accept`](Self::accepts) it:
    /// counted as [`on_frame`](Self::on_frame) would have counted it.
    pub fn note_ignored(&mut self) {
        self.counters.frames_in += 1;
        self.counters.ignored += 1;
    }

    /// Dispatch by COB-ID (CiA 301 §7.3.3 pre-defined connection set); `false` if nothing
    /// took the frame.
    fn route(&mut self, frame: &CanFrame, now: Duration, out: &mut Vec<CanFrame>) -> bool {
        let id = frame.id();
        let state = self.nmt;
        if id == 0 && !frame.is_rtr() {
            return self.on_nmt(frame.data(), now, out);
        }
        if id == LSS_RX_ID && !frame.is_rtr() {
            return self.on_lss(frame.data(), now, out);
        }
        if state == NmtState::Initialising {
            return false;
        }
        let own = u16::from(self.node_id);
        if frame.is_rtr() {
            if id == 0x700 + own {
                return self.on_guarding(now, out);
            }
            if state.allows(Service::Pdo) {
                if let Some(t) = self
                    .tpdos
                    .iter_mut()
                    .find(|t| t.active() && t.comm.can_id() == id)
                {
                    t.on_rtr(self.device.od(), now, out);
                    return true;
                }
            }
            return false;
        }
        if (0x701..=0x77F).contains(&id) && self.consumers.monitors((id - 0x700) as u8) {
            return self.on_heartbeat((id - 0x700) as u8, frame.data(), now, out);
        }
        if id == 0x600 + own {
            // CiA 301 SDO frames always carry 8 bytes; others are ignored.
            if !state.allows(Service::Sdo) || frame.len() != 8 {
                return false;
            }
            let mut sdo = std::mem::take(&mut self.sdo);
            sdo.on_request(frame.padded(), now, self, out);
            self.sdo = sdo;
            return true;
        }
        if self.sync.can_id == Some(id) && state.allows(Service::Sync) {
            self.on_sync(frame.data(), now, out);
            return true;
        }
        if state.allows(Service::Pdo) {
            if let Some(k) = self
                .rpdos
                .iter()
                .position(|r| r.active() && r.comm.can_id() == id)
            {
                self.on_rpdo(k, frame.data(), now);
                return true;
            }
        }
        false
    }

    fn on_nmt(&mut self, data: &[u8], now: Duration, out: &mut Vec<CanFrame>) -> bool {
        if self.nmt == NmtState::Initialising {
            return false;
        }
        let Some(cmd) = NmtCommand::parse(data, self.node_id) else {
            return false;
        };
        self.counters.nmt_commands += 1;
        match cmd {
            NmtCommand::ResetNode => self.reset_node(now, out),
            NmtCommand::ResetCommunication => self.reset_communication(now, out),
            other => self.set_state(other.target(), now, out),
        }
        true
    }

    /// A state change of the running node (CiA 301 §7.3.2.2).
    fn set_state(&mut self, to: NmtState, now: Duration, out: &mut Vec<CanFrame>) {
        let from = self.nmt;
        if from == to {
            return;
        }
        self.nmt = to;
        if !to.allows(Service::Sdo) {
            self.sdo.reset();
        }
        if from == NmtState::Operational {
            for r in &mut self.rpdos {
                r.buffered = None;
                r.deadline = None;
            }
        }
        if to == NmtState::Operational {
            for t in &mut self.tpdos {
                t.start(now);
            }
        }
        self.event(NodeEvent::NmtStateChanged { from, to });
        if self.producer.send_now(now) {
            self.send_heartbeat(out);
        }
    }

    fn send_heartbeat(&mut self, out: &mut Vec<CanFrame>) {
        out.push(CanFrame::short(
            0x700 + u16::from(self.node_id),
            [self.nmt.code(), 0, 0, 0, 0, 0, 0, 0],
            1,
        ));
    }

    fn on_guarding(&mut self, now: Duration, out: &mut Vec<CanFrame>) -> bool {
        // With a heartbeat producer configured, heartbeat replaces guarding (CiA 301 §7.2.8.3.2).
        if self.producer.enabled() {
            return false;
        }
        let (reply, recovered) = self.guarding.on_rtr(self.nmt.code(), now);
        out.push(CanFrame::short(
            0x700 + u16::from(self.node_id),
            [reply, 0, 0, 0, 0, 0, 0, 0],
            1,
        ));
        if recovered {
            self.recovered(None, LossCause::LifeGuarding, now);
        }
        true
    }

    fn on_heartbeat(
        &mut self,
        node: u8,
        data: &[u8],
        now: Duration,
        _out: &mut Vec<CanFrame>,
    ) -> bool {
        let [state] = *data else {
            return false;
        };
        match self.consumers.on_heartbeat(node, state, now) {
            Some(ConsumerEvent::Recovered(n)) => self.recovered(Some(n), LossCause::Heartbeat, now),
            Some(ConsumerEvent::BootUp(n)) => self.event(NodeEvent::RemoteBootUp { node_id: n }),
            None => {}
        }
        true
    }

    fn on_sync(&mut self, data: &[u8], now: Duration, out: &mut Vec<CanFrame>) {
        let counter = match self.sync.on_frame(data) {
            Ok(c) => c,
            Err(_) => {
                self.counters.sync_length_errors += 1;
                self.raise(emcy::code::SYNC_LENGTH, register::COMMUNICATION, [0; 5]);
                return;
            }
        };
        self.counters.sync += 1;
        if self.nmt == NmtState::Operational {
            for k in 0..self.rpdos.len() {
                let buffered = self.rpdos.get_mut(k).and_then(|r| r.buffered.take());
                if let Some((data, len)) = buffered {
                    self.apply_rpdo(k, data.get(..len).unwrap_or_default());
                }
            }
        }
        self.event(NodeEvent::Sync { counter });
        if self.nmt == NmtState::Operational {
            let overflow = self.sync.overflow;
            for t in &mut self.tpdos {
                t.on_sync(counter, overflow, self.device.od(), now, out);
            }
        }
    }

    fn on_rpdo(&mut self, k: usize, data: &[u8], now: Duration) {
        let Some(r) = self.rpdos.get_mut(k) else {
            return;
        };
        let result = r.on_frame(data, now);
        self.clear(emcy::code::RPDO_TIMEOUT);
        let too_long = match result {
            Received::TooShort => {
                self.counters.rpdo_length_errors += 1;
                self.raise(emcy::code::PDO_LENGTH, register::COMMUNICATION, [0; 5]);
                return;
            }
            Received::Apply { too_long } | Received::Buffered { too_long } => too_long,
        };
        self.counters.rpdos += 1;
        if too_long {
            self.counters.rpdo_length_errors += 1;
            self.raise(
                emcy::code::PDO_LENGTH_EXCEEDED,
                register::COMMUNICATION,
                [0; 5],
            );
        } else {
            self.clear(emcy::code::PDO_LENGTH);
            self.clear(emcy::code::PDO_LENGTH_EXCEEDED);
        }
        if matches!(result, Received::Apply { .. }) {
            self.apply_rpdo(k, data);
        }
    }

    /// Write an RPDO's mapped objects as a master would (the device's rules apply).
    fn apply_rpdo(&mut self, k: usize, data: &[u8]) {
        let Some(r) = self.rpdos.get(k) else {
            return;
        };
        let (n, entries) = (r.n, r.map.entries.clone());
        let mut pos = 0;
        for e in entries {
            let bytes = data.get(pos..pos + e.len);
            pos += e.len;
            let (Some(bytes), Some(data_type), false) = (bytes, e.data_type, e.dummy) else {
                continue;
            };
            let written = Value::from_le_bytes(data_type, bytes)
                .ok()
                .map(|v| self.device.write(e.index, e.subindex, v));
            if !matches!(written, Some(Ok(()))) {
                self.counters.rpdo_write_errors += 1;
            }
        }
        self.event(NodeEvent::RpdoReceived { pdo: n });
    }

    fn on_lss(&mut self, data: &[u8], now: Duration, out: &mut Vec<CanFrame>) -> bool {
        self.counters.lss_requests += 1;
        let identity = self.identity();
        let (reply, effect) = self.lss.on_request(data, identity, self.node_id);
        if let Some(r) = reply {
            out.push(CanFrame::full(LSS_TX_ID, r));
        }
        match effect {
            // CiA 305: an unconfigured node takes its new id on leaving configuration.
            Some(LssEffect::BackToWaiting)
                if self.node_id == UNCONFIGURED && valid_node_id(self.lss.pending_id) =>
            {
                self.reset_communication(now, out);
            }
            Some(LssEffect::ActivateBitTiming {
                table_index,
                delay_ms,
            }) => self.event(NodeEvent::BitTimingActivated {
                table_index,
                delay_ms,
            }),
            Some(LssEffect::Store {
                node_id,
                bit_timing,
            }) => self.event(NodeEvent::LssStoreRequested {
                node_id,
                bit_timing,
            }),
            Some(LssEffect::BackToWaiting) | None => {}
        }
        true
    }

    /// 0x1018 from the dictionary.
    fn identity(&self) -> [u32; 4] {
        let od = self.device.od();
        [1, 2, 3, 4].map(|s| crate::device::get_u32(od, idx::IDENTITY, s).unwrap_or(0))
    }

    // ---- time ----

    /// Advance to `now`: heartbeat, consumer and guarding timeouts, SDO timeout,
    /// event-driven TPDOs, RPDO deadlines, queued EMCY. Returns the frames to send.
    pub fn on_tick(&mut self, now: Duration) -> Vec<CanFrame> {
        let mut out = Vec::new();
        self.on_tick_into(now, &mut out);
        out
    }

    pub fn on_tick_into(&mut self, now: Duration, out: &mut Vec<CanFrame>) {
        let before = out.len();
        self.now = now;
        if self.nmt != NmtState::Initialising {
            if self.producer.due(now) {
                self.send_heartbeat(out);
            }
            for node in self.consumers.expired(now) {
                self.lost(Some(node), LossCause::Heartbeat, now, out);
            }
            if self.guarding.expired(now) {
                self.lost(None, LossCause::LifeGuarding, now, out);
            }
            self.sdo.on_tick(now, out);
            if self.nmt == NmtState::Operational {
                for t in &mut self.tpdos {
                    t.on_tick(self.device.od(), now, out);
                }
                let expired = self.rpdos.iter_mut().any(|r| r.expired(now));
                if expired {
                    self.raise(emcy::code::RPDO_TIMEOUT, register::COMMUNICATION, [0; 5]);
                }
            }
        }
        self.emcy
            .flush(self.device.od(), now, self.nmt.allows(Service::Emcy), out);
        self.counters.frames_out += (out.len() - before) as u64;
    }

    /// The earliest time at which [`on_tick`](Self::on_tick) has something to do (besides
    /// noticing changed TPDO data, which the application's own tick covers).
    pub fn next_deadline(&self) -> Option<Duration> {
        let mut d = [
            self.producer.deadline(),
            self.consumers.deadline(),
            self.guarding.deadline(),
            self.sdo.deadline(),
            self.emcy.deadline(),
        ]
        .into_iter()
        .flatten()
        .min();
        if self.nmt == NmtState::Operational {
            let pdo = self
                .tpdos
                .iter()
                .filter_map(Tpdo::deadline)
                .chain(self.rpdos.iter().filter_map(|r| {
                    r.deadline
                        .map(|x| x.saturating_add(Duration::from_nanos(1)))
                }))
                .min();
            d = match (d, pdo) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            };
        }
        d
    }

    // ---- communication errors ----

    fn lost(
        &mut self,
        node_id: Option<u8>,
        cause: LossCause,
        now: Duration,
        out: &mut Vec<CanFrame>,
    ) {
        self.event(NodeEvent::MasterLost { node_id, cause });
        self.raise(emcy::code::HEARTBEAT, register::COMMUNICATION, [0; 5]);
        // The EMCY goes out before the reaction (which may be Stopped, where EMCY is silent).
        self.emcy
            .flush(self.device.od(), now, self.nmt.allows(Service::Emcy), out);
        let behaviour = get_u8(self.device.od(), idx::ERROR_BEHAVIOUR, 1)
            .and_then(ErrorBehaviour::from_code)
            .unwrap_or_default();
        match behaviour {
            ErrorBehaviour::PreOperational if self.nmt == NmtState::Operational => {
                self.set_state(NmtState::PreOperational, now, out)
            }
            ErrorBehaviour::Stopped => self.set_state(NmtState::Stopped, now, out),
            _ => {}
        }
    }

    fn recovered(&mut self, node_id: Option<u8>, cause: LossCause, _now: Duration) {
        self.event(NodeEvent::MasterRecovered { node_id, cause });
        if !self.consumers.any_lost() {
            self.clear(emcy::code::HEARTBEAT);
        }
    }

    // ---- application API ----

    fn raise(&mut self, code: u16, bits: u8, info: [u8; 5]) -> bool {
        self.emcy.raise(self.device.od_mut(), code, bits, info)
    }

    fn clear(&mut self, code: u16) -> bool {
        self.emcy.clear(self.device.od_mut(), code)
    }

    /// Raise an error (CiA 301 §7.2.7): 0x1001 gains `register_bits` (and bit 0), 0x1003 the
    /// code, and an EMCY goes out as the inhibit time (0x1015) and NMT state allow. An error
    /// already active is not sent again.
    pub fn raise_error(
        &mut self,
        code: u16,
        register_bits: u8,
        manufacturer: [u8; 5],
        now: Duration,
    ) -> Vec<CanFrame> {
        self.raise(code, register_bits, manufacturer);
        self.flush_emcy(now)
    }

    /// An error went away: 0x1001 updated and an "error reset" EMCY (code 0x0000) sent.
    pub fn clear_error(&mut self, code: u16, now: Duration) -> Vec<CanFrame> {
        self.clear(code);
        self.flush_emcy(now)
    }

    pub fn error_active(&self, code: u16) -> bool {
        self.emcy.is_active(code)
    }

    fn flush_emcy(&mut self, now: Duration) -> Vec<CanFrame> {
        let mut out = Vec::new();
        self.now = now;
        self.emcy.flush(
            self.device.od(),
            now,
            self.nmt.allows(Service::Emcy),
            &mut out,
        );
        self.counters.frames_out += out.len() as u64;
        out
    }

    /// Ask an event-driven or acyclic synchronous TPDO (0-based: 0x1800 + pdo) to go out
    /// (at the next tick or SYNC), whether or not its data changed.
    pub fn request_tpdo(&mut self, pdo: u16) {
        if let Some(t) = self.tpdos.iter_mut().find(|t| t.n == pdo) {
            t.request();
        }
    }

    /// The transport persisted (or failed to persist) the image of the last
    /// `StoreRequested`/`RestoreRequested`; the SDO confirmation (or abort 0x06060000) goes out.
    pub fn finish_persist(&mut self, saved: bool, now: Duration) -> Vec<CanFrame> {
        let mut out = Vec::new();
        self.now = now;
        let image = self.persisting.take();
        if saved {
            if image.is_some() {
                self.stored = image;
            }
            self.sdo.finish_deferred(Ok(()), &mut out);
        } else {
            self.sdo
                .finish_deferred(Err(crate::sdo::SdoAbort::HARDWARE), &mut out);
        }
        self.counters.frames_out += out.len() as u64;
        out
    }
}
