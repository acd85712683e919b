//! `mbpoll` (libmodbus) and pymodbus against `mcemu run`'s Modbus TCP front-end on the default
//! machine (map `generic`), virtual clock: every table read and written by both clients, 32-bit
//! floats and 64-bit values decoded by the clients, the user table written by one client and
//! read back by the other, and each value checked against the engine through `GET /state`.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use mcemu_tests::{mbpoll, mbpoll_values, run_python_client, Mcemu};
use serde_json::{json, Value};

/// mbpoll's common arguments for TCP at `port`, PDU addressing, one poll, 2 s timeout.
fn tcp<'a>(port: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec!["-m", "tcp", "-p", port, "-a", "1", "-0", "-1", "-o", "2"];
    args.extend_from_slice(extra);
    args
}

/// mbpoll that must succeed; its `[ref]: value` lines.
fn mbpoll_ok(args: &[&str]) -> Vec<(u32, String)> {
    let (ok, out, err) = mbpoll(args);
    assert!(ok, "mbpoll {args:?} failed\n{out}\n{err}");
    mbpoll_values(&out)
}

fn values(pairs: &[(u32, &str)]) -> Vec<(u32, String)> {
    pairs.iter().map(|(r, v)| (*r, v.to_string())).collect()
}

fn pymodbus(port: &str, ops: Value) -> Value {
    run_python_client(
        ["--client", "pymodbus", "--transport", "tcp", "--port", port],
        &ops,
    )
}

fn f64_words(v: f64) -> Vec<u16> {
    let b = v.to_be_bytes();
    b.chunks(2)
        .map(|c| u16::from_be_bytes([c[0], c[1]]))
        .collect()
}

fn words_f64(words: &Value) -> f64 {
    let w: Vec<u16> = words
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as u16)
        .collect();
    let bytes: Vec<u8> = w.iter().flat_map(|x| x.to_be_bytes()).collect();
    f64::from_be_bytes(bytes.try_into().unwrap())
}

