//! Runtime tests. Virtual-clock tests are exact; realtime and scaled logic is tested exactly
//! with a gated fake clock; the system-clock tests assert only what a loaded VM cannot break.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::VecDeque;
use std::future::Future;
use std::pin::pin;
use std::sync::mpsc;
use std::sync::{Arc, Condvar, Mutex};
use std::task::{Context, Poll, Wake, Waker};
use std::thread;
use std::time::{Duration, Instant};

use super::*;
use crate::command::{Enable, MoveVelocity, Stop};
use crate::config::{AxisConfig, EngineConfig};
use crate::status::AxisFlags;

// ---- helpers ---------------------------------------------------------------------------------

fn engine(axes: usize) -> Engine {
    let config = EngineConfig {
        axes: vec![AxisConfig::default(); axes],
        ..EngineConfig::default()
    };
    Engine::new(&config).unwrap()
}

fn virtual_runtime(axes: usize) -> (EngineHandle, RuntimeGuard) {
    Runtime::start(engine(axes), RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap()
}

fn enable(axis: u16) -> Command {
    Command::from(Enable { axis })
}

/// Polls `f` until it is true; a generous timeout only turns a hang into a failure.
fn eventually(what: &str, mut f: impl FnMut() -> bool) {
    let give_up = Instant::now() + Duration::from_secs(60);
    while !f() {
        assert!(Instant::now() < give_up, "timed out waiting for {what}");
        thread::sleep(Duration::from_millis(1));
    }
}

/// A hand-written single-future executor: the runtime's futures need no particular one.
fn block_on<F: Future>(future: F) -> F::Output {
    struct Unparker(thread::Thread);
    impl Wake for Unparker {
        fn wake(self: Arc<Self>) {
            self.0.unpark();
        }
    }
    let waker = Waker::from(Arc::new(Unparker(thread::current())));
    let mut cx = Context::from_waker(&waker);
    let mut future = pin!(future);
    loop {
        if let Poll::Ready(output) = future.as_mut().poll(&mut cx) {
            return output;
        }
        thread::park();
    }
}

/// Checks the relations that hold at every publication, whatever the clock did.
fn assert_consistent(stats: &RuntimeStats, start_tick: u64) {
    assert_eq!(stats.tick, start_tick + stats.ticks_run, "{stats:?}");
    assert!(stats.caught_up_ticks <= stats.ticks_run, "{stats:?}");
    assert!(stats.overruns <= stats.ticks_run, "{stats:?}");
    // One lateness sample per wake-up, at most one wake-up per batch of ticks.
    assert!(
        stats.lateness.count() <= stats.ticks_run - stats.caught_up_ticks + 1,
        "{stats:?}"
    );
    // Only ticks whose deadline has passed are run, and dropped ticks are never run.
    assert!(
        stats.drift <= -(stats.dropped_ticks as f64) * stats.period + 1e-9,
        "{stats:?}"
    );
}

/// A fake clock: time moves only when the servo thread sleeps (to the deadline plus a scripted
/// lateness) or, with `now_step`, on every reading. Sleeps pass a gate the test opens, so the
/// test can look at the runtime while its servo thread waits at a known point.
#[derive(Clone, Default)]
struct FakeClock(Arc<(Mutex<FakeState>, Condvar)>);

#[derive(Default)]
struct FakeState {
    now: Duration,
    now_step: Duration,
    lateness: VecDeque<Duration>,
    sleeps_allowed: u64,
    waiting_at_gate: bool,
    /// Reading number `block_at_read` (from 1) after an allowed sleep blocks until `release`
    /// (readings before the first allowed sleep depend on how often the gate timed out).
    sleeps_done: u64,
    reads_since_sleep: u64,
    block_at_read: Option<u64>,
    blocked: bool,
}

impl FakeClock {
    fn new(lateness: &[Duration]) -> FakeClock {
        let clock = FakeClock::default();
        clock.state().lateness = lateness.iter().copied().collect();
        clock
    }

    fn state(&self) -> std::sync::MutexGuard<'_, FakeState> {
        self.0 .0.lock().unwrap()
    }

    /// Let `n` more sleeps through the gate.
    fn allow(&self, n: u64) {
        self.state().sleeps_allowed += n;
        self.0 .1.notify_all();
    }

    /// Wait until the servo thread has used every allowed sleep and waits at the gate again
    /// (everything before that sleep is published by then).
    fn wait_at_gate(&self) {
        let give_up = Instant::now() + Duration::from_secs(60);
        let mut state = self.state();
        while !(state.waiting_at_gate && state.sleeps_allowed == 0) {
            assert!(
                Instant::now() < give_up,
                "the servo thread never reached the gate"
            );
            state = self
                .0
                 .1
                .wait_timeout(state, Duration::from_millis(50))
                .unwrap()
                .0;
        }
    }
}

impl FakeClock {
    fn wait_blocked(&self) {
        let give_up = Instant::now() + Duration::from_secs(60);
        let mut state = self.state();
        while !state.blocked {
            assert!(
                Instant::now() < give_up,
                "the servo thread never read the clock"
            );
            state = self
                .0
                 .1
                .wait_timeout(state, Duration::from_millis(50))
                .unwrap()
                .0;
        }
    }

    fn release(&self) {
        self.state().block_at_read = None;
        self.0 .1.notify_all();
    }
}

impl Clock for FakeClock {
    fn now(&self) -> Duration {
        let mut state = self.state();
        state.reads_since_sleep += 1;
        if state.sleeps_done > 0 && state.block_at_read == Some(state.reads_since_sleep) {
            state.blocked = true;
            self.0 .1.notify_all();
            while state.block_at_read.is_some() {
                state = self.0 .1.wait(state).unwrap();
            }
            state.blocked = false;
        }
        let now = state.now;
        let step = state.now_step;
        state.now += step;
        now
    }

    fn sleep_until(&self, deadline: Duration) {
        let mut state = self.state();
        if state.sleeps_allowed == 0 {
            state.waiting_at_gate = true;
            self.0 .1.notify_all();
            // Returns early now and then so the servo thread sees a stop request.
            let mut state = self
                .0
                 .1
                .wait_timeout(state, Duration::from_millis(5))
                .unwrap()
                .0;
            state.waiting_at_gate = false;
            return;
        }
        state.sleeps_allowed -= 1;
        state.sleeps_done += 1;
        state.reads_since_sleep = 0;
        let late = state.lateness.pop_front().unwrap_or_default();
        state.now = state.now.max(deadline + late);
    }
}

fn paced_fake(
    clock: ClockMode,
    lateness: &[Duration],
    options: RuntimeOptions,
) -> (EngineHandle, RuntimeGuard, FakeClock) {
    let fake = FakeClock::new(lateness);
    let options = RuntimeOptions { clock, ..options };
    let (handle, guard) = Runtime::start_with_clock(engine(2), options, fake.clone()).unwrap();
    (handle, guard, fake)
}

const MS: Duration = Duration::from_millis(1);

// ---- virtual clock ---------------------------------------------------------------------------

