//! The real `mcemu` binary under test: found (and built when its sources are newer), started
//! with every TCP listener on an ephemeral port and a fresh state directory, its `listening:`
//! lines read, its control API at hand, stopped with SIGTERM or killed on drop.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::OnceLock;
use std::thread;
use std::time::{Duration, Instant, SystemTime};

use serde_json::Value;

use crate::{workspace_root, READY_TIMEOUT};

pub use mcemu_harness::STOP_TIMEOUT;

/// The `mcemu` binary of this build: `$MCEMU_BIN` if set, else `mcemu` in the profile directory
/// of the running test executable (`target/debug/`), built first with `cargo build -p mcemu
/// --bin mcemu` when it is missing or older than a source it is built from. (Tests of another
/// package cannot use `CARGO_BIN_EXE_mcemu`; `cargo nextest run --workspace` has built the binary
/// already, `cargo nextest run -p mcemu-tests` may not have.) Checked once per process.
pub fn mcemu_bin() -> PathBuf {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| mcemu_in("MCEMU_BIN", profile_dir()))
        .clone()
}

/// The optimised `mcemu` binary: `$MCEMU_RELEASE_BIN` if set, else `<target>/release/mcemu`,
/// built first with `cargo build --release -p mcemu --bin mcemu` when it is missing or older than
/// a source, as [`mcemu_bin`]. For tests whose figures depend on the servo thread keeping up with the wall clock where
/// a debug build cannot: under the vcan VM's TCG a debug tick takes longer than the 1 ms period
/// (`./scripts/test` builds it before the tests, so this only checks). Checked once per process.
pub fn mcemu_release_bin() -> PathBuf {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        let target = profile_dir()
            .parent()
            .expect("the profile directory lies in the target directory")
            .join("release");
        mcemu_in("MCEMU_RELEASE_BIN", target)
    })
    .clone()
}

/// `$env_var` if set, else `mcemu` in `profile_dir`, built first when it is missing or older
/// than a source it is built from.
fn mcemu_in(env_var: &str, profile_dir: PathBuf) -> PathBuf {
    if let Some(bin) = std::env::var_os(env_var) {
        let bin = PathBuf::from(bin);
        assert!(bin.is_file(), "{env_var}={} is not a file", bin.display());
        return bin;
    }
    let bin = profile_dir.join("mcemu");
    let built = modified(&bin);
    let newest_source = newest_source();
    if built.is_none_or(|b| newest_source.is_some_and(|s| s > b)) {
        build_mcemu(&profile_dir);
    }
    assert!(bin.is_file(), "{} was not built", bin.display());
    bin
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// The latest modification among the files the binary is built from.
fn newest_source() -> Option<SystemTime> {
    fn walk(dir: &Path, newest: &mut Option<SystemTime>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, newest);
            } else if let Some(t) = modified(&path) {
                *newest = Some(newest.map_or(t, |n| n.max(t)));
            }
        }
    }
    let root = workspace_root();
    let mut newest = None;
    let mut dirs = vec![root.join("fixtures")];
    let mut files = vec![root.join("Cargo.lock"), root.join("Cargo.toml")];
    // Every crate of the workspace (axes, profile, path, emulator, and each protocol crate
    // under protocols/): the binary links them all; this test crate does not count.
    let crate_dirs = |dir: PathBuf| {
        std::fs::read_dir(dir)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.join("Cargo.toml").is_file() && p.join("src").is_dir())
            .collect::<Vec<_>>()
    };
    for krate in crate_dirs(root.clone())
        .into_iter()
        .chain(crate_dirs(root.join("protocols")))
        .filter(|p| p.file_name().is_some_and(|n| n != "tests"))
    {
        dirs.push(krate.join("src"));
        files.push(krate.join("Cargo.toml"));
    }
    for dir in &dirs {
        walk(dir, &mut newest);
    }
    for file in &files {
        if let Some(t) = modified(file) {
            newest = Some(newest.map_or(t, |n: SystemTime| n.max(t)));
        }
    }
    newest
}

/// The directory of the running test executable's profile (`<target>/debug`).
pub(crate) fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test executable's path");
    // target/<profile>/deps/<test>-<hash>
    exe.parent()
        .and_then(Path::parent)
        .expect("the test executable lives in <target>/<profile>/deps")
        .to_path_buf()
}

