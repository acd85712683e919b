//! CANopen SDO transfers of a 100 kB DOMAIN (block, download and upload) and of 1 kB
//! (segmented), timed with python-canopen's SDO client against mcemu, beside python-canopen's
//! `LocalNode` serving the same object in the same run and the CANopenDemo figures for
//! CANopenNode on vcan (anchors §27: 100 kB block 70/145 ms, 1 kB segmented 10/24 ms).
//!
//! ```sh
//! cargo bench -p mcemu --bench canopen_sdo
//! MCEMU_SDO_REPS=5 cargo bench -p mcemu --bench canopen_sdo
//! MCEMU_SDO_VCAN=0 cargo bench -p mcemu --bench canopen_sdo   # socketcand rows only
//! MCEMU_SDO_VM_LOCALNODE_100K=1 cargo bench -p mcemu --bench canopen_sdo
//! ```
//!
//! Two transports, each a section of the run:
//! - `socketcand`, on this host: mcemu serves its bus over socketcand only (the interface is
//!   set to none with `--set`); the clients are TCP clients of it. python-can's socketcand
//!   interface runs with `tcp_tune=True` (TCP_NODELAY, TCP_QUICKACK); one row shows its
//!   default (`tcp_tune` off). The `LocalNode` baseline reaches the same bus through mcemu's
//!   hub (node 2 beside mcemu's node 1), so it pays the same two TCP hops.
//! - `vcan (VM)`: this binary re-executed inside `tests/vcan/run` (`MCEMU_BENCH_ROLE=sdo-vcan`),
//!   with mcemu bridged to a real SocketCAN vcan0 and every client on vcan0 — a qemu TCG VM on
//!   this machine (its kernel has no CAN), where CPU-bound code runs 10–30 times slower, so
//!   these figures bound what the VM can do rather than what mcemu can.
//!
//! Servers: mcemu on `fixtures/bench/canopen-sdo.toml` (node 1, the manufacturer DOMAIN 0x2F00
//! of the shipped `cia402-drive.eds`), at its 1 ms servo period and again at 250 µs
//! (`--period 250us`, to show what the servo tick costs); `tests/python/canopen_bench_localnode.py`
//! (python-canopen 2.4 `LocalNode`, node 2): it has no block transfers (it aborts a block
//! download with 0x05040001 and answers a block upload as segmented, which python-canopen's
//! client rejects), so its 100 kB figure is segmented, run once (in the VM only with
//! `MCEMU_SDO_VM_LOCALNODE_100K=1`: it takes 4–5 minutes there).
//!
//! Clients: `tests/python/canopen_bench_sdo.py` (python-canopen's `SdoClient`: `sdo.open(...,
//! block_transfer=True)`, `download`/`upload`), and a raw Rust client (`canopen_support`: CRC
//! on, 127-segment sub-blocks written at once) that shows the servers without Python's cost.
//! Every transfer writes fresh random data and reads it back, compared. `MCEMU_SDO_REPS`
//! (default 3) repetitions of each; the table gives median [min–max].

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod canopen_support;

use std::process::Command;
use std::time::{Duration, Instant};

use canopen_support::{emit, open, run_in_vcan, spread, RawSdo, Transport, ROLE_VAR};
use mcemu_tests::{python, python_script, run_with_timeout, spawn_until_line, Mcemu};
use serde_json::{json, Value};

const VCAN_ROLE: &str = "sdo-vcan";
const INDEX: u16 = 0x2F00;
const BIG: usize = 100 * 1024;
const SMALL: usize = 1024;
const CONFIG: &str = "fixtures/bench/canopen-sdo.toml";
const LOCAL_NODE: &str = "LocalNode (python)";
/// CANopenDemo `test/test_report.md`, CANopenNode on vcan (anchors §27): (transfer, down, up).
const CANOPENDEMO: [(&str, usize, f64, f64); 2] = [
    ("block", BIG, 70.0, 145.0),
    ("segmented", SMALL, 10.0, 24.0),
];

