//! Persisted Modbus memory end to end: the generic map's user table (HR 3000 … 3999,
//! `persist = true`) written by pymodbus survives a SIGTERM and a restart with the same
//! `--state-dir`, and survives a SIGKILL once the periodic save (each second) has happened; a
//! corrupt or mismatched state file is reported on stderr, naming the file and the reason, and
//! does not stop the start (the table starts from its initial values and the next save replaces
//! the file).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;
use std::time::Duration;

use mcemu_tests::{run_pymodbus_tcp, run_python_client, wait_for, Mcemu, TempDir};
use serde_json::{json, Value};

/// Where the TCP front-end keeps its persisted areas.
fn state_file(dir: &Path) -> std::path::PathBuf {
    dir.join("modbus/modbus_tcp.json")
}

fn start(dir: &Path) -> Mcemu {
    Mcemu::start(
        None,
        &["--clock", "virtual", "--state-dir", dir.to_str().unwrap()],
    )
}

fn pymodbus(m: &Mcemu, ops: Value) -> Value {
    let port = m.port("modbus-tcp");
    run_pymodbus_tcp(&port, &ops)
}

fn stop(m: Mcemu) -> String {
    let exit = m.terminate();
    assert!(exit.status.success(), "{exit:?}");
    assert!(
        exit.stdout.iter().any(|l| l == "mcemu: stopped"),
        "{exit:?}"
    );
    exit.stderr
}

const VALUES: [u16; 5] = [1, 65535, 0, 4242, 7];

#[test]
fn the_user_table_survives_sigterm_and_a_restart() {
    let dir = TempDir::new("persist");
    let m = start(dir.path());
    let r = pymodbus(
        &m,
        json!([
            {"op": "write_registers", "address": 3000, "values": VALUES},
            {"op": "write_register", "address": 3999, "value": 99},
            // Not persisted: the analog output of HR 1000 is the machine's, not memory.
            {"op": "write_float", "address": 1000, "value": 1.5, "word_order": "big"},
        ]),
    );
    assert_eq!(r, json!([{"ok": null}, {"ok": null}, {"ok": null}]));
    let stderr = stop(m);
    assert!(!stderr.contains("not restored"), "{stderr}");
    let saved: Value =
        serde_json::from_str(&std::fs::read_to_string(state_file(dir.path())).unwrap()).unwrap();
    let table = &saved["units"]["any"]["user_table"];
    assert_eq!(table.as_array().unwrap().len(), 1000, "{saved}");
    assert_eq!(
        table.as_array().unwrap()[0..5],
        json!(VALUES).as_array().unwrap()[..]
    );

    let m = start(dir.path());
    let r = pymodbus(
        &m,
        json!([
            {"op": "read_holding_registers", "address": 3000, "count": 6},
            {"op": "read_holding_registers", "address": 3999, "count": 1},
            {"op": "read_float", "address": 1000, "word_order": "big"},
        ]),
    );
    assert_eq!(r[0], json!({"ok": [1, 65535, 0, 4242, 7, 0]}));
    assert_eq!(r[1], json!({"ok": [99]}));
    assert_eq!(r[2], json!({"ok": 0.0}), "analog outputs start at 0");
    // Another front-end's memory is its own (and its own file).
    let port = m.port("modbus-rtu-over-tcp");
    let r = run_python_client(
        [
            "--client",
            "pymodbus",
            "--transport",
            "rtu-over-tcp",
            "--port",
            &port,
        ],
        &json!([{"op": "read_holding_registers", "address": 3000, "count": 2}]),
    );
    assert_eq!(r[0], json!({"ok": [0, 0]}));
    let stderr = stop(m);
    assert!(!stderr.contains("not restored"), "{stderr}");
}

#[test]
fn the_periodic_save_survives_sigkill() {
    let dir = TempDir::new("persist-kill");
    let mut m = start(dir.path());
    pymodbus(
        &m,
        json!([{"op": "write_registers", "address": 3010, "values": [11, 22, 33]}]),
    );
    // Saved within a second of the write, without a stop: wait (wall time) for the file.
    let file = state_file(dir.path());
    wait_for("the periodic save", Duration::from_secs(10), || {
        let text = std::fs::read_to_string(&file).ok()?;
        let saved: Value = serde_json::from_str(&text).ok()?;
        let table = saved["units"]["any"]["user_table"].as_array()?.clone();
        (table.get(10..13)? == json!([11, 22, 33]).as_array()?.as_slice()).then_some(())
    });
    // No chance to save at exit.
    let pid = m.pid();
    let status = std::process::Command::new("kill")
        .args(["-KILL", &pid.to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    drop(std::mem::replace(&mut m, start(dir.path())));
    let r = pymodbus(
        &m,
        json!([{"op": "read_holding_registers", "address": 3010, "count": 3}]),
    );
    assert_eq!(r[0], json!({"ok": [11, 22, 33]}));
    stop(m);
}

#[test]
fn a_corrupt_state_file_is_reported_and_does_not_stop_the_start() {
    let dir = TempDir::new("persist-corrupt");
    let file = state_file(dir.path());
    std::fs::create_dir_all(file.parent().unwrap()).unwrap();
    let shown = file.display().to_string();

    for (content, reason) in [
        ("{\"units\": {\"any\": {\"user_ta", "not JSON"),
        (
            "{\"units\": {\"any\": {\"user_table\": [1, 2, 3]}}}",
            "units.any.user_table: area `user_table` has 1000 addresses, the saved state 3",
        ),
        (
            "{\"units\": {\"any\": {\"user_table\": [1, -2, 70000]}}}",
            "units.any.user_table: not a list of 16-bit words",
        ),
    ] {
        std::fs::write(&file, content).unwrap();
        let m = start(dir.path());
        let expected = format!("mcemu: {shown}: persisted Modbus memory not restored: {reason}");
        // Printed before the listeners, but stderr is another pipe, read on its own thread.
        wait_for(
            &format!("`{expected}` on stderr"),
            Duration::from_secs(10),
            || m.stderr_text().contains(&expected).then_some(()),
        );
        // It runs, from the initial values, and its next save replaces the file.
        let r = pymodbus(
            &m,
            json!([
                {"op": "read_holding_registers", "address": 3000, "count": 3},
                {"op": "write_register", "address": 3001, "value": 5},
            ]),
        );
        assert_eq!(r[0], json!({"ok": [0, 0, 0]}), "{content}");
        stop(m);
        let saved: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap())
            .unwrap_or_else(|e| panic!("{content}: the file was not replaced: {e}"));
        assert_eq!(saved["units"]["any"]["user_table"][1], 5, "{content}");
    }
    // The replaced file restores cleanly.
    let m = start(dir.path());
    let r = pymodbus(
        &m,
        json!([{"op": "read_holding_registers", "address": 3000, "count": 2}]),
    );
    assert_eq!(r[0], json!({"ok": [0, 5]}));
    let stderr = stop(m);
    assert!(!stderr.contains("not restored"), "{stderr}");
}
