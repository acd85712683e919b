//! `mcemu run`'s CANopen front-end: the bus (a `mcemu_can::Hub`), the drives' nodes on it as a
//! fieldbus inside the servo tick, the map-backed nodes (CT E10) as tasks of their own for frames
//! with their timers in the servo tick, the SocketCAN bridge and the socketcand server, the
//! candump log, and stored parameter images (0x1010) in the machine's state directory.

use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};

use axes::runtime::ClockMode;
use mcemu_can::socketcan::{SocketCanBridge, SocketCanConfig};
use mcemu_can::socketcand::{SocketcandConfig, SocketcandServer};
use mcemu_can::{BitTiming, Endpoint, EndpointOptions, Hub, HubConfig, WireFrame};
use mcemu_canopen::cia402::{CanopenFieldbus, FramePort, NodeStatus, Persister};
use std::future::Future;
use std::pin::Pin;
use std::time::Duration;

use axes::runtime::{CallError, EngineHandle};
use axes::status::Snapshot;
use mcemu_canopen::{CanFrame, Node, NodeEvent};
use mcemu_modbus::map::UnitService;
use serde_json::{json, Map, Value};
use tokio::sync::watch;
use tokio::task::JoinSet;

use super::buslog::BusLog;
use super::mapped::{MapDevice, ServiceRegisters};
use crate::state_dir::StateDir;

use crate::config::ConfigError;
use crate::control::error::ApiError;
use crate::frontend::CanLog;
use crate::frontend::{announce, FrontendError};
use crate::frontend::{handles, Frontend, FrontendContext, StartFuture};

/// The running CAN bus, for the control API.
pub struct CanopenFrontend {
    hub: Hub,
    nodes: Arc<Mutex<Vec<NodeStatus>>>,
    mapped: Arc<Mutex<Vec<MappedStatus>>>,
    socketcan: Mutex<Option<SocketCanBridge>>,
    socketcand: Mutex<Option<SocketcandServer>>,
    log: BusLog,
}

