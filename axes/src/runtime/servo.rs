//! The servo thread: owns the engine, drains the queue, steps, publishes.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::Ordering;
use std::sync::mpsc::{Receiver, TryRecvError};
use std::sync::{Arc, PoisonError};
use std::time::Duration;

use arc_swap::ArcSwap;

use super::{
    AdvanceError, CallError, Clock, Condition, Fieldbus, Observer, ObserverId, ReplySender,
    RuntimeOptions, RuntimeStats, Shared, Until,
};
use crate::command::{Command, EngineError, Reply};
use crate::engine::Engine;
use crate::engine::MAX_ATOMIC_COMMANDS;
use crate::status::Snapshot;

pub(super) enum Request {
    Command {
        command: Command,
        reply: ReplySender<Reply, CallError>,
    },
    /// Commands applied in one go, between the same two ticks, all or none
    /// ([`Engine::apply_batch`]).
    Batch {
        commands: Vec<Command>,
        reply: ReplySender<Vec<Reply>, CallError>,
    },
    /// Commands applied one after another between the same two ticks, each on its own (a
    /// refusal is that command's reply; the others stand), answered together.
    Each {
        commands: Vec<Command>,
        reply: ReplySender<Vec<Result<Reply, EngineError>>, CallError>,
    },
    Advance {
        ticks: u64,
        until: Option<Condition>,
        reply: ReplySender<Until, AdvanceError>,
    },
    Observe {
        observer: Observer,
        reply: ReplySender<ObserverId, CallError>,
    },
    RemoveObserver {
        id: ObserverId,
        reply: ReplySender<bool, CallError>,
    },
    AddFieldbus {
        fieldbus: Box<dyn Fieldbus>,
        reply: ReplySender<(), CallError>,
    },
    /// A fieldbus has input waiting: a virtual runtime serves it at the current tick.
    Poke,
}

/// A virtual-clock advance without a condition publishes the snapshot after every this many
/// ticks and after its last.
const ADVANCE_PUBLISH_STRIDE: u64 = 64;

/// Publishes values through an `ArcSwap`, refilling the buffer it got back from the previous
/// swap when no reader holds it any more: steady state allocates nothing.
struct Publisher<T> {
    spare: Option<Arc<T>>,
    allocations: u64,
}

impl<T: Clone + Default> Publisher<T> {
    fn new() -> Publisher<T> {
        Publisher {
            spare: None,
            allocations: 0,
        }
    }

    fn publish(&mut self, target: &ArcSwap<T>, fill: impl FnOnce(&mut T)) {
        let mut next = match self.spare.take() {
            Some(spare) => spare,
            None => {
                self.allocations += 1;
                Arc::new(T::default())
            }
        };
        if Arc::get_mut(&mut next).is_none() {
            self.allocations += 1; // a reader still holds it: make_mut clones
        }
        fill(Arc::make_mut(&mut next));
        self.spare = Some(target.swap(next));
    }
}

/// Absolute deadlines of a paced clock: tick n (n ≥ 1 since start) is due at
/// start + round(n × wall period), computed from n each time so no error accumulates.
#[derive(Clone, Copy, Debug)]
pub(super) struct Schedule {
    start: Duration,
    wall_period_ns: f64,
}

impl Schedule {
    pub(super) fn new(start: Duration, wall_period: f64) -> Schedule {
        Schedule {
            start,
            wall_period_ns: wall_period * 1e9,
        }
    }

    pub(super) fn deadline(&self, n: u64) -> Duration {
        let offset = (n as f64 * self.wall_period_ns).round() as u64; // saturating cast
        self.start.saturating_add(Duration::from_nanos(offset))
    }

    /// The largest n whose deadline is ≤ `now` (0 when none).
    pub(super) fn due_through(&self, now: Duration) -> u64 {
        let elapsed = now.saturating_sub(self.start).as_nanos() as f64;
        let mut n = (elapsed / self.wall_period_ns).floor() as u64;
        // The division and the rounded product can disagree by one at an edge.
        while self.deadline(n.saturating_add(1)) <= now && n < u64::MAX {
            n += 1;
        }
        while n > 0 && self.deadline(n) > now {
            n -= 1;
        }
        n
    }
}

