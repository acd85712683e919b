//! End-to-end tests of the control API: the real `mcemu` binary on a port the OS picks, driven
//! over real sockets by a real HTTP client (ureq). Physics is checked on the virtual clock,
//! which `/time/advance` drives deterministically; one test runs the realtime clock.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::PathBuf;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use serde_json::{json, Value};

/// Two stepper axes (`x`, `y`) in mm with limit switches at ±500, 100 mm/s, 1000 mm/s²,
/// following-error limit 1 mm; some I/O.
fn machine(clock: &str) -> String {
    let mut text =
        format!("[machine]\nname = \"control-test\"\nperiod = 0.001\nclock = \"{clock}\"\n");
    for name in ["x", "y"] {
        text.push_str(&format!(
            r#"
[[axes]]
name = "{name}"
[axes.params]
axis_type = "stepper"
units = 1000
rep_mode = "finite"
speed = 100
accel = 1000
decel = 1000
fast_decel = 10000
fe_limit = 1
[axes.switches.limit_pos]
position = 500
[axes.switches.limit_neg]
position = -500
"#
        ));
    }
    text.push_str(
        r#"
[io]
digital_inputs = 16
digital_outputs = 8
analog_inputs = 4
analog_outputs = 2

[frontends.control]
enabled = true
bind = "127.0.0.1:0"
"#,
    );
    text
}

const PERIOD: f64 = 1e-3;

/// A running `mcemu run`; killed on drop, so a failing test never leaks it.
struct Mcemu {
    child: Child,
    base: String,
    stdout: Receiver<String>,
    agent: ureq::Agent,
    _config: TempFile,
}

struct TempFile(PathBuf);

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// A response: status, the headers we look at, body text.
struct Reply {
    status: u16,
    body: String,
    content_type: String,
    headers: ureq::http::HeaderMap,
}

impl Reply {
    fn json(&self) -> Value {
        serde_json::from_str(&self.body)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {} {}", self.status, self.body))
    }

    /// Assert the status and return the JSON body.
    fn expect(&self, status: u16) -> Value {
        assert_eq!(self.status, status, "{}", self.body);
        assert!(
            self.content_type.starts_with("application/json"),
            "{}",
            self.content_type
        );
        self.json()
    }
}

impl Mcemu {
    fn start(clock: &str, args: &[&str]) -> Mcemu {
        static N: AtomicUsize = AtomicUsize::new(0);
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
        let path = dir.join(format!(
            "control_api-{}-{}.toml",
            std::process::id(),
            N.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::write(&path, machine(clock)).unwrap();
        let config = TempFile(path);
        let mut child = Command::new(env!("CARGO_BIN_EXE_mcemu"))
            .arg("run")
            .arg("--config")
            .arg(&config.0)
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .unwrap();
        let out = child.stdout.take().unwrap();
        let (tx, stdout) = mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(out).lines() {
                let Ok(line) = line else { break };
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        let agent = ureq::Agent::config_builder()
            .http_status_as_error(false)
            .timeout_global(Some(Duration::from_secs(60)))
            .build()
            .into();
        let mut mcemu = Mcemu {
            child,
            base: String::new(),
            stdout,
            agent,
            _config: config,
        };
        let line = mcemu.wait_for_line("listening: control ");
        let address = line.trim_start_matches("listening: control ");
        assert!(address.starts_with("127.0.0.1:"), "{line}");
        mcemu.base = format!("http://{address}");
        mcemu
    }

    fn wait_for_line(&mut self, prefix: &str) -> String {
        let deadline = Instant::now() + Duration::from_secs(30);
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.stdout.recv_timeout(left) {
                Ok(line) if line.starts_with(prefix) => return line,
                Ok(_) => {}
                Err(RecvTimeoutError::Timeout) => panic!("no `{prefix}` line within 30 s"),
                Err(RecvTimeoutError::Disconnected) => {
                    panic!(
                        "mcemu closed its stdout before `{prefix}`: {:?}",
                        self.child.try_wait()
                    )
                }
            }
        }
    }

    fn url(&self, path: &str) -> String {
        format!("{}{path}", self.base)
    }

    fn reply(response: Result<ureq::http::Response<ureq::Body>, ureq::Error>) -> Reply {
        let mut response = response.unwrap();
        let status = response.status().as_u16();
        let headers = response.headers().clone();
        let content_type = headers
            .get("content-type")
            .and_then(|v| v.to_str().ok())
            .unwrap_or("")
            .to_string();
        let body = response
            .body_mut()
            .with_config()
            .limit(1 << 30)
            .read_to_string()
            .unwrap();
        Reply {
            status,
            body,
            content_type,
            headers,
        }
    }

    fn get(&self, path: &str) -> Reply {
        Mcemu::reply(self.agent.get(self.url(path)).call())
    }

    fn post_raw(&self, path: &str, content_type: &str, body: &str) -> Reply {
        Mcemu::reply(
            self.agent
                .post(self.url(path))
                .header("content-type", content_type)
                .send(body),
        )
    }

    fn post(&self, path: &str, body: Value) -> Reply {
        self.post_raw(path, "application/json", &body.to_string())
    }

    fn state(&self) -> Value {
        self.get("/api/v1/state").expect(200)
    }

    fn axis(&self, axis: usize) -> Value {
        self.state()["axes"][axis].clone()
    }

    /// A command that must succeed; its reply.
    fn command(&self, command: Value) -> Value {
        self.post("/api/v1/commands", command).expect(200)
    }

    fn advance(&self, request: Value) -> Value {
        self.post("/api/v1/time/advance", request).expect(200)
    }

    /// SIGTERM, then the exit status and the rest of stdout.
    fn terminate(mut self) -> (ExitStatus, Vec<String>) {
        let pid = self.child.id().to_string();
        let killed = Command::new("kill").args(["-TERM", &pid]).status().unwrap();
        assert!(killed.success());
        let deadline = Instant::now() + Duration::from_secs(30);
        let status = loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                break status;
            }
            assert!(Instant::now() < deadline, "mcemu did not stop on SIGTERM");
            std::thread::sleep(Duration::from_millis(10));
        };
        // The process has exited: the reader thread ends at EOF, after the last line.
        let rest = self.stdout.iter().collect();
        (status, rest)
    }