fn main() {
    // The bench's own mcemu, never a rebuild from inside the VM.
    std::env::set_var("MCEMU_BIN", env!("CARGO_BIN_EXE_mcemu"));
    let reps = canopen_support::env_f64("MCEMU_SDO_REPS", 3.0).max(1.0) as usize;
    if std::env::var(ROLE_VAR).as_deref() == Ok(VCAN_ROLE) {
        for row in measure(true, reps) {
            emit(&row);
        }
        return;
    }
    println!(
        "canopen_sdo: {BIG} B DOMAIN by block transfer, {SMALL} B segmented; {reps} repetitions \
         each (MCEMU_SDO_REPS); each transfer writes fresh random data and reads it back"
    );
    let started = Instant::now();
    let mut rows = measure(false, reps);
    println!(
        "  socketcand section: {:.0} s",
        started.elapsed().as_secs_f64()
    );
    if std::env::var("MCEMU_SDO_VCAN").as_deref() != Ok("0") {
        let started = Instant::now();
        println!("  vcan section: this bench inside tests/vcan/run (a TCG VM here; minutes)");
        rows.extend(run_in_vcan(VCAN_ROLE, Duration::from_secs(1800)));
        println!("  vcan section: {:.0} s", started.elapsed().as_secs_f64());
    }
    print_table(&rows);
}

/// Every row of one transport: SocketCAN vcan0 in the VM (`vm`), else socketcand here.
fn measure(vm: bool, reps: usize) -> Vec<Value> {
    let config = canopen_support::workspace_path(CONFIG);
    let mut rows = Vec::new();
    let transport_of = |mcemu: &Mcemu| {
        if vm {
            Transport::SocketCan("vcan0".into())
        } else {
            Transport::Socketcand {
                addr: mcemu.address("socketcand").to_string(),
                bus: "vcan0".into(),
            }
        }
    };
    let mut args = vec!["--set", "frontends.socketcand.bind=\"127.0.0.1:0\""];
    if !vm {
        // socketcand only, even on a host whose vcan0 exists (and may carry others' frames).
        args.extend(["--set", "frontends.canopen.interface=\"\""]);
    }

    {
        let mcemu = Mcemu::start(Some(&config), &args);
        let t = transport_of(&mcemu);
        let server = "mcemu 1 ms tick";
        rows.extend(python_client(
            &t,
            1,
            server,
            reps,
            &[("block", BIG), ("segmented", SMALL)],
            true,
        ));
        if !vm {
            rows.extend(python_client(&t, 1, server, 1, &[("block", BIG)], false));
        }
        rows.extend(raw_client(&t, 1, server, reps, true));
        report_servo(server, &mcemu);
        if !vm {
            // The LocalNode baseline on the same hub: node 2 beside mcemu's node 1.
            rows.extend(local_node(&t, reps, true));
        }
    }
    {
        let mut args = args.clone();
        args.extend(["--period", "250us"]);
        let mcemu = Mcemu::start(Some(&config), &args);
        let t = transport_of(&mcemu);
        let server = "mcemu 250 µs tick";
        rows.extend(raw_client(&t, 1, server, reps, true));
        report_servo(server, &mcemu);
    }
    if vm {
        // mcemu is gone: the VM's two vCPUs are the Python processes' alone.
        let big = std::env::var("MCEMU_SDO_VM_LOCALNODE_100K").as_deref() == Ok("1");
        rows.extend(local_node(&Transport::SocketCan("vcan0".into()), reps, big));
    }
    for r in &mut rows {
        r["transport"] = json!(if vm { "vcan (VM)" } else { "socketcand" });
    }
    rows
}

/// The servo runtime's view of the run so far (a tick-served SDO server must not overrun).
fn report_servo(server: &str, mcemu: &Mcemu) {
    let r = &mcemu.state()["runtime"];
    println!(
        "  {server}: servo ticks {}, overruns {}, caught up {}, dropped {}, max tick {:.2} ms, \
         wake-up lateness p99 ≤ {:.2} ms, max {:.2} ms",
        r["ticks_run"],
        r["overruns"],
        r["caught_up_ticks"],
        r["dropped_ticks"],
        r["max_tick_time"].as_f64().unwrap_or(0.0) * 1e3,
        r["lateness"]["p99"].as_f64().unwrap_or(0.0) * 1e3,
        r["lateness"]["max"].as_f64().unwrap_or(0.0) * 1e3,
    );
}

