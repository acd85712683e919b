//! [`MoveTiming`]: how long the last move took and how long it took to settle, measured on the
//! virtual clock (HIMC `GetMoveTime` / `GetSettlingTime`, digest 004 §2.4 5.3.17–18; §3.7 infers
//! move time = the profile generator's output time, settling = profile end → in position).
//!
//! Input: [`MoveTiming::update`] once per tick, after the in-position timing, with the tick, the
//! servo period, whether the commanded position is changing and whether the axis is in position.
//! Output: [`MoveTiming::move_time`] and [`MoveTiming::settling_time`] in seconds.

/// The last move's durations and the move being measured.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct MoveTiming {
    /// The first tick of the move being run.
    started: Option<u64>,
    /// The tick the last move ended, while it has not settled yet.
    ended: Option<u64>,
    move_time: f64,
    settling_time: f64,
}

impl MoveTiming {
    /// Account for tick `tick`: a move starts at the first tick the commanded position changes
    /// and ends at the first tick it does not; it settles at the first tick in position after.
    pub(super) fn update(&mut self, tick: u64, period: f64, moving: bool, in_position: bool) {
        if moving {
            if self.started.is_none() {
                self.started = Some(tick);
                self.ended = None;
            }
            return;
        }
        if let Some(start) = self.started.take() {
            self.move_time = tick.saturating_sub(start) as f64 * period;
            self.settling_time = 0.0;
            self.ended = Some(tick);
        }
        if let (Some(end), true) = (self.ended, in_position) {
            self.settling_time = tick.saturating_sub(end) as f64 * period;
            self.ended = None;
        }
    }

    /// Seconds the last finished move's commanded position changed (0 before any).
    pub(super) fn move_time(&self) -> f64 {
        self.move_time
    }

    /// Seconds from the end of the last move until the axis was in position; 0 while it has
    /// not settled yet.
    pub(super) fn settling_time(&self) -> f64 {
        self.settling_time
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PERIOD: f64 = 0.001;

    fn run(t: &mut MoveTiming, ticks: std::ops::Range<u64>, moving: bool, in_position: bool) {
        for tick in ticks {
            t.update(tick, PERIOD, moving, in_position);
        }
    }

    #[test]
    fn a_move_of_n_ticks_takes_n_periods_and_settles_when_in_position() {
        let mut t = MoveTiming::default();
        run(&mut t, 0..10, false, true);
        assert_eq!(t.move_time(), 0.0);
        run(&mut t, 10..260, true, false);
        // Still moving: the previous (no) move's figures stand.
        assert_eq!(t.move_time(), 0.0);
        run(&mut t, 260..275, false, false);
        assert!((t.move_time() - 0.250).abs() < 1e-12);
        assert_eq!(t.settling_time(), 0.0, "not settled yet");
        run(&mut t, 275..280, false, true);
        assert!((t.settling_time() - 0.015).abs() < 1e-12);
        // Staying in position changes nothing.
        assert!((t.settling_time() - 0.015).abs() < 1e-12);
    }

    #[test]
    fn the_next_move_replaces_the_figures() {
        let mut t = MoveTiming::default();
        run(&mut t, 0..100, true, false);
        run(&mut t, 100..101, false, true);
        assert!((t.move_time() - 0.1).abs() < 1e-12);
        assert_eq!(t.settling_time(), 0.0, "in position at once");
        run(&mut t, 101..121, true, false);
        run(&mut t, 121..130, false, false);
        assert!((t.move_time() - 0.02).abs() < 1e-12);
        run(&mut t, 130..131, false, true);
        assert!((t.settling_time() - 0.009).abs() < 1e-12);
    }
}
