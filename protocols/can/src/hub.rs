//! The in-process bus: endpoints (the emulator's nodes, each transport) attach and get a
//! sender and a receiver; a frame one endpoint sends reaches every other endpoint.
//!
//! - Like a SocketCAN socket without `CAN_RAW_RECV_OWN_MSGS`, the sender does not receive its
//!   own frame unless it attached with [`EndpointOptions::receive_own`].
//! - Sending never blocks: each endpoint has a bounded receive queue, and a frame that finds
//!   it full is dropped for that endpoint and counted (a slow reader loses frames, as a CAN
//!   controller with a full receive FIFO does), never slowing the bus.
//! - Without a bit-rate model a frame is delivered during `send`. With one
//!   ([`HubConfig::timing`]) it waits for the bus, wins arbitration by id and arrives when its
//!   transmission ends; something must then run the bus: [`Hub::advance`] with a virtual clock,
//!   [`Hub::drive_realtime`] (a tokio task) with the real one.
//! - Receivers work synchronously ([`FrameReceiver::try_recv`], for a servo thread or a unit
//!   test) and asynchronously ([`FrameReceiver::recv`]).

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

use tokio::sync::mpsc::{self, error::TrySendError};
use tokio::sync::Notify;

use crate::clock::{Clock, Timestamp};
use crate::counters::{BusCounters, EndpointCounters};
pub use crate::endpoint::EndpointId;
use crate::frame::WireFrame;
use crate::log::{CandumpLog, LogSummary};
use crate::model::{BusModel, Transmitted, TxQueueFull};
use crate::timing::BitTiming;

/// Receive-queue length of an endpoint unless its options say otherwise.
pub const DEFAULT_QUEUE: usize = 1024;
/// Transmit-queue length of a bus with the bit-rate model.
pub const DEFAULT_TX_QUEUE: usize = 4096;

/// How a hub is set up.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HubConfig {
    /// The bus's name (`vcan0`): the interface column of its candump log, the bus name that
    /// socketcand clients open.
    pub name: String,
    pub clock: Clock,
    /// Default receive-queue length of each endpoint.
    pub queue_capacity: usize,
    /// The bit-rate model; `None` (the default) delivers every frame at once.
    pub timing: Option<BitTiming>,
    /// Transmit-queue length with the bit-rate model.
    pub tx_queue: usize,
    /// Wall-clock time of bus time 0 (since the Unix epoch), for log and socketcand stamps;
    /// `None`: when the hub is created.
    pub epoch: Option<Duration>,
}

impl HubConfig {
    /// Real clock, no bit-rate model, default queues.
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            clock: Clock::Real,
            queue_capacity: DEFAULT_QUEUE,
            timing: None,
            tx_queue: DEFAULT_TX_QUEUE,
            epoch: None,
        }
    }

    pub fn with_clock(self, clock: Clock) -> Self {
        Self { clock, ..self }
    }

    pub fn with_timing(self, timing: BitTiming) -> Self {
        Self {
            timing: Some(timing),
            ..self
        }
    }

    pub fn with_queue_capacity(self, queue_capacity: usize) -> Self {
        Self {
            queue_capacity,
            ..self
        }
    }

    pub fn with_epoch(self, epoch: Duration) -> Self {
        Self {
            epoch: Some(epoch),
            ..self
        }
    }
}

/// Called after a frame is queued for an endpoint (by the thread that delivered it, with the
/// hub locked: it must be short and must not touch the hub). It is how a reader that does not
/// await its endpoint, such as the servo thread polling it, learns that a frame is waiting.
#[derive(Clone)]
pub struct OnDelivery(pub Arc<dyn Fn() + Send + Sync>);

impl std::fmt::Debug for OnDelivery {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("OnDelivery")
    }
}

impl PartialEq for OnDelivery {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl Eq for OnDelivery {}

/// How an endpoint attaches.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EndpointOptions {
    /// For counters and logs (`node 5`, `socketcand 127.0.0.1:40012`).
    pub name: String,
    /// Also receive the frames this endpoint sends (SocketCAN's `CAN_RAW_RECV_OWN_MSGS`).
    pub receive_own: bool,
    /// Receive-queue length; `None`: the hub's default.
    pub queue_capacity: Option<usize>,
    pub on_delivery: Option<OnDelivery>,
}

