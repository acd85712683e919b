//! Native ASCII throughput (issue 14, Performance): `GetPosFb(0)` calls per second, p50 and
//! p99, from 1 and from 16 clients (one connection each, one call in flight each), beside a bare
//! line-echo server over the same loopback in the same run: the floor. Aim: ≥ 0.8× the echo.
//!
//! ```sh
//! cargo bench -p mcemu --bench ascii_throughput
//! MCEMU_ASCII_CALLS=5000 MCEMU_ASCII_ROUNDS=9 cargo bench -p mcemu --bench ascii_throughput
//! ```
//!
//! mcemu runs as its own process (`mcemu run --config fixtures/himc.toml`, listeners on free
//! ports); the echo server is a thread per connection of this process reading a line and
//! writing it back.
//!
//! A loaded host moves both figures by more than the difference between them, so the two are
//! measured in interleaved rounds (echo then mcemu, then mcemu then echo, …), each round gives
//! a ratio, and the figure is the median ratio (with the lowest and highest); the host's load
//! average is printed before and after. Beside it, the median of echo p50 ÷ mcemu p50: with one
//! call in flight the p50 latency is the rate a call takes when neither side is descheduled,
//! which a loaded host moves least.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{BufRead, BufReader, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::time::{Duration, Instant};

use mcemu_tests::{workspace_root, Mcemu};

const CALL: &[u8] = b"GetPosFb(0)\r\n";

fn calls() -> usize {
    std::env::var("MCEMU_ASCII_CALLS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(2000)
}

fn rounds() -> usize {
    std::env::var("MCEMU_ASCII_ROUNDS")
        .ok()
        .and_then(|v| v.parse().ok())
        .filter(|&r| r > 0)
        .unwrap_or(7)
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".into())
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// One client: send the call, read one reply line.
struct Client {
    reader: BufReader<TcpStream>,
    writer: TcpStream,
    line: String,
}

impl Client {
    fn connect(address: SocketAddr) -> Client {
        let s = TcpStream::connect(address).unwrap();
        s.set_nodelay(true).unwrap();
        Client {
            writer: s.try_clone().unwrap(),
            reader: BufReader::new(s),
            line: String::new(),
        }
    }

    fn call(&mut self) {
        self.writer.write_all(CALL).unwrap();
        self.line.clear();
        let n = self.reader.read_line(&mut self.line).unwrap();
        assert!(
            n > 0 && self.line.ends_with('\n'),
            "no reply: {:?}",
            self.line
        );
    }
}

/// Calls/s, p50 and p99 of `clients` connections each making `n` calls.
fn measure(address: SocketAddr, clients: usize, n: usize) -> (f64, Duration, Duration) {
    let mut conns: Vec<Client> = (0..clients).map(|_| Client::connect(address)).collect();
    for c in &mut conns {
        for _ in 0..200 {
            c.call();
        }
    }
    let start = Instant::now();
    let handles: Vec<_> = conns
        .into_iter()
        .map(|mut c| {
            std::thread::spawn(move || {
                (0..n)
                    .map(|_| {
                        let t = Instant::now();
                        c.call();
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

fn report(what: &str, clients: usize, (rate, p50, p99): (f64, Duration, Duration)) {
    println!(
        "{what:<24} {clients:>2} client(s): {rate:>9.0} calls/s  p50 {:>7.1} µs  p99 {:>7.1} µs",
        p50.as_secs_f64() * 1e6,
        p99.as_secs_f64() * 1e6
    );
}

/// A line echo: each line read is written back.
fn echo(s: TcpStream) {
    let _ = s.set_nodelay(true);
    let mut writer = s.try_clone().unwrap();
    let mut reader = BufReader::new(s);
    let mut line = Vec::new();
    loop {
        line.clear();
        match reader.read_until(b'\n', &mut line) {
            Ok(n) if n > 0 => {}
            _ => return,
        }
        if writer.write_all(&line).is_err() {
            return;
        }
    }
}

fn main() {
    let n = calls();
    let rounds = rounds();
    let m = Mcemu::start(Some(&workspace_root().join("fixtures/himc.toml")), &[]);
    let native: SocketAddr = m.address("ascii-native").parse().unwrap();
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let echo_addr = listener.local_addr().unwrap();
    std::thread::spawn(move || {
        for s in listener.incoming().flatten() {
            std::thread::spawn(move || echo(s));
        }
    });
    println!(
        "GetPosFb(0) over Native ASCII, {n} calls per client, {rounds} interleaved rounds \
         (mcemu {native}); load average {}",
        load_average()
    );
    for clients in [1, 16] {
        let mut ratios = Vec::with_capacity(rounds);
        let mut p50_ratios = Vec::with_capacity(rounds);
        for round in 0..rounds {
            // Alternate which goes first, so a drift in the host's load favours neither.
            let (floor, got) = if round % 2 == 0 {
                let floor = measure(echo_addr, clients, n);
                (floor, measure(native, clients, n))
            } else {
                let got = measure(native, clients, n);
                (measure(echo_addr, clients, n), got)
            };
            report("line echo", clients, floor);
            report("GetPosFb(0), Native ASCII", clients, got);
            ratios.push(got.0 / floor.0);
            p50_ratios.push(floor.1.as_secs_f64() / got.1.as_secs_f64());
        }
        let (low, high) = ratios
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), &r| (l.min(r), h.max(r)));
        println!(
            "{:>24} {clients:>2} client(s): median {:.2}× the echo (rounds {low:.2}–{high:.2}×); \
             by p50 latency {:.2}×",
            "ratio",
            median(&mut ratios),
            median(&mut p50_ratios)
        );
    }
    println!("load average after: {}", load_average());
}
