//! An axis's PT/PVT buffer and its run (issue 12 item 3; NMC digest 001 §2.13–2.14, §4.7; HIMC
//! `MovePVT` digest 004 §5.2.8).
//!
//! Points become [`Segment`]s when they are pushed (the velocities of a PT segment depend on the
//! one before it, so they are fixed then); the tick only samples the segment at the cursor, and
//! moves the cursor on past the segments that ended (at most the buffer's length per tick, whole
//! static loops skipped at once).
//!
//! Buffers: refresh mode holds 2 × 32 points and gives a FIFO half's room back once all its
//! points have run (NMC "一个 FIFO 运行完后空间会切换到另一个 FIFO"); static mode holds 32, keeps
//! them after the run and replays them `loop_count` times, each run continuing from where the
//! last ended (positions and times add up); `pvt_move` (HIMC) runs up to 50 knots once.

mod segment;

use std::collections::VecDeque;

use crate::command::{
    bounded, AxisIndex, EngineError, PtPoint, PvtPoint, StreamMode, MAX_PUSH_POINTS,
    MAX_PVT_MOVE_POINTS,
};
use crate::error::StreamPointProblem;
use crate::status::StreamStatus;

pub(crate) use segment::{Kinematics, Knot, Segment};

/// Points of one NMC PT FIFO ("缓冲区大小为 32 段", digest 001 TV57).
pub(crate) const FIFO_POINTS: usize = 32;

/// A last velocity below this (units/ms) counts as rest: a NORMAL chain that ends at rest in
/// exact arithmetic may end a few ulps away from it.
const REST_VELOCITY: f64 = 1e-12;

/// The kinematic limits a stream's segments must keep (units/ms, units/ms²); 0 = none.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct StreamLimits {
    pub velocity: f64,
    pub acceleration: f64,
}

/// How a sample ended the run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum StreamEnd {
    /// The last point was reached at rest.
    Finished,
    /// The points ran out with the axis still moving.
    Underrun,
}

/// The stream's state at one time of its run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StreamSample {
    pub kinematics: Kinematics,
    pub end: Option<StreamEnd>,
}

#[derive(Clone, Debug)]
pub(crate) struct PvtStream {
    mode: StreamMode,
    loop_count: u32,
    /// units/s²; `None` = the axis's `decel`.
    stop_deceleration: Option<f64>,
    /// The buffer holds a `pvt_move`'s knots (run once, then emptied).
    once: bool,
    /// Refresh mode: the segments not yet run out; static and once: all of them.
    segments: VecDeque<Segment>,
    /// The end of the last segment pushed: where the next point's segment starts. The start
    /// (0, 0, 0) while nothing is pushed.
    chain: Knot,
    /// Refresh mode: segments run out since the buffer was last empty (a FIFO half's room
    /// comes back when its 32th has run).
    finished: u64,
    /// Static and once: the running segment.
    cursor: usize,
    loops_done: u32,
    running: bool,
    time_ms: f64,
    underruns: u32,
}

impl Default for PvtStream {
    fn default() -> Self {
        PvtStream {
            mode: StreamMode::Refresh,
            loop_count: 1,
            stop_deceleration: None,
            once: false,
            segments: VecDeque::new(),
            chain: Knot::default(),
            finished: 0,
            cursor: 0,
            loops_done: 0,
            running: false,
            time_ms: 0.0,
            underruns: 0,
        }
    }
}

impl PvtStream {
    /// Set the mode and empty the buffer (NMC `MtPtSetStatic`).
    pub fn configure(&mut self, mode: StreamMode, loop_count: u32, stop_deceleration: Option<f64>) {
        self.mode = mode;
        self.loop_count = loop_count;
        self.stop_deceleration = stop_deceleration;
        self.clear();
    }

    /// Empty the buffer (NMC `MtPtBufClr`).
    pub fn clear(&mut self) {
        self.segments.clear();
        self.chain = Knot::default();
        self.finished = 0;
        self.cursor = 0;
        self.loops_done = 0;
        self.once = false;
    }

    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    pub fn is_running(&self) -> bool {
        self.running
    }

    pub fn mode(&self) -> StreamMode {
        if self.once {
            StreamMode::Once
        } else {
            self.mode
        }
    }

    pub fn stop_deceleration(&self) -> Option<f64> {
        self.stop_deceleration
    }

    fn capacity(&self) -> usize {
        match self.mode() {
            StreamMode::Refresh => 2 * FIFO_POINTS,
            StreamMode::Static => FIFO_POINTS,
            StreamMode::Once => MAX_PVT_MOVE_POINTS,
        }
    }