/// `cargo` with the target directory and profile of the running test executable.
pub(crate) fn cargo_in_profile(profile_dir: &Path, subcommand: &[&str]) -> Command {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut command = Command::new(cargo);
    command.current_dir(workspace_root()).args(subcommand);
    if let Some(target) = profile_dir.parent() {
        command.arg("--target-dir").arg(target);
    }
    match profile_dir.file_name().and_then(|n| n.to_str()) {
        Some("debug") | None => {}
        Some("release") => {
            command.arg("--release");
        }
        Some(profile) => {
            command.args(["--profile", profile]);
        }
    }
    command
}

/// The executable of integration test `test` of package `package`, in this build's target
/// directory and profile: `cargo test -p PACKAGE --test TEST --no-run` (which builds it when its
/// sources changed, and otherwise only checks) names it. For tests that run another crate's
/// tests elsewhere, e.g. inside the vcan VM.
pub fn cargo_test_executable(package: &str, test: &str) -> PathBuf {
    let mut command = cargo_in_profile(
        &profile_dir(),
        &[
            "test",
            "-p",
            package,
            "--test",
            test,
            "--no-run",
            "--message-format=json-render-diagnostics",
        ],
    );
    let what = format!("{command:?}");
    let output = command
        .stderr(Stdio::piped())
        .output()
        .unwrap_or_else(|e| panic!("cannot run {what}: {e}"));
    assert!(
        output.status.success(),
        "{what} failed\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|line| serde_json::from_str::<Value>(line).ok())
        .filter(|m| m["reason"] == "compiler-artifact" && m["target"]["name"] == test)
        .find_map(|m| m["executable"].as_str().map(PathBuf::from))
        .unwrap_or_else(|| panic!("{what} named no executable for test `{test}`"))
}

fn build_mcemu(profile_dir: &Path) {
    let mut command = cargo_in_profile(profile_dir, &["build", "-p", "mcemu", "--bin", "mcemu"]);
    let what = format!("{command:?}");
    let output = command
        .output()
        .unwrap_or_else(|e| panic!("cannot run {what}: {e}"));
    assert!(
        output.status.success(),
        "{what} failed\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// A directory under the system's temp directory, removed (with its contents) on drop.
#[derive(Debug)]
pub struct TempDir(mcemu_harness::TempDir);

impl TempDir {
    pub fn new(label: &str) -> TempDir {
        TempDir(
            mcemu_harness::TempDir::new(&format!("tests-{label}"))
                .unwrap_or_else(|e| panic!("{e}")),
        )
    }

    pub fn path(&self) -> &Path {
        self.0.path()
    }
}

/// How a stopped `mcemu` ended.
pub type McemuExit = mcemu_harness::Exit;

/// A running `mcemu run` (the users' harness, `mcemu_harness::Machine`, with this workspace's
/// binary), killed on drop. Its helpers panic with the request and reply: a failed call fails
/// the test that made it.
pub struct Mcemu {
    machine: mcemu_harness::Machine,
    /// `listening:` lines in order: (protocol, address), e.g. ("modbus-tcp", "127.0.0.1:4711").
    pub listeners: Vec<(String, String)>,
    /// `http://127.0.0.1:PORT/api/v1`.
    pub api: String,
    /// The state directory it was given.
    pub state_dir: PathBuf,
}

impl std::fmt::Debug for Mcemu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.machine.fmt(f)
    }
}

impl Mcemu {
    /// `mcemu run [--config CONFIG] ARGS…` on the realtime clock unless `args` says otherwise,
    /// with every TCP listener of the config on a free port (`--any-port`; `args` may pin one
    /// with `--set`) and a fresh temporary `--state-dir` unless `args` has one. Returns once the
    /// control API's `listening:` line (printed last, so every listener is up) has been read;
    /// panics with what the process printed if it exits or stays silent first.
    pub fn start(config: Option<&Path>, args: &[&str]) -> Mcemu {
        let mut options = mcemu_harness::Options::new(mcemu_bin())
            .clock(None)
            .ready_timeout(READY_TIMEOUT)
            .args(args.iter().copied());
        if let Some(path) = config {
            options = options.config(path);
        }
        let machine = options.start().unwrap_or_else(|e| panic!("{e}"));
        Mcemu {
            listeners: machine.listeners.clone(),
            api: machine.api.clone(),
            state_dir: machine.state_dir.clone().unwrap_or_default(),
            machine,
        }
    }

    pub fn pid(&self) -> u32 {
        self.machine.pid()
    }

    /// Whether it has exited, and how.
    pub fn try_wait(&mut self) -> Option<ExitStatus> {
        self.machine.try_wait()
    }

    /// The address of the `listening: PROTOCOL ADDRESS` line (a pty path for `modbus-rtu`).
    pub fn address(&self, protocol: &str) -> &str {
        self.machine
            .address(protocol)
            .unwrap_or_else(|| panic!("no `listening: {protocol}` line in {:?}", self.listeners))
    }

    /// The port of a TCP listener, as text for command lines.
    pub fn port(&self, protocol: &str) -> String {
        let address = self.address(protocol);
        address
            .rsplit_once(':')
            .map(|(_, p)| p.to_string())
            .unwrap_or_else(|| panic!("not a TCP address: {address}"))
    }

    /// Every listener by protocol.
    pub fn listener_map(&self) -> BTreeMap<String, String> {
        self.listeners.iter().cloned().collect()
    }

    /// Everything printed on stdout so far.
    pub fn stdout_text(&self) -> String {
        self.machine.stdout_text()
    }

    /// Everything printed on stderr so far.
    pub fn stderr_text(&self) -> String {
        self.machine.stderr_text()
    }

    /// `GET /api/v1PATH`, which must answer 200; its JSON.
    pub fn get(&self, path: &str) -> Value {
        let (status, json) = self.machine.get_any(path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(status, 200, "GET {path}: {json}");
        json
    }

    /// `POST /api/v1PATH` with a JSON body: status and JSON reply.
    pub fn post(&self, path: &str, body: &Value) -> (u16, Value) {
        self.machine
            .post_any(path, body)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// `POST` that must answer 200; its JSON.
    pub fn post_ok(&self, path: &str, body: &Value) -> Value {
        let (status, json) = self.post(path, body);
        assert_eq!(status, 200, "POST {path} {body}: {json}");
        json
    }

    /// `GET /state`.
    pub fn state(&self) -> Value {
        self.get("/state")
    }

    /// `GET /state`'s `frontends` entry named `name` (`modbus_tcp` …).
    pub fn frontend(&self, name: &str) -> Value {
        let state = self.state();
        state["frontends"]
            .as_array()
            .and_then(|a| a.iter().find(|f| f["name"] == name))
            .cloned()
            .unwrap_or_else(|| panic!("no front-end `{name}` in {}", state["frontends"]))
    }

    /// `GET /state`'s `axes[axis]`.
    pub fn axis(&self, axis: usize) -> Value {
        self.state()["axes"][axis].clone()
    }

    /// `POST /time/advance` (virtual clock), e.g. `{"seconds": 1}`.
    pub fn advance(&self, body: &Value) -> Value {
        self.post_ok("/time/advance", body)
    }

    /// `POST /faults`, which must be accepted; returns `active_faults`.
    pub fn fault(&self, body: &Value) -> Value {
        self.post_ok("/faults", body)["active_faults"].clone()
    }

    /// SIGTERM, then wait (at most [`STOP_TIMEOUT`]) for the exit; everything it printed.
    pub fn terminate(self) -> McemuExit {
        self.machine.terminate().unwrap_or_else(|e| panic!("{e}"))
    }
}

/// Poll `probe` every 10 ms until it returns `Some`, for at most `timeout`; panics naming `what`
/// (and the last value seen, through `probe`'s own message) when the deadline passes. For
/// realtime behaviour only: on the virtual clock, advance time instead.
pub fn wait_for<T>(what: &str, timeout: Duration, mut probe: impl FnMut() -> Option<T>) -> T {
    let deadline = Instant::now() + timeout;
    loop {
        if let Some(v) = probe() {
            return v;
        }
        assert!(Instant::now() < deadline, "{what}: not within {timeout:?}");
        thread::sleep(Duration::from_millis(10));
    }
}
