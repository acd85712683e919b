//! CANopen masters written by others against the `mcemu` binary: python-canopen (`RemoteNode`,
//! `BaseNode402`), python-can and can-utils, over both ways a master reaches the bus.
//!
//! The cases live in one Python process per bus, `tests/python/canopen_suite.py` (its docstring
//! lists what each case proves); it starts and stops the `mcemu` processes itself, because on a
//! real vcan0 the emulator has to run where the interface is. Two tests run it:
//!
//! - over socketcand on the host (`--interface socketcand`), every case but the can-utils one;
//! - over a real SocketCAN `vcan0` (`--interface socketcan`) through `tests/vcan/run`, which on
//!   these machines boots a qemu VM: one boot runs the whole suite (the CT E10 of `cpu226h.toml`
//!   included, phase E), the can-utils case and then mcemu-can's `#[ignore]`d SocketCAN tests
//!   (`protocols/can/tests/socketcan.rs`), so that they count in CI too. The VM runs the release
//!   build of `mcemu`: under qemu's TCG a debug build's servo tick outlasts its 1 ms period. A VM that fails to boot, or times out, fails the test; nothing skips.
//!
//! Each test asserts that every expected case ran and passed: a case the script lost (renamed,
//! filtered, crashed before it) fails here, and so does one the script reports but this file
//! does not know.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;
use std::process::Command;
use std::time::Duration;

use mcemu_tests::{
    cargo_test_executable, fresh_dir, mcemu_bin, mcemu_release_bin, output_report, python,
    python_script, run_with_timeout, workspace_root,
};
use serde_json::Value;

/// The cases both buses run, in the script's order (`start_*` are the mcemu starts).
const CASES: &[&str] = &[
    "start_V",
    "v_bootup",
    "v_sdo_objects",
    "v_sdo_segmented",
    "v_sdo_block_domain",
    "v_pdo_config",
    "v_store_reset",
    "v_nmt",
    "v_heartbeat_exact",
    "v_emcy",
    "v_bad_input",
    "start_R",
    "r_stored_survive",
    "r_heartbeat",
    "r_readme",
    "r_ds402",
    "r_homing",
    "r_csp",
    "start_E",
    "e_enable_position",
    "e_timers_one_advance",
    "e_store_reset",
];
/// Cases that need SocketCAN (can-utils), after `v_bad_input`.
const SOCKETCAN_CASES: &[&str] = &["v_can_utils"];

/// Bound of the host run (about 20 s when the machine is quiet).
const HOST_TIMEOUT: Duration = Duration::from_secs(240);
/// Bound of the VM run given to the harness (boot included), and the outer bound here.
const VM_TIMEOUT_SECS: u64 = 480;

/// What the suite wrote to `results`, checked: exactly `expected` cases, in order, all passed.
/// Returns the results (with the cases' notes: measured figures) for the caller's output.
fn check_suite(results: &Path, expected: &[&str], context: &str) -> Value {
    let text = std::fs::read_to_string(results)
        .unwrap_or_else(|e| panic!("{}: {e}\n{context}", results.display()));
    let json: Value = serde_json::from_str(&text)
        .unwrap_or_else(|e| panic!("{}: not JSON ({e})\n{context}", results.display()));
    let cases = json["results"].as_array().expect("results array");
    let failed: Vec<String> = cases
        .iter()
        .filter(|c| c["ok"] != true)
        .map(|c| {
            format!(
                "{}: {}",
                c["name"].as_str().unwrap_or("?"),
                c["error"].as_str().unwrap_or("(no error text)")
            )
        })
        .collect();
    assert!(
        failed.is_empty(),
        "{} of {} cases failed:\n{}\n{context}",
        failed.len(),
        cases.len(),
        failed.join("\n\n")
    );
    let names: Vec<&str> = cases.iter().filter_map(|c| c["name"].as_str()).collect();
    assert_eq!(names, expected, "the cases that ran\n{context}");
    json
}

/// The figures the cases measured, one line each, for `--nocapture` and failure output.
fn notes(json: &Value) -> String {
    let mut lines = vec![format!(
        "canopen suite ({}, vm: {}): {} s",
        json["interface"], json["vm"], json["seconds"]
    )];
    for case in json["results"].as_array().into_iter().flatten() {
        lines.push(format!(
            "  {:<20} {:>7} s  {}",
            case["name"].as_str().unwrap_or("?"),
            case["seconds"],
            if case["notes"].is_null() {
                String::new()
            } else {
                case["notes"].to_string()
            }
        ));
    }
    lines.join("\n")
}

