//! A small SDO client and NMT master for tests, benchmarks and the in-process bus: it runs
//! each transfer to its end over a [`Bus`] (the node answers within the same call).

use std::time::Duration;

use crate::bus::Bus;
use crate::device::Device;
use crate::frame::CanFrame;
use crate::nmt::NmtCommand;
use crate::sdo::{crc::crc16, SdoAbort};

/// Why a client transfer failed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ClientError {
    #[error("the server aborted with {0}")]
    Abort(SdoAbort),
    #[error("no response from the server")]
    NoResponse,
    #[error("unexpected response {0}")]
    Protocol(CanFrame),
}

/// SDO client of node `node_id` (default channel 0x600/0x580 + id).
#[derive(Clone, Copy, Debug)]
pub struct SdoClient {
    pub node_id: u8,
    /// Block size the client offers in block uploads.
    pub block_size: u8,
}

fn frame(id: u16, d: [u8; 8]) -> CanFrame {
    CanFrame::full(id, d)
}

fn mux(cmd: u8, index: u16, sub: u8, tail: [u8; 4]) -> [u8; 8] {
    crate::sdo::with_mux(cmd, index, sub, tail)
}

/// Send an NMT command to `node_id` (0 = all).
pub fn nmt<D: Device>(bus: &mut Bus<D>, cmd: NmtCommand, node_id: u8) -> Vec<CanFrame> {
    bus.send(CanFrame::full(0, [cmd.specifier(), node_id, 0, 0, 0, 0, 0, 0]).truncated(2))
}

impl CanFrame {
    /// The first `len` bytes only.
    pub(crate) fn truncated(self, len: usize) -> CanFrame {
        CanFrame::short(self.id(), self.padded(), len)
    }
}

impl SdoClient {
    pub fn new(node_id: u8) -> SdoClient {
        SdoClient {
            node_id,
            block_size: 127,
        }
    }

    fn rx(&self) -> u16 {
        0x600 + u16::from(self.node_id)
    }

    fn tx(&self) -> u16 {
        0x580 + u16::from(self.node_id)
    }

    /// Send one request and return the server's reply on 0x580 + id.
    pub fn request<D: Device>(&self, bus: &mut Bus<D>, d: [u8; 8]) -> Result<[u8; 8], ClientError> {
        let replies = bus.send(frame(self.rx(), d));
        let reply = replies
            .iter()
            .find(|f| f.id() == self.tx())
            .ok_or(ClientError::NoResponse)?;
        let r = reply.padded();
        if r[0] == 0x80 {
            return Err(ClientError::Abort(SdoAbort(u32::from_le_bytes([
                r[4], r[5], r[6], r[7],
            ]))));
        }
        Ok(r)
    }

    /// Expedited or segmented upload.
    pub fn upload<D: Device>(
        &self,
        bus: &mut Bus<D>,
        index: u16,
        sub: u8,
    ) -> Result<Vec<u8>, ClientError> {
        let r = self.request(bus, mux(0x40, index, sub, [0; 4]))?;
        if r[0] & 0xE0 != 0x40 {
            return Err(ClientError::Protocol(frame(self.tx(), r)));
        }
        self.finish_upload(bus, r)
    }

    /// The rest of a normal upload whose initiate response is `r`: its expedited data, or the
    /// segments that follow (toggle checked).
    fn finish_upload<D: Device>(
        &self,
        bus: &mut Bus<D>,
        r: [u8; 8],
    ) -> Result<Vec<u8>, ClientError> {
        if r[0] & 0x02 != 0 {
            let n = if r[0] & 0x01 != 0 {
                4 - usize::from((r[0] >> 2) & 3)
            } else {
                4
            };
            return Ok(r.get(4..4 + n).unwrap_or_default().to_vec());
        }
        let mut data = Vec::new();
        let mut toggle = 0u8;
        loop {
            let s = self.request(bus, [0x60 | toggle, 0, 0, 0, 0, 0, 0, 0])?;
            if s[0] & 0xE0 != 0 || s[0] & 0x10 != toggle {
                return Err(ClientError::Protocol(frame(self.tx(), s)));
            }
            let n = 7 - usize::from((s[0] >> 1) & 7);
            data.extend_from_slice(s.get(1..1 + n).unwrap_or_default());
            if s[0] & 0x01 != 0 {
                return Ok(data);
            }
            toggle ^= 0x10;
        }
    }

