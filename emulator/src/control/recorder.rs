//! Trace recording for `POST /trace/start`, `POST /trace/stop` and `GET /trace`.
//!
//! A runtime observer copies the recorded axes into a bounded buffer on the servo thread after
//! every tick, so the trace has every tick, not polled snapshots. When the row cap would be
//! exceeded the recording stops at a whole tick (state `full`) and the observer removes itself;
//! with no recording there is no observer, so a tick pays nothing for this.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use axes::command::ErrorKind;
use axes::runtime::{EngineHandle, ObserverId};
use axes::status::{AxisFlags, AxisState, AxisStatus, CouplingKind, StreamStatus};
use axes::Engine;
use serde::{Deserialize, Serialize};

use super::error::ApiError;
use crate::trace::GroupColumns;

/// Default of `[frontends.control] trace_max_rows`: the row cap when a start request gives
/// none, and the largest it may give — about 185 MB of buffer and about 170 MB of CSV at most.
pub const MAX_TRACE_ROWS: usize = 1_000_000;

/// Rows copied out of the buffer per lock while a trace is read, so a long read never holds
/// the servo thread up for more than a few microseconds at a time.
const READ_CHUNK: usize = 8192;

/// One recorded axis at one tick: what a trace row needs, and no more (184 bytes: the group
/// columns are kept with an `in_group` flag rather than as an `Option`, whose tag would cost 8
/// bytes, so the coupling kind, stream count and Z-phase output fit; the HIMC status
/// quantities take 40, the HMC compensation offset 8).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceRow {
    pub tick: u64,
    pub axis: u16,
    pub state: AxisState,
    pub last_error: Option<ErrorKind>,
    pub flags: AxisFlags,
    pub cmd_pos: f64,
    pub cmd_vel: f64,
    pub cmd_acc: f64,
    pub act_pos: f64,
    pub act_vel: f64,
    pub following_error: f64,
    pub pulses: i64,
    pub encoder_counts: i64,
    pub captures: u32,
    pub capture_position: f64,
    pub compare_outputs: u32,
    /// The coupling the axis is the slave of, and the points in its PT/PVT buffer.
    pub coupling: Option<CouplingKind>,
    pub stream_used: u16,
    /// `group` holds a member axis's group columns.
    in_group: bool,
    /// The output position is `cmd_pos + compensation` (as the status computes it).
    pub compensation: f64,
    /// A gantry axis's deviation from its master (0 off a gantry).
    pub gantry_deviation: f64,
    /// The group columns of a member axis (see `in_group`).
    group: GroupColumns,
    /// The HIMC status quantities (issue 14): the last move's and settling times, the user
    /// frame's offset, rollover turns, torque.
    pub move_time: f64,
    pub settling_time: f64,
    pub position_offset: f64,
    pub rollover_turns: i64,
    pub torque: f64,
    /// HMC's Z-phase output level and axis position compensation offset (issue 12).
    pub z_output: bool,
    pub compensation_offset: f64,
}

impl TraceRow {
    fn new(tick: u64, axis: u16, s: &AxisStatus, group: Option<GroupColumns>) -> TraceRow {
        TraceRow {
            tick,
            axis,
            state: s.state,
            last_error: s.last_error,
            flags: s.flags,
            cmd_pos: s.cmd_pos,
            cmd_vel: s.cmd_vel,
            cmd_acc: s.cmd_acc,
            act_pos: s.act_pos,
            act_vel: s.act_vel,
            following_error: s.following_error,
            pulses: s.pulses,
            encoder_counts: s.encoder_counts,
            captures: s.captures,
            capture_position: s.capture_position,
            compare_outputs: s.compare_outputs,
            compensation: s.compensation,
            gantry_deviation: s.gantry_deviation,
            coupling: s.coupling,
            stream_used: s.stream.used,
            in_group: group.is_some(),
            group: group.unwrap_or_default(),
            move_time: s.move_time,
            settling_time: s.settling_time,
            position_offset: s.position_offset,
            rollover_turns: s.rollover_turns,
            torque: s.torque,
            z_output: s.z_output,
            compensation_offset: s.compensation_offset,
        }
    }

    /// The group columns of a member axis.
    pub fn group(&self) -> Option<&GroupColumns> {
        self.in_group.then_some(&self.group)
    }

