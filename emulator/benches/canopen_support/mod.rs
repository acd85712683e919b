//! What the CANopen benches share: a CAN link (raw SocketCAN or a socketcand TCP client), a
//! minimal raw SDO client on it, the re-execution of a bench inside the vcan VM, and CPU time
//! from `/proc`.
//!
//! Included by `canopen_sdo.rs` and `canopen_sync.rs` (`mod canopen_support;`); a directory
//! without `main.rs`, so cargo does not take it for a bench of its own.

#![allow(dead_code)] // each bench uses its own part

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use mcemu_tests::{RawFrame, Socketcand};

pub const ROLE_VAR: &str = "MCEMU_BENCH_ROLE";
/// How the vcan side's results come back to the host: one `ROW {json}` line each.
pub const ROW_PREFIX: &str = "ROW ";

/// A classic CAN frame with an 11-bit id, as the benches see it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    pub id: u16,
    pub len: u8,
    pub data: [u8; 8],
    /// Arrival: the kernel's receive stamp (SocketCAN) or the hub's (socketcand), nanoseconds
    /// since the Unix epoch; 0 for frames being sent.
    pub at_ns: u64,
}

impl Frame {
    pub fn new(id: u16, bytes: &[u8]) -> Frame {
        let mut data = [0; 8];
        let len = bytes.len().min(8);
        data[..len].copy_from_slice(&bytes[..len]);
        Frame {
            id,
            len: len as u8,
            data,
            at_ns: 0,
        }
    }

    pub fn bytes(&self) -> &[u8] {
        &self.data[..usize::from(self.len)]
    }
}

/// Where the benches reach the bus.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Transport {
    /// Raw SocketCAN on an interface (`vcan0`).
    SocketCan(String),
    /// The socketcand protocol over TCP: server address and bus name.
    Socketcand { addr: String, bus: String },
}

impl Transport {
    pub fn label(&self) -> &'static str {
        match self {
            Transport::SocketCan(_) => "vcan (VM)",
            Transport::Socketcand { .. } => "socketcand",
        }
    }
}

/// One connection to the bus. It does not receive its own frames (as SocketCAN without
/// `CAN_RAW_RECV_OWN_MSGS`, and mcemu's socketcand).
pub trait Link: Send {
    fn send(&mut self, frame: &Frame);
    /// Several frames as one write where the transport can (socketcand); in order.
    fn send_all(&mut self, frames: &[Frame]) {
        for f in frames {
            self.send(f);
        }
    }
    /// The next frame, waiting at most `timeout`; error frames, remote and 29-bit frames are
    /// skipped.
    fn recv(&mut self, timeout: Duration) -> Option<Frame>;
    /// From now on this connection only sends: what arrives for it is thrown away (a raw
    /// socket filters everything out; a socketcand connection is drained on a thread, because
    /// mcemu's socketcand server stops reading a client's commands while its writes to that
    /// client wait, so a client that never reads ends up unable to send).
    fn discard_input(&mut self);
    /// Receive only frames whose id matches one of `(id, mask)` where the transport filters
    /// (SocketCAN, in the kernel); elsewhere everything still arrives.
    fn only(&mut self, _filters: &[(u16, u16)]) {}
}

pub fn open(transport: &Transport) -> Box<dyn Link> {
    match transport {
        Transport::SocketCan(iface) => Box::new(raw::RawLink::open(iface)),
        Transport::Socketcand { addr, bus } => Box::new(SocketcandLink::open(addr, bus)),
    }
}

/// How often a blocking read returns to look at its deadline.
const POLL: Duration = Duration::from_millis(20);

pub fn now_ns() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64)
}

#[cfg(target_os = "linux")]
mod raw {
    use super::*;
    use socketcan::{CanFrame, CanSocket, EmbeddedFrame, Frame as _, Socket, SocketOptions};

    pub struct RawLink {
        socket: CanSocket,
        timeout: Option<Duration>,
    }

