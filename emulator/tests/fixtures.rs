//! The machine fixtures (`fixtures/*.toml`): each validates through the real binary, loads into a
//! running engine with the values it promises, and moves and homes as the machine would. And the
//! config errors: each class gives its message (file, key path, reason) and a non-zero exit.

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command as Process, Output};

use axes::command::Reply;
use axes::config::PlantModel;
use axes::{AxisFlags, AxisState, AxisStatus, Command, Engine, ParamId};
use mcemu::config::Config;
use serde_json::json;

/// Every machine config in `fixtures/`; a new one must be added here (and tested below).
const FIXTURES: &[&str] = &[
    "cia402-can.toml",
    "cpu226h.toml",
    "default.toml",
    "gaochuan-gcn.toml",
    "gaochuan-gcn-ecat.toml",
    "himc.toml",
    "hollysys-mc.toml",
];

fn fixtures_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures")
}

fn mcemu(args: &[&str]) -> Output {
    Process::new(env!("CARGO_BIN_EXE_mcemu"))
        .args(args)
        .output()
        .expect("run mcemu")
}

#[test]
fn every_fixture_is_listed_here() {
    let found: BTreeSet<String> = std::fs::read_dir(fixtures_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    let listed: BTreeSet<String> = FIXTURES.iter().map(|s| s.to_string()).collect();
    assert_eq!(found, listed);
}

#[test]
fn every_fixture_validates_through_the_binary() {
    for name in FIXTURES {
        let path = fixtures_dir().join(name);
        let out = mcemu(&["validate", path.to_str().unwrap()]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(stdout.contains(": ok ("), "{name}: {stdout}");
    }
}

#[test]
fn the_cia402_can_fixture_puts_each_drive_on_the_bus_with_the_shipped_eds() {
    let path = fixtures_dir().join("cia402-can.toml");
    let config = Config::load(&path).unwrap();
    let specs = mcemu::canopen::node_specs(&config, path.to_str().unwrap()).unwrap();
    let nodes: Vec<(u8, usize)> = specs
        .drives
        .iter()
        .map(|s| (s.config.node_id, s.slave))
        .collect();
    assert_eq!(nodes, [(1, 0), (2, 1), (3, 2), (4, 3)]);
    assert!(specs.mapped.is_empty());
    for s in &specs.drives {
        // The EDS brings the CiA 402 pre-defined PDO mapping: TPDO1 = statusword.
        let tpdo1 = s
            .objects
            .iter()
            .find(|d| d.index == 0x1A00 && d.subindex == 1);
        assert_eq!(
            tpdo1.map(|d| d.default.clone()),
            Some(axes::od::Value::U32(0x6041_0010)),
            "node {}",
            s.config.node_id
        );
    }
}

#[test]
fn the_cpu226h_fixture_puts_its_can_e10_on_the_bus_over_the_e10_map() {
    let path = fixtures_dir().join("cpu226h.toml");
    let config = Config::load(&path).unwrap();
    let c = config.frontends.canopen.as_ref().unwrap();
    assert!(c.enabled);
    let specs = mcemu::canopen::node_specs(&config, path.to_str().unwrap()).unwrap();
    assert!(specs.drives.is_empty());
    let [e10] = specs.mapped.as_slice() else {
        panic!("one map-backed node expected");
    };
    assert_eq!(
        (e10.config.node_id, e10.axis),
        (2, 5),
        "node 2 = axis e10_can"
    );
    assert_eq!(e10.map.name, "ct-e10-servo");
    let register = |index: u16| {
        e10.backed
            .iter()
            .find(|b| b.index == index)
            .map(|b| b.register)
    };
    // P282 control word, R204 output state, P290 given position, P113 ramps.
    assert_eq!(register(0x211A), Some(282));
    assert_eq!(register(0x20CC), Some(204));
    assert_eq!(register(0x2122), Some(290));
    assert_eq!(register(0x2071), Some(113));
}

#[test]
fn the_embedded_default_machine_is_the_default_fixture() {
    let file = Config::load(&fixtures_dir().join("default.toml")).unwrap();
    assert_eq!(file, Config::default_machine().unwrap());
}

// ---- loading and running ------------------------------------------------------------------------

fn load(name: &str) -> (Config, Engine) {
    let config = Config::load(&fixtures_dir().join(name)).unwrap();
    let engine = Engine::new(&config.engine_config()).unwrap();
    assert_eq!(engine.axis_count(), config.axes.len());
    (config, engine)
}

fn command(e: &mut Engine, c: serde_json::Value) -> Reply {
    let c: Command = serde_json::from_value(c.clone()).unwrap_or_else(|err| panic!("{c}: {err}"));
    e.apply(c.clone())
        .unwrap_or_else(|err| panic!("{c:?} refused: {err}"))
}

fn status(e: &Engine, axis: usize) -> AxisStatus {
    e.axis_status(axis).unwrap()
}

fn param(e: &Engine, axis: usize, id: ParamId) -> f64 {
    e.axis(axis).unwrap().params().get(id)
}

/// Step until `done` holds, at most `seconds` of engine time; the ticks it took.
fn run_until(e: &mut Engine, seconds: f64, mut done: impl FnMut(&Engine) -> bool) -> Option<u64> {
    let ticks = (seconds / e.period()).ceil() as u64;
    for t in 1..=ticks {
        e.step();
        if done(e) {
            return Some(t);
        }
    }
    None
}

fn run(e: &mut Engine, seconds: f64) {
    let _ = run_until(e, seconds, |_| false);
}

fn healthy(s: &AxisStatus) -> bool {
    s.state != AxisState::ErrorStop
        && !s
            .flags
            .intersects(AxisFlags::FE_FAULT | AxisFlags::DRIVE_ALARM | AxisFlags::ENCODER_LOSS)
}

fn enable(e: &mut Engine, axis: usize) {
    command(e, json!({ "type": "enable", "axis": axis }));
    assert!(
        run_until(e, 0.5, |e| status(e, axis)
            .flags
            .contains(AxisFlags::ENABLED))
        .is_some(),
        "axis {axis} did not enable"
    );
}

/// Move `axis` to `target` with its own parameters; it must arrive and stay healthy. Returns the
/// final status after `settle` seconds more.
fn move_to(e: &mut Engine, axis: usize, target: f64, settle: f64) -> AxisStatus {
    command(
        e,
        json!({ "type": "move_absolute", "axis": axis, "position": target }),
    );
    let done = run_until(e, 60.0, |e| {
        let s = status(e, axis);
        s.state == AxisState::Standstill && s.fifo_len == 0 || !healthy(&s)
    });
    let s = status(e, axis);
    assert!(done.is_some(), "axis {axis} still moving: {s:?}");
    assert!(healthy(&s), "axis {axis}: {s:?}");
    run(e, settle);
    status(e, axis)
}

/// Home `axis` with its own `home_*` parameters; it must succeed.
fn home(e: &mut Engine, axis: usize) -> AxisStatus {
    command(e, json!({ "type": "home", "axis": axis }));
    let done = run_until(e, 120.0, |e| {
        let s = status(e, axis);
        s.state != AxisState::Homing && s.fifo_len == 0
    });
    let s = status(e, axis);
    assert!(done.is_some(), "axis {axis} still homing: {s:?}");
    assert!(s.flags.contains(AxisFlags::HOMED), "axis {axis}: {s:?}");
    assert!(healthy(&s), "axis {axis}: {s:?}");
    s
}

/// The GCN400E-xA: local pulse axes 0, 1 and engine-mastered drives on axes 2, 3 (the NMC
/// card's 16, 17); the drives power their axes and home with the manual's method 21 on the home
/// sensor at −3000 (digest 001 §3.14, C5§4(2)), the home point reading 0.
#[test]
fn gaochuan_gcn400e_ecat() {
    let (config, mut e) = load("gaochuan-gcn-ecat.toml");
    assert_eq!(config.axes.len(), 4);
    assert_eq!(config.drives.len(), 2);
    let nmc = config.frontends.nmc.as_ref().map(|n| n.device.io_slaves);
    assert_eq!(nmc, Some(1));
    for axis in 2..4 {
        enable(&mut e, axis);
        let s = move_to(&mut e, axis, 2000.0, 0.01);
        assert!((s.act_pos - 2000.0).abs() < 1.0, "{s:?}");
        let s = home(&mut e, axis);
        assert!(
            s.cmd_pos.abs() < 50.0,
            "rests just past the home point: {s:?}"
        );
    }
}

#[test]
fn default_machine() {
    let (config, mut e) = load("default.toml");
    assert_eq!(config.axes.len(), 4);
    assert_eq!(config.machine.period, 1e-3);
    for axis in 0..4 {
        assert_eq!(param(&e, axis, ParamId::AxisType), 10.0);
        assert_eq!(param(&e, axis, ParamId::RepMode), 0.0);
        enable(&mut e, axis);
    }
    let s = move_to(&mut e, 0, 100.0, 0.0);
    assert_eq!(s.cmd_pos, 100.0);
    assert_eq!(s.pulses, 100_000);
}

#[test]
fn hollysys_mc1008() {
    let (config, mut e) = load("hollysys-mc.toml");
    // 8 direct axes and a virtual result axis (digest 000 §1.1).
    assert_eq!(config.axes.len(), 9);
    let types: Vec<f64> = (0..9).map(|a| param(&e, a, ParamId::AxisType)).collect();
    assert_eq!(types, [10.0, 10.0, 10.0, 10.0, 20.0, 20.0, 20.0, 20.0, 0.0]);
    for axis in 0..8 {
        // The HMC's limit behaviour and overshoot quirk on every real axis.
        assert_eq!(param(&e, axis, ParamId::LimitLatch), 0.0);
        assert_eq!(param(&e, axis, ParamId::LimitDecelMode), 1.0);
        assert_eq!(param(&e, axis, ParamId::OvershootMode), 1.0);
        assert_eq!(config.axes[axis].fifo_depth, Some(64));
    }
    for axis in [0, 1, 2, 4, 5, 6] {
        assert_eq!(param(&e, axis, ParamId::RepMode), 0.0, "axis {axis}");
    }
    for axis in 4..8 {
        assert_eq!(param(&e, axis, ParamId::ServoLoop), 1.0);
        assert_eq!(config.axes[axis].plant.model, PlantModel::PositionLoop);
    }
    // Ks/Ke of digest 000 §8.7 ex. 51/52 on the rotary axis.
    assert_eq!(param(&e, 3, ParamId::KsNumerator), 8192.0);
    assert_eq!(param(&e, 3, ParamId::KsDenominator), 360.0);
    assert_eq!(param(&e, 3, ParamId::KeNumerator), 360.0);
    assert_eq!(param(&e, 8, ParamId::RepMode), 2.0);

    for axis in 0..9 {
        enable(&mut e, axis);
    }
    // A stepper: 50 mm is 50 000 pulses (digest 000 §8.7 ex. 50).
    let s = move_to(&mut e, 0, 50.0, 0.0);
    assert_eq!((s.cmd_pos, s.pulses), (50.0, 50_000));
    // The rotary axis: 180° is 4096 pulses (ex. 51); 540° wraps to 180°.
    let s = move_to(&mut e, 3, 180.0, 0.0);
    assert_eq!(s.pulses, 4096);
    // An analog servo closes the loop: it follows within its FELimit and settles on the target.
    command(
        &mut e,
        json!({ "type": "move_absolute", "axis": 4, "position": 200.0 }),
    );
    let mut worst_fe: f64 = 0.0;
    run_until(&mut e, 5.0, |e| {
        let s = status(e, 4);
        worst_fe = worst_fe.max(s.following_error.abs());
        s.state == AxisState::Standstill
    })
    .unwrap();
    // Well inside FELimit = 2 mm (≈ 0.32 mm at 3000 mm/s² through the 2 ms velocity loop).
    assert!(worst_fe < 0.5, "FE reached {worst_fe} mm");
    run(&mut e, 0.2);
    let s = status(&e, 4);
    assert!(healthy(&s), "{s:?}");
    assert!((s.act_pos - 200.0).abs() < 0.005, "{}", s.act_pos);
    assert!(s.dac_out.abs() <= 32767.0);
    // The conveyor wraps at its 600 mm pitch.
    let s = move_to(&mut e, 7, 700.0, 0.3);
    assert!((s.act_pos - 100.0).abs() < 0.01, "{}", s.act_pos);
    // Homing with HMC mode 1 (CiA 402 21) on x and on a servo.
    home(&mut e, 0);
    home(&mut e, 5);
}

#[test]
fn gaochuan_gcn400() {
    let (config, mut e) = load("gaochuan-gcn.toml");
    assert_eq!(config.axes.len(), 4);
    for axis in 0..4 {
        // Pulse units and the NMC defaults of a fresh axis (digest 001 TV05–TV07).
        assert_eq!(param(&e, axis, ParamId::Units), 1.0);
        assert_eq!(param(&e, axis, ParamId::DriveAlarmEnable), 0.0);
        assert_eq!(param(&e, axis, ParamId::LimitLatch), 1.0);
        assert_eq!(param(&e, axis, ParamId::FsLimit), 2147483647.0);
        assert_eq!(param(&e, axis, ParamId::RsLimit), -2147483647.0);
        assert_eq!(param(&e, axis, ParamId::FastDecel), 32767.0 * 1e6);
        assert_eq!(param(&e, axis, ParamId::MaxVelocity), 32767.0 * 1e3);
        assert_eq!(param(&e, axis, ParamId::MaxAccel), 32767.0 * 1e6);
        assert_eq!(param(&e, axis, ParamId::FeLimit), 0.0);
        assert_eq!(param(&e, axis, ParamId::InPositionWindow), 0.0);
        enable(&mut e, axis);
    }
    // The alarm input is off: an alarm does not fault the axis.
    command(
        &mut e,
        json!({ "type": "force_input", "axis": 2, "input": "drive_alarm", "value": true }),
    );
    run(&mut e, 0.01);
    let s = status(&e, 2);
    assert!(
        s.state != AxisState::ErrorStop && s.flags.contains(AxisFlags::ENABLED),
        "{s:?}"
    );
    command(
        &mut e,
        json!({ "type": "force_input", "axis": 2, "input": "drive_alarm" }),
    );
    // 100 000 pulses on the servo axis (which follows with a lag) and the stepper.
    let s = move_to(&mut e, 0, 100_000.0, 0.1);
    assert_eq!(s.pulses, 100_000);
    assert_eq!(s.encoder_counts, 100_000);
    let s = move_to(&mut e, 2, 50_000.0, 0.0);
    assert_eq!(s.pulses, 50_000);
    home(&mut e, 1);
}

#[test]
fn cpu226h_with_its_e10_drives() {
    let (config, mut e) = load("cpu226h.toml");
    // 4 pulse axes and the two E10 drives the PLC talks to.
    assert_eq!(config.axes.len(), 6);
    for axis in 0..4 {
        assert_eq!(config.axes[axis].pulse.max_frequency, 200_000.0);
        assert_eq!(param(&e, axis, ParamId::Units), 1.0);
        assert_eq!(param(&e, axis, ParamId::StartVelocity), 500.0);
        assert!(param(&e, axis, ParamId::AccelTime) > 0.0);
    }
    for axis in 4..6 {
        assert_eq!(param(&e, axis, ParamId::AxisType), 40.0);
    }
    for axis in 0..6 {
        enable(&mut e, axis);
    }
    // MIN_SPEED/MAX_SPEED/TA: 60 000 pulses at 20 kHz after a 0.1 s ramp.
    let s = move_to(&mut e, 0, 60_000.0, 0.0);
    assert_eq!(s.pulses, 60_000);
    // 200 kHz is the ceiling of the pulse outputs, whatever the command asks.
    command(
        &mut e,
        json!({ "type": "move_relative", "axis": 3, "distance": 3000.0,
                "velocity": 300000.0, "acceleration": 1e9, "deceleration": 1e9 }),
    );
    let mut fastest: f64 = 0.0;
    run_until(&mut e, 1.0, |e| {
        let s = status(e, 3);
        fastest = fastest.max(s.pulse_frequency.abs());
        s.state == AxisState::Standstill && s.pulses == 3000
    })
    .unwrap();
    assert_eq!(fastest, 200_000.0);
    // The E10s: a speed-controlled one and a position-controlled one.
    command(
        &mut e,
        json!({ "type": "move_velocity", "axis": 4, "velocity": 500000.0 }),
    );
    run(&mut e, 0.5);
    let s = status(&e, 4);
    assert!(healthy(&s), "{s:?}");
    assert!((s.cmd_vel - 500_000.0).abs() < 1e-6, "{}", s.cmd_vel);
    let s = move_to(&mut e, 5, 100_000.0, 0.1);
    assert!((s.act_pos - 100_000.0).abs() < 1.0, "{}", s.act_pos);
    // MC_HOMING mode 3 (CiA 402 21).
    home(&mut e, 1);
    // 14 inputs; the Z pulse of axis 0 (once per 1000 pulses) shows on I0.2 = DI 2.
    assert_eq!(e.io().di.len(), 14);
    move_to(&mut e, 0, 60_500.0, 0.002);
    assert!(!e.io().di[2]);
    move_to(&mut e, 0, 60_000.0, 0.002);
    assert!(e.io().di[2]);
}

#[test]
fn himc_in_mm_and_deg() {
    let (config, mut e) = load("himc.toml");
    assert_eq!(config.axes.len(), 4);
    assert_eq!(config.drives.len(), 4);
    // The rollover axis is cyclic on [0, 360) (SetRollover).
    assert_eq!(param(&e, 3, ParamId::Rollover), 360.0);
    assert_eq!(param(&e, 3, ParamId::RepMode), 1.0);
    assert_eq!(param(&e, 3, ParamId::RepDist), 360.0);
    for axis in 0..4 {
        // HIMC homing defaults (digest 004 §4.2).
        assert_eq!(param(&e, axis, ParamId::HomeMethod), 33.0);
        assert_eq!(param(&e, axis, ParamId::HomeSwitchVelocity), 20.0);
        assert_eq!(param(&e, axis, ParamId::HomeZeroVelocity), 5.0);
        assert_eq!(param(&e, axis, ParamId::HomeAcceleration), 2000.0);
        assert_eq!(param(&e, axis, ParamId::HomeTimeout), 120.0);
        assert_eq!(param(&e, axis, ParamId::AxisType), 50.0);
        assert!(param(&e, axis, ParamId::InPositionWindow) > 0.0);
        assert!(param(&e, axis, ParamId::InPositionTime) > 0.0);
        // Enable goes through the drive's state machine (engine-mastered CiA 402 drives).
        enable(&mut e, axis);
        assert!(e.drive_of(axis).is_some());
    }
    for axis in 0..3 {
        assert_eq!(param(&e, axis, ParamId::SwLimitRejectTargets), 1.0);
    }
    // A move in mm, in position within the window.
    let s = move_to(&mut e, 0, 250.0, 0.05);
    assert!((s.act_pos - 250.0).abs() < 0.01, "{}", s.act_pos);
    assert!(s.flags.contains(AxisFlags::IN_POSITION), "{s:?}");
    // A target beyond the software right limit is refused up front.
    let c: Command =
        serde_json::from_value(json!({ "type": "move_absolute", "axis": 0, "position": 600.0 }))
            .unwrap();
    assert!(e.apply(c).is_err());
    // 450° on the rollover axis ends at 90°.
    let s = move_to(&mut e, 3, 450.0, 0.05);
    assert!((s.act_pos - 90.0).abs() < 0.01, "{}", s.act_pos);
    // HOME_METHOD_33: the index, searching negative.
    home(&mut e, 1);
}

// ---- config errors through the binary --------------------------------------------------------

/// A config file in a private temporary directory, removed on drop.
struct TempConfig {
    dir: PathBuf,
    path: PathBuf,
}

impl TempConfig {
    fn new(name: &str, text: &str) -> TempConfig {
        let dir =
            std::env::temp_dir().join(format!("mcemu-fixtures-test-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, text).unwrap();
        TempConfig { dir, path }
    }

    fn path(&self) -> &str {
        self.path.to_str().unwrap()
    }
}

impl Drop for TempConfig {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// `mcemu validate` on `text`: it must fail, and its message name the file and contain `parts`.
fn refused(name: &str, text: &str, parts: &[&str]) -> String {
    let file = TempConfig::new(name, text);
    let out = mcemu(&["validate", file.path()]);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "{name}: accepted");
    assert_ne!(out.status.code(), Some(0));
    assert!(stderr.contains(file.path()), "{name}: {stderr}");
    for part in parts {
        assert!(stderr.contains(part), "{name}: no `{part}` in {stderr}");
    }
    stderr
}

#[test]
fn an_unreadable_file_is_named() {
    let missing = std::env::temp_dir().join("mcemu-fixtures-test-no-such-file.toml");
    let out = mcemu(&["validate", missing.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains(missing.to_str().unwrap()), "{stderr}");
    assert!(stderr.contains("cannot read it"), "{stderr}");
}

#[test]
fn a_toml_syntax_error_shows_line_and_column() {
    refused(
        "syntax",
        "[machine]\nname = \"m\"\nperiod = = 0.001\n",
        &["TOML parse error", "line 3", "column"],
    );
}

#[test]
fn an_unknown_key_is_named_by_its_path() {
    refused(
        "unknown-key",
        "[[axes]]\n[[axes]]\nfifo_dept = 3\n",
        &["axes[1].fifo_dept", "unknown field"],
    );
    refused(
        "unknown-parameter",
        "[[axes]]\n[axes.params]\nSpeeed = 3\n",
        &["axes[0].params", "unknown parameter `Speeed`"],
    );
}

#[test]
fn a_wrong_type_is_named_by_its_path() {
    refused(
        "wrong-type",
        "[machine]\nperiod = \"fast\"\n",
        &["machine.period", "invalid type"],
    );
    refused(
        "wrong-type-nested",
        "[[axes]]\n[axes.pulse]\nmax_frequency = true\n",
        &["axes[0].pulse.max_frequency", "invalid type"],
    );
}

#[test]
fn a_bad_parameter_value_gives_name_value_and_reason() {
    refused(
        "bad-parameter",
        "[[axes]]\n[axes.params]\nAccel = -3\n",
        &[
            "axes[0].params.accel",
            "`accel` = -3",
            "must be greater than 0",
        ],
    );
    refused(
        "bad-enum",
        "[[axes]]\n[axes.params]\nrep_mode = \"circular\"\n",
        &["axes[0].params", "must be one of finite"],
    );
}

#[test]
fn a_cross_field_error_names_the_key() {
    refused(
        "limits",
        "[[axes]]\n[axes.switches.limit_pos]\nposition = -10\n[axes.switches.limit_neg]\nposition = 10\n",
        &["axes[0].switches.limit_pos.position", "must be above the negative limit"],
    );
    refused(
        "plant",
        "[[axes]]\n[axes.params]\naxis_type = \"servo_analog\"\n",
        &["axes[0].plant.model", "position_loop"],
    );
    refused(
        "drive",
        "[[axes]]\n[[drives]]\naxis = 3\n",
        &["drives[0].axis", "does not exist"],
    );
}

#[test]
fn a_period_out_of_range_is_refused() {
    refused(
        "period",
        "[machine]\nperiod = 0.02\n",
        &["machine.period", "outside"],
    );
    refused(
        "period-short",
        "[machine]\nperiod = 1e-6\n",
        &["machine.period", "outside"],
    );
}

#[test]
fn a_fault_that_cannot_apply_to_its_transport_is_refused() {
    refused(
        "fault",
        "[[axes]]\n[frontends.modbus_tcp]\nenabled = false\n\
         [[frontends.modbus_tcp.faults]]\nfault = \"corrupt\"\nbit = 1\n",
        &["frontends.modbus_tcp.faults[0]", "RTU"],
    );
}

#[test]
fn one_bad_file_fails_the_run_and_the_others_are_still_checked() {
    let bad = TempConfig::new("mixed", "[machine]\nperiod = 1.0\n");
    let good = fixtures_dir().join("himc.toml");
    let out = mcemu(&["validate", good.to_str().unwrap(), bad.path()]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("himc.toml: ok"));
    assert!(String::from_utf8_lossy(&out.stderr).contains("machine.period"));
}