/// A reply waiting for the snapshot that includes its effect.
enum HeldReply {
    One(ReplySender<Reply, CallError>, Result<Reply, CallError>),
    Batch(
        ReplySender<Vec<Reply>, CallError>,
        Result<Vec<Reply>, CallError>,
    ),
    Each(
        ReplySender<Vec<Result<Reply, EngineError>>, CallError>,
        Result<Vec<Result<Reply, EngineError>>, CallError>,
    ),
}

/// The virtual clock's servo state, behind `Shared::core`'s lock: whoever holds the lock serves
/// the queue. A virtual clock needs no clock.
pub(super) type VirtualServo = Servo<Unpaced>;

/// The clock of a [`VirtualServo`]: never read (bus time is engine time on the virtual clock).
pub(super) struct Unpaced;

impl Clock for Unpaced {
    fn now(&self) -> Duration {
        Duration::ZERO
    }

    fn sleep_until(&self, _deadline: Duration) {}
}

std::thread_local! {
    /// The runtimes whose queue this thread is serving now (innermost last), as `Shared`
    /// addresses: a blocking call to one of them from inside (a condition, an observer, a
    /// fieldbus) would wait for itself, and is refused instead.
    static SERVING: std::cell::RefCell<Vec<usize>> = const { std::cell::RefCell::new(Vec::new()) };
}

fn shared_id(shared: &Shared) -> usize {
    std::ptr::from_ref(shared) as usize
}

/// Whether this thread is serving `shared`'s queue right now.
pub(super) fn serving(shared: &Shared) -> bool {
    let id = shared_id(shared);
    SERVING.with(|s| s.borrow().contains(&id))
}

/// Marks this thread as serving a runtime's queue for as long as it lives.
struct ServingMark;

impl ServingMark {
    fn enter(shared: &Shared) -> ServingMark {
        SERVING.with(|s| s.borrow_mut().push(shared_id(shared)));
        ServingMark
    }
}

impl Drop for ServingMark {
    fn drop(&mut self) {
        SERVING.with(|s| s.borrow_mut().pop());
    }
}

/// Virtual clock: serve the queue on this thread, everything in it in order, the caller's own
/// request included. A blocking caller does this instead of waking the servo thread and
/// sleeping until its reply (two thread wake-ups, ~20 µs each on an idle VM: more than a
/// 32-tick advance of 8 axes; decisions.md, "PT streams through the runtime"). Blocks while
/// another thread serves; returns at once once the runtime has stopped. The requests are taken
/// off the queue only under the lock, so the queue's order is the order they are served in.
///
/// A panic in the engine loses it as a dying servo thread did: the state is dropped (every
/// queued request is answered `Stopped`), the runtime stops running and `RuntimeGuard::stop`
/// reports `ServoPanicked`.
pub(super) fn serve_virtual(shared: &Shared) {
    let mut core = shared.core.lock().unwrap_or_else(PoisonError::into_inner);
    let Some(servo) = core.as_mut() else {
        return;
    };
    let _mark = ServingMark::enter(shared);
    if catch_unwind(AssertUnwindSafe(|| servo.serve_queue())).is_err() {
        *core = None;
        shared.running.store(false, Ordering::Release);
    }
}

/// The virtual clock's servo thread: serves what non-blocking callers queue (they unpark it),
/// sleeps in between, and at a stop takes the state out of the lock and gives the engine back
/// (`None` when the engine was lost to a panic).
pub(super) fn run_virtual(shared: Arc<Shared>) -> Option<Engine> {
    let _ = shared.servo_thread.set(std::thread::current().id());
    let _ = shared.servo_waker.set(std::thread::current());
    let running = RunningFlag(Arc::clone(&shared));
    // A request queued before the waker was set is served by the first pass; one queued after
    // a pass found the queue empty unparks the thread, so the park returns at once. The stop's
    // unpark may have been used up by a park inside the pass (a condition waiting on a
    // channel), hence the check between the pass and the park.
    loop {
        serve_virtual(&shared);
        if shared.stop.load(Ordering::Acquire) || !shared.running.load(Ordering::Acquire) {
            break;
        }
        std::thread::park();
    }
    drop(running);
    let servo = shared
        .core
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .take()?;
    Some(servo.finish())
}

