//! The SDO server state machine: dispatch, expedited and segmented transfers
//! (CiA 301 §7.2.4.3.3–§7.2.4.3.8), abort and timeout.

use std::time::Duration;

use super::block::{BlockDownload, BlockUpload};
use super::{mux, with_mux, word, Completion, Failure, Limit, ObjectAccess, SdoAbort};
use crate::frame::CanFrame;

/// Command specifiers of client requests (bits 7–5 of byte 0).
mod ccs {
    pub const DOWNLOAD_SEGMENT: u8 = 0;
    pub const INITIATE_DOWNLOAD: u8 = 1;
    pub const INITIATE_UPLOAD: u8 = 2;
    pub const UPLOAD_SEGMENT: u8 = 3;
    pub const ABORT: u8 = 4;
    pub const BLOCK_UPLOAD: u8 = 5;
    pub const BLOCK_DOWNLOAD: u8 = 6;
}

#[derive(Debug, Default)]
pub(crate) enum State {
    #[default]
    Idle,
    Download {
        index: u16,
        subindex: u8,
        toggle: bool,
        size: Option<usize>,
        limit: Limit,
        data: Vec<u8>,
    },
    Upload {
        index: u16,
        subindex: u8,
        toggle: bool,
        data: Vec<u8>,
        pos: usize,
    },
    BlockDownload(BlockDownload),
    BlockUpload(BlockUpload),
    /// Waiting for the application (store/restore); `reply` confirms the download.
    Deferred {
        index: u16,
        subindex: u8,
        reply: [u8; 8],
    },
}

impl State {
    /// The multiplexer of the transfer in progress.
    fn mux(&self) -> Option<(u16, u8)> {
        match self {
            State::Idle => None,
            State::Download {
                index, subindex, ..
            }
            | State::Upload {
                index, subindex, ..
            }
            | State::Deferred {
                index, subindex, ..
            } => Some((*index, *subindex)),
            State::BlockDownload(b) => Some(b.mux()),
            State::BlockUpload(b) => Some(b.mux()),
        }
    }
}

/// Counters of the server, for metrics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct SdoCounters {
    pub requests: u64,
    pub uploads: u64,
    pub downloads: u64,
    pub aborts_sent: u64,
    pub aborts_received: u64,
    pub timeouts: u64,
}

/// What a segmented download in progress knows besides its data.
#[derive(Clone, Copy, Debug)]
struct Segment {
    index: u16,
    subindex: u8,
    toggle: bool,
    size: Option<usize>,
    limit: Limit,
}

/// One SDO server channel (0x1200).
#[derive(Debug, Default)]
pub(crate) struct SdoServer {
    state: State,
    last_activity: Duration,
    pub(crate) timeout: Duration,
    pub(crate) block_size: u8,
    pub(crate) max_len: usize,
    /// COB-ID of responses (0x580 + node id).
    pub(crate) tx_id: u16,
    pub(crate) counters: SdoCounters,
}

impl SdoServer {
    pub(crate) fn new(timeout: Duration, block_size: u8, max_len: usize) -> SdoServer {
        SdoServer {
            timeout,
            block_size: block_size.clamp(1, 127),
            max_len,
            ..SdoServer::default()
        }
    }

    /// Drop any transfer (NMT reset, stop).
    pub(crate) fn reset(&mut self) {
        self.state = State::Idle;
    }

    fn send(&self, data: [u8; 8], out: &mut Vec<CanFrame>) {
        out.push(CanFrame::full(self.tx_id, data));
    }

    fn send_abort(&mut self, (index, subindex, code): Failure, out: &mut Vec<CanFrame>) {
        self.counters.aborts_sent += 1;
        self.send(with_mux(0x80, index, subindex, code.0.to_le_bytes()), out);
    }

