//! Modbus TCP load: FC 3 reading 10 holding registers, as fast as the server answers, with 1
//! and 16 concurrent clients for a fixed time each; requests/s and p50/p99 latency per target,
//! beside two baselines measured in the same run.
//!
//! ```sh
//! cargo bench -p mcemu --bench modbus_load
//! MCEMU_LOAD_SECONDS=10 cargo bench -p mcemu --bench modbus_load
//! MCEMU_LOAD_MCEMU_CONFIG=machine.toml cargo bench -p mcemu --bench modbus_load
//! ```
//!
//! Targets, each a process of its own so that no server shares a runtime with the clients:
//! - `tokio-modbus`: a bare `tokio-modbus` TCP server over a `Vec<u16>` in memory (this bench
//!   binary re-executed with `MCEMU_BENCH_ROLE=tokio-modbus-server`): the floor of what a
//!   Rust Modbus server costs.
//! - `pymodbus`: `tests/python/modbus_server_pymodbus.py` (pymodbus 3.16.1, in memory) with the
//!   venv of `scripts/setup`.
//! - `mcemu`: `mcemu run --config fixtures/himc.toml` (or `$MCEMU_LOAD_MCEMU_CONFIG`, a path
//!   relative to the workspace root, which must enable `[frontends.modbus_tcp]`) with its
//!   listeners moved to free ports by `--set`. Registers 0–9 of the himc map are axis 0's motion
//!   and fault status and its position and velocity feedback: every request goes through the
//!   map and the engine's snapshot.
//!
//! Client: a minimal MBAP client on raw tokio `TcpStream`s, all on one current-thread runtime,
//! one outstanding request per connection, every answer checked (transaction id, function,
//! byte count). Each run connects, warms up with 50 requests per connection, then counts for
//! `MCEMU_LOAD_SECONDS` (default 3) seconds. Every loop is bounded by that deadline or a count,
//! and every read by a 5 s timeout; only 127.0.0.1.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::Read;
use std::net::SocketAddr;
use std::process::Command;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use mcemu_tests::{python, python_script, spawn_until_line, KillOnDrop, READY_TIMEOUT};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{TcpListener, TcpStream};

const ROLE_VAR: &str = "MCEMU_BENCH_ROLE";
const TOKIO_MODBUS_ROLE: &str = "tokio-modbus-server";
const REGISTERS: u16 = 10;
const WARMUP_REQUESTS: usize = 50;
const READ_TIMEOUT: Duration = Duration::from_secs(5);
/// (connections, requests in flight per connection): the issue's 1 and 16 clients with one
/// request each, and 16 pipelining 8 (Modbus TCP allows several outstanding transactions on a
/// connection, §4.2 of the messaging guide), which shows what a server can do when the client
/// and the loopback round trip stop being the limit.
const LOADS: [(usize, usize); 3] = [(1, 1), (16, 1), (16, 8)];

