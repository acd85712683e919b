//! CANopen process data under load: 32 CiA 402 nodes on one bus, SYNC at 1 kHz, one RPDO and
//! one TPDO per node per SYNC. Counts the TPDOs that were late (not in before the next SYNC)
//! or missing, the SYNC rate actually produced, the CPU mcemu used, and the servo runtime's own
//! statistics, beside a baseline measured in the same run.
//!
//! ```sh
//! cargo bench -p mcemu --bench canopen_sync                       # 60 s per measurement
//! MCEMU_SYNC_SECONDS=5 cargo bench -p mcemu --bench canopen_sync  # a short run
//! MCEMU_SYNC_NODES=8 MCEMU_SYNC_VCAN=0 cargo bench -p mcemu --bench canopen_sync
//! ```
//!
//! The machine is generated: `MCEMU_SYNC_NODES` (default 32) `bus_position` axes, each with a
//! CiA 402 drive (`master = "external"`) that is CANopen node 1…N with the shipped
//! `cia402-drive.eds`, at mcemu's default 1 ms servo period. The master (this bench, Rust):
//! - configures each node over SDO (expedited writes, one request to every node at once): TPDO1,
//!   TPDO2 and TPDO4 invalid, so that TPDO3 is the one TPDO — the EDS default: COB-ID 0x380+id,
//!   transmission type 1 (every SYNC), statusword 0x6041 and position actual value 0x6064;
//!   mode of operation 8 (cyclic synchronous position); then NMT start (all nodes);
//! - sends SYNC (0x080, no data) every 1 ms against absolute deadlines, each followed by one
//!   RPDO3 per node (0x400+id: controlword 0x6040 and target position 0x607A; the controlword
//!   walks shutdown → switch on → enable operation over the first 200 SYNCs, the target stays
//!   0). A deadline missed by more than a period is skipped, not caught up in a burst
//!   (counted as a slip);
//! - receives everything on a second connection with the transport's own arrival stamps (the
//!   kernel's SO_TIMESTAMPNS on SocketCAN, the hub's on socketcand) and judges each SYNC
//!   window (from one SYNC to the next, in arrival order): a node whose TPDO is not in it is
//!   late or missing; a TPDO that never arrived is missing.
//!
//! 500 SYNCs of warm-up, then `MCEMU_SYNC_SECONDS` (default 60) seconds measured. CPU: utime +
//! stime from `/proc/PID/stat` over the measured window, as % of one core; servo statistics:
//! `GET /api/v1/state` `runtime` at the window's start and end (differences).
//!
//! Targets, on each transport:
//! - `reflector` (baseline): this binary re-executed (`MCEMU_BENCH_ROLE=sync-reflector`), which
//!   answers every SYNC at once with one 6-byte TPDO per node id: what the master, the checker
//!   and the transport do on their own, with a slave that costs nothing.
//! - `mcemu`: the nodes served inside mcemu's servo tick.
//!
//! Transports: `socketcand` on this host (mcemu serves the bus over socketcand only; the
//! reflector reaches it through an mcemu with no nodes, a plain hub), and `vcan (VM)`: this
//! binary inside `tests/vcan/run` (`MCEMU_BENCH_ROLE=sync-vcan`) on a real vcan0, in a qemu
//! TCG VM on this machine (no CAN in its kernel), where CPU-bound code is 10–30 times slower.
//! `MCEMU_SYNC_VCAN=0` skips it.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod canopen_support;

use std::io::Read;
use std::process::Command;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use canopen_support::{cpu_seconds, emit, open, run_in_vcan, Frame, Link, Transport, ROLE_VAR};
use mcemu_tests::{spawn_until_line, Mcemu, TempDir};
use serde_json::{json, Value};

const VCAN_ROLE: &str = "sync-vcan";
const REFLECTOR_ROLE: &str = "sync-reflector";
const PERIOD: Duration = Duration::from_millis(1);
const WARMUP_SYNCS: u64 = 500;
const IDLE: Duration = Duration::from_secs(3);
/// The controlword of SYNC k: shutdown, switch on, enable operation (CiA 402 §6.2).
fn controlword(k: u64) -> u16 {
    match k {
        0..100 => 0x0006,
        100..200 => 0x0007,
        _ => 0x000F,
    }
}

struct Settings {
    nodes: u16,
    seconds: f64,
}