    impl RawLink {
        pub fn open(iface: &str) -> RawLink {
            let socket = CanSocket::open(iface).unwrap_or_else(|e| {
                panic!("cannot open SocketCAN {iface}: {e} (run this bench through tests/vcan/run)")
            });
            socket
                .set_recv_timestamp(true)
                .unwrap_or_else(|e| panic!("{iface}: SO_TIMESTAMPNS: {e}"));
            // A checker at 65 000 frames/s under TCG must not lose frames to a small queue:
            // SO_RCVBUFFORCE (root, as in the VM), else what rmem_max allows.
            const SOL_SOCKET: i32 = 1;
            const SO_RCVBUFFORCE: i32 = 33;
            if socket
                .set_socket_option_int(SOL_SOCKET, SO_RCVBUFFORCE, 16 << 20)
                .is_err()
            {
                let _ = socket.as_raw_socket().set_recv_buffer_size(16 << 20);
            }
            RawLink {
                socket,
                timeout: None,
            }
        }
    }

    impl Link for RawLink {
        fn discard_input(&mut self) {
            self.socket
                .set_filter_drop_all()
                .unwrap_or_else(|e| panic!("CAN_RAW_FILTER: {e}"));
        }

        fn only(&mut self, filters: &[(u16, u16)]) {
            let filters: Vec<(u32, u32)> = filters
                .iter()
                .map(|&(id, mask)| (u32::from(id), u32::from(mask)))
                .collect();
            self.socket
                .set_filters(&filters)
                .unwrap_or_else(|e| panic!("CAN_RAW_FILTER: {e}"));
        }

        fn send(&mut self, frame: &Frame) {
            let f = CanFrame::from_raw_id(u32::from(frame.id), frame.bytes())
                .unwrap_or_else(|| panic!("not a CAN frame: {frame:?}"));
            // vcan never pushes back; ENOBUFS (a full queue on a real controller) is retried.
            for attempt in 0.. {
                match self.socket.write_frame(&f) {
                    Ok(()) => return,
                    Err(e) if attempt < 1000 && e.raw_os_error() == Some(105) => {
                        std::thread::sleep(Duration::from_micros(100));
                    }
                    Err(e) => panic!("SocketCAN write {frame:?}: {e}"),
                }
            }
        }

        fn recv(&mut self, timeout: Duration) -> Option<Frame> {
            let deadline = Instant::now() + timeout;
            loop {
                if Instant::now() >= deadline {
                    return None;
                }
                if self.timeout.is_none() {
                    // One poll granularity, set once (a setsockopt per read costs under TCG).
                    self.socket.set_read_timeout(POLL).ok()?;
                    self.timeout = Some(POLL);
                }
                let (f, at) = match self.socket.read_frame_with_timestamp() {
                    Ok(x) => x,
                    Err(e)
                        if matches!(
                            e.kind(),
                            std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                        ) =>
                    {
                        continue
                    }
                    Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                    Err(e) => panic!("SocketCAN read: {e}"),
                };
                if f.is_extended() || f.is_remote_frame() || matches!(f, CanFrame::Error(_)) {
                    continue;
                }
                let mut frame = Frame::new(f.raw_id() as u16, f.data());
                frame.at_ns = at
                    .duration_since(UNIX_EPOCH)
                    .map_or(0, |d| d.as_nanos() as u64);
                return Some(frame);
            }
        }
    }
}

#[cfg(not(target_os = "linux"))]
mod raw {
    use super::*;
    pub struct RawLink;
    impl RawLink {
        pub fn open(iface: &str) -> RawLink {
            panic!("SocketCAN ({iface}) is Linux only")
        }
    }
    impl Link for RawLink {
        fn discard_input(&mut self) {}
        fn send(&mut self, _: &Frame) {}
        fn recv(&mut self, _: Duration) -> Option<Frame> {
            None
        }
    }
}

/// A socketcand client in raw mode (what python-can's `socketcand` interface speaks): the
/// tests' [`Socketcand`], with sends queued so that a batch goes out in one write.
pub struct SocketcandLink {
    link: Socketcand,
    out: String,
}

