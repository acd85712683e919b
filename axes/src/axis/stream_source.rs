//! The PT/PVT stream as the axis's command source (issue 12 item 3): sampled once per tick in
//! closed form, and the end of its run (done at rest, or an underrun fault while moving).

use super::pvt::StreamEnd;
use super::{Activity, Axis, Context, Ramp, RunGoal, Source};
use crate::command::{CommandState, ErrorKind};
use crate::param::ParamId;
use crate::profile::MotionState;
use crate::status::AxisFlags;

impl Axis {
    /// Sample the stream for this tick: stream time is (tick − origin)·period in ms. At the last
    /// point the axis stands there (the run ends in `progress_stream`); if the points ran out
    /// while moving, it decelerates from the last point's velocity with the stream's stop
    /// deceleration (NMC `smoothDec`), and `progress_stream` raises the fault.
    pub(super) fn advance_stream(&mut self, tick: u64, origin: u64, base: f64) {
        let t_ms = tick.saturating_sub(origin) as f64 * (self.period * 1e3);
        let sample = self.stream.sample(t_ms);
        let k = sample.kinematics;
        let before = self.raw.a;
        // Stream units are ms: velocity ×10³, acceleration ×10⁶ to units/s and units/s².
        self.raw = MotionState {
            p: base + k.p,
            v: k.v * 1e3,
            a: k.a * 1e6,
        };
        self.raw_jerk = (self.raw.a - before) * self.rate;
        match sample.end {
            None => {}
            Some(StreamEnd::Finished) => {
                self.raw.v = 0.0;
                self.raw.a = 0.0;
                self.source = Source::Hold;
            }
            Some(StreamEnd::Underrun) => {
                self.stream_dry = true;
                self.raw.a = 0.0;
                let decel = self.stream_stop_deceleration();
                self.plan_stop(tick, decel);
            }
        }
    }

    pub(super) fn stream_stop_deceleration(&self) -> f64 {
        self.stream
            .stop_deceleration()
            .unwrap_or_else(|| self.param(ParamId::Decel))
    }

    /// The end of a running stream: done once the source stands at the last point (and the
    /// smoothing behind it has settled), or an underrun.
    pub(super) fn progress_stream(&mut self, ctx: &mut Context, dry: bool) {
        if dry {
            // Ran dry while moving: a typed fault (STREAM_UNDERRUN, ErrorStop until reset), the
            // stop ramp planned at the sample; docs/decisions.md "PT and PVT streams".
            self.stream.count_underrun();
            self.latched |= AxisFlags::STREAM_UNDERRUN | AxisFlags::MOTION_ERROR;
            self.blocking |= AxisFlags::STREAM_UNDERRUN;
            self.last_error = Some(ErrorKind::Fault);
            self.abort_all(ctx, CommandState::Error(ErrorKind::Fault));
            self.activity = if matches!(self.source, Source::Hold) {
                Activity::Idle
            } else {
                Activity::Ramping(Ramp::Fault)
            };
            return;
        }
        if matches!(self.source, Source::Hold) && self.motion_done(ctx.tick) {
            self.end_running(ctx, CommandState::Done);
            self.start_head(ctx);
        }
    }

    /// Whether the running command is the stream.
    pub(super) fn stream_runs(&self) -> bool {
        matches!(&self.activity, Activity::Running(run) if run.goal == RunGoal::Stream)
    }

    /// Called wherever a running command ends: a stream's run is over (done, stopped, aborted,
    /// faulted, disabled).
    pub(super) fn release_stream(&mut self) {
        if self.stream_runs() {
            self.stream.stopped();
        }
    }
}
