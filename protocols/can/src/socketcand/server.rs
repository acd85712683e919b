//! The socketcand TCP server: a thin tokio transport around [`Session`] and [`Decoder`] that
//! serves hubs by bus name, so hosts without SocketCAN (or tools that prefer TCP) reach the
//! emulated bus: `can.Bus(interface="socketcand", host=…, port=…, channel="vcan0")`.
//!
//! Bounded: at most `max_connections` clients (at the limit the client idle longest is closed,
//! or with [`AtLimit::Refuse`] the next gets `< error … >` and is closed),
//! [`super::codec::MAX_ELEMENT`] bytes per element, and per client the hub's receive queue
//! plus [`FRAME_BACKLOG`] bytes of frame messages the socket has not taken yet. A client that
//! does not read loses frames (counted on the hub, per endpoint and in `rx_dropped`), as a
//! slow CAN controller does; its commands are still read and its frames still sent, and it
//! stays connected however long it does not read.

use std::collections::BTreeMap;
use std::io;
use std::net::{Ipv4Addr, SocketAddr};
use std::sync::Arc;
use std::time::Duration;

use mcemu_frontend::bound::{self, AtLimit, Bound, Connection, ConnectionTable};
use mcemu_frontend::counter::{ConnectionCounters, Counter};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::watch;
use tokio::time::Instant;

use crate::hub::{Delivery, Endpoint, EndpointOptions, Hub};
use crate::socketcand::codec::{encode_error_reply, Decoder, HI};
use crate::socketcand::session::{Session, SessionAction};

/// socketcand's default port.
pub const DEFAULT_PORT: u16 = 29536;

/// Bytes of frame messages held for a client beyond what its socket has taken. Past this the
/// server takes no more frames from the client's endpoint, whose queue then drops new frames
/// (counted on the hub) until the client reads.
pub const FRAME_BACKLOG: usize = 16 * 1024;

/// Bytes of unwritten output past which the server stops reading a client's commands. Replies
/// are never dropped (the client's protocol depends on them), so only a client that sends
/// commands with replies and never reads them (`< echo >`s, bad commands) is held back;
/// frames alone stay below [`FRAME_BACKLOG`] plus one batch.
pub const OUTPUT_LIMIT: usize = 64 * 1024;

/// Frames taken from the endpoint per wake-up, written together.
const FRAME_BATCH: usize = 64;

/// How the server listens.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SocketcandConfig {
    /// 127.0.0.1:29536 by default (ARCHITECTURE §8: loopback unless configured).
    pub bind: SocketAddr,
    pub max_connections: usize,
    /// What a new client meets while `max_connections` are open (`refuse`: `< error … >`).
    pub at_limit: AtLimit,
    /// After `< rawmode >`'s `< ok >`, frames wait this long before they flow. python-can
    /// reads the `< ok >` with a single `recv` and fails if a frame arrived in the same read;
    /// on a busy bus (SYNC at 1 kHz) that would be most connections. Frames are held (in the
    /// client's bounded queue), not dropped.
    pub rawmode_settle: Duration,
}

impl Default for SocketcandConfig {
    fn default() -> Self {
        Self {
            bind: SocketAddr::from((Ipv4Addr::LOCALHOST, DEFAULT_PORT)),
            max_connections: 16,
            at_limit: AtLimit::EvictIdle,
            rawmode_settle: Duration::from_millis(20),
        }
    }
}

/// The server's counters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SocketcandStats {
    pub accepted: u64,
    /// Connections refused because `max_connections` were open.
    pub refused: u64,
    /// Connections closed to admit a new one, idle longest.
    pub evicted_idle: u64,
    pub active: u64,
    /// Elements received (commands and errors).
    pub commands: u64,
    /// Elements answered with `< error … >`.
    pub errors: u64,
    /// Frames clients put on the bus.
    pub frames_from_clients: u64,
    /// Frames sent to clients.
    pub frames_to_clients: u64,
}

#[derive(Default)]
struct Stats {
    /// Accepted (opened), refused, evicted, active (open).
    connections: Arc<ConnectionCounters>,
    commands: Counter,
    errors: Counter,
    frames_from_clients: Counter,
    frames_to_clients: Counter,
}

impl Stats {
    fn snapshot(&self) -> SocketcandStats {
        let c = &self.connections;
        SocketcandStats {
            accepted: c.opened.get(),
            refused: c.refused_at_limit.get(),
            evicted_idle: c.evicted_idle.get(),
            active: c.open(),
            commands: self.commands.get(),
            errors: self.errors.get(),
            frames_from_clients: self.frames_from_clients.get(),
            frames_to_clients: self.frames_to_clients.get(),
        }
    }
}

