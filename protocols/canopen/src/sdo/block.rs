//! SDO block download and block upload (CiA 301 §7.2.4.3.9–§7.2.4.3.16): sub-blocks of up
//! to 127 segments, acknowledgement with the last good sequence number (the client repeats
//! from there), CRC over the whole data.

use super::Failure;
use super::{crc, mux, with_mux, word, Limit, ObjectAccess, SdoAbort};
use crate::frame::CanFrame;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum DownPhase {
    Subblock,
    /// The last segment arrived; waiting for "end block download".
    End,
}

/// A block download in progress.
#[derive(Debug)]
pub(crate) struct BlockDownload {
    index: u16,
    subindex: u8,
    crc: bool,
    size: Option<usize>,
    limit: Limit,
    data: Vec<u8>,
    phase: DownPhase,
    blksize: u8,
    /// Next sequence number expected in this sub-block (1-based).
    expected: u8,
    /// A segment was missed in this sub-block; the rest is ignored until its end.
    gap: bool,
}

impl BlockDownload {
    /// CiA 301 §7.2.4.3.9: initiate; answers with the server's block size and CRC support.
    pub(crate) fn initiate(
        d: [u8; 8],
        blksize: u8,
        max_len: usize,
        access: &mut dyn ObjectAccess,
    ) -> Result<(BlockDownload, [u8; 8]), Failure> {
        let (index, subindex) = mux(&d);
        let fail = |a| (index, subindex, a);
        let size = (d[0] & 0x02 != 0).then(|| word(&d) as usize);
        // The object's checks first (beyond its maximum: 0x06070012), then the server's buffer.
        access.check_download(index, subindex, size).map_err(fail)?;
        let limit = Limit::new(access.max_len(index, subindex), max_len);
        if size.is_some_and(|s| s > limit.len) {
            return Err(fail(limit.abort));
        }
        let b = BlockDownload {
            index,
            subindex,
            crc: d[0] & 0x04 != 0,
            size,
            limit,
            data: Vec::with_capacity(size.unwrap_or(0).min(limit.len)),
            phase: DownPhase::Subblock,
            blksize,
            expected: 1,
            gap: false,
        };
        // scs 5, sc = 1 (the server checks CRCs), ss 0.
        Ok((b, with_mux(0xA4, index, subindex, [blksize, 0, 0, 0])))
    }

    pub(crate) fn mux(&self) -> (u16, u8) {
        (self.index, self.subindex)
    }

    pub(crate) fn in_subblock(&self) -> bool {
        self.phase == DownPhase::Subblock
    }

    /// CiA 301 §7.2.4.3.10: one segment of a sub-block. In-order segments are kept; after a
    /// missing one the rest of the sub-block is ignored and its end is acknowledged with the
    /// last good sequence number, so the client repeats from there.
    pub(crate) fn on_segment(
        &mut self,
        d: [u8; 8],
        tx_id: u16,
        out: &mut Vec<CanFrame>,
    ) -> Result<(), Failure> {
        let last = d[0] & 0x80 != 0;
        let seq = d[0] & 0x7F;
        if seq == 0 || seq > self.blksize {
            return Err((self.index, self.subindex, SdoAbort::SEQUENCE));
        }
        let in_order = !self.gap && seq == self.expected;
        if in_order {
            // Data already at the limit: this segment would carry more.
            if self.data.len() >= self.limit.len {
                return Err((self.index, self.subindex, self.limit.abort));
            }
            self.data.extend_from_slice(d.get(1..).unwrap_or_default());
            self.expected = seq + 1;
        } else if seq > self.expected {
            self.gap = true;
        }
        let end_of_subblock = seq == self.blksize || (last && in_order);
        if end_of_subblock || (last && self.gap) {
            let ackseq = self.expected - 1;
            out.push(CanFrame::full(
                tx_id,
                [0xA2, ackseq, self.blksize, 0, 0, 0, 0, 0],
            ));
            if last && in_order {
                self.phase = DownPhase::End;
            }
            self.expected = 1;
            self.gap = false;
        }
        Ok(())
    }

    /// Segments of this sub-block arrived but its end did not (the last one was lost).
    pub(crate) fn awaiting_rest(&self) -> bool {
        self.phase == DownPhase::Subblock && (self.expected > 1 || self.gap)
    }

    /// Acknowledge what arrived so far, so the client repeats the rest.
    pub(crate) fn ack_now(&mut self, tx_id: u16, out: &mut Vec<CanFrame>) {
        out.push(CanFrame::full(
            tx_id,
            [0xA2, self.expected - 1, self.blksize, 0, 0, 0, 0, 0],
        ));
        self.expected = 1;
        self.gap = false;
    }