#[test]
fn virtual_advance_runs_exactly_the_ticks_asked() {
    let (handle, guard) = virtual_runtime(1);
    assert_eq!(handle.snapshot().tick, 0);
    assert_eq!(handle.advance(10).unwrap(), 10);
    assert_eq!(handle.advance(0).unwrap(), 10);
    assert_eq!(handle.advance(5).unwrap(), 15);
    assert_eq!(handle.snapshot().tick, 15);
    let stats = handle.stats();
    assert_eq!(stats.ticks_run, 15);
    assert_eq!(stats.clock, ClockMode::Virtual);
    assert_eq!((stats.wall_period, stats.drift), (0.0, 0.0));
    assert_eq!(stats.lateness.count(), 0);
    assert_consistent(&stats, 0);
    assert_eq!(guard.stop().unwrap().tick(), 15);
}

#[test]
fn virtual_command_is_applied_at_once_and_visible_on_reply() {
    let (handle, _guard) = virtual_runtime(2);
    assert_eq!(handle.call(enable(1)).unwrap(), Reply::Done);
    // The reply comes after the snapshot with the command's effect is published.
    let snapshot = handle.snapshot();
    assert_eq!(snapshot.tick, 0);
    assert!(snapshot.axes[1].flags.contains(AxisFlags::ENABLED));
    assert!(!snapshot.axes[0].flags.contains(AxisFlags::ENABLED));
    assert_eq!(handle.stats().commands_applied, 1);
}

#[test]
fn virtual_commands_queued_together_are_each_answered_after_their_effect() {
    let (handle, _guard) = virtual_runtime(2);
    // Hold the servo thread inside an advance until everything below is queued, so the
    // commands are taken off the queue as one run (published once) and the advance behind
    // them is carried over.
    let (release, gate) = mpsc::channel::<()>();
    let gate = Mutex::new(gate);
    let held = handle
        .submit_advance(
            1,
            Some(Box::new(move |_: &Snapshot| {
                gate.lock().unwrap().recv().is_ok()
            })),
        )
        .unwrap();
    let first = handle.submit(enable(0)).unwrap();
    let refused = handle.submit(enable(7)).unwrap();
    let second = handle.submit(enable(1)).unwrap();
    let advance = handle.submit_advance(3, None).unwrap();
    release.send(()).unwrap();
    assert_eq!(held.wait().unwrap().tick, 1);
    assert_eq!(first.wait(), Ok(Reply::Done));
    let snapshot = handle.snapshot();
    assert!(snapshot.axes[0].flags.contains(AxisFlags::ENABLED));
    assert!(matches!(
        refused.wait(),
        Err(CallError::Engine(EngineError::InvalidAxis { axis: 7, .. }))
    ));
    assert_eq!(second.wait(), Ok(Reply::Done));
    assert!(handle.snapshot().axes[1].flags.contains(AxisFlags::ENABLED));
    // The advance taken off the queue behind the commands is served, not lost.
    assert_eq!(advance.wait().unwrap().tick, 4);
    assert_eq!(handle.stats().commands_applied, 3);
}

#[test]
fn a_blocking_call_serves_what_was_queued_before_it_first() {
    let (handle, _guard) = virtual_runtime(2);
    // Whichever thread serves them (the servo thread woken by the submits, or this one in the
    // advance), the queue's order holds: both commands before the advance, the refused one
    // answered with its own error, and every reply in by the time the advance returns.
    let first = handle.submit(enable(0)).unwrap();
    let refused = handle.submit(enable(7)).unwrap();
    let batch = handle.submit_batch(vec![enable(1)]).unwrap();
    assert_eq!(handle.advance(2), Ok(2));
    assert_eq!(first.try_take(), Some(Ok(Reply::Done)));
    assert!(matches!(
        refused.try_take(),
        Some(Err(CallError::Engine(EngineError::InvalidAxis {
            axis: 7,
            ..
        })))
    ));
    assert_eq!(batch.try_take(), Some(Ok(vec![Reply::Done])));
    let enabled_at = |axis: usize| {
        handle.snapshot().axes[axis]
            .flags
            .contains(AxisFlags::ENABLED)
    };
    assert!(enabled_at(0) && enabled_at(1));
    let stats = handle.stats();
    assert_eq!((stats.commands_applied, stats.ticks_run), (3, 2));
}

#[test]
fn engine_errors_come_back_as_call_errors() {
    let (handle, _guard) = virtual_runtime(2);
    assert_eq!(
        handle.call(enable(7)),
        Err(CallError::Engine(EngineError::InvalidAxis {
            axis: 7,
            count: 2
        }))
    );
    // The runtime goes on.
    assert_eq!(handle.call(enable(0)), Ok(Reply::Done));
}

fn jog(axis: u16, velocity: f64) -> Command {
    Command::from(MoveVelocity {
        axis,
        velocity,
        acceleration: None,
        deceleration: None,
        jerk: None,
        buffer_mode: Default::default(),
    })
}

#[test]
fn a_batch_is_applied_in_one_go_and_a_refused_one_not_at_all() {
    let (handle, _guard) = virtual_runtime(2);
    let replies = handle
        .call_batch(vec![enable(0), enable(1), jog(0, 1.0), jog(1, -1.0)])
        .unwrap();
    assert_eq!(replies.len(), 4);
    assert_eq!(replies[2], Reply::Accepted { id: 1 });
    assert_eq!(handle.stats().commands_applied, 4);
    handle.advance(1).unwrap();
    let snapshot = handle.snapshot();
    assert!(snapshot.axes[0].cmd_vel > 0.0 && snapshot.axes[1].cmd_vel < 0.0);
    // Refused at index 1: the stop of axis 0 before it is undone too.
    let before = handle.snapshot();
    let stop = Command::from(Stop {
        axis: 0,
        mode: crate::command::StopMode::Immediate,
        deceleration: None,
    });
    let err = block_on(handle.call_batch_async(vec![stop, enable(9)])).unwrap_err();
    let CallError::Engine(EngineError::Item { list, index, error }) = err else {
        panic!("{err:?}");
    };
    assert_eq!((list, index), ("commands", 1));
    assert_eq!(*error, EngineError::InvalidAxis { axis: 9, count: 2 });
    assert_eq!(*handle.snapshot(), *before);
    assert_eq!(handle.stats().commands_applied, 4);
}

