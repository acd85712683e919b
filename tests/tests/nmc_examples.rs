//! The manual's examples (digest 001 §5) and test vectors (§6) as C programs (`tests/nmc/`),
//! compiled with gcc `-Wall -Wextra -Werror` against mcemu's headers, linked with
//! `libnmc_lib20.so`, and run against `mcemu run` on the Gaochuan fixture; the headers compiled
//! as C and C++ pedantic; 8 threads on one handle; a lost mcemu; a Python ctypes client.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{BufRead, BufReader, Lines, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};
use std::time::{Duration, Instant};

use mcemu_tests::{
    compile_example, fresh_dir, nmc_library_dir, output_report, python, python_script, run_example,
    run_with_timeout, wait_for, workspace_root, Mcemu, PROGRAM_TIMEOUT,
};
use serde_json::json;

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
    example_on(&gaochuan(), name, args)
}

/// [`example_with`] on the machine `config`.
fn example_on(config: &std::path::Path, name: &str, args: &[&str]) -> String {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), &format!("nmc-{name}"));
    let exe = compile_example(name, &dir, &[]);
    let m = Mcemu::start(Some(config), args);
    let out = run_example(&exe, m.address("nmc"));
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success() && stdout.lines().last() == Some("ok"),
        "{}",
        output_report(name, &out)
    );
    stdout
}

/// Start the compiled program `exe` against the NMC server at `address`, for a test that talks
/// to it between its steps: the child, its stdin and its stdout's lines.
fn spawn_interactive(
    exe: &Path,
    address: &str,
) -> (Child, ChildStdin, Lines<BufReader<ChildStdout>>) {
    let mut child = Command::new(exe)
        .env("MCEMU_NMC", address)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let stdin = child.stdin.take().unwrap();
    let lines = BufReader::new(child.stdout.take().unwrap()).lines();
    (child, stdin, lines)
}

/// S-COLLECT: data collection sampled every planning period, a rising trigger, bad arguments.
#[test]
fn s_collect() {
    example("s_collect.c");
}

/// USER1's login and password, command debugging to a file, NMC_UserPrint.
#[test]
fn users_and_command_debugging() {
    example("s_users.c");
}

/// The configuration saved to and loaded from a file on the host; bad paths and files.
#[test]
fn configuration_file() {
    example("s_config_file.c");
}

/// The change counters of the dedicated inputs (limits, home, Z).
#[test]
fn dedicated_input_change_counters() {
    example("di_dedicated_counts.c");
}

/// The execution time of a pushed program, computed and not run.
#[test]
fn crd_execution_time() {
    example("s_exe_time.c");
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
fn s_io_tv37_tv38() {
    example("s_io.c");
}

/// I/O by type, masked DO, encoder channels, extension module 2, identity (rows 0x12xx).
#[test]
fn io_by_type_encoders_modules_identity() {
    example("io_ext.c");
}

/// The plain aliases, inversions, timed outputs, filters (TV74), edge counters, DIO mappings.
#[test]
fn io_aliases_inversion_timed_outputs_counters_tv74() {
    example("io_extras.c");
}

/// DevWriteID, system parameters, the RTC, the system password, backed variables.
#[test]
fn controller_services() {
    example("dev_services.c");
}

/// S-HOST-C++ (digest 001 §5, C4): a C++ host program built with g++.
#[test]
fn s_host_cpp() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-s_host");
    let exe = compile_example("s_host.cpp", &dir, &["-xc++", "-std=c++11"]);
    let m = Mcemu::start(Some(&gaochuan()), &[]);
    let out = run_example(&exe, m.address("nmc"));
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success() && stdout.lines().last() == Some("ok"),
        "{}",
        output_report("s_host.cpp", &out)
    );
}

#[test]
fn s_gear_tv58() {
    example("s_gear.c");
}

#[test]
fn s_pt_static_stream_and_pvt_tv55_tv57() {
    example("s_pt.c");
}