/// Why the server could not start.
#[derive(Debug, thiserror::Error)]
pub enum SocketcandError {
    #[error("socketcand: cannot listen on {addr}: {source}")]
    Bind { addr: SocketAddr, source: io::Error },
    #[error("socketcand: two buses are named {0}")]
    DuplicateBus(String),
    #[error("socketcand: no bus to serve")]
    NoBus,
}

/// A running server; [`SocketcandServer::shutdown`] stops it and its connections.
pub struct SocketcandServer {
    local_addr: SocketAddr,
    stats: Arc<Stats>,
    shutdown: watch::Sender<bool>,
    task: tokio::task::JoinHandle<()>,
}

struct Shared {
    config: SocketcandConfig,
    buses: BTreeMap<String, Hub>,
    served: Vec<String>,
    stats: Arc<Stats>,
}

impl SocketcandServer {
    /// Listen and serve `buses` (each under its hub's name) on a spawned task.
    pub async fn start(config: SocketcandConfig, buses: Vec<Hub>) -> Result<Self, SocketcandError> {
        let mut by_name = BTreeMap::new();
        for hub in buses {
            let name = hub.name().to_string();
            if by_name.insert(name.clone(), hub).is_some() {
                return Err(SocketcandError::DuplicateBus(name));
            }
        }
        if by_name.is_empty() {
            return Err(SocketcandError::NoBus);
        }
        let listener =
            TcpListener::bind(config.bind)
                .await
                .map_err(|source| SocketcandError::Bind {
                    addr: config.bind,
                    source,
                })?;
        let local_addr = listener
            .local_addr()
            .map_err(|source| SocketcandError::Bind {
                addr: config.bind,
                source,
            })?;
        let stats = Arc::new(Stats::default());
        let shared = Arc::new(Shared {
            served: by_name.keys().cloned().collect(),
            buses: by_name,
            config,
            stats: Arc::clone(&stats),
        });
        let (shutdown, stop) = watch::channel(false);
        let task = tokio::spawn(accept_loop(listener, shared, stop));
        Ok(Self {
            local_addr,
            stats,
            shutdown,
            task,
        })
    }

    pub fn local_addr(&self) -> SocketAddr {
        self.local_addr
    }

    pub fn stats(&self) -> SocketcandStats {
        self.stats.snapshot()
    }

    /// Stop accepting, close every connection, and wait for them.
    pub async fn shutdown(self) {
        let _ = self.shutdown.send(true);
        let _ = self.task.await;
    }
}

async fn accept_loop(listener: TcpListener, shared: Arc<Shared>, mut stop: watch::Receiver<bool>) {
    let config = &shared.config;
    let bound = Bound {
        max_connections: config.max_connections,
        at_limit: config.at_limit,
    };
    let table = ConnectionTable::new(bound, Arc::clone(&shared.stats.connections));
    let max = table.bound().max_connections;
    let on_connected = |c: Connection| {
        let shared = Arc::clone(&shared);
        async move {
            if let Err(e) = serve(c, &shared).await {
                tracing::debug!("connection ended: {e}");
            }
        }
    };
    let shutdown = async move { bound::stopping(&mut stop).await };
    let on_refused = |stream, _| refuse(stream, max);
    bound::serve(
        listener,
        table,
        "socketcand",
        shutdown,
        on_connected,
        on_refused,
    )
    .await;
}

async fn refuse(mut stream: TcpStream, max: usize) {
    let mut out = String::new();
    encode_error_reply(&mut out, &format!("too many connections (at most {max})"));
    let _ = tokio::time::timeout(Duration::from_secs(1), stream.write_all(out.as_bytes())).await;
}

/// Where frames for this client come from: its endpoint once a bus is open, held back until
/// `hold_until` after entering raw mode.
struct Feed {
    endpoint: Option<Endpoint>,
    hold_until: Option<Instant>,
}

impl Feed {
    async fn next(&mut self) -> Option<Delivery> {
        let Some(endpoint) = self.endpoint.as_mut() else {
            return std::future::pending().await;
        };
        if let Some(until) = self.hold_until {
            tokio::time::sleep_until(until).await;
            self.hold_until = None;
        }
        endpoint.recv().await
    }
}

