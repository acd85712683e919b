//! `mcemu run`'s NMC front-ends: each enabled section bound and announced
//! (`listening: nmc ADDR`, `listening: nmc-local PATH`), its connections bounded by the kit's
//! connection table, each served by a loop over the sans-IO `mcemu_nmc::session`.

use std::sync::Arc;
use std::time::Duration;

use mcemu_frontend::bound::{self, Activity, AtLimit, Bound, ConnectionTable};
use mcemu_frontend::counter::ConnectionCounters;
use mcemu_nmc::session::{CloseReason, Event, ServerSession};
use serde_json::{json, Map, Value};
use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt};
use tokio::net::UnixListener;
use tokio::sync::watch;
use tokio::task::JoinSet;

use super::config::NmcDevice;
use super::service::NmcService;
use crate::control::ApiError;
use crate::frontend::{
    announce, bind, handles, Frontend, FrontendContext, FrontendError, StartFuture,
};

/// One running NMC section.
pub struct NmcFrontend {
    name: &'static str,
    service: Arc<NmcService>,
    connections: Arc<ConnectionCounters>,
}

impl Frontend for NmcFrontend {
    fn name(&self) -> &str {
        self.name
    }

    fn inject(&self, fault: Map<String, Value>) -> Result<Value, ApiError> {
        let request = super::faults::parse(&fault).map_err(|e| ApiError::InvalidBody {
            detail: e.message,
            field: e.field,
            line: 0,
            column: 0,
        })?;
        let active = self.service.faults.list.apply(request);
        Ok(json!({ "active_faults": active }))
    }

    fn state(&self) -> Value {
        let c = &self.service.counters;
        let k = &self.connections;
        json!({
            "name": self.name,
            "device": {
                "kind": self.service.device.kind,
                "id": self.service.device.id,
                "ip": self.service.device.ip.to_string(),
                "index": self.service.device.index,
            },
            "connections": {
                "open": k.open(),
                "opened": k.opened.get(),
                "closed": k.closed.get(),
                "refused_at_limit": k.refused_at_limit.get(),
                "evicted_idle": k.evicted_idle.get(),
                "idle_closed": c.idle_closed.get(),
            },
            "requests": c.requests.get(),
            "refused": c.refused.get(),
            "unknown_function": c.unknown_function.get(),
            "bad_frames": c.bad_frames.get(),
            "version_refused": c.version_refused.get(),
            "last_refusal": self.service.last_refusal.get(),
            "active_faults": self.service.faults.list.active(),
            "faults_applied": self.service.faults.applied(),
        })
    }
}

/// Bind and announce the enabled NMC sections and spawn their accept loops on `tasks`.
pub fn start<'a>(cx: &'a FrontendContext<'a>, tasks: &'a mut JoinSet<()>) -> StartFuture<'a> {
    Box::pin(async move { Ok(handles(start_sections(cx, tasks).await?)) })
}

/// `TCardInfo`'s counts: the local DI/DO (64 at most; the channels beyond are extension
/// modules, digest 001 §4.8), ADC, DAC.
fn io_counts(cx: &FrontendContext<'_>) -> [i16; 4] {
    let io = &cx.config.io;
    let local = crate::nmc::io_state::LOCAL_BITS as u16;
    [
        io.digital_inputs.min(local),
        io.digital_outputs.min(local),
        io.analog_inputs,
        io.analog_outputs,
    ]
    .map(|n| i16::try_from(n).unwrap_or(i16::MAX))
}

