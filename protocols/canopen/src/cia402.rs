//! The CiA 402 binding: each CANopen-served drive of the engine is one node on the bus, served
//! inside the servo tick (ARCHITECTURE §3.8, §5).
//!
//! [`CanopenFieldbus`] is an [`axes::runtime::Fieldbus`]: before every step it feeds the frames
//! that arrived to the nodes (NMT, SDO, RPDO, SYNC — so a controlword or a CSP set-point
//! written by a master is what that step sees); after it, the nodes send what the step produced
//! (TPDOs on SYNC, heartbeats, EMCY for the drive's faults). The drive and its dictionary stay
//! the engine's, so the control API, the trace and every other dialect see the same objects.
//!
//! The node ([`Node`]) owns the device it serves; the engine owns the drive. Around each call
//! the binding swaps the engine's drive into the node and back ([`DriveNode::with_drive`]):
//! two moves of a struct, no copy of the dictionary, and no second source of truth.

use std::time::Duration;

use axes::cia402::Cia402Drive;
use axes::od::{EntryDef, ObjectDictionary, OdError, Value};
use axes::runtime::Fieldbus;
use axes::Engine;

use crate::device::Device;
use crate::events::NodeEvent;
use crate::frame::CanFrame;
use crate::node::{Node, NodeCounters, NodeError};
use crate::objects::NodeConfig;

impl Device for Cia402Drive {
    fn od(&self) -> &ObjectDictionary {
        Cia402Drive::od(self)
    }

    fn od_mut(&mut self) -> &mut ObjectDictionary {
        Cia402Drive::od_mut(self)
    }

    /// A master's write goes through the drive's own rules (supported modes, homing methods).
    fn write(&mut self, index: u16, subindex: u8, value: Value) -> Result<(), OdError> {
        Cia402Drive::write(self, index, subindex, value)
    }
}

/// Where a fieldbus's frames come from and go to (a CAN hub endpoint, a test queue). Both
/// calls run on the servo thread: they must not block.
pub trait FramePort: Send {
    /// The next received frame, if one is waiting.
    fn try_recv(&mut self) -> Option<CanFrame>;
    /// Send a frame; a full queue drops it (counted by the port).
    fn send(&mut self, frame: CanFrame);
    /// A CAN error frame was received since the last call (counted by the nodes).
    fn take_error_frames(&mut self) -> u64 {
        0
    }
    /// Bus time is now `now` (a port whose bus keeps virtual time moves it on).
    fn set_time(&mut self, _now: Duration) {}
}

/// Where stored parameter images go (0x1010 "save"). Runs on the servo thread, so it only hands
/// the image over; the disk write happens elsewhere and its result comes back through
/// [`Persister::poll_done`].
pub trait Persister: Send {
    /// Save `image` for the node with `node_id` (the whole new image).
    fn save(&mut self, node_id: u8, image: Vec<u8>);
    /// A save that finished: (node id, saved).
    fn poll_done(&mut self) -> Option<(u8, bool)>;
}

/// One node to serve: which drive (slave number) and how.
#[derive(Clone, Debug)]
pub struct DriveNodeSpec {
    pub slave: usize,
    pub config: NodeConfig,
    /// Objects of the node's EDS; those the drive's dictionary lacks are added to it (PDO
    /// parameters with the EDS's default mappings, store/restore, manufacturer objects). The
    /// drive's own objects keep the drive's definitions.
    pub objects: Vec<EntryDef>,
    /// The stored parameter image from an earlier run, if any.
    pub stored_image: Option<Vec<u8>>,
}

/// A node serving one engine drive.
pub struct DriveNode {
    slave: usize,
    /// Holds a stand-in drive between calls; the engine's drive during them.
    node: Node<Cia402Drive>,
    /// The 0x603F code of the fault the drive reported last (for the EMCY that clears it).
    active_fault: Option<u16>,
}

