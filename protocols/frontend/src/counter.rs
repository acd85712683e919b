//! Counts a front-end keeps for `GET /state`: plain atomics (relaxed: each count is independent
//! and only ever read for display), so a request path takes no lock.

use std::sync::atomic::{AtomicU64, Ordering};

/// One count.
#[derive(Debug, Default)]
pub struct Counter(AtomicU64);

impl Counter {
    pub fn inc(&self) {
        self.add(1);
    }

    pub fn add(&self, n: u64) {
        self.0.fetch_add(n, Ordering::Relaxed);
    }

    pub fn get(&self) -> u64 {
        self.0.load(Ordering::Relaxed)
    }

    /// Back to 0: only for counts a protocol lets its client clear (Modbus FC 8 diagnostics).
    pub fn reset(&self) {
        self.0.store(0, Ordering::Relaxed);
    }
}

/// The connections of one TCP front-end, kept by [`crate::bound`].
#[derive(Debug, Default)]
pub struct ConnectionCounters {
    /// Connections admitted.
    pub opened: Counter,
    /// Admitted connections that have ended (evicted ones included).
    pub closed: Counter,
    /// Connections closed at once because `max_connections` were open (`at_limit = "refuse"`,
    /// or every open connection was in the middle of a request).
    pub refused_at_limit: Counter,
    /// Connections closed to admit a new one because they had been idle longest
    /// (`at_limit = "evict_idle"`).
    pub evicted_idle: Counter,
}

impl ConnectionCounters {
    /// Connections open now.
    pub fn open(&self) -> u64 {
        self.opened.get().saturating_sub(self.closed.get())
    }
}
