//! What a hub counts: a plain snapshot, cheap to take, for the control API and tests.

use std::time::Duration;

use crate::endpoint::EndpointId;

/// A snapshot of a bus's counters.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BusCounters {
    /// Frames that went over the bus (each once, however many endpoints received it).
    pub frames: u64,
    /// Their data bytes.
    pub data_bytes: u64,
    /// Error frames among them.
    pub error_frames: u64,
    /// Deliveries lost because an endpoint's receive queue was full (all endpoints, including
    /// detached ones).
    pub rx_dropped: u64,
    /// Frames refused because the bus's transmit queue was full (bit-rate model on).
    pub tx_overflow: u64,
    /// Frames the candump log dropped because its writer fell behind.
    pub log_dropped: u64,
    /// Frames waiting for the bus (bit-rate model on).
    pub pending: usize,
    /// Bus time spent transmitting (bit-rate model on; 0 without it).
    pub busy: Duration,
    /// Bus time since the hub started.
    pub elapsed: Duration,
    /// Longest time from `send` to delivery (queueing plus transmission; 0 without the model).
    pub latency_max: Duration,
    /// Sum of those times over `frames` (for the mean).
    pub latency_total: Duration,
    pub endpoints: Vec<EndpointCounters>,
}

/// One attached endpoint's counters.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EndpointCounters {
    pub id: EndpointId,
    pub name: String,
    pub sent: u64,
    pub received: u64,
    /// Frames it missed because its receive queue was full.
    pub dropped: u64,
}

impl BusCounters {
    /// Bus load since the start, in percent of bus time (bit-rate model on).
    pub fn load_percent(&self) -> f64 {
        percent(self.busy, self.elapsed)
    }

    /// Bus load between an earlier snapshot and this one, in percent.
    pub fn load_percent_since(&self, earlier: &BusCounters) -> f64 {
        percent(
            self.busy.saturating_sub(earlier.busy),
            self.elapsed.saturating_sub(earlier.elapsed),
        )
    }

    /// Mean time from `send` to delivery.
    pub fn latency_mean(&self) -> Duration {
        match u32::try_from(self.frames) {
            Ok(0) => Duration::ZERO,
            Ok(n) => self.latency_total / n,
            Err(_) => {
                Duration::from_secs_f64(self.latency_total.as_secs_f64() / self.frames as f64)
            }
        }
    }
}

fn percent(part: Duration, whole: Duration) -> f64 {
    if whole.is_zero() {
        0.0
    } else {
        100.0 * part.as_secs_f64() / whole.as_secs_f64()
    }
}
