//! Fault injection end to end: faults installed through the control API (`POST /faults`) on the
//! running binary, each observed by a real client (pymodbus; raw frames where the exact bytes
//! matter), each counted in `GET /state`'s `frontends[…]` (`faults_applied`, exceptions, no
//! response), listed in `active_faults` while in force and gone when spent or cleared; and an
//! engine refusal (04) recorded as `last_error` with the engine's reason.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;
use std::time::{Duration, Instant};

use mcemu_tests::{rtu_frame, run_python_client, to_hex, ByteLink, MbapClient, Mcemu, RawSerial};
use serde_json::{json, Value};

fn start() -> Mcemu {
    Mcemu::start(None, &["--clock", "virtual"])
}

fn tcp_client<'a>(port: &'a str, timeout: &'a str) -> Vec<&'a str> {
    vec![
        "--client",
        "pymodbus",
        "--transport",
        "tcp",
        "--port",
        port,
        "--timeout",
        timeout,
    ]
}

fn applied(m: &Mcemu, frontend: &str, kind: &str) -> u64 {
    m.frontend(frontend)["counters"]["faults_applied"][kind]
        .as_u64()
        .unwrap()
}

#[test]
fn tcp_forced_exception_at_an_address_and_function_then_spent() {
    let m = start();
    let port = m.port("modbus-tcp");
    // Exception 06 (server busy) for FC 3 requests covering HR 3000, twice.
    let active = m.fault(&json!({
        "frontend": "modbus_tcp", "fault": "exception",
        "code": 6, "function": 3, "address": 3000, "count": 2
    }));
    assert_eq!(
        active,
        json!([{"fault": "exception", "code": 6, "function": 3, "address": 3000, "count": 2}])
    );
    assert_eq!(m.frontend("modbus_tcp")["active_faults"], active);
    let r = run_python_client(
        tcp_client(&port, "2"),
        &json!([
            {"op": "write_registers", "address": 2998, "values": [1, 2, 3, 4]},
            {"op": "read_holding_registers", "address": 2999, "count": 3},
            {"op": "read_holding_registers", "address": 3001, "count": 2},
            {"op": "read_holding_registers", "address": 3000, "count": 1},
            {"op": "read_holding_registers", "address": 3000, "count": 1},
        ]),
    );
    // HR 2998–2999 are outside the map (02 first: the fault needs FC 3); FC 16 is not faulted.
    assert_eq!(r[0], json!({"exception": 2}));
    assert_eq!(r[1], json!({"exception": 6}), "covers 3000");
    assert_eq!(r[2], json!({"ok": [0, 0]}), "does not cover 3000");
    assert_eq!(r[3], json!({"exception": 6}));
    assert_eq!(r[4], json!({"ok": [0]}), "the fault is spent");
    let f = m.frontend("modbus_tcp");
    assert_eq!(f["active_faults"], json!([]), "{f}");
    assert_eq!(f["counters"]["faults_applied"]["exception"], 2, "{f}");
    assert_eq!(f["counters"]["exceptions_by_code"]["6"], 2, "{f}");
    assert_eq!(f["counters"]["diagnostics"]["server_busy_count"], 2, "{f}");

    // Until cleared: every FC 6, whatever the address, gets 04; clearing ends it.
    m.fault(&json!({"frontend": "modbus_tcp", "fault": "exception", "code": 4, "function": 6}));
    let r = run_python_client(
        tcp_client(&port, "2"),
        &json!([
            {"op": "write_register", "address": 3000, "value": 7},
            {"op": "write_register", "address": 3500, "value": 7},
            {"op": "write_registers", "address": 3000, "values": [8]},
        ]),
    );
    assert_eq!(r[0], json!({"exception": 4}));
    assert_eq!(r[1], json!({"exception": 4}));
    assert_eq!(r[2], json!({"ok": null}));
    assert_eq!(
        m.fault(&json!({"frontend": "modbus_tcp", "fault": "clear", "kind": "exception"})),
        json!([])
    );
    let r = run_python_client(
        tcp_client(&port, "2"),
        &json!([
            {"op": "write_register", "address": 3500, "value": 9},
            {"op": "read_holding_registers", "address": 3000, "count": 1},
            {"op": "read_holding_registers", "address": 3500, "count": 1},
        ]),
    );
    assert_eq!(r[0], json!({"ok": null}));
    assert_eq!(r[1], json!({"ok": [8]}), "the faulted FC 6 wrote nothing");
    assert_eq!(r[2], json!({"ok": [9]}));
    assert_eq!(applied(&m, "modbus_tcp", "exception"), 4);
    // A forced 04 is no engine refusal: last_error stays empty.
    assert_eq!(m.frontend("modbus_tcp")["last_error"], Value::Null);
}

