use super::*;

fn parse(text: &str) -> Result<Scenario, ScenarioError> {
    Scenario::parse(text, "s.toml", Path::new(""))
}

/// One stepper axis in mm, limits at ±500, 1 ms period.
const MACHINE: &str = r#"
[machine]
period = 0.001
[[axes]]
[axes.params]
axis_type = "stepper"
units = 1000
rep_mode = "finite"
speed = 100
accel = 1000
decel = 1000
[axes.switches.limit_pos]
position = 500
[axes.switches.limit_neg]
position = -500
"#;

fn with_machine(scenario: &str) -> String {
    // Top-level keys first: TOML puts keys after a table header into that table.
    format!("{scenario}\n{MACHINE}")
}

/// One `[[axes]]` table in mm (no switches) of the given `axis_type`, for machines of several.
fn mm_axis(axis_type: &str) -> String {
    format!(
        "[[axes]]\n[axes.params]\naxis_type = \"{axis_type}\"\nunits = 1000\nrep_mode = \"finite\"\nspeed = 100\naccel = 1000\ndecel = 1000\n"
    )
}

/// Runs the scenario and requires `expectations` checks, all met.
fn runs_clean(text: &str, expectations: usize) {
    let r = parse(text).unwrap().run(None).unwrap();
    assert_eq!(r.expectations, expectations);
    assert!(r.failures.is_empty(), "{:#?}", r.failures);
}

fn err(text: &str) -> ScenarioError {
    match parse(text) {
        Ok(s) => panic!("parsed: {s:?}"),
        Err(e) => e,
    }
}

#[test]
fn ticks_round_up_forgiving_rounding() {
    assert_eq!(tick_of(0.0, 1e-3), Ok(0));
    assert_eq!(tick_of(0.01, 1e-3), Ok(10));
    assert_eq!(tick_of(0.0105, 1e-3), Ok(11));
    assert_eq!(tick_of(0.3, 0.1), Ok(3));
    assert_eq!(tick_of(3600.0, 1e-3), Ok(3_600_000));
    assert_eq!(tick_of(1e9 * 0.1, 0.1), Ok(1_000_000_000));
    assert_eq!(tick_of(1e9 * 1e-3 + 1e-3, 1e-3), Ok(1_000_000_001));
    assert_eq!(tick_of(0.0015, 1e-3), Ok(2));
    assert!(tick_of(-1.0, 1e-3).is_err());
    assert!(tick_of(f64::NAN, 1e-3).is_err());
    assert!(tick_of(1e12, 1e-3).is_err());
}

#[test]
fn an_inline_scenario_parses_in_execution_order() {
    let s = parse(&with_machine(
        r#"
end = 1.0
[[step]]
at = 0.5
expect = { axis = 0, state = "standstill" }
[[step]]
at = 0.0
command = { type = "enable", axis = 0 }
[[step]]
at = 0.5
force = { axis = 0, input = "limit_pos", value = true }
"#,
    ))
    .unwrap();
    assert_eq!(s.end_tick(), 1000);
    assert_eq!(s.config().axes.len(), 1);
    let order: Vec<(usize, u64)> = s.steps.iter().map(|s| (s.index, s.tick)).collect();
    assert_eq!(order, [(1, 0), (0, 500), (2, 500)]);
}