fn main() {
    std::env::set_var("MCEMU_BIN", env!("CARGO_BIN_EXE_mcemu"));
    let settings = Settings {
        nodes: canopen_support::env_f64("MCEMU_SYNC_NODES", 32.0) as u16,
        seconds: canopen_support::env_f64("MCEMU_SYNC_SECONDS", 60.0),
    };
    assert!(
        (1..=127).contains(&settings.nodes),
        "MCEMU_SYNC_NODES: 1 … 127"
    );
    match std::env::var(ROLE_VAR).as_deref() {
        Ok(REFLECTOR_ROLE) => return reflector(),
        Ok(VCAN_ROLE) => {
            for row in measure(true, &settings) {
                emit(&row);
            }
            return;
        }
        _ => {}
    }
    println!(
        "canopen_sync: {} nodes, SYNC every {PERIOD:?} + one RPDO and one TPDO per node; \
         {WARMUP_SYNCS} SYNCs warm-up, then {} s measured per target (MCEMU_SYNC_SECONDS)",
        settings.nodes, settings.seconds
    );
    let mut rows = measure(false, &settings);
    if std::env::var("MCEMU_SYNC_VCAN").as_deref() != Ok("0") {
        println!("  vcan section: this bench inside tests/vcan/run (a TCG VM here)");
        let timeout = Duration::from_secs_f64(2.0 * (settings.seconds + 60.0) + 300.0);
        rows.extend(run_in_vcan(VCAN_ROLE, timeout));
    }
    print_table(&rows, &settings);
}

/// The machine: N drives as nodes 1…N (none for the plain hub the host's reflector uses).
fn machine(nodes: u16, with_nodes: bool, interface: &str) -> String {
    let mut s = String::from(
        "# canopen_sync bench machine (generated)\n[machine]\nname = \"canopen-sync-bench\"\n\
         period = 0.001\nclock = \"realtime\"\n",
    );
    let count = if with_nodes { nodes } else { 1 };
    for i in 0..count {
        s += &format!(
            "\n[[axes]]\nname = \"a{i}\"\n[axes.params]\naxis_type = \"bus_position\"\n\
             units = 10000\nrep_mode = \"finite\"\n"
        );
    }
    if with_nodes {
        for i in 0..nodes {
            s += &format!(
                "\n[[drives]]\naxis = {i}\nmaster = \"external\"\nincrements_per_unit = 10000\n\
                 name = \"bench drive {i}\"\nserial = {}\n",
                i + 1
            );
        }
    }
    s += &format!(
        "\n[frontends.control]\nenabled = true\nbind = \"127.0.0.1:0\"\n\n\
         [frontends.canopen]\nenabled = true\ninterface = \"{interface}\"\n\
         interface_optional = false\n"
    );
    if with_nodes {
        for i in 0..nodes {
            s += &format!(
                "[[frontends.canopen.nodes]]\nnode_id = {}\ndrive = {i}\neds = \"cia402-drive\"\n",
                i + 1
            );
        }
    }
    s += "\n[frontends.socketcand]\nenabled = true\nbind = \"127.0.0.1:0\"\n";
    s
}

fn measure(vm: bool, settings: &Settings) -> Vec<Value> {
    let dir = TempDir::new("canopen-sync");
    let transport_name = if vm { "vcan (VM)" } else { "socketcand" };
    let mut rows = Vec::new();

    // Baseline: the reflector.
    {
        let hub = (!vm).then(|| {
            let path = dir.path().join("hub.toml");
            std::fs::write(&path, machine(settings.nodes, false, "")).unwrap();
            Mcemu::start(Some(&path), &[])
        });
        let t = match &hub {
            Some(m) => socketcand(m),
            None => Transport::SocketCan("vcan0".into()),
        };
        let mut command = Command::new(std::env::current_exe().unwrap());
        command
            .env(ROLE_VAR, REFLECTOR_ROLE)
            .env("MCEMU_SYNC_NODES", settings.nodes.to_string())
            .env("MCEMU_SYNC_TRANSPORT", transport_spec(&t));
        let (mut reflector, _) = spawn_until_line(command, "ready", mcemu_tests::READY_TIMEOUT);
        let mut cpu = vec![("reflector", reflector.id())];
        if let Some(m) = &hub {
            cpu.push(("mcemu hub", m.pid()));
        }
        let mut row = run(&t, settings, None, &cpu, vm);
        row["target"] = json!("reflector");
        row["transport"] = json!(transport_name);
        println!("  {}", summary(&row));
        rows.push(row);
        reflector.kill();
    }

    // mcemu with N nodes.
    {
        let path = dir.path().join("nodes.toml");
        let interface = if vm { "vcan0" } else { "" };
        std::fs::write(&path, machine(settings.nodes, true, interface)).unwrap();
        let mcemu = Mcemu::start(Some(&path), &[]);
        let t = if vm {
            Transport::SocketCan("vcan0".into())
        } else {
            socketcand(&mcemu)
        };
        let pid = mcemu.pid();
        let mut row = run(&t, settings, Some(&mcemu), &[("mcemu", pid)], vm);
        row["target"] = json!("mcemu");
        row["transport"] = json!(transport_name);
        println!("  {}", summary(&row));
        rows.push(row);
    }
    rows
}

