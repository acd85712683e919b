//! pymodbus and minimalmodbus against `mcemu run`'s RTU front-ends on the default machine (map
//! `generic`, unit 1), virtual clock: (a) on the pty mcemu creates, (b) on a device that is one
//! end of a socat pty pair, the clients on the other end, and (c) RTU over TCP (pymodbus's RTU
//! framer; minimalmodbus speaks serial lines only). Each client writes and reads every table,
//! uses FC 8, 17, 22, 23 and 43/14, gets one exception 02, and its writes are checked against
//! the engine through `GET /state`.
//!
//! The clients open ptys with no parity: Linux's pty driver drops `PARENB` (so a pty has no
//! parity to get wrong), and this kernel answers pyserial's request for even parity on a pty
//! with EINVAL. mcemu's own line is configured 8E1 as the default machine says.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use mcemu_tests::{run_python_client, Mcemu, PtyPair};
use serde_json::{json, Value};

/// One client's session; `n` makes its values its own (the front-end's memory outlives it).
fn exercise(m: &Mcemu, args: &[&str], n: u16) {
    let base = 3000 + 10 * n;
    let ops = json!([
        {"op": "write_registers", "address": base, "values": [n, 0xFFFF - n, 0x00F0]},
        {"op": "read_holding_registers", "address": base, "count": 3},
        {"op": "mask_write_register", "address": base + 2, "and_mask": 0x00F2, "or_mask": 0x0025},
        {"op": "readwrite_registers", "read_address": base, "read_count": 4,
         "write_address": base + 3, "values": [n + 100]},
        {"op": "write_coil", "address": 0, "value": true},
        {"op": "read_discrete_inputs", "address": 0, "count": 3},
        {"op": "write_coils", "address": 1000 + n, "values": [true, true]},
        {"op": "read_coils", "address": 1000 + n, "count": 2},
        {"op": "write_float", "address": 1000 + 2 * n, "value": 0.5 + f64::from(n), "word_order": "big"},
        {"op": "read_float", "address": 1000 + 2 * n, "word_order": "big"},
        {"op": "read_input_registers", "address": 16, "count": 1},
        {"op": "report_server_id"},
        {"op": "read_device_information", "read_code": 1, "object_id": 0},
        {"op": "diag_echo", "data": "a55a"},
        {"op": "read_holding_registers", "address": 4000, "count": 1},
    ]);
    let r = run_python_client(args, &ops);
    let ok = |v: Value| json!({ "ok": v });
    let expect = [
        ok(Value::Null),
        ok(json!([n, 0xFFFF - n, 0x00F0])),
        ok(Value::Null),
        // (0xF0 & 0xF2) | (0x25 & !0xF2) = 0xF0 | 0x05; FC 23 writes before it reads.
        ok(json!([n, 0xFFFF - n, 0xF5, n + 100])),
        ok(Value::Null),
        // enabled, not moving, in position
        ok(json!([true, false, true])),
        ok(Value::Null),
        ok(json!([true, true])),
        ok(Value::Null),
        ok(json!(0.5 + f64::from(n))),
        ok(json!([1])), // standstill
        ok(json!({"id": "4d", "running": true})),
        ok(
            json!({"conformity": 0x82, "more_follows": false, "next_object_id": 0,
                  "objects": {"0": "mcemu", "1": "MCEMU-GENERIC", "2": "1.0"}}),
        ),
        ok(json!("a55a")),
        json!({"exception": 2}),
    ];
    for (i, e) in expect.iter().enumerate() {
        assert_eq!(&r[i], e, "{args:?}: operation {i}: {}", ops[i]);
    }
    // The engine saw the writes.
    let state = m.state();
    assert_eq!(state["axes"][0]["state"], "standstill", "{args:?}");
    let n = usize::from(n);
    assert_eq!(state["io"]["do"][n], true, "{args:?}");
    assert_eq!(state["io"]["do"][n + 1], true, "{args:?}");
    assert_eq!(state["io"]["ao"][n], 0.5 + n as f64, "{args:?}");
    // Disabled again for the next client.
    let r = run_python_client(
        args,
        &json!([{"op": "write_coil", "address": 0, "value": false}]),
    );
    assert_eq!(r[0], json!({"ok": null}), "{args:?}");
    assert_eq!(m.axis(0)["state"], "disabled", "{args:?}");
}

fn serial_args<'a>(client: &'a str, device: &'a str) -> Vec<&'a str> {
    vec![
        "--client",
        client,
        "--transport",
        "rtu",
        "--device",
        device,
        "--baud",
        "19200",
        "--parity",
        "N",
        // minimalmodbus waits this long after its one exception answer.
        "--timeout",
        "1.0",
    ]
}

/// The requests the front-end counted: every operation of every session, nothing dropped.
fn assert_counted(m: &Mcemu, frontend: &str, sessions: u64) {
    let f = m.frontend(frontend);
    let c = &f["counters"];
    // 15 operations (FC 23 and 22 are one request each) + the disable, per session.
    assert_eq!(c["requests"], 16 * sessions, "{frontend}: {c}");
    assert_eq!(c["replies"], 16 * sessions, "{frontend}: {c}");
    assert_eq!(c["exceptions_by_code"]["2"], sessions, "{frontend}: {c}");
    assert_eq!(c["crc_errors"], 0, "{frontend}: {c}");
    for fc in [
        "1", "2", "3", "4", "5", "8", "15", "16", "17", "22", "23", "43",
    ] {
        assert!(
            c["requests_by_function"][fc].as_u64().unwrap_or(0) >= sessions,
            "{frontend}: FC {fc}: {c}"
        );
    }
}

#[test]
fn pymodbus_and_minimalmodbus_on_the_pty_mcemu_creates() {
    let m = Mcemu::start(None, &["--clock", "virtual"]);
    let device = m.address("modbus-rtu").to_string();
    assert!(device.starts_with("/dev/pts/"), "{device}");
    exercise(&m, &serial_args("pymodbus", &device), 1);
    exercise(&m, &serial_args("minimalmodbus", &device), 2);
    assert_counted(&m, "modbus_rtu", 2);
}

#[test]
fn pymodbus_and_minimalmodbus_on_a_socat_pty_pair() {
    let pair = PtyPair::new();
    let a = pair.a.to_str().unwrap();
    let b = pair.b.to_str().unwrap();
    let m = Mcemu::start(
        None,
        &[
            "--clock",
            "virtual",
            "--set",
            &format!("frontends.modbus_rtu.device=\"{a}\""),
        ],
    );
    assert_eq!(m.address("modbus-rtu"), a);
    exercise(&m, &serial_args("pymodbus", b), 3);
    exercise(&m, &serial_args("minimalmodbus", b), 4);
    assert_counted(&m, "modbus_rtu", 2);
}

#[test]
fn pymodbus_over_rtu_over_tcp() {
    let m = Mcemu::start(None, &["--clock", "virtual"]);
    let port = m.port("modbus-rtu-over-tcp");
    exercise(
        &m,
        &[
            "--client",
            "pymodbus",
            "--transport",
            "rtu-over-tcp",
            "--port",
            &port,
        ],
        5,
    );
    assert_counted(&m, "modbus_rtu_over_tcp", 1);
}
