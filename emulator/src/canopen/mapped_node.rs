//! The map-backed CANopen nodes (the CT E10 of `fixtures/cpu226h.toml`): their dictionary is
//! a register map over the engine (`super::mapped`). Each node's frames are served by a task of
//! its own, because the map's writes await engine commands, which the servo thread must never
//! do; its timers (heartbeats, TPDO event timers, inhibit times) run inside the servo tick
//! (`MappedTicks`, a `Fieldbus`), like the CiA 402 nodes' (decisions.md, "CT E10 on CANopen").

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError, TryLockError};
use std::time::Duration;

use axes::runtime::{EngineHandle, Fieldbus};
use axes::status::Snapshot;
use axes::Engine;
use mcemu_can::{EndpointOptions, FrameReceiver, FrameSender, Hub, WireFrame};
use mcemu_canopen::{CanFrame, NmtState, Node, NodeEvent};
use mcemu_modbus::map::UnitService;
use tokio::sync::watch;

use super::mapped::{MapDevice, ServiceRegisters};
use super::wire::{from_wire, to_wire, Incoming};
use super::{image_file, CanopenStartError};
use crate::state_dir::StateDir;

/// What a map-backed node has done, for `GET /state`.
#[derive(Clone, Debug)]
pub(super) struct MappedStatus {
    pub(super) node_id: u8,
    pub(super) axis: usize,
    pub(super) nmt: mcemu_canopen::NmtState,
    pub(super) counters: mcemu_canopen::NodeCounters,
    pub(super) refresh_errors: u64,
    pub(super) rpdo_write_errors: u64,
    pub(super) parameter_errors: u64,
    pub(super) ticks_skipped: u64,
}

/// Frames a map-backed node's task takes per wake-up before it lets the servo tick in.
const MAPPED_FRAMES_PER_WAKE: usize = 256;

/// A map-backed node (the CT E10), shared by the task that takes its frames and the servo tick
/// that runs its timers.
struct MappedNode {
    node: Node<MapDevice<ServiceRegisters>>,
    axis: usize,
    sender: FrameSender,
    /// Bus time (the fieldbus `now`: engine time on the virtual clock) of the latest servo
    /// tick, which the task's frames are handled at too.
    now: Duration,
    /// Servo ticks that found the node busy with a frame (their timers ran at the next one).
    ticks_skipped: u64,
    out: Vec<CanFrame>,
}

impl MappedNode {
    /// Send what the node produced and publish its status (skipped when the control API holds
    /// the status; the next call publishes).
    fn flush(&mut self, status: &Mutex<Vec<MappedStatus>>, slot: usize) {
        self.send();
        self.publish(status, slot);
    }

    fn send(&mut self) {
        for frame in self.out.drain(..) {
            if let Some(wire) = to_wire(&frame) {
                // A full queue is counted by the hub (tx_overflow).
                let _ = self.sender.send(wire);
            }
        }
    }

    fn publish(&self, status: &Mutex<Vec<MappedStatus>>, slot: usize) {
        if let Ok(mut s) = status.try_lock() {
            if let Some(slot) = s.get_mut(slot) {
                let device = self.node.device();
                *slot = MappedStatus {
                    node_id: self.node.node_id(),
                    axis: self.axis,
                    nmt: self.node.nmt_state(),
                    counters: self.node.counters(),
                    refresh_errors: device.refresh_errors,
                    rpdo_write_errors: device.rpdo_write_errors,
                    parameter_errors: device.parameter_errors,
                    ticks_skipped: self.ticks_skipped,
                };
            }
        }
    }
}

fn lock_node(node: &Mutex<MappedNode>) -> MutexGuard<'_, MappedNode> {
    // A panic while handling a frame leaves at worst a half-written dictionary: keep serving.
    node.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The map-backed nodes' timers, run inside the servo tick like the CiA 402 nodes': heartbeats,
/// TPDO event timers, inhibit times and changed TPDO data at the tick they fall on, with that
/// tick's values, however long an advance of the virtual clock is (decisions.md, "CT E10 on
/// CANopen"). Only reads: the map's writes await the engine and stay in the task.
pub(super) struct MappedTicks {
    nodes: Vec<TickedNode>,
    status: Arc<Mutex<Vec<MappedStatus>>>,
    /// The engine of this tick, for the map's reads (the published snapshot is the tick before).
    sample: Snapshot,
}

/// A node as the servo tick sees it.
struct TickedNode {
    shared: Arc<Mutex<MappedNode>>,
    /// Its slot in the status list.
    slot: usize,
    /// Ticks that found it busy.
    skipped: u64,
    clock: Arc<BusClock>,
}

impl MappedTicks {
    pub(super) fn new(status: Arc<Mutex<Vec<MappedStatus>>>) -> MappedTicks {
        MappedTicks {
            nodes: Vec::new(),
            status,
            sample: Snapshot::default(),
        }
    }