fn main() {
    if std::env::var(ROLE_VAR).as_deref() == Ok(TOKIO_MODBUS_ROLE) {
        tokio_modbus_server::run();
        return;
    }
    // `cargo bench` passes `--bench`; nothing else is accepted.
    let seconds: f64 = std::env::var("MCEMU_LOAD_SECONDS")
        .ok()
        .map(|s| {
            s.parse()
                .unwrap_or_else(|_| panic!("MCEMU_LOAD_SECONDS={s}: not a number"))
        })
        .unwrap_or(3.0);
    let duration = Duration::from_secs_f64(seconds);
    println!(
        "modbus_load: FC 3, {REGISTERS} registers at 0; {seconds} s per run after {WARMUP_REQUESTS} \
         warm-up requests per connection; client: raw MBAP, one tokio thread, `depth` requests \
         in flight per connection"
    );

    let mut rows: Vec<Row> = Vec::new();

    {
        let mut command = Command::new(std::env::current_exe().unwrap());
        command.env(ROLE_VAR, TOKIO_MODBUS_ROLE);
        let (mut server, addr) =
            spawn_until_line(command, "listening: tokio-modbus ", READY_TIMEOUT);
        for (clients, depth) in LOADS {
            rows.push(measure("tokio-modbus", &addr, clients, depth, duration));
        }
        server.kill();
    }

    {
        let mut command = Command::new(python());
        command
            .arg(python_script("modbus_server_pymodbus.py"))
            .args(["--port", "0"]);
        let (mut server, addr) = spawn_until_line(command, "ready ", READY_TIMEOUT);
        // pymodbus answers only the first of several requests sent at once (the rest wait
        // until the 5 s timeout), so it is measured without pipelining.
        for (clients, depth) in LOADS.into_iter().filter(|&(_, depth)| depth == 1) {
            rows.push(measure("pymodbus", &addr, clients, depth, duration));
        }
        println!("  pymodbus     pipelined: not measured (it does not answer pipelined requests)");
        server.kill();
    }

    {
        // cargo runs benches in emulator/: a relative path is taken from the workspace root.
        let config = std::env::var_os("MCEMU_LOAD_MCEMU_CONFIG")
            .map_or_else(|| "fixtures/himc.toml".into(), std::path::PathBuf::from);
        let config = mcemu_tests::workspace_root().join(config);
        let (mut server, addr) = start_mcemu(&config);
        for (clients, depth) in LOADS {
            rows.push(measure("mcemu", &addr, clients, depth, duration));
        }
        server.kill();
    }

    print_table(&rows);
}

/// mcemu on `config` with its Modbus TCP and control listeners moved to free ports, state kept
/// in a temporary directory.
fn start_mcemu(config: &std::path::Path) -> (KillOnDrop, String) {
    let state = std::env::temp_dir().join(format!("mcemu-modbus-load-{}", std::process::id()));
    let mut command = Command::new(env!("CARGO_BIN_EXE_mcemu"));
    command
        .args(["run", "--config"])
        .arg(config)
        .arg("--state-dir")
        .arg(&state)
        .args(["--set", "frontends.modbus_tcp.bind=127.0.0.1:0"])
        .args(["--set", "frontends.modbus_tcp.max_connections=64"])
        .args(["--set", "frontends.control.bind=127.0.0.1:0"]);
    spawn_until_line(command, "listening: modbus-tcp ", READY_TIMEOUT)
}

struct Row {
    target: &'static str,
    clients: usize,
    depth: usize,
    requests: usize,
    elapsed: Duration,
    p50: Duration,
    p99: Duration,
}

impl Row {
    fn rate(&self) -> f64 {
        self.requests as f64 / self.elapsed.as_secs_f64()
    }
}

/// One run: `clients` connections to `addr`, each with `depth` requests in flight, for
/// `duration`.
fn measure(
    target: &'static str,
    addr: &str,
    clients: usize,
    depth: usize,
    duration: Duration,
) -> Row {
    let addr: SocketAddr = addr
        .parse()
        .unwrap_or_else(|e| panic!("{target}: bad address {addr:?}: {e}"));
    assert!(addr.ip().is_loopback(), "{target}: {addr} is not loopback");
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    runtime.block_on(async move {
        let mut connections = Vec::with_capacity(clients);
        for _ in 0..clients {
            let stream = TcpStream::connect(addr)
                .await
                .unwrap_or_else(|e| panic!("{target}: connect {addr}: {e}"));
            stream.set_nodelay(true).unwrap();
            connections.push(Client::new(stream));
        }
        // Warm-up (not counted), bounded by count.
        for c in &mut connections {
            for _ in 0..WARMUP_REQUESTS.div_ceil(depth) {
                c.requests(target, depth, &mut Vec::new()).await;
            }
        }
        let start = Instant::now();
        let deadline = start + duration;
        let tasks: Vec<_> = connections
            .into_iter()
            .map(|mut c| {
                tokio::spawn(async move {
                    let mut latencies = Vec::with_capacity(1 << 16);
                    while Instant::now() < deadline {
                        c.requests(target, depth, &mut latencies).await;
                    }
                    latencies
                })
            })
            .collect();
        let mut all: Vec<Duration> = Vec::new();
        for t in tasks {
            all.extend(t.await.unwrap());
        }
        let elapsed = start.elapsed();
        assert!(!all.is_empty(), "{target}: no request completed");
        all.sort_unstable();
        let at = |q: f64| all[((all.len() - 1) as f64 * q).round() as usize];
        let row = Row {
            target,
            clients,
            depth,
            requests: all.len(),
            elapsed,
            p50: at(0.50),
            p99: at(0.99),
        };
        println!(
            "  {target:<12} clients={clients:<2} depth={depth} {:>9.0} req/s, p50 {:>8.1?}, p99 {:>8.1?} ({} requests)",
            row.rate(),
            row.p50,
            row.p99,
            row.requests
        );
        row
    })
}

