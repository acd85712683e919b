//! `mcemu scenario` end to end: the real binary, its exit status, its messages, and the physics
//! of its traces checked from the CSV alone.

// Test helpers: failing loudly is the point.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const FIXTURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../fixtures");

fn mcemu(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mcemu"))
        .args(args)
        .output()
        .expect("run mcemu")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("scenario-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn fixture(name: &str) -> String {
    format!("{FIXTURES}/scenarios/{name}")
}

/// Relative tolerance of the limit checks: the planner's own numeric tolerance is far below.
const REL: f64 = 1e-9;
/// Absolute slack for the same checks (values near 0).
const ABS: f64 = 1e-9;

fn within(value: f64, limit: f64) -> bool {
    value.abs() <= limit * (1.0 + REL) + ABS
}

/// One trace row.
#[derive(Clone, Debug)]
struct Row {
    time: f64,
    state: String,
    cmd_pos: f64,
    cmd_vel: f64,
    cmd_acc: f64,
    act_pos: f64,
    pulses: i64,
    encoder_counts: i64,
    limit_pos: bool,
    homed: bool,
    error: String,
}

/// The trace as rows per axis, after checking its shape: the header, every axis at every tick
/// from 0 on, the ticks evenly spaced.
fn read_trace(path: &Path, axes: usize) -> Vec<Vec<Row>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(mcemu::trace::HEADER));
    let mut per_axis = vec![Vec::new(); axes];
    for (n, line) in lines.enumerate() {
        let c: Vec<&str> = line.split(',').collect();
        assert_eq!(c.len(), 36, "line {n}: {line}");
        let f = |i: usize| -> f64 { c[i].parse().unwrap_or_else(|_| panic!("{line}")) };
        let int = |i: usize| -> i64 { c[i].parse().unwrap_or_else(|_| panic!("{line}")) };
        let flag = |i: usize| match c[i] {
            "0" => false,
            "1" => true,
            other => panic!("flag `{other}` in {line}"),
        };
        let axis: usize = c[1].parse().unwrap();
        assert_eq!(axis, n % axes, "rows go axis by axis: {line}");
        per_axis[axis].push(Row {
            time: f(0),
            state: c[2].to_string(),
            cmd_pos: f(3),
            cmd_vel: f(4),
            cmd_acc: f(5),
            act_pos: f(6),
            pulses: int(9),
            encoder_counts: int(10),
            limit_pos: flag(11),
            homed: flag(14),
            error: c[15].to_string(),
        });
    }
    for rows in &per_axis {
        assert_eq!(rows[0].time, 0.0, "the trace starts at tick 0");
        for (k, r) in rows.iter().enumerate() {
            assert!(
                (r.time - k as f64 * 1e-3).abs() < 1e-12,
                "tick {k} at {}",
                r.time
            );
        }
    }
    per_axis
}

/// Checks that hold for any commanded motion with limits `v`, `a` (|v| growing) and `d` (|v|
/// shrinking), on the trace's own columns and on finite differences of them (mean values over
/// a tick cannot exceed the bound either). Returns the peaks seen (|v|, |a|, |Δa|/dt).
fn check_limits(rows: &[Row], dt: f64, v: f64, a: f64, d: f64, what: &str) -> (f64, f64, f64) {
    let (mut v_peak, mut a_peak, mut j_peak) = (0.0f64, 0.0f64, 0.0f64);
    for w in rows.windows(2) {
        let (p, r) = (&w[0], &w[1]);
        let t = r.time;
        assert!(
            within(r.cmd_vel, v),
            "{what} at {t}: |v| = {} > {v}",
            r.cmd_vel
        );
        let speeding_up = r.cmd_vel * r.cmd_acc > 0.0;
        let limit = if speeding_up { a } else { d };
        assert!(
            within(r.cmd_acc, limit),
            "{what} at {t}: |a| = {} > {limit}",
            r.cmd_acc
        );
        let mean_v = (r.cmd_pos - p.cmd_pos) / dt;
        assert!(within(mean_v, v), "{what} at {t}: Δp/dt = {mean_v} > {v}");
        let mean_a = (r.cmd_vel - p.cmd_vel) / dt;
        let limit = if r.cmd_vel.abs() > p.cmd_vel.abs() {
            a
        } else {
            d
        };
        assert!(
            within(mean_a, limit),
            "{what} at {t}: Δv/dt = {mean_a} > {limit}"
        );
        v_peak = v_peak.max(r.cmd_vel.abs());
        a_peak = a_peak.max(r.cmd_acc.abs());
        j_peak = j_peak.max(((r.cmd_acc - p.cmd_acc) / dt).abs());
    }
    (v_peak, a_peak, j_peak)
}