#[test]
fn call_each_answers_each_command_in_order_and_a_refusal_loses_nothing() {
    let (handle, _guard) = virtual_runtime(2);
    // The jog of axis 1 comes before its enable (refused), axis 0's after (accepted): applied
    // in order. The refused ones keep their places; the others stand.
    let replies = handle
        .call_each(vec![
            jog(1, 1.0),
            enable(0),
            enable(7),
            jog(0, 1.0),
            enable(1),
        ])
        .unwrap();
    assert_eq!(replies.len(), 5);
    assert!(
        matches!(replies[0], Err(EngineError::AxisDisabled { axis: 1 })),
        "{replies:?}"
    );
    assert_eq!(replies[1], Ok(Reply::Done));
    assert_eq!(
        replies[2],
        Err(EngineError::InvalidAxis { axis: 7, count: 2 })
    );
    assert_eq!(replies[3], Ok(Reply::Accepted { id: 1 }));
    assert_eq!(replies[4], Ok(Reply::Done));
    // One request, one publication: the reply follows the snapshot with every effect.
    let snapshot = handle.snapshot();
    assert!(snapshot.axes[0].flags.contains(AxisFlags::ENABLED));
    assert!(snapshot.axes[1].flags.contains(AxisFlags::ENABLED));
    assert_eq!(handle.stats().commands_applied, 5);
    handle.advance(1).unwrap();
    let snapshot = handle.snapshot();
    assert!(snapshot.axes[0].cmd_vel > 0.0 && snapshot.axes[1].cmd_vel == 0.0);
    // Async and not waited on alike; more than an atomic batch may carry is refused whole.
    let pending = handle.submit_each(vec![jog(1, -1.0)]).unwrap();
    assert_eq!(
        block_on(pending.into_future()),
        Ok(vec![Ok(Reply::Accepted { id: 2 })])
    );
    let too_many = vec![enable(0); crate::engine::MAX_ATOMIC_COMMANDS + 1];
    assert!(matches!(
        block_on(handle.call_each_async(too_many)),
        Err(CallError::Engine(EngineError::InvalidArgument {
            name: "commands",
            ..
        }))
    ));
    assert_eq!(handle.stats().commands_applied, 6);
}

#[test]
fn a_batch_on_a_paced_clock_lands_between_two_ticks_as_one_request() {
    let options = RuntimeOptions {
        max_commands_per_tick: 1,
        ..RuntimeOptions::default()
    };
    let (handle, _guard, fake) = paced_fake(ClockMode::Realtime, &[], options);
    fake.wait_at_gate();
    let batch = handle
        .submit_batch(vec![enable(0), enable(1), jog(0, 1.0), jog(1, 1.0)])
        .unwrap();
    fake.allow(1);
    fake.wait_at_gate();
    assert_eq!(batch.try_take().map(|r| r.map(|r| r.len())), Some(Ok(4)));
    let snapshot = handle.snapshot();
    // Both jogs started before the same step: their first velocities are equal.
    assert!(snapshot.axes[0].cmd_vel > 0.0);
    assert_eq!(snapshot.axes[0].cmd_vel, snapshot.axes[1].cmd_vel);
    assert_eq!(handle.stats().command_bound_hits, 1);
}

/// Runs the same script of commands and advances, returning every snapshot seen after an
/// advance and the engine at the end.
fn scripted_run() -> (Vec<String>, Snapshot) {
    let (handle, guard) = virtual_runtime(3);
    let mut seen = Vec::new();
    let mut record = |s: &Snapshot| seen.push(serde_json::to_string(s).unwrap());
    for axis in 0..3 {
        let _ = handle.call(enable(axis));
        let _ = handle.call(Command::from(MoveVelocity {
            axis,
            velocity: 10.0 * f64::from(axis + 1),
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: Default::default(),
        }));
    }
    handle.advance(100).unwrap();
    record(&handle.snapshot());
    let _ = handle.call(Command::from(Stop {
        axis: 1,
        mode: Default::default(),
        deceleration: None,
    }));
    let until = handle.advance_until(|s| s.tick >= 250, 1000).unwrap();
    assert_eq!(
        until,
        Until {
            met: true,
            tick: 250
        }
    );
    record(&handle.snapshot());
    handle.advance(1234).unwrap();
    record(&handle.snapshot());
    let engine = guard.stop().unwrap();
    (seen, engine.snapshot())
}

#[test]
fn virtual_runs_are_bit_identical() {
    let (first, first_end) = scripted_run();
    let (second, second_end) = scripted_run();
    assert_eq!(first, second);
    assert_eq!(
        serde_json::to_string(&first_end).unwrap(),
        serde_json::to_string(&second_end).unwrap()
    );
    assert_eq!(first_end.tick, 1484);
}

#[test]
fn virtual_runtime_matches_the_bare_engine() {
    let (handle, guard) = virtual_runtime(2);
    let mut bare = engine(2);
    for axis in 0..2 {
        assert_eq!(
            handle.call(enable(axis)),
            bare.apply(enable(axis)).map_err(Into::into)
        );
    }
    handle.advance(500).unwrap();
    for _ in 0..500 {
        bare.step();
    }
    assert_eq!(*handle.snapshot(), bare.snapshot());
    assert_eq!(guard.stop().unwrap().snapshot(), bare.snapshot());
}

#[test]
fn advance_until_stops_when_the_condition_holds() {
    let (handle, _guard) = virtual_runtime(1);
    let until = handle.advance_until(|s| s.tick == 25, 100).unwrap();
    assert_eq!(
        until,
        Until {
            met: true,
            tick: 25
        }
    );
    // Not evaluated before the first tick: an already-true condition still steps once.
    let until = handle.advance_until(|_| true, 100).unwrap();
    assert_eq!(
        until,
        Until {
            met: true,
            tick: 26
        }
    );
    assert_eq!(handle.snapshot().tick, 26);
}

#[test]
fn advance_until_respects_its_bound() {
    let (handle, _guard) = virtual_runtime(1);
    let until = handle.advance_until(|_| false, 40).unwrap();
    assert_eq!(
        until,
        Until {
            met: false,
            tick: 40
        }
    );
    let until = handle.advance_until(|_| true, 0).unwrap();
    assert_eq!(
        until,
        Until {
            met: false,
            tick: 40
        }
    );
    assert_eq!(handle.stats().ticks_run, 40);
}

#[test]
fn advance_until_condition_panic_fails_the_advance_only() {
    let (handle, guard) = virtual_runtime(1);
    let result = handle.advance_until(|s| s.tick == 3 && panic!("condition bug"), 10);
    assert_eq!(result, Err(AdvanceError::ConditionPanicked { tick: 3 }));
    assert!(handle.is_running());
    assert_eq!(handle.advance(1).unwrap(), 4);
    assert_eq!(guard.stop().unwrap().tick(), 4);
}

/// A condition that records the thread it runs on and what blocking calls back into the
/// handle give.
type Seen = Arc<
    Mutex<
        Option<(
            Option<String>,
            Result<Reply, CallError>,
            Result<u64, AdvanceError>,
        )>,
    >,
>;

fn reentering_condition(handle: &EngineHandle, seen: &Seen) -> Condition {
    let inner = handle.clone();
    let seen = Arc::clone(seen);
    Box::new(move |_| {
        let name = thread::current().name().map(str::to_owned);
        *seen.lock().unwrap() = Some((name, inner.call(enable(0)), inner.advance(1)));
        true
    })
}