    /// The status record as `trace::write_row` reads it (fields a row has no column for are
    /// left at their defaults).
    pub fn status(&self) -> AxisStatus {
        AxisStatus {
            state: self.state,
            last_error: self.last_error,
            flags: self.flags,
            cmd_pos: self.cmd_pos,
            cmd_vel: self.cmd_vel,
            cmd_acc: self.cmd_acc,
            act_pos: self.act_pos,
            act_vel: self.act_vel,
            following_error: self.following_error,
            pulses: self.pulses,
            encoder_counts: self.encoder_counts,
            captures: self.captures,
            capture_position: self.capture_position,
            compare_outputs: self.compare_outputs,
            output_pos: self.cmd_pos + self.compensation,
            compensation: self.compensation,
            gantry_deviation: self.gantry_deviation,
            coupling: self.coupling,
            stream: StreamStatus {
                used: self.stream_used,
                ..StreamStatus::default()
            },
            move_time: self.move_time,
            settling_time: self.settling_time,
            position_offset: self.position_offset,
            rollover_turns: self.rollover_turns,
            torque: self.torque,
            z_output: self.z_output,
            compensation_offset: self.compensation_offset,
            ..AxisStatus::default()
        }
    }
}

/// Where a recording is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TraceState {
    /// Nothing recorded since the machine started.
    #[default]
    Idle,
    Recording,
    /// Stopped by `POST /trace/stop`.
    Stopped,
    /// Stopped because the next tick's rows would have exceeded `max_rows`.
    Full,
}

impl TraceState {
    pub fn name(self) -> &'static str {
        match self {
            TraceState::Idle => "idle",
            TraceState::Recording => "recording",
            TraceState::Stopped => "stopped",
            TraceState::Full => "full",
        }
    }
}

/// `POST /trace/start` body; every field optional.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TraceStart {
    /// Axes to record, in this order; all when absent.
    #[serde(default)]
    pub axes: Option<Vec<u16>>,
    /// Row cap (rows = ticks × axes), 1 … the configured `trace_max_rows`; that maximum when
    /// absent.
    #[serde(default)]
    pub max_rows: Option<usize>,
}

/// What `/state` and the trace routes report about the recording.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct TraceStatus {
    pub state: TraceState,
    pub axes: Vec<u16>,
    pub rows: usize,
    pub max_rows: usize,
    /// First and last recorded tick.
    pub first_tick: Option<u64>,
    pub last_tick: Option<u64>,
}

#[derive(Debug, Default)]
struct Recording {
    /// Bumped by every start: an observer of an older recording removes itself.
    generation: u64,
    state: TraceState,
    axes: Vec<u16>,
    max_rows: usize,
    rows: Vec<TraceRow>,
    observer: Option<ObserverId>,
}

impl Recording {
    fn status(&self) -> TraceStatus {
        TraceStatus {
            state: self.state,
            axes: self.axes.clone(),
            rows: self.rows.len(),
            max_rows: self.max_rows,
            first_tick: self.rows.first().map(|r| r.tick),
            last_tick: self.rows.last().map(|r| r.tick),
        }
    }

    /// The servo thread's part: record one tick; `false` ends the observer.
    fn record(&mut self, generation: u64, engine: &Engine) -> bool {
        if self.generation != generation || self.state != TraceState::Recording {
            return false;
        }
        if self.rows.len() + self.axes.len() > self.max_rows {
            self.state = TraceState::Full;
            self.observer = None;
            return false;
        }
        let tick = engine.tick();
        for &axis in &self.axes {
            if let Some(status) = engine.axis_status(usize::from(axis)) {
                let group = GroupColumns::of(engine, usize::from(axis));
                self.rows.push(TraceRow::new(tick, axis, &status, group));
            }
        }
        true
    }
}

/// The recording shared by the HTTP handlers and the servo thread's observer.
#[derive(Clone)]
pub struct TraceRecorder {
    recording: Arc<Mutex<Recording>>,
    /// Largest row cap a start request may ask for, and the cap when it asks for none.
    limit: usize,
}

impl Default for TraceRecorder {
    fn default() -> Self {
        Self::with_limit(MAX_TRACE_ROWS)
    }
}

/// Everything under the lock is plain data updated without panicking, so a poisoned lock
/// (impossible today) still holds a consistent recording.
fn lock(recording: &Mutex<Recording>) -> MutexGuard<'_, Recording> {
    recording.lock().unwrap_or_else(PoisonError::into_inner)
}

