//! An HMI's flow on each shipped map, through Modbus only (pymodbus), on the virtual clock:
//! enable an axis, set a target, start, let virtual time run until the axis is at rest, poll the
//! in-position status and read the position; every step checked against the engine through
//! `GET /state` (state, flags, `act_pos`). Time is advanced through the control API with an
//! `until` condition, never slept.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use mcemu_tests::{run_python_client, workspace_root, Mcemu};
use serde_json::{json, Value};

// ---- word orders ---------------------------------------------------------------------------

fn words_of(bytes: &[u8]) -> Vec<u16> {
    bytes
        .chunks(2)
        .map(|c| u16::from_be_bytes([c[0], c[1]]))
        .collect()
}

fn bytes_of(words: &[u16]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_be_bytes()).collect()
}

/// High word first (`abcd`).
fn f64_abcd(v: f64) -> Vec<u16> {
    words_of(&v.to_be_bytes())
}

/// Low word first (`cdab`, HIMC): the words of `abcd` reversed.
fn f64_cdab(v: f64) -> Vec<u16> {
    let mut w = f64_abcd(v);
    w.reverse();
    w
}

fn regs(result: &Value) -> Vec<u16> {
    result["ok"]
        .as_array()
        .unwrap_or_else(|| panic!("not registers: {result}"))
        .iter()
        .map(|v| v.as_u64().unwrap() as u16)
        .collect()
}

fn abcd_f64(words: &[u16]) -> f64 {
    f64::from_be_bytes(bytes_of(words).try_into().unwrap())
}

fn cdab_f64(words: &[u16]) -> f64 {
    let mut w = words.to_vec();
    w.reverse();
    abcd_f64(&w)
}

fn flags(axis: &Value) -> Vec<String> {
    axis["flags"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap().to_string())
        .collect()
}

fn has(axis: &Value, flag: &str) -> bool {
    flags(axis).iter().any(|f| f == flag)
}

/// Run virtual time until `axis` is at rest (standstill), at most `seconds`; it must get there.
fn until_standstill(m: &Mcemu, axis: usize, seconds: f64) {
    let r = m.advance(&json!({
        "seconds": seconds,
        "until": {"axis": axis, "state": "standstill"}
    }));
    assert_eq!(
        r["met"], true,
        "axis {axis} not at rest after {seconds} s: {r}"
    );
}

/// The pymodbus session's results, each of which must be `ok`.
fn pymodbus(args: &[&str], ops: Value) -> Vec<Value> {
    let r = run_python_client(args, &ops);
    let r = r.as_array().unwrap().clone();
    for (i, v) in r.iter().enumerate() {
        assert!(v.get("ok").is_some(), "operation {i} {}: {v}", ops[i]);
    }
    r
}

fn tcp_args(port: &str) -> Vec<&str> {
    vec!["--client", "pymodbus", "--transport", "tcp", "--port", port]
}

#[test]
fn generic_map_enable_target_start_in_position() {
    let m = Mcemu::start(None, &["--clock", "virtual"]);
    let port = m.port("modbus-tcp");
    let args = tcp_args(&port);
    let axis = 1; // the second block: base + 1 × stride
    let (coil, hr, ir, di) = (
        16 * axis as u16,
        32 * axis as u16,
        32 * axis as u16,
        16 * axis as u16,
    );

    // Enable (coil 0 of the block).
    pymodbus(
        &args,
        json!([{"op": "write_coil", "address": coil, "value": true}]),
    );
    assert_eq!(m.axis(axis)["state"], "standstill");
    // Target 25 mm at 50 mm/s, then a rising edge on the start coil.
    pymodbus(
        &args,
        json!([
            {"op": "write_registers", "address": hr, "values": f64_abcd(25.0)},
            {"op": "write_registers", "address": hr + 4, "values": f64_abcd(50.0)},
            {"op": "write_coil", "address": coil + 1, "value": true},
            {"op": "read_discrete_inputs", "address": di, "count": 3},
        ]),
    );
    let moving = m.axis(axis);
    assert_eq!(moving["state"], "discrete_motion", "{moving}");
    assert_eq!(moving["target_pos"], 25.0, "{moving}");
    until_standstill(&m, axis, 5.0);

    let r = pymodbus(
        &args,
        json!([
            {"op": "read_discrete_inputs", "address": di, "count": 3},
            {"op": "read_input_registers", "address": ir, "count": 8},
            {"op": "read_input_registers", "address": ir + 16, "count": 1},
        ]),
    );
    let state = m.axis(axis);
    assert_eq!(state["state"], "standstill");
    assert!(has(&state, "in_position"), "{state}");
    // enabled, not moving, in position
    assert_eq!(r[0]["ok"], json!([true, false, true]));
    let words = regs(&r[1]);
    let act = abcd_f64(&words[0..4]);
    let cmd = abcd_f64(&words[4..8]);
    assert_eq!(act, state["act_pos"].as_f64().unwrap(), "{state}");
    assert_eq!(cmd, state["cmd_pos"].as_f64().unwrap(), "{state}");
    assert!((act - 25.0).abs() < 1e-3, "act_pos {act}");
    assert_eq!(regs(&r[2]), [1], "state code: standstill");
    // The other axes did not move.
    assert_eq!(m.axis(0)["act_pos"], 0.0);
}

