//! The manual's examples (digest 001 §5) and test vectors (§6) as C programs (`tests/nmc/`),
//! compiled with gcc `-Wall -Wextra -Werror` against mcemu's headers, linked with
//! `libnmc_lib20.so`, and run against `mcemu run` on the Gaochuan fixture; the headers compiled
//! as C and C++ pedantic; 8 threads on one handle; a lost mcemu; a Python ctypes client.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{BufRead, BufReader, Write};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use mcemu_tests::{
    compile_example, fresh_dir, nmc_library_dir, output_report, python, python_script, run_example,
    run_with_timeout, workspace_root, Mcemu, PROGRAM_TIMEOUT,
};

fn gaochuan() -> PathBuf {
    workspace_root().join("fixtures/gaochuan-gcn.toml")
}

/// Compile `name`, start a fresh mcemu on the Gaochuan fixture, run the program against it and
/// expect its last line to be `ok`.
fn example(name: &str) -> String {
    example_with(name, &[])
}

/// [`example`] with extra `mcemu run` arguments (a scaled clock for the long paths).
fn example_with(name: &str, args: &[&str]) -> String {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), &format!("nmc-{name}"));
    let exe = compile_example(name, &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), args);
    let out = run_example(&exe, m.address("nmc"));
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success() && stdout.lines().last() == Some("ok"),
        "{}",
        output_report(name, &out)
    );
    stdout
}

#[test]
fn s_open_tv01_tv03_tv25_and_bad_handles() {
    example("s_open.c");
}

#[test]
fn s_status_and_the_125us_clock() {
    example("s_status.c");
}

#[test]
fn s_ptp_stepwise_abs_rel_tv11_tv15_tv69() {
    example("s_ptp.c");
}

#[test]
fn s_jog_stop_abrupt_estp_tv16_tv20() {
    example("s_jog.c");
}

#[test]
fn s_home_1_tv29_tv30() {
    example("s_home.c");
}

#[test]
fn s_io_tv38() {
    example("s_io.c");
}

#[test]
fn s_config_tv05_tv10_tv22_tv68() {
    example("s_config.c");
}

#[test]
fn s_io_analog_tv41_and_appendix_a_dog() {
    example("s_analog.c");
}

/// S-ECAT-START and TV33 on an EtherCAT card; the same calls refused on the network card.
#[test]
fn s_ecat_start_tv33() {
    example_with("s_ecat.c", &["--set", "frontends.nmc.device.kind=\"ecat\""]);
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-s_ecat-pulse");
    let exe = compile_example("s_ecat.c", &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), &[]);
    let mut command = Command::new(&exe);
    command.arg("pulse").env("MCEMU_NMC", m.address("nmc"));
    let out = run_with_timeout(command, b"", PROGRAM_TIMEOUT);
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success() && stdout.lines().last() == Some("ok"),
        "{}",
        output_report("s_ecat.c pulse", &out)
    );
}

#[test]
fn user_parameter_areas_tv66() {
    example("s_user_para.c");
}

/// The coordinate-system examples (S-CRD-*) and TV04, TV42–TV54, on a clock 5× real time.
#[test]
fn s_crd_examples_tv42_tv54() {
    example_with("s_crd.c", &["--clock", "scaled:5"]);
}

#[test]
fn eight_threads_on_one_handle_each_get_their_reply() {
    example("threads.c");
}

#[test]
fn the_headers_compile_as_c_and_cpp_pedantic() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-header");
    for flags in [
        &["-std=c99", "-pedantic"][..],
        &["-xc++", "-std=c++11", "-pedantic"][..],
    ] {
        let exe = compile_example("header.c", &dir, flags);
        assert!(exe.is_file());
    }
}

/// mcemu killed between two calls: the next call returns −1 within the timeout (500 ms
/// here), and once mcemu is back on the same address the call after works.
#[test]
fn a_lost_mcemu_is_minus_one_and_the_next_call_reconnects() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-reconnect");
    let exe = compile_example("reconnect.c", &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), &[]);
    let address = m.address("nmc").to_string();
    let mut child = Command::new(&exe)
        .env("MCEMU_NMC", &address)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    assert_eq!(lines.next().unwrap().unwrap(), "ready");
    drop(m);
    let asked = Instant::now();
    writeln!(stdin, "go").unwrap();
    assert_eq!(lines.next().unwrap().unwrap(), "lost -1");
    assert!(
        asked.elapsed() < Duration::from_secs(5),
        "{:?}",
        asked.elapsed()
    );
    let set = format!("frontends.nmc.bind={address}");
    let _m = Mcemu::start(Some(&gaochuan()), &["--set", &set]);
    writeln!(stdin, "go").unwrap();
    assert_eq!(lines.next().unwrap().unwrap(), "back 0");
    assert!(child.wait().unwrap().success());
}

/// The library driven from Python through ctypes, as users of vendor Python wrappers do.
#[test]
fn python_ctypes_drives_the_library() {
    let lib = nmc_library_dir().join("libnmc_lib20.so");
    let m = Mcemu::start(Some(&gaochuan()), &[]);
    let mut command = Command::new(python());
    command
        .arg(python_script("nmc_ctypes.py"))
        .arg(&lib)
        .env("MCEMU_NMC", m.address("nmc"));
    let out = run_with_timeout(command, b"", PROGRAM_TIMEOUT);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && stdout.contains("prfPos 5000"),
        "{}",
        output_report("nmc_ctypes.py", &out)
    );
}
