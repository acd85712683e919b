//! `mcemu run`'s Modbus front-ends: each enabled section bound (or its pty created) and
//! announced, its units served over the engine, its faults and counters reachable through the
//! control API, its persisted memory areas loaded at start and saved while it runs.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

use mcemu_modbus::faults::FaultSpec;
use mcemu_modbus::map::{MapModel, UnitService};
use mcemu_modbus::state::{Framing, FrontendState};
use mcemu_modbus::transport::rtu::{serve_rtu, RtuLine};
use mcemu_modbus::transport::rtu_over_tcp::serve_rtu_over_tcp;
use mcemu_modbus::transport::tcp::serve_tcp;
use serde_json::{json, Map, Value};
use tokio::sync::watch;
use tokio::task::JoinSet;

use crate::config::ConfigError;
use crate::control::ApiError;
use crate::frontend::{announce, bind, FrontendError};
use crate::frontend::{handles, Frontend, FrontendContext, StartFuture};
use crate::state_dir::StateDir;

/// How often a front-end with persisted areas checks for writes to save.
const SAVE_INTERVAL: Duration = Duration::from_secs(1);

/// One running Modbus front-end (a config section).
pub struct ModbusFrontend {
    state: Arc<FrontendState>,
    units: Vec<(Option<u8>, Arc<UnitService>)>,
    /// Where its persisted areas live; `None` when it has none or there is no state directory.
    store: Option<StateDir>,
    /// Memory writes (summed over units) at the last save.
    saved_writes: AtomicU64,
}

impl ModbusFrontend {
    fn file(&self) -> String {
        format!("modbus/{}.json", self.state.name())
    }

    fn memory_writes(&self) -> u64 {
        self.units.iter().map(|(_, u)| u.memory_writes()).sum()
    }

    /// Load the persisted areas saved by an earlier run. A file that cannot be used is reported
    /// and left alone (the next save replaces it); the areas keep their initial values.
    fn load(&self) {
        let Some(store) = &self.store else { return };
        let file = self.file();
        let warn = |reason: String| {
            tracing::warn!(file = %store.display(&file), "persisted Modbus memory not restored: {reason}");
            eprintln!(
                "mcemu: {}: persisted Modbus memory not restored: {reason}",
                store.display(&file)
            );
        };
        let bytes = match store.read(&file) {
            Ok(Some(b)) => b,
            Ok(None) => return,
            Err(e) => return warn(format!("cannot read it: {e}")),
        };
        let saved: Value = match serde_json::from_slice(&bytes) {
            Ok(v) => v,
            Err(e) => return warn(format!("not JSON: {e}")),
        };
        for (id, service) in &self.units {
            let key = unit_key(*id);
            let Some(areas) = saved.get("units").and_then(|u| u.get(&key)) else {
                continue;
            };
            for (name, _) in service.persisted() {
                let Some(words) = areas.get(&name) else {
                    continue;
                };
                let words: Option<Vec<u16>> = words.as_array().and_then(|a| {
                    a.iter()
                        .map(|w| w.as_u64().and_then(|w| u16::try_from(w).ok()))
                        .collect()
                });
                let restored = words
                    .ok_or_else(|| "not a list of 16-bit words".to_string())
                    .and_then(|w| service.restore(&name, &w));
                if let Err(reason) = restored {
                    warn(format!("units.{key}.{name}: {reason}"));
                }
            }
        }
        self.saved_writes
            .store(self.memory_writes(), Ordering::Release);
    }

    /// Save the persisted areas if memory was written since the last save.
    pub fn save_if_changed(&self) {
        let Some(store) = &self.store else { return };
        let writes = self.memory_writes();
        if writes == self.saved_writes.load(Ordering::Acquire) {
            return;
        }
        let mut units = Map::new();
        for (id, service) in &self.units {
            let areas: Map<String, Value> = service
                .persisted()
                .into_iter()
                .map(|(name, words)| (name, json!(words)))
                .collect();
            if !areas.is_empty() {
                units.insert(unit_key(*id), Value::Object(areas));
            }
        }
        let text = json!({ "frontend": self.state.name(), "units": units }).to_string();
        match store.write(&self.file(), text.as_bytes()) {
            Ok(()) => self.saved_writes.store(writes, Ordering::Release),
            Err(e) => tracing::error!(
                file = %store.display(&self.file()),
                error = %e,
                "cannot save persisted Modbus memory"
            ),
        }
    }
}

fn unit_key(id: Option<u8>) -> String {
    id.map_or_else(|| "any".to_string(), |id| id.to_string())
}

impl Frontend for ModbusFrontend {
    fn name(&self) -> &str {
        self.state.name()
    }

    fn inject(&self, fault: Map<String, Value>) -> Result<Value, ApiError> {
        self.state
            .inject(&fault)
            .map_err(|e| ApiError::InvalidBody {
                detail: e.message,
                field: e.field,
                line: 0,
                column: 0,
            })
    }

    fn state(&self) -> Value {
        serde_json::to_value(self.state.snapshot()).unwrap_or(Value::Null)
    }

    fn save(&self) {
        self.save_if_changed();
    }
}