#[test]
fn blocking_calls_from_the_servo_thread_are_refused() {
    let (handle, _guard) = virtual_runtime(1);
    let seen = Seen::default();
    // A blocking advance is served on the caller's thread, a submitted one on the servo
    // thread; either way the engine's thread must not wait for itself.
    let condition = reentering_condition(&handle, &seen);
    handle.advance_until(condition, 1).unwrap();
    let (name, call, advance) = seen.lock().unwrap().take().unwrap();
    assert_eq!(name, thread::current().name().map(str::to_owned));
    assert_eq!(call, Err(CallError::OnServoThread));
    assert_eq!(advance, Err(AdvanceError::OnServoThread));
    let condition = reentering_condition(&handle, &seen);
    let submitted = handle.submit_advance(1, Some(condition)).unwrap();
    assert_eq!(submitted.wait(), Ok(Until { met: true, tick: 2 }));
    let (name, call, advance) = seen.lock().unwrap().take().unwrap();
    assert_eq!(name.as_deref(), Some("mcemu-servo"));
    assert_eq!(call, Err(CallError::OnServoThread));
    assert_eq!(advance, Err(AdvanceError::OnServoThread));
    assert_eq!(handle.call(enable(0)), Ok(Reply::Done)); // not left marked
}

/// Stalls a virtual servo thread inside an advance_until condition until the returned sender is
/// dropped; returns once the servo thread is stalled (so its queue is empty and not drained).
fn stall(handle: &EngineHandle) -> (mpsc::Sender<()>, Pending<Until, AdvanceError>) {
    let (entered_tx, entered_rx) = mpsc::channel();
    let (release_tx, release_rx) = mpsc::channel::<()>();
    let pending = handle
        .submit_advance(
            3,
            Some(Box::new(move |_| {
                let _ = entered_tx.send(());
                let _ = release_rx.recv(); // until the test drops `release_tx`
                false
            })),
        )
        .unwrap();
    entered_rx.recv().unwrap();
    (release_tx, pending)
}

#[test]
fn full_queue_is_an_error_to_the_caller() {
    let options = RuntimeOptions {
        queue_capacity: 2,
        ..RuntimeOptions::with_clock(ClockMode::Virtual)
    };
    let (handle, _guard) = Runtime::start(engine(1), options).unwrap();
    let (release, advance) = stall(&handle);
    let first = handle.submit(enable(0)).unwrap();
    let second = handle.submit(enable(0)).unwrap();
    assert!(matches!(
        handle.submit(enable(0)),
        Err(SubmitError::QueueFull { capacity: 2 })
    ));
    assert_eq!(
        handle.call(enable(0)),
        Err(CallError::Submit(SubmitError::QueueFull { capacity: 2 }))
    );
    assert_eq!(
        handle.submit_advance(1, None).err(),
        Some(SubmitError::QueueFull { capacity: 2 }.into())
    );
    assert!(first.try_take().is_none());
    drop(release);
    assert_eq!(
        advance.wait(),
        Ok(Until {
            met: false,
            tick: 3
        })
    );
    assert_eq!(first.wait(), Ok(Reply::Done));
    assert_eq!(second.wait(), Ok(Reply::Done));
    assert_eq!(handle.call(enable(0)), Ok(Reply::Done));
}

#[test]
fn requests_pending_at_shutdown_are_answered_stopped() {
    let (handle, guard) = virtual_runtime(1);
    let (release, advance) = stall(&handle);
    let queued: Vec<_> = (0..5).map(|_| handle.submit(enable(0)).unwrap()).collect();
    let queued_advance = handle.submit_advance(10, None).unwrap();
    let stopper = thread::spawn(move || guard.stop());
    // Once the stop flag is up, new submissions are refused without queueing.
    eventually("the stop request", || {
        handle.submit(enable(0)).err() == Some(SubmitError::Stopped)
    });
    drop(release);
    let engine = stopper.join().unwrap().unwrap();
    assert_eq!(engine.tick(), 1); // the stalled advance finished its tick, no more
    let stopped = SubmitError::Stopped;
    assert_eq!(advance.wait(), Err(AdvanceError::Submit(stopped)));
    assert_eq!(queued_advance.wait(), Err(AdvanceError::Submit(stopped)));
    for reply in queued {
        assert_eq!(reply.wait(), Err(CallError::Submit(stopped)));
    }
    assert!(!handle.is_running());
    assert_eq!(handle.call(enable(0)), Err(CallError::Submit(stopped)));
    assert_eq!(handle.advance(1), Err(AdvanceError::Submit(stopped)));
    assert_eq!(handle.snapshot().tick, 1); // the last snapshot stays readable
}

#[test]
fn dropping_the_guard_stops_the_runtime() {
    let (handle, guard) = virtual_runtime(1);
    handle.advance(3).unwrap();
    assert!(handle.is_running());
    drop(guard);
    assert!(!handle.is_running());
    assert_eq!(handle.submit(enable(0)).err(), Some(SubmitError::Stopped));
    assert_eq!(handle.stats().tick, 3);
}

#[test]
fn handle_is_clone_send_sync_and_its_futures_are_send() {
    fn assert_handle<T: Clone + Send + Sync + 'static>() {}
    fn assert_send<T: Send>(_: &T) {}
    assert_handle::<EngineHandle>();
    assert_handle::<RuntimeStats>();
    let (handle, _guard) = virtual_runtime(1);
    assert_send(&handle.call_async(enable(0)));
    assert_send(&handle.advance_async(1));
    assert_send(&handle.advance_until_async(|_| true, 1));
    assert_send(&handle.submit(enable(0)).unwrap().into_future());
}

#[test]
fn handle_clones_work_from_many_threads() {
    let (handle, guard) = virtual_runtime(4);
    let callers: Vec<_> = (0..8u16)
        .map(|i| {
            let handle = handle.clone();
            thread::spawn(move || {
                for n in 0..200u16 {
                    let axis = (i + n) % 5; // axis 4 does not exist
                    let reply = handle.call(enable(axis));
                    assert_eq!(reply.is_ok(), axis < 4, "{reply:?}");
                    let _ = handle.snapshot();
                }
            })
        })
        .collect();
    let advancer = {
        let handle = handle.clone();
        thread::spawn(move || {
            for _ in 0..100 {
                handle.advance(1).unwrap();
                let _ = handle.stats();
            }
        })
    };
    for t in callers {
        t.join().unwrap();
    }
    advancer.join().unwrap();
    let stats = handle.stats();
    assert_eq!(stats.commands_applied, 1600);
    assert_eq!(stats.ticks_run, 100);
    assert_eq!(guard.stop().unwrap().tick(), 100);
}

#[test]
fn async_calls_work_under_a_hand_written_executor() {
    fn assert_send<T: Send>(_: &T) {}
    let (handle, _guard) = virtual_runtime(2);
    let call = handle.call_async(enable(1));
    assert_send(&call);
    assert_eq!(block_on(call), Ok(Reply::Done));
    assert_eq!(block_on(handle.advance_async(7)), Ok(7));
    let until = block_on(handle.advance_until_async(|s| s.tick == 9, 100));
    assert_eq!(until, Ok(Until { met: true, tick: 9 }));
    let pending = handle.submit(enable(5)).unwrap();
    assert!(matches!(
        block_on(pending.into_future()),
        Err(CallError::Engine(EngineError::InvalidAxis { .. }))
    ));
    assert!(handle.snapshot().axes[1].flags.contains(AxisFlags::ENABLED));
}

