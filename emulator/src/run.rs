//! `mcemu run`: the engine on its servo runtime, every enabled front-end on a tokio runtime,
//! until SIGINT or SIGTERM. Each listener prints `listening: <protocol> <address>` once bound.

use std::sync::Arc;
use std::time::{Duration, Instant};

use axes::command::{Command, Stop, StopMode};
use axes::runtime::{EngineHandle, Runtime, RuntimeOptions};
use axes::{AxisState, Engine};
use tokio::sync::watch;
use tokio::task::JoinSet;

use crate::config::Config;
use crate::control::{self, ControlState};
use crate::frontend::{bind, BindError, Frontend, FrontendContext, FrontendError, Start};
use crate::listener::BoundedListener;
use crate::state_dir::StateDir;

/// Why a machine could not run.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("{0}")]
    Config(#[from] crate::config::ConfigError),
    #[error("cannot start the servo runtime: {0}")]
    Runtime(#[from] axes::runtime::RuntimeError),
    #[error("cannot start the front-end runtime: {0}")]
    Io(#[from] std::io::Error),
    /// The control API's listener.
    #[error("{0}")]
    Bind(#[from] BindError),
    /// A protocol front-end did not start: its config section and the cause, as its module
    /// typed it (`BindError`, `ConfigError`, `SocketcandError` …).
    #[error(transparent)]
    Frontend(#[from] FrontendError),
}

/// Every protocol front-end, in start order. Adding a front-end is its module (a [`Start`]
/// function), an entry here and its config section.
pub const FRONTENDS: [Start; 5] = [
    crate::modbus::serve::start,
    crate::canopen::serve::start,
    crate::ascii::start,
    crate::ascii::user::start,
    crate::nmc::serve::start,
];

/// Start every front-end of [`FRONTENDS`]; the first failure stops the start.
pub async fn start_all(
    cx: &FrontendContext<'_>,
    tasks: &mut JoinSet<()>,
) -> Result<Vec<Arc<dyn Frontend>>, FrontendError> {
    let mut started = Vec::new();
    for start in FRONTENDS {
        started.extend(start(cx, tasks).await?);
    }
    Ok(started)
}

/// Run `config` until a signal arrives. `file` names the config in errors and is where relative
/// paths start; `state_dir` is where persisted state lives (`None`: nowhere, it lasts the run).
pub fn run(config: Config, file: &str, state_dir: Option<StateDir>) -> Result<(), RunError> {
    let engine = Engine::new(&config.engine_config()).map_err(|e| crate::config::ConfigError {
        file: file.to_string(),
        key: e.key,
        reason: e.reason,
    })?;
    let axes = engine.axis_count();
    let clock = config.machine.clock;
    let (handle, guard) = Runtime::start(engine, RuntimeOptions::with_clock(clock.0))?;
    println!(
        "mcemu: machine {}, {axes} axes, servo period {} ms, clock {clock}",
        config.machine.name,
        config.machine.period * 1e3,
    );
    let frontends = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .thread_name("mcemu-io")
        .enable_all()
        .build()?;
    let served = frontends.block_on(serve(&config, file, handle.clone(), state_dir.as_ref()));
    // Whatever ended the serving, stop the machine cleanly.
    stop_axes(&handle, axes);
    drop(frontends);
    let _ = guard.stop();
    println!("mcemu: stopped");
    served
}

/// Start every enabled front-end, the control API last (so its `listening:` line says all the
/// others are up), and serve until a signal; then stop them and save what they persist.
async fn serve(
    config: &Config,
    file: &str,
    handle: EngineHandle,
    state_dir: Option<&StateDir>,
) -> Result<(), RunError> {
    let stop = signals();
    let (shutdown_tx, shutdown) = watch::channel(false);
    let mut servers = tokio::task::JoinSet::new();
    let cx = FrontendContext {
        config,
        file,
        handle: &handle,
        state_dir,
        shutdown: &shutdown,
    };
    let frontends = start_all(&cx, &mut servers).await?;
    let control = &config.frontends.control;
    let mut control_task = None;
    if control.enabled {
        let (access, generated) = control::Access::for_bind(control.bind, control.token.as_deref());
        if let Some(token) = generated {
            // Before the `listening:` line, so whoever waits for that has the token too.
            println!("control token: {token}");
        }
        let listener = BoundedListener::new(
            bind("control", control.bind).await?,
            control.max_connections,
        );
        let can_log = frontends.iter().find_map(|f| f.can_log());
        let app = control::router(
            ControlState::new(handle.clone(), config)
                .with_frontends(frontends.clone())
                .with_can_log(can_log)
                .with_access(access),
        );
        control_task = Some(tokio::spawn(async move {
            if let Err(e) = axum::serve(listener, app).await {
                tracing::error!(error = %e, "control API stopped");
            }
        }));
    }
    stop.await;
    if let Some(task) = control_task {
        task.abort();
    }
    // Front-ends stop accepting and close their connections; a second is plenty.
    let _ = shutdown_tx.send(true);
    let _ = tokio::time::timeout(Duration::from_secs(1), async {
        for frontend in &frontends {
            frontend.shutdown().await;
        }
    })
    .await;
    let drained = tokio::time::timeout(Duration::from_secs(1), async {
        while servers.join_next().await.is_some() {}
    })
    .await;
    if drained.is_err() {
        servers.abort_all();
    }
    for frontend in &frontends {
        frontend.save();
    }
    Ok(())
}

/// Register SIGINT and SIGTERM handlers now, before any listener is announced (a supervisor or
/// test may signal as soon as it reads a `listening:` line), and return the wait for either.
fn signals() -> impl std::future::Future<Output = ()> {
    #[cfg(unix)]
    {
        use tokio::signal::unix::{signal, SignalKind};
        let streams = (
            signal(SignalKind::interrupt()),
            signal(SignalKind::terminate()),
        );
        async move {
            match streams {
                (Ok(mut int), Ok(mut term)) => {
                    tokio::select! {
                        _ = int.recv() => {}
                        _ = term.recv() => {}
                    }
                }
                _ => {
                    let _ = tokio::signal::ctrl_c().await;
                }
            }
        }
    }
    #[cfg(not(unix))]
    {
        async {
            let _ = tokio::signal::ctrl_c().await;
        }
    }
}

/// Bring every axis to rest before the engine stops: an abrupt stop, then up to a second of
/// wall time for the ramps (a virtual clock does not move without an advance, so it skips the
/// wait).
fn stop_axes(handle: &EngineHandle, axes: usize) {
    for axis in 0..axes as u16 {
        let _ = handle.call(Command::from(Stop {
            axis,
            mode: StopMode::Abrupt,
            deceleration: None,
        }));
    }
    if handle.clock() == axes::runtime::ClockMode::Virtual {
        return;
    }
    let deadline = Instant::now() + Duration::from_secs(1);
    while Instant::now() < deadline {
        let at_rest = handle
            .snapshot()
            .axes
            .iter()
            .all(|a| a.state != AxisState::Stopping && a.cmd_vel == 0.0);
        if at_rest {
            break;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}
