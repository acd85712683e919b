//! NMC round trips: `NMC_MtGetSts` through mcemu's `nmc_lib20` (its rlib, called as C calls
//! it) from 1 and from 8 threads on one device handle, over TCP and over the Unix socket,
//! beside a bare echo of the same frame sizes (18 bytes each way) over the same transport in
//! the same run: the floor.
//!
//! ```sh
//! cargo bench -p mcemu --bench nmc_roundtrip
//! MCEMU_NMC_CALLS=20000 cargo bench -p mcemu --bench nmc_roundtrip
//! ```
//!
//! mcemu runs as its own process (`mcemu run --config fixtures/gaochuan-gcn.toml`, listeners on
//! free ports, the Unix socket in a temporary directory); the echo servers are threads of this
//! process answering one frame at a time. 8 threads share one connection (the library's gate;
//! the echo's mutex), as 8 threads on one `HAND` do.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::os::unix::net::{UnixListener, UnixStream};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use mcemu_tests::{fresh_dir, workspace_root, Mcemu};
use nmc_lib20::ffi::axis::{NMC_MtGetSts, NMC_MtOpen};
use nmc_lib20::ffi::device::NMC_DevOpen;

/// Request and reply of `NMC_MtGetSts`: header + u16 handle / header + i16 word.
const FRAME: usize = 18;

fn calls() -> usize {
    std::env::var("MCEMU_NMC_CALLS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5000)
}

/// Calls/s, p50 and p99 of `threads` threads each running `one` `n` times.
fn measure(
    threads: usize,
    n: usize,
    one: Arc<dyn Fn() + Send + Sync>,
) -> (f64, Duration, Duration) {
    for _ in 0..200 {
        one();
    }
    let start = Instant::now();
    let handles: Vec<_> = (0..threads)
        .map(|_| {
            let one = Arc::clone(&one);
            std::thread::spawn(move || {
                (0..n)
                    .map(|_| {
                        let t = Instant::now();
                        one();
                        t.elapsed()
                    })
                    .collect::<Vec<_>>()
            })
        })
        .collect();
    let mut all: Vec<Duration> = handles
        .into_iter()
        .flat_map(|h| h.join().unwrap())
        .collect();
    let wall = start.elapsed();
    all.sort_unstable();
    let q = |p: f64| all[((all.len() - 1) as f64 * p) as usize];
    (all.len() as f64 / wall.as_secs_f64(), q(0.5), q(0.99))
}

fn report(what: &str, threads: usize, (rate, p50, p99): (f64, Duration, Duration)) {
    println!(
        "{what:<28} {threads} thread(s): {rate:>9.0} calls/s  p50 {:>7.1} µs  p99 {:>7.1} µs",
        p50.as_secs_f64() * 1e6,
        p99.as_secs_f64() * 1e6
    );
}

/// An echo server answering each 18-byte frame with 18 bytes.
fn echo<S: Read + Write>(mut s: S) {
    let mut buf = [0u8; FRAME];
    while s.read_exact(&mut buf).is_ok() {
        if s.write_all(&buf).is_err() {
            return;
        }
    }
}

fn echo_client<S: Read + Write + Send + 'static>(s: S) -> Arc<dyn Fn() + Send + Sync> {
    let s = Mutex::new(s);
    Arc::new(move || {
        let mut s = s.lock().unwrap();
        let mut buf = [7u8; FRAME];
        s.write_all(&buf).unwrap();
        s.read_exact(&mut buf).unwrap();
    })
}

/// `NMC_MtGetSts` on axis 0 of the device `MCEMU_NMC` names.
fn nmc_client(address: &str) -> Arc<dyn Fn() + Send + Sync> {
    // Read once, at DevOpen: set before any library call, while this process has one thread.
    std::env::set_var("MCEMU_NMC", address);
    let (mut dev, mut ax) = (0u16, 0u16);
    assert_eq!(NMC_DevOpen(0, &mut dev), 0);
    assert_eq!(NMC_MtOpen(dev, 0, &mut ax), 0);
    Arc::new(move || {
        let mut sts: i16 = 0;
        assert_eq!(NMC_MtGetSts(ax, &mut sts), 0);
    })
}

fn main() {
    let n = calls();
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-bench");
    let sock = dir.join("nmc.sock");
    let set = format!("frontends.nmc_local.path={}", sock.display());
    let m = Mcemu::start(
        Some(&workspace_root().join("fixtures/gaochuan-gcn.toml")),
        &["--set", "frontends.nmc_local.enabled=true", "--set", &set],
    );

    let tcp = TcpListener::bind("127.0.0.1:0").unwrap();
    let tcp_addr = tcp.local_addr().unwrap();
    std::thread::spawn(move || {
        for s in tcp.incoming().flatten() {
            let _ = s.set_nodelay(true);
            std::thread::spawn(move || echo(s));
        }
    });
    let echo_sock = dir.join("echo.sock");
    let unix = UnixListener::bind(&echo_sock).unwrap();
    std::thread::spawn(move || {
        for s in unix.incoming().flatten() {
            std::thread::spawn(move || echo(s));
        }
    });

    println!(
        "NMC_MtGetSts round trips, {n} calls per thread (mcemu {}):",
        m.address("nmc")
    );
    let tcp_nmc = nmc_client(m.address("nmc"));
    let unix_nmc = nmc_client(&format!("unix:{}", sock.display()));
    for threads in [1, 8] {
        let s = TcpStream::connect(tcp_addr).unwrap();
        s.set_nodelay(true).unwrap();
        report(
            "echo 18 B, TCP",
            threads,
            measure(threads, n, echo_client(s)),
        );
        report(
            "NMC_MtGetSts, TCP",
            threads,
            measure(threads, n, Arc::clone(&tcp_nmc)),
        );
        let s = UnixStream::connect(&echo_sock).unwrap();
        report(
            "echo 18 B, Unix socket",
            threads,
            measure(threads, n, echo_client(s)),
        );
        report(
            "NMC_MtGetSts, Unix socket",
            threads,
            measure(threads, n, Arc::clone(&unix_nmc)),
        );
    }
}