/// Which side of a step a fieldbus is served on.
#[derive(Clone, Copy)]
enum Phase {
    Input,
    Output,
}

pub(super) struct Servo<C> {
    engine: Engine,
    rx: Receiver<Request>,
    shared: Arc<Shared>,
    clock: C,
    max_commands_per_tick: usize,
    max_catch_up_ticks: u64,
    snapshots: Publisher<Snapshot>,
    stats_publisher: Publisher<RuntimeStats>,
    stats: RuntimeStats,
    /// Replies held back until the snapshot with their effect is published.
    replies: Vec<HeldReply>,
    /// Called after every step, in installation order.
    observers: Vec<(ObserverId, Observer)>,
    next_observer: u64,
    /// Served around every step, in installation order.
    fieldbuses: Vec<Box<dyn Fieldbus>>,
    /// Paced clocks: how bus time is derived from the clock ([`Fieldbus`]); `None` on the
    /// virtual clock, where bus time is engine time.
    bus_origin: Option<BusOrigin>,
}

/// Bus time on a paced clock: `engine_start + (clock.now() - wall_start) × scale`.
#[derive(Clone, Copy, Debug)]
struct BusOrigin {
    wall_start: Duration,
    engine_start: Duration,
    /// Engine seconds per wall second (the scaled clock's k; 1 in real time).
    scale: f64,
}

/// Stats are published at least every this many ticks of a catch-up batch, so readers do not
/// see figures a whole batch old.
const STATS_EVERY_TICKS: u64 = 64;

/// Clears `running` when the servo thread ends, by return or by unwinding.
struct RunningFlag(Arc<Shared>);

impl Drop for RunningFlag {
    fn drop(&mut self) {
        self.0.running.store(false, Ordering::Release);
    }
}

impl<C: Clock> Servo<C> {
    pub(super) fn new(
        engine: Engine,
        rx: Receiver<Request>,
        shared: Arc<Shared>,
        clock: C,
        options: &RuntimeOptions,
    ) -> Servo<C> {
        let stats = RuntimeStats::new(options.clock, engine.period(), engine.tick());
        Servo {
            engine,
            rx,
            shared,
            clock,
            max_commands_per_tick: options.max_commands_per_tick,
            max_catch_up_ticks: options.max_catch_up_ticks,
            snapshots: Publisher::new(),
            stats_publisher: Publisher::new(),
            stats,
            replies: Vec::with_capacity(options.max_commands_per_tick.min(4096)),
            observers: Vec::new(),
            next_observer: 1,
            fieldbuses: Vec::new(),
            bus_origin: None,
        }
    }

    /// The paced servo thread: ticks on `clock` until stopped, then gives the engine back.
    pub(super) fn run(mut self) -> Option<Engine> {
        let _ = self.shared.servo_thread.set(std::thread::current().id());
        let _ = self.shared.servo_waker.set(std::thread::current());
        let running = RunningFlag(Arc::clone(&self.shared));
        if let Some(wall_period) = self.shared.clock.wall_period(self.engine.period()) {
            self.run_paced(wall_period);
        }
        drop(running);
        Some(self.finish())
    }

    /// Publishes the final statistics and returns the engine. Dropping the queue answers every
    /// request still in it `Stopped` (ReplySender::drop), including any that races in after.
    fn finish(mut self) -> Engine {
        self.publish_stats();
        let Servo { engine, rx, .. } = self;
        drop(rx);
        engine
    }

    fn stopping(&self) -> bool {
        self.shared.stop.load(Ordering::Acquire)
    }

    // ---- virtual clock -------------------------------------------------------------------

