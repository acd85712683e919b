//! Shared helpers of the cross-crate integration tests in `tests/tests/`, and of any crate's
//! tests that drive mcemu with external tools (`mcemu-tests = { path = "../tests" }` as a
//! dev-dependency).
//!
//! The external tools come from `scripts/setup` (which `scripts/test` runs first): Debian's
//! `mbpoll` and `socat`, and a venv in `.venv/` with the pinned Python clients of
//! `scripts/requirements-test.txt`. A helper that cannot find its tool **panics** with the
//! install step to run: a test that needs a tool fails loudly without it, it never skips.
//!
//! Every helper that runs a process bounds it in time and kills it on timeout; every process
//! handle kills its process on drop.

// Test-support code: a panic is how a helper fails the test that called it.
#![allow(clippy::panic, clippy::expect_used, clippy::unwrap_used)]

use std::ffi::OsStr;
use std::io::{BufRead, BufReader, Read, Write};
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStderr, ChildStdout, Command, ExitStatus, Output, Stdio};
use std::sync::{mpsc, Arc, Mutex};
use std::thread::{self, JoinHandle};
use std::time::{Duration, Instant};

mod ascii;
mod browser;
mod mcemu;
mod modbus;
mod nmc;
mod socketcand;

pub use ascii::{run_transcript, AsciiClient, ASCII_REPLY_TIMEOUT};
pub use browser::{run_dashboard_scenario, run_web_unit_tests, CHROMIUM};
pub use mcemu::{
    cargo_test_executable, mcemu_bin, mcemu_release_bin, wait_for, Mcemu, McemuExit, TempDir,
    STOP_TIMEOUT,
};
pub use modbus::{
    crc16, hex, mbap_frame, mbpoll, mbpoll_values, rtu_frame, to_hex, ByteLink, MbapClient,
    MbapReply, RawSerial, REPLY_TIMEOUT,
};
pub use nmc::{compile_example, nmc_include_dir, nmc_library_dir, run_example, PROGRAM_TIMEOUT};
pub use socketcand::{RawFrame, Socketcand};

/// How long [`run_python_client`] lets one client run before killing it.
pub const CLIENT_TIMEOUT: Duration = Duration::from_secs(60);
/// How long a server or `socat` may take to say it is ready.
pub const READY_TIMEOUT: Duration = Duration::from_secs(30);

/// The workspace root (the directory of the root `Cargo.toml`).
pub fn workspace_root() -> PathBuf {
    let tests = Path::new(env!("CARGO_MANIFEST_DIR"));
    tests
        .parent()
        .expect("tests/ has a parent directory")
        .to_path_buf()
}

