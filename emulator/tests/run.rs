//! `mcemu run` end to end: the real binary comes up, reports its listeners, honours its flags,
//! and stops cleanly on SIGINT and SIGTERM.

// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

/// A running `mcemu`, killed if the test fails before stopping it.
struct Mcemu {
    child: Child,
    lines: mpsc::Receiver<String>,
}

impl Mcemu {
    fn start(args: &[&str]) -> Mcemu {
        let mut child = Command::new(env!("CARGO_BIN_EXE_mcemu"))
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start mcemu");
        let stdout = child.stdout.take().expect("stdout");
        let (tx, lines) = mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        Mcemu { child, lines }
    }

    /// The next stdout line; generous timeout so a loaded CI machine does not flake.
    fn line(&self) -> String {
        self.lines
            .recv_timeout(Duration::from_secs(30))
            .expect("mcemu printed nothing for 30 s")
    }

    /// Read lines until one starts with `prefix`.
    fn until(&self, prefix: &str) -> String {
        loop {
            let line = self.line();
            if line.starts_with(prefix) {
                return line;
            }
        }
    }

    fn signal(&self, signal: &str) {
        let status = Command::new("kill")
            .args([&format!("-{signal}"), &self.child.id().to_string()])
            .status()
            .expect("kill");
        assert!(status.success());
    }

    /// Wait for the exit; returns the status and everything left on stdout.
    fn wait(mut self) -> (std::process::ExitStatus, Vec<String>) {
        let status = self.child.wait().expect("wait");
        // The process has exited: the reader thread ends at EOF, after the last line.
        let rest: Vec<String> = self.lines.iter().collect();
        (status, rest)
    }
}

impl Drop for Mcemu {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn temp_config(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("mcemu-run-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn the_default_machine_comes_up_reports_its_listeners_and_stops_on_sigint() {
    let m = Mcemu::start(&["run"]);
    let banner = m.line();
    assert!(
        banner.starts_with("mcemu: machine default, 4 axes, servo period 1 ms, clock realtime"),
        "{banner}"
    );
    // Every front-end of the default machine, the control API last.
    let listening: Vec<String> = (0..7).map(|_| m.until("listening: ")).collect();
    assert_eq!(listening[0], "listening: modbus-tcp 127.0.0.1:1502");
    let pty = listening[1]
        .strip_prefix("listening: modbus-rtu /dev/pts/")
        .unwrap_or_else(|| panic!("{listening:?}"));
    assert!(std::path::Path::new(&format!("/dev/pts/{pty}")).exists());
    assert_eq!(
        listening[2],
        "listening: modbus-rtu-over-tcp 127.0.0.1:1503"
    );
    assert_eq!(listening[3], "listening: ascii-native 127.0.0.1:3999");
    assert_eq!(listening[4], "listening: ascii-user 127.0.0.1:4000");
    assert_eq!(listening[5], "listening: nmc 127.0.0.1:7700");
    assert_eq!(listening[6], "listening: control 127.0.0.1:8700");
    // The ports really are open.
    for port in [1502, 1503, 3999, 4000, 7700, 8700] {
        TcpStream::connect(("127.0.0.1", port)).expect("the port accepts connections");
    }
    m.signal("INT");
    let (status, rest) = m.wait();
    assert!(status.success(), "{status}");
    assert!(rest.iter().any(|l| l == "mcemu: stopped"), "{rest:?}");
}

#[test]
fn state_lists_the_listeners_the_listening_lines_announced() {
    let m = Mcemu::start(&["run", "--any-port"]);
    let mut announced = Vec::new();
    loop {
        let line = m.until("listening: ");
        let rest = line.strip_prefix("listening: ").unwrap();
        let (protocol, address) = rest.split_once(' ').unwrap();
        announced.push(serde_json::json!({"protocol": protocol, "address": address}));
        if protocol == "control" {
            break;
        }
    }
    let control = announced.last().unwrap()["address"]
        .as_str()
        .unwrap()
        .to_string();
    let body = ureq::get(format!("http://{control}/api/v1/state"))
        .call()
        .unwrap()
        .body_mut()
        .read_to_string()
        .unwrap();
    let state: serde_json::Value = serde_json::from_str(&body).unwrap();
    // Every line, in order, with the port that was really bound (`--any-port` asked for 0).
    assert_eq!(
        state["listeners"],
        serde_json::Value::Array(announced.clone())
    );
    assert!(announced.len() >= 5, "{announced:?}");
    assert!(announced
        .iter()
        .all(|l| !l["address"].as_str().unwrap().ends_with(":0")));
    m.signal("INT");
    let (status, _) = m.wait();
    assert!(status.success(), "{status}");
}

#[test]
fn flags_override_the_clock_and_period_and_sigterm_stops_cleanly() {
    let config = temp_config(
        "flags.toml",
        "[machine]\nname = \"flags\"\n[[axes]]\n[frontends.control]\nbind = \"127.0.0.1:0\"\n",
    );
    let m = Mcemu::start(&[
        "run",
        "--config",
        config.to_str().unwrap(),
        "--clock",
        "scaled:2",
        "--period",
        "250us",
    ]);
    let banner = m.line();
    assert_eq!(
        banner,
        "mcemu: machine flags, 1 axes, servo period 0.25 ms, clock scaled:2"
    );
    let listening = m.until("listening: control 127.0.0.1:");
    let port: u16 = listening.rsplit(':').next().unwrap().parse().unwrap();
    assert_ne!(port, 0, "the actual port is reported, not the requested 0");
    m.signal("TERM");
    let (status, rest) = m.wait();
    assert!(status.success(), "{status}");
    assert!(rest.iter().any(|l| l == "mcemu: stopped"), "{rest:?}");
}

#[test]
fn bad_flags_and_configs_exit_non_zero_with_a_message() {
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_mcemu"))
            .args(args)
            .output()
            .unwrap();
        (
            out.status,
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let (status, err) = run(&["run", "--clock", "fast"]);
    assert!(!status.success());
    assert!(err.contains("`fast` is not a clock"), "{err}");
    let (status, err) = run(&["run", "--period", "20ms"]);
    assert!(!status.success());
    assert!(
        err.contains("machine.period") && err.contains("--period"),
        "{err}"
    );
    let (status, err) = run(&["run", "--period", "fast"]);
    assert!(!status.success());
    assert!(err.contains("is not a period"), "{err}");
    let (status, err) = run(&["run", "--config", "/nonexistent/machine.toml"]);
    assert!(!status.success());
    assert!(
        err.contains("/nonexistent/machine.toml") && err.contains("cannot read it"),
        "{err}"
    );
    // A port that is already taken is an error naming the protocol and address.
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let address = taken.local_addr().unwrap();
    let config = temp_config(
        "taken.toml",
        &format!("[frontends.control]\nbind = \"{address}\"\n"),
    );
    let (status, err) = run(&["run", "--config", config.to_str().unwrap()]);
    assert!(!status.success());
    assert!(
        err.contains(&format!("cannot listen on {address} for control")),
        "{err}"
    );
}
