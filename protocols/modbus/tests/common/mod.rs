//! Shared test rigs: servers on real sockets and ptys, raw-byte clients; register maps over
//! an engine ([`map_unit`]).
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used, clippy::panic)]

pub mod map_unit;

use std::fs::OpenOptions;
use std::future::Future;
use std::net::SocketAddr;
use std::os::fd::OwnedFd;
use std::os::unix::fs::OpenOptionsExt;
use std::sync::Arc;
use std::time::Duration;

use mcemu_modbus::config::{RtuOverTcpConfig, TcpConfig};
use mcemu_modbus::frame::rtu;
use mcemu_modbus::memory::{MemoryModel, Table};
use mcemu_modbus::model::DataModel;
use mcemu_modbus::state::{Framing, FrontendState};
use mcemu_modbus::transport::rtu_over_tcp::serve_rtu_over_tcp;
use mcemu_modbus::transport::tcp::serve_tcp;
use nix::sys::termios::{cfmakeraw, tcgetattr, tcsetattr, SetArg};
use tokio::io::unix::AsyncFd;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::oneshot;
use tokio::task::JoinHandle;

/// Upper bound on waiting for something that must happen; only a broken server reaches it.
pub const MUST_HAPPEN: Duration = Duration::from_secs(5);

/// The table layout the conformance tests use: every table holds addresses 100..200, so
/// 99 and 200 are start−1 and end+1.
pub fn model_100_to_199() -> MemoryModel {
    MemoryModel::new()
        .with_range(Table::Coils, 100, 100)
        .with_range(Table::DiscreteInputs, 100, 100)
        .with_range(Table::InputRegisters, 100, 100)
        .with_range(Table::HoldingRegisters, 100, 100)
}

/// A server task on a real socket, stopped on drop.
pub struct Running<D> {
    pub addr: SocketAddr,
    pub state: Arc<FrontendState>,
    pub model: Arc<D>,
    stop: Option<oneshot::Sender<()>>,
    task: Option<JoinHandle<()>>,
}

impl<D> Running<D> {
    /// Stop the server and wait until it has closed every connection.
    pub async fn shutdown(mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        if let Some(t) = self.task.take() {
            tokio::time::timeout(MUST_HAPPEN, t).await.unwrap().unwrap();
        }
    }
}

impl<D> Drop for Running<D> {
    fn drop(&mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
    }
}

fn stopper() -> (oneshot::Sender<()>, impl Future<Output = ()>) {
    let (tx, rx) = oneshot::channel::<()>();
    (tx, async move {
        let _ = rx.await;
    })
}

pub async fn start_tcp<D: DataModel>(model: D, config: TcpConfig) -> Running<D> {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let state = Arc::new(FrontendState::new("modbus_tcp", Framing::Tcp, &config.faults).unwrap());
    let model = Arc::new(model);
    let (stop, shutdown) = stopper();
    let task = tokio::spawn({
        let (model, state) = (Arc::clone(&model), Arc::clone(&state));
        async move { serve_tcp(listener, model, &config, state, shutdown).await }
    });
    Running {
        addr,
        state,
        model,
        stop: Some(stop),
        task: Some(task),
    }
}

pub async fn start_rtu_over_tcp<D: DataModel>(model: D, config: RtuOverTcpConfig) -> Running<D> {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let state = Arc::new(
        FrontendState::new("modbus_rtu_over_tcp", Framing::RtuOverTcp, &config.faults).unwrap(),
    );
    let model = Arc::new(model);
    let (stop, shutdown) = stopper();
    let task = tokio::spawn({
        let (model, state) = (Arc::clone(&model), Arc::clone(&state));
        async move { serve_rtu_over_tcp(listener, model, &config, state, shutdown).await }
    });
    Running {
        addr,
        state,
        model,
        stop: Some(stop),
        task: Some(task),
    }
}

/// An MBAP request: transaction id, unit, PDU.
pub fn mbap(transaction: u16, unit: u8, pdu: &[u8]) -> Vec<u8> {
    let mut out = transaction.to_be_bytes().to_vec();
    out.extend_from_slice(&[0, 0]);
    out.extend_from_slice(&((pdu.len() + 1) as u16).to_be_bytes());
    out.push(unit);
    out.extend_from_slice(pdu);
    out
}

/// Read one MBAP frame (header, then as many bytes as its length says).
pub async fn read_mbap(stream: &mut TcpStream) -> Vec<u8> {
    tokio::time::timeout(MUST_HAPPEN, async {
        let mut header = [0u8; 7];
        stream.read_exact(&mut header).await.unwrap();
        let len = u16::from_be_bytes([header[4], header[5]]) as usize;
        let mut rest = vec![0u8; len - 1];
        stream.read_exact(&mut rest).await.unwrap();
        let mut frame = header.to_vec();
        frame.extend_from_slice(&rest);
        frame
    })
    .await
    .expect("no reply")
}