    /// Serves every request in the queue, in order, at the current tick (advances included),
    /// until it is empty or a stop is requested; a request taken off the queue after the stop
    /// is dropped, so its caller gets `Stopped`. Called with the virtual core's lock held, by
    /// the servo thread or by a blocking caller ([`serve_virtual`]).
    fn serve_queue(&mut self) {
        // A request taken off the queue while applying a run of commands, served next.
        let mut carried: Option<Request> = None;
        loop {
            let request = match carried.take() {
                Some(request) => request,
                None => match self.rx.try_recv() {
                    Ok(request) => request,
                    Err(TryRecvError::Empty | TryRecvError::Disconnected) => return,
                },
            };
            if self.stopping() {
                return; // `request` is dropped: its caller gets `Stopped`
            }
            match request {
                request @ (Request::Command { .. }
                | Request::Batch { .. }
                | Request::Each { .. }) => {
                    carried = self.apply_queued_commands(request);
                }
                Request::Advance {
                    ticks,
                    until,
                    reply,
                } => {
                    let result = self.advance(ticks, until.as_ref());
                    self.publish_stats();
                    reply.send(result);
                }
                Request::Observe { observer, reply } => self.observe(observer, reply),
                Request::RemoveObserver { id, reply } => self.remove_observer(id, reply),
                Request::AddFieldbus { fieldbus, reply } => {
                    self.fieldbuses.push(fieldbus);
                    reply.send(Ok(()));
                }
                Request::Poke => {
                    // Time stands still: what arrived is served at the current tick, and what
                    // it changed is published. Input arriving from now on needs a new poke.
                    self.shared.poked.store(false, Ordering::Release);
                    self.serve_poke();
                }
            }
        }
    }

    /// Applies `first` and the commands queued right behind it, all at the current tick, then
    /// publishes one snapshot and sends their replies (each still after a snapshot with its
    /// effect). A host refilling 8 streams sent 8 pushes in a row, each paying a snapshot of
    /// every axis (decisions.md, "PT streams through the runtime"). Returns the first other
    /// request taken off the queue, to be served next.
    fn apply_queued_commands(&mut self, first: Request) -> Option<Request> {
        let mut request = first;
        let mut applied = 0;
        let carried = loop {
            match request {
                Request::Command { command, reply } => self.apply(command, reply),
                Request::Batch { commands, reply } => self.apply_batch(commands, reply),
                Request::Each { commands, reply } => self.apply_each(commands, reply),
                other => break Some(other),
            }
            applied += 1;
            if applied >= self.max_commands_per_tick || self.stopping() {
                break None;
            }
            match self.rx.try_recv() {
                Ok(next) => request = next,
                Err(TryRecvError::Empty | TryRecvError::Disconnected) => break None,
            }
        };
        self.publish_snapshot();
        self.publish_stats();
        self.send_replies();
        carried
    }

    fn advance(&mut self, ticks: u64, until: Option<&Condition>) -> Result<Until, AdvanceError> {
        // Without a condition nothing on this thread reads the snapshot between ticks, and a
        // reader on another thread sees whichever tick it races to anyway: publish every
        // ADVANCE_PUBLISH_STRIDE ticks (live views keep moving) and after the last one, not
        // after each (it cost as much as a third of a tick; decisions.md, "PT streams").
        for done in 1..=ticks {
            if self.stopping() {
                self.publish_snapshot();
                return Err(AdvanceError::Submit(super::SubmitError::Stopped));
            }
            let publish = until.is_some() || done % ADVANCE_PUBLISH_STRIDE == 0 || done == ticks;
            self.step_and_publish(publish);
            if let Some(condition) = until {
                let snapshot = self.shared.snapshot.load();
                // The condition is the caller's code: a panic in it fails this advance, not the
                // runtime (it only saw a shared reference, so the engine is intact).
                match catch_unwind(AssertUnwindSafe(|| condition(&snapshot))) {
                    Ok(true) => {
                        return Ok(Until {
                            met: true,
                            tick: self.engine.tick(),
                        })
                    }
                    Ok(false) => {}
                    Err(_) => {
                        return Err(AdvanceError::ConditionPanicked {
                            tick: self.engine.tick(),
                        })
                    }
                }
            }
        }
        Ok(Until {
            met: false,
            tick: self.engine.tick(),
        })
    }

    // ---- paced clocks (realtime, scaled) ---------------------------------------------------