/// A minimal Modbus TCP client: FC 3, address 0, 10 registers.
struct Client {
    stream: TcpStream,
    transaction: u16,
    batch: Vec<u8>,
    response: Vec<u8>,
}

impl Client {
    fn new(stream: TcpStream) -> Client {
        Client {
            stream,
            transaction: 0,
            batch: Vec::new(),
            response: vec![0; 260],
        }
    }

    /// `depth` requests written at once, then their answers in order; pushes each round-trip
    /// time (from the write to its own answer). Panics on a wrong answer.
    async fn requests(&mut self, target: &str, depth: usize, latencies: &mut Vec<Duration>) {
        let q = REGISTERS.to_be_bytes();
        let first = self.transaction.wrapping_add(1);
        self.batch.clear();
        for _ in 0..depth {
            self.transaction = self.transaction.wrapping_add(1);
            let t = self.transaction.to_be_bytes();
            self.batch
                .extend_from_slice(&[t[0], t[1], 0, 0, 0, 6, 1, 3, 0, 0, q[0], q[1]]);
        }
        let sent = Instant::now();
        self.stream.write_all(&self.batch).await.unwrap();
        for k in 0..depth {
            let t = first.wrapping_add(k as u16).to_be_bytes();
            let header = &mut self.response[..7];
            tokio::time::timeout(READ_TIMEOUT, self.stream.read_exact(header))
                .await
                .unwrap_or_else(|_| panic!("{target}: no answer within {READ_TIMEOUT:?}"))
                .unwrap_or_else(|e| panic!("{target}: read: {e}"));
            let length = usize::from(u16::from_be_bytes([header[4], header[5]]));
            assert!(
                header[..2] == t && header[2..4] == [0, 0] && (2..=254).contains(&length),
                "{target}: bad MBAP header {header:02x?}"
            );
            let body = &mut self.response[7..6 + length];
            tokio::time::timeout(READ_TIMEOUT, self.stream.read_exact(body))
                .await
                .unwrap_or_else(|_| panic!("{target}: truncated answer"))
                .unwrap_or_else(|e| panic!("{target}: read: {e}"));
            latencies.push(sent.elapsed());
            let expected_count = 2 * usize::from(REGISTERS);
            assert!(
                body[0] == 3
                    && usize::from(body[1]) == expected_count
                    && length == 3 + expected_count,
                "{target}: unexpected answer {body:02x?} (an exception is 0x83 then its code)"
            );
        }
    }
}