/// python-canopen's client: `transfers` (mode, size), `reps` times each, a process per
/// transfer kind (after a failed transfer python-canopen's queue of responses can be out of
/// step, which would fail every later transfer of the same process).
fn python_client(
    t: &Transport,
    node: u8,
    server: &str,
    reps: usize,
    transfers: &[(&str, usize)],
    tcp_tune: bool,
) -> Vec<Value> {
    transfers
        .iter()
        .flat_map(|transfer| python_process(t, node, server, reps, transfer, tcp_tune))
        .collect()
}

fn python_process(
    t: &Transport,
    node: u8,
    server: &str,
    reps: usize,
    (mode, size): &(&str, usize),
    tcp_tune: bool,
) -> Vec<Value> {
    let mut command = Command::new(python());
    command.arg(python_script("canopen_bench_sdo.py"));
    bus_args(&mut command, t);
    command
        .args(["--node", &node.to_string()])
        .args(["--index", &format!("{INDEX:#x}")])
        .args(["--reps", &reps.to_string()])
        .args(["--tcp-tune", if tcp_tune { "on" } else { "off" }])
        .args(["--transfer", &format!("{mode}:{size}")]);
    let what = format!("{command:?}");
    let output = run_with_timeout(command, b"", Duration::from_secs(1500));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{what} failed ({})\n--- stdout\n{stdout}\n--- stderr\n{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    let client = if tcp_tune || matches!(t, Transport::SocketCan(_)) {
        "python-canopen"
    } else {
        "python, tcp_tune off"
    };
    stdout
        .lines()
        .map(|line| {
            let mut row: Value = serde_json::from_str(line)
                .unwrap_or_else(|e| panic!("{what}: not JSON ({e}): {line}"));
            row["server"] = json!(server);
            row["client"] = json!(client);
            println!("  {}", one_line(&row));
            row
        })
        .collect()
}

fn bus_args(command: &mut Command, t: &Transport) {
    match t {
        Transport::SocketCan(iface) => {
            command.args(["--interface", "socketcan", "--channel", iface]);
        }
        Transport::Socketcand { addr, bus } => {
            let (host, port) = addr.rsplit_once(':').unwrap();
            command.args([
                "--interface",
                "socketcand",
                "--host",
                host,
                "--port",
                port,
                "--channel",
                bus,
            ]);
        }
    }
}

/// The raw Rust client: 100 kB by block transfer (if `block`), 1 kB segmented.
fn raw_client(t: &Transport, node: u8, server: &str, reps: usize, block: bool) -> Vec<Value> {
    let mut link = open(t);
    let mut sdo = RawSdo::new(&mut *link, node, Duration::from_secs(5));
    let mut seed = 0x9E37_79B9_7F4A_7C15u64 ^ u64::from(node);
    let mut random = |n: usize| -> Vec<u8> {
        (0..n)
            .map(|_| {
                // xorshift64*: fresh data each transfer, no dependency.
                seed ^= seed >> 12;
                seed ^= seed << 25;
                seed ^= seed >> 27;
                (seed.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 56) as u8
            })
            .collect()
    };
    let mut rows = Vec::new();
    let mut kinds = vec![("segmented", SMALL)];
    if block {
        kinds.insert(0, ("block", BIG));
    }
    for (mode, size) in kinds {
        let mut down =
            json!({"mode": mode, "size": size, "direction": "down", "ms": [], "error": null});
        let mut up =
            json!({"mode": mode, "size": size, "direction": "up", "ms": [], "error": null});
        for _ in 0..reps {
            let data = random(size);
            let start = Instant::now();
            let result = if mode == "block" {
                sdo.block_download(INDEX, 0, &data)
            } else {
                sdo.segmented_download(INDEX, 0, &data)
            };
            if let Err(e) = result {
                down["error"] = json!(e.to_string());
                up["error"] = json!("not run: the download failed");
                break;
            }
            push_ms(&mut down, start.elapsed());
            let start = Instant::now();
            let result = if mode == "block" {
                sdo.block_upload(INDEX, 0)
            } else {
                sdo.segmented_upload(INDEX, 0)
            };
            match result {
                Ok(back) if back == data => push_ms(&mut up, start.elapsed()),
                Ok(back) => {
                    up["error"] = json!(format!(
                        "upload differs from the download ({} of {size} bytes)",
                        back.len()
                    ));
                    break;
                }
                Err(e) => {
                    up["error"] = json!(e.to_string());
                    break;
                }
            }
        }
        for mut row in [down, up] {
            row["server"] = json!(server);
            row["client"] = json!("raw Rust");
            println!("  {}", one_line(&row));
            rows.push(row);
        }
    }
    if sdo.retransmitted > 0 {
        println!(
            "  raw Rust client vs {server}: {} block segments repeated",
            sdo.retransmitted
        );
    }
    rows
}

fn push_ms(row: &mut Value, elapsed: Duration) {
    row["ms"]
        .as_array_mut()
        .unwrap()
        .push(json!(elapsed.as_secs_f64() * 1e3));
}

/// python-canopen's `LocalNode` (node 2) serving the same DOMAIN, timed with the same clients;
/// its 100 kB segmented transfer if `big`.
fn local_node(t: &Transport, reps: usize, big: bool) -> Vec<Value> {
    let mut command = Command::new(python());
    command.arg(python_script("canopen_bench_localnode.py"));
    bus_args(&mut command, t);
    command.args(["--node", "2", "--index", &format!("{INDEX:#x}")]);
    // Python's imports take seconds in the VM.
    let (mut server, _) = spawn_until_line(command, "ready", Duration::from_secs(120));
    let name = LOCAL_NODE;
    let mut rows = python_client(t, 2, name, reps, &[("segmented", SMALL)], true);
    // Once each: the block attempt shows the refusal; 100 kB segmented takes seconds here and
    // 4–5 minutes in the VM.
    let mut once = vec![("block", BIG)];
    if big {
        once.push(("segmented", BIG));
    }
    rows.extend(python_client(t, 2, name, 1, &once, true));
    rows.extend(raw_client(t, 2, name, reps, false));
    server.kill();
    rows
}

fn one_line(row: &Value) -> String {
    let ms: Vec<String> = row["ms"]
        .as_array()
        .map(|a| {
            a.iter()
                .map(|v| format!("{:.1}", v.as_f64().unwrap_or(0.0)))
                .collect()
        })
        .unwrap_or_default();
    format!(
        "{:<26} {:<30} {:<9} {:>6} B {:<4} ms [{}]{}",
        row["server"].as_str().unwrap_or(""),
        row["client"].as_str().unwrap_or(""),
        row["mode"].as_str().unwrap_or(""),
        row["size"],
        row["direction"].as_str().unwrap_or(""),
        ms.join(", "),
        row["error"]
            .as_str()
            .map(|e| format!(" error: {e}"))
            .unwrap_or_default()
    )
}

/// Median [min–max] of a row's times, or its error.
fn cell(row: Option<&Value>) -> (String, Option<f64>) {
    let Some(row) = row else {
        return ("-".into(), None);
    };
    let ms: Vec<f64> = row["ms"]
        .as_array()
        .map(|a| a.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default();
    // A failure after some good repetitions: the figures of those, marked "!" (the
    // failures are listed under the table).
    let mark = if row["error"].is_string() { "!" } else { "" };
    match (spread(&ms), row["error"].as_str()) {
        (Some(_), Some(e)) if e.starts_with("unverified") => ("(unverified) !".into(), None),
        (Some((med, lo, hi)), _) if ms.len() > 1 => {
            (format!("{med:.1} [{lo:.1}–{hi:.1}]{mark}"), Some(med))
        }
        (Some((med, _, _)), _) => (format!("{med:.1}{mark}"), Some(med)),
        (None, Some(e)) => {
            let e = e.trim_start_matches("SdoCommunicationError: ");
            (e.chars().take(24).collect(), None)
        }
        (None, None) => ("-".into(), None),
    }
}

type Key = (String, String, String, String, u64);

fn print_table(rows: &[Value]) {
    let key = |r: &Value| -> Key {
        (
            r["transport"].as_str().unwrap_or("").to_string(),
            r["server"].as_str().unwrap_or("").to_string(),
            r["client"].as_str().unwrap_or("").to_string(),
            r["mode"].as_str().unwrap_or("").to_string(),
            r["size"].as_u64().unwrap_or(0),
        )
    };
    let mut keys: Vec<Key> = Vec::new();
    for r in rows {
        let k = key(r);
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    let find = |k: &Key, dir: &str| rows.iter().find(|r| key(r) == *k && r["direction"] == dir);
    let ratio = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => format!("{:.2}", a / b),
        _ => "-".into(),
    };
    let line = |cols: [&str; 8]| {
        println!(
            "{:<10} {:<17} {:<20} {:<14} {:>24} {:>24} {:>11} {:>12}",
            cols[0], cols[1], cols[2], cols[3], cols[4], cols[5], cols[6], cols[7]
        );
    };
    println!();
    line([
        "transport",
        "server",
        "client",
        "transfer",
        "download ms",
        "upload ms",
        "÷ CANopen-",
        "÷ LocalNode",
    ]);
    line([
        "",
        "",
        "",
        "",
        "median [min–max]",
        "median [min–max]",
        "Demo dn/up",
        "dn/up",
    ]);
    for k in &keys {
        let (down, down_ms) = cell(find(k, "down"));
        let (up, up_ms) = cell(find(k, "up"));
        let demo = CANOPENDEMO
            .iter()
            .find(|(m, s, _, _)| *m == k.3 && *s as u64 == k.4)
            .map_or("-".to_string(), |(_, _, d, u)| {
                format!("{}/{}", ratio(down_ms, Some(*d)), ratio(up_ms, Some(*u)))
            });
        // LocalNode on the same transport, with the same kind of client (python or raw), the
        // same size; the same transfer, or segmented where LocalNode has no block transfer
        // (marked *): the fastest it serves that object.
        let base_client = if k.2 == "raw Rust" {
            "raw Rust"
        } else {
            "python-canopen"
        };
        let base = |mode: &str| -> Key {
            (
                k.0.clone(),
                LOCAL_NODE.to_string(),
                base_client.to_string(),
                mode.to_string(),
                k.4,
            )
        };
        let measured = |b: &Key| (cell(find(b, "down")).1, cell(find(b, "up")).1);
        let (mut bd, mut bu) = measured(&base(&k.3));
        let mut mark = "";
        if bd.is_none() && bu.is_none() && k.3 == "block" {
            (bd, bu) = measured(&base("segmented"));
            mark = "*";
        }
        let local = if k.1 == LOCAL_NODE || (bd.is_none() && bu.is_none()) {
            "-".to_string()
        } else {
            format!("{}/{}{mark}", ratio(down_ms, bd), ratio(up_ms, bu))
        };
        let transfer = format!("{} {} kB", k.3, k.4 as f64 / 1024.0);
        line([&k.0, &k.1, &k.2, &transfer, &down, &up, &demo, &local]);
    }
    for (mode, size, d, u) in CANOPENDEMO {
        let transfer = format!("{mode} {} kB", size as f64 / 1024.0);
        let (d, u) = (format!("{d:.1}"), format!("{u:.1}"));
        line([
            "vcan",
            "CANopenNode",
            "CANopenDemo report",
            &transfer,
            &d,
            &u,
            "",
            "",
        ]);
    }
    let failures: Vec<&Value> = rows.iter().filter(|r| r["error"].is_string()).collect();
    if !failures.is_empty() {
        println!("failures (a transfer's remaining repetitions were not run after one):");
        for r in failures {
            println!(
                "  {} {} {} {} {} B {}: {} (after {} good)",
                r["transport"].as_str().unwrap_or(""),
                r["server"].as_str().unwrap_or(""),
                r["client"].as_str().unwrap_or(""),
                r["mode"].as_str().unwrap_or(""),
                r["size"],
                r["direction"].as_str().unwrap_or(""),
                r["error"].as_str().unwrap_or(""),
                r["ms"].as_array().map_or(0, Vec::len)
                    - usize::from(
                        r["error"]
                            .as_str()
                            .is_some_and(|e| e.starts_with("unverified"))
                    ),
            );
        }
    }
    println!(
        "(aim: 100 kB block below 50 ms both ways. ÷ = ratio of medians, < 1 faster than the \
         baseline. ÷ LocalNode: same transport, size and client kind; * = against LocalNode's \
         segmented transfer of the object, as it has no block transfer. CANopenNode: CANopenDemo's \
         test report (anchors §27), not measured here.)"
    );
}