fn socketcand(m: &Mcemu) -> Transport {
    Transport::Socketcand {
        addr: m.address("socketcand").to_string(),
        bus: "vcan0".into(),
    }
}

fn transport_spec(t: &Transport) -> String {
    match t {
        Transport::SocketCan(iface) => format!("socketcan:{iface}"),
        Transport::Socketcand { addr, bus } => format!("socketcand:{addr}:{bus}"),
    }
}

fn parse_transport(spec: &str) -> Transport {
    if let Some(iface) = spec.strip_prefix("socketcan:") {
        return Transport::SocketCan(iface.into());
    }
    let rest = spec.strip_prefix("socketcand:").expect("transport spec");
    let (addr, bus) = rest.rsplit_once(':').unwrap();
    Transport::Socketcand {
        addr: addr.into(),
        bus: bus.into(),
    }
}

/// The baseline slave: every SYNC answered at once with a TPDO (statusword "operation
/// enabled", position 0) from each node id 1…N. Exits when its stdin ends.
fn reflector() {
    let nodes = canopen_support::env_f64("MCEMU_SYNC_NODES", 32.0) as u16;
    let t = parse_transport(&std::env::var("MCEMU_SYNC_TRANSPORT").unwrap());
    let mut link = open(&t);
    std::thread::spawn(|| {
        let _ = std::io::stdin().read_to_end(&mut Vec::new());
        std::process::exit(0);
    });
    let tpdos: Vec<Frame> = (1..=nodes)
        .map(|n| Frame::new(0x380 + n, &[0x27, 0x02, 0, 0, 0, 0]))
        .collect();
    println!("ready");
    loop {
        if let Some(f) = link.recv(Duration::from_millis(100)) {
            if f.id == 0x080 {
                link.send_all(&tpdos);
            }
        }
    }
}

/// Expedited SDO writes of one value to every node at once, then every answer; panics on an
/// abort or a missing answer.
fn configure(link: &mut dyn Link, nodes: u16) {
    let writes: [(u16, u8, u32, usize); 4] = [
        (0x1800, 1, 0xC000_0180, 4),
        (0x1801, 1, 0xC000_0280, 4),
        (0x1803, 1, 0xC000_0480, 4),
        (0x6060, 0, 8, 1),
    ];
    for (index, sub, value, len) in writes {
        let frames: Vec<Frame> = (1..=nodes)
            .map(|n| {
                // COB-IDs carry the node id; 0x6060 does not.
                let v = if index < 0x2000 {
                    value + u32::from(n)
                } else {
                    value
                };
                let b = v.to_le_bytes();
                let i = index.to_le_bytes();
                let cmd = 0x23 | (((4 - len) as u8) << 2);
                Frame::new(0x600 + n, &[cmd, i[0], i[1], sub, b[0], b[1], b[2], b[3]])
            })
            .collect();
        link.send_all(&frames);
        let mut answered = vec![false; usize::from(nodes)];
        let deadline = Instant::now() + Duration::from_secs(30);
        while answered.iter().any(|a| !a) {
            let left = deadline.saturating_duration_since(Instant::now());
            let f = link.recv(left).unwrap_or_else(|| {
                panic!("SDO write {index:04X}:{sub}: no answer from every node within 30 s")
            });
            if !(0x581..=0x580 + nodes).contains(&f.id) {
                continue;
            }
            let n = f.id - 0x580;
            match f.data[0] {
                0x60 => answered[usize::from(n - 1)] = true,
                0x80 => panic!(
                    "SDO write {index:04X}:{sub} to node {n}: abort 0x{:08X}",
                    u32::from_le_bytes([f.data[4], f.data[5], f.data[6], f.data[7]])
                ),
                _ => {}
            }
        }
    }
}