fn print_table(rows: &[Row]) {
    println!();
    println!(
        "{:<14} {:>7} {:>5} {:>10} {:>10} {:>10} {:>9} {:>9} {:>8}",
        "target", "clients", "depth", "req/s", "p50", "p99", "÷ tokio", "÷ pymod", "p99 ×"
    );
    for r in rows {
        let base = |target: &str| {
            rows.iter()
                .find(|b| b.target == target && b.clients == r.clients && b.depth == r.depth)
        };
        let ratio =
            |b: Option<&Row>| b.map_or("-".into(), |b| format!("{:.2}", r.rate() / b.rate()));
        let p99 = base("tokio-modbus").map_or("-".into(), |b| {
            format!("{:.2}", r.p99.as_secs_f64() / b.p99.as_secs_f64())
        });
        println!(
            "{:<14} {:>7} {:>5} {:>10.0} {:>10} {:>10} {:>9} {:>9} {:>8}",
            r.target,
            r.clients,
            r.depth,
            r.rate(),
            format!("{:.1?}", r.p50),
            format!("{:.1?}", r.p99),
            ratio(base("tokio-modbus")),
            ratio(base("pymodbus")),
            p99
        );
    }
    println!(
        "(÷ = throughput ratio to that baseline, same clients and depth; p99 × = p99 latency ratio \
         to tokio-modbus)"
    );
}

/// The `tokio-modbus` baseline server: FC 3, 6 and 16 over 10 000 registers in memory.
mod tokio_modbus_server {
    use super::*;
    use std::future::{ready, Ready};
    use tokio_modbus::server::tcp::{accept_tcp_connection, Server};
    use tokio_modbus::{ExceptionCode, Request, Response};

    const SIZE: usize = 10_000;

    struct Memory {
        registers: Arc<Mutex<Vec<u16>>>,
    }

    impl tokio_modbus::server::Service for Memory {
        type Request = Request<'static>;
        type Response = Response;
        type Exception = ExceptionCode;
        type Future = Ready<Result<Response, ExceptionCode>>;

        fn call(&self, req: Request<'static>) -> Self::Future {
            let mut regs = self.registers.lock().unwrap();
            let range = |addr: u16, n: usize| {
                let start = usize::from(addr);
                (start + n <= SIZE).then_some(start..start + n)
            };
            ready(match req {
                Request::ReadHoldingRegisters(addr, n) => match range(addr, usize::from(n)) {
                    Some(r) => Ok(Response::ReadHoldingRegisters(regs[r].to_vec())),
                    None => Err(ExceptionCode::IllegalDataAddress),
                },
                Request::WriteSingleRegister(addr, value) => match range(addr, 1) {
                    Some(r) => {
                        regs[r.start] = value;
                        Ok(Response::WriteSingleRegister(addr, value))
                    }
                    None => Err(ExceptionCode::IllegalDataAddress),
                },
                Request::WriteMultipleRegisters(addr, values) => match range(addr, values.len()) {
                    Some(r) => {
                        regs[r].copy_from_slice(&values);
                        Ok(Response::WriteMultipleRegisters(addr, values.len() as u16))
                    }
                    None => Err(ExceptionCode::IllegalDataAddress),
                },
                _ => Err(ExceptionCode::IllegalFunction),
            })
        }
    }

    /// Serve on 127.0.0.1:0, print `listening: tokio-modbus ADDR`, exit when stdin ends (the
    /// bench process holds it open and dies or drops it at the end).
    pub fn run() {
        std::thread::spawn(|| {
            let mut sink = Vec::new();
            let _ = std::io::stdin().read_to_end(&mut sink);
            std::process::exit(0);
        });
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .enable_all()
            .build()
            .unwrap();
        runtime.block_on(async {
            let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
            println!("listening: tokio-modbus {}", listener.local_addr().unwrap());
            let registers = Arc::new(Mutex::new((0..SIZE as u16).collect::<Vec<u16>>()));
            let server = Server::new(listener);
            let on_connected = |stream, socket_addr| {
                let registers = Arc::clone(&registers);
                async move {
                    accept_tcp_connection(stream, socket_addr, move |_| {
                        Ok(Some(Memory {
                            registers: Arc::clone(&registers),
                        }))
                    })
                }
            };
            let on_process_error = |err| eprintln!("tokio-modbus server: {err}");
            server.serve(&on_connected, on_process_error).await.unwrap();
        });
    }
}
