//! The time source of the paced (realtime and scaled) clocks, a trait so that the pacing logic
//! can be tested with a fake clock.

use std::time::{Duration, Instant};

/// A monotonic time source the servo thread paces itself with.
pub trait Clock: Send + 'static {
    /// Time since an origin fixed when the clock was made.
    fn now(&self) -> Duration;

    /// Block until `now() >= deadline`, or less: the caller re-checks `now()` and its stop flag
    /// and calls again, so an implementation may return early (to spin, or when the servo thread
    /// is unparked for shutdown).
    fn sleep_until(&self, deadline: Duration);
}

/// The OS monotonic clock. Sleeps with `park_timeout`, so that a shutdown's `unpark` cuts the
/// sleep short, until `spin_window` before the deadline, then yields the CPU in a loop until the
/// deadline: a plain sleep on this VM wakes ~65–100 µs late at the median (timer slack plus
/// wake-up), the final yield loop brings that to ~0–15 µs for ~3–4 % of a core at 1 ms
/// (docs/decisions.md, Runtime).
#[derive(Debug)]
pub struct SystemClock {
    origin: Instant,
    spin_window: Duration,
}

impl SystemClock {
    pub fn new(spin_window: Duration) -> SystemClock {
        SystemClock {
            origin: Instant::now(),
            spin_window,
        }
    }
}

impl Clock for SystemClock {
    fn now(&self) -> Duration {
        self.origin.elapsed()
    }

    fn sleep_until(&self, deadline: Duration) {
        let remaining = deadline.saturating_sub(self.now());
        if remaining.is_zero() {
            return;
        }
        if remaining > self.spin_window {
            std::thread::park_timeout(remaining - self.spin_window);
        } else {
            std::thread::yield_now();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn system_clock_sleeps_at_least_until_the_deadline() {
        let clock = SystemClock::new(Duration::from_micros(100));
        let deadline = clock.now() + Duration::from_millis(2);
        while clock.now() < deadline {
            clock.sleep_until(deadline);
        }
        assert!(clock.now() >= deadline);
    }
}