#[test]
fn tcp_delay_and_no_reply() {
    let m = start();
    let port = m.port("modbus-tcp");
    let mut raw = MbapClient::connect(m.address("modbus-tcp"));
    let read = [3, 0x0B, 0xB8, 0, 1]; // HR 3000, 1 register

    // delay: the next reply waits 400 ms, the one after does not.
    m.fault(&json!({"frontend": "modbus_tcp", "fault": "delay", "ms": 400, "count": 1}));
    let t = Instant::now();
    assert_eq!(raw.request(1, &read), [3, 2, 0, 0]);
    let delayed = t.elapsed();
    let t = Instant::now();
    assert_eq!(raw.request(1, &read), [3, 2, 0, 0]);
    let prompt = t.elapsed();
    assert!(delayed >= Duration::from_millis(400), "{delayed:?}");
    assert!(prompt < Duration::from_millis(300), "{prompt:?}");
    // A real client with a shorter timeout than the delay gets no answer in time.
    m.fault(&json!({"frontend": "modbus_tcp", "fault": "delay", "ms": 1500, "count": 1}));
    let r = run_python_client(
        tcp_client(&port, "0.5"),
        &json!([{"op": "read_holding_registers", "address": 3000, "count": 1}]),
    );
    assert!(r[0]["error"].is_string(), "{r}");
    assert_eq!(applied(&m, "modbus_tcp", "delay"), 2);

    // no_reply: the request is swallowed (not executed), the next one is answered.
    m.fault(&json!({"frontend": "modbus_tcp", "fault": "no_reply", "count": 1}));
    let r = run_python_client(
        tcp_client(&port, "0.5"),
        &json!([
            {"op": "write_register", "address": 3000, "value": 42},
            {"op": "read_holding_registers", "address": 3000, "count": 1},
        ]),
    );
    assert!(r[0]["error"].is_string(), "{r}");
    assert_eq!(
        r[1],
        json!({"ok": [0]}),
        "the swallowed write was not executed"
    );
    let f = m.frontend("modbus_tcp");
    assert_eq!(f["counters"]["faults_applied"]["no_reply"], 1, "{f}");
    assert_eq!(f["counters"]["no_response"], 1, "{f}");
    assert_eq!(
        f["counters"]["diagnostics"]["server_no_response_count"], 1,
        "{f}"
    );
    assert_eq!(f["active_faults"], json!([]), "{f}");

    // RTU-only faults are refused on Modbus TCP, naming the field; so is a bad code.
    for bad in [
        json!({"frontend": "modbus_tcp", "fault": "drop_bytes", "bytes": 2}),
        json!({"frontend": "modbus_tcp", "fault": "corrupt", "bit": 1}),
        json!({"frontend": "modbus_tcp", "fault": "exception", "code": 9}),
        json!({"frontend": "modbus_tcp", "fault": "delay"}),
    ] {
        let (status, body) = m.post("/faults", &bad);
        assert_eq!(status, 400, "{bad}: {body}");
        assert!(body["field"].is_string(), "{bad}: {body}");
    }
    let (status, body) = m.post(
        "/faults",
        &json!({"frontend": "modbus_x", "fault": "clear"}),
    );
    assert_eq!(
        (status, body["error"].as_str()),
        (400, Some("no_such_frontend")),
        "{body}"
    );
}

