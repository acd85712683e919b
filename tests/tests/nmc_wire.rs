//! The NMC front-end's wire from raw sockets: unknown function ids are answered with an error
//! and the connection stays; garbage and oversized frames are answered and closed; none of it
//! disturbs another client; the Unix socket serves the same protocol; `/state` counts it all.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{Read, Write};
use std::net::TcpStream;
use std::os::unix::net::UnixStream;
use std::time::Duration;

use mcemu_nmc::errors::{RTN_ARG_RANGE, RTN_FRAME_TOO_LARGE, RTN_UNKNOWN_FUNCTION};
use mcemu_nmc::frame::{Frame, FrameDecoder, Kind, VERSION};
use mcemu_nmc::handle::Handle;
use mcemu_nmc::payload::Writer;
use mcemu_nmc::session::{hello, request};
use mcemu_nmc::table;
use mcemu_tests::{fresh_dir, workspace_root, Mcemu};

const TIMEOUT: Duration = Duration::from_secs(10);

/// A raw client: write bytes, read whole frames.
struct Raw<S: Read + Write> {
    stream: S,
    decoder: FrameDecoder,
}

impl<S: Read + Write> Raw<S> {
    fn new(stream: S) -> Raw<S> {
        Raw {
            stream,
            decoder: FrameDecoder::new(),
        }
    }

    fn send(&mut self, bytes: &[u8]) {
        self.stream.write_all(bytes).unwrap();
    }

    /// The next frame, `None` when the server closed.
    fn frame(&mut self) -> Option<Frame> {
        let mut buf = [0u8; 4096];
        loop {
            if let Some(f) = self.decoder.next_frame().unwrap() {
                return Some(f);
            }
            match self.stream.read(&mut buf) {
                Ok(0) | Err(_) => return None,
                Ok(n) => self.decoder.push(&buf[..n]),
            }
        }
    }

    fn negotiate(&mut self) {
        let mut b = Vec::new();
        hello(VERSION, VERSION, &mut b);
        self.send(&b);
        let f = self.frame().unwrap();
        assert_eq!((f.header.kind, f.header.status), (Kind::Hello, 0));
    }

    fn call(&mut self, sequence: u32, function: u16, payload: &[u8]) -> Frame {
        let mut b = Vec::new();
        request(sequence, function, payload, &mut b);
        self.send(&b);
        let f = self.frame().unwrap();
        assert_eq!(f.header.sequence, sequence);
        f
    }

    /// `NMC_MtGetSts` of axis 0: the reply's status.
    fn get_sts(&mut self, sequence: u32) -> i16 {
        let mut w = Writer::new();
        w.u16(Handle::axis(0, 0).encode());
        self.call(sequence, table::MT_GET_STS.id, &w.bytes)
            .header
            .status
    }
}

fn tcp(address: &str) -> Raw<TcpStream> {
    let s = TcpStream::connect(address).unwrap();
    s.set_read_timeout(Some(TIMEOUT)).unwrap();
    Raw::new(s)
}

#[test]
fn bad_frames_are_answered_and_closed_and_others_carry_on() {
    let m = Mcemu::start(
        Some(&workspace_root().join("fixtures/gaochuan-gcn.toml")),
        &[],
    );
    let address = m.address("nmc").to_string();
    let mut good = tcp(&address);
    good.negotiate();
    assert_eq!(good.get_sts(1), 0);

    // An unknown function id: an error reply, and the connection stays.
    let mut odd = tcp(&address);
    odd.negotiate();
    let f = odd.call(7, 0x7777, &[]);
    assert_eq!(f.header.status, RTN_UNKNOWN_FUNCTION);
    assert_eq!(odd.get_sts(8), 0);
    // A payload too short for its function: a range of its own, the connection stays.
    let f = odd.call(9, table::MT_OPEN.id, &[0, 0x40]);
    assert_ne!(f.header.status, 0);
    // An argument out of range names it.
    let mut w = Writer::new();
    w.u16(Handle::device(0).encode()).i16(99);
    let f = odd.call(10, table::MT_OPEN.id, &w.bytes);
    assert_eq!(f.header.status, RTN_ARG_RANGE);
    assert!(String::from_utf8_lossy(&f.payload).contains("itemNo"));

    // Garbage: a reply, then the close.
    let mut garbage = tcp(&address);
    garbage.send(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n");
    let f = garbage.frame().unwrap();
    assert_ne!(f.header.status, 0);
    assert!(garbage.frame().is_none(), "still open after garbage");

    // A frame announcing a payload above the limit.
    let mut big = tcp(&address);
    big.negotiate();
    let mut b = Vec::new();
    request(1, table::MT_GET_STS.id, &[], &mut b);
    b[12..16].copy_from_slice(&(1u32 << 30).to_le_bytes());
    big.send(&b);
    assert_eq!(big.frame().unwrap().header.status, RTN_FRAME_TOO_LARGE);
    assert!(big.frame().is_none());

    // The first client never noticed.
    assert_eq!(good.get_sts(2), 0);
    let state = m.frontend("nmc");
    assert_eq!(state["unknown_function"], 1, "{state}");
    assert_eq!(state["bad_frames"], 2, "{state}");
    assert!(state["refused"].as_u64().unwrap() >= 2, "{state}");
    assert_eq!(state["connections"]["opened"], 4, "{state}");
}

#[test]
fn the_unix_socket_serves_the_same_protocol() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-unix");
    let path = dir.join("nmc.sock");
    let set_path = format!("frontends.nmc_local.path={}", path.display());
    let m = Mcemu::start(
        Some(&workspace_root().join("fixtures/gaochuan-gcn.toml")),
        &[
            "--set",
            "frontends.nmc_local.enabled=true",
            "--set",
            &set_path,
        ],
    );
    assert_eq!(m.address("nmc-local"), path.display().to_string());
    let s = UnixStream::connect(&path).unwrap();
    s.set_read_timeout(Some(TIMEOUT)).unwrap();
    let mut raw = Raw::new(s);
    raw.negotiate();
    assert_eq!(raw.get_sts(1), 0);
    // A PCIe card (the local section's default) refuses NMC_DevOpenByIP (TV03).
    let f = raw.call(2, table::DEV_OPEN_BY_IP.id, &[192, 168, 1, 110]);
    assert_eq!(f.header.status, mcemu_nmc::errors::RTN_NOT_ON_THIS_CARD);
    let f = raw.call(3, table::DEV_OPEN.id, &0i16.to_le_bytes());
    assert_eq!(f.header.status, 0);
    assert_eq!(m.frontend("nmc_local")["requests"], 3);
}
