//! The servo runtime (ARCHITECTURE §4): servo thread, bounded command queue with one-shot
//! replies, lock-free snapshots, and the realtime, virtual and scaled clocks.
//!
//! [`Runtime::start`] moves an [`Engine`] onto the servo thread ("mcemu-servo") and returns an
//! [`EngineHandle`], which front-ends clone freely (blocking and async calls, no tokio), and a
//! [`RuntimeGuard`], which stops the thread and gives the engine back. Observers
//! ([`EngineHandle::add_observer`]) see the engine after every tick, on the servo thread (on the
//! virtual clock: on whichever thread serves the queue, the servo thread or a blocking caller,
//! one at a time; see [`EngineHandle::advance`]).
//!
//! Ordering guarantees:
//! - commands are applied in the order the queue received them;
//! - a command's reply is sent after the snapshot that includes its effect is published, so a
//!   caller that got a reply and then reads [`EngineHandle::snapshot`] sees its own write;
//! - virtual clock: the queue is processed strictly in order, an advance included, so the same
//!   commands submitted between the same advances give bit-identical engine states.

mod clock;
mod servo;
mod stats;
#[cfg(test)]
mod tests;

use std::future::{Future, IntoFuture};
use std::pin::Pin;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, SyncSender, TrySendError};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
use std::task::{Context, Poll};
use std::thread::{JoinHandle, ThreadId};
use std::time::Duration;

use arc_swap::ArcSwap;
use serde::{Deserialize, Serialize};

use crate::command::{Command, EngineError, Reply};
use crate::engine::Engine;
use crate::status::Snapshot;

pub use clock::{Clock, SystemClock};
pub use stats::{LatenessHistogram, RuntimeStats, LATENESS_BUCKETS};

use servo::{Request, Servo, Unpaced, VirtualServo};

/// Range of the scaled clock's factor: beyond it a tick's wall period leaves the range a
/// deadline can be computed and slept for meaningfully (62.5 ns … 10⁴ s).
pub const MIN_SCALE: f64 = 1e-3;
pub const MAX_SCALE: f64 = 1e3;

/// How engine time relates to wall time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ClockMode {
    /// One tick per period of wall time, on absolute deadlines.
    #[default]
    Realtime,
    /// Ticks only when asked ([`EngineHandle::advance`]); for tests and scenarios.
    Virtual,
    /// `k` × real time ([`MIN_SCALE`] ≤ k ≤ [`MAX_SCALE`]): one tick per `period / k` of wall
    /// time.
    Scaled(f64),
}

impl ClockMode {
    /// Wall seconds per tick, `None` for the virtual clock.
    pub fn wall_period(self, period: f64) -> Option<f64> {
        match self {
            ClockMode::Realtime => Some(period),
            ClockMode::Virtual => None,
            ClockMode::Scaled(k) => Some(period / k),
        }
    }
}

/// Options of [`Runtime::start`]. Times in seconds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RuntimeOptions {
    pub clock: ClockMode,
    /// Requests (commands and advances) that may wait in the queue; one more is `QueueFull`.
    pub queue_capacity: usize,
    /// Commands applied per tick at most (paced clocks); the rest wait for the next tick.
    pub max_commands_per_tick: usize,
    /// Missed ticks run back to back after a late wake-up, at most; the rest are dropped.
    pub max_catch_up_ticks: u64,
    /// Time before a deadline when the system clock stops sleeping and yields in a loop.
    /// `None`: min(100 µs, wall period / 10).
    pub spin_window: Option<f64>,
}

impl Default for RuntimeOptions {
    fn default() -> Self {
        RuntimeOptions {
            clock: ClockMode::Realtime,
            queue_capacity: 1024,
            max_commands_per_tick: 256,
            max_catch_up_ticks: 1000,
            spin_window: None,
        }
    }
}

