//! The last request a front-end's engine refused, for `GET /state`: when, from whom, the
//! protocol's own account of the request and its answer, and the engine's reason.

use std::sync::Mutex;
use std::time::{SystemTime, UNIX_EPOCH};

use serde::Serialize;

/// One refusal; `detail` is the protocol's (Modbus: unit, function, exception), its fields
/// shown beside the others.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Refusal<T> {
    /// Wall-clock time, milliseconds since the Unix epoch.
    pub time_unix_ms: u64,
    /// `IP:port`, or the serial device path.
    pub peer: String,
    #[serde(flatten)]
    pub detail: T,
    /// The engine's reason.
    pub reason: String,
}

/// The last refusal of one front-end, replaced by each new one.
#[derive(Debug)]
pub struct LastRefusal<T>(Mutex<Option<Refusal<T>>>);

impl<T> Default for LastRefusal<T> {
    fn default() -> Self {
        LastRefusal(Mutex::new(None))
    }
}

impl<T: Clone> LastRefusal<T> {
    pub fn record(&self, peer: String, detail: T, reason: &str) {
        let time_unix_ms = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| u64::try_from(d.as_millis()).unwrap_or(u64::MAX));
        // A poisoned lock still holds a whole record (it is replaced in one assignment).
        *self.0.lock().unwrap_or_else(|e| e.into_inner()) = Some(Refusal {
            time_unix_ms,
            peer,
            detail,
            reason: reason.to_owned(),
        });
    }

    pub fn get(&self) -> Option<Refusal<T>> {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }
}
