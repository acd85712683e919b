//! The CT E10 servo of the CPU 226H's CANopen example (digest 003 §6, manual §10.2) as mcemu
//! serves it: node 2 of `fixtures/cpu226h.toml`, objects from `fixtures/canopen/ct-e10.eds`,
//! parameter semantics from the Modbus map `ct-e10-servo` — driven by python-canopen (a real
//! master) over mcemu's socketcand server, on a virtual clock.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;
use std::time::Duration;

use mcemu_tests::{python, python_script, run_with_timeout, workspace_root};
use mcemu_tests::{Mcemu, RawFrame, Socketcand};
use serde_json::{json, Value};

const AXIS: usize = 5; // e10_can
const NODE: u8 = 2;

/// One python-canopen session: the ops' results (see tests/python/canopen_e10.py).
fn session(m: &Mcemu, ops: &Value) -> Vec<Value> {
    session_at(&m.port("socketcand"), ops)
}

fn session_at(port: &str, ops: &Value) -> Vec<Value> {
    session_with(port, None, ops)
}

/// A session that may also advance the virtual clock (`advance` ops) through `control`.
fn session_with(port: &str, control: Option<&str>, ops: &Value) -> Vec<Value> {
    let mut command = Command::new(python());
    command
        .arg(python_script("canopen_e10.py"))
        .args(["--host", "127.0.0.1", "--port", port])
        .args(["--channel", "vcan0", "--node", &NODE.to_string()])
        .arg("--eds")
        .arg(workspace_root().join("fixtures/canopen/ct-e10.eds"));
    if let Some(control) = control {
        command.args(["--control", control]);
    }
    let what = format!("{command:?}");
    let out = run_with_timeout(command, ops.to_string().as_bytes(), Duration::from_secs(60));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "{what} failed\n--- stdout\n{stdout}\n--- stderr\n{stderr}"
    );
    let r: Value = serde_json::from_str(&stdout)
        .unwrap_or_else(|e| panic!("{what}: no JSON ({e})\n{stdout}\n{stderr}"));
    r.as_array().unwrap().clone()
}

fn bytes(result: &Value) -> Vec<u8> {
    let hex = result["ok"]
        .as_str()
        .unwrap_or_else(|| panic!("not bytes: {result}"));
    (0..hex.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&hex[i..i + 2], 16).unwrap())
        .collect()
}

fn u16_of(result: &Value) -> u16 {
    let b = bytes(result);
    assert_eq!(b.len(), 2, "{result}");
    u16::from_le_bytes([b[0], b[1]])
}