impl RuntimeOptions {
    pub fn with_clock(clock: ClockMode) -> RuntimeOptions {
        RuntimeOptions {
            clock,
            ..RuntimeOptions::default()
        }
    }

    fn validate(&self) -> Result<(), RuntimeError> {
        let invalid = |option: &'static str, reason: &str| {
            Err(RuntimeError::InvalidOptions {
                option,
                reason: reason.to_owned(),
            })
        };
        if let ClockMode::Scaled(k) = self.clock {
            if !(MIN_SCALE..=MAX_SCALE).contains(&k) {
                return invalid("clock", "the scale factor must be between 0.001 and 1000");
            }
        }
        if self.queue_capacity == 0 {
            return invalid("queue_capacity", "must be at least 1");
        }
        if self.max_commands_per_tick == 0 {
            return invalid("max_commands_per_tick", "must be at least 1");
        }
        if let Some(spin) = self.spin_window {
            if !(spin.is_finite() && (0.0..=1.0).contains(&spin)) {
                return invalid("spin_window", "must be between 0 and 1 second");
            }
        }
        Ok(())
    }

    fn spin_window_for(&self, wall_period: f64) -> Duration {
        let auto = || (wall_period / 10.0).min(100e-6);
        Duration::try_from_secs_f64(self.spin_window.unwrap_or_else(auto)).unwrap_or_default()
    }
}

/// Starting or stopping the runtime failed.
#[derive(Debug, thiserror::Error)]
pub enum RuntimeError {
    #[error("runtime option `{option}`: {reason}")]
    InvalidOptions {
        option: &'static str,
        reason: String,
    },
    #[error("cannot start the servo thread: {0}")]
    Spawn(#[source] std::io::Error),
    #[error("the servo thread panicked; the engine is lost")]
    ServoPanicked,
}

/// Why a request was not queued (or, when it arrives as a reply, not carried out).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SubmitError {
    #[error("the engine's command queue is full ({capacity} requests); retry later")]
    QueueFull { capacity: usize },
    #[error("the runtime is stopped")]
    Stopped,
}

/// Why a command call did not produce a reply from the engine.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CallError {
    /// Not queued (`QueueFull`, `Stopped`), or queued but the runtime stopped before applying
    /// it (`Stopped`).
    #[error(transparent)]
    Submit(#[from] SubmitError),
    /// The reply channel closed without a reply (the servo thread died).
    #[error("no reply: the servo thread died")]
    NoReply,
    /// A blocking call from the servo thread itself (e.g. an `advance_until` condition) would
    /// wait for itself forever.
    #[error("a blocking call from the servo thread would deadlock")]
    OnServoThread,
    #[error(transparent)]
    Engine(#[from] EngineError),
}

/// Why an advance did not complete.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum AdvanceError {
    #[error("advance needs the virtual clock; this runtime runs {0:?}")]
    NotVirtual(ClockMode),
    /// Not queued, or the runtime stopped before the advance completed (`Stopped`).
    #[error(transparent)]
    Submit(#[from] SubmitError),
    #[error("no reply: the servo thread died")]
    NoReply,
    #[error("a blocking call from the servo thread would deadlock")]
    OnServoThread,
    /// The `advance_until` condition panicked after the step to `tick`; the runtime goes on.
    #[error("the advance_until condition panicked at tick {tick}")]
    ConditionPanicked { tick: u64 },
}

/// Errors a reply channel can produce when no reply comes: the runtime stopped, or died.
trait ReplyError {
    fn stopped() -> Self;
    fn no_reply() -> Self;
}

impl ReplyError for CallError {
    fn stopped() -> Self {
        CallError::Submit(SubmitError::Stopped)
    }
    fn no_reply() -> Self {
        CallError::NoReply
    }
}

impl ReplyError for AdvanceError {
    fn stopped() -> Self {
        AdvanceError::Submit(SubmitError::Stopped)
    }
    fn no_reply() -> Self {
        AdvanceError::NoReply
    }
}

/// Result of [`EngineHandle::advance_until`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Until {
    /// The condition became true (after the step to `tick`).
    pub met: bool,
    /// Engine tick when the advance ended.
    pub tick: u64,
}