impl TraceRecorder {
    /// A recorder whose traces hold at most `limit` rows (at least one).
    pub fn with_limit(limit: usize) -> Self {
        Self {
            recording: Arc::default(),
            limit: limit.max(1),
        }
    }

    pub fn status(&self) -> TraceStatus {
        lock(&self.recording).status()
    }

    /// Start a new recording (discarding any previous one) from the next tick on.
    pub async fn start(
        &self,
        handle: &EngineHandle,
        request: TraceStart,
    ) -> Result<TraceStatus, ApiError> {
        let axis_count = handle.snapshot().axes.len();
        let axes = match request.axes {
            None => (0..axis_count)
                .map(|a| u16::try_from(a).unwrap_or(u16::MAX))
                .collect(),
            Some(axes) => axes,
        };
        if axes.is_empty() {
            return Err(ApiError::InvalidRequest(
                "`axes` is empty: name at least one axis, or leave it out for all".into(),
            ));
        }
        if let Some(&bad) = axes.iter().find(|&&a| usize::from(a) >= axis_count) {
            return Err(ApiError::InvalidRequest(format!(
                "axis {bad} does not exist (the machine has {axis_count} axes)"
            )));
        }
        for (i, a) in axes.iter().enumerate() {
            if axes.iter().skip(i + 1).any(|b| b == a) {
                return Err(ApiError::InvalidRequest(format!(
                    "axis {a} is listed twice in `axes`"
                )));
            }
        }
        let limit = self.limit;
        let max_rows = request.max_rows.unwrap_or(limit);
        if !(1..=limit).contains(&max_rows) {
            return Err(ApiError::InvalidRequest(format!(
                "`max_rows` = {max_rows}: must be between 1 and {limit} \
                 (`[frontends.control] trace_max_rows`)"
            )));
        }
        // The whole cap is reserved here, off the servo thread: growing the buffer later would
        // copy it there, mid-tick. Untouched pages of the reservation cost no memory.
        let rows = Vec::with_capacity(max_rows);
        let (generation, previous, old_rows) = {
            let mut rec = lock(&self.recording);
            rec.generation += 1;
            rec.state = TraceState::Recording;
            rec.axes = axes;
            rec.max_rows = max_rows;
            let old_rows = std::mem::replace(&mut rec.rows, rows);
            (rec.generation, rec.observer.take(), old_rows)
        };
        drop(old_rows); // outside the lock the servo thread may be waiting for
        if let Some(id) = previous {
            // It would remove itself at its next tick (older generation); this is tidier.
            handle.remove_observer_async(id).await?;
        }
        let shared = Arc::clone(&self.recording);
        let installed = handle
            .add_observer_async(move |engine: &Engine| lock(&shared).record(generation, engine))
            .await;
        let mut rec = lock(&self.recording);
        match installed {
            Ok(id) if rec.generation == generation => {
                rec.observer = Some(id);
                Ok(rec.status())
            }
            // A later start replaced this one while it was being installed.
            Ok(_) => Ok(rec.status()),
            Err(e) => {
                if rec.generation == generation {
                    rec.state = TraceState::Stopped;
                }
                Err(e.into())
            }
        }
    }

    /// Stop recording (the rows stay until the next start). Stopping a stopped or full
    /// recording changes nothing.
    pub async fn stop(&self, handle: &EngineHandle) -> Result<TraceStatus, ApiError> {
        let observer = {
            let mut rec = lock(&self.recording);
            if rec.state == TraceState::Idle {
                return Err(ApiError::NoTrace);
            }
            if rec.state == TraceState::Recording {
                // Effective at once: the observer's next call sees it and records nothing.
                rec.state = TraceState::Stopped;
            }
            rec.observer.take()
        };
        if let Some(id) = observer {
            handle.remove_observer_async(id).await?;
        }
        Ok(self.status())
    }