    pub(super) fn add(&mut self, task: &MappedNodeTask) {
        self.nodes.push(TickedNode {
            shared: Arc::clone(&task.shared),
            slot: task.slot,
            skipped: 0,
            clock: Arc::clone(&task.bus_clock),
        });
    }
}

impl Fieldbus for MappedTicks {
    fn before_step(&mut self, _engine: &mut Engine, _now: Duration) {}

    fn after_step(&mut self, engine: &mut Engine, now: Duration) {
        let mut sampled = false;
        for TickedNode {
            shared,
            slot,
            skipped,
            clock,
        } in &mut self.nodes
        {
            // Before the lock, which may be busy: the task's next frame is handled at this
            // tick's time even when this tick's timers have to wait for the next one.
            clock.advance(now);
            // Never wait: the task holds the node while a write awaits the engine, which may be
            // this very thread. Its timers then run at the next tick (on the virtual clock, a
            // frame that arrives during an advance; its timing was a race anyway).
            let mut n = match shared.try_lock() {
                Ok(n) => n,
                Err(TryLockError::Poisoned(p)) => p.into_inner(),
                Err(TryLockError::WouldBlock) => {
                    *skipped += 1;
                    continue;
                }
            };
            n.ticks_skipped = *skipped;
            n.now = n.now.max(now);
            let now = n.now;
            if n.node.nmt_state() == NmtState::Operational {
                // Event-driven TPDOs compare their data every tick: this tick's values.
                if !sampled {
                    engine.snapshot_into(&mut self.sample);
                    sampled = true;
                }
                n.node.device_mut().refresh_in(&self.sample);
            } else if n.node.next_deadline().is_none_or(|d| d > now) {
                // Nothing due; the boot-up message may still be waiting for its first service.
                if !n.out.is_empty() {
                    n.flush(&self.status, *slot);
                }
                continue;
            }
            let MappedNode { node, out, .. } = &mut *n;
            node.on_tick_into(now, out);
            // Stores, restores and resets come from frames, which the task handles; what a tick
            // raises (a lost master's state change) needs nothing more here.
            while node.poll_event().is_some() {}
            n.flush(&self.status, *slot);
        }
    }
}

/// A map-backed node's frames, served by a task of its own: its writes go through the register
/// map, which awaits engine commands — something the servo thread, where the CiA 402 nodes run,
/// must never do (decisions.md, "CT E10 on CANopen").
pub(super) struct MappedNodeTask {
    shared: Arc<Mutex<MappedNode>>,
    receiver: FrameReceiver,
    handle: EngineHandle,
    state_dir: Option<StateDir>,
    status: Arc<Mutex<Vec<MappedStatus>>>,
    slot: usize,
    /// The snapshot the objects were last refreshed from.
    refreshed: Option<Arc<Snapshot>>,
    /// Bus time of the latest servo tick, written by every tick whether or not it got the node.
    bus_clock: Arc<BusClock>,
}

/// The latest servo tick's bus time, for the node's task. The node's own `now` moves only when
/// a tick gets the node's lock; a task preempted while holding it (a loaded machine) would
/// otherwise handle its next frames at a stale time, e.g. before an inhibit time that has in
/// fact passed, and hold back the TPDOs an NMT start owes.
#[derive(Debug, Default)]
struct BusClock(AtomicU64);

impl BusClock {
    fn advance(&self, now: Duration) {
        let nanos = u64::try_from(now.as_nanos()).unwrap_or(u64::MAX);
        self.0.fetch_max(nanos, Ordering::Relaxed);
    }

    /// `now` moved up to the latest tick's time.
    fn catch_up(&self, now: Duration) -> Duration {
        now.max(Duration::from_nanos(self.0.load(Ordering::Relaxed)))
    }
}

impl MappedNodeTask {
    pub(super) fn new(
        spec: super::MappedNodeSpec,
        hub: &Hub,
        handle: EngineHandle,
        state_dir: Option<StateDir>,
        status: Arc<Mutex<Vec<MappedStatus>>>,
    ) -> Result<MappedNodeTask, CanopenStartError> {
        let node_id = spec.config.node_id;
        let service = Arc::new(UnitService::new(spec.map, handle.clone()));
        let mut device = MapDevice::new(spec.od, ServiceRegisters(service), spec.backed);
        // The map's values now (or a DCF's), before any stored image, are the parameters'
        // defaults and power-on values.
        device.refresh();
        device.adopt_power_on_defaults(&spec.configured);
        let mut node = Node::new(spec.config, device)
            .map_err(|source| CanopenStartError::Node { node_id, source })?;
        node.set_stored_image(spec.stored_image);
        let slot = {
            let mut s = status.lock().unwrap_or_else(PoisonError::into_inner);
            s.push(MappedStatus {
                node_id,
                axis: spec.axis,
                nmt: node.nmt_state(),
                counters: node.counters(),
                refresh_errors: 0,
                rpdo_write_errors: 0,
                parameter_errors: 0,
                ticks_skipped: 0,
            });
            s.len() - 1
        };
        let (sender, receiver) = hub
            .attach(EndpointOptions::new(format!("e10 node {node_id}")))
            .split();
        Ok(MappedNodeTask {
            shared: Arc::new(Mutex::new(MappedNode {
                node,
                axis: spec.axis,
                sender,
                now: Duration::ZERO,
                ticks_skipped: 0,
                out: Vec::new(),
            })),
            receiver,
            handle,
            state_dir,
            status,
            slot,
            refreshed: None,
            bus_clock: Arc::new(BusClock::default()),
        })
    }