fn section(
    cx: &FrontendContext<'_>,
    name: &'static str,
    device: &NmcDevice,
    max_connections: usize,
) -> (Arc<NmcFrontend>, Arc<ConnectionTable>) {
    let service = NmcService::new(cx.handle.clone(), device.clone(), io_counts(cx));
    service.set_saving(cx.state_dir.cloned(), name);
    service.set_bus(crate::nmc::ecat_bus::EcatBus::new(
        device.kind,
        &cx.config.drives,
        device.io_slaves,
    ));
    let connections = Arc::new(ConnectionCounters::default());
    let table = ConnectionTable::new(
        Bound {
            max_connections,
            at_limit: AtLimit::EvictIdle,
        },
        Arc::clone(&connections),
    );
    let frontend = Arc::new(NmcFrontend {
        name,
        service,
        connections,
    });
    (frontend, table)
}

fn idle(seconds: f64) -> Option<Duration> {
    (seconds > 0.0).then(|| Duration::from_secs_f64(seconds.min(1e9)))
}

async fn start_sections(
    cx: &FrontendContext<'_>,
    tasks: &mut JoinSet<()>,
) -> Result<Vec<Arc<NmcFrontend>>, FrontendError> {
    let f = &cx.config.frontends;
    let mut started = Vec::new();
    if let Some(c) = f.nmc.as_ref().filter(|c| c.enabled) {
        let (frontend, table) = section(cx, "nmc", &c.device, c.max_connections);
        super::saved_config::restore_at_start(&frontend.service).await;
        super::user_para_file::restore_at_start(&frontend.service);
        let listener = bind("nmc", c.bind)
            .await
            .map_err(|e| FrontendError::new("nmc", e))?;
        let (service, idle) = (Arc::clone(&frontend.service), idle(c.idle_timeout));
        let stop = stopped(cx.shutdown);
        tasks.spawn(async move {
            bound::serve(
                listener,
                table,
                "nmc",
                stop,
                move |conn| {
                    let service = Arc::clone(&service);
                    async move {
                        let peer = conn.peer.to_string();
                        connection(
                            conn.stream,
                            service,
                            peer,
                            Some(conn.activity),
                            conn.stop,
                            idle,
                        )
                        .await;
                    }
                },
                |_stream, _peer| async {},
            )
            .await;
        });
        started.push(frontend);
    }
    if let Some(c) = f.nmc_local.as_ref().filter(|c| c.enabled) {
        let (frontend, table) = section(cx, "nmc_local", &c.device, c.max_connections);
        super::saved_config::restore_at_start(&frontend.service).await;
        super::user_para_file::restore_at_start(&frontend.service);
        // A socket file left by an earlier run would make the bind fail.
        if std::fs::symlink_metadata(&c.path).is_ok_and(|m| {
            use std::os::unix::fs::FileTypeExt;
            m.file_type().is_socket()
        }) {
            let _ = std::fs::remove_file(&c.path);
        }
        let listener = UnixListener::bind(&c.path).map_err(|e| {
            FrontendError::new(
                "nmc_local",
                std::io::Error::new(
                    e.kind(),
                    format!("cannot listen on {}: {e}", c.path.display()),
                ),
            )
        })?;
        announce("nmc-local", c.path.display());
        let (service, idle) = (Arc::clone(&frontend.service), idle(c.idle_timeout));
        let stop = cx.shutdown.clone();
        tasks.spawn(serve_unix(listener, table, service, idle, stop));
        started.push(frontend);
    }
    Ok(started)
}

/// The Unix socket's accept loop: the kit's table admits (evicting the connection idle
/// longest at the bound), each connection in its own task.
async fn serve_unix(
    listener: UnixListener,
    table: Arc<ConnectionTable>,
    service: Arc<NmcService>,
    idle: Option<Duration>,
    shutdown: watch::Receiver<bool>,
) {
    let shutdown = stopped(&shutdown);
    tokio::pin!(shutdown);
    let mut tasks = JoinSet::new();
    let (stop_tx, stop_rx) = watch::channel(false);
    loop {
        tokio::select! {
            () = &mut shutdown => break,
            Some(_) = tasks.join_next(), if !tasks.is_empty() => {}
            accepted = listener.accept() => {
                let Ok((stream, _)) = accepted else {
                    tokio::time::sleep(Duration::from_millis(100)).await;
                    continue;
                };
                let Some(admitted) = table.admit() else { continue };
                let (service, stop) = (Arc::clone(&service), stop_rx.clone());
                tasks.spawn(async move {
                    let slot = admitted.slot;
                    tokio::select! {
                        () = connection(stream, service, "local".into(), Some(admitted.activity), stop, idle) => {}
                        Ok(()) = admitted.evicted => {}
                    }
                    drop(slot);
                });
            }
        }
    }
    let _ = stop_tx.send(true);
    while tasks.join_next().await.is_some() {}
}

