//! The CAN bus's `candump -L` log, from the config and at run time through the control API
//! (`POST /api/v1/canopen/log/start`, `/stop`): the real `mcemu` binary on
//! `fixtures/cia402-can.toml` (virtual clock, the bus served over socketcand only), traffic from
//! a raw socketcand client (SDO uploads the nodes answer), and the log files read back.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;

use mcemu_tests::{workspace_root, Mcemu, Socketcand, TempDir};
use serde_json::{json, Value};

/// One `candump -L` line, `(SECS.USECS) vcan0 ID#DATA`, as its `ID#DATA`; `None` when the line
/// has another form.
fn candump_frame(line: &str) -> Option<&str> {
    let (stamp, rest) = line.split_once(' ')?;
    let (secs, micros) = stamp
        .strip_prefix('(')?
        .strip_suffix(')')?
        .split_once('.')?;
    let digits = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_digit());
    let (iface, frame) = rest.split_once(' ')?;
    let (id, data) = frame.split_once('#')?;
    let hex = |s: &str| s.chars().all(|c| c.is_ascii_hexdigit());
    (digits(secs)
        && digits(micros)
        && micros.len() == 6
        && iface == "vcan0"
        && id.len() == 3
        && hex(id)
        && data.len() % 2 == 0
        && hex(data))
    .then_some(frame)
}

/// A log file's frames (`ID#DATA`), every line checked to be candump -L's.
fn logged_frames(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    text.lines()
        .map(|line| {
            candump_frame(line)
                .unwrap_or_else(|| panic!("not a candump -L line: `{line}` in {}", path.display()))
                .to_string()
        })
        .collect()
}

#[test]
fn the_bus_log_starts_and_stops_through_the_control_api() {
    let dir = TempDir::new("canopen-log");
    let config_log = dir.path().join("from-config.log");
    let api_log = dir.path().join("from-api.log");
    let fixture = workspace_root().join("fixtures/cia402-can.toml");
    let m = Mcemu::start(
        Some(&fixture),
        &[
            "--clock",
            "virtual",
            "--set",
            r#"frontends.canopen.interface="""#,
            "--set",
            &format!(
                "frontends.canopen.log={:?}",
                config_log.display().to_string()
            ),
        ],
    );
    let canopen = m.frontend("canopen");
    assert_eq!(
        canopen["log"],
        json!({"path": config_log.display().to_string()}),
        "{canopen}"
    );
    let mut bus = Socketcand::open(m.address("socketcand"), "vcan0");

    // The config's log runs: a second one is refused.
    let (status, body) = m.post("/canopen/log/start", &json!({"path": api_log}));
    assert_eq!(
        (status, &body["error"]),
        (409, &json!("already_logging")),
        "{body}"
    );
    let a = bus.sdo_upload(1, 0x1000, 0);
    assert_eq!(a.1, "581#4300100092010200", "device type of node 1");

    // Stopping it (whoever started it) flushes the file before the answer.
    let stopped = m.post_ok("/canopen/log/stop", &json!({}));
    assert_eq!(stopped["path"], json!(config_log.display().to_string()));
    let frames = logged_frames(&config_log);
    assert_eq!(stopped["lines"], json!(frames.len()), "{stopped}");
    assert_eq!(stopped["dropped"], json!(0));
    // The nodes' boot-up messages (on the virtual clock the nodes start when the servo thread
    // first serves them, so they may follow the first request) and the SDO exchange, each once.
    let mut expected: Vec<String> = (1..=4).map(|id| format!("70{id}#00")).collect();
    expected.extend([a.0.clone(), a.1.clone()]);
    let mut sorted = frames.clone();
    sorted.sort();
    expected.sort();
    assert_eq!(sorted, expected, "{frames:?}");
    let at = |f: &str| frames.iter().position(|x| x == f).unwrap();
    assert!(
        at(&a.0) < at(&a.1),
        "the answer before the request: {frames:?}"
    );
    assert_eq!(m.frontend("canopen")["log"], Value::Null);
    let (status, body) = m.post("/canopen/log/stop", &json!({}));
    assert_eq!(
        (status, &body["error"]),
        (409, &json!("not_logging")),
        "{body}"
    );

    // Refusals: an existing file, a directory that does not exist, a body without a path.
    let (status, body) = m.post("/canopen/log/start", &json!({"path": config_log}));
    assert_eq!(
        (status, &body["error"]),
        (409, &json!("log_exists")),
        "{body}"
    );
    let nowhere = dir.path().join("no-such-dir/bus.log");
    let (status, body) = m.post("/canopen/log/start", &json!({"path": nowhere}));
    assert_eq!(
        (status, &body["error"]),
        (400, &json!("log_not_writable")),
        "{body}"
    );
    let (status, body) = m.post("/canopen/log/start", &json!({"file": "x.log"}));
    assert_eq!(
        (status, &body["error"]),
        (400, &json!("invalid_body")),
        "{body}"
    );
    assert_eq!(m.frontend("canopen")["log"], Value::Null);

    // A log started at run time has exactly the traffic between start and stop.
    let started = m.post_ok("/canopen/log/start", &json!({"path": api_log}));
    assert_eq!(
        started,
        json!({"logging": true, "bus": "vcan0", "path": api_log.display().to_string()})
    );
    assert_eq!(
        m.frontend("canopen")["log"]["path"],
        json!(api_log.display().to_string())
    );
    let b = bus.sdo_upload(2, 0x1018, 1);
    assert_eq!(b.1, "582#4318100100000000", "vendor id of node 2");
    let c = bus.sdo_upload(3, 0x6041, 0);
    let stopped = m.post_ok("/canopen/log/stop", &json!({}));
    assert_eq!(stopped["lines"], json!(4), "{stopped}");
    assert_eq!(logged_frames(&api_log), [b.0, b.1, c.0, c.1]);
    // The config's log ended with its stop: nothing after it.
    assert_eq!(logged_frames(&config_log), frames);

    let exit = m.terminate();
    assert!(exit.status.success(), "{}", exit.stderr);
}
