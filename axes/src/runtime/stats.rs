//! Timing statistics of the servo thread: counters and a fixed log-scale lateness histogram.

use std::time::Duration;

use serde::ser::{SerializeSeq, SerializeStruct};
use serde::{Serialize, Serializer};

use super::ClockMode;

/// R10 preferred numbers (×100): ten buckets per decade, so a quantile read as its bucket's upper
/// edge overstates by at most 26 %.
const R10: [u64; 10] = [100, 125, 160, 200, 250, 315, 400, 500, 630, 800];
/// 1 µs … 10 s.
const DECADES: usize = 7;
const EDGE_COUNT: usize = DECADES * 10 + 1;
/// One bucket per edge (values ≤ that edge) plus one overflow bucket (> 10 s).
pub const LATENESS_BUCKETS: usize = EDGE_COUNT + 1;

/// Upper bucket edges in nanoseconds: 1 µs, 1.25 µs, 1.6 µs … 8 s, 10 s.
const EDGES_NS: [u64; EDGE_COUNT] = edges();

const fn edges() -> [u64; EDGE_COUNT] {
    let mut edges = [0; EDGE_COUNT];
    let mut scale = 10; // R10[0] × 10 ns = 1 µs
    let mut decade = 0;
    while decade < DECADES {
        let mut i = 0;
        while i < 10 {
            edges[decade * 10 + i] = R10[i] * scale;
            i += 1;
        }
        scale *= 10;
        decade += 1;
    }
    edges[EDGE_COUNT - 1] = R10[0] * scale;
    edges
}

/// Histogram of wake-up lateness (how long after its deadline the servo thread woke up).
///
/// Fixed buckets, so recording never allocates. The maximum is exact; quantiles are the upper
/// edge of the bucket that holds them (capped at the maximum), i.e. "at most".
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LatenessHistogram {
    counts: [u64; LATENESS_BUCKETS],
    count: u64,
    sum_ns: u64,
    max_ns: u64,
}

impl Default for LatenessHistogram {
    fn default() -> Self {
        LatenessHistogram {
            counts: [0; LATENESS_BUCKETS],
            count: 0,
            sum_ns: 0,
            max_ns: 0,
        }
    }
}

impl LatenessHistogram {
    pub fn record(&mut self, lateness: Duration) {
        let ns = u64::try_from(lateness.as_nanos()).unwrap_or(u64::MAX);
        let bucket = EDGES_NS.partition_point(|&edge| edge < ns);
        if let Some(slot) = self.counts.get_mut(bucket) {
            *slot += 1;
        }
        self.count += 1;
        self.sum_ns = self.sum_ns.saturating_add(ns);
        self.max_ns = self.max_ns.max(ns);
    }

    /// Wake-ups recorded.
    pub fn count(&self) -> u64 {
        self.count
    }

    pub fn max(&self) -> Duration {
        Duration::from_nanos(self.max_ns)
    }

    pub fn mean(&self) -> Duration {
        Duration::from_nanos(self.sum_ns.checked_div(self.count).unwrap_or(0))
    }

    /// Upper bound of the `q`-quantile (0 ≤ q ≤ 1); zero when nothing was recorded.
    pub fn quantile(&self, q: f64) -> Duration {
        if self.count == 0 {
            return Duration::ZERO;
        }
        let rank = ((q.clamp(0.0, 1.0) * self.count as f64).ceil() as u64).max(1);
        let mut seen = 0;
        for (bucket, &n) in self.counts.iter().enumerate() {
            seen += n;
            if seen >= rank {
                let edge = EDGES_NS.get(bucket).copied().unwrap_or(u64::MAX);
                return Duration::from_nanos(edge.min(self.max_ns));
            }
        }
        self.max()
    }

    pub fn p50(&self) -> Duration {
        self.quantile(0.5)
    }

    pub fn p99(&self) -> Duration {
        self.quantile(0.99)
    }

    /// Non-empty buckets as (upper edge, count); the overflow bucket (> 10 s) has no edge.
    pub fn buckets(&self) -> impl Iterator<Item = (Option<Duration>, u64)> + '_ {
        self.counts
            .iter()
            .enumerate()
            .filter(|(_, &n)| n > 0)
            .map(|(i, &n)| (EDGES_NS.get(i).map(|&ns| Duration::from_nanos(ns)), n))
    }
}

/// JSON shape: `{count, p50, p99, max, mean, buckets: [{le, count}]}`, times in seconds, only
/// non-empty buckets (`le` null for the overflow bucket).
impl Serialize for LatenessHistogram {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        struct Buckets<'a>(&'a LatenessHistogram);
        #[derive(Serialize)]
        struct Bucket {
            le: Option<f64>,
            count: u64,
        }
        impl Serialize for Buckets<'_> {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                let mut seq = serializer.serialize_seq(None)?;
                for (le, count) in self.0.buckets() {
                    seq.serialize_element(&Bucket {
                        le: le.map(|d| d.as_secs_f64()),
                        count,
                    })?;
                }
                seq.end()
            }
        }
        let mut s = serializer.serialize_struct("LatenessHistogram", 6)?;
        s.serialize_field("count", &self.count)?;
        s.serialize_field("p50", &self.p50().as_secs_f64())?;
        s.serialize_field("p99", &self.p99().as_secs_f64())?;
        s.serialize_field("max", &self.max().as_secs_f64())?;
        s.serialize_field("mean", &self.mean().as_secs_f64())?;
        s.serialize_field("buckets", &Buckets(self))?;
        s.end()
    }
}