/// Acknowledge what was read at once rather than after the delayed-ACK timer (40 ms on Linux).
/// A client that leaves Nagle's algorithm on (python-can's socketcand bus unless `tcp_tune`)
/// holds each small `send` until the previous one is acknowledged: bursts of frames such as an
/// SDO block (127 frames, then the server's answer) would otherwise cost 40 ms each. Linux
/// leaves quick-ack mode on its own, so it is set again after every read.
fn quick_ack(reader: &tokio::net::tcp::OwnedReadHalf) {
    #[cfg(target_os = "linux")]
    {
        let _ = socket2::SockRef::from(reader.as_ref()).set_tcp_quickack(true);
    }
    #[cfg(not(target_os = "linux"))]
    let _ = reader;
}

async fn serve(c: Connection, shared: &Shared) -> io::Result<()> {
    let stats = &shared.stats;
    let Connection {
        stream,
        peer,
        activity,
        mut stop,
    } = c;
    let (mut reader, mut writer) = stream.into_split();
    // The greeting goes out alone, before any reply: the socket's buffer is empty, so this
    // does not wait on the client.
    writer.write_all(HI.as_bytes()).await?;
    let mut session = Session::new();
    let mut decoder = Decoder::new();
    let mut feed = Feed {
        endpoint: None,
        hold_until: None,
    };
    let mut actions = Vec::new();
    let mut buf = vec![0u8; 4096];
    // What the socket has not taken yet: written as the client's window allows, while its
    // commands go on being read (a client that never reads can still send).
    let mut pending: Vec<u8> = Vec::new();
    let mut out = String::new();
    loop {
        let backlog = pending.len();
        tokio::select! {
            _ = stop.changed() => return Ok(()),
            written = writer.write(&pending), if backlog > 0 => {
                match written? {
                    0 => return Err(io::ErrorKind::WriteZero.into()),
                    n => {
                        pending.drain(..n.min(backlog));
                    }
                }
            }
            read = reader.read(&mut buf), if backlog < OUTPUT_LIMIT => {
                let n = read?;
                if n == 0 {
                    return Ok(());
                }
                activity.received();
                quick_ack(&reader);
                decoder.decode(buf.get(..n).unwrap_or_default(), |command| {
                    stats.commands.inc();
                    session.on_command(command, &shared.served, &mut actions);
                });
                for action in actions.drain(..) {
                    match action {
                        SessionAction::Reply(reply) => {
                            stats.errors.add(u64::from(reply.starts_with("< error")));
                            out.push_str(&reply);
                        }
                        SessionAction::Attach(bus) => {
                            if let Some(hub) = shared.buses.get(&bus) {
                                let name = format!("socketcand {peer}");
                                feed.endpoint = Some(hub.attach(EndpointOptions::new(name)));
                            }
                        }
                        SessionAction::Transmit(frame) => {
                            let sent = feed.endpoint.as_ref().map(|e| e.send(frame));
                            match sent {
                                Some(Ok(())) => stats.frames_from_clients.inc(),
                                Some(Err(full)) => {
                                    stats.errors.inc();
                                    encode_error_reply(&mut out, &full.to_string());
                                }
                                None => {}
                            }
                        }
                        SessionAction::EnteredRawMode => {
                            // Frames of the BCM phase were never asked for.
                            if let Some(endpoint) = feed.endpoint.as_mut() {
                                while endpoint.try_recv().is_some() {}
                            }
                            feed.hold_until = Some(Instant::now() + shared.config.rawmode_settle);
                        }
                    }
                }
                pending.extend_from_slice(out.as_bytes());
                out.clear();
            }
            // Past the backlog frames stay in the endpoint's bounded queue, which drops.
            delivery = feed.next(), if backlog < FRAME_BACKLOG => {
                let Some(first) = delivery else { return Ok(()) };
                let Some(hub) = feed.endpoint.as_ref().map(|e| e.hub().clone()) else {
                    continue;
                };
                // Batch what is already queued into one write.
                let mut next = Some(first);
                let mut batched = 0;
                while let Some(delivery) = next {
                    if session.on_frame(hub.stamp(delivery.at), &delivery.frame, &mut out) {
                        stats.frames_to_clients.inc();
                    }
                    batched += 1;
                    next = if batched < FRAME_BATCH {
                        feed.endpoint.as_mut().and_then(Endpoint::try_recv)
                    } else {
                        None
                    };
                }
                pending.extend_from_slice(out.as_bytes());
                out.clear();
            }
        }
    }
}