    fn run_paced(&mut self, wall_period: f64) {
        let schedule = Schedule::new(self.clock.now(), wall_period);
        self.bus_origin = Some(BusOrigin {
            wall_start: schedule.start,
            engine_start: self.engine_time(),
            scale: self.engine.period() / wall_period,
        });
        self.paced_loop(&schedule);
        // A stop can come in mid-batch: the final statistics get a drift of their own.
        self.update_drift(&schedule);
    }

    /// Runs batches of ticks on `schedule` until a stop is requested.
    fn paced_loop(&mut self, schedule: &Schedule) {
        let wall_period = Duration::from_nanos(schedule.wall_period_ns.round() as u64);
        // Ticks accounted for since start: run or dropped.
        let mut scheduled: u64 = 0;
        loop {
            let deadline = schedule.deadline(scheduled.saturating_add(1));
            let mut now = self.clock.now();
            if now < deadline {
                while now < deadline {
                    if self.stopping() {
                        return;
                    }
                    // Input that arrived while the thread slept is served now, not at the
                    // deadline (EngineHandle::poke).
                    if self.shared.poked.swap(false, Ordering::AcqRel) {
                        self.serve_poke();
                    }
                    self.clock.sleep_until(deadline);
                    now = self.clock.now();
                }
                self.stats.lateness.record(now - deadline);
            }
            if self.stopping() {
                return;
            }
            let due = schedule.due_through(now).saturating_sub(scheduled).max(1);
            let missed = due - 1;
            let caught_up = missed.min(self.max_catch_up_ticks);
            self.stats.dropped_ticks += missed - caught_up;
            scheduled = scheduled.saturating_add(due);
            for n in 0..=caught_up {
                if self.stopping() {
                    return;
                }
                self.paced_tick(wall_period);
                // Counted as run, so a stop in mid-batch keeps caught_up ⊆ ticks_run.
                if n > 0 {
                    self.stats.caught_up_ticks += 1;
                    if n % STATS_EVERY_TICKS == 0 {
                        self.update_drift(schedule);
                        self.publish_stats();
                    }
                }
            }
            self.update_drift(schedule);
            self.publish_stats();
        }
    }

    fn update_drift(&mut self, schedule: &Schedule) {
        let elapsed = self.clock.now().saturating_sub(schedule.start);
        self.stats.elapsed = elapsed.as_secs_f64();
        self.stats.drift = (self.stats.ticks_run as f64
            - elapsed.as_nanos() as f64 / schedule.wall_period_ns)
            * self.engine.period();
    }

    fn paced_tick(&mut self, wall_period: Duration) {
        let started = self.clock.now();
        let mut applied = 0;
        while applied < self.max_commands_per_tick {
            match self.rx.try_recv() {
                Ok(Request::Command { command, reply }) => {
                    self.apply(command, reply);
                    applied += 1;
                }
                // A batch counts as one request: its size is bounded by MAX_ATOMIC_COMMANDS.
                Ok(Request::Batch { commands, reply }) => {
                    self.apply_batch(commands, reply);
                    applied += 1;
                }
                Ok(Request::Each { commands, reply }) => {
                    self.apply_each(commands, reply);
                    applied += 1;
                }
                Ok(Request::Advance { reply, .. }) => {
                    reply.send(Err(AdvanceError::NotVirtual(self.shared.clock)));
                }
                Ok(Request::Observe { observer, reply }) => self.observe(observer, reply),
                Ok(Request::RemoveObserver { id, reply }) => self.remove_observer(id, reply),
                Ok(Request::AddFieldbus { fieldbus, reply }) => {
                    self.fieldbuses.push(fieldbus);
                    reply.send(Ok(()));
                }
                // The next step serves it.
                Ok(Request::Poke) => {}
                // Disconnected: the guard is gone, so the stop flag is set.
                Err(TryRecvError::Empty | TryRecvError::Disconnected) => break,
            }
        }
        if applied == self.max_commands_per_tick {
            self.stats.command_bound_hits += 1;
        }
        // The step serves whatever input is waiting.
        self.shared.poked.store(false, Ordering::Release);
        self.step();
        self.send_replies();
        let busy = self.clock.now().saturating_sub(started);
        if busy > wall_period {
            self.stats.overruns += 1;
        }
        self.stats.max_tick_time = self.stats.max_tick_time.max(busy.as_secs_f64());
    }