/// Why the CAN bus could not start (besides its config and its transports' own errors).
#[derive(Debug, thiserror::Error)]
pub enum CanopenStartError {
    #[error("cannot start the parameter image writer: {0}")]
    StoreThread(#[source] std::io::Error),
    #[error("cannot install the nodes in the servo loop: {0}")]
    Fieldbus(#[from] CallError),
    #[error("node {node_id}: {source}")]
    Node {
        node_id: u8,
        source: mcemu_canopen::NodeError,
    },
}

impl Frontend for CanopenFrontend {
    fn name(&self) -> &str {
        "canopen"
    }

    fn inject(&self, _fault: Map<String, Value>) -> Result<Value, ApiError> {
        Err(ApiError::InvalidRequest(
            "the CANopen front-end takes no faults of its own; a drive fault is an axis input \
             (`{\"axis\": N, \"input\": \"drive_alarm\"}` on /faults), which the node sends as EMCY"
                .into(),
        ))
    }

    fn state(&self) -> Value {
        let c = self.hub.counters();
        let nodes = render_under_lock(&self.nodes, |n| {
            let mut v = node_json(n.node_id, n.nmt, &n.counters);
            v.insert("drive".into(), json!(n.slave));
            v
        });
        let mapped = render_under_lock(&self.mapped, |n| {
            let mut v = node_json(n.node_id, n.nmt, &n.counters);
            v.insert("axis".into(), json!(n.axis));
            v.insert("refresh_errors".into(), json!(n.refresh_errors));
            v.insert("rpdo_write_errors".into(), json!(n.rpdo_write_errors));
            v.insert("parameter_errors".into(), json!(n.parameter_errors));
            v.insert("ticks_skipped".into(), json!(n.ticks_skipped));
            v
        });
        let link = self
            .socketcan
            .lock()
            .ok()
            .and_then(|b| b.as_ref().map(|b| format!("{:?}", b.state())));
        json!({
            "name": "canopen",
            "bus": self.hub.name(),
            "socketcan": link,
            "frames": c.frames,
            "data_bytes": c.data_bytes,
            "error_frames": c.error_frames,
            "rx_dropped": c.rx_dropped,
            "tx_overflow": c.tx_overflow,
            "load_percent": c.load_percent(),
            "nodes": nodes,
            "mapped_nodes": mapped,
            "log": self.log.status(),
            "log_dropped": c.log_dropped,
        })
    }

    /// Close the transports.
    fn shutdown(&self) -> Pin<Box<dyn Future<Output = ()> + '_>> {
        Box::pin(async {
            let bridge = self.socketcan.lock().ok().and_then(|mut b| b.take());
            if let Some(b) = bridge {
                b.stop().await;
            }
            let server = self.socketcand.lock().ok().and_then(|mut s| s.take());
            if let Some(s) = server {
                s.shutdown().await;
            }
            let _ = self.hub.stop_log();
        })
    }

    fn can_log(&self) -> Option<Arc<dyn CanLog>> {
        Some(Arc::new(self.log.clone()))
    }
}

/// A published status list as JSON, rendered under its lock rather than cloned first: the
/// servo thread's `try_lock` skips one publication at worst.
fn render_under_lock<T>(
    list: &Mutex<Vec<T>>,
    render: impl Fn(&T) -> Map<String, Value>,
) -> Vec<Value> {
    list.lock()
        .map(|list| list.iter().map(|n| Value::Object(render(n))).collect())
        .unwrap_or_default()
}

/// What `/state` shows of any node: id, NMT state and counters.
fn node_json(
    node_id: u8,
    nmt: mcemu_canopen::NmtState,
    counters: &mcemu_canopen::NodeCounters,
) -> Map<String, Value> {
    let mut v = Map::new();
    v.insert("node_id".into(), json!(node_id));
    v.insert("nmt".into(), json!(nmt));
    v.insert("counters".into(), json!(counters));
    v
}

/// A hub frame as a CANopen node sees it.
enum Incoming {
    Frame(CanFrame),
    /// A CAN error frame (counted by the nodes).
    Error,
    /// Not CANopen traffic (29-bit identifiers) or not a frame the node can hold.
    Other,
}

fn from_wire(f: &WireFrame) -> Incoming {
    if f.is_error() {
        return Incoming::Error;
    }
    // CiA 301 uses base frames only; a 29-bit frame is someone else's traffic.
    if f.is_extended() {
        return Incoming::Other;
    }
    let id = f.id().raw() as u16;
    let frame = if f.is_remote() {
        CanFrame::remote(id, f.dlc())
    } else {
        CanFrame::new(id, f.data())
    };
    frame.map_or(Incoming::Other, Incoming::Frame)
}

/// A node's frame as the hub carries it (`None`: not a frame a CAN bus can carry).
fn to_wire(frame: &CanFrame) -> Option<WireFrame> {
    let wire = if frame.is_rtr() {
        mcemu_can::CanId::standard(frame.id())
            .and_then(|id| WireFrame::remote(id, frame.len() as u8))
    } else {
        WireFrame::standard(frame.id(), frame.data())
    };
    wire.ok()
}

fn send_to(endpoint: &Endpoint, frame: &CanFrame) {
    if let Some(wire) = to_wire(frame) {
        // A full queue is counted by the hub (tx_overflow).
        let _ = endpoint.send(wire);
    }
}

/// The nodes' side of the hub, as the binding sees it.
struct HubPort {
    endpoint: Endpoint,
    error_frames: u64,
}

impl HubPort {
    /// The nodes' endpoint: each frame queued for it pokes the servo thread, which serves it
    /// between ticks (an SDO answered as it arrives, a TPDO right after its SYNC).
    fn attach(hub: &Hub, handle: &EngineHandle) -> HubPort {
        let engine = handle.clone();
        let options = EndpointOptions::new("canopen nodes").on_delivery(move || engine.poke());
        HubPort {
            endpoint: hub.attach(options),
            error_frames: 0,
        }
    }
}

impl FramePort for HubPort {
    fn try_recv(&mut self) -> Option<CanFrame> {
        while let Some(delivery) = self.endpoint.try_recv() {
            match from_wire(&delivery.frame) {
                Incoming::Frame(frame) => return Some(frame),
                Incoming::Error => self.error_frames += 1,
                Incoming::Other => {}
            }
        }
        None
    }

    fn send(&mut self, frame: CanFrame) {
        send_to(&self.endpoint, &frame);
    }

    fn take_error_frames(&mut self) -> u64 {
        std::mem::take(&mut self.error_frames)
    }

    /// On the virtual clock the bus keeps engine time, so candump and socketcand stamps (and
    /// the bit-rate model) are reproducible.
    fn set_time(&mut self, now: Duration) {
        let hub = self.endpoint.hub();
        if hub.clock() == mcemu_can::Clock::Virtual {
            hub.advance(now);
        }
    }
}

/// Stored parameter images: handed from the servo thread to a task that writes them.
struct ImagePersister {
    to_writer: Sender<(u8, Vec<u8>)>,
    done: Receiver<(u8, bool)>,
}

impl Persister for ImagePersister {
    fn save(&mut self, node_id: u8, image: Vec<u8>) {
        let _ = self.to_writer.send((node_id, image));
    }

