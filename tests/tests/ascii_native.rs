//! HIMC Native ASCII end to end (issue 14): `mcemu run` on the HIMC machine
//! (`fixtures/himc.toml`, virtual clock), real TCP clients — the golden transcripts of
//! `tests/ascii/` over a plain `TcpStream`, OpenBSD `nc`, a plain Python socket client — and
//! the clients that misbehave (mid-line disconnects, 10 MB without a newline, binary garbage, a
//! client that never reads), each counted in `GET /api/v1/state` while another client goes on
//! being served.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::Duration;

use mcemu_tests::{run_pymodbus_tcp, run_transcript, wait_for, workspace_root, AsciiClient, Mcemu};
use serde_json::{json, Value};

fn himc(args: &[&str]) -> Mcemu {
    let mut all = vec!["--clock", "virtual"];
    all.extend_from_slice(args);
    Mcemu::start(Some(&workspace_root().join("fixtures/himc.toml")), &all)
}

fn transcripts() -> PathBuf {
    workspace_root().join("tests/ascii")
}

fn counters(m: &Mcemu) -> Value {
    m.frontend("ascii_native")["counters"].clone()
}

fn count(m: &Mcemu, name: &str) -> u64 {
    counters(m)[name]
        .as_u64()
        .unwrap_or_else(|| panic!("no counter {name} in {}", counters(m)))
}

/// A second client still served after `m`'s first misbehaved.
fn still_served(m: &Mcemu) {
    let mut other = AsciiClient::connect(m.address("ascii-native"));
    assert_eq!(other.call("IsSystemOper()"), "1");
    assert_eq!(other.call("GetAxisNum()"), "4");
}

/// One test per golden transcript `tests/ascii/NAME.in`, each on a fresh machine.
macro_rules! transcripts {
    ($($name:ident),* $(,)?) => {
        $(
            #[test]
            fn $name() {
                run_transcript(&himc(&[]), &transcripts(), stringify!($name));
            }
        )*
    };
}

mod transcript {
    use super::*;

    transcripts!(
        system,
        axis_motion,
        axis_parameters,
        homing_gpio_errors,
        strings_math,
        groups,
        gear_gantry,
        group_settings,
        slaves,
        tables_triggers,
        measured,
        gpio_invert_estop_config,
        filters_config,
        vectors,
        compensation_limit
    );
}

#[test]
fn nc_with_cr_lf_and_crlf_line_ends() {
    let m = himc(&[]);
    let port = m.port("ascii-native");
    // OpenBSD netcat: -N shuts the socket down at the end of its input; the server then
    // closes after the last reply.
    let mut nc = Command::new("nc")
        .args(["-N", "127.0.0.1", &port])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("nc (netcat-openbsd, scripts/setup): {e}"));
    nc.stdin
        .take()
        .unwrap()
        .write_all(b"IsSystemOper()\rGetAxisNum()\nGetECATSt()\r\nStringLen(\"abc\");\r\n")
        .unwrap();
    let out = nc.wait_with_output().unwrap();
    assert_eq!(String::from_utf8_lossy(&out.stdout), "1\r\n4\r\n8\r\n3\r\n");
    assert_eq!(count(&m, "lines"), 4);
    assert_eq!(count(&m, "calls_ok"), 4);
}

#[test]
fn a_plain_python_socket_client() {
    let m = himc(&[]);
    let script = r#"
import socket, sys
host, port = sys.argv[1].rsplit(":", 1)
s = socket.create_connection((host, int(port)), timeout=20)
f = s.makefile("rb")
for call in ["Enable(0)", "GetVel(0)", "GetAxisLastErr(2)", "NoSuch()", "sqrt(2)"]:
    s.sendall(call.encode() + b"\r\n")
    print(f.readline().decode().rstrip("\r\n"))
"#;
    let out = Command::new("python3")
        .args(["-c", script, m.address("ascii-native")])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        "0\n500\n0\n5201\n1.4142135623731\n"
    );
    assert_eq!(count(&m, "unsupported"), 1);
}

