//! Self-test of the external-client harness (`mcemu-tests`, `tests/python/`, `scripts/setup`),
//! **not of mcemu**: the peers here are the plain pymodbus server of
//! `tests/python/modbus_server_pymodbus.py`, `mbpoll` and the Python client driver. These tests
//! prove that the tools install, start, talk to each other over TCP, RTU over TCP and a socat
//! pty pair, and that the driver reports values, Modbus exceptions and errors faithfully, so
//! that a failure in an mcemu test that uses them points at mcemu.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;
use std::time::{Duration, Instant};

use mcemu_tests::{
    require_tool, run_pymodbus_tcp, run_python_client, run_with_timeout, PtyPair, PymodbusServer,
};
use serde_json::{json, Value};

const TOOL_TIMEOUT: Duration = Duration::from_secs(20);

/// Run mbpoll once (`-1`) with `args`; returns (success, stdout, stderr).
fn mbpoll(args: &[&str]) -> (bool, String, String) {
    let mut command = Command::new(require_tool("mbpoll"));
    command.args(args);
    let out = run_with_timeout(command, b"", TOOL_TIMEOUT);
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The `[ref]: value` lines of mbpoll's output (a register above 32767 is followed by its
/// signed reading in parentheses: `[501]: 65534 (-2)`).
fn mbpoll_values(stdout: &str) -> Vec<(u32, i64)> {
    stdout
        .lines()
        .filter_map(|l| {
            let (r, v) = l.trim().strip_prefix('[')?.split_once("]:")?;
            Some((r.parse().ok()?, v.split_whitespace().next()?.parse().ok()?))
        })
        .collect()
}

fn ok(v: Value) -> Value {
    json!({ "ok": v })
}

/// The operations every client/transport combination runs: writes, read-backs, an
/// out-of-range address (exception 02), the float word orders, and the functions beyond the
/// basic reads and writes.
fn exercise(args: &[&str]) {
    let ops = json!([
        {"op": "write_registers", "address": 10, "values": [1, 2, 3, 65535]},
        {"op": "read_holding_registers", "address": 10, "count": 5},
        {"op": "write_register", "address": 9999, "value": 42},
        {"op": "read_holding_registers", "address": 9999, "count": 1},
        {"op": "read_holding_registers", "address": 9999, "count": 2},
        {"op": "write_register", "address": 10000, "value": 1},
        {"op": "write_coils", "address": 3, "values": [true, false, true]},
        {"op": "write_coil", "address": 0, "value": true},
        {"op": "read_coils", "address": 0, "count": 7},
        {"op": "read_coils", "address": 9999, "count": 2},
        {"op": "read_discrete_inputs", "address": 0, "count": 3},
        {"op": "read_input_registers", "address": 0, "count": 2},
        {"op": "mask_write_register", "address": 11, "and_mask": 0x00F2, "or_mask": 0x0025},
        {"op": "read_holding_registers", "address": 11, "count": 1},
        {"op": "readwrite_registers", "read_address": 10, "read_count": 4,
         "write_address": 12, "values": [7, 8]},
        {"op": "write_float", "address": 100, "value": 1.5, "word_order": "little"},
        {"op": "write_float", "address": 102, "value": 1.5, "word_order": "big"},
        {"op": "read_holding_registers", "address": 100, "count": 4},
        {"op": "read_float", "address": 100, "word_order": "little"},
        {"op": "read_float", "address": 102, "word_order": "big"},
        {"op": "report_server_id"},
        {"op": "read_device_information", "read_code": 1, "object_id": 0},
        {"op": "diag_echo", "data": "a55a"},
    ]);
    let r = run_python_client(args, &ops);
    let expect = [
        ok(Value::Null),
        ok(json!([1, 2, 3, 65535, 0])),
        ok(Value::Null),
        ok(json!([42])),
        json!({"exception": 2}),
        json!({"exception": 2}),
        ok(Value::Null),
        ok(Value::Null),
        ok(json!([true, false, false, true, false, true, false])),
        json!({"exception": 2}),
        ok(json!([false, false, false])),
        ok(json!([0, 0])),
        ok(Value::Null),
        // (2 & 0xF2) | (0x25 & !0xF2) = 2 | 5
        ok(json!([7])),
        // FC 23 writes before it reads.
        ok(json!([1, 7, 7, 8])),
        ok(Value::Null),
        ok(Value::Null),
        // 1.5f32 = 0x3FC0_0000: low word first, then high word first.
        ok(json!([0, 0x3FC0, 0x3FC0, 0])),
        ok(json!(1.5)),
        ok(json!(1.5)),
    ];
    for (i, e) in expect.iter().enumerate() {
        assert_eq!(&r[i], e, "{args:?}: operation {i}: {}", ops[i]);
    }
    let id = &r[20]["ok"];
    assert_eq!(id["running"], json!(true), "{args:?}: {id}");
    assert!(!id["id"].as_str().unwrap().is_empty(), "{args:?}: {id}");
    let info = &r[21]["ok"]["objects"];
    assert_eq!(
        info,
        &json!({"0": "pymodbus-baseline", "1": "PM", "2": "3.16.1"}),
        "{args:?}"
    );
    assert_eq!(r[22], ok(json!("a55a")), "{args:?}");
}

/// pymodbus (the driver) and mbpoll against the pymodbus TCP server: each reads back what it
/// and the other wrote, and both see exception 02 beyond the server's 10 000 registers.
#[test]
fn tcp_driver_and_mbpoll_against_the_pymodbus_server() {
    let server = PymodbusServer::tcp();
    let port = server.port().to_string();
    exercise(&[
        "--client",
        "pymodbus",
        "--transport",
        "tcp",
        "--port",
        &port,
    ]);

    let tcp = ["-m", "tcp", "-p", &port, "-a", "1", "-0", "-1", "-o", "2"];
    let with = |extra: &[&'static str]| -> Vec<&str> {
        tcp.iter().copied().chain(extra.iter().copied()).collect()
    };
    // mbpoll writes 3 registers at 500, reads them and the register the driver wrote.
    let (written, out, err) = mbpoll(&with(&["-r", "500", "127.0.0.1", "123", "65534", "7"]));
    assert!(written, "mbpoll write failed\n{out}\n{err}");
    let (read, out, err) = mbpoll(&with(&["-r", "500", "-c", "3", "127.0.0.1"]));
    assert!(read, "mbpoll read failed\n{out}\n{err}");
    assert_eq!(
        mbpoll_values(&out),
        [(500, 123), (501, 65534), (502, 7)],
        "{out}"
    );
    let (read, out, err) = mbpoll(&with(&["-r", "9999", "127.0.0.1"]));
    assert!(read, "mbpoll read failed\n{out}\n{err}");
    assert_eq!(mbpoll_values(&out), [(9999, 42)], "{out}");
    // The driver reads what mbpoll wrote.
    let r = run_pymodbus_tcp(
        &port,
        &json!([{"op": "read_holding_registers", "address": 500, "count": 3}]),
    );
    assert_eq!(r[0], ok(json!([123, 65534, 7])));
    // Out of range: mbpoll fails and names the exception.
    let (read, out, err) = mbpoll(&with(&["-r", "10000", "127.0.0.1"]));
    assert!(!read, "mbpoll read beyond the map succeeded\n{out}");
    assert!(err.contains("Illegal data address"), "{out}\n{err}");
}

/// pymodbus with its RTU framer over TCP against the server's RTU-over-TCP mode; and a
/// request for a socket-framed server through the RTU framer gets no valid answer: an error
/// result, not an exception and not a hang.
#[test]
fn rtu_over_tcp_driver_against_the_pymodbus_server() {
    let server = PymodbusServer::rtu_over_tcp();
    let port = server.port().to_string();
    exercise(&[
        "--client",
        "pymodbus",
        "--transport",
        "rtu-over-tcp",
        "--port",
        &port,
    ]);

    let socket = PymodbusServer::tcp();
    let port = socket.port().to_string();
    let r = run_python_client(
        [
            "--client",
            "pymodbus",
            "--transport",
            "rtu-over-tcp",
            "--port",
            &port,
            "--timeout",
            "0.5",
        ],
        &json!([{"op": "read_holding_registers", "address": 0, "count": 2}]),
    );
    assert!(r[0]["error"].is_string(), "{r}");
}

/// RTU on a socat pty pair: the pymodbus server on one end; minimalmodbus, pymodbus's serial
/// client and mbpoll on the other, one after the other (the pair outlives each client's
/// close).
#[test]
fn rtu_clients_over_a_pty_pair() {
    let pair = PtyPair::new();
    assert_ne!(pair.a, pair.b);
    assert!(
        pair.a.starts_with("/dev/pts") && pair.b.starts_with("/dev/pts"),
        "{pair:?}"
    );
    let _server = PymodbusServer::rtu(&pair.a);
    let device = pair.b.to_str().unwrap();
    for client in ["minimalmodbus", "pymodbus"] {
        let started = Instant::now();
        exercise(&[
            "--client",
            client,
            "--transport",
            "rtu",
            "--device",
            device,
            "--baud",
            "19200",
            // minimalmodbus waits this long after each exception answer (3 here).
            "--timeout",
            "1.0",
        ]);
        eprintln!("{client} over the pty pair: {:?}", started.elapsed());
    }
    let rtu = [
        "-m", "rtu", "-b", "19200", "-P", "none", "-a", "1", "-0", "-1", "-o", "1",
    ];
    let (read, out, err) = mbpoll(&[&rtu[..], &["-r", "10", "-c", "2", device]].concat());
    assert!(read, "mbpoll RTU read failed\n{out}\n{err}");
    assert_eq!(mbpoll_values(&out), [(10, 1), (11, 7)], "{out}");
    let (read, out, err) = mbpoll(&[&rtu[..], &["-r", "10000", device]].concat());
    assert!(
        !read && err.contains("Illegal data address"),
        "{out}\n{err}"
    );
}

/// Without a server the driver exits non-zero and the helper fails with its stderr.
#[test]
#[should_panic(expected = "could not connect")]
fn the_client_helper_fails_loudly_without_a_server() {
    // A port that was free a moment ago: bind, read the port, close.
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
        .to_string();
    run_python_client(
        [
            "--client",
            "pymodbus",
            "--transport",
            "tcp",
            "--port",
            &port,
        ],
        &json!([{"op": "read_coils", "address": 0, "count": 1}]),
    );
}

#[test]
#[should_panic(expected = "run scripts/setup")]
fn a_missing_tool_is_a_loud_failure() {
    require_tool("mcemu-no-such-tool");
}

/// A process that outlives its bound is killed, and the helper says so.
#[test]
fn run_with_timeout_kills_a_process_that_does_not_finish() {
    let started = Instant::now();
    let result = std::panic::catch_unwind(|| {
        let mut command = Command::new("sleep");
        command.arg("30");
        run_with_timeout(command, b"", Duration::from_millis(300))
    });
    let message = *result.unwrap_err().downcast::<String>().unwrap();
    assert!(message.contains("was killed"), "{message}");
    assert!(started.elapsed() < Duration::from_secs(10));
}

/// Dropping the pair ends socat.
#[test]
fn dropping_a_pty_pair_ends_socat() {
    let pair = PtyPair::new();
    let proc_dir = std::path::PathBuf::from(format!("/proc/{}", pair.pid()));
    assert!(proc_dir.exists());
    drop(pair);
    // Reaped by the drop: no zombie, no process.
    assert!(!proc_dir.exists());
}

/// A server that exits without its ready line fails the helper, which shows what it printed.
#[test]
fn spawn_until_line_reports_a_process_that_exits_first() {
    let result = std::panic::catch_unwind(|| {
        let mut command = Command::new("sh");
        command.args(["-c", "echo starting; echo oops >&2; exit 3"]);
        mcemu_tests::spawn_until_line(command, "ready ", Duration::from_secs(20))
    });
    let message = *result.unwrap_err().downcast::<String>().unwrap();
    assert!(
        message.contains("exited before printing `ready …`"),
        "{message}"
    );
    assert!(
        message.contains("starting") && message.contains("oops"),
        "{message}"
    );
}