#[test]
fn errors_name_the_key() {
    let key = |text: &str| err(&with_machine(text)).key;
    assert_eq!(key("end = 1.0\n[[step]]\nat = 0.5\n"), "step[0]");
    assert_eq!(
        key("end = 1.0\n[[step]]\nat = 0.5\ncommand = { type = \"enable\", axis = 0 }\nexpect = { axis = 0, state = \"standstill\" }\n"),
        "step[0]"
    );
    assert_eq!(
        key("end = 1.0\n[[step]]\nat = 2\ncommand = { type = \"enable\", axis = 0 }\n"),
        "step[0].at"
    );
    assert_eq!(
        key("end = 1.0\n[[step]]\nat = -1\ncommand = { type = \"enable\", axis = 0 }\n"),
        "step[0].at"
    );
    assert_eq!(
        key("end = 1.0\n[[step]]\nat = 0\nexpect = { axis = 4, state = \"standstill\" }\n"),
        "step[0].expect.axis"
    );
    assert_eq!(
        key("end = 1.0\n[[step]]\nat = 0\ncommand = { type = \"enable\", axis = 4 }\n"),
        "step[0].command.axis"
    );
    assert_eq!(
        key("end = 1.0\n[[step]]\nat = 0\nforce = { axis = 0, input = \"limit_up\" }\n"),
        "step[0].force.input"
    );
    assert_eq!(
        key("end = 1.0\n[[step]]\nat = 0\nforce = { di = 64, value = true }\n"),
        "step[0].force.di"
    );
    assert_eq!(
        key("end = 1.0\n[[step]]\nat = 0\nexpect = { axis = 0, positon = 1.0 }\n"),
        "step[0].expect.positon"
    );
    assert_eq!(
        key("[[step]]\nat = 0\nexpect = { di = 1, value = true }\n"),
        "end"
    );
    assert_eq!(key("end = 1.0\nends = 2.0\n"), "ends");
    let e = err(&with_machine("end = 1.0\nends = 2.0\n"));
    assert!(e.reason.contains("unknown key `ends`"), "{e}");
    assert!(e.reason.contains("`axes`"), "{e}");
}

#[test]
fn the_machine_is_given_once() {
    let e = err("end = 1.0\n");
    assert_eq!(e.key, "config");
    assert!(e.reason.contains("no machine"), "{e}");
    let e = err(&with_machine("config = \"m.toml\"\nend = 1.0\n"));
    assert!(["machine", "axes"].contains(&e.key.as_str()), "{e}");
    assert!(e.reason.contains("given twice"), "{e}");
    let e = err("config = \"does/not/exist.toml\"\nend = 1.0\n");
    assert_eq!(e.key, "config");
    assert!(
        e.reason.contains("does/not/exist.toml: cannot read it"),
        "{e}"
    );
    let e = err("end = 1.0\n[config.machine]\nperiod = 0.001\n");
    assert_eq!(e.key, "config");
    assert!(e.reason.contains("not under [config]"), "{e}");
    // Inline config errors are the config's own: key path and reason, named by the scenario.
    let e = err("end = 1.0\n[machine]\nperiod = 0.5\n");
    assert_eq!(
        (e.file.as_str(), e.key.as_str()),
        ("s.toml", "machine.period")
    );
    let e = err("end = 1.0\n[[axes]]\n[axes.params]\naccel = -3\n");
    assert_eq!(e.key, "axes[0].params.accel");
}

#[test]
fn command_state_refers_to_an_earlier_motion_command() {
    let base = "end = 1.0\n[[step]]\nat = 0\ncommand = { type = \"enable\", axis = 0 }\n[[step]]\nat = 0.1\ncommand = { type = \"move_relative\", axis = 0, distance = 1.0 }\n";
    let ok =
        format!("{base}[[step]]\nat = 0.1\nexpect = {{ step = 1, command_state = \"running\" }}\n");
    parse(&with_machine(&ok)).unwrap();
    for (target, at, why) in [
        (0, "0.5", "not a motion command"),
        (1, "0.05", "runs after this one"),
        (7, "0.5", "no step[7]"),
    ] {
        let text = format!(
            "{base}[[step]]\nat = {at}\nexpect = {{ step = {target}, command_state = \"done\" }}\n"
        );
        let e = err(&with_machine(&text));
        assert_eq!(e.key, "step[2].expect.step");
        assert!(e.reason.contains(why), "{e}");
    }
}