    // ---- common ----------------------------------------------------------------------------

    /// One engine step with its fieldbuses around it, its observers, its snapshot.
    fn step(&mut self) {
        self.step_and_publish(true);
    }

    /// One tick; the snapshot is published after it when `publish`.
    fn step_and_publish(&mut self, publish: bool) {
        if !self.fieldbuses.is_empty() {
            self.serve_fieldbuses(Phase::Input);
        }
        self.engine.step();
        if !self.fieldbuses.is_empty() {
            self.serve_fieldbuses(Phase::Output);
        }
        self.stats.ticks_run += 1;
        if !self.observers.is_empty() {
            self.notify_observers();
        }
        if publish {
            self.publish_snapshot();
        }
    }

    /// Serve the fieldbuses' waiting input between steps, at the current tick, and publish
    /// what it changed.
    fn serve_poke(&mut self) {
        if !self.fieldbuses.is_empty() {
            self.serve_fieldbuses(Phase::Input);
            self.publish_snapshot();
        }
    }

    /// Engine time of the current tick, in integer nanoseconds (exact multiples of the period).
    fn engine_time(&self) -> Duration {
        let period_ns = (self.engine.period() * 1e9).round() as u64;
        Duration::from_nanos(self.engine.tick().saturating_mul(period_ns))
    }

    /// What the fieldbuses' timers run on ([`Fieldbus`]).
    fn bus_time(&self) -> Duration {
        match self.bus_origin {
            None => self.engine_time(),
            Some(o) => {
                let wall = self.clock.now().saturating_sub(o.wall_start);
                let scaled = Duration::try_from_secs_f64(wall.as_secs_f64() * o.scale);
                o.engine_start
                    .saturating_add(scaled.unwrap_or(Duration::MAX))
            }
        }
    }

    fn serve_fieldbuses(&mut self, phase: Phase) {
        let now = self.bus_time();
        let engine = &mut self.engine;
        self.fieldbuses.retain_mut(|bus| {
            // The fieldbus is the caller's code: a panic removes it, not the runtime. It may
            // have left a slave's dictionary half-written, which a master sees as odd values,
            // never as unsafety.
            catch_unwind(AssertUnwindSafe(|| match phase {
                Phase::Input => bus.before_step(engine, now),
                Phase::Output => bus.after_step(engine, now),
            }))
            .is_ok()
        });
    }

    fn notify_observers(&mut self) {
        let engine = &self.engine;
        self.observers.retain_mut(|(_, observer)| {
            // The observer is the caller's code: a panic removes it, not the runtime (it only
            // saw a shared reference, so the engine is intact).
            catch_unwind(AssertUnwindSafe(|| observer(engine))).unwrap_or(false)
        });
    }

    fn observe(&mut self, observer: Observer, reply: ReplySender<ObserverId, CallError>) {
        let id = ObserverId(self.next_observer);
        self.next_observer += 1;
        self.observers.push((id, observer));
        reply.send(Ok(id));
    }

    fn remove_observer(&mut self, id: ObserverId, reply: ReplySender<bool, CallError>) {
        let before = self.observers.len();
        self.observers.retain(|(installed, _)| *installed != id);
        reply.send(Ok(self.observers.len() != before));
    }

    fn apply(&mut self, command: Command, reply: ReplySender<Reply, CallError>) {
        let result = self.engine.apply(command).map_err(CallError::Engine);
        self.stats.commands_applied += 1;
        self.replies.push(HeldReply::One(reply, result));
    }

    fn apply_batch(&mut self, commands: Vec<Command>, reply: ReplySender<Vec<Reply>, CallError>) {
        let count = commands.len() as u64;
        let result = self.engine.apply_batch(commands).map_err(CallError::Engine);
        if result.is_ok() {
            self.stats.commands_applied += count;
        }
        self.replies.push(HeldReply::Batch(reply, result));
    }