#[test]
fn rtu_drop_bytes_and_corrupt_on_the_pty() {
    let m = start();
    let device = m.address("modbus-rtu").to_string();
    let request = rtu_frame(1, &[3, 0x0B, 0xB8, 0, 2]); // HR 3000, 2 registers
    let answer = rtu_frame(1, &[3, 4, 0, 0, 0, 0]);
    let quiet = Duration::from_millis(200);
    {
        let mut line = RawSerial::open(Path::new(&device));
        line.exchange(&request, &answer, quiet);

        // drop_bytes: the last 2 bytes (the CRC) are not sent.
        m.fault(&json!({"frontend": "modbus_rtu", "fault": "drop_bytes", "bytes": 2, "count": 1}));
        line.send(&request);
        let got = line.drain(quiet);
        assert_eq!(to_hex(&got), to_hex(&answer[..answer.len() - 2]));
        line.exchange(&request, &answer, quiet);

        // corrupt: bit 0 of the last PDU byte flipped, the CRC left as it was.
        m.fault(&json!({"frontend": "modbus_rtu", "fault": "corrupt", "count": 1}));
        line.send(&request);
        let got = line.drain(quiet);
        let mut corrupted = answer.clone();
        let last_pdu = corrupted.len() - 3;
        corrupted[last_pdu] ^= 1;
        assert_eq!(to_hex(&got), to_hex(&corrupted));
        line.exchange(&request, &answer, quiet);
        // Another bit of another byte, by index (the function code).
        m.fault(
            &json!({"frontend": "modbus_rtu", "fault": "corrupt", "byte": 1, "bit": 7, "count": 1}),
        );
        line.send(&request);
        let got = line.drain(quiet);
        let mut corrupted = answer.clone();
        corrupted[1] ^= 0x80;
        assert_eq!(to_hex(&got), to_hex(&corrupted));
    }
    // Real clients see an error, then an answer.
    let args = [
        "--client",
        "pymodbus",
        "--transport",
        "rtu",
        "--device",
        &device,
        "--parity",
        "N",
        "--timeout",
        "0.5",
    ];
    m.fault(&json!({"frontend": "modbus_rtu", "fault": "corrupt", "count": 1}));
    let r = run_python_client(
        args,
        &json!([
            {"op": "read_holding_registers", "address": 3000, "count": 2},
            {"op": "read_holding_registers", "address": 3000, "count": 2},
        ]),
    );
    assert!(r[0]["error"].is_string(), "corrupted reply accepted: {r}");
    assert_eq!(r[1], json!({"ok": [0, 0]}));
    m.fault(&json!({"frontend": "modbus_rtu", "fault": "drop_bytes", "bytes": 3, "count": 1}));
    let mut mm = args.to_vec();
    mm[1] = "minimalmodbus";
    let r = run_python_client(
        &mm,
        &json!([
            {"op": "read_holding_registers", "address": 3000, "count": 2},
            {"op": "read_holding_registers", "address": 3000, "count": 2},
        ]),
    );
    assert!(r[0]["error"].is_string(), "truncated reply accepted: {r}");
    assert_eq!(r[1], json!({"ok": [0, 0]}));

    let f = m.frontend("modbus_rtu");
    assert_eq!(f["counters"]["faults_applied"]["drop_bytes"], 2, "{f}");
    assert_eq!(f["counters"]["faults_applied"]["corrupt"], 3, "{f}");
    assert_eq!(f["active_faults"], json!([]), "{f}");
    assert_eq!(
        f["counters"]["crc_errors"], 0,
        "mcemu's own input was clean: {f}"
    );
}