impl SocketcandLink {
    pub fn open(addr: &str, bus: &str) -> SocketcandLink {
        SocketcandLink {
            link: Socketcand::open(addr, bus),
            out: String::new(),
        }
    }

    fn queue(&mut self, frame: &Frame) {
        use std::fmt::Write as _;
        let _ = write!(self.out, "< send {:03X} {}", frame.id, frame.len);
        for b in frame.bytes() {
            let _ = write!(self.out, " {b:02X}");
        }
        self.out.push_str(" >");
    }

    fn flush(&mut self) {
        self.link.send(&self.out);
        self.out.clear();
    }
}

impl Link for SocketcandLink {
    fn discard_input(&mut self) {
        let mut reader = self.link.stream().try_clone().unwrap();
        reader.set_read_timeout(None).unwrap();
        std::thread::spawn(move || {
            let mut sink = [0u8; 65536];
            while matches!(reader.read(&mut sink), Ok(n) if n > 0) {}
        });
    }

    fn send(&mut self, frame: &Frame) {
        self.queue(frame);
        self.flush();
    }

    fn send_all(&mut self, frames: &[Frame]) {
        for f in frames {
            self.queue(f);
        }
        self.flush();
    }

    fn recv(&mut self, timeout: Duration) -> Option<Frame> {
        let deadline = Instant::now() + timeout;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let element = self.link.element(left)?;
            if let Some(raw) = RawFrame::parse(&element) {
                let mut frame = Frame::new(raw.id, &raw.data);
                frame.at_ns = raw.at_ns;
                return Some(frame);
            }
        }
    }
}

// ---- a raw SDO client ------------------------------------------------------------------------

/// Why a raw SDO transfer failed.
#[derive(Debug)]
pub enum SdoError {
    Abort(u32),
    Timeout(&'static str),
    Protocol(String),
}

impl std::fmt::Display for SdoError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SdoError::Abort(code) => write!(f, "abort 0x{code:08X}"),
            SdoError::Timeout(what) => write!(f, "no response ({what})"),
            SdoError::Protocol(what) => write!(f, "protocol: {what}"),
        }
    }
}

/// A minimal SDO client (CiA 301 §7.2.4.3) on a [`Link`]: expedited, segmented and block
/// transfers, written for the benches (the node's default SDO channel 0x600/0x580 + id).
pub struct RawSdo<'a> {
    pub link: &'a mut dyn Link,
    pub node: u8,
    pub timeout: Duration,
    /// Segments the server asked to repeat (block transfers).
    pub retransmitted: u64,
}

fn mux(cmd: u8, index: u16, sub: u8, tail: [u8; 4]) -> [u8; 8] {
    let i = index.to_le_bytes();
    [cmd, i[0], i[1], sub, tail[0], tail[1], tail[2], tail[3]]
}

impl<'a> RawSdo<'a> {
    pub fn new(link: &'a mut dyn Link, node: u8, timeout: Duration) -> RawSdo<'a> {
        RawSdo {
            link,
            node,
            timeout,
            retransmitted: 0,
        }
    }

    fn request(&mut self, data: [u8; 8]) {
        self.link
            .send(&Frame::new(0x600 + u16::from(self.node), &data));
    }

    fn response(&mut self, what: &'static str) -> Result<[u8; 8], SdoError> {
        let deadline = Instant::now() + self.timeout;
        let id = 0x580 + u16::from(self.node);
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let f = self.link.recv(left).ok_or(SdoError::Timeout(what))?;
            if f.id != id || f.len != 8 {
                continue;
            }
            if f.data[0] == 0x80 {
                let code = u32::from_le_bytes([f.data[4], f.data[5], f.data[6], f.data[7]]);
                return Err(SdoError::Abort(code));
            }
            return Ok(f.data);
        }
    }

    fn abort(&mut self, index: u16, sub: u8, code: u32) {
        self.request(mux(0x80, index, sub, code.to_le_bytes()));
    }