    fn poll_done(&mut self) -> Option<(u8, bool)> {
        self.done.try_recv().ok()
    }
}

fn image_file(node_id: u8) -> String {
    format!("canopen/node-{node_id}.img")
}

/// Start the bus if `[frontends.canopen]` is enabled: nodes installed as a fieldbus, then the
/// transports, each announced.
pub fn start<'a>(cx: &'a FrontendContext<'a>, tasks: &'a mut JoinSet<()>) -> StartFuture<'a> {
    Box::pin(async move { Ok(handles(start_bus(cx, tasks).await?)) })
}

async fn start_bus(
    cx: &FrontendContext<'_>,
    tasks: &mut JoinSet<()>,
) -> Result<Option<Arc<CanopenFrontend>>, FrontendError> {
    let Some(c) = cx.config.frontends.canopen.as_ref().filter(|c| c.enabled) else {
        return Ok(None);
    };
    let fail = |e| FrontendError::new("canopen", e);
    let socketcand = cx
        .config
        .frontends
        .socketcand
        .as_ref()
        .filter(|s| s.enabled);
    let super::NodeSpecs {
        drives: mut specs,
        mapped: mut mapped_specs,
    } = super::node_specs(cx.config, cx.file).map_err(fail)?;
    let bus_name = if c.interface.is_empty() {
        "vcan0".to_string()
    } else {
        c.interface.clone()
    };
    let mut hub_config = HubConfig::new(bus_name.clone());
    if cx.handle.clock() == ClockMode::Virtual {
        hub_config = hub_config.with_clock(mcemu_can::Clock::Virtual);
    }
    if let Some(timing) = BitTiming::new(c.bitrate).filter(|_| c.bitrate > 0) {
        hub_config = hub_config.with_timing(timing);
    }
    let hub = Hub::new(hub_config);
    if c.bitrate > 0 {
        let h = hub.clone();
        tasks.spawn(async move { h.drive_realtime().await });
    }
    let log = BusLog::new(hub.clone(), mcemu_frontend::artefact::config_dir(cx.file));
    if !c.log.is_empty() {
        log.start_from_config(&c.log)
            .map_err(|e| ConfigError {
                file: cx.file.to_string(),
                key: "frontends.canopen.log".into(),
                reason: format!("cannot write it: {e}"),
            })
            .map_err(fail)?;
    }

    // Stored images from earlier runs; saves go to a writer task.
    if let Some(dir) = cx.state_dir {
        for spec in &mut specs {
            spec.stored_image = dir.read(&image_file(spec.config.node_id)).ok().flatten();
        }
        for spec in &mut mapped_specs {
            spec.stored_image = dir.read(&image_file(spec.config.node_id)).ok().flatten();
        }
    }
    let (to_writer, from_fieldbus) = mpsc::channel::<(u8, Vec<u8>)>();
    let (done_tx, done) = mpsc::channel();
    let dir = cx.state_dir.cloned();
    // On the virtual clock nothing serves the nodes until a frame or an advance comes: the
    // writer pokes the servo thread, so the master gets its 0x1010/0x1011 confirmation at once.
    let poker = cx.handle.clone();
    std::thread::Builder::new()
        .name("mcemu-canopen-store".into())
        .spawn(move || {
            for (node_id, image) in from_fieldbus {
                let saved = match &dir {
                    Some(d) => d.write(&image_file(node_id), &image).map_err(|e| {
                        tracing::error!(node_id, error = %e, "cannot store the parameter image");
                    }),
                    None => Err(()),
                };
                if done_tx.send((node_id, saved.is_ok())).is_err() {
                    break;
                }
                poker.poke();
            }
        })
        .map_err(|e| FrontendError::new("canopen", CanopenStartError::StoreThread(e)))?;

    let port = HubPort::attach(&hub, cx.handle);
    let fieldbus = CanopenFieldbus::new(port, specs)
        .with_persister(Box::new(ImagePersister { to_writer, done }));
    let nodes = fieldbus.status();
    install(cx.handle, Box::new(fieldbus)).await?;

    let mapped = Arc::new(Mutex::new(Vec::new()));
    if !mapped_specs.is_empty() {
        // Frames go to each node's task; the nodes' timers run inside the servo tick.
        let mut ticks = MappedTicks::new(Arc::clone(&mapped));
        let mut powered = Vec::new();
        for spec in mapped_specs {
            let task = MappedNodeTask::new(
                spec,
                &hub,
                cx.handle.clone(),
                cx.state_dir.cloned(),
                Arc::clone(&mapped),
            )
            .map_err(|e| FrontendError::new("canopen", e))?;
            ticks.add(&task);
            let (done, on) = tokio::sync::oneshot::channel();
            powered.push(on);
            tasks.spawn(task.run(cx.shutdown.clone(), done));
        }
        install(cx.handle, Box::new(ticks)).await?;
        // Announced once their stored parameters are in the map (a client's first read sees them).
        for on in powered {
            let _ = on.await;
        }
    }

    let mut bridge = None;
    if !c.interface.is_empty() {
        let config = SocketCanConfig {
            interface: c.interface.clone(),
            ..SocketCanConfig::default()
        };
        match SocketCanBridge::start(&hub, config).await {
            Ok(started) => {
                announce("canopen", &c.interface);
                bridge = Some(started);
            }
            Err(e) if c.interface_optional && socketcand.is_some() => {
                eprintln!("mcemu: {e}; the CAN bus is served over socketcand only");
            }
            Err(e) => {
                return Err(fail(ConfigError {
                    file: cx.file.to_string(),
                    key: "frontends.canopen.interface".into(),
                    reason: e.to_string(),
                }))
            }
        }
    }
    let mut server = None;
    if let Some(s) = socketcand {
        let config = SocketcandConfig {
            bind: s.bind,
            max_connections: s.max_connections.max(1),
            at_limit: s.at_limit,
            ..SocketcandConfig::default()
        };
        let started = SocketcandServer::start(config, vec![hub.clone()])
            .await
            .map_err(|e| FrontendError::new("socketcand", e))?;
        announce("socketcand", started.local_addr());
        server = Some(started);
    }
    Ok(Some(Arc::new(CanopenFrontend {
        hub,
        nodes,
        mapped,
        socketcan: Mutex::new(bridge),
        socketcand: Mutex::new(server),
        log,
    })))
}