/// What the receiving connection saw.
#[derive(Default)]
struct Checker {
    nodes: usize,
    syncs_seen: u64,
    windows: u64,
    in_window: Vec<u32>,
    window_sync_ns: u64,
    complete_after: Option<u64>,
    distinct: usize,
    received: Vec<u64>,
    empty: Vec<u64>,
    extra: u64,
    completion_us: Vec<u32>,
    sync_ns: Vec<u64>,
    status: Vec<Option<u16>>,
    emcy: u64,
    bad_length: u64,
}

impl Checker {
    fn new(nodes: usize) -> Checker {
        Checker {
            nodes,
            in_window: vec![0; nodes],
            received: vec![0; nodes],
            empty: vec![0; nodes],
            status: vec![None; nodes],
            ..Checker::default()
        }
    }

    fn measuring(&self) -> bool {
        self.syncs_seen > WARMUP_SYNCS
    }

    fn close_window(&mut self) {
        if self.measuring() {
            self.windows += 1;
            for n in 0..self.nodes {
                match self.in_window[n] {
                    0 => self.empty[n] += 1,
                    c => self.extra += u64::from(c - 1),
                }
            }
            if let Some(ns) = self.complete_after {
                self.completion_us
                    .push(((ns.saturating_sub(self.window_sync_ns)) / 1000) as u32);
            }
        }
        self.in_window.iter_mut().for_each(|c| *c = 0);
        self.distinct = 0;
        self.complete_after = None;
    }

    fn frame(&mut self, f: &Frame) {
        match f.id {
            0x080 => {
                if self.syncs_seen > 0 {
                    self.close_window();
                }
                self.syncs_seen += 1;
                self.window_sync_ns = f.at_ns;
                if self.measuring() {
                    self.sync_ns.push(f.at_ns);
                }
            }
            id if (0x381..0x381 + self.nodes as u16).contains(&id) => {
                let n = usize::from(id - 0x381);
                if f.len != 6 {
                    self.bad_length += 1;
                    return;
                }
                self.status[n] = Some(u16::from_le_bytes([f.data[0], f.data[1]]));
                if self.syncs_seen == 0 {
                    return;
                }
                if self.measuring() {
                    self.received[n] += 1;
                }
                self.in_window[n] += 1;
                if self.in_window[n] == 1 {
                    self.distinct += 1;
                    if self.distinct == self.nodes {
                        self.complete_after = Some(f.at_ns);
                    }
                }
            }
            id if (0x081..0x081 + self.nodes as u16).contains(&id) => self.emcy += 1,
            _ => {}
        }
    }
}

