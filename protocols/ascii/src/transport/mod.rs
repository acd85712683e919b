//! The tokio side of the ASCII servers: one connection loop for both, the front-end kit's
//! bounded accept loop around it. Per connection: read → [`LineSplitter`] →
//! [`LineServer::handle`] → reply, one line after the other, and (User ASCII) the broadcasts in
//! between lines. Clients interleave at line boundaries: each is its own task.
//!
//! [`native::Server`] serves Native ASCII (port 3999), [`user::Server`] User ASCII (4000).
//!
//! The per-line path arms no timer (issue 14, Performance): the idle limit is one sleep per
//! connection that, when it fires, re-arms itself from the last read's time unless the client
//! has been silent for the whole limit; a reply is first written without waiting, and only a
//! reply the socket cannot take at once waits, within the write limit. The replies to the lines
//! one read brought (a client that pipelines) go out in one write, up to the first line that
//! waits for the engine.

pub mod native;
pub mod user;

use std::future::Future;
use std::sync::Arc;
use std::task::Poll;
use std::time::Duration;

use mcemu_dialects::himc::system::HMPL_STR_MAX_LEN;
use mcemu_frontend::bound::{self, AtLimit, Bound, Connection, ConnectionTable};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::broadcast;
use tokio::time::Instant;

use crate::counters::StreamCounters;
use crate::line::{Line, LineSplitter};

/// A text server the connection loop drives: its reply to each line, its limits and counters.
pub trait LineServer: Send + Sync + 'static {
    /// The reply to one line (line ending included; may be empty: nothing is sent).
    fn handle(&self, line: &Line) -> impl Future<Output = String> + Send;
    fn limits(&self) -> Limits;
    fn stream_counters(&self) -> &StreamCounters;
    /// Messages every connection writes between lines (User ASCII's broadcast); `None`: none.
    fn broadcasts(&self) -> Option<broadcast::Receiver<Arc<[u8]>>> {
        None
    }
}

/// A server's connection bound and timeouts (its config section's).
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// The config section, for logs.
    pub frontend: &'static str,
    pub max_connections: usize,
    pub at_limit: AtLimit,
    /// 0 = never.
    pub idle_timeout_ms: u64,
    /// 0 = never.
    pub write_timeout_ms: u64,
}

/// Accept clients on `listener` until `shutdown`, within the server's connection bound.
pub async fn serve<S: LineServer>(
    listener: TcpListener,
    server: Arc<S>,
    shutdown: impl Future<Output = ()>,
) {
    let limits = server.limits();
    let bound = Bound {
        max_connections: limits.max_connections,
        at_limit: limits.at_limit,
    };
    let connections = Arc::clone(&server.stream_counters().connections);
    let table = ConnectionTable::new(bound, connections);
    let refuse = |stream: TcpStream, _| async move { drop(stream) };
    let serve = |c: Connection| connection(Arc::clone(&server), c);
    bound::serve(listener, table, limits.frontend, shutdown, serve, refuse).await;
}

fn limit(ms: u64) -> Option<Duration> {
    (ms > 0).then(|| Duration::from_millis(ms))
}

/// Run `work`, giving up after `limit` if there is one.
async fn within<T>(limit: Option<Duration>, work: impl Future<Output = T>) -> Option<T> {
    match limit {
        Some(d) => tokio::time::timeout(d, work).await.ok(),
        None => Some(work.await),
    }
}

/// What woke a connection up.
enum Event {
    Read(std::io::Result<usize>),
    /// The idle sleep fired (the client may have sent something since it was armed).
    IdleCheck,
    Broadcast(Arc<[u8]>),
    Stop,
}

/// The next broadcast; never, without a channel. A lagging client misses the oldest ones.
async fn next_broadcast(rx: &mut Option<broadcast::Receiver<Arc<[u8]>>>) -> Arc<[u8]> {
    loop {
        let Some(r) = rx.as_mut() else {
            return std::future::pending().await;
        };
        match r.recv().await {
            Ok(m) => return m,
            Err(broadcast::error::RecvError::Lagged(_)) => continue,
            Err(broadcast::error::RecvError::Closed) => *rx = None,
        }
    }
}