    /// SIGTERM and check the clean exit.
    fn stop(self) {
        let (status, rest) = self.terminate();
        assert!(status.success(), "{status:?}");
        assert!(rest.iter().any(|l| l == "mcemu: stopped"), "{rest:?}");
    }
}

impl Drop for Mcemu {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

fn has_flag(axis: &Value, flag: &str) -> bool {
    axis["flags"]
        .as_array()
        .unwrap()
        .iter()
        .any(|f| f.as_str() == Some(flag))
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

// ---- state ---------------------------------------------------------------------------------

#[test]
fn control_state_reports_machine_axes_io_drives_runtime_and_trace() {
    let m = Mcemu::start("virtual", &[]);
    let s = m.state();
    assert_eq!(s["machine"], "control-test");
    assert_eq!(s["clock"], "virtual");
    assert_eq!(
        (s["period"].as_f64(), s["tick"].as_u64()),
        (Some(PERIOD), Some(0))
    );
    assert_eq!(s["time"], 0.0);
    let axes = s["axes"].as_array().unwrap();
    assert_eq!(axes.len(), 2);
    let x = &axes[0];
    assert_eq!(
        (x["axis"].as_u64(), x["name"].as_str()),
        (Some(0), Some("x"))
    );
    assert_eq!(x["state"], "disabled");
    assert!(x["flags"].is_array() && !has_flag(x, "enabled"), "{x}");
    assert_eq!(x["latched"], json!([]));
    for key in [
        "cmd_pos",
        "cmd_vel",
        "cmd_acc",
        "act_pos",
        "act_vel",
        "following_error",
        "target_pos",
        "pulses",
        "encoder_counts",
        "fifo_len",
        "homing_phase",
    ] {
        assert!(x[key].is_number(), "{key}: {x}");
    }
    for key in ["current_command", "next_command", "last_error"] {
        assert!(x[key].is_null(), "{key}: {x}");
    }
    assert_eq!(s["io"]["di"].as_array().unwrap().len(), 16);
    assert_eq!(s["io"]["do"].as_array().unwrap().len(), 8);
    assert_eq!(s["io"]["ai"].as_array().unwrap().len(), 4);
    assert_eq!(s["io"]["ao"].as_array().unwrap().len(), 2);
    assert_eq!(s["drives"], json!([]));
    let runtime = &s["runtime"];
    assert_eq!(runtime["clock"], "virtual");
    for key in [
        "ticks_run",
        "caught_up_ticks",
        "dropped_ticks",
        "overruns",
        "drift",
    ] {
        assert!(runtime[key].is_number(), "{key}: {runtime}");
    }
    for key in ["p50", "p99", "max"] {
        assert!(runtime["lateness"][key].is_number(), "{key}: {runtime}");
    }
    assert_eq!(s["trace"]["state"], "idle");
    let index = m.get("/api/v1").expect(200);
    assert!(index["routes"].as_array().unwrap().len() >= 8, "{index}");
    m.stop();
}

// ---- motion ----------------------------------------------------------------------------------

#[test]
fn control_moves_an_axis_in_virtual_time() {
    let m = Mcemu::start("virtual", &[]);
    assert_eq!(
        m.command(json!({"type": "enable", "axis": 0})),
        json!({"reply": "done"})
    );
    let reply = m.command(json!({
        "type": "move_absolute", "axis": 0, "position": 100, "velocity": 50
    }));
    assert_eq!(reply["reply"], "accepted");
    let id = reply["id"].as_u64().unwrap();
    // Trapezoid: 50 ms ramps at 1000 mm/s², so after 1 s the axis is at 1.25 + 47.5 mm.
    let reached = m.advance(json!({"seconds": 1.0}));
    assert_eq!(
        reached,
        json!({"tick": 1000, "time": 1.0, "ticks_run": 1000})
    );
    let x = m.axis(0);
    assert_eq!(x["state"], "discrete_motion");
    assert!(has_flag(&x, "moving"), "{x}");
    assert!((f(&x["cmd_pos"]) - 48.75).abs() < 1e-9, "{x}");
    assert!((f(&x["cmd_vel"]) - 50.0).abs() < 1e-9, "{x}");
    assert_eq!(
        x["current_command"],
        json!({"id": id, "kind": "move_absolute"})
    );
    let state = m.command(json!({"type": "command_state", "id": id}));
    assert_eq!(state["state"], "running");
    // Until it stops: 2.05 s of motion in all.
    let done = m.advance(json!({"seconds": 5, "until": {"axis": 0, "state": "standstill"}}));
    assert_eq!(done["met"], true);
    let tick = done["tick"].as_u64().unwrap();
    assert!((2040..=2070).contains(&tick), "{done}");
    let x = m.axis(0);
    assert_eq!(x["cmd_pos"], 100.0);
    assert!((f(&x["act_pos"]) - 100.0).abs() < 1e-6, "{x}");
    assert_eq!(x["cmd_vel"], 0.0);
    assert_eq!(x["pulses"], 100_000);
    assert!(!has_flag(&x, "moving"), "{x}");
    let state = m.command(json!({"type": "command_state", "id": id}));
    assert_eq!(state["state"], "done");
    // The other axis never moved.
    assert_eq!(m.axis(1)["cmd_pos"], 0.0);
    m.stop();
}

#[test]
fn control_state_lists_the_handwheels() {
    let m = Mcemu::start("virtual", &[]);
    assert_eq!(m.state()["handwheels"], json!([]));
    // S-HANDWHEEL (digest 001 §2.15): axis 0 follows the first external encoder × 5.
    m.command(json!([
        {"type": "enable", "axis": 0},
        {"type": "handwheel_in", "axis": 0, "input": 256, "numerator": 5, "denominator": 1,
         "velocity": 10, "acceleration": 1},
        {"type": "handwheel_turn", "input": 256, "counts": 4}
    ]));
    m.advance(json!({"seconds": 10}));
    let wheels = m.state()["handwheels"].clone();
    assert_eq!(wheels.as_array().unwrap().len(), 1, "{wheels}");
    let wheel = &wheels[0];
    assert_eq!(
        (&wheel["axis"], &wheel["input"], &wheel["counts"]),
        (&json!(0), &json!(256), &json!(4)),
        "{wheel}"
    );
    assert_eq!((f(&wheel["ratio"]), f(&wheel["target"])), (5.0, 20.0));
    assert!((f(&wheel["lag"]) - (20.0 - f(&m.axis(0)["cmd_pos"]))).abs() < 1e-9);
    m.stop();
}

#[test]
fn control_command_arrays_apply_in_order_and_stop_at_the_first_error() {
    let m = Mcemu::start("virtual", &[]);
    let replies = m.command(json!([
        {"type": "enable", "axis": 0},
        {"type": "move_relative", "axis": 0, "distance": 10},
    ]));
    assert_eq!(replies[0], json!({"reply": "done"}));
    assert_eq!(replies[1]["reply"], "accepted");
    let e = m
        .post(
            "/api/v1/commands",
            json!([
                {"type": "set_parameter", "axis": 1, "name": "speed", "value": 20},
                {"type": "enable", "axis": 7},
                {"type": "enable", "axis": 1},
            ]),
        )
        .expect(422);
    assert_eq!(e["code"], "invalid_axis");
    assert_eq!(
        (e["axis"].as_u64(), e["count"].as_u64()),
        (Some(7), Some(2))
    );
    assert_eq!(e["index"], 1);
    assert_eq!(e["replies"], json!([{"reply": "done"}]));
    assert_eq!(
        e["message"],
        "axis 7 does not exist (the machine has 2 axes)"
    );
    // Applied before the error, not after it.
    let speed = m.command(json!({"type": "get_parameter", "axis": 1, "name": "speed"}));
    assert_eq!(speed, json!({"reply": "value", "value": 20.0}));
    assert_eq!(m.axis(1)["state"], "disabled");
    assert_eq!(m.command(json!([])), json!([]));
    m.stop();
}

#[test]
fn control_atomic_arrays_apply_in_one_tick_all_or_none() {
    let m = Mcemu::start("virtual", &[]);
    m.post_raw("/api/v1/trace/start", "text/plain", "")
        .expect(200);
    let replies = m
        .post(
            "/api/v1/commands?atomic=true",
            json!([
                {"type": "enable", "axis": 0},
                {"type": "enable", "axis": 1},
                {"type": "move_together", "moves": [
                    {"type": "move_absolute", "axis": 0, "position": 10},
                    {"type": "move_relative", "axis": 1, "distance": -5, "velocity": 20},
                ]},
            ]),
        )
        .expect(200);
    assert_eq!(replies[0], json!({"reply": "done"}));
    assert_eq!(replies[2], json!({"reply": "accepted_all", "ids": [1, 2]}));
    m.advance(json!({"ticks": 20}));
    // Same tick: both axes' first non-zero commanded velocity is on the first tick recorded.
    let (header, rows) = parse_csv(&m.get("/api/v1/trace").body);
    let (time, axis, cmd_vel) = (
        column(&header, "time_s"),
        column(&header, "axis"),
        column(&header, "cmd_vel"),
    );
    let first_moving = |a: &str| {
        rows.iter()
            .find(|r| r[axis] == a && r[cmd_vel].parse::<f64>().unwrap() != 0.0)
            .map(|r| r[time].clone())
    };
    assert_eq!(first_moving("0"), Some("0.001".to_string()));
    assert_eq!(first_moving("1"), first_moving("0"));

    // Refused at index 2: the parameter and the output written before it are undone.
    let e = m
        .post(
            "/api/v1/commands?atomic=true",
            json!([
                {"type": "set_parameter", "axis": 1, "name": "speed", "value": 20},
                {"type": "write_digital_output", "channel": 0, "value": true},
                {"type": "enable", "axis": 7},
            ]),
        )
        .expect(422);
    assert_eq!(e["code"], "invalid_axis");
    assert_eq!(e["index"], 2);
    assert_eq!(e["replies"], json!([]));
    assert_eq!(
        e["message"],
        "axis 7 does not exist (the machine has 2 axes)"
    );
    let speed = m.command(json!({"type": "get_parameter", "axis": 1, "name": "speed"}));
    assert_eq!(speed, json!({"reply": "value", "value": 100.0}));
    assert_eq!(m.state()["io"]["do"][0], false);

    // A refused move inside a batch: the batch's index, the move's item and its own error.
    let e = m
        .post(
            "/api/v1/commands?atomic=true",
            json!([
                {"type": "disable_all"},
                {"type": "move_together", "moves": [
                    {"type": "move_relative", "axis": 0, "distance": 1},
                ]},
            ]),
        )
        .expect(422);
    assert_eq!(e["code"], "axis_disabled");
    assert_eq!(
        (e["index"].as_u64(), e["list"].as_str()),
        (Some(1), Some("moves"))
    );
    assert_eq!(e["item"], 0);
    assert_eq!(e["error"]["code"], "axis_disabled");
    assert_eq!(e["error"]["axis"], 0);
    assert_eq!(e["message"], "moves[0]: axis 0 is disabled");
    assert!(has_flag(&m.axis(0), "enabled"), "disable_all was undone");

    // Bad input, nothing applied.
    let e = m
        .post("/api/v1/commands?atomic=true", json!([]))
        .expect(422);
    assert_eq!(
        (e["code"].as_str(), e["name"].as_str()),
        (Some("invalid_argument"), Some("commands"))
    );
    let many = vec![json!({"type": "disable_all"}); 1025];
    let e = m
        .post("/api/v1/commands?atomic=true", json!(many))
        .expect(400);
    assert_eq!(e["error"], "invalid_request");
    let e = m
        .post(
            "/api/v1/commands?atomic=true",
            json!([
                {"type": "write_digital_output", "channel": 1, "value": true},
                {"type": "move_absolute", "axis": 0, "position": 1e13},
            ]),
        )
        .expect(422);
    assert_eq!(
        (e["code"].as_str(), e["index"].as_u64()),
        (Some("invalid_argument"), Some(1))
    );
    let e = m
        .post(
            "/api/v1/commands?atomic=true",
            json!([{"type": "disable_all"}, {"type": "teleport", "axis": 0}]),
        )
        .expect(400);
    assert_eq!(e["error"], "invalid_body");
    let e = m
        .post(
            "/api/v1/commands?atomic=maybe",
            json!([{"type": "disable_all"}]),
        )
        .expect(400);
    assert_eq!(e["error"], "invalid_request");
    assert!(has_flag(&m.axis(0), "enabled"));
    assert_eq!(m.state()["io"]["do"][1], false);
    m.stop();
}

#[test]
fn control_forced_limit_refuses_motion_into_it() {
    let m = Mcemu::start("virtual", &[]);
    m.command(json!({"type": "enable", "axis": 0}));
    let forced = m.post(
        "/api/v1/inputs",
        json!({"axis": 0, "input": "limit_pos", "value": true}),
    );
    assert_eq!(forced.expect(200), json!({"reply": "done"}));
    m.advance(json!({"ticks": 1})); // inputs are sampled by the tick
    let x = m.axis(0);
    assert!(has_flag(&x, "hw_limit_pos"), "{x}");
    let refused = m
        .post(
            "/api/v1/commands",
            json!({"type": "move_relative", "axis": 0, "distance": 5}),
        )
        .expect(422);
    assert_eq!(refused["code"], "limit_active");
    assert_eq!(refused["direction"], "positive");
    assert_eq!(refused["axis"], 0);
    assert_eq!(
        refused["message"],
        "axis 0: positive limit active; motion further into it is refused"
    );
    // Out of the limit is allowed.
    let out = m.command(json!({"type": "move_relative", "axis": 0, "distance": -5}));
    assert_eq!(out["reply"], "accepted");
    m.advance(json!({"seconds": 1}));
    assert!((f(&m.axis(0)["cmd_pos"]) + 5.0).abs() < 1e-9);
    // Released (no value): the simulated switch at +500 mm is far away.
    m.post("/api/v1/inputs", json!({"axis": 0, "input": "limit_pos"}))
        .expect(200);
    m.advance(json!({"ticks": 1}));
    assert!(!has_flag(&m.axis(0), "hw_limit_pos"));
    m.stop();
}

#[test]
fn control_drive_alarm_stops_the_axis_in_error_stop_until_cleared_and_reset() {
    let m = Mcemu::start("virtual", &[]);
    m.command(json!({"type": "enable", "axis": 0}));
    m.command(json!({"type": "move_velocity", "axis": 0, "velocity": 20}));
    m.advance(json!({"ticks": 100}));
    assert_eq!(m.axis(0)["state"], "continuous_motion");
    let injected = m.post(
        "/api/v1/faults",
        json!({"axis": 0, "fault": "drive_alarm", "active": true}),
    );
    assert_eq!(injected.expect(200), json!({"reply": "done"}));
    m.advance(json!({"seconds": 0.5}));
    let x = m.axis(0);
    assert_eq!(x["state"], "error_stop");
    assert!(has_flag(&x, "drive_alarm"), "{x}");
    assert!(x["latched"]
        .as_array()
        .unwrap()
        .contains(&json!("drive_alarm")));
    assert_eq!(x["cmd_vel"], 0.0);
    let refused = m
        .post(
            "/api/v1/commands",
            json!({"type": "move_relative", "axis": 0, "distance": 1}),
        )
        .expect(422);
    assert_eq!(refused["code"], "axis_in_error");
    assert!(refused["faults"]
        .as_array()
        .unwrap()
        .contains(&json!("drive_alarm")));
    // While the alarm is on, a reset cannot clear it.
    let still = m
        .post("/api/v1/commands", json!({"type": "reset", "axis": 0}))
        .expect(422);
    assert_eq!(still["code"], "cause_still_present");
    m.post(
        "/api/v1/faults",
        json!({"axis": 0, "fault": "drive_alarm", "active": false}),
    )
    .expect(200);
    m.advance(json!({"ticks": 1}));
    m.command(json!({"type": "reset", "axis": 0}));
    m.advance(json!({"ticks": 1}));
    // A drive in alarm switched itself off (docs/decisions.md): reset leaves it disabled.
    let x = m.axis(0);
    assert_eq!(
        (x["state"].as_str(), &x["latched"]),
        (Some("disabled"), &json!([]))
    );
    m.command(json!({"type": "enable", "axis": 0}));
    assert_eq!(m.axis(0)["state"], "standstill");
    m.stop();
}

#[test]
fn control_following_error_and_encoder_loss_faults() {
    let m = Mcemu::start("virtual", &[]);
    m.command(json!({"type": "enable", "axis": 0}));
    m.command(json!({"type": "enable", "axis": 1}));
    m.post(
        "/api/v1/faults",
        json!({"axis": 0, "fault": "following_error", "amount": 5.0}),
    )
    .expect(200);
    m.post(
        "/api/v1/faults",
        json!({"axis": 1, "fault": "encoder_loss"}),
    )
    .expect(200);
    m.advance(json!({"seconds": 0.1}));
    let s = m.state();
    let (x, y) = (&s["axes"][0], &s["axes"][1]);
    assert_eq!(x["state"], "error_stop");
    assert_eq!(x["last_error"], "fault");
    assert!(has_flag(x, "fe_fault"), "{x}");
    assert_eq!(y["state"], "error_stop");
    assert!(has_flag(y, "encoder_loss"), "{y}");
    let missing = m
        .post(
            "/api/v1/faults",
            json!({"axis": 0, "fault": "following_error"}),
        )
        .expect(400);
    assert_eq!(missing["error"], "invalid_request");
    let cleared = m.post(
        "/api/v1/faults",
        json!({"axis": 0, "fault": "following_error", "active": false}),
    );
    cleared.expect(200);
    m.stop();
}

#[test]
fn control_inputs_force_and_release_digital_and_analog_channels() {
    let m = Mcemu::start("virtual", &[]);
    m.post("/api/v1/inputs", json!({"di": 5, "value": true}))
        .expect(200);
    m.post("/api/v1/inputs", json!({"ai": 2, "value": 3.3}))
        .expect(200);
    let io = m.state()["io"].clone();
    assert_eq!(io["di"][5], true);
    assert_eq!(io["di"][4], false);
    assert_eq!(io["ai"][2], 3.3);
    m.post("/api/v1/inputs", json!({"di": 5, "value": null}))
        .expect(200);
    m.post("/api/v1/inputs", json!({"ai": 2})).expect(200);
    let io = m.state()["io"].clone();
    assert_eq!(
        (io["di"][5].as_bool(), io["ai"][2].as_f64()),
        (Some(false), Some(0.0))
    );
    let e = m
        .post("/api/v1/inputs", json!({"di": 16, "value": true}))
        .expect(422);
    assert_eq!(e["code"], "invalid_channel");
    let e = m
        .post("/api/v1/inputs", json!({"di": 1, "value": 1}))
        .expect(400);
    assert_eq!(e["field"], "value");
    let e = m
        .post(
            "/api/v1/inputs",
            json!({"axis": 0, "input": "limit_up", "value": true}),
        )
        .expect(400);
    assert_eq!(e["field"], "input");
    m.stop();
}

// ---- traces --------------------------------------------------------------------------------

/// The CSV's rows as maps column → text.
fn parse_csv(csv: &str) -> (String, Vec<Vec<String>>) {
    let mut lines = csv.lines();
    let header = lines.next().unwrap().to_string();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

fn column(header: &str, name: &str) -> usize {
    header.split(',').position(|c| c == name).unwrap()
}

#[test]
fn control_trace_records_every_tick_of_an_advance() {
    let m = Mcemu::start("virtual", &[]);
    let e = m.get("/api/v1/trace").expect(409);
    assert_eq!(e["error"], "no_trace");
    m.command(json!({"type": "enable", "axis": 0}));
    m.advance(json!({"ticks": 7}));
    let started = m
        .post_raw("/api/v1/trace/start", "text/plain", "")
        .expect(200);
    assert_eq!(started["state"], "recording");
    assert_eq!(started["axes"], json!([0, 1]));
    m.command(json!({"type": "move_absolute", "axis": 0, "position": 20, "velocity": 50}));
    m.advance(json!({"ticks": 500}));
    let stopped = m
        .post_raw("/api/v1/trace/stop", "text/plain", "")
        .expect(200);
    assert_eq!(stopped["state"], "stopped");
    assert_eq!(stopped["rows"], 1000);
    m.advance(json!({"ticks": 50})); // not recorded
    let end = m.axis(0);

    let trace = m.get("/api/v1/trace");
    assert_eq!(trace.status, 200);
    assert!(
        trace.content_type.starts_with("text/csv"),
        "{}",
        trace.content_type
    );
    assert_eq!(trace.headers["x-mcemu-trace-state"], "stopped");
    assert_eq!(trace.headers["x-mcemu-trace-rows"], "1000");
    let (header, rows) = parse_csv(&trace.body);
    assert_eq!(header, mcemu::trace::HEADER);
    assert_eq!(rows.len(), 500 * 2);
    let (time, axis, state, cmd_pos, cmd_vel, cmd_acc, act_pos) = (
        column(&header, "time_s"),
        column(&header, "axis"),
        column(&header, "state"),
        column(&header, "cmd_pos"),
        column(&header, "cmd_vel"),
        column(&header, "cmd_acc"),
        column(&header, "act_pos"),
    );
    let num = |row: &[String], c: usize| row[c].parse::<f64>().unwrap();
    let mut last_pos = f64::NEG_INFINITY;
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), 36, "{row:?}");
        // One row per tick per axis, ticks 8 … 507, axes in order.
        let tick = 8 + (i / 2) as u64;
        assert_eq!(num(row, time), tick as f64 * PERIOD, "row {i}: {row:?}");
        assert_eq!(row[axis], (i % 2).to_string(), "row {i}");
        if i % 2 == 1 {
            assert_eq!(row[state], "disabled");
            assert_eq!(num(row, cmd_pos), 0.0);
            continue;
        }
        let p = num(row, cmd_pos);
        assert!(p >= last_pos, "row {i}: {p} < {last_pos}");
        last_pos = p;
        assert!(num(row, cmd_vel) <= 50.0 + 1e-9, "row {i}: {row:?}");
        assert!(num(row, cmd_acc).abs() <= 1000.0 + 1e-6, "row {i}: {row:?}");
    }
    // 20 mm at 50 mm/s takes 0.45 s: the trace ends at rest, on target, where /state is.
    let last = &rows[rows.len() - 2];
    assert_eq!(num(last, cmd_pos), 20.0);
    assert_eq!(last[state], "standstill");
    assert_eq!(num(last, cmd_pos), f(&end["cmd_pos"]));
    assert_eq!(num(last, act_pos), f(&end["act_pos"]));
    // The first recorded tick already moved.
    assert!(num(&rows[0], cmd_pos) > 0.0);
    m.stop();
}