#[test]
fn himc_map_enable_target_start_in_position() {
    let m = Mcemu::start(
        Some(&workspace_root().join("fixtures/himc.toml")),
        &["--clock", "virtual"],
    );
    let port = m.port("modbus-tcp");
    let args = tcp_args(&port);
    let axis = 0; // HR 30 = axis 0 enable (digest 004 §1.9)
    let base = 100 * axis as u16;

    pymodbus(
        &args,
        json!([{"op": "write_register", "address": base + 30, "value": 1}]),
    );
    // The EtherCAT drive follows the enable over a few cycles.
    until_standstill(&m, axis, 2.0);
    assert!(has(&m.axis(axis), "enabled"));
    pymodbus(
        &args,
        json!([
            {"op": "write_registers", "address": base + 40, "values": f64_cdab(12.5)},
            {"op": "write_register", "address": base + 48, "value": 1},
        ]),
    );
    assert_eq!(m.axis(axis)["state"], "discrete_motion");
    until_standstill(&m, axis, 10.0);

    let r = pymodbus(
        &args,
        json!([
            {"op": "read_holding_registers", "address": base, "count": 8},
            {"op": "read_holding_registers", "address": base + 30, "count": 1},
            {"op": "read_holding_registers", "address": base + 50, "count": 4},
            {"op": "read_holding_registers", "address": 8208, "count": 1},
        ]),
    );
    let state = m.axis(axis);
    assert!(has(&state, "in_position"), "{state}");
    let words = regs(&r[0]);
    // Motion status, low word first: bit 0 enabled, bit 1 moving, bit 2 in position.
    let status = u32::from(words[1]) << 16 | u32::from(words[0]);
    assert_eq!(status & 0b111, 0b101, "motion status {status:#x}");
    let pos = cdab_f64(&words[4..8]);
    assert_eq!(pos, state["act_pos"].as_f64().unwrap(), "{state}");
    assert!((pos - 12.5).abs() < 1e-3, "pos_fb {pos}");
    assert_eq!(regs(&r[1]), [1], "enable reads bit 0 = enabled");
    assert_eq!(
        cdab_f64(&regs(&r[2])),
        state["cmd_pos"].as_f64().unwrap(),
        "{state}"
    );
    assert_eq!(regs(&r[3]), [2], "controller status: synchronous (ready)");
}

#[test]
fn hollysys_map_enable_target_start_in_position() {
    let m = Mcemu::start(
        Some(&workspace_root().join("fixtures/hollysys-mc.toml")),
        &["--clock", "virtual"],
    );
    let port = m.port("modbus-tcp");
    let args = tcp_args(&port);
    let axis = 2;
    let base = 200 * axis as u16; // block stride 200

    pymodbus(
        &args,
        json!([{"op": "write_register", "address": base + 199, "value": 1}]),
    );
    until_standstill(&m, axis, 2.0);
    assert!(has(&m.axis(axis), "enabled"));
    let r = pymodbus(
        &args,
        json!([
            // Speed 100 mm/s, then HMC_MoveAbs to argument 1 = 40 mm.
            {"op": "write_registers", "address": base + 42, "values": f64_abcd(100.0)},
            {"op": "read_holding_registers", "address": base + 42, "count": 4},
            {"op": "write_registers", "address": base + 190, "values": f64_abcd(40.0)},
            {"op": "write_register", "address": base + 198, "value": 14},
            {"op": "read_holding_registers", "address": base + 6, "count": 1},
        ]),
    );
    assert_eq!(abcd_f64(&regs(&r[1])), 100.0, "Speed reads back");
    assert_eq!(regs(&r[4]), [14], "MCmdType: HMC_MoveAbs running");
    assert_eq!(m.axis(axis)["state"], "discrete_motion");
    until_standstill(&m, axis, 10.0);

    let r = pymodbus(
        &args,
        json!([
            {"op": "read_holding_registers", "address": base + 8, "count": 2},
            {"op": "read_holding_registers", "address": base + 13, "count": 8},
            {"op": "read_holding_registers", "address": base + 199, "count": 1},
        ]),
    );
    let state = m.axis(axis);
    assert!(has(&state, "in_position"), "{state}");
    let words = regs(&r[1]);
    let mpos = abcd_f64(&words[0..4]);
    let dpos = abcd_f64(&words[4..8]);
    assert_eq!(mpos, state["act_pos"].as_f64().unwrap(), "MPos: {state}");
    assert_eq!(dpos, state["cmd_pos"].as_f64().unwrap(), "DPos: {state}");
    assert!((mpos - 40.0).abs() < 1e-3, "MPos {mpos}");
    assert_eq!(regs(&r[2]), [1], "drive enable reads 1");
    let status = regs(&r[0]);
    assert_eq!(status.len(), 2, "AxisStatus u32");
}