#[test]
fn a_run_reports_failures_and_refusals() {
    let s = parse(&with_machine(
        r#"
end = 2.0
[[step]]
at = 0
command = { type = "enable", axis = 0 }
[[step]]
at = 0.01
command = { type = "move_absolute", axis = 0, position = 10.0, velocity = 50.0 }
[[step]]
at = 0.02
command = { type = "move_absolute", axis = 0, position = 10.0, velocity = -1.0 }
[[step]]
at = 0.03
command = { type = "enable", axis = 9 }
expect_error = "invalid_axis"
[[step]]
at = 1.5
expect = { axis = 0, state = "standstill", position = 10.0, flags = ["in_position"] }
[[step]]
at = 1.5
expect = { axis = 0, position = 11.0, tolerance = 0.5 }
[[step]]
at = 1.5
expect = { step = 1, command_state = "error" }
"#,
    ))
    .unwrap();
    let r = s.run(None).unwrap();
    assert_eq!(r.ticks, 2000);
    assert_eq!(r.expectations, 3);
    assert_eq!(r.failures.len(), 3, "{:#?}", r.failures);
    assert!(
        r.failures[0]
            .starts_with("s.toml: step[2] at 0.02 s: move_absolute refused (invalid_argument)"),
        "{}",
        r.failures[0]
    );
    assert!(
        r.failures[1].contains("step[5] at 1.5 s: axis 0 position: expected 11 ± 0.5, saw 10"),
        "{}",
        r.failures[1]
    );
    assert!(
        r.failures[2].contains("step[6] at 1.5 s: command of step[1]: expected error, saw"),
        "{}",
        r.failures[2]
    );
}

#[test]
fn the_trace_has_a_row_per_axis_per_tick_from_tick_0() {
    let s = parse(&with_machine(
        "end = 0.01\n[[step]]\nat = 0\ncommand = { type = \"enable\", axis = 0 }\n",
    ))
    .unwrap();
    let mut out = Vec::new();
    let r = s.run(Some(&mut out)).unwrap();
    let text = String::from_utf8(out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], crate::trace::HEADER);
    assert_eq!(lines.len(), 1 + 11);
    assert_eq!(r.trace_rows, 11);
    assert_eq!(r.trace_bytes as usize, text.len());
    // Written after the tick's steps: the enable shows at tick 0.
    assert!(lines[1].starts_with("0,0,standstill,"), "{}", lines[1]);
    assert!(lines[11].starts_with("0.01,0,standstill,"), "{}", lines[11]);
}

#[test]
fn a_gear_and_a_config_cam_table_run_and_are_checked_by_expect() {
    // The README's "Gear, cam and streams" example on two steppers, plus a cam on a table from
    // `[[cam_tables]]`.
    let axis = mm_axis("stepper");
    let text = format!(
        r#"
end = 3.0
[[step]]
at = 0
command = {{ type = "enable", axis = 0 }}
[[step]]
at = 0
command = {{ type = "enable", axis = 1 }}
[[step]]
at = 0
command = {{ type = "enable", axis = 2 }}
[[step]]
at = 0
command = {{ type = "gear_in", master = 0, slave = 1, numerator = -1, denominator = 2, clutch_distance = 10 }}
[[step]]
at = 0
command = {{ type = "cam_in", master = 0, slave = 2, table = 4 }}
[[step]]
at = 0
command = {{ type = "move_absolute", axis = 0, position = 100, velocity = 50 }}
[[step]]
at = 0.05
expect = {{ axis = 1, coupling = "engaging", flags = ["coupled"], not_flags = ["in_sync"] }}
[[step]]
at = 2.9
expect = {{ axis = 1, coupling = "in_sync", command_position = -47.5, tolerance = 1e-9, flags = ["coupled", "in_sync"] }}
[[step]]
at = 2.9
expect = {{ axis = 2, coupling = "in_sync", command_position = 25.0, tolerance = 1e-9 }}
[[step]]
at = 2.9
expect = {{ axis = 0, coupling = "none" }}
[[step]]
at = 2.9
command = {{ type = "gear_out", slave = 1 }}
[[step]]
at = 2.95
expect = {{ axis = 1, coupling = "none", not_flags = ["coupled"] }}

[machine]
period = 0.001
{axis}{axis}{axis}
[[cam_tables]]
table = 4
points = [{{ master = 0, slave = 0 }}, {{ master = 200, slave = 50 }}]
"#
    );
    runs_clean(&text, 5);
}