#[test]
fn async_call_waits_for_a_stalled_servo_thread() {
    let (handle, _guard) = virtual_runtime(1);
    let (release, _advance) = stall(&handle);
    let waiter = {
        let handle = handle.clone();
        thread::spawn(move || block_on(handle.call_async(enable(0))))
    };
    drop(release);
    assert_eq!(waiter.join().unwrap(), Ok(Reply::Done));
}

#[test]
fn steady_state_publication_reuses_the_snapshot_buffer() {
    let (handle, _guard) = virtual_runtime(8);
    handle.advance(1000).unwrap();
    assert_eq!(handle.stats().snapshot_allocations, 1);
    // A reader holding a snapshot keeps an unchanged copy; the runtime allocates around it.
    let held = handle.snapshot();
    // Two advances: the second publication comes round to the buffer the reader holds (an
    // advance publishes every 64 ticks and after its last).
    handle.advance(10).unwrap();
    handle.advance(10).unwrap();
    assert_eq!(held.tick, 1000);
    assert_eq!(handle.snapshot().tick, 1020);
    let allocations = handle.stats().snapshot_allocations;
    assert!((2..=3).contains(&allocations), "{allocations}");
    drop(held);
    handle.advance(1000).unwrap();
    assert_eq!(handle.stats().snapshot_allocations, allocations);
}

#[test]
fn an_advance_publishes_its_last_tick_and_with_a_condition_every_tick() {
    let (handle, _guard) = virtual_runtime(1);
    handle.advance(200).unwrap();
    assert_eq!(handle.snapshot().tick, 200);
    let before = handle.stats().snapshot_allocations;
    // Publications after ticks 264, 328, 392 and 400, each refilling the spare buffer.
    handle.advance(200).unwrap();
    assert_eq!(handle.snapshot().tick, 400);
    assert_eq!(handle.stats().snapshot_allocations, before);
    // With a condition every tick is published for it: it sees tick 401 first.
    let seen = Arc::new(Mutex::new(Vec::new()));
    let until = {
        let seen = Arc::clone(&seen);
        handle
            .advance_until(
                move |s| {
                    seen.lock().unwrap().push(s.tick);
                    false
                },
                5,
            )
            .unwrap()
    };
    assert_eq!(until.tick, 405);
    assert_eq!(seen.lock().unwrap().as_slice(), [401, 402, 403, 404, 405]);
}

#[test]
fn advance_is_refused_by_paced_clocks() {
    let (handle, _guard, _fake) = paced_fake(ClockMode::Realtime, &[], RuntimeOptions::default());
    assert_eq!(
        handle.advance(1),
        Err(AdvanceError::NotVirtual(ClockMode::Realtime))
    );
    assert_eq!(
        block_on(handle.advance_until_async(|_| true, 1)),
        Err(AdvanceError::NotVirtual(ClockMode::Realtime))
    );
}

#[test]
fn invalid_options_are_refused() {
    let bad = |options: RuntimeOptions| match Runtime::start(engine(1), options) {
        Err(RuntimeError::InvalidOptions { option, .. }) => option,
        other => panic!("accepted: {:?}", other.map(|(h, _)| h)),
    };
    let virt = RuntimeOptions::with_clock(ClockMode::Virtual);
    for k in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-4, 1e4] {
        assert_eq!(
            bad(RuntimeOptions::with_clock(ClockMode::Scaled(k))),
            "clock"
        );
    }
    let zero_queue = RuntimeOptions {
        queue_capacity: 0,
        ..virt.clone()
    };
    assert_eq!(bad(zero_queue), "queue_capacity");
    let zero_per_tick = RuntimeOptions {
        max_commands_per_tick: 0,
        ..virt.clone()
    };
    assert_eq!(bad(zero_per_tick), "max_commands_per_tick");
    let spin = RuntimeOptions {
        spin_window: Some(-1.0),
        ..virt
    };
    assert_eq!(bad(spin), "spin_window");
}

#[test]
fn options_and_stats_serialize() {
    let options = RuntimeOptions::with_clock(ClockMode::Scaled(2.5));
    let json = serde_json::to_value(&options).unwrap();
    assert_eq!(json["clock"], serde_json::json!({ "scaled": 2.5 }));
    let back: RuntimeOptions = serde_json::from_value(json).unwrap();
    assert_eq!(back, options);
    let (handle, _guard) = virtual_runtime(1);
    handle.advance(2).unwrap();
    let stats = serde_json::to_value(handle.stats()).unwrap();
    assert_eq!(stats["clock"], "virtual");
    assert_eq!(stats["ticks_run"], 2);
    assert_eq!(stats["lateness"]["count"], 0);
}

// ---- observers -------------------------------------------------------------------------------

/// An observer that records the tick it saw, while it keeps returning `keep(tick)`.
fn tick_recorder(
    keep: impl Fn(u64) -> bool + Send + 'static,
) -> (
    Arc<Mutex<Vec<u64>>>,
    impl FnMut(&Engine) -> bool + Send + 'static,
) {
    let seen = Arc::new(Mutex::new(Vec::new()));
    let sink = Arc::clone(&seen);
    let observer = move |engine: &Engine| {
        sink.lock().unwrap().push(engine.tick());
        keep(engine.tick())
    };
    (seen, observer)
}

#[test]
fn observer_sees_every_tick_of_an_advance_and_nothing_else() {
    let (handle, _guard) = virtual_runtime(1);
    handle.advance(3).unwrap();
    let (seen, observer) = tick_recorder(|_| true);
    let id = handle.add_observer(observer).unwrap();
    handle.call(enable(0)).unwrap(); // a command is not a tick
    handle.advance(5).unwrap();
    assert_eq!(*seen.lock().unwrap(), vec![4, 5, 6, 7, 8]);
    assert_eq!(handle.remove_observer(id), Ok(true));
    assert_eq!(handle.remove_observer(id), Ok(false));
    handle.advance(2).unwrap();
    assert_eq!(seen.lock().unwrap().len(), 5);
}

#[test]
fn observer_sees_the_engine_after_the_step() {
    let (handle, _guard) = virtual_runtime(1);
    handle.call(enable(0)).unwrap();
    handle
        .call(Command::from(MoveVelocity {
            axis: 0,
            velocity: 10.0,
            acceleration: None,
            deceleration: None,
            jerk: None,
            buffer_mode: Default::default(),
        }))
        .unwrap();
    let positions = Arc::new(Mutex::new(Vec::new()));
    let sink = Arc::clone(&positions);
    handle
        .add_observer(move |e: &Engine| {
            sink.lock().unwrap().push(e.axis_status(0).unwrap().cmd_pos);
            true
        })
        .unwrap();
    handle.advance(20).unwrap();
    let positions = positions.lock().unwrap();
    assert_eq!(positions.len(), 20);
    assert_eq!(
        *positions.last().unwrap(),
        handle.snapshot().axes[0].cmd_pos
    );
    assert!(positions.windows(2).all(|w| w[0] < w[1]), "{positions:?}");
}

