//! Frames: a fixed 16-byte little-endian header and a payload.
//!
//! ```text
//! offset size field
//!      0    2 magic     b"NM"
//!      2    1 version   the protocol version the frame speaks (a hello: the newest the sender
//!                       speaks)
//!      3    1 kind      0 hello, 1 request, 2 reply
//!      4    4 sequence  chosen by the client, echoed by the reply that answers it
//!      8    2 function  the function id of the table (0 in a hello)
//!     10    2 status    a reply's return code (i16, 0 = RTN_CMD_SUCCESS); 0 in a request
//!     12    4 length    payload bytes that follow, at most MAX_PAYLOAD
//! ```
//!
//! Version negotiation: the client's first frame is a hello whose payload is the lowest and the
//! highest version it speaks (u16 each); the server answers with a hello whose payload is the
//! version chosen (status 0), or a hello with status `RTN_VERSION` and closes.

/// The first two bytes of every frame.
pub const MAGIC: [u8; 2] = *b"NM";
/// The protocol version this crate speaks.
pub const VERSION: u8 = 1;
/// Header bytes.
pub const HEADER_LEN: usize = 16;
/// Largest payload either side accepts: bigger than any call of the table (the largest,
/// `NMC_MtMovePtpAbsPack8`, is under 1 KiB), small enough that a garbage length cannot make a
/// peer buffer much.
pub const MAX_PAYLOAD: usize = 16 * 1024;

/// What a frame is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Hello = 0,
    Request = 1,
    Reply = 2,
}

impl Kind {
    fn from_u8(b: u8) -> Option<Kind> {
        match b {
            0 => Some(Kind::Hello),
            1 => Some(Kind::Request),
            2 => Some(Kind::Reply),
            _ => None,
        }
    }
}

/// A frame's header.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    pub version: u8,
    pub kind: Kind,
    pub sequence: u32,
    pub function: u16,
    pub status: i16,
    pub length: u32,
}

/// A whole frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    pub header: Header,
    pub payload: Vec<u8>,
}

/// Why bytes are not a frame. Both are fatal to the connection: after them no later byte can be
/// trusted to start a frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// The bytes do not start with [`MAGIC`], or the kind is unknown: not this protocol.
    Garbage,
    /// The header announces a payload above [`MAX_PAYLOAD`].
    TooLarge { length: u32 },
}

impl std::fmt::Display for FrameError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FrameError::Garbage => write!(f, "not an NMC frame (bad magic or kind)"),
            FrameError::TooLarge { length } => write!(
                f,
                "payload of {length} bytes is above the limit of {MAX_PAYLOAD}"
            ),
        }
    }
}

impl std::error::Error for FrameError {}

/// Append the frame `header` + `payload` to `out`; `header.length` is taken from `payload`.
pub fn encode(header: Header, payload: &[u8], out: &mut Vec<u8>) {
    out.extend_from_slice(&MAGIC);
    out.push(header.version);
    out.push(header.kind as u8);
    out.extend_from_slice(&header.sequence.to_le_bytes());
    out.extend_from_slice(&header.function.to_le_bytes());
    out.extend_from_slice(&header.status.to_le_bytes());
    let length = u32::try_from(payload.len()).unwrap_or(u32::MAX);
    out.extend_from_slice(&length.to_le_bytes());
    out.extend_from_slice(payload);
}

/// The header at the start of `bytes`, if 16 bytes are there.
pub fn decode_header(bytes: &[u8]) -> Option<Result<Header, FrameError>> {
    let h: &[u8; HEADER_LEN] = bytes.get(..HEADER_LEN)?.try_into().ok()?;
    if h[0..2] != MAGIC {
        return Some(Err(FrameError::Garbage));
    }
    let Some(kind) = Kind::from_u8(h[3]) else {
        return Some(Err(FrameError::Garbage));
    };
    let length = u32::from_le_bytes([h[12], h[13], h[14], h[15]]);
    if length as usize > MAX_PAYLOAD {
        return Some(Err(FrameError::TooLarge { length }));
    }
    Some(Ok(Header {
        version: h[2],
        kind,
        sequence: u32::from_le_bytes([h[4], h[5], h[6], h[7]]),
        function: u16::from_le_bytes([h[8], h[9]]),
        status: i16::from_le_bytes([h[10], h[11]]),
        length,
    }))
}

