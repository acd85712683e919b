//! `mcemu run`'s CANopen front-end: the bus (a `mcemu_can::Hub`), the drives' nodes on it as a
//! fieldbus inside the servo tick, the SocketCAN bridge and the socketcand server, the
//! candump log, and stored parameter images (0x1010) in the machine's state directory.

use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};

use axes::runtime::{ClockMode, EngineHandle};
use mcemu_can::socketcan::{SocketCanBridge, SocketCanConfig};
use mcemu_can::socketcand::{SocketcandConfig, SocketcandServer};
use mcemu_can::{BitTiming, CandumpLog, Endpoint, EndpointOptions, Hub, HubConfig, WireFrame};
use mcemu_canopen::cia402::{CanopenFieldbus, FramePort, NodeStatus, Persister};
use mcemu_canopen::CanFrame;
use serde_json::{json, Map, Value};
use tokio::sync::watch;
use tokio::task::JoinSet;

use crate::config::{Config, ConfigError};
use crate::control::{ApiError, Frontend};
use crate::run::{announce, RunError};
use crate::state_dir::StateDir;

/// The running CAN bus, for the control API.
pub struct CanopenFrontend {
    hub: Hub,
    nodes: Arc<Mutex<Vec<NodeStatus>>>,
    socketcan: Mutex<Option<SocketCanBridge>>,
    socketcand: Mutex<Option<SocketcandServer>>,
}

impl CanopenFrontend {
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
                json!({
                    "node_id": n.node_id,
                    "drive": n.slave,
                    "nmt": format!("{:?}", n.nmt),
                    "counters": format!("{:?}", n.counters),
                })
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
        })
    }
}

/// The nodes' side of the hub, as the binding sees it.
struct HubPort {
    endpoint: Endpoint,
    error_frames: u64,
}

impl FramePort for HubPort {
    fn try_recv(&mut self) -> Option<CanFrame> {
        while let Some(delivery) = self.endpoint.try_recv() {
            let f = delivery.frame;
            if f.is_error() {
                self.error_frames += 1;
                continue;
            }
            // CiA 301 uses base frames only; a 29-bit frame is someone else's traffic.
            if f.is_extended() {
                continue;
            }
            let id = f.id().raw() as u16;
            let frame = if f.is_remote() {
                CanFrame::remote(id, f.dlc())
            } else {
                CanFrame::new(id, f.data())
            };
            if let Ok(frame) = frame {
                return Some(frame);
            }
        }
        None
    }

    fn send(&mut self, frame: CanFrame) {
        let wire = if frame.is_rtr() {
            mcemu_can::CanId::standard(frame.id())
                .and_then(|id| WireFrame::remote(id, frame.len() as u8))
        } else {
            WireFrame::standard(frame.id(), frame.data())
        };
        if let Ok(wire) = wire {
            // A full queue is counted by the hub (tx_overflow).
            let _ = self.endpoint.send(wire);
        }
    }

    fn take_error_frames(&mut self) -> u64 {
        std::mem::take(&mut self.error_frames)
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

/// What `start` needs of `mcemu run`.
pub struct Context<'a> {
    pub config: &'a Config,
    pub file: &'a str,
    pub handle: &'a EngineHandle,
    pub state_dir: Option<&'a StateDir>,
    pub shutdown: &'a watch::Receiver<bool>,
}

/// Start the bus if `[frontends.canopen]` is enabled: nodes installed as a fieldbus, then the
/// transports, each announced.
pub async fn start(
    cx: &Context<'_>,
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
    let mut specs = super::node_specs(cx.config, cx.file)?;
    let bus_name = if c.interface.is_empty() {
        "vcan0".to_string()
    } else {
        c.interface.clone()
    };
    let mut hub_config = HubConfig::new(bus_name.clone());
    if let Some(timing) = BitTiming::new(c.bitrate).filter(|_| c.bitrate > 0) {
        hub_config = hub_config.with_timing(timing);
    }
    let hub = Hub::new(hub_config);
    if c.bitrate > 0 {
        let h = hub.clone();
        tasks.spawn(async move { h.drive_realtime().await });
    }
    if !c.log.is_empty() {
        let base = std::path::Path::new(cx.file)
            .parent()
            .unwrap_or(std::path::Path::new(""));
        let path = base.join(&c.log);
        let log = CandumpLog::create(&path, &bus_name, mcemu_can::log::DEFAULT_LOG_QUEUE).map_err(
            |e| ConfigError {
                file: cx.file.to_string(),
                key: "frontends.canopen.log".into(),
                reason: format!("cannot write {}: {e}", path.display()),
            },
        )?;
        let _ = hub.start_log(log);
    }

    // Stored images from earlier runs; saves go to a writer task.
    if let Some(dir) = cx.state_dir {
        for spec in &mut specs {
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

    let port = HubPort {
        endpoint: hub.attach(EndpointOptions::new("canopen nodes")),
        error_frames: 0,
    };
    let fieldbus = CanopenFieldbus::new(port, specs)
        .with_persister(Box::new(ImagePersister { to_writer, done }));
    let nodes = fieldbus.status();
    cx.handle
        .submit_fieldbus(Box::new(fieldbus))
        .map_err(|e| RunError::Io(std::io::Error::other(e.to_string())))?
        .await
        .map_err(|e| RunError::Io(std::io::Error::other(e.to_string())))?;
    if cx.handle.clock() == ClockMode::Virtual {
        // Time stands still: a frame for the nodes pokes the servo thread, which serves them
        // at the current tick.
        let mut watcher = hub.attach(EndpointOptions::new("virtual-clock poke"));
        let (handle, mut shutdown) = (cx.handle.clone(), cx.shutdown.clone());
        tasks.spawn(async move {
            loop {
                tokio::select! {
                    d = watcher.recv() => match d {
                        Some(_) => handle.poke(),
                        None => break,
                    },
                    _ = shutdown.wait_for(|s| *s) => break,
                }
            }
        });
    }

    let frontend = Arc::new(CanopenFrontend {
        hub: hub.clone(),
        nodes,
        socketcan: Mutex::new(None),
        socketcand: Mutex::new(None),
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

fn poisoned() -> RunError {
    RunError::Io(std::io::Error::other("a lock was poisoned"))
}