    /// Expedited download of 1–4 bytes.
    pub fn write(&mut self, index: u16, sub: u8, value: &[u8]) -> Result<(), SdoError> {
        assert!((1..=4).contains(&value.len()));
        let mut tail = [0u8; 4];
        tail[..value.len()].copy_from_slice(value);
        let n = (4 - value.len()) as u8;
        self.request(mux(0x23 | (n << 2), index, sub, tail));
        let r = self.response("expedited download")?;
        if r[0] != 0x60 {
            return Err(SdoError::Protocol(format!("download response {r:02X?}")));
        }
        Ok(())
    }

    /// Segmented download (size indicated).
    pub fn segmented_download(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), SdoError> {
        self.request(mux(0x21, index, sub, (data.len() as u32).to_le_bytes()));
        let r = self.response("initiate download")?;
        if r[0] != 0x60 {
            return Err(SdoError::Protocol(format!("initiate response {r:02X?}")));
        }
        let mut toggle = 0u8;
        let count = data.len().div_ceil(7).max(1);
        for (k, chunk) in data
            .chunks(7)
            .chain(data.is_empty().then_some(&[][..]))
            .enumerate()
        {
            let last = k + 1 == count;
            let n = (7 - chunk.len()) as u8;
            let mut seg = [0u8; 8];
            seg[0] = (toggle << 4) | (n << 1) | u8::from(last);
            seg[1..1 + chunk.len()].copy_from_slice(chunk);
            self.request(seg);
            let r = self.response("download segment")?;
            if r[0] != 0x20 | (toggle << 4) {
                return Err(SdoError::Protocol(format!("segment response {r:02X?}")));
            }
            toggle ^= 1;
        }
        Ok(())
    }

    /// Upload (expedited or segmented, as the server chooses).
    pub fn segmented_upload(&mut self, index: u16, sub: u8) -> Result<Vec<u8>, SdoError> {
        self.request(mux(0x40, index, sub, [0; 4]));
        let r = self.response("initiate upload")?;
        if r[0] & 0xE0 != 0x40 {
            return Err(SdoError::Protocol(format!("initiate response {r:02X?}")));
        }
        if r[0] & 0x02 != 0 {
            let len = if r[0] & 0x01 != 0 {
                4 - usize::from((r[0] >> 2) & 3)
            } else {
                4
            };
            return Ok(r[4..4 + len].to_vec());
        }
        let mut out = Vec::new();
        let mut toggle = 0u8;
        loop {
            self.request([0x60 | (toggle << 4), 0, 0, 0, 0, 0, 0, 0]);
            let r = self.response("upload segment")?;
            if r[0] & 0xE0 != 0 || (r[0] >> 4) & 1 != toggle {
                return Err(SdoError::Protocol(format!("segment {r:02X?}")));
            }
            let n = usize::from((r[0] >> 1) & 7);
            out.extend_from_slice(&r[1..8 - n]);
            toggle ^= 1;
            if r[0] & 1 != 0 {
                return Ok(out);
            }
        }
    }