/// One measurement against the bus of `t`: configure the nodes (when `mcemu` has them), start
/// them, SYNC for warm-up + the measured seconds, judge. `cpu`: processes whose CPU to report.
fn run(
    t: &Transport,
    settings: &Settings,
    mcemu: Option<&Mcemu>,
    cpu: &[(&str, u32)],
    vm: bool,
) -> Value {
    let nodes = settings.nodes;
    let mut tx = open(t);
    let mut idle = Vec::new();
    if mcemu.is_some() {
        // The servo tick and its idle nodes (pre-operational, no SYNC), for comparison.
        let before: Vec<f64> = cpu.iter().map(|(_, p)| cpu_seconds(*p)).collect();
        std::thread::sleep(IDLE);
        for ((name, p), b) in cpu.iter().zip(before) {
            idle.push(json!({"process": name, "percent": (cpu_seconds(*p) - b) / IDLE.as_secs_f64() * 100.0}));
        }
        configure(&mut *tx, nodes);
    }
    tx.send(&Frame::new(0x000, &[0x01, 0x00]));
    tx.discard_input();

    // Checker.
    let stop = Arc::new(AtomicBool::new(false));
    let checker = {
        let mut rx = open(t);
        // SYNC and EMCY (0x080–0x0FF), TPDO3 (0x380–0x3FF): the RPDOs would double the
        // checker's work for nothing.
        rx.only(&[(0x080, 0x780), (0x380, 0x780)]);
        let stop = Arc::clone(&stop);
        let nodes = usize::from(nodes);
        std::thread::spawn(move || {
            let mut c = Checker::new(nodes);
            while !stop.load(Ordering::Relaxed) {
                if let Some(f) = rx.recv(Duration::from_millis(100)) {
                    c.frame(&f);
                }
            }
            // Drain what is queued, then close the last window.
            while let Some(f) = rx.recv(Duration::from_millis(1)) {
                c.frame(&f);
            }
            c.close_window();
            c
        })
    };
    std::thread::sleep(Duration::from_millis(200)); // the checker is on the bus

    // Producer.
    // Bounded by time, not count: where the producer cannot keep 1 kHz (the VM), the window
    // still lasts the given seconds and the rate shows what it managed.
    let measured = Duration::from_secs_f64(settings.seconds);
    let (warm_tx, warm_rx) = mpsc::channel();
    let producer = std::thread::spawn(move || {
        let t0 = Instant::now() + Duration::from_millis(5);
        let (mut slot, mut sent, mut slips) = (0u64, 0u64, 0u64);
        let mut late_us: Vec<u32> = Vec::with_capacity(70_000);
        let mut frames = Vec::with_capacity(usize::from(nodes) + 1);
        let mut first_measured: Option<Instant> = None;
        while first_measured.is_none_or(|f| f.elapsed() < measured) {
            let deadline = t0 + PERIOD * slot as u32;
            let now = Instant::now();
            if now < deadline {
                std::thread::sleep(deadline - now);
            } else if now - deadline > PERIOD {
                let behind = ((now - t0).as_nanos() / PERIOD.as_nanos()) as u64;
                slips += behind - slot;
                slot = behind;
                continue;
            }
            if sent == WARMUP_SYNCS {
                let _ = warm_tx.send(());
                first_measured = Some(Instant::now());
            }
            late_us.push(
                Instant::now()
                    .saturating_duration_since(deadline)
                    .as_micros() as u32,
            );
            frames.clear();
            frames.push(Frame::new(0x080, &[]));
            let cw = controlword(sent).to_le_bytes();
            for n in 1..=nodes {
                frames.push(Frame::new(0x400 + n, &[cw[0], cw[1], 0, 0, 0, 0]));
            }
            tx.send_all(&frames);
            sent += 1;
            slot += 1;
        }
        let span = first_measured.map_or(Duration::ZERO, |f| f.elapsed());
        (sent, slips, span, late_us)
    });
    warm_rx
        .recv_timeout(Duration::from_secs(600))
        .expect("the producer's warm-up");
    let start = Instant::now();
    let cpu0: Vec<f64> = cpu.iter().map(|(_, p)| cpu_seconds(*p)).collect();
    let self0 = cpu_seconds(std::process::id());
    let state0 = mcemu.map(Mcemu::state);
    let (sent, slips, span, mut late_us) = producer.join().unwrap();
    let wall = start.elapsed().as_secs_f64();
    let cpu1: Vec<f64> = cpu.iter().map(|(_, p)| cpu_seconds(*p)).collect();
    let self1 = cpu_seconds(std::process::id());
    // The last window's TPDOs: a period is enough on the host; the VM gets longer.
    std::thread::sleep(if vm {
        Duration::from_millis(500)
    } else {
        Duration::from_millis(50)
    });
    let state1 = mcemu.map(Mcemu::state);
    stop.store(true, Ordering::Relaxed);
    let c = checker.join().unwrap();

    let nodes_n = u64::from(nodes);
    let windows = c.windows;
    let late_or_missing: u64 = c.empty.iter().sum();
    let missing: u64 = c.received.iter().map(|&r| windows.saturating_sub(r)).sum();
    let intervals: Vec<u32> = c
        .sync_ns
        .windows(2)
        .map(|w| ((w[1].saturating_sub(w[0])) / 1000) as u32)
        .collect();
    let rate = if c.sync_ns.len() > 1 {
        (c.sync_ns.len() - 1) as f64
            / ((c.sync_ns[c.sync_ns.len() - 1] - c.sync_ns[0]) as f64 / 1e9)
    } else {
        0.0
    };
    late_us.drain(..(WARMUP_SYNCS as usize).min(late_us.len()));
    let enabled = c
        .status
        .iter()
        .filter(|s| s.is_some_and(|s| s & 0x6F == 0x27))
        .count();
    let mut row = json!({
        "nodes": nodes,
        "seconds": settings.seconds,
        "syncs_sent": sent - WARMUP_SYNCS,
        "producer_rate": (sent - WARMUP_SYNCS) as f64 / span.as_secs_f64().max(1e-9),
        "producer_slips": slips,
        "producer_late_us": quantiles(&mut late_us),
        "syncs_seen": c.syncs_seen.saturating_sub(WARMUP_SYNCS),
        "windows": windows,
        "sync_rate": rate,
        "sync_interval_us": quantiles(&mut intervals.clone()),
        "tpdos_expected": windows * nodes_n,
        "tpdos_received": c.received.iter().sum::<u64>(),
        "late_or_missing": late_or_missing,
        "missing": missing,
        "late": late_or_missing.saturating_sub(missing),
        "extra": c.extra,
        "bad_length": c.bad_length,
        "emcy": c.emcy,
        "complete_windows": c.completion_us.len(),
        "all_tpdos_in_us": quantiles(&mut c.completion_us.clone()),
        "nodes_operation_enabled": enabled,
        "cpu": cpu.iter().zip(cpu0.iter().zip(cpu1.iter())).map(|((name, _), (a, b))| {
            json!({"process": name, "percent": (b - a) / wall * 100.0})
        }).collect::<Vec<_>>(),
        "cpu_idle": idle,
        "checker_cpu_percent": (self1 - self0) / wall * 100.0,
        "window_s": wall,
    });
    if let (Some(s0), Some(s1)) = (state0, state1) {
        row["servo"] = servo_window(&s0["runtime"], &s1["runtime"]);
        // The engine's tick from the snapshot (published every tick); the runtime statistics
        // are published once per batch of ticks, which is stale while the thread catches up.
        row["servo"]["engine_ticks"] = json!(s1["tick"]
            .as_u64()
            .unwrap_or(0)
            .saturating_sub(s0["tick"].as_u64().unwrap_or(0)));
        row["bus"] = bus_window(&s0, &s1);
    }
    row
}

