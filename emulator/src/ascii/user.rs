//! `mcemu run`'s HIMC User ASCII front-end (`[frontends.ascii_user]`): bound and announced
//! (`listening: ascii-user ADDR`), served by `mcemu_ascii::transport::user` over the engine; its
//! counters in `GET /api/v1/state`, its broadcast at `POST /api/v1/frontends/ascii_user/broadcast`.

use std::sync::Arc;

use mcemu_ascii::transport::serve;
use mcemu_ascii::transport::user::Server;
use serde_json::Value;
use tokio::task::JoinSet;

use crate::control::ApiError;
use crate::frontend::{bind, handles, Frontend, FrontendContext, FrontendError, StartFuture};

/// The running User ASCII server.
pub struct AsciiUserFrontend {
    server: Arc<Server>,
}

impl Frontend for AsciiUserFrontend {
    fn name(&self) -> &str {
        "ascii_user"
    }

    fn state(&self) -> Value {
        let counters =
            serde_json::to_value(self.server.counters().snapshot()).unwrap_or(Value::Null);
        serde_json::json!({ "name": "ascii_user", "counters": counters })
    }

    fn broadcast(&self, message: &str) -> Result<Value, ApiError> {
        match self.server.broadcast(message) {
            Ok(clients) => Ok(serde_json::json!({ "bytes": message.len(), "clients": clients })),
            Err(e) => Err(ApiError::BroadcastTooLong {
                length: e.length,
                limit: mcemu_ascii::user::BROADCAST_MAX,
            }),
        }
    }
}

/// Bind, announce and serve `[frontends.ascii_user]` if enabled.
pub fn start<'a>(cx: &'a FrontendContext<'a>, tasks: &'a mut JoinSet<()>) -> StartFuture<'a> {
    Box::pin(async move {
        let Some(config) = cx
            .config
            .frontends
            .ascii_user
            .as_ref()
            .filter(|c| c.enabled)
        else {
            return Ok(Vec::new());
        };
        let server = Server::new(config.clone(), cx.handle.clone())
            .map_err(|e| FrontendError::new("ascii_user", e))?;
        let listener = bind("ascii-user", config.bind)
            .await
            .map_err(|e| FrontendError::new("ascii_user", e))?;
        let mut shutdown = cx.shutdown.clone();
        let serving = Arc::clone(&server);
        tasks.spawn(async move {
            let stop = async move {
                let _ = shutdown.wait_for(|stop| *stop).await;
            };
            serve(listener, serving, stop).await;
        });
        Ok(handles([Arc::new(AsciiUserFrontend { server })]))
    })
}
