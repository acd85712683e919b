//! `mcemu run`'s CANopen front-end: the bus (a `mcemu_can::Hub`), the drives' nodes on it as a
//! fieldbus inside the servo tick, the map-backed nodes (CT E10) as tasks of their own for frames
//! with their timers in the servo tick, the SocketCAN bridge and the socketcand server, the
//! candump log, and stored parameter images (0x1010) in the machine's state directory.

use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};

use axes::runtime::ClockMode;
use mcemu_can::socketcan::{SocketCanBridge, SocketCanConfig};
use mcemu_can::socketcand::{SocketcandConfig, SocketcandServer};
use mcemu_can::{BitTiming, Endpoint, EndpointOptions, Hub, HubConfig};
use mcemu_canopen::cia402::{CanopenFieldbus, FramePort, NodeStatus, Persister};
use std::future::Future;
use std::pin::Pin;
use std::time::Duration;

use axes::runtime::{EngineHandle, Fieldbus};
use mcemu_canopen::CanFrame;
use serde_json::{json, Map, Value};
use tokio::task::JoinSet;

use super::buslog::BusLog;
use super::mapped_node::{MappedNodeTask, MappedStatus, MappedTicks};
use super::wire::{from_wire, to_wire, Incoming};
use super::{image_file, CanopenStartError};

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