/// Install `fieldbus` in the servo loop and wait until it runs.
async fn install(handle: &EngineHandle, fieldbus: Box<dyn Fieldbus>) -> Result<(), FrontendError> {
    let installed = match handle.submit_fieldbus(fieldbus) {
        Ok(pending) => pending.await,
        Err(e) => Err(e.into()),
    };
    installed.map_err(|e| FrontendError::new("canopen", CanopenStartError::Fieldbus(e)))
}

// ---- map-backed nodes (the CT E10) ----------------------------------------------------------

use std::sync::{MutexGuard, PoisonError, TryLockError};

use axes::runtime::Fieldbus;
use axes::Engine;
use mcemu_can::{FrameReceiver, FrameSender};
use mcemu_canopen::NmtState;

/// What a map-backed node has done, for `GET /state`.
#[derive(Clone, Debug)]
struct MappedStatus {
    node_id: u8,
    axis: usize,
    nmt: mcemu_canopen::NmtState,
    counters: mcemu_canopen::NodeCounters,
    refresh_errors: u64,
    rpdo_write_errors: u64,
    parameter_errors: u64,
    ticks_skipped: u64,
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
struct MappedTicks {
    /// Each node, its status slot, and the ticks that found it busy.
    nodes: Vec<(Arc<Mutex<MappedNode>>, usize, u64)>,
    status: Arc<Mutex<Vec<MappedStatus>>>,
    /// The engine of this tick, for the map's reads (the published snapshot is the tick before).
    sample: Snapshot,
}

impl MappedTicks {
    fn new(status: Arc<Mutex<Vec<MappedStatus>>>) -> MappedTicks {
        MappedTicks {
            nodes: Vec::new(),
            status,
            sample: Snapshot::default(),
        }
    }

    fn add(&mut self, task: &MappedNodeTask) {
        self.nodes.push((Arc::clone(&task.shared), task.slot, 0));
    }
}

impl Fieldbus for MappedTicks {
    fn before_step(&mut self, _engine: &mut Engine, _now: Duration) {}

    fn after_step(&mut self, engine: &mut Engine, now: Duration) {
        let mut sampled = false;
        for (shared, slot, skipped) in &mut self.nodes {
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
struct MappedNodeTask {
    shared: Arc<Mutex<MappedNode>>,
    receiver: FrameReceiver,
    handle: EngineHandle,
    state_dir: Option<StateDir>,
    status: Arc<Mutex<Vec<MappedStatus>>>,
    slot: usize,
    /// The snapshot the objects were last refreshed from.
    refreshed: Option<Arc<Snapshot>>,
}

impl MappedNodeTask {
    fn new(
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

    async fn run(
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
