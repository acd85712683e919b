//! Bus time and wall-clock stamps.
//!
//! Bus time is a `Duration` since the hub started: real (measured with `Instant`) or virtual
//! (set by the caller, e.g. from the engine's tick count). Logs and socketcand need wall-clock
//! stamps; they are the hub's epoch plus bus time, so a virtual-clock run logs reproducible
//! stamps when its epoch is fixed.

use std::fmt;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

/// Where a hub's bus time comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Clock {
    /// Time since the hub was created, from the OS's monotonic clock.
    #[default]
    Real,
    /// Time set by [`crate::Hub::advance`]; it stands still in between.
    Virtual,
}

/// A wall-clock stamp in seconds and microseconds since the Unix epoch, as candump and
/// socketcand print it (`1700000000.123456`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Timestamp {
    pub secs: u64,
    pub micros: u32,
}

impl Timestamp {
    /// `epoch + at`, truncated to microseconds.
    pub fn at(epoch: Duration, at: Duration) -> Self {
        let t = epoch.saturating_add(at);
        Self {
            secs: t.as_secs(),
            micros: t.subsec_micros(),
        }
    }

    /// The wall clock now, as an epoch for bus time 0.
    pub fn now_epoch() -> Duration {
        SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .unwrap_or(Duration::ZERO)
    }
}

impl fmt::Display for Timestamp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}.{:06}", self.secs, self.micros)
    }
}
