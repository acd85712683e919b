//! The `candump -L` log of the CAN bus: started by `[frontends.canopen] log` at start, and
//! started and stopped at run time through the control API (`POST /api/v1/canopen/log/start`,
//! `/stop`). One log at a time, whoever started it; the hub writes it on a thread of its own
//! (`mcemu_can::CandumpLog`), so the bus never waits for the disk.

use std::fs::OpenOptions;
use std::io;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};

use mcemu_can::log::DEFAULT_LOG_QUEUE;
use mcemu_can::{CandumpLog, Hub};
use serde_json::{json, Value};

use crate::control::error::ApiError;
use crate::frontend::CanLog;

/// The log of one bus.
#[derive(Clone)]
pub struct BusLog {
    hub: Hub,
    /// Relative paths start here: the config file's directory, as for the config's `log`.
    base: PathBuf,
    /// The file being written, while a log runs. Held across a start or stop, so two requests
    /// cannot both start one.
    running: Arc<Mutex<Option<PathBuf>>>,
}

impl BusLog {
    pub fn new(hub: Hub, base: PathBuf) -> BusLog {
        BusLog {
            hub,
            base,
            running: Arc::new(Mutex::new(None)),
        }
    }

    fn running(&self) -> MutexGuard<'_, Option<PathBuf>> {
        self.running
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// The config's `log`: created or truncated, as candump does with its output file.
    pub fn start_from_config(&self, path: &str) -> io::Result<PathBuf> {
        let path = self.base.join(path);
        let mut running = self.running();
        let log = CandumpLog::create(&path, self.hub.name(), DEFAULT_LOG_QUEUE)?;
        let _ = self.hub.start_log(log);
        *running = Some(path.clone());
        Ok(path)
    }

    /// A log started over the API: a new file only. The API is reachable by every local user
    /// and writes as mcemu's user, so it never truncates a file that exists.
    fn start_new(&self, path: &str) -> Result<PathBuf, ApiError> {
        if path.trim().is_empty() {
            return Err(ApiError::InvalidRequest(
                "`path` is empty: give the file to write the candump log to".into(),
            ));
        }
        let path = self.base.join(path);
        let mut running = self.running();
        if let Some(current) = running.as_ref() {
            return Err(ApiError::AlreadyLogging {
                path: current.display().to_string(),
            });
        }
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
            .map_err(|e| match e.kind() {
                io::ErrorKind::AlreadyExists => ApiError::LogExists {
                    path: path.display().to_string(),
                },
                _ => ApiError::LogNotWritable {
                    path: path.display().to_string(),
                    reason: e.to_string(),
                },
            })?;
        let log = CandumpLog::to_writer(file, self.hub.name(), DEFAULT_LOG_QUEUE)
            .map_err(|e| ApiError::Internal(format!("cannot start the log writer: {e}")))?;
        let _ = self.hub.start_log(log);
        *running = Some(path.clone());
        Ok(path)
    }

    /// The file being written, if a log runs.
    pub fn path(&self) -> Option<PathBuf> {
        self.running().clone()
    }

    /// For `GET /state`: the file, or null.
    pub fn status(&self) -> Value {
        match self.path() {
            Some(path) => json!({ "path": path.display().to_string() }),
            None => Value::Null,
        }
    }
}

impl CanLog for BusLog {
    fn start(&self, path: &str) -> Result<Value, ApiError> {
        let path = self.start_new(path)?;
        Ok(json!({
            "logging": true,
            "bus": self.hub.name(),
            "path": path.display().to_string(),
        }))
    }

    /// Stops whichever log runs, the config's included; the writer flushes before the answer.
    fn stop(&self) -> Result<Value, ApiError> {
        let mut running = self.running();
        let Some(path) = running.take() else {
            return Err(ApiError::NotLogging);
        };
        match self.hub.stop_log() {
            Some(Ok(summary)) => Ok(json!({
                "logging": false,
                "bus": self.hub.name(),
                "path": path.display().to_string(),
                "lines": summary.lines,
                "dropped": summary.dropped,
            })),
            Some(Err(e)) => Err(ApiError::Internal(format!(
                "the candump log {} failed: {e}",
                path.display()
            ))),
            None => Err(ApiError::NotLogging),
        }
    }
}
