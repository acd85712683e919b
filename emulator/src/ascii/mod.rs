//! `mcemu run`'s HIMC Native ASCII front-end (`[frontends.ascii_native]`): bound and announced
//! (`listening: ascii-native ADDR`), served by `mcemu_ascii::transport::native` over the engine,
//! its counters in `GET /api/v1/state`. The User ASCII front-end is [`user`].
//!
//! It runs on a thread of its own with a single-threaded tokio runtime (issue 14,
//! Performance): a client's line is read, answered and written by the thread epoll woke,
//! without the shared runtime waking a second worker for every line. Only what a line sends to
//! the engine crosses to the servo thread; a getter answers from the latest snapshot.

pub mod user;

use std::future::Future;
use std::sync::Arc;

use mcemu_ascii::transport::native::Server;
use mcemu_ascii::transport::serve;
use serde_json::Value;
use tokio::net::TcpListener;
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
        // The E-stop input (BindEMO, digest 004 §1.10) is watched every servo tick.
        cx.handle
            .add_observer_async(server.estop_observer())
            .await
            .map_err(|e| FrontendError::new("ascii_native", e))?;
        let mut shutdown = cx.shutdown.clone();
        let serving = Arc::clone(&server);
        let done = on_own_thread("mcemu-ascii", listener, move |listener| async move {
            let stop = async move {
                let _ = shutdown.wait_for(|stop| *stop).await;
            };
            serve(listener, serving, stop).await;
        })
        .map_err(|e| FrontendError::new("ascii_native", e))?;
        tasks.spawn(async move {
            let _ = done.await;
        });
        Ok(handles([Arc::new(AsciiNativeFrontend { server })]))
    })
}

/// Run `serve(listener)` on a new thread `name` with a single-threaded runtime (the listener
/// moves to that runtime's reactor, so every connection's readiness is that thread's). The
/// receiver resolves when the serving has ended.
fn on_own_thread<F, Fut>(
    name: &str,
    listener: TcpListener,
    serve: F,
) -> std::io::Result<tokio::sync::oneshot::Receiver<()>>
where
    F: FnOnce(TcpListener) -> Fut + Send + 'static,
    Fut: Future<Output = ()>,
{
    let listener = listener.into_std()?;
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()?;
    let (done, ended) = tokio::sync::oneshot::channel();
    std::thread::Builder::new()
        .name(name.into())
        .spawn(move || {
            runtime.block_on(async move {
                match TcpListener::from_std(listener) {
                    Ok(listener) => serve(listener).await,
                    Err(e) => tracing::error!("cannot serve on its own thread: {e}"),
                }
            });
            let _ = done.send(());
        })?;
    Ok(ended)
}