#[test]
fn an_engine_refusal_is_the_last_error_with_the_engines_reason() {
    let m = start();
    let port = m.port("modbus-tcp");
    assert_eq!(m.frontend("modbus_tcp")["last_error"], Value::Null);
    // Command register of axis 2 (block 2 × 32 + 8): move absolute, axis disabled.
    let r = run_python_client(
        tcp_client(&port, "2"),
        &json!([
            {"op": "write_register", "address": 2 * 32 + 8, "value": 1},
            {"op": "read_holding_registers", "address": 4000, "count": 1},
        ]),
    );
    assert_eq!(r[0], json!({"exception": 4}));
    assert_eq!(r[1], json!({"exception": 2}));
    let f = m.frontend("modbus_tcp");
    let last = &f["last_error"];
    assert_eq!(last["exception"], 4, "{last}");
    assert_eq!(last["function"], 6, "{last}");
    assert_eq!(last["unit"], 1, "{last}");
    assert_eq!(
        last["reason"], "`command@axis2`: axis 2 is disabled",
        "{last}"
    );
    assert!(
        last["peer"].as_str().unwrap().starts_with("127.0.0.1:"),
        "{last}"
    );
    assert!(
        last["time_unix_ms"].as_u64().unwrap() > 1_600_000_000_000,
        "{last}"
    );
    assert_eq!(f["counters"]["exceptions_by_code"]["4"], 1, "{f}");
    // The exception 02 after it did not replace it: only refusals are recorded.
    assert_eq!(f["counters"]["exceptions_by_code"]["2"], 1, "{f}");
    // The engine agrees: the axis is still disabled and remembers why.
    let axis = m.axis(2);
    assert_eq!(axis["state"], "disabled");
    assert_eq!(axis["last_error"], "axis_disabled");
}

/// A Modbus front-end's entry in `GET /state`, whole: its keys and shape are the control API's
/// contract (one request served, a fault in force, no refusal yet).
#[test]
fn the_state_of_a_modbus_frontend_is_pinned() {
    let m = start();
    let mut client = MbapClient::connect(m.address("modbus-tcp"));
    assert_eq!(client.request(1, &[3, 0x0B, 0xB8, 0, 1])[..2], [3, 2]);
    m.fault(&json!({"frontend": "modbus_tcp", "fault": "delay", "ms": 5, "count": 2}));
    let zeros = |keys: &[&str]| -> Value {
        Value::Object(keys.iter().map(|k| (k.to_string(), json!(0))).collect())
    };
    let expected = json!({
        "name": "modbus_tcp",
        "framing": "tcp",
        "listen_only": false,
        "counters": {
            "requests": 1,
            "requests_by_function": {"3": 1},
            "replies": 1,
            "exceptions": 0,
            "exceptions_by_code": {},
            "no_response": 0,
            "broadcasts": 0,
            "other_unit_ignored": 0,
            "crc_errors": 0,
            "malformed_frames": zeros(&["too_short", "too_long", "not_modbus_protocol", "bad_length"]),
            "connections": {
                "open": 1,
                "opened": 1,
                "closed": 0,
                "refused_at_limit": 0,
                "evicted_idle": 0,
                "idle_timeouts": 0,
                "frame_timeouts": 0
            },
            // MBAP header 7 + PDU 5 in; 7 + 4 out.
            "bytes_in": 12,
            "bytes_out": 11,
            "faults_applied": zeros(&["delay", "no_reply", "exception", "drop_bytes", "corrupt", "close"]),
            "diagnostics": {
                "bus_message_count": 1,
                "bus_communication_error_count": 0,
                "server_exception_error_count": 0,
                "server_message_count": 1,
                "server_no_response_count": 0,
                "server_nak_count": 0,
                "server_busy_count": 0,
                "bus_character_overrun_count": 0
            }
        },
        "active_faults": [{"fault": "delay", "ms": 5, "count": 2}],
        "last_error": null
    });
    assert_eq!(m.frontend("modbus_tcp"), expected);
}

/// `close` through the control API: the request's connection is closed unanswered, counted; a
/// new connection is served.
#[test]
fn tcp_close_fault_closes_the_connection() {
    let m = start();
    let active = m.fault(&json!({"frontend": "modbus_tcp", "fault": "close", "count": 1}));
    assert_eq!(active, json!([{"fault": "close", "count": 1}]));
    let mut client = MbapClient::connect(m.address("modbus-tcp"));
    client.send_raw(&mcemu_tests::mbap_frame(1, 1, &[3, 0x0B, 0xB8, 0, 1]));
    assert!(client.closed_within(Duration::from_secs(5)));
    assert_eq!(applied(&m, "modbus_tcp", "close"), 1);
    assert_eq!(m.frontend("modbus_tcp")["active_faults"], json!([]));
    let mut again = MbapClient::connect(m.address("modbus-tcp"));
    assert_eq!(again.request(1, &[3, 0x0B, 0xB8, 0, 1])[..2], [3, 2]);
}