#[test]
fn s_capt_repeat_and_advcapt_tv60_tv62() {
    example("s_capt.c");
}

#[test]
fn s_cmp_2d_and_1d_tv63() {
    example("s_cmp.c");
}

#[test]
fn s_gantry_and_handwheel_tv73() {
    example("s_gang.c");
}

#[test]
fn s_leadscrew_backlash_2dcomp_tv72() {
    example("s_comp.c");
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

/// TV34–TV36 on the EtherCAT fixture: bus axes 16 and 17 on CiA 402 drives (servo through the
/// state machine, motion, fault as alarm and fault reset, drive homing by NMC_EcatStartHome and
/// by NMC_MtHome mode 1021, SDO with abort codes), and the documented codes for bad arguments.
#[test]
fn ecat_bus_axes_tv34_tv36() {
    let fixture = workspace_root().join("fixtures/gaochuan-gcn-ecat.toml");
    example_on(&fixture, "ecat_bus.c", &[]);
}

/// S-LASER (digest 001 §5, C3§2.2–2.3): settings read back, the switch and DA echoes, buffered
/// on/off in path order.
#[test]
fn s_laser_echoes_and_buffered_on_off() {
    example("s_laser.c");
}

/// S-LASER's SHIO examples (C3§2.4.3): the gate pin, pulse trains, the buffered gate in path
/// order.
#[test]
fn s_shio_gate_and_pwm() {
    example("s_shio.c");
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
fn s_crd_lookahead_pack4_wait_pos() {
    example_with("s_crd_lookahead.c", &["--clock", "scaled:5"]);
}

#[test]
fn s_crd_circles_and_buffer_length() {
    example_with("s_crd_circle.c", &["--clock", "scaled:5"]);
}

/// Family 0x17xx: S-TRANS-ROTATE, the polar machine, S-TRANS-XYZA, the buffer offset, arc
/// sections, the A axis's corner velocity and the break point.
#[test]
fn crd_transforms_offset_arc_sections_and_break_point() {
    example_with("crd_frames.c", &["--clock", "scaled:5"]);
}

/// NMC_CrdSetTransPolar on the coordinate system's X and Y: Cartesian lines and arcs fed to the
/// rotary and feed axes as (θ, r), RunToPolarPos's (5000, 5000) → 45°, the pole refused.
#[test]
fn crd_polar_machine_transforms_lines_and_arcs() {
    example_with("crd_polar.c", &["--clock", "scaled:5"]);
}

/// NMC_SetMvProtect and TmvProtectPara: mode 0 stops, mode 1 retreats, read-back, refusals.
#[test]
fn crd_move_protection() {
    example_with("mv_protect.c", &["--clock", "scaled:5"]);
}

/// TV51–TV53: the override's range, at most 4 axes, D8Pack's count.
#[test]
fn crd_refusals_tv51_tv53() {
    example("crd_refusals.c");
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
    let (mut child, mut stdin, mut lines) = spawn_interactive(&exe, &address);
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

/// TV60 and TV61 on DI0, which this harness drives through the control API between the
/// program's steps (falls with axis 2 at 500, rises at 1500).
#[test]
fn tv60_tv61_capture_on_di0() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-capt-di");
    let exe = compile_example("capt_di.c", &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), &[]);
    let di0 = |value: bool| {
        m.post_ok(
            "/commands",
            &json!({"type": "force_digital_input", "channel": 0, "value": value}),
        );
    };
    di0(true);
    let (mut child, mut stdin, mut lines) = spawn_interactive(&exe, m.address("nmc"));
    assert_eq!(lines.next().unwrap().unwrap(), "at 500");
    di0(false);
    writeln!(stdin, "fell").unwrap();
    assert_eq!(lines.next().unwrap().unwrap(), "at 1500");
    di0(true);
    writeln!(stdin, "rose").unwrap();
    assert_eq!(lines.next().unwrap().unwrap(), "ok");
    assert!(child.wait().unwrap().success());
}

/// Server-side faults through `POST /api/v1/faults` (issue 13): a delay beyond the timeout, no
/// reply, a closed connection, a garbage frame (a bit of the magic flipped) and a wrong
/// sequence number each give the call −1 within the timeout (400 ms), and the next call works.
#[test]
fn nmc_faults_give_minus_one_and_the_next_call_works() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-faults");
    let exe = compile_example("faults.c", &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), &[]);
    let (mut child, mut stdin, mut lines) = spawn_interactive(&exe, m.address("nmc"));
    assert_eq!(lines.next().unwrap().unwrap(), "ready");
    let faults = [
        json!({"frontend": "nmc", "fault": "delay", "ms": 1500, "count": 1}),
        json!({"frontend": "nmc", "fault": "no_reply", "count": 1}),
        json!({"frontend": "nmc", "fault": "close", "count": 1}),
        json!({"frontend": "nmc", "fault": "corrupt", "count": 1}),
        json!({"frontend": "nmc", "fault": "wrong_sequence", "count": 1}),
    ];
    for fault in &faults {
        let active = m.fault(fault);
        assert_eq!(active.as_array().map(Vec::len), Some(1), "{active}");
        let asked = Instant::now();
        writeln!(stdin, "go").unwrap();
        assert_eq!(lines.next().unwrap().unwrap(), "faulted -1", "{fault}");
        assert!(asked.elapsed() < Duration::from_secs(5), "{fault}");
        assert_eq!(lines.next().unwrap().unwrap(), "after 0", "{fault}");
    }
    let f = m.frontend("nmc");
    assert_eq!(f["active_faults"], json!([]), "{f}");
    for kind in ["delay", "no_reply", "close", "corrupt", "wrong_sequence"] {
        assert_eq!(f["faults_applied"][kind], 1, "{f}");
    }
    let (status, _) = m.post("/faults", &json!({"frontend": "nmc", "fault": "exception"}));
    assert_eq!(status, 400);
    drop(stdin);
    assert!(child.wait().unwrap().success());
}