#[test]
fn control_trace_cap_stops_the_recording_at_a_whole_tick() {
    let m = Mcemu::start("virtual", &[]);
    let started = m
        .post(
            "/api/v1/trace/start",
            json!({"axes": [1, 0], "max_rows": 11}),
        )
        .expect(200);
    assert_eq!(started["max_rows"], 11);
    m.advance(json!({"ticks": 20}));
    let status = m.state()["trace"].clone();
    assert_eq!(status["state"], "full");
    assert_eq!(status["rows"], 10);
    assert_eq!(
        (status["first_tick"].as_u64(), status["last_tick"].as_u64()),
        (Some(1), Some(5))
    );
    let trace = m.get("/api/v1/trace");
    assert_eq!(trace.headers["x-mcemu-trace-state"], "full");
    let (header, rows) = parse_csv(&trace.body);
    assert_eq!(rows.len(), 10);
    let axis = column(&header, "axis");
    assert_eq!((rows[0][axis].as_str(), rows[1][axis].as_str()), ("1", "0"));
    // Bad starts.
    for (body, field) in [
        (json!({"axes": [2]}), "axis 2 does not exist"),
        (json!({"max_rows": 0}), "max_rows"),
        (json!({"max_rows": 1_000_001}), "max_rows"),
    ] {
        let e = m.post("/api/v1/trace/start", body).expect(400);
        assert!(e["detail"].as_str().unwrap().contains(field), "{e}");
    }
    let e = m
        .post("/api/v1/trace/start", json!({"axis": [0]}))
        .expect(400);
    assert_eq!(e["field"], "axis");
    m.stop();
}

