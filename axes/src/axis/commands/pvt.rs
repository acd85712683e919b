//! PT/PVT stream commands of one axis (issue 12 item 3): configure, push, clear, start, and
//! HIMC's `MovePVT`. The buffer and its sampling are in `axis::pvt`; the run as a command
//! source in `axis::stream_source`.

use super::*;
use crate::axis::pvt::StreamLimits;
use crate::command::{CommandId, PtPoint, PvtPoint, StreamMode};

impl Axis {
    /// NMC `MtPtSetStatic` / `MtPvtSetPara` / `MtPtSetPara`: the mode empties the buffer.
    pub(crate) fn stream_config(
        &mut self,
        mode: StreamMode,
        loop_count: u32,
        stop_deceleration: Option<f64>,
    ) -> Result<Reply, EngineError> {
        if let Err(e) = self.check_stream_idle() {
            return self.refuse(e);
        }
        if mode == StreamMode::Once {
            return self.refuse(EngineError::InvalidArgument {
                name: "mode",
                value: 2.0,
                reason: "`once` is what pvt_move sets; configure `refresh` or `static`",
            });
        }
        if let Some(d) = stop_deceleration {
            if let Err(e) = positive("stop_deceleration", d) {
                return self.refuse(e);
            }
        }
        self.stream.configure(mode, loop_count, stop_deceleration);
        Ok(Reply::Done)
    }

    /// NMC `MtPtPush`: 1–32 points after the last one, all or none.
    pub(crate) fn pt_push(&mut self, points: &[PtPoint]) -> Result<Reply, EngineError> {
        let limits = self.stream_limits();
        let pushed = self
            .check_stream_push()
            .and_then(|()| self.stream.pt_append(self.index, points, limits));
        self.pushed(pushed)
    }

    /// NMC `MtPvtData`: 1–32 knots after the last one, all or none.
    pub(crate) fn pvt_push(&mut self, points: &[PvtPoint]) -> Result<Reply, EngineError> {
        let pushed = self
            .check_stream_push()
            .and_then(|()| {
                self.stream
                    .pvt_segments(self.index, points, self.stream_limits(), false)
            })
            .map(|segments| self.stream.append(segments));
        self.pushed(pushed)
    }

    /// The outcome of a push: a running stream now ends farther on.
    fn pushed(&mut self, pushed: Result<(), EngineError>) -> Result<Reply, EngineError> {
        match pushed {
            Ok(()) => {
                if self.stream_runs() {
                    if let Source::Stream { base, .. } = self.source {
                        self.target_pos = base + self.stream.final_position();
                    }
                }
                Ok(Reply::Done)
            }
            Err(e) => self.refuse(e),
        }
    }

    /// NMC `MtPtBufClr` / `MtPvtBufClr`.
    pub(crate) fn stream_clear(&mut self) -> Result<Reply, EngineError> {
        if let Err(e) = self.check_stream_idle() {
            return self.refuse(e);
        }
        self.stream.clear();
        Ok(Reply::Done)
    }

    /// NMC `MtPtStartMtn` (one axis of it; the engine starts the others in the same tick).
    pub(crate) fn stream_start(&mut self, ctx: &mut Context) -> Result<CommandId, EngineError> {
        if let Err(e) = self.check_stream_start() {
            return self.refuse(e);
        }
        if self.stream.is_empty() {
            let e = self.invalid_state("start a PT/PVT stream with no points");
            return self.refuse(e);
        }
        // Not further into an active limit: the first segment's direction.
        if let Err(e) = self.admit(direction_of_travel(self.stream.initial_direction())) {
            return self.refuse(e);
        }
        Ok(self.start_stream_command(ctx))
    }