fn i32_at(b: &[u8], at: usize) -> i32 {
    i32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

fn has(axis: &Value, flag: &str) -> bool {
    axis["flags"]
        .as_array()
        .unwrap()
        .iter()
        .any(|f| f.as_str() == Some(flag))
}

fn abort(result: &Value) -> u64 {
    result["abort"]
        .as_u64()
        .unwrap_or_else(|| panic!("an SDO abort expected: {result}"))
}

#[test]
fn python_canopen_enables_reads_and_positions_the_e10_at_node_2() {
    let m = Mcemu::start(
        Some(&workspace_root().join("fixtures/cpu226h.toml")),
        &["--clock", "virtual"],
    );
    assert!(!has(&m.axis(AXIS), "enabled"));

    // ---- enable over SDO (P282 bit 0), ready back (R204 bit 0), the process image ----------
    let r = session(
        &m,
        &json!([
            {"op": "sdo_read", "index": 0x20CC},
            {"op": "read_pdo_config"},
            {"op": "sdo_write", "index": 0x211A, "data": "0100"},
            {"op": "sdo_read", "index": 0x20CC},
            {"op": "sdo_read", "index": 0x2071},
            {"op": "sdo_write", "index": 0x2071, "data": "6400c800"},
            {"op": "sdo_read", "index": 0x2071},
            {"op": "sdo_write", "index": 0x20CC, "data": "0100"},
            {"op": "sdo_write", "index": 0x211A, "data": "010000"},
            {"op": "nmt", "state": "OPERATIONAL"},
            // Answered after every frame the start sent (decisions.md, "CT E10 on CANopen").
            {"op": "sdo_read", "index": 0x1000},
            {"op": "frames", "cob_id": 0x182},
            {"op": "frames", "cob_id": 0x702},
        ]),
    );
    // Time stood still since the start: the boot-up went out at the first frame, this
    // session's first SDO request.
    assert_eq!(r[12]["ok"], json!(["00"]), "boot-up: {}", r[12]);
    assert_eq!(
        u16_of(&r[0]) & 1,
        0,
        "R204 bit 0 before the enable: {}",
        r[0]
    );
    // The default PDOs are the §10.2 process image, read back over SDO by python-canopen.
    assert_eq!(
        r[1]["ok"],
        json!({
            "rpdo1": [0x211A, 0x2119, 0x2122],
            "rpdo2": [0x2061, 0x2071, 0x2065],
            "rpdo3": [0x2066],
            "tpdo1": [0x20CA, 0x20CC, 0x20D8],
            "tpdo2": [0x20DD],
        }),
        "{}",
        r[1]
    );
    assert_eq!(r[2]["ok"], true, "{}", r[2]);
    let state = m.axis(AXIS);
    assert!(
        has(&state, "enabled"),
        "P282 bit 0 enables e10_can: {state}"
    );
    assert_eq!(u16_of(&r[3]) & 1, 1, "R204 bit 0 ready: {}", r[3]);
    // P113: acceleration time (ms) in bits 0–15, deceleration time in bits 16–31 — the
    // fixture's 0.1 s / 0.1 s, then the Modbus example's 100 / 200 ms written as one object.
    assert_eq!(bytes(&r[4]), [100, 0, 100, 0]);
    assert_eq!(r[5]["ok"], true, "{}", r[5]);
    assert_eq!(bytes(&r[6]), [100, 0, 200, 0], "decel 200 ms read back");
    assert_eq!(abort(&r[7]), 0x0601_0002, "R204 is a monitor");
    assert_eq!(abort(&r[8]), 0x0607_0012, "3 bytes into a 16-bit object");
    // TPDO1 (R202, R204, R216) goes out on entering Operational, ready set.
    let frames = r[11]["ok"].as_array().unwrap();
    let tpdo1 =
        bytes(&json!({"ok": frames.first().unwrap_or_else(|| panic!("no TPDO1: {}", r[11]))}));
    assert_eq!(tpdo1.len(), 8, "{tpdo1:02x?}");
    assert_eq!(
        u16::from_le_bytes([tpdo1[0], tpdo1[1]]),
        0,
        "R202: no error"
    );
    assert_eq!(tpdo1[2] & 1, 1, "R204 bit 0 in TPDO1: {tpdo1:02x?}");

    // ---- positioning as the PLC does it: RPDO1 = P282 P281 P290 --------------------------
    // P282 = 3 (enable, bit 1 rising = position to P290), P281 = 0, P290 = 20 000 counts, in
    // one frame: the set-point is taken before the start.
    let r = session(
        &m,
        &json!([
            {"op": "send", "cob_id": 0x202, "data": "03000000204e0000"},
            // Answered after the RPDO's writes: the node takes its frames in order.
            {"op": "sdo_read", "index": 0x1000},
        ]),
    );
    assert_eq!(r[0]["ok"], true);
    let state = m.axis(AXIS);
    assert_eq!(state["state"], "discrete_motion", "{state}");
    assert_eq!(state["target_pos"], 20000.0, "{state}");
    let until = m.advance(&json!({
        "seconds": 5.0,
        "until": {"axis": AXIS, "state": "standstill"}
    }));
    assert_eq!(until["met"], true, "{until}");
    // The drive's own loop lags the set-point (first order, 5 ms).
    m.advance(&json!({"seconds": 0.1}));
    let state = m.axis(AXIS);
    let act = state["act_pos"].as_f64().unwrap();
    assert!((act - 20000.0).abs() <= 1.0, "{state}");

    // ---- live values: TPDO1 by its event timer as time advances, SDO uploads ------------
    // Time stands still until advanced: the event timer (100 ms) fires in the advance.
    let r = session_with(
        &m.port("socketcand"),
        Some(&m.api),
        &json!([
            {"op": "advance", "body": {"seconds": 0.2}},
            {"op": "sdo_read", "index": 0x20D8},
            {"op": "sdo_read", "index": 0x20CC},
            // Disabled, the drive refuses a run command (P281 = 1): the map's 04.
            {"op": "sdo_write", "index": 0x211A, "data": "0000"},
            {"op": "sdo_write", "index": 0x2119, "data": "0100"},
            {"op": "frames", "cob_id": 0x182},
        ]),
    );
    let frames = r[5]["ok"].as_array().unwrap();
    let tpdo1 = unhex(frames.first().unwrap().as_str().unwrap());
    let state = m.axis(AXIS);
    assert!(!has(&state, "enabled"), "P282 = 0 disables: {state}");
    let act = state["act_pos"].as_f64().unwrap().round() as i32;
    assert_eq!(
        i32_at(&tpdo1, 4),
        act,
        "R216 in TPDO1: {tpdo1:02x?} {state}"
    );
    assert_eq!(
        tpdo1[2] & 0b111,
        0b011,
        "ready, in position, still: {tpdo1:02x?}"
    );
    assert_eq!(i32_at(&bytes(&r[1]), 0), act, "R216 over SDO");
    assert_eq!(u16_of(&r[2]) & 0b111, 0b011, "R204 over SDO");
    assert_eq!(r[3]["ok"], true, "{}", r[3]);
    assert_eq!(abort(&r[4]), 0x0800_0022, "a disabled drive cannot run");

    let canopen = m.frontend("canopen");
    let node = &canopen["mapped_nodes"][0];
    assert_eq!(node["node_id"], 2, "{canopen}");
    assert_eq!(node["axis"], AXIS, "{canopen}");
    assert_eq!(node["nmt"], "Operational", "{canopen}");
    assert_eq!(node["refresh_errors"], 0, "{canopen}");
    assert_eq!(node["rpdo_write_errors"], 0, "{canopen}");
}

fn hex_list(result: &Value) -> Vec<String> {
    result["ok"]
        .as_array()
        .unwrap_or_else(|| panic!("not a frame list: {result}"))
        .iter()
        .map(|f| f.as_str().unwrap().to_string())
        .collect()
}

fn unhex(hex: &str) -> Vec<u8> {
    bytes(&json!({ "ok": hex }))
}

/// What the E10 sent in one second of a run.
#[derive(Debug, PartialEq)]
struct Heard {
    heartbeats: Vec<String>,
    tpdo1: Vec<String>,
    tpdo2: Vec<String>,
    /// Bus time of each heartbeat and TPDO1, µs after the first heartbeat (socketcand stamps:
    /// on the virtual clock the bus keeps engine time).
    heartbeat_at: Vec<i64>,
    tpdo1_at: Vec<i64>,
    act_pos: f64,
}

fn micros_after(first: f64, stamps: &Value) -> Vec<i64> {
    stamps["ok"]
        .as_array()
        .unwrap_or_else(|| panic!("no stamps: {stamps}"))
        .iter()
        .map(|t| ((t.as_f64().unwrap() - first) * 1e6).round() as i64)
        .collect()
}

/// What the E10 sends while the virtual clock runs 1 s in `steps` (an advance of ticks each):
/// its heartbeats (0x702), TPDO1 (R202 R204 R216) and TPDO2 (R221), heard from the start of a
/// positioning to 20 000 counts, with when they were sent, and the final position.
fn one_second_of_positioning(steps: &Value) -> Heard {
    let m = Mcemu::start(
        Some(&workspace_root().join("fixtures/cpu226h.toml")),
        &["--clock", "virtual"],
    );
    let r = session_with(
        &m.port("socketcand"),
        Some(&m.api),
        &json!([
            {"op": "sdo_write", "index": 0x1017, "data": "6400"},    // heartbeat 100 ms
            {"op": "sdo_write", "index": 0x211A, "data": "0100"},    // P282 bit 0: enable
            {"op": "sdo_write", "index": 0x2122, "data": "204e0000"}, // P290 = 20 000
            {"op": "nmt", "state": "OPERATIONAL"},
            {"op": "sdo_read", "index": 0x1000},   // every frame of the set-up is in
            {"op": "clear"},
            {"op": "sdo_write", "index": 0x211A, "data": "0300"},    // bit 1 rising: position
            steps,
            {"op": "sdo_read", "index": 0x20D8},   // every frame of the advance is in
            {"op": "frames", "cob_id": 0x702},
            {"op": "frames", "cob_id": 0x182},
            {"op": "frames", "cob_id": 0x282},
            {"op": "stamps", "cob_id": 0x702},
            {"op": "stamps", "cob_id": 0x182},
        ]),
    );
    for (i, result) in r.iter().enumerate().take(9) {
        assert!(result.get("ok").is_some(), "op {i}: {result}");
    }
    let state = m.axis(AXIS);
    assert_eq!(state["state"], "standstill", "{state}");
    assert_eq!(
        i32_at(&bytes(&r[8]), 0) as f64,
        state["act_pos"].as_f64().unwrap().round(),
        "R216 over SDO"
    );
    let canopen = m.frontend("canopen");
    assert_eq!(canopen["mapped_nodes"][0]["ticks_skipped"], 0, "{canopen}");
    let first = r[12]["ok"][0]
        .as_f64()
        .unwrap_or_else(|| panic!("no heartbeat stamps: {}", r[12]));
    Heard {
        heartbeats: hex_list(&r[9]),
        tpdo1: hex_list(&r[10]),
        tpdo2: hex_list(&r[11]),
        heartbeat_at: micros_after(first, &r[12]),
        tpdo1_at: micros_after(first, &r[13]),
        act_pos: state["act_pos"].as_f64().unwrap(),
    }
}

/// On the virtual clock the E10's timers fire at the ticks they fall on, with that tick's values,
/// however the time is advanced: one advance of 1 000 ticks sends exactly the frames that 1 000
/// advances of one tick send — heartbeats every 100 ms, TPDO1 whenever R216 changes and its
/// 10 ms inhibit time has passed, then every 100 ms by its event timer — in the same order with
/// the same data. (Before, the node ran once per advance: one heartbeat and one TPDO for the
/// whole second.)
#[test]
fn e10_timers_in_one_long_advance_fire_at_their_ticks() {
    let one = one_second_of_positioning(&json!({"op": "advance", "body": {"ticks": 1000}}));
    // 0x1017 and the start sent one each at tick 0, before the clear; then ticks 100 … 1000,
    // stamped with their bus time.
    assert_eq!(
        one.heartbeats,
        vec!["05"; 10],
        "heartbeats in one advance of 1 s"
    );
    assert_eq!(
        one.heartbeat_at,
        (0..10).map(|k| k * 100_000).collect::<Vec<i64>>(),
        "heartbeat times (µs after the first)"
    );
    let positions: Vec<i32> = one.tpdo1.iter().map(|f| i32_at(&unhex(f), 4)).collect();
    // The move takes about 0.2 s: TPDO1 every 10 ms (the inhibit time) while R216 changes.
    let moving = positions.windows(2).filter(|w| w[0] != w[1]).count();
    assert!(moving >= 10, "TPDO1 while moving: {positions:?}");
    assert!(
        positions.windows(2).all(|w| w[0] <= w[1]),
        "R216 only grows: {positions:?}"
    );
    assert_eq!(
        *positions.last().unwrap() as f64,
        one.act_pos.round(),
        "{positions:?}"
    );
    // Sent on whole ticks; while moving 10 ms apart (the inhibit time), at rest 100 ms apart
    // (the event timer) with the same data.
    assert!(
        one.tpdo1_at.iter().all(|t| t % 1000 == 0),
        "{:?}",
        one.tpdo1_at
    );
    let gaps: Vec<i64> = one.tpdo1_at.windows(2).map(|w| w[1] - w[0]).collect();
    assert_eq!(gaps[..moving], vec![10_000; moving], "{gaps:?}");
    assert_eq!(gaps[gaps.len() - 3..], [100_000; 3], "{gaps:?}");
    let last = one.tpdo1.last().unwrap();
    assert!(
        one.tpdo1.iter().rev().take(4).all(|f| f == last),
        "TPDO1 at rest: {:?}",
        one.tpdo1
    );
    assert!(one.tpdo2.len() >= 10, "TPDO2: {:?}", one.tpdo2);

    let ticks =
        one_second_of_positioning(&json!({"op": "advance", "body": {"ticks": 1}, "repeat": 1000}));
    assert_eq!(
        ticks, one,
        "1 000 advances of one tick against one of 1 000"
    );
}

/// What the E10 sends goes out in the order of its causes, however the frames reach it: an NMT
/// start and an SDO request written in one TCP write (one batch for the node) give the start's
/// TPDOs before the SDO answer, as two separate writes do. (Before, the node ran its timers once
/// after a batch: the answer came first, and a master that took the answer as "everything
/// before is in" lost the TPDOs — the cause of a flaky `e10_timers_…` run.)
#[test]
fn an_nmt_start_and_an_sdo_request_in_one_write_answer_in_order() {
    let m = Mcemu::start(
        Some(&workspace_root().join("fixtures/cpu226h.toml")),
        &["--clock", "virtual"],
    );
    let mut bus = Socketcand::open(m.address("socketcand"), "vcan0");
    for round in 0..5 {
        // Pre-operational (no PDOs) past the TPDOs' inhibit time, then start and read 0x1000
        // in one write.
        bus.send(&format!("< send 000 2 80 {NODE:02X} >"));
        bus.sdo_upload(u16::from(NODE), 0x1000, 0);
        m.advance(&json!({"seconds": 0.05}));
        bus.send(&format!(
            "< send 000 2 01 {NODE:02X} >< send {:03X} 8 40 00 10 00 00 00 00 00 >",
            0x600 + u16::from(NODE)
        ));
        let answer = 0x580 + u16::from(NODE);
        let mut before = Vec::new();
        loop {
            let Some(frame) = RawFrame::parse(&bus.next_element()) else {
                continue;
            };
            if frame.id == answer {
                assert!(
                    frame.data.starts_with(&[0x43, 0x00, 0x10, 0x00]),
                    "round {round}: {frame:?}"
                );
                break;
            }
            before.push(frame.id);
        }
        for tpdo in [0x182, 0x282] {
            assert!(
                before.contains(&tpdo),
                "round {round}: TPDO {tpdo:03X} of the start before the SDO answer: {before:03X?}"
            );
        }
    }
}

/// The axis's ramp times, in seconds (the parameters P113/P114 set).
fn ramp_times(m: &Mcemu) -> (f64, f64) {
    let get = |name: &str| {
        let r = m.post_ok(
            "/commands",
            &json!({"type": "get_parameter", "axis": AXIS, "name": name}),
        );
        r["value"].as_f64().unwrap_or_else(|| panic!("{name}: {r}"))
    };
    (get("accel_time"), get("decel_time"))
}

fn e10_with_state(dir: &mcemu_tests::TempDir) -> Mcemu {
    Mcemu::start(
        Some(&workspace_root().join("fixtures/cpu226h.toml")),
        &[
            "--clock",
            "virtual",
            "--state-dir",
            dir.path().to_str().unwrap(),
        ],
    )
}

/// 0x1010 "save" keeps the E10's P parameters over a power cycle, as a drive's parameter save
/// does, and they reach the drive at power-on (P113 sets the axis's ramps); the control word
/// P282 is process data and is not kept (the drive powers up disabled). NMT reset node returns
/// to the saved values; 0x1011 "load" (restore defaults) and a power cycle give the machine's
/// own values back (P113 = the fixture's 100 ms / 100 ms, P97 and P290 = 0).
#[test]
fn e10_p_parameters_survive_a_restart_after_a_store_and_not_after_a_restore() {
    let dir = mcemu_tests::TempDir::new("e10-store");
    let image = dir.path().join("canopen/node-2.img");

    // ---- run 1: set, store, change without storing ---------------------------------------
    let m = e10_with_state(&dir);
    assert_eq!(ramp_times(&m), (0.1, 0.1), "the fixture's ramps");
    let r = session(
        &m,
        &json!([
            {"op": "sdo_write", "index": 0x2061, "data": "d204"},      // P97 = 1234 rpm
            {"op": "sdo_write", "index": 0x2071, "data": "9600fa00"},  // P113 = 150 | 250 ms
            {"op": "sdo_write", "index": 0x2122, "data": "f7fcffff"},  // P290 = −777
            {"op": "sdo_write", "index": 0x211A, "data": "0100"},      // P282: enable
            {"op": "sdo_write", "index": 0x1017, "data": "c800"},      // heartbeat 200 ms
            {"op": "sdo_write", "index": 0x1010, "sub": 1, "data": "73617665"},
            {"op": "sdo_write", "index": 0x2061, "data": "0500"},      // P97 = 5, not stored
        ]),
    );
    for (i, result) in r.iter().enumerate() {
        assert_eq!(result["ok"], true, "op {i}: {result}");
    }
    assert!(image.is_file(), "{} after the save", image.display());
    assert_eq!(ramp_times(&m), (0.15, 0.25), "P113 written over SDO");
    assert!(has(&m.axis(AXIS), "enabled"));
    let exit = m.terminate();
    assert!(exit.status.success(), "{exit:?}");

    // ---- run 2: the stored values are the power-on values ------------------------------
    let m = e10_with_state(&dir);
    assert_eq!(
        ramp_times(&m),
        (0.15, 0.25),
        "the stored P113 reached the axis"
    );
    assert!(!has(&m.axis(AXIS), "enabled"), "P282 is not stored");
    let r = session_with(
        &m.port("socketcand"),
        Some(&m.api),
        &json!([
            {"op": "sdo_read", "index": 0x2061},
            {"op": "sdo_read", "index": 0x2071},
            {"op": "sdo_read", "index": 0x2122},
            {"op": "sdo_read", "index": 0x211A},
            {"op": "sdo_read", "index": 0x1017},
            // Changed, then NMT reset node: back to the stored values.
            {"op": "sdo_write", "index": 0x2061, "data": "0900"},
            {"op": "sdo_write", "index": 0x2071, "data": "c800c800"},
            {"op": "clear", "cob_id": 0x702},
            {"op": "nmt", "state": "RESET"},
            {"op": "wait_count", "cob_id": 0x702, "count": 1, "timeout": 10},
            {"op": "sdo_read", "index": 0x2061},
            {"op": "sdo_read", "index": 0x2071},
            // Restore defaults: effective at the next reset or power-on, not before.
            {"op": "sdo_write", "index": 0x1011, "sub": 1, "data": "6c6f6164"},
            {"op": "sdo_read", "index": 0x2061},
        ]),
    );
    assert_eq!(bytes(&r[0]), 1234i16.to_le_bytes(), "P97 after the restart");
    assert_eq!(bytes(&r[1]), [150, 0, 250, 0], "P113 after the restart");
    assert_eq!(i32_at(&bytes(&r[2]), 0), -777, "P290 after the restart");
    assert_eq!(u16_of(&r[3]), 0, "P282 after the restart");
    assert_eq!(u16_of(&r[4]), 200, "0x1017 after the restart");
    assert_eq!(
        r[9]["ok"],
        json!(["00"]),
        "boot-up after reset node: {}",
        r[9]
    );
    assert_eq!(bytes(&r[10]), 1234i16.to_le_bytes(), "P97 after reset node");
    assert_eq!(bytes(&r[11]), [150, 0, 250, 0], "P113 after reset node");
    assert_eq!(ramp_times(&m), (0.15, 0.25), "the axis after reset node");
    assert_eq!(r[12]["ok"], true, "{}", r[12]);
    assert_eq!(
        bytes(&r[13]),
        1234i16.to_le_bytes(),
        "P97 right after 0x1011"
    );
    let canopen = m.frontend("canopen");
    assert_eq!(
        canopen["mapped_nodes"][0]["parameter_errors"], 0,
        "{canopen}"
    );
    let exit = m.terminate();
    assert!(exit.status.success(), "{exit:?}");

    // ---- run 3: defaults -------------------------------------------------------------------
    let m = e10_with_state(&dir);
    assert_eq!(
        ramp_times(&m),
        (0.1, 0.1),
        "the fixture's ramps after the restore"
    );
    let r = session(
        &m,
        &json!([
            {"op": "sdo_read", "index": 0x2061},
            {"op": "sdo_read", "index": 0x2071},
            {"op": "sdo_read", "index": 0x2122},
            {"op": "sdo_read", "index": 0x1017},
        ]),
    );
    assert_eq!(bytes(&r[0]), [0, 0], "P97 after restore + restart");
    assert_eq!(
        bytes(&r[1]),
        [100, 0, 100, 0],
        "P113 after restore + restart"
    );
    assert_eq!(i32_at(&bytes(&r[2]), 0), 0, "P290 after restore + restart");
    assert_eq!(u16_of(&r[3]), 0, "0x1017 after restore + restart");
}