/// mcemu killed DURING a call (the request is in, held by a `no_reply` fault): the call returns
/// −1 well within its timeout, and after mcemu restarts on the same address the next call
/// reconnects.
#[test]
fn mcemu_killed_during_a_call_is_minus_one_and_the_next_call_reconnects() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-kill-during");
    let exe = compile_example("faults.c", &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), &[]);
    let address = m.address("nmc").to_string();
    let (mut child, mut stdin, mut lines) = spawn_interactive(&exe, &address);
    assert_eq!(lines.next().unwrap().unwrap(), "ready");
    m.fault(&json!({"frontend": "nmc", "fault": "no_reply"}));
    let requests = m.frontend("nmc")["requests"].as_u64().unwrap();
    writeln!(stdin, "during").unwrap();
    assert_eq!(lines.next().unwrap().unwrap(), "calling");
    // The request reached the server (and is held there): now kill it.
    wait_for("the call reaching mcemu", Duration::from_secs(5), || {
        (m.frontend("nmc")["requests"].as_u64().unwrap() > requests).then_some(())
    });
    drop(m);
    assert_eq!(lines.next().unwrap().unwrap(), "lost -1");
    let set = format!("frontends.nmc.bind={address}");
    let _m = Mcemu::start(Some(&gaochuan()), &["--set", &set]);
    writeln!(stdin, "after").unwrap();
    assert_eq!(lines.next().unwrap().unwrap(), "after 0");
    drop(stdin);
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

/// The axis-level additions (family 0x13xx): StsMulti, StsPack12Ex, the Pack8 moves, SetAxisPos,
/// SetEncPos, ZeroPos, HomeSns and the electrical motion-I/O levels, SvClr, TV64.
#[test]
fn axis_additions_packed_status_and_moves_tv64() {
    example("ax_status.c");
}