#[test]
fn mbpoll_and_pymodbus_read_and_write_every_table_of_the_default_machine() {
    let m = Mcemu::start(None, &["--clock", "virtual"]);
    let port = m.port("modbus-tcp");
    let port = port.as_str();

    // ---- coils: axis 0 enable (coil 0) through mbpoll, seen by the engine and both clients.
    assert_eq!(m.axis(0)["state"], "disabled");
    mbpoll_ok(&tcp(port, &["-t", "0", "-r", "0", "127.0.0.1", "1"]));
    assert_eq!(m.axis(0)["state"], "standstill", "enable through coil 0");
    assert_eq!(
        mbpoll_ok(&tcp(port, &["-t", "0", "-r", "0", "-c", "3", "127.0.0.1"])),
        values(&[(0, "1"), (1, "0"), (2, "0")])
    );
    // Digital outputs at coil 1000 + N: written by pymodbus (FC 15) and mbpoll (FC 5).
    let r = pymodbus(
        port,
        json!([
            {"op": "write_coils", "address": 1000, "values": [true, false, true]},
            {"op": "read_coils", "address": 0, "count": 1},
            {"op": "read_coils", "address": 1000, "count": 4},
        ]),
    );
    assert_eq!(r[0], json!({"ok": null}));
    assert_eq!(r[1], json!({"ok": [true]}));
    assert_eq!(r[2], json!({"ok": [true, false, true, false]}));
    mbpoll_ok(&tcp(port, &["-t", "0", "-r", "1063", "127.0.0.1", "1"]));
    let io = &m.state()["io"];
    assert_eq!(io["do"][0], true);
    assert_eq!(io["do"][1], false);
    assert_eq!(io["do"][2], true);
    assert_eq!(io["do"][63], true);

    // ---- discrete inputs: axis status bits and machine inputs forced through the API.
    m.post_ok("/inputs", &json!({"di": 5, "value": true}));
    m.post_ok("/inputs", &json!({"ai": 2, "value": 1.25}));
    m.advance(&json!({"ticks": 1})); // inputs are sampled by the tick
    assert_eq!(
        mbpoll_ok(&tcp(port, &["-t", "1", "-r", "0", "-c", "8", "127.0.0.1"])),
        values(&[
            (0, "1"), // enabled
            (1, "0"), // moving
            (2, "1"), // in position
            (3, "0"), // homed
            (4, "0"),
            (5, "0"),
            (6, "0"),
            (7, "0"),
        ])
    );
    assert_eq!(
        mbpoll_ok(&tcp(
            port,
            &["-t", "1", "-r", "1004", "-c", "3", "127.0.0.1"]
        )),
        values(&[(1004, "0"), (1005, "1"), (1006, "0")])
    );
    let r = pymodbus(
        port,
        json!([
            {"op": "read_discrete_inputs", "address": 1005, "count": 1},
            {"op": "read_discrete_inputs", "address": 16, "count": 3},
        ]),
    );
    assert_eq!(r[0], json!({"ok": [true]}));
    assert_eq!(
        r[1],
        json!({"ok": [false, false, false]}),
        "axis 1: disabled"
    );

    // ---- input registers: f32 analog input, u32 tick, f64 positions, state code.
    assert_eq!(
        mbpoll_ok(&tcp(
            port,
            &["-t", "3:float", "-B", "-r", "1004", "127.0.0.1"]
        )),
        values(&[(1004, "1.25")])
    );
    let tick = m.state()["tick"].as_u64().unwrap();
    assert_eq!(
        mbpoll_ok(&tcp(
            port,
            &["-t", "3:int", "-B", "-r", "2000", "127.0.0.1"]
        )),
        values(&[(2000, &tick.to_string())])
    );
    let r = pymodbus(
        port,
        json!([
            {"op": "read_float", "address": 1004, "function": 4, "word_order": "big"},
            {"op": "read_input_registers", "address": 16, "count": 2},
            {"op": "read_input_registers", "address": 2000, "count": 2},
        ]),
    );
    assert_eq!(r[0], json!({"ok": 1.25}));
    assert_eq!(r[1], json!({"ok": [1, 0]}), "state standstill, no error");
    assert_eq!(r[2], json!({"ok": [(tick >> 16) as u16, tick as u16]}));

    // ---- holding registers: f32 analog output through mbpoll, f64 parameter through pymodbus.
    mbpoll_ok(&tcp(
        port,
        &["-t", "4:float", "-B", "-r", "1002", "127.0.0.1", "2.5"],
    ));
    assert_eq!(m.state()["io"]["ao"][1], 2.5);
    assert_eq!(
        mbpoll_ok(&tcp(
            port,
            &["-t", "4:float", "-B", "-r", "1002", "127.0.0.1"]
        )),
        values(&[(1002, "2.5")])
    );
    let r = pymodbus(
        port,
        json!([
            {"op": "read_float", "address": 1002, "word_order": "big"},
            {"op": "read_holding_registers", "address": 10, "count": 4},
            {"op": "write_registers", "address": 32 + 10, "values": f64_words(42.5)},
            {"op": "read_holding_registers", "address": 32 + 10, "count": 4},
        ]),
    );
    assert_eq!(r[0], json!({"ok": 2.5}));
    assert_eq!(words_f64(&r[1]["ok"]), 100.0, "axis 0 speed, mm/s");
    assert_eq!(r[2], json!({"ok": null}));
    assert_eq!(words_f64(&r[3]["ok"]), 42.5, "axis 1 speed written");

    // ---- the user table: written by one client, read back by the other.
    mbpoll_ok(&tcp(
        port,
        &[
            "-t",
            "4",
            "-r",
            "3000",
            "127.0.0.1",
            "11",
            "65535",
            "0",
            "12345",
        ],
    ));
    let r = pymodbus(
        port,
        json!([
            {"op": "read_holding_registers", "address": 3000, "count": 5},
            {"op": "write_registers", "address": 3996, "values": [1, 2, 3, 4]},
            {"op": "write_register", "address": 3500, "value": 777},
            {"op": "write_float", "address": 3100, "value": -3.5, "word_order": "big"},
            {"op": "read_float", "address": 3100, "word_order": "big"},
        ]),
    );
    assert_eq!(r[0], json!({"ok": [11, 65535, 0, 12345, 0]}));
    assert_eq!(r[1], json!({"ok": null}));
    assert_eq!(r[2], json!({"ok": null}));
    assert_eq!(r[4], json!({"ok": -3.5}));
    assert_eq!(
        mbpoll_ok(&tcp(
            port,
            &["-t", "4", "-r", "3996", "-c", "4", "127.0.0.1"]
        )),
        values(&[(3996, "1"), (3997, "2"), (3998, "3"), (3999, "4")])
    );
    assert_eq!(
        mbpoll_ok(&tcp(port, &["-t", "4", "-r", "3500", "127.0.0.1"])),
        values(&[(3500, "777")])
    );
    assert_eq!(
        mbpoll_ok(&tcp(
            port,
            &["-t", "4:float", "-B", "-r", "3100", "127.0.0.1"]
        )),
        values(&[(3100, "-3.5")])
    );

    // ---- beyond the user table: both clients see exception 02.
    let (ok, out, err) = mbpoll(&tcp(
        port,
        &["-t", "4", "-r", "3999", "-c", "2", "127.0.0.1"],
    ));
    assert!(
        !ok,
        "read across the end of the user table succeeded\n{out}"
    );
    assert!(err.contains("Illegal data address"), "{out}\n{err}");
    let r = pymodbus(
        port,
        json!([{"op": "write_register", "address": 4000, "value": 1}]),
    );
    assert_eq!(r[0], json!({"exception": 2}));

    // Every request above was counted by the front-end.
    let counters = &m.frontend("modbus_tcp")["counters"];
    assert!(counters["requests"].as_u64().unwrap() >= 20, "{counters}");
    assert_eq!(counters["exceptions_by_code"]["2"], 2, "{counters}");
}
