//! Request round trips through each Modbus transport, against `MemoryModel`: FC 3 reading 10
//! holding registers, one request in flight. Baseline in the same run: the same request through
//! `Server::handle` alone (no I/O), so the figures show what each transport adds.
//!
//! `cargo bench -p mcemu-modbus --bench transport`

// A benchmark that cannot set up its sockets should stop loudly.
#![allow(clippy::expect_used, clippy::unwrap_used)]

use std::os::fd::OwnedFd;
use std::os::unix::fs::OpenOptionsExt;
use std::sync::Arc;
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mcemu_modbus::config::{RtuConfig, RtuOverTcpConfig, TcpConfig};
use mcemu_modbus::frame::rtu;
use mcemu_modbus::memory::MemoryModel;
use mcemu_modbus::model::Peer;
use mcemu_modbus::server::{Outcome, Server};
use mcemu_modbus::state::{Framing, FrontendState};
use mcemu_modbus::transport::rtu::{serve_rtu, RtuLine};
use mcemu_modbus::transport::rtu_over_tcp::serve_rtu_over_tcp;
use mcemu_modbus::transport::tcp::serve_tcp;
use nix::sys::termios::{cfmakeraw, tcgetattr, tcsetattr, SetArg};
use tokio::io::unix::AsyncFd;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::runtime::Runtime;

const PDU: [u8; 5] = [3, 0, 0, 0, 10];
/// FC 3 reply for 10 registers: FC, byte count, 20 bytes.
const REPLY_PDU: usize = 22;

fn state(framing: Framing) -> Arc<FrontendState> {
    Arc::new(FrontendState::new("bench", framing, &[]).expect("state"))
}

fn runtime() -> Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .expect("runtime")
}

/// `iters` sequential round trips on a connected stream.
async fn round_trips(s: &mut TcpStream, request: &[u8], reply_len: usize, iters: u64) -> Duration {
    let mut reply = vec![0u8; reply_len];
    let start = Instant::now();
    for _ in 0..iters {
        s.write_all(request).await.unwrap();
        s.read_exact(&mut reply).await.unwrap();
    }
    start.elapsed()
}

fn transports(c: &mut Criterion) {
    let rt = runtime();
    let mut group = c.benchmark_group("modbus_fc3_10_registers");
    group.throughput(Throughput::Elements(1));

    // Baseline: the handler alone.
    let server = Server::new(Arc::new(MemoryModel::new()), state(Framing::Tcp));
    let peer = Peer::Serial("bench".into());
    group.bench_function("server_handle_only", |b| {
        b.iter_custom(|iters| {
            rt.block_on(async {
                let start = Instant::now();
                for _ in 0..iters {
                    let out = server.handle(1, &PDU, &peer).await;
                    assert!(matches!(out, Outcome::Reply(ref r) if r.len() == REPLY_PDU));
                }
                start.elapsed()
            })
        })
    });

    // Modbus TCP over loopback.
    let mut tcp = rt.block_on(async {
        let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        tokio::spawn(async move {
            serve_tcp(
                listener,
                Arc::new(MemoryModel::new()),
                &TcpConfig::default(),
                state(Framing::Tcp),
                std::future::pending(),
            )
            .await
        });
        let s = TcpStream::connect(addr).await.unwrap();
        s.set_nodelay(true).unwrap();
        s
    });
    let mut request = vec![0, 1, 0, 0, 0, 6, 1];
    request.extend_from_slice(&PDU);
    group.bench_function("tcp_loopback", |b| {
        b.iter_custom(|iters| rt.block_on(round_trips(&mut tcp, &request, 7 + REPLY_PDU, iters)))
    });

    // RTU over TCP over loopback.
    let mut rot = rt.block_on(async {
        let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        tokio::spawn(async move {
            serve_rtu_over_tcp(
                listener,
                Arc::new(MemoryModel::new()),
                &RtuOverTcpConfig::default(),
                state(Framing::RtuOverTcp),
                std::future::pending(),
            )
            .await
        });
        let s = TcpStream::connect(addr).await.unwrap();
        s.set_nodelay(true).unwrap();
        s
    });
    let mut frame = vec![];
    rtu::encode(1, &PDU, &mut frame);
    group.bench_function("rtu_over_tcp_loopback", |b| {
        b.iter_custom(|iters| rt.block_on(round_trips(&mut rot, &frame, 1 + REPLY_PDU + 2, iters)))
    });

    // RTU on a pty the server creates (early end of frame by length and CRC).
    let client = rt.block_on(async {
        let line = RtuLine::open(&RtuConfig::default()).unwrap();
        let path = line.path().to_owned();
        tokio::spawn(serve_rtu(
            line,
            Arc::new(MemoryModel::new()),
            state(Framing::Rtu),
            std::future::pending(),
        ));
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .custom_flags(nix::libc::O_NOCTTY | nix::libc::O_NONBLOCK)
            .open(path)
            .unwrap();
        let fd = OwnedFd::from(file);
        let mut t = tcgetattr(&fd).unwrap();
        cfmakeraw(&mut t);
        tcsetattr(&fd, SetArg::TCSANOW, &t).unwrap();
        // An `OwnedFd` keeps its fd for the `AsyncFd`'s whole life (see the transport).
        #[allow(deprecated)]
        AsyncFd::new(fd).unwrap()
    });
    group.bench_function("rtu_pty", |b| {
        b.iter_custom(|iters| {
            rt.block_on(async {
                let mut buf = [0u8; 64];
                let want = 1 + REPLY_PDU + 2;
                let start = Instant::now();
                for _ in 0..iters {
                    let mut sent = 0;
                    while sent < frame.len() {
                        let mut g = client.writable().await.unwrap();
                        if let Ok(r) = g.try_io(|fd| {
                            nix::unistd::write(fd.get_ref(), &frame[sent..]).map_err(Into::into)
                        }) {
                            sent += r.unwrap();
                        }
                    }
                    let mut got = 0;
                    while got < want {
                        let mut g = client.readable().await.unwrap();
                        if let Ok(r) = g.try_io(|fd| {
                            nix::unistd::read(fd.get_ref(), &mut buf[got..want]).map_err(Into::into)
                        }) {
                            got += r.unwrap();
                        }
                    }
                }
                start.elapsed()
            })
        })
    });
    group.finish();
}

criterion_group!(benches, transports);
criterion_main!(benches);