    /// Block download with CRC (CiA 301 §7.2.4.3.9–11): sub-blocks as large as the server
    /// offers, each written at once (one write per sub-block on socketcand).
    pub fn block_download(&mut self, index: u16, sub: u8, data: &[u8]) -> Result<(), SdoError> {
        self.request(mux(0xC6, index, sub, (data.len() as u32).to_le_bytes()));
        let r = self.response("initiate block download")?;
        if r[0] & 0xFB != 0xA0 {
            return Err(SdoError::Protocol(format!("initiate response {r:02X?}")));
        }
        let crc = r[0] & 0x04 != 0;
        let mut blksize = usize::from(r[4]);
        if !(1..=127).contains(&blksize) {
            return Err(SdoError::Protocol(format!("block size {blksize}")));
        }
        let id = 0x600 + u16::from(self.node);
        let mut offset = 0usize;
        let mut frames = Vec::with_capacity(127);
        let last_len;
        loop {
            frames.clear();
            let block_start = offset;
            let mut end = false;
            for seq in 1..=blksize {
                let chunk = &data[offset.min(data.len())..(offset + 7).min(data.len())];
                end = offset + 7 >= data.len();
                let mut seg = [0u8; 8];
                seg[0] = seq as u8 | if end { 0x80 } else { 0 };
                seg[1..1 + chunk.len()].copy_from_slice(chunk);
                frames.push(Frame::new(id, &seg));
                offset += chunk.len();
                if end {
                    break;
                }
            }
            self.link.send_all(&frames);
            let r = self.response("block acknowledge")?;
            if r[0] != 0xA2 {
                return Err(SdoError::Protocol(format!("block ack {r:02X?}")));
            }
            let acked = usize::from(r[1]);
            let sent = frames.len();
            blksize = usize::from(r[2]).clamp(1, 127);
            if acked < sent {
                // Repeat from the first segment the server did not take.
                self.retransmitted += (sent - acked) as u64;
                offset = block_start + 7 * acked;
                continue;
            }
            if end {
                last_len = data.len() - 7 * (data.len().saturating_sub(1) / 7);
                break;
            }
        }
        let n = (7 - last_len) as u8;
        let sum = if crc {
            mcemu_canopen::sdo::crc::crc16(data)
        } else {
            0
        };
        let s = sum.to_le_bytes();
        self.request([0xC1 | (n << 2), s[0], s[1], 0, 0, 0, 0, 0]);
        let r = self.response("end block download")?;
        if r[0] != 0xA1 {
            return Err(SdoError::Protocol(format!("end response {r:02X?}")));
        }
        Ok(())
    }

    /// Block upload with CRC, sub-blocks of 127 segments, no protocol switch.
    pub fn block_upload(&mut self, index: u16, sub: u8) -> Result<Vec<u8>, SdoError> {
        const BLKSIZE: u8 = 127;
        self.request(mux(0xA4, index, sub, [BLKSIZE, 0, 0, 0]));
        let r = self.response("initiate block upload")?;
        if r[0] & 0xF9 != 0xC0 {
            return Err(SdoError::Protocol(format!("initiate response {r:02X?}")));
        }
        let crc = r[0] & 0x04 != 0;
        let size = (r[0] & 0x02 != 0).then(|| u32::from_le_bytes([r[4], r[5], r[6], r[7]]));
        let mut out = Vec::with_capacity(size.map_or(0, |s| s as usize));
        self.request([0xA3, 0, 0, 0, 0, 0, 0, 0]);
        let id = 0x580 + u16::from(self.node);
        loop {
            // One sub-block: take segments in sequence; a gap is ignored to the block's end
            // and acknowledged with the last good sequence number, so the server repeats.
            let block_start = out.len();
            let mut good = 0u8;
            let mut last = false;
            loop {
                let deadline = Instant::now() + self.timeout;
                let f = loop {
                    let left = deadline.saturating_duration_since(Instant::now());
                    let f = self
                        .link
                        .recv(left)
                        .ok_or(SdoError::Timeout("upload segment"))?;
                    if f.id == id && f.len == 8 {
                        break f;
                    }
                };
                if f.data[0] == 0x80 {
                    let code = u32::from_le_bytes([f.data[4], f.data[5], f.data[6], f.data[7]]);
                    return Err(SdoError::Abort(code));
                }
                let seq = f.data[0] & 0x7F;
                if seq == good + 1 {
                    good = seq;
                    out.extend_from_slice(&f.data[1..8]);
                    last = f.data[0] & 0x80 != 0;
                } else {
                    self.retransmitted += 1;
                }
                if last || seq >= BLKSIZE {
                    break;
                }
            }
            if good == 0 && !last {
                out.truncate(block_start);
            }
            self.request([0xA2, good, BLKSIZE, 0, 0, 0, 0, 0]);
            if last {
                break;
            }
        }
        let r = self.response("end block upload")?;
        if r[0] & 0xE3 != 0xC1 {
            return Err(SdoError::Protocol(format!("end {r:02X?}")));
        }
        let n = usize::from((r[0] >> 2) & 7);
        out.truncate(out.len().saturating_sub(n));
        if crc {
            let sum = u16::from_le_bytes([r[1], r[2]]);
            if sum != mcemu_canopen::sdo::crc::crc16(&out) {
                self.abort(index, sub, 0x0504_0004);
                return Err(SdoError::Protocol("CRC mismatch".into()));
            }
        }
        self.request([0xA1, 0, 0, 0, 0, 0, 0, 0]);
        if let Some(size) = size {
            if out.len() != size as usize {
                return Err(SdoError::Protocol(format!(
                    "{} bytes received, {size} announced",
                    out.len()
                )));
            }
        }
        Ok(out)
    }
}