#[test]
fn ct_e10_servo_map_enable_position_and_internal_speed_over_rtu() {
    let m = Mcemu::start(
        Some(&workspace_root().join("fixtures/cpu226h.toml")),
        &["--clock", "virtual"],
    );
    let device = m.address("modbus-rtu").to_string();
    // The drive at slave address 2 on the fixture's pty (no parity on a pty: see
    // modbus_rtu_clients.rs).
    let args = [
        "--client",
        "pymodbus",
        "--transport",
        "rtu",
        "--device",
        &device,
        "--parity",
        "N",
        "--unit",
        "2",
    ];
    let axis = 4; // e10_rtu

    // P282 bit 0: servo enable (40283).
    pymodbus(
        &args,
        json!([{"op": "write_register", "address": 282, "value": 1}]),
    );
    until_standstill(&m, axis, 2.0);
    // P290 = 20 000 counts (i32, high word first), then a rising bit 1 of P282: positioning.
    pymodbus(
        &args,
        json!([
            {"op": "write_registers", "address": 290, "values": [0, 20000]},
            {"op": "write_register", "address": 282, "value": 3},
        ]),
    );
    assert_eq!(m.axis(axis)["state"], "discrete_motion");
    until_standstill(&m, axis, 5.0);
    // The drive's own loop lags the setpoint (first order, 5 ms): 20 time constants more.
    m.advance(&json!({"seconds": 0.1}));
    let r = pymodbus(
        &args,
        json!([
            {"op": "read_holding_registers", "address": 204, "count": 1},
            {"op": "read_holding_registers", "address": 216, "count": 2},
        ]),
    );
    let state = m.axis(axis);
    let r204 = regs(&r[0])[0];
    assert_eq!(
        r204 & 0b111,
        u16::from(has(&state, "enabled"))
            | u16::from(has(&state, "in_position")) << 1
            | u16::from(has(&state, "moving")) << 2,
        "R204 {r204:#b}: {state}"
    );
    assert_eq!(r204 & 0b111, 0b011, "ready, in position, still: {state}");
    let words = regs(&r[1]);
    let r216 = (u32::from(words[0]) << 16 | u32::from(words[1])) as i32;
    let act = state["act_pos"].as_f64().unwrap();
    assert_eq!(f64::from(r216), act.round(), "R216: {state}");
    assert!((act - 20000.0).abs() <= 1.0, "{state}");

    // Speed control over communication (the purpose of §10.1): P95 = 300 rpm, P281 = 1.
    pymodbus(
        &args,
        json!([
            {"op": "write_register", "address": 95, "value": 300},
            {"op": "write_register", "address": 281, "value": 1},
        ]),
    );
    m.advance(&json!({"seconds": 1.0}));
    let r = pymodbus(
        &args,
        json!([{"op": "read_holding_registers", "address": 221, "count": 1}]),
    );
    let state = m.axis(axis);
    assert_eq!(state["state"], "continuous_motion", "{state}");
    // 300 rpm = 50 000 counts/s at 10 000 counts per revolution.
    let vel = state["act_vel"].as_f64().unwrap();
    assert!((vel - 50_000.0).abs() < 50.0, "{state}");
    assert_eq!(
        regs(&r[0]),
        [(vel * 0.006).round() as u16],
        "R221 rpm: {state}"
    );
    assert_eq!(regs(&r[0]), [300]);
    // P281 = 0: stop.
    pymodbus(
        &args,
        json!([{"op": "write_register", "address": 281, "value": 0}]),
    );
    until_standstill(&m, axis, 2.0);
    m.advance(&json!({"seconds": 0.1}));
    let r = pymodbus(
        &args,
        json!([{"op": "read_holding_registers", "address": 221, "count": 1}]),
    );
    let state = m.axis(axis);
    assert_eq!(state["cmd_vel"], 0.0, "{state}");
    assert!(state["act_vel"].as_f64().unwrap().abs() < 1.0, "{state}");
    assert_eq!(regs(&r[0]), [0], "R221 rpm at rest: {state}");
}
