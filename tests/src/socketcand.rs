//! A raw-mode socketcand client (the protocol of python-can's `socketcand` interface), for the
//! tests and the CANopen benches: they control how frames are written (several frames in one
//! TCP write reach mcemu as one batch, which no Python client can force) and read every element
//! the server sends.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};

/// How long one read may block while an element is awaited.
const POLL: Duration = Duration::from_millis(20);
/// How long [`Socketcand::next_element`] and the handshake wait.
const ELEMENT_TIMEOUT: Duration = Duration::from_secs(10);

/// A connection to a socketcand server in raw mode on one bus, with TCP_NODELAY.
pub struct Socketcand {
    stream: TcpStream,
    buffer: Vec<u8>,
    /// Where the unread part of `buffer` begins.
    start: usize,
}

impl Socketcand {
    /// Connect to `addr`, open `bus` and switch to raw mode; panics when the server does not
    /// answer as socketcand does.
    pub fn open(addr: &str, bus: &str) -> Socketcand {
        let stream = TcpStream::connect(addr).unwrap_or_else(|e| panic!("socketcand {addr}: {e}"));
        stream.set_nodelay(true).unwrap();
        stream.set_read_timeout(Some(POLL)).unwrap();
        let mut c = Socketcand {
            stream,
            buffer: Vec::with_capacity(1 << 16),
            start: 0,
        };
        assert_eq!(c.next_element(), "< hi >", "socketcand {addr}");
        c.send(&format!("< open {bus} >"));
        assert_eq!(c.next_element(), "< ok >", "socketcand {addr}: open {bus}");
        c.send("< rawmode >");
        assert_eq!(c.next_element(), "< ok >", "socketcand {addr}: rawmode");
        c
    }

    /// Write `text` (one or more elements) in one write.
    pub fn send(&mut self, text: &str) {
        self.stream
            .write_all(text.as_bytes())
            .unwrap_or_else(|e| panic!("socketcand write: {e}"));
    }

    /// The connection's stream, for a reader of its own (a bench that only sends drains it).
    pub fn stream(&self) -> &TcpStream {
        &self.stream
    }

    /// The next `< … >` element; panics when none comes within 10 s.
    pub fn next_element(&mut self) -> String {
        self.element(ELEMENT_TIMEOUT)
            .unwrap_or_else(|| panic!("no element from socketcand within {ELEMENT_TIMEOUT:?}"))
    }

    /// The next `< … >` element, waiting at most `timeout`.
    pub fn element(&mut self, timeout: Duration) -> Option<String> {
        let deadline = Instant::now() + timeout;
        loop {
            let pending = &self.buffer[self.start..];
            if let Some(open) = pending.iter().position(|&b| b == b'<') {
                if let Some(close) = pending[open..].iter().position(|&b| b == b'>') {
                    let element = &pending[open..open + close + 1];
                    let text = String::from_utf8_lossy(element).into_owned();
                    self.start += open + close + 1;
                    return Some(text);
                }
            }
            if self.start > 0 {
                self.buffer.drain(..self.start);
                self.start = 0;
            }
            if Instant::now() >= deadline {
                return None;
            }
            let mut chunk = [0u8; 16384];
            match self.stream.read(&mut chunk) {
                Ok(0) => panic!("socketcand: the server closed the connection"),
                Ok(n) => self.buffer.extend_from_slice(&chunk[..n]),
                Err(e)
                    if matches!(
                        e.kind(),
                        std::io::ErrorKind::WouldBlock
                            | std::io::ErrorKind::TimedOut
                            | std::io::ErrorKind::Interrupted
                    ) => {}
                Err(e) => panic!("socketcand read: {e}"),
            }
        }
    }

    /// Send an expedited SDO upload request of (index, sub) to `node` and wait for the node's
    /// answer; both frames as candump's `ID#DATA`.
    pub fn sdo_upload(&mut self, node: u16, index: u16, sub: u8) -> (String, String) {
        let [lo, hi] = index.to_le_bytes();
        let request = [0x40, lo, hi, sub, 0, 0, 0, 0];
        let bytes: Vec<String> = request.iter().map(|b| format!("{b:02X}")).collect();
        self.send(&format!(
            "< send {:03X} 8 {} >",
            0x600 + node,
            bytes.join(" ")
        ));
        loop {
            if let Some(frame) = RawFrame::parse(&self.next_element()) {
                if frame.id == 0x580 + node {
                    return (
                        format!("{:03X}#{}", 0x600 + node, hex(&request)),
                        format!("{:03X}#{}", frame.id, hex(&frame.data)),
                    );
                }
            }
        }
    }
}

/// A frame as socketcand sends it in raw mode: `< frame ID SECS.USECS HEX >`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RawFrame {
    pub id: u16,
    /// The server's stamp (mcemu's bus time), nanoseconds.
    pub at_ns: u64,
    pub data: Vec<u8>,
}

impl RawFrame {
    /// The frame of an element; `None` for other elements, 29-bit ids and malformed frames.
    pub fn parse(element: &str) -> Option<RawFrame> {
        let inner = element.strip_prefix("< frame ")?.strip_suffix('>')?;
        let mut parts = inner.split_ascii_whitespace();
        let id = parts.next()?;
        if id.len() != 3 {
            return None;
        }
        let id = u16::from_str_radix(id, 16).ok()?;
        let (secs, usecs) = parts.next()?.split_once('.')?;
        let at_ns = secs.parse::<u64>().ok()? * 1_000_000_000 + usecs.parse::<u64>().ok()? * 1000;
        let hex = parts.next().unwrap_or("");
        if hex.len() > 16 || hex.len() % 2 != 0 {
            return None;
        }
        let data = (0..hex.len())
            .step_by(2)
            .map(|i| u8::from_str_radix(&hex[i..i + 2], 16).ok())
            .collect::<Option<Vec<u8>>>()?;
        Some(RawFrame { id, at_ns, data })
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02X}")).collect()
}