    /// The recording as CSV (`trace::HEADER`, then `trace::write_row` rows) and its status.
    /// Copies the buffer out in chunks, so it can run while the servo thread records.
    pub fn csv(&self, period: f64) -> Result<(Vec<u8>, TraceStatus), ApiError> {
        let (generation, status) = {
            let rec = lock(&self.recording);
            if rec.state == TraceState::Idle {
                return Err(ApiError::NoTrace);
            }
            (rec.generation, rec.status())
        };
        // About 110 bytes a row.
        let mut out = Vec::with_capacity(status.rows.saturating_mul(110).min(1 << 28));
        out.extend_from_slice(crate::trace::HEADER.as_bytes());
        out.push(b'\n');
        let mut chunk = Vec::with_capacity(READ_CHUNK.min(status.rows));
        let mut next = 0;
        while next < status.rows {
            chunk.clear();
            {
                let rec = lock(&self.recording);
                if rec.generation != generation {
                    return Err(ApiError::TraceRestarted);
                }
                let end = (next + READ_CHUNK).min(status.rows);
                chunk.extend_from_slice(rec.rows.get(next..end).unwrap_or_default());
            }
            if chunk.is_empty() {
                break; // cannot happen: rows only grow within a generation
            }
            next += chunk.len();
            for row in &chunk {
                let time = row.tick as f64 * period;
                crate::trace::write_member_row(
                    &mut out,
                    time,
                    usize::from(row.axis),
                    &row.status(),
                    row.group(),
                )
                .map_err(|e| ApiError::Internal(format!("cannot write a trace row: {e}")))?;
            }
        }
        Ok((out, status))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;
    use axes::command::{Command, Enable, GantryEnable, InjectFollowingError};
    use axes::config::{AxisConfig, EngineConfig};
    use axes::runtime::{ClockMode, Runtime, RuntimeGuard, RuntimeOptions};

    fn runtime(axes: usize) -> (EngineHandle, RuntimeGuard) {
        let config = EngineConfig {
            axes: vec![AxisConfig::default(); axes],
            ..EngineConfig::default()
        };
        let engine = Engine::new(&config).unwrap();
        Runtime::start(engine, RuntimeOptions::with_clock(ClockMode::Virtual)).unwrap()
    }

    fn block_on<F: std::future::Future>(f: F) -> F::Output {
        tokio::runtime::Builder::new_current_thread()
            .build()
            .unwrap()
            .block_on(f)
    }

    fn csv_lines(recorder: &TraceRecorder) -> Vec<String> {
        let (csv, _) = recorder.csv(1e-3).unwrap();
        String::from_utf8(csv)
            .unwrap()
            .lines()
            .map(str::to_string)
            .collect()
    }

    #[test]
    fn records_every_tick_of_the_chosen_axes_until_stopped() {
        let (handle, _guard) = runtime(3);
        let recorder = TraceRecorder::default();
        assert!(matches!(recorder.csv(1e-3), Err(ApiError::NoTrace)));
        handle.advance(5).unwrap();
        let request = TraceStart {
            axes: Some(vec![2, 0]),
            max_rows: None,
        };
        block_on(recorder.start(&handle, request)).unwrap();
        handle.call(Command::from(Enable { axis: 2 })).unwrap();
        handle.advance(10).unwrap();
        let status = block_on(recorder.stop(&handle)).unwrap();
        handle.advance(10).unwrap();
        assert_eq!(status.state, TraceState::Stopped);
        assert_eq!(status.rows, 20);
        assert_eq!((status.first_tick, status.last_tick), (Some(6), Some(15)));
        let lines = csv_lines(&recorder);
        assert_eq!(lines[0], crate::trace::HEADER);
        assert_eq!(lines.len(), 21);
        assert!(lines[1].starts_with("0.006,2,standstill,"), "{}", lines[1]);
        assert!(lines[2].starts_with("0.006,0,disabled,"), "{}", lines[2]);
        assert!(lines[20].starts_with("0.015,0,"), "{}", lines[20]);
        assert_eq!(recorder.status().rows, 20);
    }

    /// The slave's deviation (slave − master actual) reaches the CSV's `gantry_deviation`
    /// column on both axes of the gantry.
    #[test]
    fn a_gantrys_deviation_appears_in_the_recorded_trace() {
        let (handle, _guard) = runtime(2);
        for axis in 0..2 {
            handle.call(Command::from(Enable { axis })).unwrap();
        }
        let gantry = GantryEnable {
            master: 0,
            slaves: vec![1],
            warning_limit: 0.0,
            fault_limit: 0.0,
            require_disabled: false,
            closed_loop: false,
        };
        handle.call(Command::from(gantry)).unwrap();
        let recorder = TraceRecorder::default();
        block_on(recorder.start(&handle, TraceStart::default())).unwrap();
        let lag = InjectFollowingError {
            axis: 1,
            amount: Some(0.5),
        };
        handle.call(Command::from(lag)).unwrap();
        handle.advance(3).unwrap();
        let lines = csv_lines(&recorder);
        let column = lines[0]
            .split(',')
            .position(|c| c == "gantry_deviation")
            .unwrap();
        let last = |axis: &str| {
            lines
                .iter()
                .rev()
                .find(|l| l.split(',').nth(1) == Some(axis))
                .and_then(|l| l.split(',').nth(column).map(str::to_string))
                .unwrap()
        };
        assert_eq!(last("1"), "-0.5");
        assert_eq!(last("0"), "-0.5");
    }

    #[test]
    fn stops_at_a_whole_tick_when_full_and_a_restart_discards() {
        let (handle, _guard) = runtime(2);
        let recorder = TraceRecorder::default();
        let request = TraceStart {
            axes: None,
            max_rows: Some(7),
        };
        block_on(recorder.start(&handle, request)).unwrap();
        handle.advance(10).unwrap();
        let status = recorder.status();
        assert_eq!(status.state, TraceState::Full);
        assert_eq!((status.rows, status.last_tick), (6, Some(3)));
        // Full: stop changes nothing, and the observer is gone.
        assert_eq!(
            block_on(recorder.stop(&handle)).unwrap().state,
            TraceState::Full
        );
        block_on(recorder.start(&handle, TraceStart::default())).unwrap();
        handle.advance(2).unwrap();
        let status = recorder.status();
        assert_eq!((status.rows, status.first_tick), (4, Some(11)));
        assert_eq!(status.max_rows, MAX_TRACE_ROWS);
    }

    #[test]
    fn the_configured_limit_caps_every_trace() {
        let (handle, _guard) = runtime(2);
        let recorder = TraceRecorder::with_limit(5);
        let too_many = TraceStart {
            axes: None,
            max_rows: Some(6),
        };
        assert!(matches!(
            block_on(recorder.start(&handle, too_many)),
            Err(ApiError::InvalidRequest(_))
        ));
        let status = block_on(recorder.start(&handle, TraceStart::default())).unwrap();
        assert_eq!(status.max_rows, 5);
        handle.advance(10).unwrap();
        // Two axes a tick: two whole ticks fit in five rows.
        let status = recorder.status();
        assert_eq!((status.state, status.rows), (TraceState::Full, 4));
    }

    #[test]
    fn bad_start_requests_are_refused() {
        let (handle, _guard) = runtime(2);
        let recorder = TraceRecorder::default();
        for (axes, max_rows) in [
            (Some(vec![]), None),
            (Some(vec![2]), None),
            (Some(vec![1, 1]), None),
            (None, Some(0)),
            (None, Some(MAX_TRACE_ROWS + 1)),
        ] {
            let e = block_on(recorder.start(&handle, TraceStart { axes, max_rows }));
            assert!(matches!(e, Err(ApiError::InvalidRequest(_))), "{e:?}");
        }
        assert_eq!(recorder.status().state, TraceState::Idle);
        assert!(matches!(
            block_on(recorder.stop(&handle)),
            Err(ApiError::NoTrace)
        ));
    }

    #[test]
    fn rows_are_compact_and_round_trip_the_columns() {
        assert!(std::mem::size_of::<TraceRow>() <= 192);
        let s = AxisStatus {
            state: AxisState::DiscreteMotion,
            flags: AxisFlags::HOMED | AxisFlags::HW_LIMIT_NEG,
            cmd_pos: 1.5,
            act_pos: 1.25,
            output_pos: 1.75,
            compensation: 0.25,
            gantry_deviation: -0.375,
            pulses: -3,
            last_error: Some(ErrorKind::LimitReached),
            coupling: Some(CouplingKind::Superimpose),
            stream: StreamStatus {
                used: 17,
                ..StreamStatus::default()
            },
            move_time: 0.25,
            settling_time: 0.01,
            position_offset: -100.0,
            rollover_turns: 2,
            torque: -0.5,
            z_output: true,
            compensation_offset: 0.125,
            ..AxisStatus::default()
        };
        let (mut a, mut b) = (Vec::new(), Vec::new());
        crate::trace::write_row(&mut a, 0.5, 1, &s).unwrap();
        crate::trace::write_row(&mut b, 0.5, 1, &TraceRow::new(500, 1, &s, None).status()).unwrap();
        assert_eq!(a, b);
    }
}