#[test]
fn an_nmc_follow_runs_its_fifo_once_and_is_checked_by_expect() {
    // S-FOLLOW's FIFO in mm (digest 001 §2.17, TV 59) with loop count 1: the master's 60 mm
    // move carries the slave 40 mm, then the Follow ends (FIFO 1 is empty).
    let axis = mm_axis("stepper");
    let text = format!(
        r#"
end = 2.0
[[step]]
at = 0
command = {{ type = "enable_all" }}
[[step]]
at = 0
command = {{ type = "follow_push", axis = 1, fifo = 0, points = [{{ master = 20, slave = 10 }}, {{ master = 40, slave = 30 }}, {{ master = 60, slave = 40 }}] }}
[[step]]
at = 0
command = {{ type = "follow_config", axis = 1, master = 0, loop_count = 1 }}
[[step]]
at = 0
command = {{ type = "follow_start", axes = [1] }}
[[step]]
at = 0
command = {{ type = "move_absolute", axis = 0, position = 60, velocity = 50 }}
[[step]]
at = 0.5
expect = {{ axis = 1, coupling = "in_sync", coupling_kind = "follow", flags = ["coupled"] }}
[[step]]
at = 1.9
expect = {{ axis = 1, coupling = "none", command_position = 40, tolerance = 1e-9, not_flags = ["coupled"] }}

[machine]
period = 0.001
{axis}{axis}
"#
    );
    runs_clean(&text, 2);
}

#[test]
fn a_gantry_and_a_handwheel_run_and_are_checked_by_expect() {
    // The README's "Gantry" and "Handwheel" examples on three steppers.
    let axis = mm_axis("stepper");
    let text = format!(
        r#"
end = 2.0
[[step]]
at = 0
command = {{ type = "enable_all" }}
[[step]]
at = 0
command = {{ type = "gantry_enable", master = 0, slaves = [1], warning_limit = 0.5, fault_limit = 2 }}
[[step]]
at = 0
command = {{ type = "move_absolute", axis = 0, position = 50 }}
[[step]]
at = 0
command = {{ type = "handwheel_in", axis = 2, input = 256, numerator = 1, denominator = 100, velocity = 20, acceleration = 200 }}
[[step]]
at = 0.1
command = {{ type = "handwheel_turn", input = 256, counts = 1000 }}
[[step]]
at = 0.2
expect = {{ axis = 1, coupling = "in_sync", flags = ["coupled"], not_flags = ["gantry_warning", "gantry_fault"], gantry_deviation = 0 }}
[[step]]
at = 1.5
expect = {{ axis = 1, command_position = 50, gantry_deviation = 0 }}
[[step]]
at = 1.5
expect = {{ axis = 2, command_position = 10, flags = ["handwheel"] }}
[[step]]
at = 1.6
command = {{ type = "handwheel_out", axis = 2 }}
[[step]]
at = 1.6
command = {{ type = "gantry_disable", master = 0 }}
[[step]]
at = 1.7
expect = {{ axis = 2, not_flags = ["handwheel"] }}

[machine]
period = 0.001
{axis}{axis}{axis}
"#
    );
    runs_clean(&text, 4);
}