/// Bind, open and announce every enabled Modbus section and spawn its transport (and its saver)
/// on `tasks`.
pub fn start<'a>(cx: &'a FrontendContext<'a>, tasks: &'a mut JoinSet<()>) -> StartFuture<'a> {
    Box::pin(async move { Ok(handles(start_sections(cx, tasks).await?)) })
}

async fn start_sections(
    cx: &FrontendContext<'_>,
    tasks: &mut JoinSet<()>,
) -> Result<Vec<Arc<ModbusFrontend>>, FrontendError> {
    let f = &cx.config.frontends;
    // Compiled by `Config::check` already; a failure here names the key all the same.
    let mut units = cx
        .config
        .modbus_units(cx.file)
        .map_err(|e| FrontendError::new("modbus", e))?;
    let mut take = |section: &str| {
        units
            .iter()
            .position(|(s, _)| *s == section)
            .map(|i| units.swap_remove(i).1)
            .unwrap_or_default()
    };
    let mut started = Vec::new();
    if let Some(c) = f.modbus_tcp.as_ref().filter(|c| c.enabled) {
        let section = "modbus_tcp";
        let frontend = frontend(cx, section, Framing::Tcp, &c.faults, take(section))
            .map_err(|e| FrontendError::new(section, e))?;
        let listener = bind("modbus-tcp", c.bind)
            .await
            .map_err(|e| FrontendError::new(section, e))?;
        let (model, state, config) = (frontend.model(), Arc::clone(&frontend.state), c.clone());
        let stop = stopped(cx.shutdown);
        tasks.spawn(async move { serve_tcp(listener, model, &config, state, stop).await });
        started.push(frontend);
    }
    if let Some(c) = f.modbus_rtu.as_ref().filter(|c| c.enabled) {
        let section = "modbus_rtu";
        let fail = |e| FrontendError::new(section, e);
        let frontend =
            frontend(cx, section, Framing::Rtu, &c.faults, take(section)).map_err(fail)?;
        let line = RtuLine::open(c)
            .map_err(|e| ConfigError {
                file: cx.file.to_string(),
                key: "frontends.modbus_rtu.device".into(),
                reason: e.to_string(),
            })
            .map_err(fail)?;
        announce("modbus-rtu", line.path());
        let (model, state) = (frontend.model(), Arc::clone(&frontend.state));
        let stop = stopped(cx.shutdown);
        tasks.spawn(async move {
            if let Err(e) = serve_rtu(line, model, state, stop).await {
                tracing::error!(error = %e, "modbus_rtu: the serial line failed; no longer served");
            }
        });
        started.push(frontend);
    }
    if let Some(c) = f.modbus_rtu_over_tcp.as_ref().filter(|c| c.enabled) {
        let section = "modbus_rtu_over_tcp";
        let frontend = frontend(cx, section, Framing::RtuOverTcp, &c.faults, take(section))
            .map_err(|e| FrontendError::new(section, e))?;
        let listener = bind("modbus-rtu-over-tcp", c.bind)
            .await
            .map_err(|e| FrontendError::new(section, e))?;
        let (model, state, config) = (frontend.model(), Arc::clone(&frontend.state), c.clone());
        let stop = stopped(cx.shutdown);
        tasks.spawn(async move { serve_rtu_over_tcp(listener, model, &config, state, stop).await });
        started.push(frontend);
    }
    for frontend in &started {
        if frontend.store.is_none() {
            continue;
        }
        let (frontend, mut shutdown) = (Arc::clone(frontend), cx.shutdown.clone());
        tasks.spawn(async move {
            let mut every = tokio::time::interval(SAVE_INTERVAL);
            loop {
                tokio::select! {
                    _ = every.tick() => frontend.save_if_changed(),
                    _ = shutdown.wait_for(|stop| *stop) => break,
                }
            }
        });
    }
    Ok(started)
}

impl ModbusFrontend {
    fn model(&self) -> Arc<MapModel> {
        Arc::new(MapModel::new(self.units.clone()))
    }
}

fn frontend(
    cx: &FrontendContext<'_>,
    section: &str,
    framing: Framing,
    faults: &[FaultSpec],
    units: Vec<crate::modbus::Unit>,
) -> Result<Arc<ModbusFrontend>, ConfigError> {
    // Checked by `Config::check` already; a failure here names the key all the same.
    let state = FrontendState::new(section, framing, faults).map_err(|e| ConfigError {
        file: cx.file.to_string(),
        key: format!("frontends.{section}.faults"),
        reason: e.message,
    })?;
    let units: Vec<(Option<u8>, Arc<UnitService>)> = units
        .into_iter()
        .map(|u| (u.id, Arc::new(UnitService::new(u.map, cx.handle.clone()))))
        .collect();
    let persists = units.iter().any(|(_, u)| !u.persisted().is_empty());
    let frontend = ModbusFrontend {
        state: Arc::new(state),
        units,
        store: cx.state_dir.filter(|_| persists).cloned(),
        saved_writes: AtomicU64::new(0),
    };
    frontend.load();
    Ok(Arc::new(frontend))
}

/// A future that resolves when the machine stops.
fn stopped(shutdown: &watch::Receiver<bool>) -> impl std::future::Future<Output = ()> + 'static {
    let mut shutdown = shutdown.clone();
    async move {
        let _ = shutdown.wait_for(|stop| *stop).await;
    }
}