    /// HIMC `MovePVT` (digest 004 §5.2.8, TV20–21): the knots replace the buffer and run once,
    /// from now. Nothing changes if they are refused.
    pub(crate) fn pvt_move(
        &mut self,
        ctx: &mut Context,
        points: &[PvtPoint],
    ) -> Result<Reply, EngineError> {
        let checked = self.check_stream_start().and_then(|()| {
            self.stream
                .pvt_segments(self.index, points, self.stream_limits(), true)
        });
        let segments = match checked {
            Ok(s) if s.is_empty() => Err(EngineError::InvalidArgument {
                name: "points",
                value: points.len() as f64,
                reason: "pvt_move needs a knot after time 0",
            }),
            other => other,
        };
        let segments = match segments {
            Ok(s) => s,
            Err(e) => return self.refuse(e),
        };
        let direction = segments
            .first()
            .map(|s| s.p1 - s.p0)
            .and_then(direction_of_travel);
        if let Err(e) = self.admit(direction) {
            return self.refuse(e);
        }
        self.stream.replace_once(segments);
        let id = self.start_stream_command(ctx);
        Ok(Reply::Accepted { id })
    }

    /// The stream's limits from `max_velocity` and `max_accel` (HIMC's "protection range"), in
    /// stream units (per ms).
    fn stream_limits(&self) -> StreamLimits {
        StreamLimits {
            velocity: self.param(ParamId::MaxVelocity) / 1e3,
            acceleration: self.param(ParamId::MaxAccel) / 1e6,
        }
    }

    /// Pushing is refused while a static or `pvt_move` buffer runs (its loops are measured on
    /// it); a refresh stream takes points while it runs.
    fn check_stream_push(&self) -> Result<(), EngineError> {
        if self.stream.is_running() && self.stream.mode() != StreamMode::Refresh {
            return Err(self.invalid_state("push to a static PT/PVT buffer while it runs"));
        }
        Ok(())
    }

    fn check_stream_idle(&self) -> Result<(), EngineError> {
        if self.stream.is_running() {
            return Err(self.invalid_state("change the PT/PVT buffer while its stream runs"));
        }
        Ok(())
    }

    /// What starting a stream needs: an axis that may move, is not fed, and stands still (the
    /// stream starts at rest: its first velocity is its own).
    fn check_stream_start(&self) -> Result<(), EngineError> {
        self.check_not_fed()?;
        self.check_can_move()?;
        if self.stream.is_running() {
            return Err(self.invalid_state("start a PT/PVT stream that is already running"));
        }
        if !self.source_at_rest() {
            return Err(self.invalid_state("start a PT/PVT stream while moving"));
        }
        Ok(())
    }

    /// Abort what the axis does (it is at rest) and run the stream as a new command.
    fn start_stream_command(&mut self, ctx: &mut Context) -> CommandId {
        self.abort_all(ctx, CommandState::Aborted);
        let id = ctx.ledger.allocate();
        self.zero_length_id = None;
        self.fifo.push(Queued {
            id,
            kind: CommandKind::Stream,
            action: MotionAction::Stream,
            overrides: Overrides::default(),
        });
        // The buffer is not empty and the axis may move: this cannot fail.
        let _ = self.begin_stream(ctx.tick, id);
        id
    }

    /// Make the stream the command source from `tick` (stream time 0), as command `id`.
    pub(super) fn begin_stream(&mut self, tick: u64, id: CommandId) -> Result<(), EngineError> {
        if self.stream.is_empty() {
            return Err(self.invalid_state("start a PT/PVT stream with no points"));
        }
        self.halted = false;
        self.stream.start();
        let base = self.raw.p;
        self.source = Source::Stream { origin: tick, base };
        self.target_pos = base + self.stream.final_position();
        let toward = self.stream.initial_direction();
        if toward != 0.0 {
            self.direction = toward.signum();
        }
        self.planned_limits = None;
        self.activity = Activity::Running(Run {
            id,
            kind: CommandKind::Stream,
            goal: RunGoal::Stream,
            overrides: Overrides::default(),
            arrived_at: None,
            homing: None,
        });
        Ok(())
    }
}