/// Condition of [`EngineHandle::advance_until`], evaluated on the snapshot published after each
/// tick (the same one readers get).
pub type Condition = Box<dyn Fn(&Snapshot) -> bool + Send>;

/// A per-tick observer ([`EngineHandle::add_observer`]): called on the servo thread (virtual
/// clock: the thread serving the queue) with the engine after every step, for as long as it
/// returns `true`.
pub type Observer = Box<dyn FnMut(&Engine) -> bool + Send>;

/// A fieldbus served inside the servo tick ([`EngineHandle::add_fieldbus`]): a protocol whose
/// slaves must see every tick and answer within it (CANopen SYNC, PDOs and SDOs on the engine's
/// CiA 402 drives), rather than go through the command queue and the snapshots.
///
/// Both calls run on the servo thread (virtual clock: the thread serving the queue), inside the
/// tick: they must be short and must not block
/// (exchange frames through lock-free or bounded queues; blocking handle calls are refused).
///
/// `now` is bus time, what the protocol's own timers (heartbeats, SDO timeouts, inhibit times)
/// run on. On the virtual clock it is engine time, so runs are reproducible. On the paced
/// clocks it is wall time since the start (× the scale factor) added to the engine time at the
/// start: after a stall the servo thread catches up a burst of ticks in a few milliseconds, and
/// timers on engine time would see a second pass in that burst while the bus saw none (an SDO
/// block transfer aborted mid-sub-block, a master's heartbeat declared lost).
pub trait Fieldbus: Send {
    /// Before every step, and whenever input is waiting ([`EngineHandle::poke`]) between steps:
    /// take what arrived and apply it (SDO writes, RPDOs, NMT, SYNC).
    fn before_step(&mut self, engine: &mut Engine, now: Duration);
    /// After every step: send what the step produced (TPDOs on SYNC, heartbeats, EMCY).
    fn after_step(&mut self, engine: &mut Engine, now: Duration);
}

/// Names an installed [`Observer`] for [`EngineHandle::remove_observer`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct ObserverId(u64);

/// The sending half of a reply: sending consumes it; dropping it unsent (the request was
/// discarded at shutdown, or the servo thread unwound) replies `Stopped`, so every request gets
/// an answer.
struct ReplySender<T, E: ReplyError>(Option<oneshot::Sender<Result<T, E>>>);

impl<T, E: ReplyError> ReplySender<T, E> {
    fn send(mut self, result: Result<T, E>) {
        if let Some(tx) = self.0.take() {
            let _ = tx.send(result); // the caller may have stopped waiting
        }
    }
}

impl<T, E: ReplyError> Drop for ReplySender<T, E> {
    fn drop(&mut self) {
        if let Some(tx) = self.0.take() {
            let _ = tx.send(Err(E::stopped()));
        }
    }
}

/// A reply on its way: wait for it ([`Pending::wait`]), poll it ([`Pending::try_take`]), or
/// `.await` it under any executor.
#[must_use = "the reply tells whether the engine accepted the request"]
pub struct Pending<T, E> {
    rx: oneshot::Receiver<Result<T, E>>,
}

/// The reply to a command ([`EngineHandle::submit`]).
pub type PendingReply = Pending<Reply, CallError>;

fn reply_channel<T, E: ReplyError>() -> (ReplySender<T, E>, Pending<T, E>) {
    let (tx, rx) = oneshot::channel();
    (ReplySender(Some(tx)), Pending { rx })
}

#[allow(private_bounds)] // `ReplyError` is implemented by the public error types only
impl<T, E: ReplyError> Pending<T, E> {
    /// Block until the reply arrives. Never on the servo thread (inside an `advance_until`
    /// condition): it would wait for itself.
    pub fn wait(self) -> Result<T, E> {
        self.rx.recv().unwrap_or_else(|_| Err(E::no_reply()))
    }

