//! One bounded accept loop for every TCP front-end (ARCHITECTURE §8: a bounded number of open
//! connections), with what it does at the bound chosen per front-end ([`AtLimit`]).
//!
//! - [`ConnectionTable`] decides: admit, evict the connection idle longest to admit, refuse, or
//!   (for a listener that cannot evict, the control API's) wait until a place frees.
//! - [`serve`] runs the loop for a front-end that serves each connection in its own task: one
//!   tracing span per connection, its protocol's refusal on refusal, and at shutdown every
//!   connection told to stop and awaited.
//!
//! "Idle" is the time since the connection last received bytes: the protocol's read path
//! stamps [`Activity::received`]. A connection in the middle of a request
//! ([`Activity::request`]: a delayed reply in flight …) is never evicted; when every open
//! connection is in one, the new connection is refused as under [`AtLimit::Refuse`].

use std::future::Future;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use serde::{Deserialize, Serialize};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{oneshot, watch, Notify};
use tokio::task::JoinSet;
use tokio::time::Instant;
use tracing::Instrument;

use crate::counter::ConnectionCounters;

/// Pause after a failed `accept` (out of file descriptors …) so the loop does not spin.
const ACCEPT_BACKOFF: Duration = Duration::from_millis(100);

/// What a front-end does with a new connection while `max_connections` are open.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum AtLimit {
    /// Close the open connection that has received nothing for longest (not one in the middle
    /// of a request) and admit the new one, as many PLCs do; counted as `evicted_idle`.
    #[default]
    EvictIdle,
    /// Close the new connection at once, after the protocol's refusal if it has one
    /// (socketcand: `< error … >`); counted as `refused_at_limit`.
    Refuse,
}

/// The bound of one front-end: how many connections, and what happens at the limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bound {
    /// At least 1.
    pub max_connections: usize,
    pub at_limit: AtLimit,
}

/// What one connection did last, written by its task and read by the table at the bound.
#[derive(Debug)]
struct Stamp {
    /// Microseconds since the table's epoch at which bytes last arrived.
    last_rx_us: AtomicU64,
    /// Requests being handled (a connection may pipeline).
    in_request: AtomicU32,
}

/// A connection's activity stamp: cheap to touch on every read (one clock read, one relaxed
/// store).
#[derive(Clone, Debug)]
pub struct Activity {
    stamp: Arc<Stamp>,
    epoch: Instant,
}

impl Activity {
    fn micros_since(epoch: Instant) -> u64 {
        u64::try_from(Instant::now().duration_since(epoch).as_micros()).unwrap_or(u64::MAX)
    }

    /// Bytes arrived: the connection is not idle.
    pub fn received(&self) {
        self.stamp
            .last_rx_us
            .store(Self::micros_since(self.epoch), Ordering::Relaxed);
    }

    /// A request is being handled until the guard drops: the connection is not evicted
    /// meanwhile, however long ago its bytes arrived.
    pub fn request(&self) -> InRequest<'_> {
        self.stamp.in_request.fetch_add(1, Ordering::Relaxed);
        InRequest(&self.stamp)
    }
}

/// A request in progress on a connection (see [`Activity::request`]).
#[must_use = "the request ends when this drops"]
pub struct InRequest<'a>(&'a Stamp);

impl Drop for InRequest<'_> {
    fn drop(&mut self) {
        self.0.in_request.fetch_sub(1, Ordering::Relaxed);
    }
}

struct Entry {
    id: u64,
    stamp: Arc<Stamp>,
    /// Fired to close the connection; taken when fired.
    evict: Option<oneshot::Sender<()>>,
}

#[derive(Default)]
struct Entries {
    next_id: u64,
    open: Vec<Entry>,
}