impl DriveNode {
    /// Build the node on the engine's drive `spec.slave`: the communication objects the drive's
    /// dictionary lacks are added to it (it keeps them for the run).
    fn new(engine: &mut Engine, spec: DriveNodeSpec) -> Result<DriveNode, BindError> {
        let slave = spec.slave;
        let drive = engine
            .drive_mut(slave)
            .ok_or(BindError::NoSuchDrive(slave))?;
        // The stand-in the engine holds while the node is built; it never runs a step.
        for def in spec.objects {
            if drive.od().entry(def.index, def.subindex).is_err() {
                drive.od_mut().insert(def).map_err(BindError::Object)?;
            }
        }
        let stand_in = drive.clone();
        let real = std::mem::replace(drive, stand_in);
        let mut node = Node::new(spec.config, real).map_err(BindError::Node)?;
        node.set_stored_image(spec.stored_image);
        let mut bound = DriveNode {
            slave,
            node,
            active_fault: None,
        };
        // The engine gets its (now augmented) drive back; the node keeps the stand-in.
        bound.swap(engine);
        Ok(bound)
    }

    fn swap(&mut self, engine: &mut Engine) {
        if let Some(drive) = engine.drive_mut(self.slave) {
            std::mem::swap(drive, self.node.device_mut());
        }
    }

    /// Run `f` on the node while it holds the engine's drive.
    pub fn with_drive<R>(
        &mut self,
        engine: &mut Engine,
        f: impl FnOnce(&mut Node<Cia402Drive>) -> R,
    ) -> R {
        self.swap(engine);
        let r = f(&mut self.node);
        self.swap(engine);
        r
    }

    pub fn node_id(&self) -> u8 {
        self.node.node_id()
    }

    pub fn slave(&self) -> usize {
        self.slave
    }
}

/// Why the binding cannot start.
#[derive(Debug, thiserror::Error)]
pub enum BindError {
    #[error("drive {0} does not exist")]
    NoSuchDrive(usize),
    #[error(transparent)]
    Node(NodeError),
    #[error("cannot add an EDS object to the drive's dictionary: {0}")]
    Object(axes::od::DefinitionError),
}

/// What the binding has done, for `GET /state`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NodeStatus {
    pub node_id: u8,
    pub slave: usize,
    pub nmt: crate::nmt::NmtState,
    pub counters: NodeCounters,
}

/// Frames handled per tick at most; more wait for the next tick (a flood must not stretch a
/// tick without bound). 1 Mbit/s carries about 8 000 frames/s, 8 per millisecond.
pub const MAX_FRAMES_PER_TICK: usize = 256;

/// The CANopen nodes of the engine's drives on one bus.
pub struct CanopenFieldbus<P: FramePort> {
    port: P,
    specs: Vec<DriveNodeSpec>,
    nodes: Vec<DriveNode>,
    persister: Option<Box<dyn Persister>>,
    /// Frames received this call, handed to each node in one go (one drive swap per node).
    inbox: Vec<CanFrame>,
    out: Vec<CanFrame>,
    started: bool,
    /// Published for readers off the servo thread.
    status: std::sync::Arc<std::sync::Mutex<Vec<NodeStatus>>>,
    /// Build failures (a spec naming a drive the machine lacks), reported once.
    pub errors: Vec<String>,
}

impl<P: FramePort> CanopenFieldbus<P> {
    pub fn new(port: P, specs: Vec<DriveNodeSpec>) -> CanopenFieldbus<P> {
        CanopenFieldbus {
            port,
            specs,
            nodes: Vec::new(),
            persister: None,
            inbox: Vec::new(),
            out: Vec::new(),
            started: false,
            status: Default::default(),
            errors: Vec::new(),
        }
    }

    pub fn with_persister(mut self, persister: Box<dyn Persister>) -> CanopenFieldbus<P> {
        self.persister = Some(persister);
        self
    }

    /// The nodes' status as of the last tick, shared with readers on other threads.
    pub fn status(&self) -> std::sync::Arc<std::sync::Mutex<Vec<NodeStatus>>> {
        std::sync::Arc::clone(&self.status)
    }

    fn start(&mut self, engine: &mut Engine, now: Duration) {
        self.started = true;
        for spec in std::mem::take(&mut self.specs) {
            let slave = spec.slave;
            match DriveNode::new(engine, spec) {
                Ok(node) => self.nodes.push(node),
                Err(e) => self.errors.push(format!("drive {slave}: {e}")),
            }
        }
        for n in &mut self.nodes {
            let frames = n.with_drive(engine, |node| node.start(now));
            self.out.extend(frames);
        }
        self.flush();
    }

    fn flush(&mut self) {
        for frame in self.out.drain(..) {
            self.port.send(frame);
        }
    }