// ---- CAN bus log -------------------------------------------------------------------------------

/// A machine without `[frontends.canopen]` has no bus to log: both routes answer 409.
#[test]
fn control_can_log_needs_a_can_bus() {
    let m = Mcemu::start("virtual", &[]);
    let e = m
        .post("/api/v1/canopen/log/start", json!({"path": "bus.log"}))
        .expect(409);
    assert_eq!(e["error"], "no_can_bus");
    assert!(
        e["detail"]
            .as_str()
            .unwrap()
            .contains("[frontends.canopen]"),
        "{e}"
    );
    let e = m.post("/api/v1/canopen/log/stop", json!({})).expect(409);
    assert_eq!(e["error"], "no_can_bus");
    let index = m.get("/api/v1").expect(200);
    let paths: Vec<&str> = index["routes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|r| r["path"].as_str())
        .collect();
    assert!(paths.contains(&"/api/v1/canopen/log/start"), "{index}");
    assert!(paths.contains(&"/api/v1/canopen/log/stop"), "{index}");
    m.stop();
}

// ---- realtime --------------------------------------------------------------------------------

#[test]
fn control_realtime_clock_moves_and_records_every_tick() {
    let m = Mcemu::start("realtime", &[]);
    assert_eq!(m.state()["clock"], "realtime");
    let e = m
        .post("/api/v1/time/advance", json!({"ticks": 10}))
        .expect(409);
    assert_eq!(e["error"], "not_virtual_clock");
    assert!(e["detail"].as_str().unwrap().contains("virtual"), "{e}");
    m.post("/api/v1/trace/start", json!({"axes": [0]}))
        .expect(200);
    m.command(json!([
        {"type": "enable", "axis": 0},
        {"type": "move_relative", "axis": 0, "distance": 5, "velocity": 50},
    ]));
    // Realtime: poll, bounded; 5 mm at 50 mm/s takes 0.15 s.
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        let x = m.axis(0);
        if x["state"] == "standstill" && x["cmd_pos"] == 5.0 {
            break;
        }
        assert!(Instant::now() < deadline, "the axis did not arrive: {x}");
        std::thread::sleep(Duration::from_millis(20));
    }
    m.post_raw("/api/v1/trace/stop", "text/plain", "")
        .expect(200);
    let s = m.state();
    assert!(
        s["runtime"]["ticks_run"].as_u64().unwrap() > 150,
        "{}",
        s["runtime"]
    );
    assert!(s["runtime"]["lateness"]["count"].as_u64().unwrap() > 0);
    // Every tick is in the trace, not a polled sample: consecutive ticks, no gaps.
    let (header, rows) = parse_csv(&m.get("/api/v1/trace").body);
    let (time, cmd_pos) = (column(&header, "time_s"), column(&header, "cmd_pos"));
    assert!(rows.len() > 150, "{}", rows.len());
    let ticks: Vec<u64> = rows
        .iter()
        .map(|r| (r[time].parse::<f64>().unwrap() / PERIOD).round() as u64)
        .collect();
    assert!(
        ticks.windows(2).all(|w| w[1] == w[0] + 1),
        "gap in {ticks:?}"
    );
    assert!(rows.iter().any(|r| r[cmd_pos] == "5"), "never reached 5");
    m.stop();
}