/// The open connections of one front-end and its [`Bound`].
///
/// Inputs: [`ConnectionTable::admit`] (or [`ConnectionTable::admit_waiting`]) for each new
/// connection, before it is served; [`Activity::received`] and [`Activity::request`] from the
/// connection's task while it runs; dropping its [`Slot`] when it ends. Outputs: the admission
/// (with the receiver that fires if the connection is evicted later) or the refusal, and the
/// counts in its [`ConnectionCounters`].
pub struct ConnectionTable {
    bound: Bound,
    counters: Arc<ConnectionCounters>,
    epoch: Instant,
    entries: Mutex<Entries>,
    freed: Notify,
}

/// A connection let in.
pub struct Admitted {
    /// Its place: dropping it frees the place and counts the connection closed.
    pub slot: Slot,
    /// What its read path stamps.
    pub activity: Activity,
    /// Resolves when the table evicts this connection: close it then.
    pub evicted: oneshot::Receiver<()>,
}

/// A place in a [`ConnectionTable`], held for a connection's lifetime.
pub struct Slot {
    table: Arc<ConnectionTable>,
    id: u64,
}

impl Drop for Slot {
    fn drop(&mut self) {
        let mut entries = self.table.lock();
        entries.open.retain(|e| e.id != self.id);
        drop(entries);
        self.table.counters.closed.inc();
        self.table.freed.notify_one();
    }
}

impl ConnectionTable {
    pub fn new(bound: Bound, counters: Arc<ConnectionCounters>) -> Arc<ConnectionTable> {
        Arc::new(ConnectionTable {
            bound: Bound {
                max_connections: bound.max_connections.max(1),
                ..bound
            },
            counters,
            epoch: Instant::now(),
            entries: Mutex::new(Entries::default()),
            freed: Notify::new(),
        })
    }

    pub fn bound(&self) -> Bound {
        self.bound
    }

    pub fn counters(&self) -> &ConnectionCounters {
        &self.counters
    }

    fn lock(&self) -> MutexGuard<'_, Entries> {
        // Every change is one push or retain: a poisoned lock still holds a whole list.
        self.entries.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn register(self: &Arc<Self>, entries: &mut Entries) -> Admitted {
        let id = entries.next_id;
        entries.next_id += 1;
        let stamp = Arc::new(Stamp {
            last_rx_us: AtomicU64::new(Activity::micros_since(self.epoch)),
            in_request: AtomicU32::new(0),
        });
        let (evict, evicted) = oneshot::channel();
        entries.open.push(Entry {
            id,
            stamp: Arc::clone(&stamp),
            evict: Some(evict),
        });
        self.counters.opened.inc();
        Admitted {
            slot: Slot {
                table: Arc::clone(self),
                id,
            },
            activity: Activity {
                stamp,
                epoch: self.epoch,
            },
            evicted,
        }
    }

    /// Admit a new connection, evicting the one idle longest if the bound says so; `None`:
    /// refused (counted), close it.
    pub fn admit(self: &Arc<Self>) -> Option<Admitted> {
        let mut entries = self.lock();
        if entries.open.len() >= self.bound.max_connections {
            if self.bound.at_limit == AtLimit::Refuse {
                drop(entries);
                self.counters.refused_at_limit.inc();
                return None;
            }
            // Idle longest: the oldest stamp among those not in a request; on a tie the
            // connection admitted first.
            let victim = entries
                .open
                .iter()
                .enumerate()
                .filter(|(_, e)| e.stamp.in_request.load(Ordering::Relaxed) == 0)
                .min_by_key(|(_, e)| e.stamp.last_rx_us.load(Ordering::Relaxed))
                .map(|(i, _)| i);
            let Some(victim) = victim else {
                drop(entries);
                self.counters.refused_at_limit.inc();
                return None;
            };
            // Out of the table now, so that the next newcomer picks another; its slot counts
            // it closed when its task has dropped it.
            let mut victim = entries.open.remove(victim);
            if let Some(evict) = victim.evict.take() {
                let _ = evict.send(());
            }
            self.counters.evicted_idle.inc();
        }
        Some(self.register(&mut entries))
    }