    /// The objects from the map, when the engine published something new since the last time.
    fn refresh(&mut self, n: &mut MappedNode) {
        let snapshot = self.handle.snapshot();
        if self
            .refreshed
            .as_ref()
            .is_some_and(|r| Arc::ptr_eq(r, &snapshot))
        {
            return;
        }
        n.node.device_mut().refresh();
        self.refreshed = Some(snapshot);
    }

    /// Power on (CiA 301 §7.3.2.2.1): the stored image over the defaults, the stored parameters'
    /// values into the map — the drive loads its saved parameters — then the boot-up message,
    /// which goes out at the node's first service (the next servo tick, or the first frame), as
    /// the CiA 402 nodes' does: on the virtual clock the first advance or the first frame of a
    /// master (decisions.md, "Power-on on the virtual clock").
    fn power_on(&mut self) {
        let shared = Arc::clone(&self.shared);
        let mut n = lock_node(&shared);
        n.now = self.bus_clock.catch_up(n.now);
        let now = n.now;
        let frames = n.node.start(now);
        n.node.device_mut().load_parameters();
        n.out.extend(frames);
        self.refreshed = None;
        n.publish(&self.status, self.slot);
    }

    /// A batch of frames, in arrival order, each followed by the node's timers at the same time
    /// (a frame may have changed TPDO data or started the node: on the virtual clock, where time
    /// stands still, an event-driven TPDO goes out at once). Ticking after each frame keeps what
    /// goes out in the order of its causes however the frames were batched: an NMT start's
    /// TPDOs precede the answer to an SDO request that followed the start.
    fn on_frames(&mut self, frames: &[WireFrame]) {
        let shared = Arc::clone(&self.shared);
        let mut n = lock_node(&shared);
        n.now = self.bus_clock.catch_up(n.now);
        let now = n.now;
        for frame in frames {
            match from_wire(frame) {
                Incoming::Frame(f) => {
                    self.refresh(&mut n);
                    let rpdo = n.node.device().is_rpdo(f.id());
                    if rpdo {
                        n.node.device_mut().begin_rpdo();
                    }
                    let MappedNode { node, out, .. } = &mut *n;
                    node.on_frame_into(&f, now, out);
                    if rpdo {
                        n.node.device_mut().finish_rpdo();
                    }
                    // A write may have issued commands: the next call reads the map again.
                    self.refreshed = None;
                    self.handle_events(&mut n, now);
                    self.refresh(&mut n);
                    let MappedNode { node, out, .. } = &mut *n;
                    node.on_tick_into(now, out);
                    self.handle_events(&mut n, now);
                }
                Incoming::Error => n.node.note_error_frame(),
                Incoming::Other => {}
            }
        }
        n.flush(&self.status, self.slot);
    }

    /// Stores go to the state directory (a small atomic write, done here); NMT reset node loads
    /// the stored parameters' power-on values into the map; a lost master has no reaction
    /// beyond the node's own (0x1029): the E10 model has no 0x6007.
    fn handle_events(&mut self, n: &mut MappedNode, now: Duration) {
        while let Some(event) = n.node.poll_event() {
            match event {
                NodeEvent::StoreRequested { image, .. }
                | NodeEvent::RestoreRequested { image, .. } => {
                    let id = n.node.node_id();
                    let saved = match &self.state_dir {
                        Some(d) => d.write(&image_file(id), &image).map_err(|e| {
                            tracing::error!(node_id = id, error = %e, "cannot store the parameter image");
                        }),
                        None => Err(()),
                    };
                    let frames = n.node.finish_persist(saved.is_ok(), now);
                    n.out.extend(frames);
                }
                NodeEvent::ResetNode => {
                    n.node.device_mut().load_reset_values();
                    self.refreshed = None;
                }
                _ => {}
            }
        }
    }

    pub(super) async fn run(
        mut self,
        mut shutdown: watch::Receiver<bool>,
        powered: tokio::sync::oneshot::Sender<()>,
    ) {
        self.power_on();
        let _ = powered.send(());
        let mut batch = Vec::with_capacity(MAPPED_FRAMES_PER_WAKE);
        loop {
            tokio::select! {
                d = self.receiver.recv() => {
                    let Some(d) = d else { break };
                    batch.clear();
                    batch.push(d.frame);
                    while batch.len() < MAPPED_FRAMES_PER_WAKE {
                        let Some(d) = self.receiver.try_recv() else { break };
                        batch.push(d.frame);
                    }
                    self.on_frames(&batch);
                }
                _ = shutdown.wait_for(|s| *s) => break,
            }
        }
    }
}