    /// The reply if it has arrived.
    pub fn try_take(&self) -> Option<Result<T, E>> {
        match self.rx.try_recv() {
            Ok(result) => Some(result),
            Err(oneshot::TryRecvError::Empty) => None,
            Err(oneshot::TryRecvError::Disconnected) => Some(Err(E::no_reply())),
        }
    }
}

#[allow(private_bounds)]
impl<T, E: ReplyError> IntoFuture for Pending<T, E> {
    type Output = Result<T, E>;
    type IntoFuture = PendingFuture<T, E>;

    fn into_future(self) -> PendingFuture<T, E> {
        PendingFuture {
            rx: self.rx.into_future(),
        }
    }
}

/// [`Pending`] as a future.
pub struct PendingFuture<T, E> {
    rx: oneshot::AsyncReceiver<Result<T, E>>,
}

#[allow(private_bounds)]
impl<T, E: ReplyError> Future for PendingFuture<T, E> {
    type Output = Result<T, E>;

    fn poll(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        Pin::new(&mut self.rx)
            .poll(cx)
            .map(|received| received.unwrap_or_else(|_| Err(E::no_reply())))
    }
}

/// State shared by the handles, the guard and the servo thread.
struct Shared {
    snapshot: ArcSwap<Snapshot>,
    stats: ArcSwap<RuntimeStats>,
    clock: ClockMode,
    queue_capacity: usize,
    stop: AtomicBool,
    running: AtomicBool,
    servo_thread: OnceLock<ThreadId>,
    /// The servo thread, to wake a paced one from its sleep when a fieldbus is poked.
    servo_waker: OnceLock<std::thread::Thread>,
    /// A fieldbus has input waiting: set by a poke, cleared when the servo thread starts to
    /// serve it (on the virtual clock the poke also queues a request, to keep it in order).
    poked: AtomicBool,
    /// Virtual clock: the engine and the queue's receiver, served by whoever holds the lock
    /// (`servo::serve_virtual`); `None` on a paced clock and once stopped.
    core: Mutex<Option<VirtualServo>>,
}

impl Shared {
    /// Whether this thread runs the engine: the paced servo thread, or any thread serving the
    /// virtual queue (a blocking call from there would wait for itself).
    fn on_servo_thread(&self) -> bool {
        self.servo_thread.get() == Some(&std::thread::current().id()) || servo::serving(self)
    }
}

/// Starts the servo thread.
pub struct Runtime;

impl Runtime {
    /// Run `engine` on a new servo thread paced by the system clock.
    pub fn start(
        engine: Engine,
        options: RuntimeOptions,
    ) -> Result<(EngineHandle, RuntimeGuard), RuntimeError> {
        options.validate()?;
        let wall_period = options.clock.wall_period(engine.period()).unwrap_or(0.0);
        let clock = SystemClock::new(options.spin_window_for(wall_period));
        Runtime::start_with_clock(engine, options, clock)
    }

