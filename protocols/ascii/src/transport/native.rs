//! The Native ASCII server over [`Native`]: a line → [`Native::line`] → the engine if asked →
//! the reply. The registers its clients share are locked only while a line is handled, never
//! across an await.

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use axes::runtime::{CallError, EngineHandle};
use axes::{AxisState, Engine};
use mcemu_dialects::himc::system::EMERGENCY_STOP;

use super::{Limits, LineServer};
use crate::config::NativeConfig;
use crate::counters::{Counters, StreamCounters};
use crate::estop::{self, Binding, EstopSent, EstopTrips};
use crate::line::Line;
use crate::native::{Native, Pending, Step};
use crate::registers::Registers;
use crate::table::Then;

/// How often a `MoveHome` that waits looks at the snapshot again.
const HOMING_POLL: Duration = Duration::from_millis(5);

/// One Native ASCII server: the core, the registers its clients share, the engine.
pub struct Server {
    native: Native,
    registers: Mutex<Registers>,
    engine: EngineHandle,
    config: NativeConfig,
    /// The E-stop input binding the engine holds (`BindEMO`, `SetGPIInvert`).
    estop_sent: EstopSent,
    /// Serialises sending it, so the engine ends with the registers' latest.
    estop_sending: tokio::sync::Mutex<()>,
    /// The engine's E-stop trips, published by the observer after every tick.
    estop_trips: Arc<EstopTrips>,
}

impl Server {
    pub fn new(config: NativeConfig, engine: EngineHandle) -> Arc<Server> {
        let counters = Arc::new(Counters::default());
        Arc::new(Server {
            native: Native::new(config.options(), counters),
            registers: Mutex::new(Registers::default()),
            engine,
            config,
            estop_sent: EstopSent::new(),
            estop_sending: tokio::sync::Mutex::new(()),
            estop_trips: Arc::new(EstopTrips::default()),
        })
    }

    /// The engine observer that reports the E-stop input's trips (digest 004 §1.10; the engine
    /// stops the axes itself, in the tick that reads the edge): the next line latches
    /// `eERR_EMERGENCY_STOP`. Install it with `EngineHandle::add_observer_async`.
    pub fn estop_observer(&self) -> impl FnMut(&Engine) -> bool + Send + 'static {
        let trips = Arc::clone(&self.estop_trips);
        move |e: &Engine| {
            trips.publish(e.estop_input_trips());
            true
        }
    }

    /// Bind the controller's E-stop input in the engine (GPI 8 at start): call once before
    /// serving.
    pub async fn install_estop(&self) {
        self.send_estop().await;
    }

    /// Send the registers' binding unless the engine holds it; read under the sending lock, so
    /// concurrent lines leave the engine with the latest.
    async fn send_estop(&self) {
        let _sending = self.estop_sending.lock().await;
        let binding: Binding = self.registers().estop_binding();
        if self.estop_sent.holds(binding) {
            return;
        }
        // A pin the machine lacks binds nothing (the engine refuses it, and an input it does
        // not have never rises); a stopped engine has nothing to stop.
        let _ = self.engine.call_async(estop::command(binding)).await;
        self.estop_sent.sent(binding);
    }

    pub fn counters(&self) -> &Counters {
        self.native.counters()
    }

    fn registers(&self) -> MutexGuard<'_, Registers> {
        // Each change is one assignment: a poisoned lock still holds whole registers.
        self.registers.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The reply to one line, after the engine if the call needs it.
    pub async fn handle(&self, line: &Line) -> String {
        let snapshot = self.engine.snapshot();
        let (step, estop) = {
            let mut registers = self.registers();
            if self.estop_trips.take_tripped() {
                registers.latch(EMERGENCY_STOP);
            }
            let step = self.native.line(line, &snapshot, &mut registers);
            (step, registers.estop_binding())
        };
        if !self.estop_sent.holds(estop) {
            self.send_estop().await;
        }
        let (commands, pending) = match step {
            Step::Reply(text) => return text,
            Step::Engine(commands, pending) => (commands, pending),
        };
        let result = match self.engine.call_batch_async(commands).await {
            Ok(replies) if matches!(pending.then, Then::Object(_)) => {
                return self
                    .native
                    .finish_object(&pending, &replies, &mut self.registers());
            }
            Ok(_) => Ok(()),
            Err(CallError::Engine(e)) => Err(Some(e)),
            Err(_) => Err(None),
        };
        if let (Ok(()), Then::AwaitHoming(axis)) = (&result, pending.then) {
            let homed = self.homing_ended(axis).await;
            return self
                .native
                .finish_homing(&pending, homed, &mut self.registers());
        }
        self.finish(&pending, result)
    }

    fn finish(&self, pending: &Pending, result: Result<(), Option<axes::EngineError>>) -> String {
        self.native.finish(pending, result, &mut self.registers())
    }

    /// Wait until axis `axis` is no longer homing (in a snapshot published after the command
    /// was applied); whether it is homed then.
    async fn homing_ended(&self, axis: u16) -> bool {
        let applied = self.engine.snapshot().tick;
        loop {
            let s = self.engine.snapshot();
            let status = s.axes.get(usize::from(axis));
            if s.tick > applied && status.is_none_or(|a| a.state != AxisState::Homing) {
                return status.is_some_and(|a| a.flags.contains(axes::AxisFlags::HOMED));
            }
            if !self.engine.is_running() {
                return false;
            }
            tokio::time::sleep(HOMING_POLL).await;
        }
    }
}

impl LineServer for Server {
    fn handle(&self, line: &Line) -> impl std::future::Future<Output = String> + Send {
        Server::handle(self, line)
    }

    fn limits(&self) -> Limits {
        Limits {
            frontend: "ascii_native",
            max_connections: self.config.max_connections,
            at_limit: self.config.at_limit,
            idle_timeout_ms: self.config.idle_timeout_ms,
            write_timeout_ms: self.config.write_timeout_ms,
        }
    }

    fn stream_counters(&self) -> &StreamCounters {
        &self.native.counters().stream
    }
}