    /// Points held: in refresh mode the ones already run of a FIFO half still running count
    /// until the half is done.
    pub fn used(&self) -> usize {
        let run_in_half = match self.mode() {
            StreamMode::Refresh => (self.finished % FIFO_POINTS as u64) as usize,
            _ => 0,
        };
        self.segments.len() + run_in_half
    }

    pub fn space(&self) -> usize {
        self.capacity().saturating_sub(self.used())
    }

    pub fn status(&self) -> StreamStatus {
        StreamStatus {
            mode: self.mode(),
            running: self.running,
            space: self.space() as u16,
            used: self.used() as u16,
            loop_count: if self.mode() == StreamMode::Static {
                self.loop_count
            } else {
                1
            },
            loops_done: self.loops_done,
            underruns: self.underruns,
            time_ms: if self.running { self.time_ms } else { 0.0 },
        }
    }

    /// Where the run ends, relative to its start: the last knot, after every static loop.
    pub fn final_position(&self) -> f64 {
        let loops = match self.mode() {
            StreamMode::Static if self.loop_count > 0 => f64::from(self.loop_count),
            _ => 1.0,
        };
        self.chain.p * loops
    }

    /// The first segment's direction of travel (for the limit check at start).
    pub fn initial_direction(&self) -> f64 {
        self.segments
            .iter()
            .map(|s| if s.v0 != 0.0 { s.v0 } else { s.p1 - s.p0 })
            .find(|d| *d != 0.0)
            .unwrap_or(0.0)
    }

    /// Check PT points after the chain's end and append their segments, all or none: a refused
    /// point leaves the buffer as it was. The segments go into the buffer as they are checked
    /// (room for all of them is checked first) rather than through a list built first: a
    /// refresh-mode host pushes every 32 ms per axis.
    pub fn pt_append(
        &mut self,
        axis: AxisIndex,
        points: &[PtPoint],
        limits: StreamLimits,
    ) -> Result<(), EngineError> {
        self.check_room(axis, points.len(), MAX_PUSH_POINTS)?;
        let kept = self.segments.len();
        let mut chain = self.chain;
        for (i, point) in points.iter().enumerate() {
            match pt_segment(chain, point, limits) {
                Ok(segment) => {
                    chain = segment.end();
                    self.segments.push_back(segment);
                }
                Err(problem) => {
                    self.segments.truncate(kept);
                    return Err(point_error(axis, i, problem));
                }
            }
        }
        self.chain = chain;
        Ok(())
    }

    /// Segments for PVT knots (velocities in units/s), checked; nothing is changed. A push
    /// (`fresh` false) continues the chain and must fit the buffer; a `pvt_move` (`fresh`)
    /// starts a new one of up to 50 knots.
    pub fn pvt_segments(
        &self,
        axis: AxisIndex,
        points: &[PvtPoint],
        limits: StreamLimits,
        fresh: bool,
    ) -> Result<Vec<Segment>, EngineError> {
        let mut chain = if fresh {
            check_count(points.len(), MAX_PVT_MOVE_POINTS)?;
            Knot::default()
        } else {
            self.check_room(axis, points.len(), MAX_PUSH_POINTS)?;
            self.chain
        };
        let mut out = Vec::with_capacity(points.len());
        for (i, point) in points.iter().enumerate() {
            let fail = |problem| point_error(axis, i, problem);
            let t = time(point.time_ms).map_err(fail)?;
            let p = position(point.position).map_err(fail)?;
            let v = bounded("velocity", point.velocity)
                .map_err(|_| StreamPointProblem::NotFinite {
                    name: "velocity",
                    value: point.velocity,
                })
                .map_err(fail)?
                / 1e3;
            if t == 0.0 && chain == Knot::default() {
                // HIMC's knots start with the start itself (digest 004 TV20: time[0] = 0).
                if p != 0.0 || v != 0.0 {
                    return Err(fail(StreamPointProblem::StartMismatch));
                }
                continue;
            }
            check_after(chain, t).map_err(fail)?;
            let segment = Segment::hermite(chain, Knot { t, p, v });
            check_segment(&segment, limits).map_err(fail)?;
            chain = segment.end();
            out.push(segment);
        }
        Ok(out)
    }

    fn check_room(&self, axis: AxisIndex, count: usize, max: usize) -> Result<(), EngineError> {
        check_count(count, max)?;
        let space = self.space();
        if count > space {
            return Err(EngineError::StreamFull {
                axis,
                space: space as u16,
                count: count as u32,
            });
        }
        Ok(())
    }

