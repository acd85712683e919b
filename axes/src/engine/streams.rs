//! PT/PVT stream commands (issue 12 item 3): each addresses one axis's buffer, except
//! `stream_start`, which starts several axes' streams between the same two ticks, all or none
//! (NMC `MtPtStartMtn` with its other axes, digest 001 §2.13).

use super::machine::Scope;
use super::Engine;
use crate::axis::{Axis, Context};
use crate::command::{
    AxisIndex, EngineError, PtPush, PvtMove, PvtPush, Reply, StreamClear, StreamCommand,
    StreamConfig, StreamStart,
};

impl Engine {
    pub(super) fn apply_stream_command(
        &mut self,
        command: StreamCommand,
    ) -> Result<Reply, EngineError> {
        match command {
            StreamCommand::Config(StreamConfig {
                axis,
                mode,
                loop_count,
                stop_deceleration,
            }) => self.with_axis(axis, |a, _| {
                a.stream_config(mode, loop_count, stop_deceleration)
            }),
            StreamCommand::PtPush(PtPush { axis, points }) => {
                self.with_axis(axis, |a, _| a.pt_push(&points))
            }
            StreamCommand::PvtPush(PvtPush { axis, points }) => {
                self.with_axis(axis, |a, _| a.pvt_push(&points))
            }
            StreamCommand::Clear(StreamClear { axis }) => {
                let cleared = self.with_axis(axis, |a, _| a.stream_clear());
                if cleared.is_ok() {
                    self.disarm_stream_start(axis);
                }
                cleared
            }
            StreamCommand::PvtMove(PvtMove { axis, points }) => {
                self.with_axis(axis, |a, ctx| a.pvt_move(ctx, &points))
            }
            StreamCommand::Start(c) => self.start_streams(c),
            StreamCommand::StartOnInput(c) => self.arm_stream_start(c),
        }
    }

    /// Every listed axis's stream starts at the same stream time 0, so all of them take their
    /// first sample on the next tick; one refusal and none starts (the error names its item).
    pub(super) fn start_streams(
        &mut self,
        StreamStart { axes }: StreamStart,
    ) -> Result<Reply, EngineError> {
        if axes.is_empty() {
            return Err(EngineError::InvalidArgument {
                name: "axes",
                value: 0.0,
                reason: "stream_start needs at least one axis",
            });
        }
        let indices = self.distinct_axes("axes", axes.iter().copied())?;
        let checkpoint = self.checkpoint(Scope::Axes(&indices));
        let mut ids = Vec::with_capacity(indices.len());
        for (item, &index) in indices.iter().enumerate() {
            let started = self.with_axis(index as AxisIndex, |a, ctx| a.stream_start(ctx));
            match started {
                Ok(id) => ids.push(id),
                Err(e) => {
                    self.rollback(checkpoint);
                    return Err(EngineError::item("axes", item, e));
                }
            }
        }
        self.commit(checkpoint);
        Ok(Reply::AcceptedAll { ids })
    }

    /// Lend one axis and a command context to `f`.
    fn with_axis<R>(
        &mut self,
        index: AxisIndex,
        f: impl FnOnce(&mut Axis, &mut Context) -> Result<R, EngineError>,
    ) -> Result<R, EngineError> {
        let (axis, mut ctx) = self.axis_with_context(index)?;
        f(axis, &mut ctx)
    }
}
