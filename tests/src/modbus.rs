//! Raw Modbus on the wire, for requests real client libraries refuse to send and for byte-exact
//! checks: MBAP frames over TCP, RTU frames (CRC computed here, independently of mcemu) over TCP
//! or a serial line, and `mbpoll`.

use std::fs::{File, OpenOptions};
use std::io::{self, Read, Write};
use std::net::TcpStream;
use std::os::unix::fs::OpenOptionsExt;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use nix::sys::termios::{
    cfmakeraw, cfsetspeed, tcflush, tcgetattr, tcsetattr, BaudRate, ControlFlags, FlushArg, SetArg,
    SpecialCharacterIndices,
};

use crate::{require_tool, run_with_timeout};

/// How long a raw client waits for a reply it expects.
pub const REPLY_TIMEOUT: Duration = Duration::from_secs(10);

/// CRC-16/MODBUS (reflected 0xA001, initial 0xFFFF), sent low byte first.
pub fn crc16(data: &[u8]) -> u16 {
    let mut crc: u16 = 0xFFFF;
    for &b in data {
        crc ^= u16::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xA001
            } else {
                crc >> 1
            };
        }
    }
    crc
}

/// An RTU frame: `unit`, `pdu`, CRC low byte first.
pub fn rtu_frame(unit: u8, pdu: &[u8]) -> Vec<u8> {
    let mut frame = Vec::with_capacity(pdu.len() + 3);
    frame.push(unit);
    frame.extend_from_slice(pdu);
    let crc = crc16(&frame);
    frame.extend_from_slice(&crc.to_le_bytes());
    frame
}

/// `"02 10 01 19"` → bytes.
pub fn hex(text: &str) -> Vec<u8> {
    text.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap_or_else(|e| panic!("`{b}` in `{text}`: {e}")))
        .collect()
}