impl EndpointOptions {
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            receive_own: false,
            queue_capacity: None,
            on_delivery: None,
        }
    }

    pub fn on_delivery(self, f: impl Fn() + Send + Sync + 'static) -> Self {
        Self {
            on_delivery: Some(OnDelivery(Arc::new(f))),
            ..self
        }
    }

    pub fn receive_own(self, receive_own: bool) -> Self {
        Self {
            receive_own,
            ..self
        }
    }

    pub fn queue_capacity(self, capacity: usize) -> Self {
        Self {
            queue_capacity: Some(capacity),
            ..self
        }
    }
}

/// A frame as an endpoint receives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Delivery {
    pub frame: WireFrame,
    /// Bus time at which the frame was complete on the bus.
    pub at: Duration,
    pub source: EndpointId,
}

/// A bus. Cheap to clone (a handle); `Send + Sync`.
#[derive(Clone)]
pub struct Hub {
    shared: Arc<Shared>,
}

struct Shared {
    name: String,
    clock: Clock,
    epoch: Duration,
    origin: Instant,
    queue_capacity: usize,
    state: Mutex<State>,
    /// Wakes the real-time driver when a frame is queued for the bus.
    wake: Notify,
}

struct Slot {
    id: EndpointId,
    name: String,
    receive_own: bool,
    tx: mpsc::Sender<Delivery>,
    on_delivery: Option<OnDelivery>,
    sent: u64,
    received: u64,
    dropped: u64,
}

#[derive(Default)]
struct Totals {
    frames: u64,
    data_bytes: u64,
    error_frames: u64,
    rx_dropped: u64,
    tx_overflow: u64,
    /// Drops of logs already finished.
    log_dropped: u64,
    latency_max: Duration,
    latency_total: Duration,
}

struct State {
    slots: Vec<Slot>,
    next_id: u64,
    model: Option<BusModel<EndpointId>>,
    log: Option<CandumpLog>,
    /// Bus time: set by `advance` (virtual), or the latest reading of the real clock.
    now: Duration,
    totals: Totals,
}

impl Hub {
    pub fn new(config: HubConfig) -> Self {
        let model = config
            .timing
            .map(|timing| BusModel::new(timing, config.tx_queue));
        Self {
            shared: Arc::new(Shared {
                name: config.name,
                clock: config.clock,
                epoch: config.epoch.unwrap_or_else(Timestamp::now_epoch),
                origin: Instant::now(),
                queue_capacity: config.queue_capacity.max(1),
                state: Mutex::new(State {
                    slots: Vec::new(),
                    next_id: 0,
                    model,
                    log: None,
                    now: Duration::ZERO,
                    totals: Totals::default(),
                }),
                wake: Notify::new(),
            }),
        }
    }

    pub fn name(&self) -> &str {
        &self.shared.name
    }

    pub fn clock(&self) -> Clock {
        self.shared.clock
    }

    /// The bit-rate model's timing, if it is on.
    pub fn timing(&self) -> Option<BitTiming> {
        self.lock().model.as_ref().map(BusModel::timing)
    }

    /// Attach an endpoint.
    pub fn attach(&self, options: EndpointOptions) -> Endpoint {
        let capacity = options
            .queue_capacity
            .unwrap_or(self.shared.queue_capacity)
            .max(1);
        let (tx, rx) = mpsc::channel(capacity);
        let mut state = self.lock();
        state.next_id += 1;
        let id = EndpointId(state.next_id);
        state.slots.push(Slot {
            id,
            name: options.name,
            receive_own: options.receive_own,
            tx,
            on_delivery: options.on_delivery,
            sent: 0,
            received: 0,
            dropped: 0,
        });
        drop(state);
        Endpoint {
            sender: FrameSender {
                hub: self.clone(),
                id,
            },
            receiver: FrameReceiver {
                hub: self.clone(),
                id,
                rx,
            },
        }
    }

    /// Bus time now.
    pub fn now(&self) -> Duration {
        let mut state = self.lock();
        self.read_clock(&mut state)
    }

    /// The wall-clock stamp of bus time `at`.
    pub fn stamp(&self, at: Duration) -> Timestamp {
        Timestamp::at(self.shared.epoch, at)
    }