/// p50, p99 and max of a sample.
fn quantiles(v: &mut [u32]) -> Value {
    if v.is_empty() {
        return json!(null);
    }
    v.sort_unstable();
    let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
    json!({"p50": at(0.5), "p99": at(0.99), "max": v[v.len() - 1]})
}

/// The servo runtime over the window: counter differences, and lateness quantiles from the
/// difference of the two histograms (upper bucket edges).
fn servo_window(a: &Value, b: &Value) -> Value {
    let d = |k: &str| {
        b[k].as_u64()
            .unwrap_or(0)
            .saturating_sub(a[k].as_u64().unwrap_or(0))
    };
    let buckets = |h: &Value| -> Vec<(Option<f64>, u64)> {
        h["buckets"]
            .as_array()
            .map(|a| {
                a.iter()
                    .map(|x| (x["le"].as_f64(), x["count"].as_u64().unwrap_or(0)))
                    .collect()
            })
            .unwrap_or_default()
    };
    let before = buckets(&a["lateness"]);
    let mut diff: Vec<(Option<f64>, u64)> = buckets(&b["lateness"])
        .into_iter()
        .map(|(le, n)| {
            let was = before.iter().find(|(l, _)| *l == le).map_or(0, |(_, c)| *c);
            (le, n.saturating_sub(was))
        })
        .filter(|(_, n)| *n > 0)
        .collect();
    diff.sort_by(|x, y| x.0.unwrap_or(f64::MAX).total_cmp(&y.0.unwrap_or(f64::MAX)));
    let total: u64 = diff.iter().map(|(_, n)| n).sum();
    let quantile = |q: f64| {
        let want = (total as f64 * q).ceil() as u64;
        let mut seen = 0;
        for (le, n) in &diff {
            seen += n;
            if seen >= want.max(1) {
                return le.map_or(json!("> 10 s"), |l| json!(l * 1e3));
            }
        }
        json!(null)
    };
    json!({
        "ticks": d("ticks_run"),
        "overruns": d("overruns"),
        "caught_up_ticks": d("caught_up_ticks"),
        "dropped_ticks": d("dropped_ticks"),
        "max_tick_ms_since_start": b["max_tick_time"].as_f64().unwrap_or(0.0) * 1e3,
        "lateness_ms": {"p50": quantile(0.5), "p99": quantile(0.99), "p999": quantile(0.999),
                        "max_since_start": b["lateness"]["max"].as_f64().unwrap_or(0.0) * 1e3},
    })
}