#[test]
fn observer_returning_false_or_panicking_is_removed() {
    let (handle, _guard) = virtual_runtime(1);
    let (stops, stopping) = tick_recorder(|tick| tick < 3);
    let (panics, panicking) = tick_recorder(|tick| {
        assert!(tick < 2, "observer panics at tick {tick}");
        true
    });
    let (stays, staying) = tick_recorder(|_| true);
    let stopping = handle.add_observer(stopping).unwrap();
    let panicking = handle.add_observer(panicking).unwrap();
    handle.add_observer(staying).unwrap();
    handle.advance(6).unwrap();
    assert_eq!(*stops.lock().unwrap(), vec![1, 2, 3]);
    assert_eq!(*panics.lock().unwrap(), vec![1, 2]);
    assert_eq!(*stays.lock().unwrap(), vec![1, 2, 3, 4, 5, 6]);
    assert_eq!(handle.remove_observer(stopping), Ok(false));
    assert_eq!(handle.remove_observer(panicking), Ok(false));
    assert_eq!(handle.snapshot().tick, 6); // the runtime went on
}

#[test]
fn observer_calls_back_into_the_handle_are_refused_not_deadlocked() {
    let (handle, _guard) = virtual_runtime(1);
    let inner = handle.clone();
    let result = Arc::new(Mutex::new(None));
    let sink = Arc::clone(&result);
    handle
        .add_observer(move |_: &Engine| {
            *sink.lock().unwrap() = Some(inner.call(enable(0)));
            false
        })
        .unwrap();
    handle.advance(1).unwrap();
    assert_eq!(*result.lock().unwrap(), Some(Err(CallError::OnServoThread)));
}

#[test]
fn observers_work_async_and_on_paced_clocks_with_caught_up_ticks() {
    let lateness = [Duration::ZERO, Duration::from_micros(4500)];
    let (handle, guard, fake) =
        paced_fake(ClockMode::Realtime, &lateness, RuntimeOptions::default());
    fake.wait_at_gate();
    let (seen, observer) = tick_recorder(|_| true);
    let pending = handle.submit_observer(Box::new(observer)).unwrap();
    fake.allow(1); // the tick that installs it (commands and observers come before the step)
    let id = block_on(pending.into_future()).unwrap();
    fake.allow(2); // one on time, one 4.5 ms late: 4 caught-up ticks
    fake.wait_at_gate();
    assert_eq!(*seen.lock().unwrap(), vec![1, 2, 3, 4, 5, 6, 7]);
    assert_eq!(handle.stats().caught_up_ticks, 4);
    // Removal is queued too: it takes effect at the start of the next tick.
    let removal = handle.submit_remove_observer(id).unwrap();
    fake.allow(1);
    assert_eq!(block_on(removal.into_future()), Ok(true));
    fake.wait_at_gate();
    assert_eq!(seen.lock().unwrap().len(), 7);
    drop(guard);
}

// ---- paced clocks, fake time -----------------------------------------------------------------

#[test]
fn on_time_wake_ups_run_one_tick_each() {
    let (handle, guard, fake) = paced_fake(ClockMode::Realtime, &[], RuntimeOptions::default());
    fake.wait_at_gate();
    assert_eq!(handle.stats().ticks_run, 0);
    fake.allow(100);
    fake.wait_at_gate();
    let stats = handle.stats();
    assert_eq!(stats.ticks_run, 100);
    assert_eq!(handle.snapshot().tick, 100);
    assert_eq!(
        (stats.caught_up_ticks, stats.dropped_ticks, stats.overruns),
        (0, 0, 0)
    );
    assert_eq!(stats.lateness.count(), 100);
    assert_eq!(stats.lateness.max(), Duration::ZERO);
    assert_eq!((stats.elapsed, stats.drift), (0.1, 0.0));
    assert_eq!(stats.wall_period, 1e-3);
    assert_consistent(&stats, 0);
    assert_eq!(guard.stop().unwrap().tick(), 100);
}

#[test]
fn late_wake_up_runs_the_missed_ticks_back_to_back() {
    let lateness = [Duration::ZERO, Duration::ZERO, Duration::from_micros(4500)];
    let (handle, _guard, fake) =
        paced_fake(ClockMode::Realtime, &lateness, RuntimeOptions::default());
    fake.allow(3);
    fake.wait_at_gate();
    // Third wake-up at 7.5 ms for the 3 ms deadline: ticks 3–7 run at once.
    let stats = handle.stats();
    assert_eq!(
        (stats.ticks_run, stats.caught_up_ticks, stats.dropped_ticks),
        (7, 4, 0)
    );
    assert!((stats.drift + 0.5e-3).abs() < 1e-12, "{}", stats.drift);
    fake.allow(7);
    fake.wait_at_gate();
    let stats = handle.stats();
    assert_eq!(
        (stats.ticks_run, stats.caught_up_ticks, stats.dropped_ticks),
        (14, 4, 0)
    );
    assert_eq!(stats.drift, 0.0); // back on schedule: deadlines are absolute
    assert_eq!(stats.lateness.count(), 10);
    assert_eq!(stats.lateness.max(), Duration::from_micros(4500));
    assert_eq!(stats.lateness.p50(), Duration::from_micros(1)); // bucket edge
    assert_consistent(&stats, 0);
}

#[test]
fn catch_up_beyond_the_bound_drops_ticks_and_shows_in_drift() {
    let options = RuntimeOptions {
        max_catch_up_ticks: 3,
        ..RuntimeOptions::default()
    };
    let lateness = [Duration::from_micros(10_500)];
    let (handle, _guard, fake) = paced_fake(ClockMode::Realtime, &lateness, options);
    fake.allow(1);
    fake.wait_at_gate();
    // Woke at 11.5 ms for the 1 ms deadline: 10 missed, 3 caught up, 7 dropped.
    let stats = handle.stats();
    assert_eq!(
        (stats.ticks_run, stats.caught_up_ticks, stats.dropped_ticks),
        (4, 3, 7)
    );
    assert!((stats.drift + 7.5e-3).abs() < 1e-12, "{}", stats.drift);
    fake.allow(5);
    fake.wait_at_gate();
    let stats = handle.stats();
    assert_eq!(
        (stats.ticks_run, stats.caught_up_ticks, stats.dropped_ticks),
        (9, 3, 7)
    );
    // On schedule again, 7 periods behind wall time for good.
    assert!((stats.drift + 7e-3).abs() < 1e-12, "{}", stats.drift);
    assert_consistent(&stats, 0);
}

#[test]
fn stop_in_mid_catch_up_keeps_the_stats_consistent() {
    let options = RuntimeOptions {
        max_catch_up_ticks: 40,
        ..RuntimeOptions::default()
    };
    let lateness = [Duration::from_millis(100)];
    let (handle, guard, fake) = paced_fake(ClockMode::Realtime, &lateness, options);
    // Readings after the sleep: 1 the wake-up, then two per tick: reading 8 starts tick 4 of
    // a batch of 41 (100 missed: 40 caught up, 60 dropped).
    fake.state().block_at_read = Some(8);
    fake.allow(1);
    fake.wait_blocked();
    let stopper = thread::spawn(move || guard.stop());
    eventually("the stop request", || {
        handle.submit(enable(0)).err() == Some(SubmitError::Stopped)
    });
    fake.release();
    assert_eq!(stopper.join().unwrap().unwrap().tick(), 4);
    let stats = handle.stats();
    assert_eq!(
        (stats.ticks_run, stats.caught_up_ticks, stats.dropped_ticks),
        (4, 3, 60)
    );
    assert!((stats.drift + 97e-3).abs() < 1e-12, "{}", stats.drift); // 4 ms − 101 ms
    assert_consistent(&stats, 0);
}