#[test]
fn the_himc_status_quantities_are_expect_keys() {
    // A 10 mm move at 1000 mm/s² and at most 100 mm/s is a triangle of 0.2 s (HIMC GetMoveTime,
    // digest 004 §3.7); set_position 0 at 10 mm moves the user frame's origin by −10 (TV 32's
    // sign, GetPosOffset); a stepper axis, finite, takes no torque at rest.
    let s = parse(&with_machine(
        r#"
end = 1.0
[[step]]
at = 0.0
command = { type = "enable", axis = 0 }
[[step]]
at = 0.01
command = { type = "move_absolute", axis = 0, position = 10 }
[[step]]
at = 0.5
expect = { axis = 0, move_time = 0.2, tolerance = 0.0015 }
[[step]]
at = 0.5
expect = { axis = 0, rollover_turns = 0, torque = 0, position_offset = 0 }
[[step]]
at = 0.6
command = { type = "set_position", axis = 0, position = 0 }
[[step]]
at = 0.7
expect = { axis = 0, position_offset = -10 }
[[step]]
at = 0.7
expect = { axis = 0, position_offset = -9, settling_time = 99, tolerance = 0.5 }
"#,
    ))
    .unwrap();
    let r = s.run(None).unwrap();
    assert_eq!(r.expectations, 4);
    let failed = |what: &str| r.failures.iter().any(|f| f.contains(what));
    assert_eq!(r.failures.len(), 2, "{:#?}", r.failures);
    assert!(
        failed("axis 0 position_offset: expected -9 ± 0.5, saw -10"),
        "{:#?}",
        r.failures
    );
    assert!(
        failed("axis 0 settling_time: expected 99 ± 0.5"),
        "{:#?}",
        r.failures
    );
}

#[test]
fn hmc_switch_tz_and_the_position_compensation_offset_are_checked_by_expect() {
    // Axis 0 passes 10 and 30 units; each toggles axis 1's Z-phase output (SwitchTZ mode 0).
    // Axis 1's offset moves by 2 on a trigger (HMC_TrigAxisCompens).
    let axis = mm_axis("stepper");
    let text = format!(
        r#"
end = 1.5
[[step]]
at = 0
command = {{ type = "enable_all" }}
[[step]]
at = 0
command = {{ type = "z_compare_start", axis = 0, positions = [10, 30], output_axis = 1 }}
[[step]]
at = 0
command = {{ type = "compensation_offset_profile", axis = 1, velocity = 10, acceleration = 100, deceleration = 100 }}
[[step]]
at = 0
command = {{ type = "compensation_offset_amount", axis = 1, amount = 2 }}
[[step]]
at = 0
command = {{ type = "compensation_offset_trigger", axis = 1 }}
[[step]]
at = 0
command = {{ type = "move_absolute", axis = 0, position = 20 }}
[[step]]
at = 0.1
expect = {{ axis = 1, z_output = 0, compensation_offset = 0.5, tolerance = 1e-6 }}
[[step]]
at = 0.5
expect = {{ axis = 1, z_output = 1, compensation_offset = 2, output_position = 2, command_position = 0 }}
[[step]]
at = 0.5
command = {{ type = "move_absolute", axis = 0, position = 40 }}
[[step]]
at = 1.2
expect = {{ axis = 1, z_output = 0 }}

[machine]
period = 0.001
{axis}{axis}
"#
    );
    runs_clean(&text, 3);
}

#[test]
fn the_hmc_add_axis_is_checked_by_expect() {
    // HMC_SetAddAxis(0, 1): axis 0 moves 30 of its own and 20 of axis 1's; 255 = none.
    let axis = mm_axis("virtual");
    let text = format!(
        r#"
end = 1.5
[[step]]
at = 0
command = {{ type = "enable_all" }}
[[step]]
at = 0
expect = {{ axis = 0, add_axis = 255 }}
[[step]]
at = 0
command = {{ type = "add_axis_set", base = 0, add = 1 }}
[[step]]
at = 0
command = {{ type = "move_relative", axis = 0, distance = 30 }}
[[step]]
at = 0
command = {{ type = "move_relative", axis = 1, distance = 20 }}
[[step]]
at = 1
expect = {{ axis = 0, add_axis = 1, command_position = 50 }}
[[step]]
at = 1
expect = {{ axis = 0, add_axis = 2 }}

[machine]
period = 0.001
{axis}{axis}
"#
    );
    let s = parse(&text).unwrap();
    let r = s.run(None).unwrap();
    assert_eq!(r.expectations, 3);
    assert_eq!(r.failures.len(), 1, "{:#?}", r.failures);
    assert!(
        r.failures[0].contains("axis 0 add_axis: expected 2"),
        "{:#?}",
        r.failures
    );
}