    /// One request frame from the client (its 8 bytes, zero-padded).
    pub(crate) fn on_request(
        &mut self,
        d: [u8; 8],
        now: Duration,
        access: &mut dyn ObjectAccess,
        out: &mut Vec<CanFrame>,
    ) {
        self.counters.requests += 1;
        self.last_activity = now;
        let state = std::mem::take(&mut self.state);
        // During a block download sub-block every frame is a segment, except an abort.
        let state = match state {
            State::BlockDownload(mut b) if b.in_subblock() && d[0] != 0x80 => {
                self.state = match b.on_segment(d, self.tx_id, out) {
                    Ok(()) => State::BlockDownload(b),
                    Err(f) => {
                        self.send_abort(f, out);
                        State::Idle
                    }
                };
                return;
            }
            other => other,
        };
        let (index, subindex) = mux(&d);
        let fallback = state.mux().unwrap_or((index, subindex));
        let result = match (d[0] >> 5, state) {
            (ccs::ABORT, _) => {
                self.counters.aborts_received += 1;
                Ok(State::Idle)
            }
            (ccs::INITIATE_DOWNLOAD, _) => self.initiate_download(d, access, out),
            (ccs::INITIATE_UPLOAD, _) => self.initiate_upload(d, access, out),
            (ccs::BLOCK_DOWNLOAD, _) if d[0] & 0x01 == 0 => {
                BlockDownload::initiate(d, self.block_size, self.max_len, access).map(|(b, r)| {
                    self.send(r, out);
                    State::BlockDownload(b)
                })
            }
            (ccs::BLOCK_UPLOAD, _) if d[0] & 0x03 == 0 => {
                self.initiate_block_upload(d, access, out)
            }
            (
                ccs::DOWNLOAD_SEGMENT,
                State::Download {
                    index,
                    subindex,
                    toggle,
                    size,
                    limit,
                    data,
                },
            ) => {
                let segment = Segment {
                    index,
                    subindex,
                    toggle,
                    size,
                    limit,
                };
                self.download_segment(d, segment, data, access, out)
            }
            (
                ccs::UPLOAD_SEGMENT,
                State::Upload {
                    index,
                    subindex,
                    toggle,
                    data,
                    pos,
                },
            ) => self.upload_segment(d, index, subindex, toggle, data, pos, out),
            (ccs::BLOCK_DOWNLOAD, State::BlockDownload(b)) => {
                let (index, subindex) = b.mux();
                b.end(d).and_then(|data| {
                    self.finish_download(
                        index,
                        subindex,
                        &data,
                        [0xA1, 0, 0, 0, 0, 0, 0, 0],
                        access,
                        out,
                    )
                })
            }
            (ccs::BLOCK_UPLOAD, State::BlockUpload(mut b)) => {
                b.on_client(d, self.tx_id, out).map(|done| {
                    if done {
                        self.counters.uploads += 1;
                        State::Idle
                    } else {
                        State::BlockUpload(b)
                    }
                })
            }
            _ => Err((fallback.0, fallback.1, SdoAbort::COMMAND)),
        };
        self.state = match result {
            Ok(state) => state,
            Err(f) => {
                self.send_abort(f, out);
                State::Idle
            }
        };
    }

    /// CiA 301 §7.2.4.3.3 / §7.2.4.3.5: expedited download, or the start of a segmented one.
    fn initiate_download(
        &mut self,
        d: [u8; 8],
        access: &mut dyn ObjectAccess,
        out: &mut Vec<CanFrame>,
    ) -> Result<State, Failure> {
        let (index, subindex) = mux(&d);
        let fail = |a| (index, subindex, a);
        let expedited = d[0] & 0x02 != 0;
        let sized = d[0] & 0x01 != 0;
        let reply = with_mux(0x60, index, subindex, [0; 4]);
        if expedited {
            let len = if sized {
                4 - usize::from((d[0] >> 2) & 0x03)
            } else {
                // Size not indicated: the object's own size, if it fits in the frame.
                access
                    .fixed_size(index, subindex)
                    .filter(|&s| s <= 4)
                    .unwrap_or(4)
            };
            access
                .check_download(index, subindex, Some(len))
                .map_err(fail)?;
            let data = d.get(4..4 + len).unwrap_or_default();
            return self.finish_download(index, subindex, data, reply, access, out);
        }
        let size = sized.then(|| word(&d) as usize);
        // The object's own checks first (a size beyond its maximum is 0x06070012), then what
        // the server can buffer.
        access.check_download(index, subindex, size).map_err(fail)?;
        let limit = Limit::new(access.max_len(index, subindex), self.max_len);
        if size.is_some_and(|s| s > limit.len) {
            return Err(fail(limit.abort));
        }
        self.send(reply, out);
        Ok(State::Download {
            index,
            subindex,
            toggle: false,
            size,
            limit,
            data: Vec::with_capacity(size.unwrap_or(0).min(limit.len)),
        })
    }