    /// Run `engine` on a new servo thread paced by `clock` (ignored by the virtual clock).
    pub fn start_with_clock<C: Clock>(
        engine: Engine,
        options: RuntimeOptions,
        clock: C,
    ) -> Result<(EngineHandle, RuntimeGuard), RuntimeError> {
        options.validate()?;
        let (tx, rx) = mpsc::sync_channel(options.queue_capacity);
        let shared = Arc::new(Shared {
            snapshot: ArcSwap::from_pointee(engine.snapshot()),
            stats: ArcSwap::from_pointee(RuntimeStats::new(
                options.clock,
                engine.period(),
                engine.tick(),
            )),
            clock: options.clock,
            queue_capacity: options.queue_capacity,
            stop: AtomicBool::new(false),
            running: AtomicBool::new(true),
            servo_thread: OnceLock::new(),
            servo_waker: OnceLock::new(),
            poked: AtomicBool::new(false),
            core: Mutex::new(None),
        });
        let builder = std::thread::Builder::new().name("mcemu-servo".to_owned());
        let spawned = if options.clock == ClockMode::Virtual {
            let servo = Servo::new(engine, rx, Arc::clone(&shared), Unpaced, &options);
            *shared.core.lock().unwrap_or_else(PoisonError::into_inner) = Some(servo);
            let serving = Arc::clone(&shared);
            builder.spawn(move || servo::run_virtual(serving))
        } else {
            let servo = Servo::new(engine, rx, Arc::clone(&shared), clock, &options);
            builder.spawn(move || servo.run())
        };
        let thread = spawned.map_err(|e| {
            // The state holds an `Arc` of `shared`: drop it, or the two keep each other alive.
            shared
                .core
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .take();
            RuntimeError::Spawn(e)
        })?;
        let handle = EngineHandle {
            shared: Arc::clone(&shared),
            tx: tx.clone(),
        };
        let guard = RuntimeGuard {
            shared,
            tx,
            thread: Some(thread),
        };
        Ok((handle, guard))
    }
}

/// What front-ends hold: submit commands, read snapshots and statistics, advance a virtual
/// clock. Cheap to clone, `Send + Sync`; no call ever blocks the servo thread.
#[derive(Clone)]
pub struct EngineHandle {
    shared: Arc<Shared>,
    tx: SyncSender<Request>,
}

impl EngineHandle {
    /// Queue a command without blocking. Virtual clock: applied as soon as the servo thread (or
    /// a blocking caller serving the queue) gets to it, no advance needed; paced clocks: at the
    /// start of the next tick.
    pub fn submit(&self, command: Command) -> Result<PendingReply, SubmitError> {
        self.request(|reply| Request::Command { command, reply })
    }

    /// Queue commands to be applied in one go, between the same two ticks, in order, all or
    /// none ([`Engine::apply_batch`]: a refusal puts the engine back and names the command's
    /// index). Without blocking; the reply holds one reply per command.
    pub fn submit_batch(
        &self,
        commands: Vec<Command>,
    ) -> Result<Pending<Vec<Reply>, CallError>, SubmitError> {
        self.request(|reply| Request::Batch { commands, reply })
    }

    /// [`EngineHandle::submit_batch`] and block until the replies. Refused on the servo thread.
    pub fn call_batch(&self, commands: Vec<Command>) -> Result<Vec<Reply>, CallError> {
        self.call_request(|reply| Request::Batch { commands, reply })
    }

    /// Queue commands to be applied one after another, between the same two ticks, in order,
    /// each on its own: a refused command gets its error in its place and the others stand, as
    /// if each had been `submit`ted, but as one request (one publication, one reply; at most
    /// [`crate::engine::MAX_ATOMIC_COMMANDS`]). What a host refilling several axes' stream
    /// buffers at once wants: no rollback to prepare, unlike [`EngineHandle::submit_batch`].
    pub fn submit_each(
        &self,
        commands: Vec<Command>,
    ) -> Result<Pending<Vec<Result<Reply, EngineError>>, CallError>, SubmitError> {
        self.request(|reply| Request::Each { commands, reply })
    }

    /// [`EngineHandle::submit_each`] and block until the replies (served on the calling thread
    /// on the virtual clock, as [`EngineHandle::call`]). Refused on the servo thread.
    pub fn call_each(
        &self,
        commands: Vec<Command>,
    ) -> Result<Vec<Result<Reply, EngineError>>, CallError> {
        self.call_request(|reply| Request::Each { commands, reply })
    }

    /// [`EngineHandle::submit_each`] and await the replies (any executor).
    pub async fn call_each_async(
        &self,
        commands: Vec<Command>,
    ) -> Result<Vec<Result<Reply, EngineError>>, CallError> {
        self.submit_each(commands)?.await
    }