    /// Append checked segments (from [`PvtStream::pt_segments`] / [`PvtStream::pvt_segments`]).
    pub fn append(&mut self, segments: Vec<Segment>) {
        if let Some(last) = segments.last() {
            self.chain = last.end();
        }
        self.segments.extend(segments);
    }

    /// Replace the buffer with a `pvt_move`'s segments.
    pub fn replace_once(&mut self, segments: Vec<Segment>) {
        self.clear();
        self.append(segments);
        self.once = true;
    }

    /// Begin a run from the first segment.
    pub fn start(&mut self) {
        self.cursor = 0;
        self.loops_done = 0;
        self.time_ms = 0.0;
        self.running = true;
    }

    /// The run ended (done, stopped, aborted, faulted). A refresh stream's remaining points
    /// and a `pvt_move`'s knots are dropped (their times count from the start that is over); a
    /// static buffer stays for the next start.
    pub fn stopped(&mut self) {
        self.running = false;
        self.time_ms = 0.0;
        if self.once || self.mode == StreamMode::Refresh {
            self.clear();
        }
    }

    pub fn count_underrun(&mut self) {
        self.underruns = self.underruns.saturating_add(1);
    }

    /// The stream at time `t` ms of its run, relative to its start. Moves the cursor past the
    /// segments that ended.
    #[inline]
    pub fn sample(&mut self, t: f64) -> StreamSample {
        self.time_ms = t;
        let looping = self.mode() == StreamMode::Static;
        // A static loop replays the buffer where the last one ended.
        let (period, rise) = (self.chain.t, self.chain.p);
        loop {
            let (t_off, p_off) = if looping {
                let k = f64::from(self.loops_done);
                (k * period, k * rise)
            } else {
                (0.0, 0.0)
            };
            let current = if looping || self.once {
                self.segments.get(self.cursor)
            } else {
                self.segments.front()
            };
            let Some(segment) = current.copied() else {
                return self.end(p_off);
            };
            let local = t - t_off;
            if local < segment.t1 {
                let mut k = segment.sample(local);
                k.p += p_off;
                return StreamSample {
                    kinematics: k,
                    end: None,
                };
            }
            if !(looping || self.once) {
                self.segments.pop_front();
                self.finished += 1;
                continue;
            }
            self.cursor += 1;
            if self.cursor < self.segments.len() {
                continue;
            }
            // The end of one run through the buffer.
            let endless = looping && self.loop_count == 0;
            let more = looping && (endless || self.loops_done + 1 < self.loop_count);
            if !more {
                self.loops_done = self.loops_done.saturating_add(1);
                self.cursor = self.segments.len();
                return self.end(p_off);
            }
            self.cursor = 0;
            // Whole loops inside one tick are skipped at once (bounded work per tick).
            let behind = ((local - period) / period).floor().max(0.0);
            let last = if endless {
                u32::MAX
            } else {
                self.loop_count - 1
            };
            let left = f64::from(last.saturating_sub(self.loops_done.saturating_add(1)));
            self.loops_done = self.loops_done.saturating_add(1 + behind.min(left) as u32);
        }
    }

    /// The run is over at the last knot (plus `p_off`, the loops before it).
    fn end(&self, p_off: f64) -> StreamSample {
        let v = self.chain.v;
        StreamSample {
            kinematics: Kinematics {
                p: p_off + self.chain.p,
                v,
                a: 0.0,
            },
            end: Some(if v.abs() <= REST_VELOCITY {
                StreamEnd::Finished
            } else {
                StreamEnd::Underrun
            }),
        }
    }
}

fn check_count(count: usize, max: usize) -> Result<(), EngineError> {
    if count == 0 || count > max {
        return Err(EngineError::InvalidArgument {
            name: "points",
            value: count as f64,
            reason: if max == MAX_PUSH_POINTS {
                "a push carries 1 to 32 points (NMC MtPtPush count ∈ [1, 32])"
            } else {
                "pvt_move carries 1 to 50 knots (HIMC MovePVT num_pt ≤ 50)"
            },
        });
    }
    Ok(())
}

fn point_error(axis: AxisIndex, point: usize, problem: StreamPointProblem) -> EngineError {
    EngineError::StreamPoint {
        axis,
        point: u32::try_from(point).unwrap_or(u32::MAX),
        problem,
    }
}