    /// CiA 301 §7.2.4.3.4: one download segment.
    fn download_segment(
        &mut self,
        d: [u8; 8],
        segment: Segment,
        mut data: Vec<u8>,
        access: &mut dyn ObjectAccess,
        out: &mut Vec<CanFrame>,
    ) -> Result<State, Failure> {
        let Segment {
            index,
            subindex,
            toggle,
            size,
            limit,
        } = segment;
        let fail = |a| (index, subindex, a);
        let t = d[0] & 0x10 != 0;
        if t != toggle {
            return Err(fail(SdoAbort::TOGGLE));
        }
        let len = 7 - usize::from((d[0] >> 1) & 0x07);
        data.extend_from_slice(d.get(1..1 + len).unwrap_or_default());
        if data.len() > limit.len {
            return Err(fail(limit.abort));
        }
        if size.is_some_and(|s| data.len() > s) {
            return Err(fail(SdoAbort::LENGTH));
        }
        let reply = [0x20 | (u8::from(t) << 4), 0, 0, 0, 0, 0, 0, 0];
        if d[0] & 0x01 == 0 {
            self.send(reply, out);
            return Ok(State::Download {
                index,
                subindex,
                toggle: !toggle,
                size,
                limit,
                data,
            });
        }
        if size.is_some_and(|s| s != data.len()) {
            return Err(fail(SdoAbort::LENGTH));
        }
        self.finish_download(index, subindex, &data, reply, access, out)
    }

    /// Store downloaded data and confirm with `reply`, or defer the confirmation.
    pub(crate) fn finish_download(
        &mut self,
        index: u16,
        subindex: u8,
        data: &[u8],
        reply: [u8; 8],
        access: &mut dyn ObjectAccess,
        out: &mut Vec<CanFrame>,
    ) -> Result<State, Failure> {
        match access.download(index, subindex, data) {
            Ok(Completion::Done) => {
                self.counters.downloads += 1;
                self.send(reply, out);
                Ok(State::Idle)
            }
            Ok(Completion::Deferred) => Ok(State::Deferred {
                index,
                subindex,
                reply,
            }),
            Err(a) => Err((index, subindex, a)),
        }
    }

    /// CiA 301 §7.2.4.3.6: expedited upload, or the start of a segmented one.
    fn initiate_upload(
        &mut self,
        d: [u8; 8],
        access: &mut dyn ObjectAccess,
        out: &mut Vec<CanFrame>,
    ) -> Result<State, Failure> {
        let (index, subindex) = mux(&d);
        let data = access
            .upload(index, subindex)
            .map_err(|a| (index, subindex, a))?;
        Ok(self.start_upload(index, subindex, data, out))
    }

    pub(crate) fn start_upload(
        &mut self,
        index: u16,
        subindex: u8,
        data: Vec<u8>,
        out: &mut Vec<CanFrame>,
    ) -> State {
        if (1..=4).contains(&data.len()) {
            let mut tail = [0; 4];
            tail.get_mut(..data.len())
                .unwrap_or_default()
                .copy_from_slice(&data);
            let n = (4 - data.len()) as u8;
            self.send(with_mux(0x43 | (n << 2), index, subindex, tail), out);
            self.counters.uploads += 1;
            return State::Idle;
        }
        let size = u32::try_from(data.len()).unwrap_or(u32::MAX);
        self.send(with_mux(0x41, index, subindex, size.to_le_bytes()), out);
        State::Upload {
            index,
            subindex,
            toggle: false,
            data,
            pos: 0,
        }
    }

