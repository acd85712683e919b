//! Self-test of the vcan harness (`tests/vcan/run`, `scripts/setup-vcan`), **not of mcemu**:
//! later CANopen tests run their clients through `tests/vcan/run` against a real `vcan0`,
//! on the host where its kernel has vcan, otherwise in a qemu VM. These tests prove that the
//! harness gives a command a working `vcan0` (can-utils and python-can exchange frames on it),
//! streams the command's stdout and stderr apart, returns its exit status, brings files the
//! command writes back to the host, and fails loudly (never a silent pass) when the VM runs
//! out of time or stops before the command has finished.
//!
//! They never skip: without qemu or the kernel image the harness exits non-zero naming
//! `scripts/setup-vcan` (which `scripts/setup` runs), and the test fails with that output.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;
use std::time::Duration;

use mcemu_tests::{fresh_dir, output_report, run_with_timeout, workspace_root};

/// Bound of one harness run seen from here: a VM boot takes about 4 s on an idle 2-core
/// machine, the self-test about 5 s more; other tests running beside it slow both down.
const HARNESS_TIMEOUT: Duration = Duration::from_secs(300);

fn harness() -> Command {
    Command::new(workspace_root().join("tests/vcan/run"))
}

/// The rest of the stdout line that starts with `prefix`.
fn line_after<'a>(stdout: &'a str, prefix: &str) -> Option<&'a str> {
    stdout.lines().find_map(|l| l.strip_prefix(prefix))
}

#[test]
fn selftest_exchanges_frames_on_a_real_vcan0() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "vcan-harness-selftest");
    let selftest = workspace_root().join("tests/vcan/selftest");
    let mut command = harness();
    // Exit 42 after a passing self-test: the status must come back as it is.
    command
        .args(["--timeout", "240", "--share"])
        .arg(&dir)
        .args(["--", "bash", "-c", r#""$1" "$2" && exit 42"#, "selftest"])
        .arg(&selftest)
        .arg(&dir);
    let out = run_with_timeout(command, b"", HARNESS_TIMEOUT);
    let report = output_report("tests/vcan/run -- tests/vcan/selftest", &out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(42), "{report}");

    // The side it ran on, and vcan0 itself.
    let side = line_after(&stdout, "selftest: running on ").expect(&report);
    assert!(
        side.starts_with("host ") || side.starts_with("vm "),
        "{report}"
    );
    assert!(
        stdout.contains("selftest: vcan0 is a vcan link and up\n"),
        "{report}"
    );

    // can-utils: the frame cansend sent is the one candump logged, in the VM, to a file that
    // is now on the host.
    let frame = line_after(&stdout, "selftest: candump received ").expect(&report);
    assert!(
        frame.len() == 12 && frame.starts_with("123#"),
        "frame {frame:?}\n{report}"
    );
    let log = std::fs::read_to_string(dir.join("candump.log"))
        .unwrap_or_else(|e| panic!("{}/candump.log: {e}\n{report}", dir.display()));
    assert!(
        log.trim_end().ends_with(&format!(" vcan0 {frame}")),
        "candump.log: {log:?}\n{report}"
    );

    // python-can: one frame and five BCM periodic frames, reported on stdout and in a file.
    let frame = line_after(&stdout, "python-can: received ").expect(&report);
    assert!(frame.starts_with("124#"), "{report}");
    assert!(
        stdout.contains("python-can: periodic send, received 5 frames 18FF0001#0102\n"),
        "{report}"
    );
    let json = std::fs::read_to_string(dir.join("python-can.json"))
        .unwrap_or_else(|e| panic!("{}/python-can.json: {e}\n{report}", dir.display()));
    let json: serde_json::Value = serde_json::from_str(&json).expect(&report);
    assert_eq!(json["frame"], frame, "{report}");
    assert_eq!(json["periodic"]["received"], 5, "{report}");

    // stderr is its own stream.
    assert!(
        stderr.contains("selftest: stderr reaches the caller\n"),
        "{report}"
    );
    assert!(!stdout.contains("stderr reaches"), "{report}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_vm_that_runs_out_of_time_fails_with_124() {
    let mut command = harness();
    command.args(["--mode", "vm", "--timeout", "2", "--", "sleep", "60"]);
    let out = run_with_timeout(command, b"", HARNESS_TIMEOUT);
    let report = output_report("tests/vcan/run --mode vm --timeout 2 -- sleep 60", &out);
    assert_eq!(out.status.code(), Some(124), "{report}");
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("vcan: timed out"),
        "{report}"
    );
}

#[test]
fn a_vm_that_stops_before_the_command_fails_with_125() {
    // A kernel that finds no init panics, and qemu exits (-no-reboot) without a status.
    let mut command = harness();
    command
        .env(
            "MCEMU_VCAN_CMDLINE",
            "rdinit=/no-such-init init=/no-such-init",
        )
        .args(["--mode", "vm", "--timeout", "120", "--", "true"]);
    let out = run_with_timeout(command, b"", HARNESS_TIMEOUT);
    let report = output_report("tests/vcan/run --mode vm -- true (no init)", &out);
    assert_eq!(out.status.code(), Some(125), "{report}");
    assert!(
        String::from_utf8_lossy(&out.stderr)
            .contains("the VM stopped (qemu exit status 0) before the command finished"),
        "{report}"
    );
}