    /// React to what the node reported: a lost master reaches the drive (0x6007), a store goes
    /// to the persister.
    fn handle_events(
        node: &mut Node<Cia402Drive>,
        persister: &mut Option<Box<dyn Persister>>,
        now: Duration,
        out: &mut Vec<CanFrame>,
    ) {
        while let Some(event) = node.poll_event() {
            match event {
                NodeEvent::MasterLost { .. } => node.device_mut().connection_lost(),
                NodeEvent::StoreRequested { image, .. }
                | NodeEvent::RestoreRequested { image, .. } => {
                    match persister {
                        Some(p) => p.save(node.node_id(), image),
                        // Nowhere to keep it: the store fails (0x06060000 to the master).
                        None => out.extend(node.finish_persist(false, now)),
                    }
                }
                _ => {}
            }
        }
    }

    /// The drive's faults as EMCY: entering one raises its 0x603F code, leaving it clears it.
    fn forward_emergencies(n: &mut DriveNode, now: Duration, out: &mut Vec<CanFrame>) {
        let emergencies = n.node.device_mut().take_emergencies();
        for e in emergencies {
            if e.code != 0 {
                n.active_fault = Some(e.code);
                // Error register bit 0 (generic) is set by the node; the drive's register adds
                // its own bits (current, voltage, …).
                out.extend(n.node.raise_error(e.code, e.register, [0; 5], now));
            } else if let Some(code) = n.active_fault.take() {
                out.extend(n.node.clear_error(code, now));
            }
        }
    }

    /// Every tick: refills the shared list in place (no allocation once it has its size), and
    /// skips the tick when a reader holds it.
    fn publish_status(&self) {
        if let Ok(mut s) = self.status.try_lock() {
            s.clear();
            s.extend(self.nodes.iter().map(|n| NodeStatus {
                node_id: n.node.node_id(),
                slave: n.slave,
                nmt: n.node.nmt_state(),
                counters: n.node.counters(),
            }));
        }
    }
}

impl<P: FramePort> Fieldbus for CanopenFieldbus<P> {
    fn before_step(&mut self, engine: &mut Engine, now: Duration) {
        self.port.set_time(now);
        if !self.started {
            self.start(engine, now);
        }
        let error_frames = self.port.take_error_frames();
        if error_frames > 0 {
            for n in &mut self.nodes {
                for _ in 0..error_frames.min(1000) {
                    n.node.note_error_frame();
                }
            }
        }
        if let Some(p) = self.persister.as_mut() {
            while let Some((id, saved)) = p.poll_done() {
                if let Some(n) = self.nodes.iter_mut().find(|n| n.node_id() == id) {
                    let frames = n.with_drive(engine, |node| node.finish_persist(saved, now));
                    self.out.extend(frames);
                }
            }
        }
        self.inbox.clear();
        while self.inbox.len() < MAX_FRAMES_PER_TICK {
            let Some(frame) = self.port.try_recv() else {
                break;
            };
            self.inbox.push(frame);
        }
        // Each node gets the frames it takes, in bus order, with its drive swapped in once
        // (32 nodes under a 1 kHz SYNC see ~33 frames a tick, each meant for one or all).
        let (inbox, out, persister) = (&self.inbox, &mut self.out, &mut self.persister);
        for n in &mut self.nodes {
            if !inbox.iter().any(|f| n.node.accepts(f)) {
                for _ in inbox {
                    n.node.note_ignored();
                }
                continue;
            }
            n.with_drive(engine, |node| {
                for frame in inbox {
                    // Acceptance can change with the frames before (an NMT start, an SDO
                    // write to a PDO's COB-ID), so it is asked again in order.
                    if node.accepts(frame) {
                        node.on_frame_into(frame, now, out);
                        Self::handle_events(node, persister, now, out);
                    } else {
                        node.note_ignored();
                    }
                }
            });
        }
        self.flush();
    }

    fn after_step(&mut self, engine: &mut Engine, now: Duration) {
        self.port.set_time(now);
        let (out, persister) = (&mut self.out, &mut self.persister);
        for n in &mut self.nodes {
            n.swap(engine);
            Self::forward_emergencies(n, now, out);
            n.node.on_tick_into(now, out);
            Self::handle_events(&mut n.node, persister, now, out);
            n.swap(engine);
        }
        self.flush();
        self.publish_status();
    }
}