#[test]
fn two_clients_interleave_at_line_boundaries() {
    let m = himc(&[]);
    let mut a = AsciiClient::connect(m.address("ascii-native"));
    let mut b = AsciiClient::connect(m.address("ascii-native"));
    assert_eq!(a.call("Enable(0)"), "0");
    assert_eq!(b.call("Enable(1)"), "0");
    m.advance(&serde_json::json!({"seconds": 0.5}));
    // A pipelines three calls; B's call comes between them on the wire; each gets its own
    // replies, in its own order.
    a.send(b"SetVel(0, 123)\r\nGetVel(0)\r\n");
    assert_eq!(b.call("GetVel(1)"), "500");
    a.send(b"IsEnabled(0)\r\n");
    let replies: Vec<String> = (0..3).map(|_| a.read_reply()).collect();
    assert_eq!(replies, ["0\r\n", "123\r\n", "1\r\n"]);
    assert_eq!(b.call("IsEnabled(1)"), "1");
    // An error latched by one client is the controller's: the other reads it.
    assert_eq!(a.call("NoSuch()"), "5201");
    assert_eq!(b.call("GetSystemLastErr()"), "5201");
    assert_eq!(count(&m, "connections_open"), 2);
}

#[test]
fn a_client_that_leaves_in_the_middle_of_a_line() {
    let m = himc(&[]);
    {
        let mut gone = TcpStream::connect(m.address("ascii-native")).unwrap();
        gone.write_all(b"GetAxisNum()\r\nMoveAbs(0, 1").unwrap();
        let mut reply = [0u8; 3];
        gone.read_exact(&mut reply).unwrap();
        assert_eq!(&reply, b"4\r\n");
    }
    wait_for("the partial line counted", Duration::from_secs(10), || {
        (count(&m, "partial_lines") == 1).then_some(())
    });
    still_served(&m);
    // The half line was never called: axis 0 has no command.
    assert_eq!(m.axis(0)["state"], "disabled");
}

#[test]
fn ten_megabytes_without_a_newline_is_one_too_long_line() {
    let m = himc(&[]);
    let mut c = AsciiClient::connect(m.address("ascii-native"));
    let chunk = vec![b'x'; 1 << 20];
    for _ in 0..10 {
        c.send(&chunk);
    }
    c.send(b"\n");
    assert_eq!(c.read_reply(), "5005\r\n", "eERR_HMPL_STR_TOO_LONG");
    assert_eq!(c.call("GetSystemLastErr()"), "5005");
    assert_eq!(c.call("GetECATSt()"), "8");
    assert_eq!(count(&m, "too_long"), 1);
    assert!(count(&m, "bytes_in") > 10 << 20);
    still_served(&m);
}

#[test]
fn binary_garbage_is_syntax_errors_and_the_connection_goes_on() {
    let m = himc(&[]);
    let mut c = AsciiClient::connect(m.address("ascii-native"));
    // Three lines of bytes that are no call (NUL, 0xff, control characters), then a call.
    c.send(b"\x00\x01\x02\xff\xfe\n\x1b[2J\x7f(\r\n\xc3\x28)\n");
    for _ in 0..3 {
        assert_eq!(c.read_reply(), "5006\r\n");
    }
    assert_eq!(c.call("IsSystemOper()"), "1");
    assert_eq!(count(&m, "syntax_errors"), 3);
    still_served(&m);
}

#[test]
fn a_client_that_never_reads_is_closed_and_the_others_are_served() {
    let m = himc(&["--set", "frontends.ascii_native.write_timeout_ms=300"]);
    let address = m.address("ascii-native").to_string();
    // Calls whose replies are long, sent without ever reading, from a socket with a small
    // receive buffer: the server's writes block, time out, and it closes the connection.
    let script = r#"
import socket, sys
host, port = sys.argv[1].rsplit(":", 1)
s = socket.socket()
s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
s.connect((host, int(port)))
s.settimeout(20)
call = b"exp(0.5)\n" * 4096
try:
    while True:
        s.sendall(call)
except OSError as e:
    print("closed", type(e).__name__)
"#;
    let out = Command::new("python3")
        .args(["-c", script, &address])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        String::from_utf8_lossy(&out.stdout).starts_with("closed"),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert_eq!(count(&m, "write_timeouts"), 1);
    still_served(&m);
}