/// The segment from `chain` to a PT point, checked.
fn pt_segment(
    chain: Knot,
    point: &PtPoint,
    limits: StreamLimits,
) -> Result<Segment, StreamPointProblem> {
    let (t, p) = (time(point.time_ms)?, position(point.position)?);
    check_after(chain, t)?;
    let segment = Segment::pt(chain, t, p, point.kind);
    check_segment(&segment, limits)?;
    Ok(segment)
}

fn time(value: f64) -> Result<f64, StreamPointProblem> {
    bounded("time_ms", value).map_err(|_| StreamPointProblem::NotFinite {
        name: "time_ms",
        value,
    })
}

fn position(value: f64) -> Result<f64, StreamPointProblem> {
    bounded("position", value).map_err(|_| StreamPointProblem::NotFinite {
        name: "position",
        value,
    })
}

fn check_after(chain: Knot, t: f64) -> Result<(), StreamPointProblem> {
    if t > chain.t {
        Ok(())
    } else {
        Err(StreamPointProblem::TimeNotIncreasing {
            time_ms: t,
            previous_ms: chain.t,
        })
    }
}

/// The segment's velocity and acceleration within the axis's limits (HIMC
/// `eERR_AXIS_PVT_MOTION_VEL_LIMIT` / `_ACC_LIMIT`: refused, not clamped — a clamped stream
/// would miss its points).
fn check_segment(segment: &Segment, limits: StreamLimits) -> Result<(), StreamPointProblem> {
    if !segment.is_finite() {
        return Err(StreamPointProblem::NotFinite {
            name: "velocity",
            value: f64::INFINITY,
        });
    }
    let (v, a) = segment.peaks();
    // A hair of slack: a segment that touches the limit exactly may overshoot it by rounding.
    let over = |value: f64, limit: f64| limit > 0.0 && value > limit * (1.0 + 1e-9);
    if over(v, limits.velocity) {
        return Err(StreamPointProblem::VelocityLimit {
            velocity: v * 1e3,
            limit: limits.velocity * 1e3,
        });
    }
    if over(a, limits.acceleration) {
        return Err(StreamPointProblem::AccelerationLimit {
            acceleration: a * 1e6,
            limit: limits.acceleration * 1e6,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::PtKind;

    fn stream_of(mode: StreamMode, loop_count: u32, points: &[(f64, f64)]) -> PvtStream {
        let mut s = PvtStream::default();
        s.configure(mode, loop_count, None);
        let points: Vec<_> = points
            .iter()
            .map(|&(position, time_ms)| PtPoint {
                position,
                time_ms,
                kind: PtKind::Even,
            })
            .collect();
        s.pt_append(0, &points, StreamLimits::default())
            .expect("valid points");
        s.start();
        s
    }

    #[test]
    fn whole_static_loops_inside_one_sample_are_skipped_at_once() {
        // A 0.01 ms loop of +1: at 1 ms, 100 loops have run.
        let mut s = stream_of(StreamMode::Static, 1000, &[(1.0, 0.01)]);
        let k = s.sample(1.0).kinematics;
        assert!((k.p - 100.0).abs() < 1e-6, "{}", k.p);
        assert!((99..=101).contains(&s.loops_done), "{}", s.loops_done);
        // Past the last loop: the end, 1000 runs of +1, still moving (an underrun).
        let end = s.sample(100.0);
        assert_eq!(end.kinematics.p, 1000.0);
        assert_eq!(end.end, Some(StreamEnd::Underrun));
        assert_eq!(s.loops_done, 1000);
        // Endless: it goes on.
        let mut s = stream_of(StreamMode::Static, 0, &[(1.0, 0.01)]);
        assert!(s.sample(1e6).end.is_none());
    }

    #[test]
    fn a_refresh_fifo_half_gives_its_room_back_once_all_its_points_have_run() {
        let points: Vec<_> = (1..=32).map(|i| (f64::from(i), f64::from(i))).collect();
        let mut s = stream_of(StreamMode::Refresh, 1, &points);
        let more: Vec<_> = (33..=40)
            .map(|i| PtPoint {
                position: f64::from(i),
                time_ms: f64::from(i),
                kind: PtKind::Even,
            })
            .collect();
        s.pt_append(0, &more, StreamLimits::default()).unwrap();
        assert_eq!((s.used(), s.space()), (40, 24));
        s.sample(31.5);
        assert_eq!(
            (s.used(), s.space()),
            (40, 24),
            "31 of the first 32 have run"
        );
        s.sample(32.0);
        assert_eq!((s.used(), s.space()), (8, 56));
    }
}