/// Serve one connection until the peer closes, the session breaks, it stays silent for
/// `idle`, or `stop` turns true.
async fn connection<S: AsyncRead + AsyncWrite + Unpin>(
    mut stream: S,
    service: Arc<NmcService>,
    peer: String,
    activity: Option<Activity>,
    mut stop: watch::Receiver<bool>,
    idle: Option<Duration>,
) {
    let mut session = ServerSession::new();
    let mut buf = vec![0u8; 8192];
    // Output in order: the session's, with a faulted reply's frame changed in place.
    let mut pending: Vec<u8> = Vec::new();
    let counters = &service.counters;
    loop {
        let read = async {
            match idle {
                Some(t) => tokio::time::timeout(t, stream.read(&mut buf)).await.ok(),
                None => Some(stream.read(&mut buf).await),
            }
        };
        let n = tokio::select! {
            r = read => r,
            () = bound::stopping(&mut stop) => return,
        };
        let n = match n {
            None => {
                counters.idle_closed.inc();
                return;
            }
            Some(Ok(0) | Err(_)) => return,
            Some(Ok(n)) => n,
        };
        if let Some(a) = &activity {
            a.received();
        }
        session.receive(buf.get(..n).unwrap_or(&[]));
        while let Some(event) = session.poll() {
            match event {
                Event::Request {
                    sequence,
                    function,
                    payload,
                } => {
                    let _in_request = activity.as_ref().map(Activity::request);
                    let fault = service.faults.take();
                    if fault.close {
                        let _ = stream.shutdown().await;
                        return;
                    }
                    let handler = super::handlers::find(function.id);
                    let (status, reply) = service.serve(function, handler, &payload, &peer).await;
                    if fault.no_reply {
                        continue;
                    }
                    if let Some(d) = fault.delay {
                        tokio::time::sleep(d).await;
                    }
                    let sequence = if fault.wrong_sequence {
                        sequence.wrapping_add(1)
                    } else {
                        sequence
                    };
                    let before = session.take_output();
                    session.reply(sequence, function.id, status, &reply);
                    let mut frame = session.take_output();
                    if let Some((byte, bit)) = fault.corrupt {
                        // Byte 0 by default: the magic, so the library sees garbage.
                        mcemu_frontend::fault::flip_bit(&mut frame, byte, bit, 0);
                    }
                    pending.extend(before);
                    pending.extend(frame);
                }
                Event::Negotiated { .. } => {}
                Event::UnknownFunction { .. } => counters.unknown_function.inc(),
                Event::Close(CloseReason::Frame(_)) => counters.bad_frames.inc(),
                Event::Close(CloseReason::Version) => counters.version_refused.inc(),
            }
        }
        pending.extend(session.take_output());
        let out = std::mem::take(&mut pending);
        if !out.is_empty() && stream.write_all(&out).await.is_err() {
            return;
        }
        if session.is_closed() {
            let _ = stream.shutdown().await;
            return;
        }
    }
}

/// A future that resolves when the machine stops.
fn stopped(shutdown: &watch::Receiver<bool>) -> impl std::future::Future<Output = ()> + 'static {
    let mut shutdown = shutdown.clone();
    async move {
        let _ = shutdown.wait_for(|stop| *stop).await;
    }
}