    /// Expedited (≤ 4 bytes) or segmented download.
    pub fn download<D: Device>(
        &self,
        bus: &mut Bus<D>,
        index: u16,
        sub: u8,
        data: &[u8],
    ) -> Result<(), ClientError> {
        if (1..=4).contains(&data.len()) {
            let mut tail = [0u8; 4];
            for (slot, b) in tail.iter_mut().zip(data) {
                *slot = *b;
            }
            let n = (4 - data.len()) as u8;
            let r = self.request(bus, mux(0x23 | (n << 2), index, sub, tail))?;
            return if r[0] == 0x60 {
                Ok(())
            } else {
                Err(ClientError::Protocol(frame(self.tx(), r)))
            };
        }
        let size = (data.len() as u32).to_le_bytes();
        let r = self.request(bus, mux(0x21, index, sub, size))?;
        if r[0] != 0x60 {
            return Err(ClientError::Protocol(frame(self.tx(), r)));
        }
        let mut toggle = 0u8;
        let mut chunks = data.chunks(7).peekable();
        if data.is_empty() {
            let r = self.request(bus, [0x0F, 0, 0, 0, 0, 0, 0, 0])?;
            return if r[0] == 0x20 {
                Ok(())
            } else {
                Err(ClientError::Protocol(frame(self.tx(), r)))
            };
        }
        while let Some(chunk) = chunks.next() {
            let last = chunks.peek().is_none();
            let mut d = [0u8; 8];
            d[0] = toggle | (((7 - chunk.len()) as u8) << 1) | u8::from(last);
            for (slot, b) in d.iter_mut().skip(1).zip(chunk) {
                *slot = *b;
            }
            let r = self.request(bus, d)?;
            if r[0] != 0x20 | toggle {
                return Err(ClientError::Protocol(frame(self.tx(), r)));
            }
            toggle ^= 0x10;
        }
        Ok(())
    }

    /// Block download with CRC; `skip` names segments (1-based sequence, within the first
    /// sub-block) to drop once, to exercise the server's retransmission request.
    pub fn block_download<D: Device>(
        &self,
        bus: &mut Bus<D>,
        index: u16,
        sub: u8,
        data: &[u8],
        skip: &[u8],
    ) -> Result<(), ClientError> {
        self.block_download_with(bus, index, sub, data, skip, None)
    }