/// Bytes → `"02 10 01 19"`.
pub fn to_hex(bytes: &[u8]) -> String {
    bytes
        .iter()
        .map(|b| format!("{b:02X}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A byte stream with a read that gives up after a short while: a TCP socket or a serial line.
pub trait ByteLink {
    /// Write all of `bytes`.
    fn send(&mut self, bytes: &[u8]);
    /// Read what is there within about 50–100 ms: `Some(0)` is the end of the stream,
    /// `None` nothing arrived.
    fn read_some(&mut self, buf: &mut [u8]) -> Option<usize>;

    /// Read until `n` bytes have arrived or `timeout` passes (or the stream ends); returns
    /// what arrived.
    fn recv(&mut self, n: usize, timeout: Duration) -> Vec<u8> {
        let deadline = Instant::now() + timeout;
        let mut out = Vec::with_capacity(n);
        let mut buf = [0u8; 512];
        while out.len() < n && Instant::now() < deadline {
            let want = (n - out.len()).min(buf.len());
            match self.read_some(&mut buf[..want]) {
                Some(0) => break,
                Some(k) => out.extend_from_slice(&buf[..k]),
                None => {}
            }
        }
        out
    }

    /// Whatever arrives until the link has been quiet for `quiet` (or the stream ends).
    fn drain(&mut self, quiet: Duration) -> Vec<u8> {
        let mut out = Vec::new();
        let mut buf = [0u8; 512];
        let mut last = Instant::now();
        while last.elapsed() < quiet {
            match self.read_some(&mut buf) {
                Some(0) => break,
                Some(k) => {
                    out.extend_from_slice(&buf[..k]);
                    last = Instant::now();
                }
                None => {}
            }
        }
        out
    }

    /// Send `request`, read `expected.len()` bytes, and check they are `expected`, then that
    /// nothing follows within `quiet`.
    fn exchange(&mut self, request: &[u8], expected: &[u8], quiet: Duration) {
        self.send(request);
        let got = self.recv(expected.len(), REPLY_TIMEOUT);
        assert_eq!(
            to_hex(&got),
            to_hex(expected),
            "reply to {}",
            to_hex(request)
        );
        let extra = self.drain(quiet);
        assert!(
            extra.is_empty(),
            "bytes after the reply to {}: {}",
            to_hex(request),
            to_hex(&extra)
        );
    }
}

impl ByteLink for TcpStream {
    fn send(&mut self, bytes: &[u8]) {
        self.write_all(bytes).expect("write to the socket");
    }

    fn read_some(&mut self, buf: &mut [u8]) -> Option<usize> {
        self.set_read_timeout(Some(Duration::from_millis(50)))
            .expect("set a read timeout");
        match self.read(buf) {
            Ok(n) => Some(n),
            Err(e)
                if matches!(
                    e.kind(),
                    io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
                ) =>
            {
                None
            }
            // A reset is the end of the stream too.
            Err(_) => Some(0),
        }
    }
}

/// A serial device (a pty end) in raw 8-bit mode, reads returning after 0.1 s of nothing.
#[derive(Debug)]
pub struct RawSerial {
    file: File,
    /// Whether even parity could be set: Linux's pty driver drops `PARENB` (and some kernels
    /// then refuse the request), and a pty has no parity to observe anyway.
    pub parity_even: bool,
}

impl RawSerial {
    /// Open `path` as 19 200 baud, 8 data bits, even parity (where the device takes it), 1 stop
    /// bit, raw; discard whatever was queued.
    pub fn open(path: &Path) -> RawSerial {
        let file = OpenOptions::new()
            .read(true)
            .write(true)
            .custom_flags(nix::libc::O_NOCTTY)
            .open(path)
            .unwrap_or_else(|e| panic!("cannot open {}: {e}", path.display()));
        let mut t = tcgetattr(&file).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        cfmakeraw(&mut t);
        t.control_flags &= !(ControlFlags::CSIZE
            | ControlFlags::PARENB
            | ControlFlags::PARODD
            | ControlFlags::CSTOPB
            | ControlFlags::CRTSCTS);
        t.control_flags |= ControlFlags::CS8 | ControlFlags::CREAD | ControlFlags::CLOCAL;
        t.control_chars[SpecialCharacterIndices::VMIN as usize] = 0;
        t.control_chars[SpecialCharacterIndices::VTIME as usize] = 1;
        cfsetspeed(&mut t, BaudRate::B19200).expect("19200 baud");
        tcsetattr(&file, SetArg::TCSANOW, &t)
            .unwrap_or_else(|e| panic!("{}: raw mode: {e}", path.display()));
        let mut even = t.clone();
        even.control_flags |= ControlFlags::PARENB;
        let parity_even = tcsetattr(&file, SetArg::TCSANOW, &even).is_ok()
            && tcgetattr(&file).is_ok_and(|t| t.control_flags.contains(ControlFlags::PARENB));
        let _ = tcflush(&file, FlushArg::TCIOFLUSH);
        RawSerial { file, parity_even }
    }
}

impl ByteLink for RawSerial {
    fn send(&mut self, bytes: &[u8]) {
        self.file
            .write_all(bytes)
            .expect("write to the serial line");
        self.file.flush().expect("flush the serial line");
    }

    fn read_some(&mut self, buf: &mut [u8]) -> Option<usize> {
        // VMIN 0, VTIME 1: 0 bytes after 0.1 s of silence is no data, not an end.
        match self.file.read(buf) {
            Ok(0) => None,
            Ok(n) => Some(n),
            Err(e) if e.kind() == io::ErrorKind::Interrupted => None,
            Err(e) => panic!("read from the serial line: {e}"),
        }
    }
}

/// A reply to an MBAP request: transaction id, unit id, PDU.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MbapReply {
    pub transaction: u16,
    pub unit: u8,
    pub pdu: Vec<u8>,
}

/// A Modbus TCP client that sends whatever PDU (or bytes) it is given.
#[derive(Debug)]
pub struct MbapClient {
    pub stream: TcpStream,
    transaction: u16,
}

/// An MBAP frame: transaction, protocol 0, length, unit, PDU.
pub fn mbap_frame(transaction: u16, unit: u8, pdu: &[u8]) -> Vec<u8> {
    let mut frame = Vec::with_capacity(pdu.len() + 7);
    frame.extend_from_slice(&transaction.to_be_bytes());
    frame.extend_from_slice(&[0, 0]);
    frame.extend_from_slice(&(pdu.len() as u16 + 1).to_be_bytes());
    frame.push(unit);
    frame.extend_from_slice(pdu);
    frame
}

impl MbapClient {
    pub fn connect(address: &str) -> MbapClient {
        let stream = TcpStream::connect(address)
            .unwrap_or_else(|e| panic!("cannot connect to {address}: {e}"));
        stream.set_nodelay(true).expect("TCP_NODELAY");
        MbapClient {
            stream,
            transaction: 0,
        }
    }

    /// Send `pdu` to `unit` and return the reply's PDU (checked: same transaction, protocol 0,
    /// same unit). Panics when no reply arrives within [`REPLY_TIMEOUT`].
    pub fn request(&mut self, unit: u8, pdu: &[u8]) -> Vec<u8> {
        self.transaction = self.transaction.wrapping_add(1);
        let transaction = self.transaction;
        self.stream.send(&mbap_frame(transaction, unit, pdu));
        let reply = self
            .read_reply(REPLY_TIMEOUT)
            .unwrap_or_else(|| panic!("no reply to {}", to_hex(pdu)));
        assert_eq!(
            (reply.transaction, reply.unit),
            (transaction, unit),
            "reply to {}: {reply:?}",
            to_hex(pdu)
        );
        reply.pdu
    }

    /// Send raw bytes.
    pub fn send_raw(&mut self, bytes: &[u8]) {
        self.stream.send(bytes);
    }

    /// Read one MBAP frame, or `None` when none arrives within `timeout` or the connection
    /// ends first.
    pub fn read_reply(&mut self, timeout: Duration) -> Option<MbapReply> {
        let header = self.stream.recv(7, timeout);
        if header.len() < 7 {
            return None;
        }
        assert_eq!(&header[2..4], [0, 0], "protocol id of {}", to_hex(&header));
        let length = usize::from(u16::from_be_bytes([header[4], header[5]]));
        assert!((2..=254).contains(&length), "length of {}", to_hex(&header));
        let pdu = self.stream.recv(length - 1, timeout);
        assert_eq!(pdu.len(), length - 1, "truncated reply {}", to_hex(&pdu));
        Some(MbapReply {
            transaction: u16::from_be_bytes([header[0], header[1]]),
            unit: header[6],
            pdu,
        })
    }

    /// Whether the server has closed the connection (reads the end of the stream within
    /// `timeout`; any data before it is an error).
    pub fn closed_within(&mut self, timeout: Duration) -> bool {
        let deadline = Instant::now() + timeout;
        let mut buf = [0u8; 64];
        while Instant::now() < deadline {
            match self.stream.read_some(&mut buf) {
                Some(0) => return true,
                Some(n) => panic!("unexpected bytes {}", to_hex(&buf[..n])),
                None => {}
            }
        }
        false
    }
}

/// Run `mbpoll ARGS` once (callers pass `-1`); (success, stdout, stderr).
pub fn mbpoll(args: &[&str]) -> (bool, String, String) {
    let mut command = Command::new(require_tool("mbpoll"));
    command.args(args);
    let out = run_with_timeout(command, b"", Duration::from_secs(30));
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The `[ref]: value` lines of mbpoll's output, as text (a register above 32767 is followed by
/// its signed reading in parentheses, `[501]: 65534 (-2)`, which is dropped).
pub fn mbpoll_values(stdout: &str) -> Vec<(u32, String)> {
    stdout
        .lines()
        .filter_map(|l| {
            let (r, v) = l.trim().strip_prefix('[')?.split_once("]:")?;
            Some((r.parse().ok()?, v.split_whitespace().next()?.to_string()))
        })
        .collect()
}