    /// Move a virtual clock to `now` (never backwards) and deliver every frame whose
    /// transmission has ended by then. With the real clock `now` is ignored and the real time
    /// is used. Returns when the next transmission will end, if one is waiting.
    pub fn advance(&self, now: Duration) -> Option<Duration> {
        let mut state = self.lock();
        if self.shared.clock == Clock::Virtual {
            state.now = state.now.max(now);
        }
        let now = self.read_clock(&mut state);
        self.run_bus(&mut state, now)
    }

    /// Run the bit-rate model in real time: deliver each frame when its transmission ends.
    /// Needed (spawned as a tokio task) only with the real clock and a bit-rate model; returns
    /// at once otherwise. Runs until the task is dropped or aborted. Delivery is as punctual as
    /// tokio's timer (about 1 ms); the delivered `at` stamps are exact.
    pub async fn drive_realtime(&self) {
        if self.shared.clock != Clock::Real || self.timing().is_none() {
            return;
        }
        loop {
            let next = self.advance(Duration::ZERO);
            match next {
                Some(at) => {
                    tokio::select! {
                        () = tokio::time::sleep_until((self.shared.origin + at).into()) => {}
                        () = self.shared.wake.notified() => {}
                    }
                }
                None => self.shared.wake.notified().await,
            }
        }
    }

    /// A snapshot of the counters.
    pub fn counters(&self) -> BusCounters {
        let mut state = self.lock();
        let elapsed = self.read_clock(&mut state);
        let t = &state.totals;
        BusCounters {
            frames: t.frames,
            data_bytes: t.data_bytes,
            error_frames: t.error_frames,
            rx_dropped: t.rx_dropped,
            tx_overflow: t.tx_overflow,
            log_dropped: t.log_dropped + state.log.as_ref().map_or(0, CandumpLog::dropped),
            pending: state.model.as_ref().map_or(0, BusModel::pending),
            busy: state.model.as_ref().map_or(Duration::ZERO, BusModel::busy),
            elapsed,
            latency_max: t.latency_max,
            latency_total: t.latency_total,
            endpoints: state
                .slots
                .iter()
                .map(|s| EndpointCounters {
                    id: s.id,
                    name: s.name.clone(),
                    sent: s.sent,
                    received: s.received,
                    dropped: s.dropped,
                })
                .collect(),
        }
    }

    /// Log every frame from now on, replacing (and finishing) a previous log.
    pub fn start_log(&self, log: CandumpLog) -> Option<std::io::Result<LogSummary>> {
        let previous = self.lock().log.replace(log);
        previous.map(|old| self.finish_log(old))
    }

    /// Stop logging; the log's writer flushes and ends. `None` when no log was running.
    pub fn stop_log(&self) -> Option<std::io::Result<LogSummary>> {
        let log = self.lock().log.take();
        log.map(|log| self.finish_log(log))
    }

    fn finish_log(&self, log: CandumpLog) -> std::io::Result<LogSummary> {
        let summary = log.finish()?;
        self.lock().totals.log_dropped += summary.dropped;
        Ok(summary)
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        // A panic elsewhere while holding the lock leaves counters at worst half-updated:
        // keep the bus running.
        self.shared
            .state
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    fn read_clock(&self, state: &mut State) -> Duration {
        if self.shared.clock == Clock::Real {
            state.now = state.now.max(self.shared.origin.elapsed());
        }
        state.now
    }

    fn send(&self, source: EndpointId, frame: WireFrame) -> Result<(), TxQueueFull> {
        let mut state = self.lock();
        let now = self.read_clock(&mut state);
        if let Some(slot) = state.slots.iter_mut().find(|s| s.id == source) {
            slot.sent += 1;
        }
        // Error frames are controller reports, not transmissions: they take no bus time.
        let queued = match state.model.as_mut() {
            Some(model) if !frame.is_error() => Some(model.enqueue(frame, source, now)),
            _ => None,
        };
        match queued {
            None => {
                self.deliver(&mut state, frame, source, now, now);
                Ok(())
            }
            Some(Err(full)) => {
                state.totals.tx_overflow += 1;
                Err(full)
            }
            Some(Ok(())) => {
                self.run_bus(&mut state, now);
                drop(state);
                self.shared.wake.notify_one();
                Ok(())
            }
        }
    }

    fn run_bus(&self, state: &mut State, now: Duration) -> Option<Duration> {
        let mut model = state.model.take()?;
        let next = model.advance(now, |t: Transmitted<EndpointId>| {
            self.deliver(state, t.frame, t.tag, t.end, t.queued_at);
        });
        state.model = Some(model);
        next
    }

    fn deliver(
        &self,
        state: &mut State,
        frame: WireFrame,
        source: EndpointId,
        at: Duration,
        queued_at: Duration,
    ) {
        let totals = &mut state.totals;
        totals.frames += 1;
        totals.data_bytes += frame.data().len() as u64;
        totals.error_frames += u64::from(frame.is_error());
        let latency = at.saturating_sub(queued_at);
        totals.latency_max = totals.latency_max.max(latency);
        totals.latency_total += latency;
        if let Some(log) = &state.log {
            log.record(self.stamp(at), &frame);
        }
        let delivery = Delivery { frame, at, source };
        for slot in &mut state.slots {
            if slot.id == source && !slot.receive_own {
                continue;
            }
            match slot.tx.try_send(delivery) {
                Ok(()) => {
                    slot.received += 1;
                    if let Some(f) = &slot.on_delivery {
                        (f.0)();
                    }
                }
                Err(TrySendError::Full(_)) => {
                    slot.dropped += 1;
                    totals.rx_dropped += 1;
                }
                // Its receiver is being dropped and will detach it.
                Err(TrySendError::Closed(_)) => {}
            }
        }
    }

    fn detach(&self, id: EndpointId) {
        self.lock().slots.retain(|s| s.id != id);
    }
}

impl std::fmt::Debug for Hub {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Hub")
            .field("name", &self.shared.name)
            .field("clock", &self.shared.clock)
            .finish_non_exhaustive()
    }
}