#[test]
fn physics_of_a_trapezoid_an_s_curve_a_limit_stop_and_a_homing_run() {
    let dir = scratch("physics");
    let trace = dir.join("physics.csv");
    let out = mcemu(&[
        "scenario",
        &fixture("physics.toml"),
        "--trace",
        trace.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("ok: 19 steps, 7 expectations, 0 failures"),
        "{stdout}"
    );
    let axes = read_trace(&trace, 4);
    let dt = 1e-3;

    // Axis 0: trapezoid to 200 mm, v 80, a 400, d 800 (jerk 0: acceleration steps are allowed).
    let x = &axes[0];
    let (v, a, _) = check_limits(x, dt, 80.0, 400.0, 800.0, "trapezoid");
    assert!(
        v >= 80.0 - 1e-9 && a >= 800.0 - 1e-9,
        "the move reached its limits: {v} {a}"
    );
    let last = x.last().unwrap();
    assert_eq!(
        (last.cmd_pos, last.act_pos),
        (200.0, 200.0),
        "target reached exactly"
    );
    assert_eq!((last.pulses, last.encoder_counts), (200_000, 200_000));
    let arrived = x.iter().position(|r| r.cmd_pos == 200.0).unwrap();
    assert!(x[arrived..]
        .iter()
        .all(|r| r.cmd_pos == 200.0 && r.cmd_vel.abs() < 1e-9));

    // Axis 1: S-curve −150 mm, v 60, a 300, jerk 3000: also |Δa|/dt ≤ jerk.
    let y = &axes[1];
    let (v, a, j) = check_limits(y, dt, 60.0, 300.0, 300.0, "s-curve");
    assert!(within(j, 3000.0), "s-curve: |Δa/dt| = {j} > 3000");
    assert!(
        v >= 60.0 - 1e-9 && a >= 300.0 - 1e-9,
        "the move reached its limits: {v} {a}"
    );
    assert!(
        j >= 0.9 * 3000.0,
        "jerk-limited, and the jerk was used: {j}"
    );
    let last = y.last().unwrap();
    assert_eq!(
        (last.cmd_pos, last.act_pos),
        (-150.0, -150.0),
        "target reached exactly"
    );
    assert_eq!(last.pulses, -150_000);

    // Axis 2: moves and a jog within v 200, a 1000, until the limit switch at 500 mm; the limit
    // stop brakes with max(fast_decel, decel) = 10 000 mm/s² (docs/decisions.md).
    let z = &axes[2];
    let a_stop = 10_000.0;
    let hit = z
        .iter()
        .position(|r| r.limit_pos)
        .expect("the limit was reached");
    check_limits(&z[..hit], dt, 200.0, 1000.0, 1000.0, "approach");
    let (p_hit, v_hit) = (z[hit].act_pos, z[hit].cmd_vel);
    assert!(
        p_hit >= 500.0 && v_hit > 0.0,
        "hit at {p_hit} moving {v_hit}"
    );
    let rest = hit + z[hit..].iter().position(|r| r.cmd_vel == 0.0).unwrap();
    let stop = &z[hit..=rest];
    check_limits(stop, dt, v_hit, 0.0, a_stop, "limit stop");
    let t_stop = z[rest].time - z[hit].time;
    assert!(
        t_stop <= v_hit / a_stop + 2.0 * dt,
        "stopped in {t_stop} s, v/a = {}",
        v_hit / a_stop
    );
    let stopping_distance = v_hit * v_hit / (2.0 * a_stop) + v_hit * dt;
    let p_rest = z[rest].cmd_pos;
    assert!(
        p_rest - p_hit <= stopping_distance + 1e-9,
        "stopped {} past the switch, stopping distance {stopping_distance}",
        p_rest - p_hit
    );
    for r in &z[rest..] {
        assert!(
            r.cmd_pos <= p_rest,
            "moved further into the limit at {}: {}",
            r.time,
            r.cmd_pos
        );
        assert!(
            r.cmd_vel <= 0.0,
            "moved further into the limit at {}",
            r.time
        );
    }
    assert!(z[rest].state == "standstill" && z[rest].error == "limit_reached");
    let last = z.last().unwrap();
    assert_eq!(last.act_pos, 400.0, "and moved out of it");
    assert!(!last.limit_pos);

    // Axis 3: to 3 mm, then method 34 (next index pulse going positive: 10 mm, every 10 000
    // counts) with offset 5, returning to the home point: homed, reading 5 at 10 000 counts.
    let h = &axes[3];
    // The user frame over the motor's (pulses are physical: 1000 per mm): it changes once, when
    // the home point is found, by offset − home point = 5 − 10 (to within one pulse).
    let frame = |r: &Row| r.cmd_pos - r.pulses as f64 / 1000.0;
    let shifts: Vec<usize> = (1..h.len())
        .filter(|&k| (frame(&h[k]) - frame(&h[k - 1])).abs() > 0.01)
        .collect();
    assert_eq!(shifts.len(), 1, "one redefinition: {shifts:?}");
    let home = shifts[0];
    let shift = frame(&h[home]) - frame(&h[home - 1]);
    assert!(
        (shift + 5.0).abs() <= 1e-3 + 1e-9,
        "frame shifted by {shift}"
    );
    // Within each frame, the homing moves keep to switch_velocity 20 and acceleration 500.
    let started = h.iter().position(|r| r.time >= 0.5).unwrap();
    check_limits(&h[started..home], dt, 20.0, 500.0, 500.0, "homing search");
    check_limits(&h[home..], dt, 20.0, 500.0, 500.0, "homing return");
    // Homed once the run is over (at rest at the home point), and from then on.
    assert!(h[..home].iter().all(|r| !r.homed));
    let homed = h.iter().position(|r| r.homed).expect("homed");
    assert_eq!(h[homed].state, "standstill");
    assert!(h[homed..].iter().all(|r| r.homed));
    let last = h.last().unwrap();
    assert_eq!(
        (last.act_pos, last.cmd_pos),
        (5.0, 5.0),
        "the home point reads the offset"
    );
    assert_eq!(
        (last.encoder_counts, last.pulses),
        (10_000, 10_000),
        "at the index pulse, 10 mm"
    );
}

#[test]
fn the_same_scenario_gives_the_same_trace() {
    let dir = scratch("determinism");
    let (a, b) = (dir.join("a.csv"), dir.join("b.csv"));
    for path in [&a, &b] {
        let out = mcemu(&[
            "scenario",
            &fixture("physics.toml"),
            "--trace",
            path.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let (a, b) = (std::fs::read(a).unwrap(), std::fs::read(b).unwrap());
    assert!(a.len() > 1_000_000);
    assert!(a == b, "traces differ");
}

#[test]
fn the_shipped_scenarios_pass() {
    for name in [
        "issue-example.toml",
        "inline-machine.toml",
        "coordinated-motion.toml",
        "hmc-result-axis.toml",
        "capture-compare.toml",
        "nmc-pt.toml",
        "superimpose-tangential.toml",
    ] {
        let out = mcemu(&["scenario", &fixture(name)]);
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        assert!(stderr(&out).is_empty(), "{name}: {}", stderr(&out));
    }
}

/// A scenario on the default machine with `steps` after the header.
fn write_scenario(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn on_default(end: f64, steps: &str) -> String {
    format!("config = \"{FIXTURES}/default.toml\"\nend = {end}\n{steps}")
}

#[test]
fn a_failed_expectation_exits_1_and_says_what_it_saw() {
    let dir = scratch("failing");
    let path = write_scenario(
        &dir,
        "failing.toml",
        &on_default(
            1.0,
            r#"
[[step]]
at = 0.0
command = { type = "enable", axis = 0 }
[[step]]
at = 0.0
command = { type = "move_absolute", axis = 0, position = 10.0 }
[[step]]
at = 0.05
expect = { axis = 0, state = "standstill", position = 10.0, tolerance = 1e-6 }
[[step]]
at = 0.9
expect = { axis = 0, position = 10.0, flags = ["homed"] }
[[step]]
at = 0.9
command = { type = "move_velocity", axis = 1, velocity = 5.0 }
"#,
        ),
    );
    let out = mcemu(&["scenario", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let err = stderr(&out);
    let file = path.display();
    for expected in [
        format!(
            "{file}: step[2] at 0.05 s: axis 0 state: expected standstill, saw discrete_motion"
        ),
        format!("{file}: step[2] at 0.05 s: axis 0 position: expected 10 ± 0.000001, saw "),
        format!("{file}: step[3] at 0.9 s: axis 0 flags: expected homed set, missing homed"),
        format!(
            "{file}: step[4] at 0.9 s: move_velocity refused (axis_disabled): axis 1 is disabled"
        ),
    ] {
        assert!(err.contains(&expected), "missing `{expected}` in:\n{err}");
    }
    assert_eq!(err.lines().count(), 4, "{err}");
    assert!(String::from_utf8_lossy(&out.stdout)
        .contains("FAILED: 5 steps, 2 expectations, 4 failures"));
}

#[test]
fn an_expected_refusal_that_does_not_come_fails() {
    let dir = scratch("refusal");
    let path = write_scenario(
        &dir,
        "refusal.toml",
        &on_default(
            0.1,
            r#"
[[step]]
at = 0.0
command = { type = "enable", axis = 0 }
expect_error = "axis_disabled"
"#,
        ),
    );
    let out = mcemu(&["scenario", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains(
            "step[0] at 0 s: enable: expected refusal axis_disabled, but it was accepted"
        ),
        "{}",
        stderr(&out)
    );
}

#[test]
fn scenarios_that_cannot_run_exit_2_with_file_key_and_reason() {
    let dir = scratch("errors");
    std::fs::write(dir.join("slow.toml"), "[machine]\nperiod = 0.5\n").unwrap();
    let enable = "[[step]]\nat = 0.0\ncommand = { type = \"enable\", axis = 0 }\n";
    let cases: Vec<(&str, String, String)> = vec![
        ("syntax.toml", "end = \n".into(), "TOML parse error".into()),
        (
            "missing-config.toml",
            "config = \"nowhere.toml\"\nend = 1.0\n".into(),
            "config: ".to_string() + &dir.join("nowhere.toml").display().to_string() + ": cannot read it",
        ),
        (
            "config-error.toml",
            "config = \"slow.toml\"\nend = 1.0\n".into(),
            "slow.toml: machine.period: 0.5 s is outside".into(),
        ),
        (
            "inline-config-error.toml",
            "end = 1.0\n[[axes]]\nfifo_dept = 3\n".into(),
            "axes[0].fifo_dept: ".into(),
        ),
        (
            "no-action.toml",
            on_default(1.0, "[[step]]\nat = 0.5\n"),
            "step[0]: no action: give one of `command`, `force` or `expect`".into(),
        ),
        (
            "two-actions.toml",
            on_default(
                1.0,
                "[[step]]\nat = 0.5\ncommand = { type = \"enable\", axis = 0 }\nforce = { di = 1, value = true }\n",
            ),
            "step[0]: 2 actions (command, force): a step has exactly one".into(),
        ),
        (
            "late.toml",
            on_default(1.0, &format!("{enable}[[step]]\nat = 1.5\nexpect = {{ di = 0, value = false }}\n")),
            "step[1].at: 1.5 s is after the end (1 s)".into(),
        ),
        (
            "negative.toml",
            on_default(1.0, "[[step]]\nat = -0.1\ncommand = { type = \"enable\", axis = 0 }\n"),
            "step[0].at: -0.1: must be a finite time ≥ 0 s".into(),
        ),
        (
            "unknown-axis.toml",
            on_default(1.0, "[[step]]\nat = 0.5\nexpect = { axis = 4, state = \"standstill\" }\n"),
            "step[0].expect.axis: axis 4 does not exist (the machine has 4 axes)".into(),
        ),
        (
            "bad-command.toml",
            on_default(1.0, "[[step]]\nat = 0.5\ncommand = { type = \"move_absolute\", axis = 0, positon = 1.0 }\n"),
            "step[0].command: ".into(),
        ),
        ("no-end.toml", format!("config = \"{FIXTURES}/default.toml\"\n"), "end: missing".into()),
    ];
    for (name, text, message) in &cases {
        let path = write_scenario(&dir, name, text);
        let out = mcemu(&["scenario", path.to_str().unwrap()]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.contains(&format!("mcemu: {}", path.display())),
            "{name} names the file: {err}"
        );
        assert!(
            err.contains(message.as_str()),
            "{name}: missing `{message}` in:\n{err}"
        );
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
    let out = mcemu(&["scenario", dir.join("absent.toml").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("absent.toml: cannot read it"));
    let out = mcemu(&[
        "scenario",
        &fixture("issue-example.toml"),
        "--trace",
        dir.join("no/such/dir/t.csv").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("cannot create the trace"),
        "{}",
        stderr(&out)
    );
}
