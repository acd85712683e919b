//! The tokio server over [`Native`]: the front-end kit's bounded accept loop; per connection,
//! read → [`LineSplitter`] → [`Native::line`] → the engine if asked → reply, one line after the
//! other. Clients interleave at line boundaries: each is its own task, and the registers they
//! share are locked only while a line is handled, never across an await.

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use axes::runtime::{CallError, EngineHandle};
use axes::AxisState;
use mcemu_dialects::himc::system::HMPL_STR_MAX_LEN;
use mcemu_frontend::bound::{self, Bound, Connection, ConnectionTable};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};

use crate::config::NativeConfig;
use crate::counters::Counters;
use crate::line::{Line, LineSplitter};
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
}

impl Server {
    pub fn new(config: NativeConfig, engine: EngineHandle) -> Arc<Server> {
        let counters = Arc::new(Counters::default());
        Arc::new(Server {
            native: Native::new(config.options(), counters),
            registers: Mutex::new(Registers::default()),
            engine,
            config,
        })
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
        let step = self.native.line(line, &snapshot, &mut self.registers());
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

/// Accept clients on `listener` until `shutdown`, within the config's connection bound.
pub async fn serve(
    listener: TcpListener,
    server: Arc<Server>,
    shutdown: impl std::future::Future<Output = ()>,
) {
    let bound = Bound {
        max_connections: server.config.max_connections,
        at_limit: server.config.at_limit,
    };
    let table = ConnectionTable::new(bound, Arc::clone(&server.counters().connections));
    let refuse = |stream: TcpStream, _| async move { drop(stream) };
    let serve = |c: Connection| connection(Arc::clone(&server), c);
    bound::serve(listener, table, "ascii_native", shutdown, serve, refuse).await;
}

fn limit(ms: u64) -> Option<Duration> {
    (ms > 0).then(|| Duration::from_millis(ms))
}

/// Run `work`, giving up after `limit` if there is one.
async fn within<T>(
    limit: Option<Duration>,
    work: impl std::future::Future<Output = T>,
) -> Option<T> {
    match limit {
        Some(d) => tokio::time::timeout(d, work).await.ok(),
        None => Some(work.await),
    }
}

async fn connection(server: Arc<Server>, mut c: Connection) {
    let counters = server.counters();
    let idle = limit(server.config.idle_timeout_ms);
    let write_limit = limit(server.config.write_timeout_ms);
    let mut splitter = LineSplitter::new(HMPL_STR_MAX_LEN);
    let mut buf = vec![0u8; 4096];
    let mut lines = Vec::new();
    loop {
        let read = tokio::select! {
            r = within(idle, c.stream.read(&mut buf)) => r,
            () = bound::stopping(&mut c.stop) => return,
        };
        let n = match read {
            None => {
                counters.idle_timeouts.inc();
                tracing::info!("closed: idle for {} ms", server.config.idle_timeout_ms);
                return;
            }
            Some(Ok(n)) if n > 0 => n,
            // Closed or failed: a line it had begun is dropped, unanswered.
            Some(_) => {
                if splitter.in_line() {
                    counters.partial_lines.inc();
                }
                return;
            }
        };
        c.activity.received();
        counters.bytes_in.add(n as u64);
        splitter.push(buf.get(..n).unwrap_or_default(), &mut lines);
        for line in lines.drain(..) {
            let reply = {
                let _in_request = c.activity.request();
                server.handle(&line).await
            };
            let written = within(write_limit, c.stream.write_all(reply.as_bytes())).await;
            match written {
                Some(Ok(())) => {}
                Some(Err(_)) => return,
                None => {
                    counters.write_timeouts.inc();
                    tracing::info!("closed: the client takes no replies");
                    return;
                }
            }
        }
    }
}