    /// [`EngineHandle::submit_batch`] and await the replies (any executor).
    pub async fn call_batch_async(&self, commands: Vec<Command>) -> Result<Vec<Reply>, CallError> {
        self.submit_batch(commands)?.await
    }

    /// Submit and block until the reply. Refused on the servo thread itself. Virtual clock: the
    /// caller serves the queue itself ([`EngineHandle::advance`]).
    pub fn call(&self, command: Command) -> Result<Reply, CallError> {
        self.call_request(|reply| Request::Command { command, reply })
    }

    /// Submit and await the reply (any executor).
    pub async fn call_async(&self, command: Command) -> Result<Reply, CallError> {
        self.submit(command)?.await
    }

    /// The latest published snapshot. Lock-free; never waits for the servo thread.
    pub fn snapshot(&self) -> Arc<Snapshot> {
        self.shared.snapshot.load_full()
    }

    /// The latest published statistics (a copy).
    pub fn stats(&self) -> RuntimeStats {
        RuntimeStats::clone(&self.shared.stats.load())
    }

    pub fn clock(&self) -> ClockMode {
        self.shared.clock
    }

    /// False once the servo thread has stopped (or died).
    pub fn is_running(&self) -> bool {
        self.shared.running.load(Ordering::Acquire)
    }

    /// Virtual clock: run `ticks` ticks, after everything queued before; returns the tick after.
    ///
    /// Like every blocking call on the virtual clock, it serves the queue on the calling thread
    /// (in order, its own request included) rather than wake the servo thread and sleep until
    /// the reply; conditions, observers and fieldbuses then run on this thread, under the lock
    /// the servo thread serves under. Non-blocking and async calls are served by the servo
    /// thread.
    pub fn advance(&self, ticks: u64) -> Result<u64, AdvanceError> {
        Ok(self.blocking_advance(ticks, None)?.tick)
    }

    fn blocking_advance(
        &self,
        ticks: u64,
        until: Option<Condition>,
    ) -> Result<Until, AdvanceError> {
        if self.shared.on_servo_thread() {
            return Err(AdvanceError::OnServoThread);
        }
        self.require_virtual()?;
        let (reply, pending) = reply_channel();
        self.enqueue_and_serve(Request::Advance {
            ticks,
            until,
            reply,
        })?;
        pending.wait()
    }

    fn require_virtual(&self) -> Result<(), AdvanceError> {
        match self.shared.clock {
            ClockMode::Virtual => Ok(()),
            clock => Err(AdvanceError::NotVirtual(clock)),
        }
    }

    pub async fn advance_async(&self, ticks: u64) -> Result<u64, AdvanceError> {
        Ok(self.submit_advance(ticks, None)?.await?.tick)
    }

    /// Virtual clock: run ticks until `condition` holds for the snapshot published after a tick,
    /// at most `max_ticks` ticks. The condition is not evaluated before the first tick, so it
    /// sees the effect of at least one step; `max_ticks = 0` returns at once, unmet.
    pub fn advance_until(
        &self,
        condition: impl Fn(&Snapshot) -> bool + Send + 'static,
        max_ticks: u64,
    ) -> Result<Until, AdvanceError> {
        self.blocking_advance(max_ticks, Some(Box::new(condition)))
    }

    pub async fn advance_until_async(
        &self,
        condition: impl Fn(&Snapshot) -> bool + Send + 'static,
        max_ticks: u64,
    ) -> Result<Until, AdvanceError> {
        self.submit_advance(max_ticks, Some(Box::new(condition)))?
            .await
    }

    /// Queue an advance without blocking.
    pub fn submit_advance(
        &self,
        ticks: u64,
        until: Option<Condition>,
    ) -> Result<Pending<Until, AdvanceError>, AdvanceError> {
        self.require_virtual()?;
        let pending = self.request(|reply| Request::Advance {
            ticks,
            until,
            reply,
        })?;
        Ok(pending)
    }