async fn connection<S: LineServer>(server: Arc<S>, mut c: Connection) {
    let limits = server.limits();
    let counters = server.stream_counters();
    let idle = limit(limits.idle_timeout_ms);
    let write_limit = limit(limits.write_timeout_ms);
    let mut broadcasts = server.broadcasts();
    let mut splitter = LineSplitter::new(HMPL_STR_MAX_LEN);
    let mut buf = vec![0u8; 4096];
    let mut lines = Vec::new();
    let mut out = Vec::new();
    let mut last_read = Instant::now();
    // Without a limit the sleep is never polled (the branch is disabled).
    let idle_sleep = tokio::time::sleep(idle.unwrap_or(Duration::ZERO));
    tokio::pin!(idle_sleep);
    loop {
        let event = tokio::select! {
            r = c.stream.read(&mut buf) => Event::Read(r),
            () = &mut idle_sleep, if idle.is_some() => Event::IdleCheck,
            m = next_broadcast(&mut broadcasts) => Event::Broadcast(m),
            () = bound::stopping(&mut c.stop) => Event::Stop,
        };
        let n = match event {
            Event::Stop => return,
            Event::Broadcast(m) => {
                if !write(&mut c.stream, &m, write_limit, counters).await {
                    return;
                }
                continue;
            }
            Event::IdleCheck => {
                let Some(limit) = idle else { continue };
                let due = last_read + limit;
                if due > Instant::now() {
                    idle_sleep.as_mut().reset(due);
                    continue;
                }
                counters.idle_timeouts.inc();
                tracing::info!("closed: idle for {} ms", limits.idle_timeout_ms);
                return;
            }
            Event::Read(Ok(n)) if n > 0 => n,
            // Closed or failed: a line it had begun is dropped, unanswered.
            Event::Read(_) => {
                if splitter.in_line() {
                    counters.partial_lines.inc();
                }
                return;
            }
        };
        last_read = Instant::now();
        c.activity.received();
        counters.bytes_in.add(n as u64);
        splitter.push(buf.get(..n).unwrap_or_default(), &mut lines);
        // The replies to the lines of one read go out in one write, as far as they are ready
        // at once; a line that waits (for the engine) first sends the replies before it.
        out.clear();
        for line in lines.drain(..) {
            let _in_request = c.activity.request();
            let handling = server.handle(&line);
            tokio::pin!(handling);
            let reply =
                match std::future::poll_fn(|cx| Poll::Ready(handling.as_mut().poll(cx))).await {
                    Poll::Ready(reply) => reply,
                    Poll::Pending => {
                        if !write(&mut c.stream, &out, write_limit, counters).await {
                            return;
                        }
                        out.clear();
                        handling.await
                    }
                };
            out.extend_from_slice(reply.as_bytes());
        }
        if !write(&mut c.stream, &out, write_limit, counters).await {
            return;
        }
    }
}

/// Write `bytes` within the write limit; whether the connection lives on. What the socket
/// takes at once is written without arming a timer (a reply line almost always fits).
async fn write(
    stream: &mut TcpStream,
    mut bytes: &[u8],
    limit: Option<Duration>,
    counters: &StreamCounters,
) -> bool {
    while !bytes.is_empty() {
        match stream.try_write(bytes) {
            Ok(0) => return false,
            Ok(n) => bytes = bytes.get(n..).unwrap_or_default(),
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => break,
            Err(_) => return false,
        }
    }
    if bytes.is_empty() {
        return true;
    }
    match within(limit, stream.write_all(bytes)).await {
        Some(Ok(())) => true,
        Some(Err(_)) => false,
        None => {
            counters.write_timeouts.inc();
            tracing::info!("closed: the client takes no replies");
            false
        }
    }
}