    /// CiA 301 §7.2.4.3.11: end block download; returns the data once length and CRC check.
    pub(crate) fn end(self, d: [u8; 8]) -> Result<Vec<u8>, Failure> {
        let fail = |a| (self.index, self.subindex, a);
        if self.phase != DownPhase::End || d[0] & 0x03 != 0x01 {
            return Err(fail(SdoAbort::COMMAND));
        }
        let unused = usize::from((d[0] >> 2) & 0x07);
        let mut data = self.data;
        data.truncate(data.len().saturating_sub(unused));
        if self.size.is_some_and(|s| s != data.len()) {
            return Err(fail(SdoAbort::LENGTH));
        }
        if self.crc && crc::crc16(&data) != u16::from_le_bytes([d[1], d[2]]) {
            return Err(fail(SdoAbort::CRC));
        }
        Ok(data)
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum UpPhase {
    /// Initiate answered; waiting for "start upload".
    Start,
    /// A sub-block went out; waiting for its acknowledgement.
    Ack,
    /// "End block upload" went out; waiting for the client's end response.
    End,
}

/// A block upload in progress.
#[derive(Debug)]
pub(crate) struct BlockUpload {
    index: u16,
    subindex: u8,
    data: Vec<u8>,
    blksize: u8,
    /// Bytes the client confirmed.
    acked: usize,
    /// Segments in the sub-block last sent.
    sent: u8,
    /// The sub-block last sent ended with the last segment.
    sent_last: bool,
    phase: UpPhase,
}

impl BlockUpload {
    /// CiA 301 §7.2.4.3.12: the answer to initiate (size indicated, CRC supported).
    pub(crate) fn initiate(
        index: u16,
        subindex: u8,
        d: [u8; 8],
        data: Vec<u8>,
    ) -> (BlockUpload, [u8; 8]) {
        let size = u32::try_from(data.len()).unwrap_or(u32::MAX);
        let b = BlockUpload {
            index,
            subindex,
            data,
            blksize: d[4],
            acked: 0,
            sent: 0,
            sent_last: false,
            phase: UpPhase::Start,
        };
        // scs 6, sc = 1, s = 1, ss 0.
        (b, with_mux(0xC6, index, subindex, size.to_le_bytes()))
    }

    pub(crate) fn mux(&self) -> (u16, u8) {
        (self.index, self.subindex)
    }

    /// A client frame; `Ok(true)` when the transfer is complete.
    pub(crate) fn on_client(
        &mut self,
        d: [u8; 8],
        tx_id: u16,
        out: &mut Vec<CanFrame>,
    ) -> Result<bool, Failure> {
        let fail = |a| (self.index, self.subindex, a);
        match (self.phase, d[0] & 0x03) {
            // Start upload (§7.2.4.3.13).
            (UpPhase::Start, 0x03) => {
                self.send_subblock(tx_id, out);
                Ok(false)
            }
            // Sub-block acknowledged (§7.2.4.3.14).
            (UpPhase::Ack, 0x02) => {
                let (ackseq, blksize) = (d[1], d[2]);
                if ackseq > self.sent {
                    return Err(fail(SdoAbort::SEQUENCE));
                }
                if !(1..=127).contains(&blksize) {
                    return Err(fail(SdoAbort::BLOCK_SIZE));
                }
                self.blksize = blksize;
                self.acked = (self.acked + 7 * usize::from(ackseq)).min(self.data.len());
                if self.sent_last && ackseq == self.sent {
                    let unused = match self.data.len() % 7 {
                        0 if self.data.is_empty() => 7,
                        0 => 0,
                        r => 7 - r,
                    } as u8;
                    let c = crc::crc16(&self.data).to_le_bytes();
                    out.push(CanFrame::full(
                        tx_id,
                        [0xC1 | (unused << 2), c[0], c[1], 0, 0, 0, 0, 0],
                    ));
                    self.phase = UpPhase::End;
                } else {
                    self.send_subblock(tx_id, out);
                }
                Ok(false)
            }
            // End response (§7.2.4.3.15).
            (UpPhase::End, 0x01) => Ok(true),
            _ => Err(fail(SdoAbort::COMMAND)),
        }
    }

    /// Send segments from the confirmed position: at most `blksize`, the last one flagged.
    fn send_subblock(&mut self, tx_id: u16, out: &mut Vec<CanFrame>) {
        let rest = self.data.get(self.acked..).unwrap_or_default();
        let chunks = rest.chunks(7).take(usize::from(self.blksize));
        let total = rest.len().div_ceil(7).max(1);
        let count = total.min(usize::from(self.blksize));
        self.sent = count as u8;
        self.sent_last = count == total;
        if rest.is_empty() {
            out.push(CanFrame::full(tx_id, [0x81, 0, 0, 0, 0, 0, 0, 0]));
        }
        for (i, chunk) in chunks.enumerate() {
            let seq = (i + 1) as u8;
            let mut frame = [0u8; 8];
            frame[0] = seq
                | if self.sent_last && i + 1 == count {
                    0x80
                } else {
                    0
                };
            frame
                .get_mut(1..1 + chunk.len())
                .unwrap_or_default()
                .copy_from_slice(chunk);
            out.push(CanFrame::full(tx_id, frame));
        }
        self.phase = UpPhase::Ack;
    }
}