    /// Admit a new connection, waiting at the bound until one closes (whatever
    /// [`AtLimit`] says): for a listener that hands its connections to a server that cannot be
    /// told to drop one (the control API's HTTP server).
    pub async fn admit_waiting(self: &Arc<Self>) -> Admitted {
        loop {
            let freed = self.freed.notified();
            {
                let mut entries = self.lock();
                if entries.open.len() < self.bound.max_connections {
                    return self.register(&mut entries);
                }
            }
            freed.await;
        }
    }
}

/// One admitted connection, as its protocol serves it.
pub struct Connection {
    pub stream: TcpStream,
    pub peer: SocketAddr,
    /// Stamp [`Activity::received`] on every read that brings bytes.
    pub activity: Activity,
    /// Turns `true` at shutdown: finish up and return.
    pub stop: watch::Receiver<bool>,
}

/// Resolves when `stop` turns `true` (or its sender is gone).
pub async fn stopping(stop: &mut watch::Receiver<bool>) {
    let _ = stop.wait_for(|stop| *stop).await;
}

/// Run `work` unless `stop` turns `true` first (a delayed reply or a slow model must not hold
/// up shutdown).
pub async fn unless_stopping<T>(
    work: impl Future<Output = T>,
    stop: &mut watch::Receiver<bool>,
) -> Option<T> {
    tokio::select! {
        r = work => Some(r),
        () = stopping(stop) => None,
    }
}

/// Accept connections on `listener` until `shutdown`, within `table`'s bound. Each admitted
/// connection runs `on_connected` in its own task, in a span naming `frontend` and the peer,
/// until it returns or the table evicts it (its future is then dropped, which closes the
/// socket). A refused connection is handed to `on_refused` (in a task of its own, so a slow
/// peer cannot hold up the loop) to say why, if its protocol can. At shutdown the connections
/// are told to stop ([`Connection::stop`]) and awaited.
pub async fn serve<F, Fut, R, RFut>(
    listener: TcpListener,
    table: Arc<ConnectionTable>,
    frontend: &str,
    shutdown: impl Future<Output = ()>,
    mut on_connected: F,
    mut on_refused: R,
) where
    F: FnMut(Connection) -> Fut,
    Fut: Future<Output = ()> + Send + 'static,
    R: FnMut(TcpStream, SocketAddr) -> RFut,
    RFut: Future<Output = ()> + Send + 'static,
{
    let (stop, stopped) = watch::channel(false);
    let mut tasks = JoinSet::new();
    tokio::pin!(shutdown);
    loop {
        tokio::select! {
            () = &mut shutdown => break,
            // Reap finished tasks so the set stays small.
            Some(_) = tasks.join_next(), if !tasks.is_empty() => {}
            accepted = listener.accept() => {
                let (stream, peer) = match accepted {
                    Ok(a) => a,
                    Err(e) => {
                        tracing::warn!(frontend, error = %e, "accept failed");
                        tokio::time::sleep(ACCEPT_BACKOFF).await;
                        continue;
                    }
                };
                let Some(admitted) = table.admit() else {
                    tracing::info!(
                        frontend, %peer, max = table.bound.max_connections,
                        "connection refused: at the connection limit"
                    );
                    tasks.spawn(on_refused(stream, peer));
                    continue;
                };
                let _ = stream.set_nodelay(true);
                let Admitted { slot, activity, evicted } = admitted;
                let conn = on_connected(Connection {
                    stream,
                    peer,
                    activity,
                    stop: stopped.clone(),
                });
                let span = tracing::info_span!("connection", frontend, %peer);
                tasks.spawn(
                    async move {
                        tracing::debug!("connection opened");
                        tokio::select! {
                            () = conn => tracing::debug!("connection closed"),
                            Ok(()) = evicted => tracing::info!(
                                "connection closed: idle longest at the connection limit"
                            ),
                        }
                        drop(slot);
                    }
                    .instrument(span),
                );
            }
        }
    }
    let _ = stop.send(true);
    while tasks.join_next().await.is_some() {}
}