#[test]
fn python_canopen_masters_over_socketcand() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "canopen-masters-socketcand");
    let results = dir.join("suite.json");
    let mut command = Command::new(python());
    command
        .arg(python_script("canopen_suite.py"))
        .arg("--mcemu")
        .arg(mcemu_bin())
        .args(["--interface", "socketcand", "--workdir"])
        .arg(dir.join("suite"))
        .arg("--out")
        .arg(&results);
    let out = run_with_timeout(command, b"", HOST_TIMEOUT);
    let context = output_report("canopen_suite.py --interface socketcand", &out);
    let json = check_suite(&results, CASES, &context);
    assert!(out.status.success(), "{context}");
    println!("{}", notes(&json));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The job the VM runs: the suite, then mcemu-can's SocketCAN tests, each leaving its exit
/// status in a file (the harness's own status then says only whether the VM ran the job).
const VM_JOB: &str = r#"
set -u
dir=$1 python=$2 suite=$3 mcemu=$4 socketcan_tests=$5
"$python" "$suite" --mcemu "$mcemu" --interface socketcan --workdir "$dir/suite" \
    --out "$dir/suite.json"
echo $? >"$dir/suite.status"
"$socketcan_tests" --ignored --test-threads 2 >"$dir/socketcan.log" 2>&1
echo $? >"$dir/socketcan.status"
exit 0
"#;

#[test]
fn python_canopen_masters_can_utils_and_socketcan_tests_on_a_real_vcan0() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "canopen-masters-vcan");
    let socketcan_tests = cargo_test_executable("mcemu-can", "socketcan");
    // The tests the VM must run: those the binary lists as ignored.
    let listed = Command::new(&socketcan_tests)
        .args(["--list", "--ignored"])
        .output()
        .expect("list mcemu-can's socketcan tests");
    let ignored = String::from_utf8_lossy(&listed.stdout)
        .lines()
        .filter(|l| l.ends_with(": test"))
        .count();
    assert!(
        ignored >= 5,
        "{} lists {ignored} ignored tests\n{}",
        socketcan_tests.display(),
        String::from_utf8_lossy(&listed.stdout)
    );

    let mut command = Command::new(workspace_root().join("tests/vcan/run"));
    command
        .args(["--timeout", &VM_TIMEOUT_SECS.to_string(), "--share"])
        .arg(&dir)
        .args(["--", "bash", "-c", VM_JOB, "vm-job"])
        .arg(&dir)
        .arg(python())
        .arg(python_script("canopen_suite.py"))
        // Optimised, as users run it: under TCG a debug build's tick outlasts the 1 ms period
        // (2 229 overruns in 1.5 s), and the CSP and heartbeat cases measure the wall clock.
        .arg(mcemu_release_bin())
        .arg(&socketcan_tests);
    let out = run_with_timeout(command, b"", Duration::from_secs(VM_TIMEOUT_SECS + 60));
    let context = output_report("tests/vcan/run -- canopen suite + socketcan tests", &out);
    assert_eq!(
        out.status.code(),
        Some(0),
        "the VM did not run the job\n{context}"
    );
    let status = |name: &str| {
        std::fs::read_to_string(dir.join(name))
            .unwrap_or_else(|e| panic!("{name}: {e}\n{context}"))
            .trim()
            .to_string()
    };

    let mut expected: Vec<&str> = CASES.to_vec();
    let at = expected.iter().position(|c| *c == "v_bad_input").unwrap() + 1;
    for (i, case) in SOCKETCAN_CASES.iter().enumerate() {
        expected.insert(at + i, case);
    }
    let json = check_suite(&dir.join("suite.json"), &expected, &context);
    assert_eq!(json["interface"], "socketcan", "{context}");
    assert_eq!(status("suite.status"), "0", "{context}");
    println!("{}", notes(&json));

    let log = std::fs::read_to_string(dir.join("socketcan.log")).unwrap_or_default();
    let summary = format!("test result: ok. {ignored} passed; 0 failed");
    assert!(
        status("socketcan.status") == "0" && log.contains(&summary),
        "mcemu-can's SocketCAN tests in the VM (`{summary}` expected)\n--- socketcan.log\n{log}\n{context}"
    );
    println!("mcemu-can socketcan tests in the VM: {summary}");
    let _ = std::fs::remove_dir_all(&dir);
}