/// A fresh, empty directory `root/name-PID`. Tests pass `env!("CARGO_TARGET_TMPDIR")` as `root`:
/// it is inside the directories the vcan harness mounts read-write in its VM.
pub fn fresh_dir(root: &str, name: &str) -> PathBuf {
    let dir = Path::new(root).join(format!("{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Everything a failed assertion about a finished process should show: what it was, its exit
/// status, stdout and stderr.
pub fn output_report(what: &str, out: &Output) -> String {
    format!(
        "{what}: {}\n--- stdout\n{}\n--- stderr\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

/// A script of the external-client harness, `tests/python/NAME`.
pub fn python_script(name: &str) -> PathBuf {
    let path = workspace_root().join("tests/python").join(name);
    assert!(path.is_file(), "{} does not exist", path.display());
    path
}

/// The venv's interpreter, `.venv/bin/python` under the workspace root, with the pinned test
/// clients installed. Panics, naming the step to run, when `scripts/setup` has not completed.
pub fn python() -> PathBuf {
    let root = workspace_root();
    let python = root.join(".venv/bin/python");
    // scripts/setup writes the stamp last, after every package installed.
    let stamp = root.join(".venv/.requirements.sha256");
    if !python.is_file() || !stamp.is_file() {
        panic!(
            "{} (with the packages of scripts/requirements-test.txt) is missing: \
             run scripts/setup",
            python.display()
        );
    }
    python
}

/// The path of the executable `name` on `PATH`, or a panic that names the install step.
pub fn require_tool(name: &str) -> PathBuf {
    let path = std::env::var_os("PATH").unwrap_or_default();
    for dir in std::env::split_paths(&path) {
        let candidate = dir.join(name);
        if let Ok(meta) = std::fs::metadata(&candidate) {
            if meta.is_file() && meta.permissions().mode() & 0o111 != 0 {
                return candidate;
            }
        }
    }
    panic!(
        "`{name}` is not on PATH: run scripts/setup (it apt-installs mbpoll, socat and \
         python3-venv; by hand: apt-get install {name})"
    );
}

/// Read a pipe to its end on a thread.
fn drain<R: Read + Send + 'static>(mut pipe: R) -> JoinHandle<Vec<u8>> {
    thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = pipe.read_to_end(&mut buf);
        buf
    })
}

/// Run `command` to completion with `stdin` as its input, killing it after `timeout`.
/// Returns its status and output; panics (with what it printed) only on timeout or when it
/// cannot be started.
pub fn run_with_timeout(mut command: Command, stdin: &[u8], timeout: Duration) -> Output {
    let what = format!("{command:?}");
    let mut child = command
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {what}: {e}"));
    let mut input = child.stdin.take().expect("piped stdin");
    let stdin = stdin.to_vec();
    let writer = thread::spawn(move || {
        let _ = input.write_all(&stdin);
        // Dropping `input` closes the pipe: the child sees the end of its input.
    });
    let out = drain(child.stdout.take().expect("piped stdout"));
    let err = drain(child.stderr.take().expect("piped stderr"));
    // The readers end when the child closes its pipes, i.e. when it exits (or is killed).
    let (done_tx, done_rx) = mpsc::channel();
    let waiter = thread::spawn(move || {
        let out = out.join().unwrap_or_default();
        let err = err.join().unwrap_or_default();
        let _ = done_tx.send(());
        (out, err)
    });
    let timed_out = done_rx.recv_timeout(timeout).is_err();
    if timed_out {
        let _ = child.kill();
    }
    let status = child.wait().expect("wait for child");
    let (stdout, stderr) = waiter.join().expect("pipe readers");
    let _ = writer.join();
    if timed_out {
        panic!(
            "{what} did not finish within {timeout:?} and was killed\n--- stdout\n{}\n--- stderr\n{}",
            String::from_utf8_lossy(&stdout),
            String::from_utf8_lossy(&stderr)
        );
    }
    Output {
        status,
        stdout,
        stderr,
    }
}

/// Run `tests/python/modbus_client.py` with `args` (`--client`, `--transport`, `--port` …)
/// and the operations `ops` (a JSON array) on stdin; return its results (a JSON array, one
/// result per operation: `{"ok": …}`, `{"exception": code}` or `{"error": "…"}`).
///
/// Panics with the script's stderr when it exits non-zero (a usage error, or it could not
/// connect), prints something that is not JSON, or runs longer than [`CLIENT_TIMEOUT`].
pub fn run_python_client<I, S>(args: I, ops: &serde_json::Value) -> serde_json::Value
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    run_python_client_with_timeout(args, ops, CLIENT_TIMEOUT)
}

/// [`run_python_client`] as pymodbus over Modbus TCP to `port` on localhost.
pub fn run_pymodbus_tcp(port: &str, ops: &serde_json::Value) -> serde_json::Value {
    run_python_client(
        ["--client", "pymodbus", "--transport", "tcp", "--port", port],
        ops,
    )
}

/// [`run_python_client`] with another time bound.
pub fn run_python_client_with_timeout<I, S>(
    args: I,
    ops: &serde_json::Value,
    timeout: Duration,
) -> serde_json::Value
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let mut command = Command::new(python());
    command.arg(python_script("modbus_client.py")).args(args);
    let what = format!("{command:?}");
    let output = run_with_timeout(command, ops.to_string().as_bytes(), timeout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    let stdout = String::from_utf8_lossy(&output.stdout);
    if !output.status.success() {
        panic!(
            "{what} failed ({})\n--- stdin\n{ops}\n--- stderr\n{stderr}\n--- stdout\n{stdout}",
            output.status
        );
    }
    let results: serde_json::Value = serde_json::from_str(&stdout).unwrap_or_else(|e| {
        panic!("{what} printed no JSON ({e})\n--- stdout\n{stdout}\n--- stderr\n{stderr}")
    });
    let n = ops.as_array().map_or(0, Vec::len);
    assert_eq!(
        results.as_array().map(Vec::len),
        Some(n),
        "{what}: one result per operation expected\n--- results\n{results}"
    );
    results
}

/// A child process that is killed (and reaped) when this value is dropped.
#[derive(Debug)]
pub struct KillOnDrop {
    child: Child,
    stderr: Option<JoinHandle<Vec<u8>>>,
}

impl KillOnDrop {
    pub fn id(&self) -> u32 {
        self.child.id()
    }

    pub fn child(&mut self) -> &mut Child {
        &mut self.child
    }

    /// Stop the process now: SIGKILL, then reap it. Returns what it wrote on stderr.
    pub fn kill(&mut self) -> String {
        let _ = self.child.kill();
        let _ = self.child.wait();
        self.stderr
            .take()
            .and_then(|h| h.join().ok())
            .map(|b| String::from_utf8_lossy(&b).into_owned())
            .unwrap_or_default()
    }

    /// Whether it has exited, and how.
    pub fn try_wait(&mut self) -> Option<ExitStatus> {
        self.child.try_wait().ok().flatten()
    }
}

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Start `command` and wait until a line of its stdout starts with `prefix`; return the
/// process and the rest of that line (e.g. the address after `ready `). The remaining stdout
/// and the stderr are drained on threads so the process never blocks on a full pipe. Its stdin
/// is a pipe that stays open until the process is dropped: a child may treat the end of its
/// input as its parent being gone.
///
/// Panics with the process's stderr when it exits first or says nothing within `timeout`.
pub fn spawn_until_line(
    mut command: Command,
    prefix: &str,
    timeout: Duration,
) -> (KillOnDrop, String) {
    let what = format!("{command:?}");
    let mut child = command
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {what}: {e}"));
    let stdout: ChildStdout = child.stdout.take().expect("piped stdout");
    let stderr: ChildStderr = child.stderr.take().expect("piped stderr");
    let mut process = KillOnDrop {
        child,
        stderr: Some(drain(stderr)),
    };
    let (tx, rx) = mpsc::channel();
    let seen = Arc::new(Mutex::new(Vec::<String>::new()));
    let seen_by_reader = Arc::clone(&seen);
    let prefix_owned = prefix.to_string();
    thread::spawn(move || {
        let mut lines = BufReader::new(stdout).lines();
        for line in lines.by_ref() {
            let Ok(line) = line else { break };
            if let Some(rest) = line.strip_prefix(&prefix_owned) {
                let _ = tx.send(Some(rest.trim().to_string()));
                // Keep draining.
                for _ in lines.by_ref() {}
                return;
            }
            if let Ok(mut seen) = seen_by_reader.lock() {
                seen.push(line);
            }
        }
        let _ = tx.send(None);
    });
    let outcome = rx.recv_timeout(timeout);
    if let Ok(Some(rest)) = outcome {
        return (process, rest);
    }
    let stderr = process.kill();
    let seen = seen.lock().map(|s| s.join("\n")).unwrap_or_default();
    let why = match outcome {
        Ok(_) => "exited before printing".to_string(),
        Err(_) => format!("did not print within {timeout:?}"),
    };
    panic!("{what} {why} `{prefix}…`\n--- stdout\n{seen}\n--- stderr\n{stderr}")
}

/// The plain pymodbus server of `tests/python/modbus_server_pymodbus.py` (a harness peer and
/// benchmark baseline, not mcemu), killed on drop.
#[derive(Debug)]
pub struct PymodbusServer {
    pub process: KillOnDrop,
    /// `127.0.0.1:PORT` for TCP, or the device path for RTU on a serial line.
    pub address: String,
}

impl PymodbusServer {
    /// Modbus TCP on 127.0.0.1, any free port.
    pub fn tcp() -> PymodbusServer {
        PymodbusServer::start(&["--port", "0"])
    }

    /// RTU over TCP on 127.0.0.1, any free port.
    pub fn rtu_over_tcp() -> PymodbusServer {
        PymodbusServer::start(&["--port", "0", "--framer", "rtu"])
    }

    /// RTU on a serial device (e.g. one end of a [`PtyPair`]) at 19 200 baud.
    pub fn rtu(device: &Path) -> PymodbusServer {
        let device = device.to_str().expect("UTF-8 device path");
        PymodbusServer::start(&["--device", device])
    }

    fn start(args: &[&str]) -> PymodbusServer {
        let mut command = Command::new(python());
        command
            .arg(python_script("modbus_server_pymodbus.py"))
            .args(args);
        let (process, address) = spawn_until_line(command, "ready ", READY_TIMEOUT);
        PymodbusServer { process, address }
    }

    /// The TCP port (panics for a serial server).
    pub fn port(&self) -> u16 {
        self.address
            .rsplit_once(':')
            .and_then(|(_, p)| p.parse().ok())
            .unwrap_or_else(|| panic!("not a TCP address: {}", self.address))
    }
}

/// Two connected pseudo-terminals made by `socat -d -d pty,raw,echo=0 pty,raw,echo=0`: bytes
/// written to one come out of the other, as on a null-modem cable. `socat` is killed on drop.
#[derive(Debug)]
pub struct PtyPair {
    pub a: PathBuf,
    pub b: PathBuf,
    process: KillOnDrop,
}

impl PtyPair {
    /// Panics (naming scripts/setup) when socat is missing, and with socat's stderr when it
    /// does not report two ptys and its transfer loop within [`READY_TIMEOUT`].
    pub fn new() -> PtyPair {
        let socat = require_tool("socat");
        let mut child = Command::new(&socat)
            .args(["-d", "-d", "pty,raw,echo=0", "pty,raw,echo=0"])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start {}: {e}", socat.display()));
        let stderr = child.stderr.take().expect("piped stderr");
        let (tx, rx) = mpsc::channel();
        // socat -d -d logs `N PTY is /dev/pts/N` twice, then `N starting data transfer loop`.
        let reader = thread::spawn(move || {
            let mut log = Vec::new();
            let mut ptys = Vec::new();
            let mut lines = BufReader::new(stderr).lines();
            for line in lines.by_ref() {
                let Ok(line) = line else { break };
                if let Some(at) = line.find("PTY is ") {
                    ptys.push(PathBuf::from(line[at + 7..].trim()));
                }
                let started = line.contains("starting data transfer loop");
                log.extend_from_slice(line.as_bytes());
                log.push(b'\n');
                if started {
                    let _ = tx.send(Ok(ptys.clone()));
                    break;
                }
            }
            if ptys.len() < 2 {
                let _ = tx.send(Err(()));
            }
            // Keep draining (socat logs again when a side closes).
            for line in lines.map_while(Result::ok) {
                log.extend_from_slice(line.as_bytes());
                log.push(b'\n');
            }
            log
        });
        let mut process = KillOnDrop {
            child,
            stderr: Some(reader),
        };
        let deadline = Instant::now() + READY_TIMEOUT;
        match rx.recv_timeout(deadline.saturating_duration_since(Instant::now())) {
            Ok(Ok(ptys)) if ptys.len() == 2 => PtyPair {
                a: ptys[0].clone(),
                b: ptys[1].clone(),
                process,
            },
            _ => {
                let log = process.kill();
                panic!("socat did not set up a pty pair within {READY_TIMEOUT:?}\n{log}")
            }
        }
    }

    /// socat's process id.
    pub fn pid(&self) -> u32 {
        self.process.id()
    }
}

impl Default for PtyPair {
    fn default() -> Self {
        PtyPair::new()
    }
}