/// The CAN front-end over the window: the hub's drops and the nodes' own SYNC and frame counts.
fn bus_window(a: &Value, b: &Value) -> Value {
    let frontend = |s: &Value| {
        s["frontends"]
            .as_array()
            .and_then(|f| f.iter().find(|f| f["name"] == "canopen"))
            .cloned()
            .unwrap_or(Value::Null)
    };
    let (fa, fb) = (frontend(a), frontend(b));
    let d = |k: &str| {
        fb[k]
            .as_u64()
            .unwrap_or(0)
            .saturating_sub(fa[k].as_u64().unwrap_or(0))
    };
    // Sum one field of the nodes' counters.
    let sum = |f: &Value, field: &str| -> u64 {
        f["nodes"]
            .as_array()
            .map(|nodes| {
                nodes
                    .iter()
                    .filter_map(|n| n["counters"][field].as_u64())
                    .sum()
            })
            .unwrap_or(0)
    };
    json!({
        "frames": d("frames"),
        "rx_dropped": d("rx_dropped"),
        "tx_overflow": d("tx_overflow"),
        "node_syncs": sum(&fb, "sync").saturating_sub(sum(&fa, "sync")),
        "node_rpdos": sum(&fb, "rpdos").saturating_sub(sum(&fa, "rpdos")),
        "node_frames_out": sum(&fb, "frames_out").saturating_sub(sum(&fa, "frames_out")),
        "socketcan": fb["socketcan"].clone(),
    })
}

fn summary(row: &Value) -> String {
    format!(
        "{:<10} {:<9} SYNC {:.1}/s, TPDOs {}/{}: late {}, missing {}, extra {}; CPU {}",
        row["transport"].as_str().unwrap_or(""),
        row["target"].as_str().unwrap_or(""),
        row["sync_rate"].as_f64().unwrap_or(0.0),
        row["tpdos_received"],
        row["tpdos_expected"],
        row["late"],
        row["missing"],
        row["extra"],
        cpu_text(&row["cpu"])
    )
}

fn cpu_text(cpu: &Value) -> String {
    cpu.as_array()
        .map(|a| {
            a.iter()
                .map(|c| {
                    format!(
                        "{} {:.1} %",
                        c["process"].as_str().unwrap_or(""),
                        c["percent"].as_f64().unwrap_or(0.0)
                    )
                })
                .collect::<Vec<_>>()
                .join(", ")
        })
        .unwrap_or_default()
}

fn q(v: &Value) -> String {
    if v.is_null() {
        return "-".into();
    }
    format!("{}/{}/{}", v["p50"], v["p99"], v["max"])
}

fn ms(v: &Value) -> String {
    v.as_f64().map_or("-".into(), |x| format!("{x:.3}"))
}