    /// Install `fieldbus`: from the next tick on, the servo thread serves it before and after
    /// every step, for as long as the runtime runs (a panic in it removes it). Queued like a
    /// command.
    pub fn submit_fieldbus(
        &self,
        fieldbus: Box<dyn Fieldbus>,
    ) -> Result<Pending<(), CallError>, SubmitError> {
        self.request(|reply| Request::AddFieldbus { fieldbus, reply })
    }

    /// [`EngineHandle::submit_fieldbus`] and block until it is installed.
    pub fn add_fieldbus(&self, fieldbus: impl Fieldbus + 'static) -> Result<(), CallError> {
        self.call_request(|reply| Request::AddFieldbus {
            fieldbus: Box::new(fieldbus),
            reply,
        })
    }

    /// Tell the servo thread that a fieldbus has input waiting; it serves its fieldbuses'
    /// input at once, between steps, at the current tick. A virtual runtime, which does not
    /// tick by itself, so answers a master's SDO while time stands still (the poke is queued
    /// in order with commands and advances). A paced one is woken from its sleep until the
    /// next deadline, so an SDO server answers as frames arrive rather than once per tick, as
    /// a drive's does (a 100 kB block transfer is ~120 request/answer round trips). Pokes
    /// coalesce: many before the servo thread wakes cost one service.
    pub fn poke(&self) {
        if self.shared.poked.swap(true, Ordering::AcqRel) {
            return; // a service is already due; it will see this input too
        }
        if self.shared.clock == ClockMode::Virtual {
            if self.tx.try_send(Request::Poke).is_err() {
                // Queue full: the requests in it get served anyway; let the next poke queue.
                self.shared.poked.store(false, Ordering::Release);
            } else {
                self.wake_virtual_servo();
            }
        } else if let Some(servo) = self.shared.servo_waker.get() {
            servo.unpark();
        }
    }

    /// Install `observer`: from the next tick on, the servo thread calls it with the engine right
    /// after every step (virtual, realtime and scaled alike, caught-up ticks included) until it
    /// returns `false` or is removed. It is how something sees every tick rather than polled
    /// snapshots (trace recording).
    ///
    /// It runs inside the tick, so it must be short (copy out what it needs) and must not block;
    /// blocking handle calls from it are refused (`OnServoThread`). A panic in it removes it;
    /// the runtime goes on. Queued like a command, so it is ordered with commands and advances.
    /// With no observer installed a tick pays one branch.
    pub fn submit_observer(
        &self,
        observer: Observer,
    ) -> Result<Pending<ObserverId, CallError>, SubmitError> {
        self.request(|reply| Request::Observe { observer, reply })
    }

    /// [`EngineHandle::submit_observer`] and block until it is installed.
    pub fn add_observer(
        &self,
        observer: impl FnMut(&Engine) -> bool + Send + 'static,
    ) -> Result<ObserverId, CallError> {
        self.call_request(|reply| Request::Observe {
            observer: Box::new(observer),
            reply,
        })
    }

    pub async fn add_observer_async(
        &self,
        observer: impl FnMut(&Engine) -> bool + Send + 'static,
    ) -> Result<ObserverId, CallError> {
        self.submit_observer(Box::new(observer))?.await
    }

    /// Remove an observer, ordered with commands and advances; the reply is `false` when it was
    /// already gone (it returned `false`, panicked, or was removed before).
    pub fn submit_remove_observer(
        &self,
        id: ObserverId,
    ) -> Result<Pending<bool, CallError>, SubmitError> {
        self.request(|reply| Request::RemoveObserver { id, reply })
    }

    /// [`EngineHandle::submit_remove_observer`] and block until it is done.
    pub fn remove_observer(&self, id: ObserverId) -> Result<bool, CallError> {
        self.call_request(|reply| Request::RemoveObserver { id, reply })
    }