    /// Each command on its own, in order; as many as an atomic batch may carry, so that one
    /// request's work between two ticks stays bounded.
    fn apply_each(
        &mut self,
        commands: Vec<Command>,
        reply: ReplySender<Vec<Result<Reply, EngineError>>, CallError>,
    ) {
        let result = if commands.len() > MAX_ATOMIC_COMMANDS {
            Err(CallError::Engine(EngineError::InvalidArgument {
                name: "commands",
                value: commands.len() as f64,
                reason: "more than 1024 commands in one request",
            }))
        } else {
            self.stats.commands_applied += commands.len() as u64;
            Ok(commands
                .into_iter()
                .map(|command| self.engine.apply(command))
                .collect())
        };
        self.replies.push(HeldReply::Each(reply, result));
    }

    fn send_replies(&mut self) {
        for held in self.replies.drain(..) {
            match held {
                HeldReply::One(reply, result) => reply.send(result),
                HeldReply::Batch(reply, result) => reply.send(result),
                HeldReply::Each(reply, result) => reply.send(result),
            }
        }
    }

    fn publish_snapshot(&mut self) {
        let engine = &self.engine;
        self.snapshots
            .publish(&self.shared.snapshot, |s| engine.snapshot_into(s));
    }

    fn publish_stats(&mut self) {
        self.stats.tick = self.engine.tick();
        self.stats.snapshot_allocations = self.snapshots.allocations;
        let stats = &self.stats;
        self.stats_publisher
            .publish(&self.shared.stats, |s| s.clone_from(stats));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deadlines_are_absolute_and_do_not_accumulate_error() {
        let s = Schedule::new(Duration::from_millis(7), 1e-3);
        assert_eq!(s.deadline(1), Duration::from_millis(8));
        assert_eq!(s.deadline(3), Duration::from_millis(10));
        // 10⁹ ticks of 1 ms: still exact to the nanosecond.
        assert_eq!(
            s.deadline(1_000_000_000),
            Duration::from_millis(7) + Duration::from_secs(1_000_000)
        );
        // A period that is not a whole number of ns: n × p, rounded once.
        let third = Schedule::new(Duration::ZERO, 1e-3 / 3.0);
        assert_eq!(third.deadline(3), Duration::from_millis(1));
        assert_eq!(third.deadline(3_000_000), Duration::from_secs(1000));
    }

    #[test]
    fn due_through_counts_deadlines_reached() {
        let s = Schedule::new(Duration::from_millis(7), 1e-3);
        assert_eq!(s.due_through(Duration::ZERO), 0);
        assert_eq!(s.due_through(Duration::from_millis(7)), 0);
        assert_eq!(s.due_through(Duration::from_nanos(7_999_999)), 0);
        assert_eq!(s.due_through(Duration::from_millis(8)), 1);
        assert_eq!(s.due_through(Duration::from_micros(12_500)), 5);
        let third = Schedule::new(Duration::ZERO, 1e-3 / 3.0);
        for n in [1u64, 2, 3, 299, 300, 301, 1_000_000] {
            assert_eq!(third.due_through(third.deadline(n)), n);
            assert_eq!(
                third.due_through(third.deadline(n) - Duration::from_nanos(1)),
                n - 1
            );
        }
    }

    #[test]
    fn publisher_reuses_the_spare_unless_a_reader_holds_it() {
        let target = ArcSwap::from_pointee(0u64);
        let mut p = Publisher::<u64>::new();
        p.publish(&target, |v| *v = 1);
        p.publish(&target, |v| *v = 2);
        assert_eq!(p.allocations, 1); // the first; the second reused the initial value's Arc
        for i in 3..100 {
            p.publish(&target, |v| *v = i);
        }
        assert_eq!(p.allocations, 1);
        let held = target.load_full(); // 99, becomes the spare on the next publish
        p.publish(&target, |v| *v = 100);
        p.publish(&target, |v| *v = 101); // the spare is `held`: must not be overwritten
        assert_eq!(*held, 99);
        assert_eq!(**target.load(), 101);
        assert_eq!(p.allocations, 2);
    }
}
