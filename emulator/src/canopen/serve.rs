//! `mcemu run`'s CANopen front-end: the bus (a `mcemu_can::Hub`), the drives' nodes on it as a
//! fieldbus inside the servo tick, the map-backed nodes (CT E10) as tasks of their own, the SocketCAN bridge and the socketcand server, the
//! candump log, and stored parameter images (0x1010) in the machine's state directory.

use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};

use axes::runtime::ClockMode;
use mcemu_can::socketcan::{SocketCanBridge, SocketCanConfig};
use mcemu_can::socketcand::{SocketcandConfig, SocketcandServer};
use mcemu_can::{BitTiming, Endpoint, EndpointOptions, Hub, HubConfig, WireFrame};
use mcemu_canopen::cia402::{CanopenFieldbus, FramePort, NodeStatus, Persister};
use std::time::Duration;

use axes::runtime::EngineHandle;
use axes::status::Snapshot;
use mcemu_canopen::{CanFrame, Node, NodeEvent};
use mcemu_modbus::map::UnitService;
use serde_json::{json, Map, Value};
use tokio::sync::{watch, Notify};
use tokio::task::JoinSet;

use super::buslog::BusLog;
use super::mapped::{MapDevice, ServiceRegisters};
use crate::state_dir::StateDir;

use crate::config::ConfigError;
use crate::control::{ApiError, Frontend};
use crate::run::{announce, FrontendContext, RunError};

/// The running CAN bus, for the control API.
pub struct CanopenFrontend {
    hub: Hub,
    nodes: Arc<Mutex<Vec<NodeStatus>>>,
    mapped: Arc<Mutex<Vec<MappedStatus>>>,
    socketcan: Mutex<Option<SocketCanBridge>>,
    socketcand: Mutex<Option<SocketcandServer>>,
    log: BusLog,
}

impl CanopenFrontend {
    /// The bus's candump log, for the control API.
    pub fn bus_log(&self) -> BusLog {
        self.log.clone()
    }