    /// Block download whose end message carries `crc` instead of the right CRC (to test).
    pub fn block_download_with<D: Device>(
        &self,
        bus: &mut Bus<D>,
        index: u16,
        sub: u8,
        data: &[u8],
        skip: &[u8],
        crc: Option<u16>,
    ) -> Result<(), ClientError> {
        let size = (data.len() as u32).to_le_bytes();
        let r = self.request(bus, mux(0xC6, index, sub, size))?;
        if r[0] & 0xE3 != 0xA0 {
            return Err(ClientError::Protocol(frame(self.tx(), r)));
        }
        let mut blksize = usize::from(r[4]);
        let mut pos = 0;
        let mut skipped_once = false;
        let mut seen = Vec::new();
        loop {
            // One sub-block.
            let start = pos;
            let mut seq = 0;
            let mut last = false;
            seen.clear();
            while seq < blksize && !last {
                seq += 1;
                let chunk = data.get(start + 7 * (seq - 1)..).unwrap_or_default();
                let chunk = chunk.get(..chunk.len().min(7)).unwrap_or_default();
                last = start + 7 * (seq - 1) + chunk.len() >= data.len();
                let mut d = [0u8; 8];
                d[0] = seq as u8 | if last { 0x80 } else { 0 };
                for (slot, b) in d.iter_mut().skip(1).zip(chunk) {
                    *slot = *b;
                }
                if !skipped_once && skip.contains(&(seq as u8)) {
                    continue;
                }
                bus.send_into(frame(self.rx(), d), &mut seen);
            }
            skipped_once = true;
            if !seen.iter().any(|f| f.id() == self.tx()) {
                // The end of the sub-block was lost: the server acknowledges after a pause.
                let until = bus.now() + Duration::from_millis(200);
                seen.extend(bus.advance(until, Duration::from_millis(10)));
            }
            let reply = seen
                .iter()
                .find(|f| f.id() == self.tx())
                .ok_or(ClientError::NoResponse)?
                .padded();
            if reply[0] == 0x80 {
                return Err(ClientError::Abort(SdoAbort(u32::from_le_bytes([
                    reply[4], reply[5], reply[6], reply[7],
                ]))));
            }
            if reply[0] != 0xA2 {
                return Err(ClientError::Protocol(frame(self.tx(), reply)));
            }
            let ackseq = usize::from(reply[1]);
            pos = (start + 7 * ackseq).min(data.len());
            blksize = usize::from(reply[2]);
            if last && ackseq == seq {
                break;
            }
        }
        let unused = match data.len() % 7 {
            0 if data.is_empty() => 7,
            0 => 0,
            r => 7 - r,
        } as u8;
        let c = crc.unwrap_or_else(|| crc16(data)).to_le_bytes();
        let r = self.request(bus, [0xC1 | (unused << 2), c[0], c[1], 0, 0, 0, 0, 0])?;
        if r[0] != 0xA1 {
            return Err(ClientError::Protocol(frame(self.tx(), r)));
        }
        Ok(())
    }

    /// Block upload with CRC check; `pst` is the protocol switch threshold.
    pub fn block_upload<D: Device>(
        &self,
        bus: &mut Bus<D>,
        index: u16,
        sub: u8,
        pst: u8,
    ) -> Result<Vec<u8>, ClientError> {
        let r = self.request(bus, mux(0xA4, index, sub, [self.block_size, pst, 0, 0]))?;
        if r[0] & 0xE0 == 0x40 {
            // The server switched to a normal upload.
            return self.finish_upload(bus, r);
        }
        if r[0] & 0xE3 != 0xC2 {
            return Err(ClientError::Protocol(frame(self.tx(), r)));
        }
        let mut data = Vec::new();
        let mut seen = bus.send(frame(self.rx(), [0xA3, 0, 0, 0, 0, 0, 0, 0]));
        loop {
            let mut ackseq = 0u8;
            let mut done = false;
            for f in seen.iter().filter(|f| f.id() == self.tx()) {
                let d = f.padded();
                if usize::from(d[0] & 0x7F) == usize::from(ackseq) + 1 {
                    ackseq += 1;
                    data.extend_from_slice(d.get(1..).unwrap_or_default());
                    done |= d[0] & 0x80 != 0;
                }
            }
            let reply = bus.send(frame(
                self.rx(),
                [0xA2, ackseq, self.block_size, 0, 0, 0, 0, 0],
            ));
            if done {
                let end = reply
                    .iter()
                    .find(|f| f.id() == self.tx())
                    .ok_or(ClientError::NoResponse)?
                    .padded();
                if end[0] & 0xE3 != 0xC1 {
                    return Err(ClientError::Protocol(frame(self.tx(), end)));
                }
                let unused = usize::from((end[0] >> 2) & 7);
                data.truncate(data.len().saturating_sub(unused));
                if crc16(&data) != u16::from_le_bytes([end[1], end[2]]) {
                    let _ = bus.send(frame(
                        self.rx(),
                        mux(0x80, index, sub, SdoAbort::CRC.0.to_le_bytes()),
                    ));
                    return Err(ClientError::Abort(SdoAbort::CRC));
                }
                bus.send(frame(self.rx(), [0xA1, 0, 0, 0, 0, 0, 0, 0]));
                return Ok(data);
            }
            seen = reply;
        }
    }

    /// Wait (advance the bus) until `t`.
    pub fn wait<D: Device>(bus: &mut Bus<D>, t: Duration) -> Vec<CanFrame> {
        bus.advance(t, Duration::from_millis(1))
    }
}