    /// CiA 301 §7.2.4.3.7: one upload segment.
    #[allow(clippy::too_many_arguments)]
    fn upload_segment(
        &mut self,
        d: [u8; 8],
        index: u16,
        subindex: u8,
        toggle: bool,
        data: Vec<u8>,
        pos: usize,
        out: &mut Vec<CanFrame>,
    ) -> Result<State, Failure> {
        let t = d[0] & 0x10 != 0;
        if t != toggle {
            return Err((index, subindex, SdoAbort::TOGGLE));
        }
        let chunk = data.get(pos..).unwrap_or_default();
        let chunk = chunk.get(..chunk.len().min(7)).unwrap_or_default();
        let last = pos + chunk.len() >= data.len();
        let mut frame = [0u8; 8];
        frame[0] = (u8::from(t) << 4) | (((7 - chunk.len()) as u8) << 1) | u8::from(last);
        frame
            .get_mut(1..1 + chunk.len())
            .unwrap_or_default()
            .copy_from_slice(chunk);
        self.send(frame, out);
        if last {
            self.counters.uploads += 1;
            return Ok(State::Idle);
        }
        Ok(State::Upload {
            index,
            subindex,
            toggle: !toggle,
            pos: pos + chunk.len(),
            data,
        })
    }

    /// CiA 301 §7.2.4.3.12: block upload initiate, or a switch to a normal upload when the
    /// data fit within the client's protocol switch threshold.
    fn initiate_block_upload(
        &mut self,
        d: [u8; 8],
        access: &mut dyn ObjectAccess,
        out: &mut Vec<CanFrame>,
    ) -> Result<State, Failure> {
        let (index, subindex) = mux(&d);
        let blksize = d[4];
        let pst = usize::from(d[5]);
        if !(1..=127).contains(&blksize) {
            return Err((index, subindex, SdoAbort::BLOCK_SIZE));
        }
        let data = access
            .upload(index, subindex)
            .map_err(|a| (index, subindex, a))?;
        if pst > 0 && data.len() <= pst {
            return Ok(self.start_upload(index, subindex, data, out));
        }
        let (b, reply) = BlockUpload::initiate(index, subindex, d, data);
        self.send(reply, out);
        Ok(State::BlockUpload(b))
    }

    /// The application finished a deferred download.
    pub(crate) fn finish_deferred(
        &mut self,
        result: Result<(), SdoAbort>,
        out: &mut Vec<CanFrame>,
    ) {
        if let State::Deferred {
            index,
            subindex,
            reply,
        } = self.state
        {
            self.state = State::Idle;
            match result {
                Ok(()) => {
                    self.counters.downloads += 1;
                    self.send(reply, out);
                }
                Err(a) => self.send_abort((index, subindex, a), out),
            }
        }
    }

    /// A sub-block whose end does not come is acknowledged after this silence, so the client
    /// repeats the missing segments before the SDO timeout aborts.
    fn subblock_timeout(&self) -> Duration {
        self.timeout / 10
    }

    /// When the transfer in progress times out, if one does.
    pub(crate) fn deadline(&self) -> Option<Duration> {
        match &self.state {
            State::Idle | State::Deferred { .. } => None,
            State::BlockDownload(b) if b.awaiting_rest() => {
                Some(self.last_activity.saturating_add(self.subblock_timeout()))
            }
            _ => Some(self.last_activity.saturating_add(self.timeout)),
        }
    }

    /// Abort a transfer whose client has been silent for the timeout (0x05040000).
    pub(crate) fn on_tick(&mut self, now: Duration, out: &mut Vec<CanFrame>) {
        let partial = now >= self.last_activity.saturating_add(self.subblock_timeout());
        if let State::BlockDownload(b) = &mut self.state {
            if b.awaiting_rest() && partial {
                b.ack_now(self.tx_id, out);
                self.last_activity = now;
                return;
            }
        }
        if self.deadline().is_some_and(|d| now >= d) {
            if let Some((index, subindex)) = self.state.mux() {
                self.counters.timeouts += 1;
                self.send_abort((index, subindex, SdoAbort::TIMEOUT), out);
            }
            self.state = State::Idle;
        }
    }
}