#[test]
fn move_home_can_wait_for_the_end_of_homing() {
    let m = himc(&["--set", "frontends.ascii_native.move_home_waits=true"]);
    let mut c = AsciiClient::connect(m.address("ascii-native"));
    assert_eq!(c.call("SetHomeMethod(1, HOME_METHOD_37)"), "0");
    assert_eq!(c.call("Enable(1)"), "0");
    m.advance(&serde_json::json!({"seconds": 0.5}));
    c.send(b"MoveHome(1)\r\n");
    // No reply before homing has run: virtual time runs in steps until the reply comes.
    let reply = (0..100).find_map(|_| {
        m.advance(&serde_json::json!({"seconds": 0.1}));
        c.try_read_reply(Duration::from_millis(100))
    });
    assert_eq!(reply.as_deref(), Some("0\r\n"));
    assert_eq!(m.axis(1)["state"], "standstill");
    assert_eq!(c.call("IsHomed(1)"), "1");
}

#[test]
fn pipelined_replies_ready_before_a_waiting_call_are_not_held_back() {
    // The replies to the lines of one read go out together, but only up to a line that waits:
    // the two getters before `MoveHome` (which waits for homing here) are answered while it
    // still waits, and the getter after it only once it has answered.
    let m = himc(&["--set", "frontends.ascii_native.move_home_waits=true"]);
    let mut c = AsciiClient::connect(m.address("ascii-native"));
    assert_eq!(c.call("SetHomeMethod(1, HOME_METHOD_37)"), "0");
    assert_eq!(c.call("Enable(1)"), "0");
    m.advance(&serde_json::json!({"seconds": 0.5}));
    c.send(b"GetAxisNum()\r\nIsHoming(1)\r\nMoveHome(1)\r\nIsHomed(1)\r\n");
    // No time passes meanwhile (virtual clock): homing cannot have ended.
    let ready = Duration::from_secs(10);
    assert_eq!(c.try_read_reply(ready).as_deref(), Some("4\r\n"));
    assert_eq!(c.try_read_reply(ready).as_deref(), Some("0\r\n"));
    let reply = (0..100).find_map(|_| {
        m.advance(&serde_json::json!({"seconds": 0.1}));
        c.try_read_reply(Duration::from_millis(100))
    });
    assert_eq!(reply.as_deref(), Some("0\r\n"), "MoveHome");
    assert_eq!(c.read_reply(), "1\r\n", "IsHomed after homing");
}

/// TV 63's fault seen by a Modbus HMI (pymodbus): set up through Native ASCII, axis 0's
/// `last_err` (HR 58–59) and the controller's `latest_error` (HR 8210–8211, both u32 low word
/// first) read eERR_AXIS_COMP_LIMIT 0x83000802 while the fault is latched.
#[test]
fn a_compensation_limit_fault_shows_in_the_modbus_last_error_view() {
    let m = himc(&[]);
    let mut c = AsciiClient::connect(m.address("ascii-native"));
    for line in [
        "SetTableValue(1, 0)",
        "SetTableValue(2, 1.5)",
        "SetupComp(0, 1, 0, 100, 2, 1)",
        "Enable(0)",
        "Enable(1)",
    ] {
        assert_eq!(c.call(line), "0", "{line}");
    }
    m.advance(&json!({"seconds": 0.5}));
    assert_eq!(c.call("MoveAbs(0, 10)"), "0");
    assert_eq!(c.call("MoveAbs(1, 100)"), "0");
    m.advance(&json!({"seconds": 1}));
    assert_eq!(c.call("Disable(0)"), "0");
    // The EtherCAT drive follows the disable over a few cycles.
    m.advance(&json!({"seconds": 0.1}));
    for line in ["SetConfigVar(0x8300007a, 2)", "EnableComp(0)", "Enable(0)"] {
        assert_eq!(c.call(line), "0", "{line}");
    }
    m.advance(&json!({"seconds": 0.5}));
    assert_eq!(c.call("SetConfigVar(0x8300007a, 1)"), "0");
    m.advance(&json!({"seconds": 0.5}));
    assert_eq!(c.call("IsErrorStop(0)"), "1");
    let port = m.port("modbus-tcp");
    let r = run_pymodbus_tcp(
        &port,
        &json!([
            {"op": "read_holding_registers", "address": 58, "count": 2},
            {"op": "read_holding_registers", "address": 8210, "count": 2},
        ]),
    );
    let code = |v: &Value| {
        let words: Vec<u64> = v["ok"]
            .as_array()
            .unwrap_or_else(|| panic!("{v}"))
            .iter()
            .map(|w| w.as_u64().unwrap())
            .collect();
        words[1] << 16 | words[0]
    };
    assert_eq!(code(&r[0]), 0x8300_0802, "{r}");
    assert_eq!(code(&r[1]), 0x8300_0802, "{r}");
}