/// TV71: the watchdog stops the jog and writes DO group 0 once the host stops calling.
#[test]
fn watchdog_fires_when_the_host_goes_quiet_tv71() {
    example("watchdog.c");
}

/// The E-stop inputs, DI1 (per axis, active low) and DI2 (advanced group, active high), which
/// this harness drives through the control API between the program's steps.
#[test]
fn estop_inputs_stop_the_axes() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-estop-di");
    let exe = compile_example("estop_di.c", &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), &[]);
    let di = |channel: u16, value: bool| {
        m.post_ok(
            "/commands",
            &json!({"type": "force_digital_input", "channel": channel, "value": value}),
        );
    };
    di(1, true);
    di(2, false);
    let (mut child, mut stdin, mut lines) = spawn_interactive(&exe, m.address("nmc"));
    for (line, (channel, value)) in [
        ("jogging", (1, false)),
        ("release", (1, true)),
        ("jogging2", (2, true)),
    ] {
        assert_eq!(lines.next().unwrap().unwrap(), line);
        di(channel, value);
        writeln!(stdin, "{line}").unwrap();
    }
    assert_eq!(lines.next().unwrap().unwrap(), "ok");
    assert!(child.wait().unwrap().success());
}

/// The watchdog and the E-stop inputs are the engine's guards: on the virtual clock, time
/// advanced in one long step stops the axes at the tick real time would (TV71; the program's
/// bounds are the positions of those ticks).
#[test]
fn guards_act_on_the_tick_on_the_virtual_clock() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-guards-virtual");
    let exe = compile_example("guards_virtual.c", &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), &["--clock", "virtual"]);
    let di = |channel: u16, value: bool| {
        m.post_ok(
            "/commands",
            &json!({"type": "force_digital_input", "channel": channel, "value": value}),
        );
    };
    let advance = |ms: u64| {
        m.advance(&json!({"seconds": ms as f64 / 1e3}));
    };
    di(1, true);
    di(2, false);
    let (mut child, mut stdin, mut lines) = spawn_interactive(&exe, m.address("nmc"));
    assert_eq!(lines.next().unwrap().unwrap(), "watchdog");
    advance(10_000);
    writeln!(stdin).unwrap();
    assert_eq!(lines.next().unwrap().unwrap(), "estop");
    advance(200);
    di(1, false);
    advance(5_000);
    writeln!(stdin).unwrap();
    assert_eq!(lines.next().unwrap().unwrap(), "estop2");
    advance(100);
    di(2, true);
    advance(5_000);
    writeln!(stdin).unwrap();
    let rest: Vec<String> = lines.map_while(Result::ok).collect();
    assert_eq!(rest.last().map(String::as_str), Some("ok"), "{rest:?}");
    assert!(child.wait().unwrap().success());
}

/// S-FOLLOW with TV59: the slave waits for the master to cross 50000, then 40000 per 60000.
#[test]
fn s_follow_tv59() {
    example("s_follow.c");
}

/// PTP compare, PT parameters read back, the 2-D status alias, the damping compensation.
#[test]
fn ptp_compare_pt_para_and_aliases() {
    example("ax_extras.c");
}

/// Closed loop and profile configuration: PID sets, DAC, TV67, TV70, the encoder coefficient.
#[test]
fn closed_loop_and_profile_config_tv67_tv70() {
    example("closed_loop.c");
}

/// NMC_SaveMotionConfig: saved, reloaded by NMC_DevReset, and there after mcemu restarts on the
/// same state directory.
#[test]
fn saved_motion_config_survives_a_restart() {
    let state = save_then_check_across_a_restart("motion_config.c");
    assert!(state.join("nmc/nmc.json").is_file());
}