// ---- the VM, processes, statistics ------------------------------------------------------------

/// Run this bench binary again inside `tests/vcan/run` (a VM with a real vcan0 on a kernel
/// without CAN, the host's vcan0 otherwise) with `MCEMU_BENCH_ROLE=role`, streaming what it
/// prints (prefixed with `vm| `) and returning its `ROW` lines as JSON. Panics when the run
/// fails or times out.
pub fn run_in_vcan(role: &str, timeout: Duration) -> Vec<serde_json::Value> {
    let root = mcemu_tests::workspace_root();
    let exe = std::env::current_exe().unwrap();
    let mut command = Command::new(root.join("tests/vcan/run"));
    command
        .arg("--timeout")
        .arg(timeout.as_secs().max(1).to_string())
        .arg("--")
        .arg(&exe)
        .env(ROLE_VAR, role)
        .current_dir(&root)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit());
    let what = format!("{command:?}");
    let mut child = command
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {what}: {e}"));
    let stdout = child.stdout.take().unwrap();
    let mut rows = Vec::new();
    for line in BufReader::new(stdout).lines().map_while(Result::ok) {
        match line.strip_prefix(ROW_PREFIX) {
            Some(json) => rows
                .push(serde_json::from_str(json).unwrap_or_else(|e| panic!("bad row {json}: {e}"))),
            None => println!("  vm| {line}"),
        }
    }
    let status = child.wait().unwrap();
    assert!(
        status.success(),
        "{what} failed ({status}; 124 = timeout, 125 = the harness)"
    );
    rows
}

/// Print a result row for the host to collect.
pub fn emit(row: &serde_json::Value) {
    println!("{ROW_PREFIX}{row}");
}

/// User + system CPU seconds of process `pid` so far (`/proc/PID/stat` fields 14 and 15, in
/// USER_HZ = 100 ticks per second on Linux).
pub fn cpu_seconds(pid: u32) -> f64 {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat"))
        .unwrap_or_else(|e| panic!("/proc/{pid}/stat: {e}"));
    // The command name (field 2) is in parentheses and may hold spaces: count after it.
    let rest = &stat[stat.rfind(')').unwrap() + 2..];
    let fields: Vec<&str> = rest.split_ascii_whitespace().collect();
    // rest starts at field 3 (state): utime is field 14, stime field 15.
    let ticks = |i: usize| fields[i - 3].parse::<u64>().unwrap();
    (ticks(14) + ticks(15)) as f64 / 100.0
}

/// Median, min and max of a sample (None when empty).
pub fn spread(values: &[f64]) -> Option<(f64, f64, f64)> {
    if values.is_empty() {
        return None;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let median = if v.len() % 2 == 1 {
        v[v.len() / 2]
    } else {
        (v[v.len() / 2 - 1] + v[v.len() / 2]) / 2.0
    };
    Some((median, v[0], v[v.len() - 1]))
}

/// A number of seconds from an environment variable, or `default`.
pub fn env_f64(name: &str, default: f64) -> f64 {
    std::env::var(name).ok().map_or(default, |s| {
        s.parse()
            .unwrap_or_else(|_| panic!("{name}={s}: not a number"))
    })
}

/// The workspace-relative path `rel` as an absolute path.
pub fn workspace_path(rel: &str) -> std::path::PathBuf {
    mcemu_tests::workspace_root().join(rel)
}

/// Whether `path` exists (for messages that name a missing setup step).
pub fn require_file(path: &Path, step: &str) {
    assert!(path.is_file(), "{} is missing: {step}", path.display());
}
