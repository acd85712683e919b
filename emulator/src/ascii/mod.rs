//! `mcemu run`'s HIMC Native ASCII front-end (`[frontends.ascii_native]`): bound and announced
//! (`listening: ascii-native ADDR`), served by `mcemu_ascii::transport::native` over the engine,
//! its counters in `GET /api/v1/state`. The User ASCII front-end is [`user`].
//!
//! It runs on the shared runtime (docs/decisions.md, "Native ASCII stays on the shared
//! runtime"). Only what a line sends to the engine crosses to the servo thread; a getter
//! answers from the latest snapshot.

pub mod user;

use std::sync::Arc;

use mcemu_ascii::transport::native::Server;
use mcemu_ascii::transport::serve;
use serde_json::Value;
use tokio::task::JoinSet;

use crate::frontend::{bind, handles, Frontend, FrontendContext, FrontendError, StartFuture};

/// The running Native ASCII server.
pub struct AsciiNativeFrontend {
    server: Arc<Server>,
}

impl Frontend for AsciiNativeFrontend {
    fn name(&self) -> &str {
        "ascii_native"
    }

    fn state(&self) -> Value {
        let counters =
            serde_json::to_value(self.server.counters().snapshot()).unwrap_or(Value::Null);
        serde_json::json!({ "name": "ascii_native", "counters": counters })
    }
}

/// Bind, announce and serve `[frontends.ascii_native]` if enabled.
pub fn start<'a>(cx: &'a FrontendContext<'a>, tasks: &'a mut JoinSet<()>) -> StartFuture<'a> {
    Box::pin(async move {
        let Some(config) = cx
            .config
            .frontends
            .ascii_native
            .as_ref()
            .filter(|c| c.enabled)
        else {
            return Ok(Vec::new());
        };
        let listener = bind("ascii-native", config.bind)
            .await
            .map_err(|e| FrontendError::new("ascii_native", e))?;
        let server = Server::new(config.clone(), cx.handle.clone());
        // The E-stop input (BindEMO, digest 004 §1.10): the engine watches it every servo
        // tick; the observer reports its trips for the error latch.
        server.install_estop().await;
        cx.handle
            .add_observer_async(server.estop_observer())
            .await
            .map_err(|e| FrontendError::new("ascii_native", e))?;
        let mut shutdown = cx.shutdown.clone();
        let serving = Arc::clone(&server);
        // On the shared runtime: a thread of its own with a current-thread runtime was never
        // faster in the release bench (docs/decisions.md, "Native ASCII stays on the shared
        // runtime").
        tasks.spawn(async move {
            let stop = async move {
                let _ = shutdown.wait_for(|stop| *stop).await;
            };
            serve(listener, serving, stop).await;
        });
        Ok(handles([Arc::new(AsciiNativeFrontend { server })]))
    })
}