#[test]
fn slow_ticks_are_counted_as_overruns() {
    let options = RuntimeOptions {
        max_catch_up_ticks: 10,
        ..RuntimeOptions::default()
    };
    let (handle, guard, fake) = paced_fake(ClockMode::Realtime, &[], options);
    // Every clock reading takes 1.5 ms of fake time, so every tick takes longer than 1 ms and
    // the servo thread never gets ahead of its deadlines again.
    fake.state().now_step = Duration::from_micros(1500);
    fake.allow(u64::MAX / 2);
    eventually("ticks", || handle.snapshot().tick >= 100);
    guard.stop().unwrap();
    let stats = handle.stats();
    assert_eq!(stats.overruns, stats.ticks_run);
    assert_eq!(stats.max_tick_time, 1.5e-3);
    assert!(stats.dropped_ticks > 0);
    assert_consistent(&stats, 0);
}

#[test]
fn scaled_clock_paces_on_the_scaled_period() {
    let (handle, _guard, fake) = paced_fake(ClockMode::Scaled(2.0), &[], RuntimeOptions::default());
    fake.allow(10);
    fake.wait_at_gate();
    let stats = handle.stats();
    assert_eq!(stats.wall_period, 0.5e-3);
    assert_eq!(stats.ticks_run, 10);
    assert_eq!(fake.state().now, 5 * MS); // 10 simulated ms in 5 wall ms
    assert_eq!((stats.elapsed, stats.drift), (5e-3, 0.0));
    assert_consistent(&stats, 0);
}

#[test]
fn commands_per_tick_are_bounded() {
    let options = RuntimeOptions {
        max_commands_per_tick: 2,
        ..RuntimeOptions::default()
    };
    let (handle, _guard, fake) = paced_fake(ClockMode::Realtime, &[], options);
    fake.wait_at_gate();
    let replies: Vec<_> = (0..5).map(|_| handle.submit(enable(0)).unwrap()).collect();
    let ready = |replies: &[PendingReply]| -> Vec<bool> {
        replies.iter().map(|r| r.try_take().is_some()).collect()
    };
    fake.allow(1);
    fake.wait_at_gate();
    let stats = handle.stats();
    assert_eq!((stats.commands_applied, stats.command_bound_hits), (2, 1));
    assert_eq!(ready(&replies[..]), [true, true, false, false, false]);
    assert!(handle.snapshot().axes[0].flags.contains(AxisFlags::ENABLED));
    fake.allow(2);
    fake.wait_at_gate();
    let stats = handle.stats();
    assert_eq!((stats.commands_applied, stats.command_bound_hits), (5, 2));
    assert_eq!(ready(&replies[2..]), [true, true, true]);
}

#[test]
fn stalled_paced_runtime_fills_its_queue_and_answers_it_at_shutdown() {
    let options = RuntimeOptions {
        queue_capacity: 3,
        ..RuntimeOptions::default()
    };
    let (handle, guard, fake) = paced_fake(ClockMode::Realtime, &[], options);
    fake.wait_at_gate();
    let queued: Vec<_> = (0..3).map(|_| handle.submit(enable(0)).unwrap()).collect();
    assert_eq!(
        handle.submit(enable(0)).err(),
        Some(SubmitError::QueueFull { capacity: 3 })
    );
    assert_eq!(guard.stop().unwrap().tick(), 0);
    for reply in queued {
        assert_eq!(reply.wait(), Err(CallError::Submit(SubmitError::Stopped)));
    }
}

// ---- paced clocks, system time (asserts only what load cannot break) ----------------------

fn system_clock_smoke(clock: ClockMode, ticks: u64) {
    let (handle, guard) = Runtime::start(engine(2), RuntimeOptions::with_clock(clock)).unwrap();
    eventually("ticks", || handle.snapshot().tick >= ticks);
    assert_eq!(handle.call(enable(1)), Ok(Reply::Done));
    assert!(handle.snapshot().axes[1].flags.contains(AxisFlags::ENABLED));
    let before = handle.snapshot().tick;
    eventually("more ticks", || handle.snapshot().tick > before);
    assert_consistent(&handle.stats(), 0);
    let engine = guard.stop().unwrap();
    let stats = handle.stats();
    assert_consistent(&stats, 0);
    assert_eq!(engine.tick(), stats.tick);
    assert_eq!(stats.commands_applied, 1);
}

#[test]
fn system_realtime_clock_ticks_and_keeps_consistent_stats() {
    system_clock_smoke(ClockMode::Realtime, 20);
}

#[test]
fn system_scaled_clock_ticks_and_keeps_consistent_stats() {
    system_clock_smoke(ClockMode::Scaled(50.0), 200);
}

// ---- fieldbuses ------------------------------------------------------------------------------

/// A fieldbus that logs its calls with the tick and, before each step, writes the controlword it
/// is given to drive 0 (what an RPDO does).
struct LoggingBus {
    log: Arc<Mutex<Vec<(&'static str, u64)>>>,
    /// The bus time of each call, in the order of `log`.
    times: Arc<Mutex<Vec<Duration>>>,
    controlword: Arc<Mutex<Option<u16>>>,
    panic_at: Option<u64>,
}

impl Fieldbus for LoggingBus {
    fn before_step(&mut self, engine: &mut Engine, now: Duration) {
        self.log.lock().unwrap().push(("before", engine.tick()));
        self.times.lock().unwrap().push(now);
        if self.panic_at == Some(engine.tick()) {
            panic!("fieldbus test panic");
        }
        if let Some(cw) = self.controlword.lock().unwrap().take() {
            let drive = engine.drive_mut(0).unwrap();
            drive
                .write(
                    crate::cia402::obj::CONTROLWORD,
                    0,
                    crate::od::Value::U16(cw),
                )
                .unwrap();
        }
    }