// ---- errors ----------------------------------------------------------------------------------

#[test]
fn control_rejects_bad_requests_with_json_errors() {
    // A realtime config run with --clock virtual: the flag wins.
    let m = Mcemu::start("realtime", &["--clock", "virtual"]);
    assert_eq!(m.state()["clock"], "virtual");
    let raw = |body: &str| m.post_raw("/api/v1/commands", "application/json", body);

    let e = raw(r#"{"type": "enable", "axis": 0"#).expect(400);
    assert_eq!(e["error"], "malformed_json");
    assert!(e["line"].is_number() && e["column"].is_number(), "{e}");
    let e = raw("").expect(400);
    assert_eq!(e["error"], "malformed_json");

    let e = raw(r#"{"type":"move_absolute","axis":0,"positon":10}"#).expect(400);
    assert_eq!(e["error"], "invalid_body");
    assert_eq!(e["field"], "positon");
    assert!(
        e["detail"]
            .as_str()
            .unwrap()
            .contains("unknown field `positon`"),
        "{e}"
    );

    let e = raw(r#"{"type":"teleport","axis":0}"#).expect(400);
    assert_eq!(e["field"], "type");
    assert!(
        e["detail"]
            .as_str()
            .unwrap()
            .contains("unknown variant `teleport`"),
        "{e}"
    );

    let e = raw(r#"{"type":"move_absolute","axis":0}"#).expect(400);
    assert_eq!(e["field"], "position");

    let e = raw(r#"{"type":"enable","axis":"zero"}"#).expect(400);
    assert_eq!(e["field"], "axis");

    let e = raw(r#"[{"type":"enable","axis":0},{"type":"enable","axis":-1}]"#).expect(400);
    assert_eq!(e["field"], "[1].axis");

    let e = raw(r#"{"type":"enable","axis":9}"#).expect(422);
    assert_eq!(e["code"], "invalid_axis");

    // JSON has no NaN or infinity: 1e400 is no number; 1e300 is, and the engine bounds it.
    let e = raw(r#"{"type":"move_absolute","axis":0,"position":1e400}"#).expect(400);
    assert_eq!(e["error"], "malformed_json");
    assert!(
        e["detail"]
            .as_str()
            .unwrap()
            .contains("number out of range"),
        "{e}"
    );
    m.command(json!({"type": "enable", "axis": 0}));
    let e = raw(r#"{"type":"move_absolute","axis":0,"position":1e300}"#).expect(422);
    assert_eq!(e["code"], "invalid_argument");
    assert_eq!(e["name"], "position");

    let e = m
        .post_raw(
            "/api/v1/commands",
            "text/plain",
            r#"{"type":"enable","axis":0}"#,
        )
        .expect(415);
    assert_eq!(e["error"], "unsupported_media_type");

    // Just over the 1 MiB bound, so the whole body fits in the socket buffers even though the
    // server answers without reading it all.
    let big = format!(
        r#"{{"type":"enable","axis":0,"pad":"{}"}}"#,
        "x".repeat(1 << 20)
    );
    let e = raw(&big).expect(413);
    assert_eq!(e["error"], "body_too_large");

    let e = m.get("/api/v1/nowhere").expect(404);
    assert_eq!(e["error"], "not_found");
    m.get("/dashboard/nowhere.js").expect(404);
    // `/` is the dashboard (issue 15).
    let page = m.get("/");
    assert_eq!(page.status, 200);
    assert!(
        page.content_type.starts_with("text/html"),
        "{}",
        page.content_type
    );
    let e = m.get("/api/v1/commands").expect(405);
    assert_eq!(e["error"], "method_not_allowed");
    let r = Mcemu::reply(m.agent.delete(m.url("/api/v1/state")).call());
    assert_eq!(r.expect(405)["error"], "method_not_allowed");
    assert_eq!(r.headers["allow"], "GET,HEAD");

    let advance = |body: Value| m.post("/api/v1/time/advance", body);
    for body in [
        json!({}),
        json!({"ticks": 1, "seconds": 1}),
        json!({"seconds": -1}),
        json!({"ticks": 3_600_001}),
        json!({"seconds": 3601}),
        json!({"ticks": 1, "until": {"axis": 5, "state": "standstill"}}),
        json!({"ticks": 1, "until": {"axis": 0, "flag": "sleepy"}}),
    ] {
        let e = advance(body.clone()).expect(400);
        assert_eq!(e["error"], "invalid_request", "{body}: {e}");
    }
    let e = advance(json!({"ticks": -1})).expect(400);
    assert_eq!(e["field"], "ticks");
    let e = advance(json!({"tiks": 1})).expect(400);
    assert_eq!(e["field"], "tiks");

    let e = m
        .post(
            "/api/v1/faults",
            json!({"frontend": "modbus_tcp", "fault": "exception", "code": 4}),
        )
        .expect(400);
    assert_eq!(e["error"], "no_such_frontend");
    assert!(e["detail"].as_str().unwrap().contains("modbus_tcp"), "{e}");
    let e = m
        .post("/api/v1/faults", json!({"axis": 0, "fault": "gremlins"}))
        .expect(400);
    assert_eq!(e["field"], "fault");

    // After all that, the server still answers and the machine is intact.
    assert_eq!(m.state()["axes"][0]["state"], "standstill");
    m.stop();
}

#[test]
fn control_bounds_the_requests_in_flight_and_recovers() {
    let m = Mcemu::start("virtual", &[]);
    let address = m.base.trim_start_matches("http://").to_string();
    // Requests whose bodies never come each hold a slot (until the 10 s body timeout). Each
    // expects `100 Continue`, which the server sends when the handler starts reading the body,
    // so past the slot limit: once every one has it, all 64 slots are held. (Polling with GETs
    // while they still arrived let a GET hold a slot just when a stalled request came, which
    // then got the 503 itself and the slots never filled.)
    let stalled: Vec<TcpStream> = (0..64)
        .map(|i| {
            let mut s = TcpStream::connect(&address).unwrap();
            s.write_all(
                b"POST /api/v1/commands HTTP/1.1\r\nHost: x\r\n\
                  Content-Type: application/json\r\nContent-Length: 100\r\n\
                  Expect: 100-continue\r\n\r\n{",
            )
            .unwrap();
            s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
            let mut head = Vec::new();
            let mut byte = [0u8];
            while !head.ends_with(b"\r\n\r\n") {
                match s.read(&mut byte) {
                    Ok(1) => head.push(byte[0]),
                    other => panic!("stalled request {i}: {other:?} after {head:?}"),
                }
            }
            let head = String::from_utf8_lossy(&head);
            assert!(
                head.starts_with("HTTP/1.1 100 "),
                "stalled request {i}: {head}"
            );
            s
        })
        .collect();
    let busy = m.get("/api/v1/state");
    assert_eq!(busy.status, 503, "{}", busy.body);
    assert_eq!(busy.json()["error"], "too_many_requests");
    assert_eq!(busy.headers["retry-after"], "1");
    drop(stalled);
    let deadline = Instant::now() + Duration::from_secs(8);
    while m.get("/api/v1/state").status != 200 {
        assert!(Instant::now() < deadline, "the slots were not released");
        std::thread::sleep(Duration::from_millis(10));
    }
    m.stop();
}

/// The README's "Coordinated motion" example over real HTTP: x and y as group 1, a square with
/// rounded corners, a buffered output, and a circle; the group in `/state`, its columns in the
/// trace, a refused bad motion.
#[test]
fn control_runs_a_group_through_a_rounded_square_and_a_circle() {
    let m = Mcemu::start("virtual", &[]);
    let replies = m.command(json!([
        {"type": "enable", "axis": 0},
        {"type": "enable", "axis": 1},
        {"type": "group_create", "group": 1, "axes": [0, 1]},
        {"type": "group_enable", "group": 1},
    ]));
    assert_eq!(replies.as_array().map(Vec::len), Some(4));
    let g = &m.state()["groups"][0];
    assert_eq!(
        (g["group"].as_u64(), g["state"].as_str()),
        (Some(1), Some("standby"))
    );
    assert_eq!(g["axes"], json!([0, 1]));
    assert!(has_flag(&m.axis(0), "in_group"));
    // A grouped axis takes no single-axis motion; a motion with one coordinate too few is
    // refused with the reason.
    let e = m
        .post(
            "/api/v1/commands",
            json!({"type": "move_absolute", "axis": 0, "position": 5}),
        )
        .expect(422);
    assert_eq!(e["code"], "invalid_state");
    assert_eq!(
        e["message"],
        "axis 0 is in group 1: it takes no single-axis motion"
    );
    let e = m
        .post(
            "/api/v1/commands",
            json!({"type": "move_linear_absolute", "group": 1, "position": [5]}),
        )
        .expect(422);
    assert_eq!(e["code"], "invalid_argument");
    assert_eq!(
        e["message"],
        "group 1: position has 1 coordinates; the group has 2 axes"
    );
    m.post("/api/v1/trace/start", json!({})).expect(200);
    let corner = |x: f64, y: f64| {
        json!({"type": "move_linear_absolute", "group": 1, "position": [x, y], "velocity": 50,
               "buffer_mode": "blending_low", "transition": {"corner_distance": 5}})
    };
    let replies = m.command(json!([
        corner(40.0, 0.0),
        corner(40.0, 40.0),
        corner(0.0, 40.0),
        {"type": "move_linear_absolute", "group": 1, "position": [0, 0], "velocity": 50},
        {"type": "group_set_output", "group": 1, "channel": 1, "value": true},
        {"type": "move_linear_relative", "group": 1, "distance": [0, 20], "velocity": 50},
        {"type": "move_circular_absolute", "group": 1, "mode": "center", "aux_point": [20, 20],
         "end_point": [0, 20], "direction": "ccw", "velocity": 50, "user_segment": 7},
    ]));
    let circle = replies[6]["id"].as_u64().unwrap();
    let reached = m.advance(json!({"seconds": 1.0}));
    assert_eq!(reached["tick"], 1000);
    let g = &m.state()["groups"][0];
    assert_eq!(g["state"], "moving");
    assert!(f(&g["path_velocity"]) > 1.0, "{g}");
    assert_eq!(g["queue_used"], 7 - g["segment"].as_u64().unwrap() + 1);
    assert_eq!(m.axis(0)["state"], "synchronized_motion");
    assert_eq!(m.state()["io"]["do"][1], false);
    let done = m.advance(json!({"seconds": 20, "until": {"group": 1, "group_state": "standby"}}));
    assert_eq!(done["met"], true, "{done}");
    let state = m.state();
    let g = &state["groups"][0];
    assert_eq!(g["position"], json!([0.0, 20.0]));
    assert_eq!(
        (g["queue_used"].as_u64(), g["user_segment"].as_u64()),
        (Some(0), Some(7))
    );
    assert_eq!(state["io"]["do"][1], true);
    assert_eq!(
        m.command(json!({"type": "command_state", "id": circle}))["state"],
        "done"
    );
    // The trace's x and y rows carry the group's columns.
    m.post("/api/v1/trace/stop", json!({})).expect(200);
    let csv = m.get("/api/v1/trace").body;
    let (header, rows) = parse_csv(&csv);
    let (group, speed) = (column(&header, "group"), column(&header, "path_velocity"));
    assert!(
        rows.iter().all(|r| r[group] == "1"),
        "every row is a member's"
    );
    let fastest = rows
        .iter()
        .map(|r| r[speed].parse::<f64>().unwrap())
        .fold(0.0, f64::max);
    assert!((fastest - 50.0).abs() < 1e-9, "{fastest}");
    m.stop();
}
