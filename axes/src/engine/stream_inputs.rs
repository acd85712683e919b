//! Streams started by a digital input edge (issue 12 item 3; NMC `MtPtStartMtnEx(axis,
//! diIndex, diSns)`, digest 001 §2.8, §4.7): `stream_start_on_input` arms an axis; at the top of
//! the first tick that sees the edge in the I/O image (a forced input changed between ticks, or
//! a wired sensor the tick before), the axis's stream starts as a `stream_start` sent between
//! those ticks would. Deterministic: the arms are checked in the order they were made.

use super::Engine;
use crate::command::{EngineError, Reply, StreamStart, StreamStartOnInput};
use crate::status::StreamInputStart;

/// One armed start and the input's level when it was last looked at.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct InputStart {
    pub arm: StreamStartOnInput,
    level: bool,
}

impl Engine {
    /// `stream_start_on_input`: the axis and the input exist; replaces an arm of the axis.
    pub(super) fn arm_stream_start(&mut self, c: StreamStartOnInput) -> Result<Reply, EngineError> {
        self.axis_status(c.axis as usize)
            .ok_or(EngineError::InvalidAxis {
                axis: u32::from(c.axis),
                count: self.axes.len() as u32,
            })?;
        let level = self.io.image.di.get(usize::from(c.input)).copied().ok_or(
            EngineError::InvalidChannel {
                kind: "digital inputs",
                channel: c.input,
                count: self.io.image.di.len() as u16,
            },
        )?;
        self.input_starts.retain(|s| s.arm.axis != c.axis);
        self.input_starts.push(InputStart { arm: c, level });
        Ok(Reply::Done)
    }

    /// `stream_clear` disarms the axis.
    pub(super) fn disarm_stream_start(&mut self, axis: crate::command::AxisIndex) {
        self.input_starts.retain(|s| s.arm.axis != axis);
    }

    /// Before a tick: start the streams whose input had its edge since the last look.
    pub(super) fn start_streams_on_inputs(&mut self) {
        if self.input_starts.is_empty() {
            return;
        }
        let mut fire = Vec::new();
        for s in &mut self.input_starts {
            let level = self
                .io
                .image
                .di
                .get(usize::from(s.arm.input))
                .copied()
                .unwrap_or(false);
            if level != s.level && s.arm.edge.accepts(Some(level)) {
                fire.push(s.arm.axis);
            }
            s.level = level;
        }
        if fire.is_empty() {
            return;
        }
        self.input_starts.retain(|s| !fire.contains(&s.arm.axis));
        for axis in fire {
            // A refusal (nothing pushed, moving, faulted) drops the arm; the axis shows it
            // did not start (its stream is not running).
            let _ = self.start_streams(StreamStart { axes: vec![axis] });
        }
    }

    /// The armed starts, as `Snapshot::stream_input_starts` shows them.
    pub(super) fn stream_input_starts_into(&self, out: &mut Vec<StreamInputStart>) {
        out.clear();
        out.extend(self.input_starts.iter().map(|s| StreamInputStart {
            axis: s.arm.axis,
            input: s.arm.input,
            edge: s.arm.edge,
        }));
    }
}
