//! The User ASCII server over [`User`]: a line → [`User::line`] → the engine if asked → the
//! reply, to the asking client only; [`Server::broadcast`] writes a message to every client
//! between their lines (a channel each connection subscribes to).

use std::sync::Arc;

use axes::runtime::{CallError, EngineHandle};
use tokio::sync::broadcast;

use super::{Limits, LineServer};
use crate::counters::{StreamCounters, UserCounters};
use crate::line::Line;
use crate::user::config::{GrammarError, UserConfig};
use crate::user::{BroadcastTooLong, Step, User};

/// Broadcasts a slow client may fall behind by before it misses the oldest.
const BROADCAST_BACKLOG: usize = 64;

/// One User ASCII server: the core, the engine, the broadcast channel.
pub struct Server {
    user: User,
    engine: EngineHandle,
    config: UserConfig,
    broadcasts: broadcast::Sender<Arc<[u8]>>,
}

impl Server {
    /// The server for `config`, its grammar compiled (the config check already did so once).
    pub fn new(config: UserConfig, engine: EngineHandle) -> Result<Arc<Server>, GrammarError> {
        let user = User::new(config.grammar()?, Arc::new(UserCounters::default()));
        let (broadcasts, _) = broadcast::channel(BROADCAST_BACKLOG);
        Ok(Arc::new(Server {
            user,
            engine,
            config,
            broadcasts,
        }))
    }

    pub fn counters(&self) -> &UserCounters {
        self.user.counters()
    }

    /// Send `message` to every connected client; how many there are.
    pub fn broadcast(&self, message: &str) -> Result<usize, BroadcastTooLong> {
        let bytes = self.user.broadcast(message)?;
        // No receiver is no error: the message reaches the clients there are, none.
        Ok(self.broadcasts.send(bytes).unwrap_or(0))
    }

    /// The reply to one line, after the engine if the line asks for it.
    pub async fn handle(&self, line: &Line) -> String {
        let (commands, pending) = match self.user.line(line, &self.engine.snapshot()) {
            Step::Reply(text) => return text,
            Step::Engine(commands, pending) => (commands, pending),
        };
        let result = match self.engine.call_batch_async(commands).await {
            Ok(_) => Ok(()),
            Err(CallError::Engine(e)) => Err(e.to_string()),
            Err(e) => Err(e.to_string()),
        };
        self.user.finish(pending, result, &self.engine.snapshot())
    }
}

impl LineServer for Server {
    fn handle(&self, line: &Line) -> impl std::future::Future<Output = String> + Send {
        Server::handle(self, line)
    }

    fn limits(&self) -> Limits {
        Limits {
            frontend: "ascii_user",
            max_connections: self.config.max_connections,
            at_limit: self.config.at_limit,
            idle_timeout_ms: self.config.idle_timeout_ms,
            write_timeout_ms: self.config.write_timeout_ms,
        }
    }

    fn stream_counters(&self) -> &StreamCounters {
        &self.user.counters().stream
    }

    fn broadcasts(&self) -> Option<broadcast::Receiver<Arc<[u8]>>> {
        Some(self.broadcasts.subscribe())
    }
}