/// Send one MBAP request and read the reply.
pub async fn transact(stream: &mut TcpStream, transaction: u16, unit: u8, pdu: &[u8]) -> Vec<u8> {
    stream
        .write_all(&mbap(transaction, unit, pdu))
        .await
        .unwrap();
    read_mbap(stream).await
}

/// The PDU of a reply frame (after the 7-byte MBAP header).
pub fn pdu_of(frame: &[u8]) -> &[u8] {
    &frame[7..]
}

/// Wait for the peer to close: `read` gives 0 bytes or a reset.
pub async fn closed_by_peer(stream: &mut TcpStream) -> bool {
    let mut b = [0u8; 64];
    tokio::time::timeout(MUST_HAPPEN, async {
        loop {
            match stream.read(&mut b).await {
                Ok(0) | Err(_) => return true,
                Ok(_) => {}
            }
        }
    })
    .await
    .unwrap_or(false)
}

/// Wait until `cond` holds (polling a counter the server sets); panics after [`MUST_HAPPEN`].
pub async fn eventually(what: &str, cond: impl Fn() -> bool) {
    let t = tokio::time::Instant::now();
    while !cond() {
        assert!(t.elapsed() < MUST_HAPPEN, "never happened: {what}");
        tokio::time::sleep(Duration::from_millis(2)).await;
    }
}

/// An RTU frame with its CRC.
pub fn rtu_frame(unit: u8, pdu: &[u8]) -> Vec<u8> {
    let mut out = vec![];
    rtu::encode(unit, pdu, &mut out);
    out
}

/// The test's end of a serial line (a pty side), non-blocking under tokio.
pub struct Line {
    fd: AsyncFd<OwnedFd>,
}

impl Line {
    /// Open a tty path the way a client would (raw mode, no controlling terminal).
    pub fn open(path: &str) -> Line {
        let file = OpenOptions::new()
            .read(true)
            .write(true)
            .custom_flags(nix::libc::O_NOCTTY | nix::libc::O_NONBLOCK)
            .open(path)
            .unwrap();
        let fd = OwnedFd::from(file);
        let mut t = tcgetattr(&fd).unwrap();
        cfmakeraw(&mut t);
        tcsetattr(&fd, SetArg::TCSANOW, &t).unwrap();
        Line::from_fd(fd)
    }

    /// Wrap an fd that is already non-blocking (e.g. a pty master).
    pub fn from_fd(fd: OwnedFd) -> Line {
        // See the transport: an `OwnedFd` keeps its fd for the `AsyncFd`'s whole life.
        #[allow(deprecated)]
        let fd = AsyncFd::new(fd).unwrap();
        Line { fd }
    }

    pub fn fd(&self) -> &OwnedFd {
        self.fd.get_ref()
    }

    pub async fn send(&self, mut bytes: &[u8]) {
        while !bytes.is_empty() {
            let mut guard = self.fd.writable().await.unwrap();
            if let Ok(r) = guard
                .try_io(|fd| nix::unistd::write(fd.get_ref(), bytes).map_err(std::io::Error::from))
            {
                bytes = &bytes[r.unwrap()..];
            }
        }
    }

    /// Read exactly `n` bytes; panics after [`MUST_HAPPEN`].
    pub async fn recv(&self, n: usize) -> Vec<u8> {
        let mut out = Vec::with_capacity(n);
        let mut buf = [0u8; 512];
        tokio::time::timeout(MUST_HAPPEN, async {
            while out.len() < n {
                let mut guard = self.fd.readable().await.unwrap();
                let want = (n - out.len()).min(buf.len());
                if let Ok(r) = guard.try_io(|fd| {
                    nix::unistd::read(fd.get_ref(), &mut buf[..want]).map_err(std::io::Error::from)
                }) {
                    let k = r.unwrap();
                    out.extend_from_slice(&buf[..k]);
                }
            }
        })
        .await
        .unwrap_or_else(|_| panic!("expected {n} bytes, got {out:02X?}"));
        out
    }

    /// Send a request frame and read a reply of `reply_len` bytes.
    pub async fn transact(&self, request: &[u8], reply_len: usize) -> Vec<u8> {
        self.send(request).await;
        self.recv(reply_len).await
    }
}

/// Make a pty pair for a test that plays the device's other end: (master, slave path).
pub fn pty_pair() -> (OwnedFd, String, OwnedFd) {
    let pty = nix::pty::openpty(None, None).unwrap();
    let path = nix::unistd::ttyname(&pty.slave)
        .unwrap()
        .to_string_lossy()
        .into_owned();
    let mut t = tcgetattr(&pty.slave).unwrap();
    cfmakeraw(&mut t);
    tcsetattr(&pty.slave, SetArg::TCSANOW, &t).unwrap();
    let flags = nix::fcntl::OFlag::from_bits_truncate(
        nix::fcntl::fcntl(&pty.master, nix::fcntl::FcntlArg::F_GETFL).unwrap(),
    );
    nix::fcntl::fcntl(
        &pty.master,
        nix::fcntl::FcntlArg::F_SETFL(flags | nix::fcntl::OFlag::O_NONBLOCK),
    )
    .unwrap();
    (pty.master, path, pty.slave)
}
