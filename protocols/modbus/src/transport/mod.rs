//! Tokio transports: Modbus TCP, RTU on a serial line, RTU over TCP. Each owns its sockets or
//! file descriptors and hands request PDUs to a [`Server`](crate::server::Server).

pub mod rtu;
pub mod rtu_over_tcp;
pub mod tcp;

use std::future::Future;
use std::io;
use std::sync::Arc;

use mcemu_frontend::bound::{self, Connection, ConnectionTable};
use tokio::io::AsyncWriteExt;
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::watch;
use tokio::time::Instant;

use crate::config::ConnectionLimits;
use crate::counters::Counters;
use crate::state::FrontendState;

/// Accept connections until `shutdown`, within `limits.bound` (the kit's accept loop: at the
/// bound the connection idle longest is closed, or the new one is closed at once, counted
/// either way). Each connection runs `serve` in its own task with a tracing span; at shutdown
/// the connections are told to stop and awaited.
pub(crate) async fn accept_loop<F, Fut>(
    listener: TcpListener,
    limits: ConnectionLimits,
    state: Arc<FrontendState>,
    shutdown: impl Future<Output = ()>,
    serve: F,
) where
    F: Fn(Connection) -> Fut,
    Fut: Future<Output = ()> + Send + 'static,
{
    let table = ConnectionTable::new(limits.bound, Arc::clone(&state.counters.connections));
    // A refused client learns at once from the close, instead of waiting in the backlog.
    let refuse = |stream: TcpStream, _| async move { drop(stream) };
    bound::serve(listener, table, state.name(), shutdown, serve, refuse).await;
}

/// What ended a wait for bytes.
pub(crate) enum Wait {
    /// Bytes were appended to the buffer.
    Received,
    /// `deadline` passed first.
    Deadline,
}

pub(crate) use mcemu_frontend::bound::{stopping, unless_stopping};

/// Read what the peer sends next into `buf` (counted, stamped on the connection's activity, and
/// the idle deadline restarted), unless
/// `deadline` passes or the front-end stops first. A closed or failed socket, or shutdown, ends
/// the connection.
pub(crate) async fn wait_for_bytes(
    c: &mut Connection,
    buf: &mut Vec<u8>,
    counters: &Counters,
    deadlines: &mut Deadlines,
    deadline: Option<Instant>,
) -> Result<Wait, Close> {
    let mut chunk = [0u8; 4096];
    loop {
        tokio::select! {
            r = tokio::io::AsyncReadExt::read(&mut c.stream, &mut chunk) => match r {
                Ok(0) => return Err(Close::Peer),
                Ok(n) => {
                    c.activity.received();
                    counters.bytes_in.add(n as u64);
                    buf.extend_from_slice(chunk.get(..n).unwrap_or_default());
                    deadlines.received();
                    return Ok(Wait::Received);
                }
                Err(e) if transient(&e) => {}
                Err(e) => {
                    tracing::debug!(error = %e, "read failed");
                    return Err(Close::Peer);
                }
            },
            () = sleep_until(deadline) => return Ok(Wait::Deadline),
            () = stopping(&mut c.stop) => return Err(Close::Shutdown),
        }
    }
}

/// Sleep until `deadline`, or forever without one.
pub(crate) async fn sleep_until(deadline: Option<Instant>) {
    match deadline {
        Some(d) => tokio::time::sleep_until(d).await,
        None => std::future::pending().await,
    }
}

/// The earlier of two optional deadlines.
pub(crate) fn earliest(a: Option<Instant>, b: Option<Instant>) -> Option<Instant> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, None) => a,
        (None, b) => b,
    }
}

/// Why a connection ends.
#[derive(Debug)]
pub(crate) enum Close {
    /// The peer closed, or the socket failed.
    Peer,
    /// Shutdown of the front-end.
    Shutdown,
    /// A timeout or protocol violation, already counted and logged.
    Ours,
}

/// The deadlines of one connection: the idle timeout runs from the last byte received; the
/// frame timeout from the first byte of a frame that is still incomplete.
pub(crate) struct Deadlines {
    limits: ConnectionLimits,
    last_rx: Instant,
    frame_started: Option<Instant>,
}

/// Which deadline passed.
pub(crate) enum Expired {
    Idle,
    Frame,
}

impl Deadlines {
    pub fn new(limits: ConnectionLimits) -> Deadlines {
        Deadlines {
            limits,
            last_rx: Instant::now(),
            frame_started: None,
        }
    }

    pub fn received(&mut self) {
        self.last_rx = Instant::now();
    }

    /// After framing: `consumed` whether a frame was taken from the buffer, `pending` whether
    /// bytes of an incomplete frame remain.
    pub fn framed(&mut self, consumed: bool, pending: bool) {
        self.frame_started = match (pending, consumed) {
            (false, _) => None,
            // What remains started with the last read.
            (true, true) => Some(self.last_rx),
            (true, false) => self.frame_started.or(Some(self.last_rx)),
        };
    }

    pub fn next(&self) -> Option<(Instant, Expired)> {
        let idle = self
            .limits
            .idle_timeout
            .map(|d| (self.last_rx + d, Expired::Idle));
        let frame = self
            .frame_started
            .zip(self.limits.frame_timeout)
            .map(|(t, d)| (t + d, Expired::Frame));
        match (idle, frame) {
            (Some(i), Some(f)) => Some(if f.0 < i.0 { f } else { i }),
            (i, None) => i,
            (None, f) => f,
        }
    }
}

/// A `close` fault ends the connection instead of a reply (counted by the server).
pub(crate) fn closed_by_fault() -> Close {
    tracing::info!("closing connection: `close` fault");
    Close::Ours
}

/// Count and log an expired deadline.
pub(crate) fn expired(counters: &Counters, which: &Expired, limits: &ConnectionLimits) {
    match which {
        Expired::Idle => {
            counters.idle_timeouts.inc();
            tracing::info!(
                timeout_ms = limits.idle_timeout.map_or(0, |d| d.as_millis()),
                "closing idle connection"
            );
        }
        Expired::Frame => {
            counters.frame_timeouts.inc();
            tracing::info!(
                timeout_ms = limits.frame_timeout.map_or(0, |d| d.as_millis()),
                "closing connection: frame not completed in time"
            );
        }
    }
}

/// Write a reply, within the frame timeout: a client that does not read cannot hold the
/// connection's task forever.
pub(crate) async fn write_reply(
    stream: &mut TcpStream,
    bytes: &[u8],
    counters: &Counters,
    limits: &ConnectionLimits,
    stop: &mut watch::Receiver<bool>,
) -> Result<(), Close> {
    let write = stream.write_all(bytes);
    let deadline = limits.frame_timeout.map(|d| Instant::now() + d);
    tokio::select! {
        r = write => match r {
            Ok(()) => {
                counters.bytes_out.add(bytes.len() as u64);
                Ok(())
            }
            Err(e) => {
                tracing::debug!(error = %e, "write failed");
                Err(Close::Peer)
            }
        },
        () = sleep_until(deadline) => {
            counters.frame_timeouts.inc();
            tracing::info!("closing connection: the client does not take its replies");
            Err(Close::Ours)
        }
        () = stopping(stop) => Err(Close::Shutdown),
    }
}

/// A read error that only means "try again".
pub(crate) fn transient(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::Interrupted | io::ErrorKind::WouldBlock
    )
}