    fn after_step(&mut self, engine: &mut Engine, now: Duration) {
        self.log.lock().unwrap().push(("after", engine.tick()));
        self.times.lock().unwrap().push(now);
    }
}

fn drive_engine() -> Engine {
    let config = EngineConfig {
        axes: vec![AxisConfig::default()],
        drives: vec![crate::cia402::DriveConfig::default()],
        ..EngineConfig::default()
    };
    Engine::new(&config).unwrap()
}

fn drive_runtime() -> (EngineHandle, RuntimeGuard) {
    Runtime::start(
        drive_engine(),
        RuntimeOptions::with_clock(ClockMode::Virtual),
    )
    .unwrap()
}

#[allow(clippy::type_complexity)]
fn logging_bus(
    panic_at: Option<u64>,
) -> (
    LoggingBus,
    Arc<Mutex<Vec<(&'static str, u64)>>>,
    Arc<Mutex<Option<u16>>>,
) {
    let log = Arc::new(Mutex::new(Vec::new()));
    let controlword = Arc::new(Mutex::new(None));
    let bus = LoggingBus {
        log: Arc::clone(&log),
        times: Arc::default(),
        controlword: Arc::clone(&controlword),
        panic_at,
    };
    (bus, log, controlword)
}

#[test]
fn a_fieldbus_is_served_around_every_step_and_its_writes_reach_the_drive() {
    let (handle, _guard) = drive_runtime();
    let (bus, log, controlword) = logging_bus(None);
    handle.add_fieldbus(bus).unwrap();
    handle.advance(2).unwrap();
    assert_eq!(
        *log.lock().unwrap(),
        vec![("before", 0), ("after", 1), ("before", 1), ("after", 2)]
    );
    // Shutdown (6) then switch on (7): the drive walks the state machine on its next steps.
    *controlword.lock().unwrap() = Some(0x06);
    handle.advance(2).unwrap();
    *controlword.lock().unwrap() = Some(0x07);
    handle.advance(2).unwrap();
    let sw = handle.snapshot().drives[0].statusword;
    assert_eq!(sw & 0x6F, 0x23, "switched on, statusword {sw:#06x}");
}

#[test]
fn a_poke_serves_input_on_a_virtual_clock_without_a_tick() {
    let (handle, _guard) = drive_runtime();
    let (bus, log, _) = logging_bus(None);
    handle.add_fieldbus(bus).unwrap();
    handle.poke();
    // The poke is queued before this command, so it has been served when the reply comes.
    handle.call(enable(0)).ok();
    assert_eq!(*log.lock().unwrap(), vec![("before", 0)]);
    assert_eq!(handle.snapshot().tick, 0);
}

#[test]
fn a_panicking_fieldbus_is_removed_and_the_runtime_goes_on() {
    let (handle, _guard) = drive_runtime();
    let (bus, log, _) = logging_bus(Some(1));
    handle.add_fieldbus(bus).unwrap();
    handle.advance(3).unwrap();
    assert_eq!(
        *log.lock().unwrap(),
        vec![("before", 0), ("after", 1), ("before", 1)]
    );
    assert_eq!(handle.snapshot().tick, 3);
}

#[test]
fn a_virtual_fieldbus_runs_on_engine_time() {
    let (handle, _guard) = drive_runtime();
    let (bus, _, _) = logging_bus(None);
    let times = Arc::clone(&bus.times);
    handle.add_fieldbus(bus).unwrap();
    handle.advance(2).unwrap();
    handle.poke();
    handle.call(enable(0)).ok();
    // Default period 1 ms: before/after each step, then the poke at tick 2.
    assert_eq!(
        *times.lock().unwrap(),
        vec![Duration::ZERO, MS, MS, 2 * MS, 2 * MS]
    );
}

/// Polls `log` until it has `len` entries (the servo thread is driven by a fake clock and a
/// poke, not by time passing).
fn wait_for_calls(log: &Mutex<Vec<(&'static str, u64)>>, len: usize) {
    let give_up = Instant::now() + Duration::from_secs(60);
    while log.lock().unwrap().len() < len {
        assert!(Instant::now() < give_up, "{:?}", log.lock().unwrap());
        std::thread::sleep(Duration::from_millis(1));
    }
}

type CallLog = Arc<Mutex<Vec<(&'static str, u64)>>>;

/// A realtime runtime on a fake clock with a [`LoggingBus`] installed by its first tick (whose
/// wake-up is `lateness[0]` late), waiting at the gate: the handle, guard, clock, call log and
/// the calls' bus times.
fn paced_logging_bus(
    lateness: &[Duration],
) -> (
    EngineHandle,
    RuntimeGuard,
    FakeClock,
    CallLog,
    Arc<Mutex<Vec<Duration>>>,
) {
    let fake = FakeClock::new(lateness);
    let options = RuntimeOptions::with_clock(ClockMode::Realtime);
    let (handle, guard) = Runtime::start_with_clock(drive_engine(), options, fake.clone()).unwrap();
    let (bus, log, _) = logging_bus(None);
    let times = Arc::clone(&bus.times);
    let installed = handle.submit_fieldbus(Box::new(bus)).unwrap();
    fake.allow(1); // the first tick installs the fieldbus (before its step)
    installed.wait().unwrap();
    fake.wait_at_gate();
    (handle, guard, fake, log, times)
}

#[test]
fn a_poke_on_a_paced_clock_serves_input_between_ticks() {
    let (handle, _guard, _fake, log, times) = paced_logging_bus(&[]);
    assert_eq!(*log.lock().unwrap(), vec![("before", 0), ("after", 1)]);
    // No deadline passes (the gate holds the clock); the poke is served anyway, at tick 1.
    handle.poke();
    wait_for_calls(&log, 3);
    assert_eq!(log.lock().unwrap()[2], ("before", 1));
    // Bus time is the clock's: 1 ms after the start, the deadline the gate let through.
    assert_eq!(times.lock().unwrap()[2], MS);
}

#[test]
fn a_catch_up_burst_does_not_run_bus_time_ahead_of_the_clock() {
    // The first wake-up is 4 ms late: ticks 1–5 run back to back at clock time 5 ms.
    let (handle, _guard, _fake, log, times) = paced_logging_bus(&[4 * MS]);
    assert_eq!(handle.snapshot().tick, 5);
    let log = log.lock().unwrap();
    assert_eq!(log.len(), 10, "{log:?}");
    // Engine time ran 0 → 5 ms within the burst; bus time stayed at the clock's 5 ms, so a
    // protocol timer does not see 5 ms pass where the bus saw none.
    assert!(
        times.lock().unwrap().iter().all(|t| *t == 5 * MS),
        "{:?}",
        times.lock().unwrap()
    );
}

#[test]
fn stats_are_published_during_a_long_catch_up_batch() {
    // One wake-up 199 ms late: a batch of 200 ticks back to back.
    let lateness = [Duration::ZERO, Duration::from_millis(199)];
    let (handle, guard, fake) =
        paced_fake(ClockMode::Realtime, &lateness, RuntimeOptions::default());
    fake.wait_at_gate();
    let seen_at_150 = Arc::new(Mutex::new(None));
    let (reader, seen) = (handle.clone(), Arc::clone(&seen_at_150));
    let pending = handle
        .submit_observer(Box::new(move |engine: &Engine| {
            if engine.tick() == 151 {
                *seen.lock().unwrap() = Some(reader.stats().ticks_run);
            }
            true
        }))
        .unwrap();
    fake.allow(1); // tick 1 installs the observer
    block_on(pending.into_future()).unwrap();
    fake.allow(1);
    fake.wait_at_gate();
    assert_eq!(handle.snapshot().tick, 201);
    // 150 ticks into the batch a reader sees figures from within it, not from before it.
    let seen = seen_at_150.lock().unwrap().unwrap();
    assert!(seen > 100, "stats at tick 151 said {seen} ticks run");
    drop(guard);
}
