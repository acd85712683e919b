//! The protocol front-ends' lifecycle in `mcemu run`. Each front-end module exports one start
//! function over a [`FrontendContext`] ([`Start`]), listed in `crate::run::FRONTENDS`; what it starts it
//! returns as handles implementing [`Frontend`], which `mcemu run` hands to the control API and
//! later shuts down and saves. Adding a front-end is its module, an entry in `FRONTENDS` and
//! its config section.
//!
//! Order (`crate::run`): every listed front-end starts, in list order; the control API starts
//! last, over their handles; at a signal the context's `shutdown` turns `true`, each handle's
//! [`Frontend::shutdown`] runs (a second for all), the tasks they spawned drain (a second), and
//! each handle's [`Frontend::save`] runs.

use std::future::Future;
use std::io::Write;
use std::pin::Pin;
use std::sync::{Arc, Mutex, PoisonError};

use axes::runtime::EngineHandle;
use serde_json::{Map, Value};
use tokio::sync::watch;
use tokio::task::JoinSet;

use tokio::net::TcpListener;

use crate::config::Config;
use crate::control::error::ApiError;
use crate::state_dir::StateDir;

/// What a protocol front-end needs of `mcemu run` to start.
pub struct FrontendContext<'a> {
    pub config: &'a Config,
    /// The config file: errors name it, relative paths start from it.
    pub file: &'a str,
    pub handle: &'a EngineHandle,
    pub state_dir: Option<&'a StateDir>,
    /// Turns `true` when the machine stops.
    pub shutdown: &'a watch::Receiver<bool>,
}

/// A running protocol front-end: what the control API shows and injects (its counters in
/// `GET /state`, its own faults — frame delay/drop, Modbus exceptions … — through
/// `POST /faults` with `{"frontend": NAME, …}`), and what `mcemu run` stops and saves.
pub trait Frontend: Send + Sync {
    /// The name requests use: the front-end's config section (`modbus_tcp`, `canopen` …).
    fn name(&self) -> &str;
    /// Inject or clear a fault; `fault` is the request body without `frontend`. By default
    /// the front-end has none, and says so.
    fn inject(&self, _fault: Map<String, Value>) -> Result<Value, ApiError> {
        Err(ApiError::InvalidBody {
            detail: format!("{} has no faults to inject", self.name()),
            field: Some("frontend".into()),
            line: 0,
            column: 0,
        })
    }
    /// Counters, active faults and last error, for `GET /state`'s `frontends`.
    fn state(&self) -> Value;
    /// Stop serving what does not stop by itself when the context's `shutdown` turns `true`
    /// (transports with a stop of their own). Nothing, by default.
    fn shutdown(&self) -> Pin<Box<dyn Future<Output = ()> + '_>> {
        Box::pin(async {})
    }
    /// Save what it persists, after it stopped serving. Nothing, by default.
    fn save(&self) {}
    /// Send `message` to every client (`POST /api/v1/frontends/NAME/broadcast`; User ASCII's
    /// `ASCII_ServerBroadcast`); what was sent. Refused by default: most protocols have none.
    fn broadcast(&self, _message: &str) -> Result<Value, ApiError> {
        Err(ApiError::NoBroadcast {
            name: self.name().to_string(),
        })
    }
    /// The CAN bus's `candump -L` log, for `/canopen/log/*`, if this front-end has a CAN bus.
    fn can_log(&self) -> Option<Arc<dyn CanLog>> {
        None
    }
}

/// The CAN bus's `candump -L` log, started and stopped at run time (`/canopen/log/*`).
pub trait CanLog: Send + Sync {
    /// Start logging to `path` (relative: from the config file's directory); what runs now.
    fn start(&self, path: &str) -> Result<Value, ApiError>;
    /// Stop the log that runs, whoever started it; what it wrote.
    fn stop(&self) -> Result<Value, ApiError>;
}

/// A protocol front-end did not start: its config section and the cause, as its module typed
/// it (`BindError`, `ConfigError`, `SocketcandError` …), reachable through `source()`.
#[derive(Debug, thiserror::Error)]
#[error("{frontend}: {source}")]
pub struct FrontendError {
    pub frontend: &'static str,
    pub source: Box<dyn std::error::Error + Send + Sync>,
}

impl FrontendError {
    /// Front-end `frontend` (its config section) did not start because of `cause`.
    pub fn new(
        frontend: &'static str,
        cause: impl Into<Box<dyn std::error::Error + Send + Sync>>,
    ) -> FrontendError {
        FrontendError {
            frontend,
            source: cause.into(),
        }
    }
}

/// A TCP listener that could not be bound.
#[derive(Debug, thiserror::Error)]
#[error("cannot listen on {address} for {protocol}: {source}")]
pub struct BindError {
    pub protocol: &'static str,
    pub address: std::net::SocketAddr,
    pub source: std::io::Error,
}

/// Bind and announce a TCP listener.
pub(crate) async fn bind(
    protocol: &'static str,
    address: std::net::SocketAddr,
) -> Result<TcpListener, BindError> {
    let listener = TcpListener::bind(address)
        .await
        .map_err(|source| BindError {
            protocol,
            address,
            source,
        })?;
    let local = listener.local_addr().unwrap_or(address);
    announce(protocol, local);
    Ok(listener)
}