    pub async fn remove_observer_async(&self, id: ObserverId) -> Result<bool, CallError> {
        self.submit_remove_observer(id)?.await
    }

    /// Queue the request `make` builds around its reply channel, without blocking.
    fn request<T, E: ReplyError>(
        &self,
        make: impl FnOnce(ReplySender<T, E>) -> Request,
    ) -> Result<Pending<T, E>, SubmitError> {
        let (reply, pending) = reply_channel();
        self.enqueue(make(reply))?;
        Ok(pending)
    }

    /// Queue the request `make` builds and block until its reply: refused on the servo thread,
    /// served on this thread on the virtual clock ([`EngineHandle::advance`]).
    fn call_request<T>(
        &self,
        make: impl FnOnce(ReplySender<T, CallError>) -> Request,
    ) -> Result<T, CallError> {
        if self.shared.on_servo_thread() {
            return Err(CallError::OnServoThread);
        }
        let (reply, pending) = reply_channel();
        self.enqueue_and_serve(make(reply))?;
        pending.wait()
    }

    /// Queue a request nobody waits on here: a virtual servo thread is woken to serve it.
    fn enqueue(&self, request: Request) -> Result<(), SubmitError> {
        self.send(request)?;
        self.wake_virtual_servo();
        Ok(())
    }

    /// Queue a request whose caller is about to block on its reply: on the virtual clock the
    /// caller serves the queue itself (`servo::serve_virtual`); a paced clock applies it at its
    /// next tick.
    fn enqueue_and_serve(&self, request: Request) -> Result<(), SubmitError> {
        self.send(request)?;
        if self.shared.clock == ClockMode::Virtual {
            servo::serve_virtual(&self.shared);
        }
        Ok(())
    }

    fn wake_virtual_servo(&self) {
        if self.shared.clock == ClockMode::Virtual {
            if let Some(servo) = self.shared.servo_waker.get() {
                servo.unpark();
            }
        }
    }

    fn send(&self, request: Request) -> Result<(), SubmitError> {
        if self.shared.stop.load(Ordering::Acquire) {
            return Err(SubmitError::Stopped);
        }
        match self.tx.try_send(request) {
            Ok(()) => Ok(()),
            Err(TrySendError::Full(_)) => Err(SubmitError::QueueFull {
                capacity: self.shared.queue_capacity,
            }),
            Err(TrySendError::Disconnected(_)) => Err(SubmitError::Stopped),
        }
    }
}

impl std::fmt::Debug for EngineHandle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EngineHandle")
            .field("clock", &self.shared.clock)
            .field("running", &self.is_running())
            .finish()
    }
}

/// Owns the servo thread: [`RuntimeGuard::stop`] stops it and returns the engine; dropping the
/// guard stops it too. Requests still queued then are answered `Stopped`.
pub struct RuntimeGuard {
    shared: Arc<Shared>,
    tx: SyncSender<Request>,
    /// Returns the engine, or `None` when a panic lost it.
    thread: Option<JoinHandle<Option<Engine>>>,
}

impl RuntimeGuard {
    /// Another handle to the running engine.
    pub fn handle(&self) -> EngineHandle {
        EngineHandle {
            shared: Arc::clone(&self.shared),
            tx: self.tx.clone(),
        }
    }

    /// Stop the servo thread after its current tick (or the current tick of an advance) and
    /// return the engine.
    pub fn stop(mut self) -> Result<Engine, RuntimeError> {
        self.stop_thread().ok_or(RuntimeError::ServoPanicked)
    }

    fn stop_thread(&mut self) -> Option<Engine> {
        let thread = self.thread.take()?;
        self.shared.stop.store(true, Ordering::Release);
        // A paced servo thread sleeps in `park_timeout`, a virtual one in `park`.
        thread.thread().unpark();
        thread.join().ok().flatten()
    }
}

impl Drop for RuntimeGuard {
    fn drop(&mut self) {
        let _ = self.stop_thread();
    }
}