fn print_table(rows: &[Value], settings: &Settings) {
    let line = |c: [&str; 12]| {
        println!(
            "{:<10} {:<9} {:>7} {:>6} {:>17} {:>8} {:>7} {:>7} {:>7} {:>17} {:>7} {:>13}",
            c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9], c[10], c[11]
        );
    };
    println!();
    println!(
        "{} nodes, {} s measured per row. late = a node's TPDO not in before the next SYNC (in \
         arrival order on the checker's connection); missing = never arrived; extra = a second \
         TPDO of a node in one window (a late one, usually). CPU = utime + stime over the \
         window, % of one core.",
        settings.nodes, settings.seconds
    );
    line([
        "transport",
        "target",
        "SYNC/s",
        "slips",
        "SYNC interval µs",
        "TPDOs",
        "late",
        "missing",
        "extra",
        "all TPDOs in µs",
        "op.en.",
        "CPU %",
    ]);
    line([
        "",
        "",
        "",
        "",
        "p50/p99/max",
        "expected",
        "",
        "",
        "",
        "p50/p99/max",
        "",
        "(idle)",
    ]);
    for r in rows {
        let idle = r["cpu_idle"]
            .as_array()
            .and_then(|a| a.first())
            .and_then(|c| c["percent"].as_f64())
            .map_or(String::new(), |p| format!(" ({p:.1})"));
        let cpu = r["cpu"]
            .as_array()
            .map(|a| {
                a.iter()
                    .map(|c| format!("{:.1}", c["percent"].as_f64().unwrap_or(0.0)))
                    .collect::<Vec<_>>()
                    .join("+")
            })
            .unwrap_or_default();
        line([
            r["transport"].as_str().unwrap_or(""),
            r["target"].as_str().unwrap_or(""),
            &format!("{:.1}", r["sync_rate"].as_f64().unwrap_or(0.0)),
            &r["producer_slips"].to_string(),
            &q(&r["sync_interval_us"]),
            &r["tpdos_expected"].to_string(),
            &r["late"].to_string(),
            &r["missing"].to_string(),
            &r["extra"].to_string(),
            &q(&r["all_tpdos_in_us"]),
            &format!("{}/{}", r["nodes_operation_enabled"], r["nodes"]),
            &format!("{cpu}{idle}"),
        ]);
    }
    println!(
        "(reflector = the baseline slave: this binary answering each SYNC at once; CPU \
         reflector[+the mcemu hub it reaches socketcand through]. mcemu (idle) = the same \
         machine before the nodes start, no traffic. op.en. = nodes whose last TPDO said \
         operation enabled: the RPDOs took effect. all TPDOs in = from a SYNC to the last \
         node's TPDO, windows where all came.)"
    );
    println!();
    println!(
        "servo runtime over the window (GET /api/v1/state, mcemu rows; its runtime statistics \
         are published at least every 64 ticks of a catch-up batch):"
    );
    for r in rows.iter().filter(|r| !r["servo"].is_null()) {
        let s = &r["servo"];
        let b = &r["bus"];
        let lateness = if s["lateness_ms"]["p50"].is_null() {
            "no late wake-up recorded in the window (a thread that is always behind never \
             sleeps)"
                .to_string()
        } else {
            format!(
                "wake-up lateness p50/p99/p99.9 ≤ {}/{}/{} ms",
                ms(&s["lateness_ms"]["p50"]),
                ms(&s["lateness_ms"]["p99"]),
                ms(&s["lateness_ms"]["p999"])
            )
        };
        println!(
            "  {}: engine ticks {} in {:.1} s; runtime statistics: ticks {}, overruns {}, caught \
             up {}, dropped {}; {lateness}; since start: lateness max {} ms, longest tick {} ms",
            r["transport"].as_str().unwrap_or(""),
            s["engine_ticks"],
            r["window_s"].as_f64().unwrap_or(0.0),
            s["ticks"],
            s["overruns"],
            s["caught_up_ticks"],
            s["dropped_ticks"],
            ms(&s["lateness_ms"]["max_since_start"]),
            ms(&s["max_tick_ms_since_start"]),
        );
        println!(
            "  {}: hub frames {}, rx_dropped {}, tx_overflow {}; the nodes counted {} SYNCs (sent \
             {} × {} nodes = {}), {} RPDOs, sent {} frames; SocketCAN link {}",
            r["transport"].as_str().unwrap_or(""),
            b["frames"],
            b["rx_dropped"],
            b["tx_overflow"],
            b["node_syncs"],
            r["syncs_sent"],
            r["nodes"],
            r["syncs_sent"].as_u64().unwrap_or(0) * r["nodes"].as_u64().unwrap_or(0),
            b["node_rpdos"],
            b["node_frames_out"],
            b["socketcan"],
        );
    }
    println!();
    println!("producer and checker:");
    for r in rows {
        println!(
            "  {} {}: producer {:.1} SYNC/s ({} sent, {} slots skipped, wake-up late \
             p50/p99/max {} µs); the checker saw {} SYNCs, used {:.1} % CPU; {} EMCY, {} TPDOs \
             of a wrong length",
            r["transport"].as_str().unwrap_or(""),
            r["target"].as_str().unwrap_or(""),
            r["producer_rate"].as_f64().unwrap_or(0.0),
            r["syncs_sent"],
            r["producer_slips"],
            q(&r["producer_late_us"]),
            r["syncs_seen"],
            r["checker_cpu_percent"].as_f64().unwrap_or(0.0),
            r["emcy"],
            r["bad_length"],
        );
    }
    println!(
        "(reference, anchors §27: a real 1 Mbit/s bus carries at most ≈8 800 8-byte frames/s, \
         about 3 axes at this rate; this load is {} frames/s, which only vcan or socketcand \
         carry. Aim: 0 late or missing.)",
        1000 * (1 + 2 * u64::from(settings.nodes))
    );
}