/// An attached endpoint: its sender and receiver together.
#[derive(Debug)]
pub struct Endpoint {
    sender: FrameSender,
    receiver: FrameReceiver,
}

impl Endpoint {
    pub fn id(&self) -> EndpointId {
        self.sender.id
    }

    pub fn hub(&self) -> &Hub {
        &self.sender.hub
    }

    /// See [`FrameSender::send`].
    pub fn send(&self, frame: WireFrame) -> Result<(), TxQueueFull> {
        self.sender.send(frame)
    }

    /// See [`FrameReceiver::try_recv`].
    pub fn try_recv(&mut self) -> Option<Delivery> {
        self.receiver.try_recv()
    }

    /// See [`FrameReceiver::recv`].
    pub async fn recv(&mut self) -> Option<Delivery> {
        self.receiver.recv().await
    }

    /// Separate halves, e.g. for a reader task and a writer task.
    pub fn split(self) -> (FrameSender, FrameReceiver) {
        (self.sender, self.receiver)
    }
}

/// Sends frames onto the bus as one endpoint. Cloneable.
#[derive(Clone)]
pub struct FrameSender {
    hub: Hub,
    id: EndpointId,
}

impl FrameSender {
    pub fn id(&self) -> EndpointId {
        self.id
    }

    pub fn hub(&self) -> &Hub {
        &self.hub
    }

    /// Put `frame` on the bus; never blocks. Fails only with the bit-rate model, when the
    /// bus's transmit queue is full (the frame is dropped and counted).
    pub fn send(&self, frame: WireFrame) -> Result<(), TxQueueFull> {
        self.hub.send(self.id, frame)
    }
}

impl std::fmt::Debug for FrameSender {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "FrameSender({} on {})", self.id, self.hub.name())
    }
}

/// Receives the frames other endpoints send. Dropping it detaches the endpoint.
pub struct FrameReceiver {
    hub: Hub,
    id: EndpointId,
    rx: mpsc::Receiver<Delivery>,
}

impl FrameReceiver {
    pub fn id(&self) -> EndpointId {
        self.id
    }

    pub fn hub(&self) -> &Hub {
        &self.hub
    }

    /// The next queued frame, if any; never blocks, needs no runtime.
    pub fn try_recv(&mut self) -> Option<Delivery> {
        self.rx.try_recv().ok()
    }

    /// Wait for the next frame. `None` only if the endpoint was detached.
    pub async fn recv(&mut self) -> Option<Delivery> {
        self.rx.recv().await
    }
}

impl Drop for FrameReceiver {
    fn drop(&mut self) {
        self.hub.detach(self.id);
    }
}

impl std::fmt::Debug for FrameReceiver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "FrameReceiver({} on {})", self.id, self.hub.name())
    }
}