/// What the servo thread did since the runtime started. Times in seconds.
///
/// Invariant: `tick` = engine tick at start + `ticks_run`; `caught_up_ticks` ⊆ `ticks_run`;
/// `dropped_ticks` were never run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RuntimeStats {
    pub clock: ClockMode,
    /// Engine servo period (simulated seconds per tick).
    pub period: f64,
    /// Wall seconds per tick: `period / k`; 0 for the virtual clock.
    pub wall_period: f64,
    /// Engine tick when these statistics were published.
    pub tick: u64,
    /// Ticks (engine steps) run by this runtime.
    pub ticks_run: u64,
    /// Ticks run back to back because the thread woke up after their deadline.
    pub caught_up_ticks: u64,
    /// Ticks skipped because catching up would have exceeded `max_catch_up_ticks`; each one
    /// leaves simulated time one period further behind wall time.
    pub dropped_ticks: u64,
    /// Ticks whose processing (commands, step, publication) took longer than `wall_period`.
    pub overruns: u64,
    /// Longest processing of one tick.
    pub max_tick_time: f64,
    /// Commands applied to the engine (whatever their result).
    pub commands_applied: u64,
    /// Ticks at which `max_commands_per_tick` was reached (the rest waited for the next tick).
    pub command_bound_hits: u64,
    /// Snapshot buffers allocated because a reader still held the spare one (plus the first).
    pub snapshot_allocations: u64,
    /// Wall seconds since start, at publication.
    pub elapsed: f64,
    /// Simulated time − k × wall time since start, at publication (simulated seconds; 0 for
    /// the virtual clock). Between −period and 0 when on schedule; negative beyond that by the
    /// dropped ticks and by a late wake-up not yet caught up.
    pub drift: f64,
    /// Wake-up lateness: one sample per sleep that ended after its deadline was reached.
    pub lateness: LatenessHistogram,
}

impl RuntimeStats {
    pub(super) fn new(clock: ClockMode, period: f64, tick: u64) -> RuntimeStats {
        RuntimeStats {
            clock,
            period,
            wall_period: clock.wall_period(period).unwrap_or(0.0),
            tick,
            ticks_run: 0,
            caught_up_ticks: 0,
            dropped_ticks: 0,
            overruns: 0,
            max_tick_time: 0.0,
            commands_applied: 0,
            command_bound_hits: 0,
            snapshot_allocations: 0,
            elapsed: 0.0,
            drift: 0.0,
            lateness: LatenessHistogram::default(),
        }
    }
}

impl Default for RuntimeStats {
    fn default() -> Self {
        RuntimeStats::new(ClockMode::Virtual, 0.0, 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edges_are_r10_from_1us_to_10s() {
        assert_eq!(EDGES_NS[0], 1_000);
        assert_eq!(EDGES_NS[1], 1_250);
        assert_eq!(EDGES_NS[10], 10_000);
        assert_eq!(EDGES_NS[EDGE_COUNT - 2], 8_000_000_000);
        assert_eq!(EDGES_NS[EDGE_COUNT - 1], 10_000_000_000);
        assert!(EDGES_NS.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn histogram_buckets_quantiles_and_max() {
        let mut h = LatenessHistogram::default();
        assert_eq!(h.p50(), Duration::ZERO);
        for _ in 0..98 {
            h.record(Duration::from_micros(99)); // bucket (80 µs, 100 µs]
        }
        h.record(Duration::from_micros(900)); // (800 µs, 1 ms]
        h.record(Duration::from_millis(5)); // exactly on an edge: (4 ms, 5 ms]
        assert_eq!(h.count(), 100);
        assert_eq!(h.p50(), Duration::from_micros(100));
        assert_eq!(h.p99(), Duration::from_millis(1));
        assert_eq!(h.quantile(1.0), Duration::from_millis(5));
        assert_eq!(h.max(), Duration::from_millis(5));
        let buckets: Vec<_> = h.buckets().collect();
        assert_eq!(
            buckets,
            vec![
                (Some(Duration::from_micros(100)), 98),
                (Some(Duration::from_millis(1)), 1),
                (Some(Duration::from_millis(5)), 1),
            ]
        );
        h.record(Duration::ZERO);
        h.record(Duration::from_secs(60));
        assert_eq!(
            h.buckets().next(),
            Some((Some(Duration::from_micros(1)), 1))
        );
        assert_eq!(h.buckets().last(), Some((None, 1)));
        assert_eq!(h.quantile(1.0), Duration::from_secs(60));
    }

    #[test]
    fn quantile_is_capped_at_the_exact_max() {
        let mut h = LatenessHistogram::default();
        h.record(Duration::from_micros(81));
        assert_eq!(h.p50(), Duration::from_micros(81));
    }

    #[test]
    fn histogram_serializes_summary_and_nonempty_buckets() {
        let mut h = LatenessHistogram::default();
        h.record(Duration::from_micros(2));
        h.record(Duration::from_micros(2));
        let json = serde_json::to_value(&h).ok();
        let expected = serde_json::json!({
            "count": 2, "p50": 2e-6, "p99": 2e-6, "max": 2e-6, "mean": 2e-6,
            "buckets": [{"le": 2e-6, "count": 2}]
        });
        assert_eq!(json, Some(expected));
    }
}