    /// Close the transports (at shutdown).
    pub async fn stop(&self) {
        let bridge = self.socketcan.lock().ok().and_then(|mut b| b.take());
        if let Some(b) = bridge {
            b.stop().await;
        }
        let server = self.socketcand.lock().ok().and_then(|mut s| s.take());
        if let Some(s) = server {
            s.shutdown().await;
        }
        let _ = self.hub.stop_log();
    }
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
        let nodes: Vec<Value> = self
            .nodes
            .lock()
            .map(|n| n.clone())
            .unwrap_or_default()
            .iter()
            .map(|n| {
                let mut v = node_json(n.node_id, n.nmt, &n.counters);
                v.insert("drive".into(), json!(n.slave));
                Value::Object(v)
            })
            .collect();
        let mapped: Vec<Value> = self
            .mapped
            .lock()
            .map(|n| n.clone())
            .unwrap_or_default()
            .iter()
            .map(|n| {
                let mut v = node_json(n.node_id, n.nmt, &n.counters);
                v.insert("axis".into(), json!(n.axis));
                v.insert("refresh_errors".into(), json!(n.refresh_errors));
                v.insert("rpdo_write_errors".into(), json!(n.rpdo_write_errors));
                Value::Object(v)
            })
            .collect();
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

fn send_to(endpoint: &Endpoint, frame: &CanFrame) {
    let wire = if frame.is_rtr() {
        mcemu_can::CanId::standard(frame.id())
            .and_then(|id| WireFrame::remote(id, frame.len() as u8))
    } else {
        WireFrame::standard(frame.id(), frame.data())
    };
    if let Ok(wire) = wire {
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
pub async fn start(
    cx: &FrontendContext<'_>,
    tasks: &mut JoinSet<()>,
) -> Result<Option<Arc<CanopenFrontend>>, RunError> {
    let Some(c) = cx.config.frontends.canopen.as_ref().filter(|c| c.enabled) else {
        return Ok(None);
    };
    let socketcand = cx
        .config
        .frontends
        .socketcand
        .as_ref()
        .filter(|s| s.enabled);
    let super::NodeSpecs {
        drives: mut specs,
        mapped: mut mapped_specs,
    } = super::node_specs(cx.config, cx.file)?;
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
    let log = BusLog::new(hub.clone(), super::buslog::config_dir(cx.file));
    if !c.log.is_empty() {
        log.start_from_config(&c.log).map_err(|e| ConfigError {
            file: cx.file.to_string(),
            key: "frontends.canopen.log".into(),
            reason: format!("cannot write it: {e}"),
        })?;
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
        .map_err(RunError::Io)?;

    let port = HubPort::attach(&hub, cx.handle);
    let fieldbus = CanopenFieldbus::new(port, specs)
        .with_persister(Box::new(ImagePersister { to_writer, done }));
    let nodes = fieldbus.status();
    cx.handle
        .submit_fieldbus(Box::new(fieldbus))
        .map_err(|e| RunError::Io(std::io::Error::other(e.to_string())))?
        .await
        .map_err(|e| RunError::Io(std::io::Error::other(e.to_string())))?;

    let mapped = Arc::new(Mutex::new(Vec::new()));
    if !mapped_specs.is_empty() {
        // Virtual clock: time moves only when a test advances it; each tick wakes the map-backed
        // nodes (coalesced), which then run their timers at the new engine time.
        let wake = if cx.handle.clock() == ClockMode::Virtual {
            let wake = Arc::new(Notify::new());
            let w = Arc::clone(&wake);
            cx.handle
                .add_observer_async(move |_| {
                    w.notify_one();
                    true
                })
                .await
                .map_err(|e| RunError::Io(std::io::Error::other(e.to_string())))?;
            Some(wake)
        } else {
            None
        };
        for spec in mapped_specs {
            let task = MappedNodeTask::new(
                spec,
                &hub,
                cx.handle.clone(),
                cx.state_dir.cloned(),
                Arc::clone(&mapped),
            )?;
            let (wake, shutdown) = (wake.clone(), cx.shutdown.clone());
            tasks.spawn(task.run(wake, shutdown));
        }
    }

    let frontend = Arc::new(CanopenFrontend {
        hub: hub.clone(),
        nodes,
        mapped,
        socketcan: Mutex::new(None),
        socketcand: Mutex::new(None),
        log,
    });
    if !c.interface.is_empty() {
        let config = SocketCanConfig {
            interface: c.interface.clone(),
            ..SocketCanConfig::default()
        };
        match SocketCanBridge::start(&hub, config).await {
            Ok(bridge) => {
                announce("canopen", &c.interface);
                *frontend.socketcan.lock().map_err(|_| poisoned())? = Some(bridge);
            }
            Err(e) if c.interface_optional && socketcand.is_some() => {
                eprintln!("mcemu: {e}; the CAN bus is served over socketcand only");
            }
            Err(e) => {
                return Err(ConfigError {
                    file: cx.file.to_string(),
                    key: "frontends.canopen.interface".into(),
                    reason: e.to_string(),
                }
                .into())
            }
        }
    }
    if let Some(s) = socketcand {
        let config = SocketcandConfig {
            bind: s.bind,
            max_connections: s.max_connections.max(1),
            ..SocketcandConfig::default()
        };
        let server = SocketcandServer::start(config, vec![hub.clone()])
            .await
            .map_err(|e| RunError::Bind {
                protocol: "socketcand",
                address: s.bind.to_string(),
                error: std::io::Error::other(e.to_string()),
            })?;
        announce("socketcand", server.local_addr());
        *frontend.socketcand.lock().map_err(|_| poisoned())? = Some(server);
    }
    Ok(Some(frontend))
}

/// What a map-backed node has done, for `GET /state`.
#[derive(Clone, Debug)]
struct MappedStatus {
    node_id: u8,
    axis: usize,
    nmt: mcemu_canopen::NmtState,
    counters: mcemu_canopen::NodeCounters,
    refresh_errors: u64,
    rpdo_write_errors: u64,
}

/// Paced clocks: how often (engine time) a map-backed node runs its tick when no deadline comes
/// sooner, so event-driven TPDOs notice changed values (half the CT E10's 10 ms inhibit time).
const MAPPED_POLL: Duration = Duration::from_millis(5);

/// Frames a map-backed node takes per wake-up before it lets its timers run.
const MAPPED_FRAMES_PER_WAKE: usize = 256;

/// A map-backed node (the CT E10) on the bus, served by a task of its own: its writes go
/// through the register map, which awaits engine commands — something the servo thread, where
/// the CiA 402 nodes run, must never do (decisions.md, "CT E10 on CANopen").
struct MappedNodeTask {
    node: Node<MapDevice<ServiceRegisters>>,
    axis: usize,
    endpoint: Endpoint,
    handle: EngineHandle,
    state_dir: Option<StateDir>,
    status: Arc<Mutex<Vec<MappedStatus>>>,
    slot: usize,
    /// The snapshot the objects were last refreshed from.
    refreshed: Option<Arc<Snapshot>>,
    out: Vec<CanFrame>,
}

impl MappedNodeTask {
    fn new(
        spec: super::MappedNodeSpec,
        hub: &Hub,
        handle: EngineHandle,
        state_dir: Option<StateDir>,
        status: Arc<Mutex<Vec<MappedStatus>>>,
    ) -> Result<MappedNodeTask, RunError> {
        let node_id = spec.config.node_id;
        let service = Arc::new(UnitService::new(spec.map, handle.clone()));
        let device = MapDevice::new(spec.od, ServiceRegisters(service), spec.backed);
        let mut node = Node::new(spec.config, device)
            .map_err(|e| RunError::Io(std::io::Error::other(format!("node {node_id}: {e}"))))?;
        node.set_stored_image(spec.stored_image);
        let slot = {
            let mut s = status.lock().map_err(|_| poisoned())?;
            s.push(MappedStatus {
                node_id,
                axis: spec.axis,
                nmt: node.nmt_state(),
                counters: node.counters(),
                refresh_errors: 0,
                rpdo_write_errors: 0,
            });
            s.len() - 1
        };
        Ok(MappedNodeTask {
            node,
            axis: spec.axis,
            endpoint: hub.attach(EndpointOptions::new(format!("e10 node {node_id}"))),
            handle,
            state_dir,
            status,
            slot,
            refreshed: None,
            out: Vec::new(),
        })
    }

    /// Engine time, tick × period in integer nanoseconds (as the CiA 402 nodes have it).
    fn now(&self) -> Duration {
        let s = self.handle.snapshot();
        let period_ns = (s.period * 1e9).round() as u64;
        Duration::from_nanos(s.tick.saturating_mul(period_ns))
    }

    /// The objects from the map, when the engine published something new since the last time.
    fn refresh(&mut self) {
        let snapshot = self.handle.snapshot();
        if self
            .refreshed
            .as_ref()
            .is_some_and(|r| Arc::ptr_eq(r, &snapshot))
        {
            return;
        }
        self.node.device_mut().refresh();
        self.refreshed = Some(snapshot);
    }

    fn on_frame(&mut self, frame: &WireFrame) {
        match from_wire(frame) {
            Incoming::Frame(f) => {
                self.refresh();
                let now = self.now();
                let rpdo = self.node.device().is_rpdo(f.id());
                if rpdo {
                    self.node.device_mut().begin_rpdo();
                }
                self.node.on_frame_into(&f, now, &mut self.out);
                if rpdo {
                    self.node.device_mut().finish_rpdo();
                }
                // A write may have issued commands: the next call reads the map again.
                self.refreshed = None;
                self.handle_events(now);
            }
            Incoming::Error => self.node.note_error_frame(),
            Incoming::Other => {}
        }
    }

    fn on_tick(&mut self) {
        self.refresh();
        let now = self.now();
        self.node.on_tick_into(now, &mut self.out);
        self.handle_events(now);
    }

    /// Stores go to the state directory (a small atomic write, done here); a lost master has
    /// no reaction beyond the node's own (0x1029): the E10 model has no 0x6007.
    fn handle_events(&mut self, now: Duration) {
        while let Some(event) = self.node.poll_event() {
            match event {
                NodeEvent::StoreRequested { image, .. }
                | NodeEvent::RestoreRequested { image, .. } => {
                    let id = self.node.node_id();
                    let saved = match &self.state_dir {
                        Some(d) => d.write(&image_file(id), &image).map_err(|e| {
                            tracing::error!(node_id = id, error = %e, "cannot store the parameter image");
                        }),
                        None => Err(()),
                    };
                    let frames = self.node.finish_persist(saved.is_ok(), now);
                    self.out.extend(frames);
                }
                _ => {}
            }
        }
    }

    fn flush(&mut self) {
        for frame in self.out.drain(..) {
            send_to(&self.endpoint, &frame);
        }
        if let Ok(mut s) = self.status.try_lock() {
            if let Some(slot) = s.get_mut(self.slot) {
                *slot = MappedStatus {
                    node_id: self.node.node_id(),
                    axis: self.axis,
                    nmt: self.node.nmt_state(),
                    counters: self.node.counters(),
                    refresh_errors: self.node.device().refresh_errors,
                    rpdo_write_errors: self.node.device().rpdo_write_errors,
                };
            }
        }
    }

    /// How long (wall time) to sleep before the next tick on a paced clock.
    fn wall_wait(&self) -> Duration {
        let now = self.now();
        let next = now + MAPPED_POLL;
        let target = self.node.next_deadline().map_or(next, |d| d.min(next));
        let engine = target.saturating_sub(now);
        let snapshot = self.handle.snapshot();
        let ratio = self
            .handle
            .clock()
            .wall_period(snapshot.period)
            .map_or(1.0, |w| w / snapshot.period);
        engine.mul_f64(ratio).max(Duration::from_micros(100))
    }

    async fn run(mut self, wake: Option<Arc<Notify>>, mut shutdown: watch::Receiver<bool>) {
        self.refresh();
        let frames = self.node.start(self.now());
        self.out.extend(frames);
        self.flush();
        loop {
            let wait = self.wall_wait();
            let timer = async {
                match &wake {
                    Some(w) => w.notified().await,
                    None => tokio::time::sleep(wait).await,
                }
            };
            tokio::select! {
                d = self.endpoint.recv() => {
                    let Some(d) = d else { break };
                    self.on_frame(&d.frame);
                    for _ in 1..MAPPED_FRAMES_PER_WAKE {
                        let Some(d) = self.endpoint.try_recv() else { break };
                        self.on_frame(&d.frame);
                    }
                    // Timers that fell due meanwhile (an SDO timeout, a TPDO).
                    self.on_tick();
                }
                _ = timer => self.on_tick(),
                _ = shutdown.wait_for(|s| *s) => break,
            }
            self.flush();
        }
    }
}

fn poisoned() -> RunError {
    RunError::Io(std::io::Error::other("a lock was poisoned"))
}