/// Compile `name`, run it as `name save` against one mcemu on a fresh state directory and as
/// `name check` against a second one started on the same directory after the first exited
/// cleanly; each run must end with `ok`. Returns the state directory.
fn save_then_check_across_a_restart(name: &str) -> PathBuf {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), &format!("nmc-{name}"));
    let exe = compile_example(name, &dir, &[]);
    let state = dir.join("state");
    let state_arg = state.to_str().unwrap();
    for mode in ["save", "check"] {
        let m = Mcemu::start(Some(&gaochuan()), &["--state-dir", state_arg]);
        let mut command = Command::new(&exe);
        command.arg(mode).env("MCEMU_NMC", m.address("nmc"));
        let out = run_with_timeout(command, b"", PROGRAM_TIMEOUT);
        let stdout = String::from_utf8_lossy(&out.stdout).to_string();
        assert!(
            out.status.success() && stdout.lines().last() == Some("ok"),
            "{}",
            output_report(mode, &out)
        );
        let exit = m.terminate();
        assert!(exit.status.success(), "{exit:?}");
    }
    state
}

/// The user parameter areas (digest 001 §2.20, non-volatile): written by one mcemu, read back
/// from a restarted one on the same state directory.
#[test]
fn user_parameter_areas_survive_a_restart() {
    let state = save_then_check_across_a_restart("user_para_restart.c");
    assert_eq!(
        std::fs::metadata(state.join("nmc/nmc.user_para_ex.bin"))
            .unwrap()
            .len(),
        32768
    );
}

/// Buffered I/O, stops and packs, advanced buffered I/O (digest 001 §2.7, §3.11, §3.12): the
/// program checks the outputs, counts and stops in path order; here DI3 and DI4 are high
/// before it starts (its buffered E-stop inputs) and DA 0 holds what `NMC_CrdBufOut` wrote
/// (16384 raw on ±10 V: 5 V) once it has finished.
#[test]
fn crd_buffered_io_stops_and_packs() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-crd-buf-io");
    let exe = compile_example("crd_buf_io.c", &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), &["--clock", "scaled:5"]);
    for channel in [3, 4] {
        m.post_ok(
            "/commands",
            &json!({"type": "force_digital_input", "channel": channel, "value": true}),
        );
    }
    let out = run_example(&exe, m.address("nmc"));
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success() && stdout.lines().last() == Some("ok"),
        "{}",
        output_report("crd_buf_io.c", &out)
    );
    let ao = m.state()["io"]["ao"][0].as_f64().unwrap();
    assert!((ao - 5.0).abs() < 1e-3, "DA 0 = {ao} V");
}

/// TV27, TV28, TV31, TV32, TV65: UpdateMulti in one cycle, Pack8's offsets, safeLen, TryHome,
/// the 125 µs clock against the controller's loop count.
#[test]
fn tv27_tv28_tv31_tv32_tv65_moves_homing_clock() {
    example("tv_motion.c");
}

/// TV21, TV23, TV24, TV26, TV40 on inputs this harness forces: the program prints
/// `post {json}` lines, each posted to the control API and answered `done`.
#[test]
fn tv21_tv23_tv24_tv26_tv40_forced_inputs() {
    let dir = fresh_dir(env!("CARGO_TARGET_TMPDIR"), "nmc-tv-inputs");
    let exe = compile_example("tv_inputs.c", &dir, &[]);
    let m = Mcemu::start(Some(&gaochuan()), &[]);
    let (mut child, mut stdin, lines) = spawn_interactive(&exe, m.address("nmc"));
    let mut last = String::new();
    for line in lines {
        let line = line.unwrap();
        if let Some(body) = line.strip_prefix("post ") {
            let body: serde_json::Value = serde_json::from_str(body).unwrap();
            m.post_ok("/commands", &body);
            writeln!(stdin, "done").unwrap();
        }
        last = line;
    }
    let status = child.wait().unwrap();
    assert!(
        status.success() && last == "ok",
        "exit {status}, last line {last:?}"
    );
}