/// Print `listening: <protocol> <address>`: tests and supervisors read these lines as they come.
/// The same pair is kept for `GET /state`'s `listeners` ([`listeners`]).
pub(crate) fn announce(protocol: &str, address: impl std::fmt::Display) {
    let address = address.to_string();
    println!("listening: {protocol} {address}");
    let _ = std::io::stdout().flush();
    LISTENERS
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .push(Listener {
            protocol: protocol.to_string(),
            address,
        });
}

/// One `listening:` line: a protocol (`modbus-tcp`, `nmc-local` …) and the address or path it
/// was bound to (port 0 resolved).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Listener {
    pub protocol: String,
    pub address: String,
}

/// Every `listening:` line this process printed, in order. Process-wide like stdout itself: a
/// process runs one machine, and each front-end announces from its own module.
static LISTENERS: Mutex<Vec<Listener>> = Mutex::new(Vec::new());

/// What this process listens on, as its `listening:` lines said.
pub fn listeners() -> Vec<Listener> {
    LISTENERS
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .clone()
}

/// What a start function gives: a handle per started front-end (none when its sections are
/// disabled), or the [`FrontendError`] naming the one that failed.
pub type StartFuture<'a> =
    Pin<Box<dyn Future<Output = Result<Vec<Arc<dyn Frontend>>, FrontendError>> + 'a>>;

/// A front-end module's start function: bind or open and announce (`listening: …`) each of its
/// enabled sections, spawn what serves them on `tasks` (they end when `cx.shutdown` turns
/// `true`), and return their handles.
pub type Start = for<'a> fn(&'a FrontendContext<'a>, &'a mut JoinSet<()>) -> StartFuture<'a>;

/// A start function's handles, from its front-end's own type.
pub fn handles<F: Frontend + 'static>(
    started: impl IntoIterator<Item = Arc<F>>,
) -> Vec<Arc<dyn Frontend>> {
    started
        .into_iter()
        .map(|f| f as Arc<dyn Frontend>)
        .collect()
}

#[cfg(test)]
mod tests {
    use std::error::Error;
    use std::io;

    use axes::runtime::{ClockMode, Runtime, RuntimeOptions};
    use axes::Engine;

    use super::*;
    use crate::run::RunError;

    /// Start the front-ends of `config` on a virtual machine; the error it gives.
    async fn start_error(config: &str) -> RunError {
        let config = Config::parse(config, "m.toml").unwrap();
        let engine = Engine::new(&config.engine_config()).unwrap();
        let (handle, guard) =
            Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap();
        let (_stop, shutdown) = watch::channel(false);
        let cx = FrontendContext {
            config: &config,
            file: "m.toml",
            handle: &handle,
            state_dir: None,
            shutdown: &shutdown,
        };
        let mut tasks = JoinSet::new();
        let Err(e) = crate::run::start_all(&cx, &mut tasks).await else {
            panic!("{config:?} started");
        };
        tasks.abort_all();
        let _ = guard.stop();
        RunError::from(e)
    }

    /// The `io::Error` at the end of `e`'s source chain.
    fn io_cause(e: &RunError) -> Option<&io::Error> {
        let mut cause = e.source();
        while let Some(c) = cause {
            if let Some(io) = c.downcast_ref::<io::Error>() {
                return Some(io);
            }
            cause = c.source();
        }
        None
    }

    #[tokio::test]
    async fn a_port_in_use_names_the_front_end_and_keeps_the_io_error() {
        let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let address = taken.local_addr().unwrap();
        let e = start_error(&format!(
            "[[axes]]\n[frontends.modbus_rtu_over_tcp]\nbind = \"{address}\"\n"
        ))
        .await;
        assert!(
            matches!(
                &e,
                RunError::Frontend(FrontendError {
                    frontend: "modbus_rtu_over_tcp",
                    ..
                })
            ),
            "{e:?}"
        );
        let bind = e.source().and_then(|c| c.downcast_ref::<BindError>());
        assert_eq!(bind.map(|b| b.address), Some(address), "{e:?}");
        assert_eq!(
            io_cause(&e).map(io::Error::kind),
            Some(io::ErrorKind::AddrInUse)
        );
        assert!(
            e.to_string().starts_with(&format!(
                "modbus_rtu_over_tcp: cannot listen on {address} for modbus-rtu-over-tcp: "
            )),
            "{e}"
        );
    }

    #[tokio::test]
    async fn socketcand_on_a_port_in_use_keeps_its_typed_error() {
        let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        let address = taken.local_addr().unwrap();
        let e = start_error(&format!(
            "[[axes]]\n[frontends.canopen]\ninterface = \"\"\n\
             [frontends.socketcand]\nbind = \"{address}\"\n"
        ))
        .await;
        assert!(
            matches!(
                &e,
                RunError::Frontend(FrontendError {
                    frontend: "socketcand",
                    ..
                })
            ),
            "{e:?}"
        );
        let cause = e
            .source()
            .and_then(|c| c.downcast_ref::<mcemu_can::socketcand::SocketcandError>());
        assert!(
            matches!(cause, Some(mcemu_can::socketcand::SocketcandError::Bind { addr, .. }) if *addr == address),
            "{e:?}"
        );
        assert_eq!(
            io_cause(&e).map(io::Error::kind),
            Some(io::ErrorKind::AddrInUse)
        );
    }
}