/// Splits a byte stream into frames.
///
/// Inputs: [`FrameDecoder::push`] the bytes read from the stream, in order. Outputs:
/// [`FrameDecoder::next_frame`] until it gives `Ok(None)` (needs more bytes), then push again.
/// After an `Err` the stream is broken: close it.
#[derive(Debug, Default)]
pub struct FrameDecoder {
    buf: Vec<u8>,
}

impl FrameDecoder {
    pub fn new() -> FrameDecoder {
        FrameDecoder::default()
    }

    /// Bytes received.
    pub fn push(&mut self, bytes: &[u8]) {
        self.buf.extend_from_slice(bytes);
    }

    /// Bytes held that are not yet a whole frame.
    pub fn pending(&self) -> usize {
        self.buf.len()
    }

    /// The next whole frame, `Ok(None)` if more bytes are needed.
    pub fn next_frame(&mut self) -> Result<Option<Frame>, FrameError> {
        let header = match decode_header(&self.buf) {
            None => return Ok(None),
            Some(h) => h?,
        };
        let end = HEADER_LEN + header.length as usize;
        let Some(payload) = self.buf.get(HEADER_LEN..end) else {
            return Ok(None);
        };
        let payload = payload.to_vec();
        self.buf.drain(..end);
        Ok(Some(Frame { header, payload }))
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn header(kind: Kind, length: u32) -> Header {
        Header {
            version: VERSION,
            kind,
            sequence: 0x0102_0304,
            function: 0x0506,
            status: -2,
            length,
        }
    }

    #[test]
    fn the_header_is_sixteen_little_endian_bytes() {
        let mut out = Vec::new();
        encode(header(Kind::Reply, 0), &[9, 8], &mut out);
        assert_eq!(
            out,
            [b'N', b'M', 1, 2, 4, 3, 2, 1, 6, 5, 0xFE, 0xFF, 2, 0, 0, 0, 9, 8]
        );
    }

    #[test]
    fn frames_split_anywhere_come_out_whole_and_in_order() {
        let mut bytes = Vec::new();
        encode(header(Kind::Request, 0), &[1, 2, 3], &mut bytes);
        encode(header(Kind::Request, 0), &[], &mut bytes);
        for cut in 0..bytes.len() {
            let mut d = FrameDecoder::new();
            d.push(&bytes[..cut]);
            let mut frames = Vec::new();
            while let Some(f) = d.next_frame().unwrap() {
                frames.push(f);
            }
            d.push(&bytes[cut..]);
            while let Some(f) = d.next_frame().unwrap() {
                frames.push(f);
            }
            assert_eq!(frames.len(), 2, "cut at {cut}");
            assert_eq!(frames[0].payload, [1, 2, 3]);
            assert_eq!(frames[0].header.length, 3);
            assert_eq!(d.pending(), 0);
        }
    }

    #[test]
    fn garbage_and_oversized_lengths_are_errors_not_allocations() {
        let mut d = FrameDecoder::new();
        d.push(b"GET / HTTP/1.1\r\n\r\n");
        assert_eq!(d.next_frame(), Err(FrameError::Garbage));
        let mut bytes = Vec::new();
        encode(header(Kind::Request, 0), &[], &mut bytes);
        bytes[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        let mut d = FrameDecoder::new();
        d.push(&bytes);
        assert_eq!(
            d.next_frame(),
            Err(FrameError::TooLarge { length: u32::MAX })
        );
        let mut bytes = Vec::new();
        encode(header(Kind::Request, 0), &[], &mut bytes);
        bytes[3] = 7;
        let mut d = FrameDecoder::new();
        d.push(&bytes);
        assert_eq!(d.next_frame(), Err(FrameError::Garbage));
    }
}
