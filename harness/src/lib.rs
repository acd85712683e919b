//! Run mcemu from Rust tests: start `mcemu run` on free ports, read what listens where, drive
//! the control API, advance virtual time, stop it. mcemu's own integration tests use this crate
//! (through `mcemu-tests`), so the harness users get is the one mcemu depends on.
//!
//! ```no_run
//! use mcemu_harness::Options;
//! use serde_json::json;
//!
//! let m = Options::new("mcemu").machine("himc").start()?;   // virtual clock, free ports
//! m.command(&json!({"type": "enable", "axis": 0}))?;
//! m.advance(&json!({"ticks": 1}))?;
//! assert!(m.state()?["axes"][0]["flags"].as_array().unwrap().contains(&json!("enabled")));
//! println!("Modbus TCP at {}", m.address("modbus-tcp").unwrap());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The inputs are an [`Options`] (which binary, which machine, clock, `--set` overrides, extra
//! arguments); [`Options::start`] returns a [`Machine`] once the control API's `listening:` line
//! (printed last, so every front-end listens) has been read, or a [`StartError`] with what mcemu
//! printed. A [`Machine`] is killed on drop; [`Machine::terminate`] stops it with SIGTERM and
//! returns its [`Exit`].

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::thread::{self, JoinHandle};
use std::time::{Duration, Instant, SystemTime};

use serde_json::Value;

/// How long `mcemu run` may take to print `listening: control` by default.
pub const READY_TIMEOUT: Duration = Duration::from_secs(60);
/// How long mcemu may take to stop after SIGTERM before [`Machine::terminate`] kills it.
pub const STOP_TIMEOUT: Duration = Duration::from_secs(30);
/// Bound of one control-API request.
const HTTP_TIMEOUT: Duration = Duration::from_secs(60);
/// Largest control-API reply read (a trace may be 110 MB of CSV; JSON replies are far smaller).
const MAX_REPLY: u64 = 256 << 20;

/// What to start: `Options::new(binary)`, then the builder methods, then [`Options::start`].
#[derive(Clone, Debug)]
pub struct Options {
    binary: PathBuf,
    config: Option<PathBuf>,
    machine: Option<String>,
    clock: Option<String>,
    state_dir: Option<PathBuf>,
    sets: Vec<String>,
    args: Vec<String>,
    any_port: bool,
    ready_timeout: Duration,
}

impl Options {
    /// The `mcemu` executable to run (a path, or a name found on `PATH`). Defaults: the embedded
    /// default machine, the virtual clock, every TCP listener on a free port, a fresh temporary
    /// state directory.
    pub fn new(binary: impl Into<PathBuf>) -> Options {
        Options {
            binary: binary.into(),
            config: None,
            machine: None,
            clock: Some("virtual".into()),
            state_dir: None,
            sets: Vec::new(),
            args: Vec::new(),
            any_port: true,
            ready_timeout: READY_TIMEOUT,
        }
    }

    /// A machine config file (`--config`).
    pub fn config(mut self, path: impl Into<PathBuf>) -> Options {
        self.config = Some(path.into());
        self
    }

    /// A shipped machine by name (`--machine`: `himc`, `gaochuan-gcn` …).
    pub fn machine(mut self, name: impl Into<String>) -> Options {
        self.machine = Some(name.into());
        self
    }

    /// `virtual` (the default), `realtime` or `scaled:K`; `None` keeps the config's clock.
    pub fn clock(mut self, clock: Option<&str>) -> Options {
        self.clock = clock.map(str::to_string);
        self
    }

    /// `--state-dir`; without it a temporary directory removed when the machine is dropped.
    pub fn state_dir(mut self, dir: impl Into<PathBuf>) -> Options {
        self.state_dir = Some(dir.into());
        self
    }

    /// A `--set key=value` override (the value is TOML: `"\"text\""`, `0.0005`, `true`).
    pub fn set(mut self, key: &str, toml_value: &str) -> Options {
        self.sets.push(format!("{key}={toml_value}"));
        self
    }

    /// Extra arguments after everything else (they may override).
    pub fn args<I, S>(mut self, args: I) -> Options
    where
        I: IntoIterator<Item = S>,
        S: Into<String>,
    {
        self.args.extend(args.into_iter().map(Into::into));
        self
    }

    /// Keep the config's ports instead of `--any-port`.
    pub fn config_ports(mut self) -> Options {
        self.any_port = false;
        self
    }

    pub fn ready_timeout(mut self, timeout: Duration) -> Options {
        self.ready_timeout = timeout;
        self
    }

    /// The command line [`Options::start`] runs, and the temporary state directory it made.
    fn command(&self) -> std::io::Result<(Command, Option<TempDir>)> {
        let mut command = Command::new(&self.binary);
        command.arg("run");
        if self.any_port {
            command.arg("--any-port");
        }
        if let Some(path) = &self.config {
            command.arg("--config").arg(path);
        }
        if let Some(name) = &self.machine {
            command.args(["--machine", name]);
        }
        if let Some(clock) = &self.clock {
            command.args(["--clock", clock]);
        }
        let temp = match (
            &self.state_dir,
            self.args.iter().any(|a| a == "--state-dir"),
        ) {
            (Some(dir), _) => {
                command.arg("--state-dir").arg(dir);
                None
            }
            (None, true) => None,
            (None, false) => {
                let dir = TempDir::new("state")?;
                command.arg("--state-dir").arg(dir.path());
                Some(dir)
            }
        };
        for set in &self.sets {
            command.args(["--set", set]);
        }
        command.args(&self.args);
        Ok((command, temp))
    }

    /// Start mcemu; returns once its control API listens.
    pub fn start(&self) -> Result<Machine, StartError> {
        let (mut command, temp) = self.command().map_err(|e| StartError {
            command: format!("{} run", self.binary.display()),
            why: e.to_string(),
            stdout: String::new(),
            stderr: String::new(),
        })?;
        let what = format!("{command:?}");
        let state_dir = temp.as_ref().map(|t| t.path().to_path_buf()).or_else(|| {
            self.state_dir.clone().or_else(|| {
                let i = self.args.iter().position(|a| a == "--state-dir")?;
                self.args.get(i + 1).map(PathBuf::from)
            })
        });
        let mut child = command
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| StartError {
                command: what.clone(),
                why: format!("cannot run it: {e}"),
                stdout: String::new(),
                stderr: String::new(),
            })?;
        let (Some(out), Some(err)) = (child.stdout.take(), child.stderr.take()) else {
            return Err(StartError {
                command: what,
                why: "its output pipes were not set up".into(),
                stdout: String::new(),
                stderr: String::new(),
            });
        };
        let stderr = Arc::new(Mutex::new(Vec::new()));
        let stderr_reader = drain_into(err, Arc::clone(&stderr));
        let stdout = Arc::new(Mutex::new(Vec::new()));
        let stdout_sink = Arc::clone(&stdout);
        let (line_tx, lines) = mpsc::channel::<String>();
        let (done_tx, stdout_done) = mpsc::channel();
        thread::spawn(move || {
            for line in BufReader::new(out).lines().map_while(Result::ok) {
                if let Ok(mut s) = stdout_sink.lock() {
                    s.push(line.clone());
                }
                let _ = line_tx.send(line);
            }
            let _ = done_tx.send(());
        });
        let agent: ureq::Agent = ureq::Agent::config_builder()
            .http_status_as_error(false)
            .timeout_global(Some(HTTP_TIMEOUT))
            .build()
            .into();
        let mut machine = Machine {
            child,
            listeners: Vec::new(),
            api: String::new(),
            state_dir,
            agent,
            stdout,
            stdout_done,
            stderr,
            stderr_reader: Some(stderr_reader),
            _temp: temp,
        };
        let deadline = Instant::now() + self.ready_timeout;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let why = match lines.recv_timeout(left) {
                Ok(line) => {
                    let Some((protocol, address)) = line
                        .strip_prefix("listening: ")
                        .and_then(|rest| rest.split_once(' '))
                    else {
                        continue;
                    };
                    let address = address.trim().to_string();
                    if protocol == "control" {
                        machine.api = format!("http://{address}/api/v1");
                    }
                    machine.listeners.push((protocol.to_string(), address));
                    if protocol == "control" {
                        return Ok(machine);
                    }
                    continue;
                }
                Err(mpsc::RecvTimeoutError::Timeout) => format!(
                    "it printed no `listening: control` line within {:?}",
                    self.ready_timeout
                ),
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    let _ = machine.stdout_done.recv_timeout(Duration::from_secs(5));
                    match machine.child.wait() {
                        Ok(status) => format!("it exited ({status})"),
                        Err(e) => format!("it closed its output ({e})"),
                    }
                }
            };
            let _ = machine.child.kill();
            let _ = machine.child.wait();
            let _ = machine.stderr_reader.take().map(|h| h.join());
            return Err(StartError {
                command: what,
                why,
                stdout: machine.stdout_text(),
                stderr: machine.stderr_text(),
            });
        }
    }
}

fn drain_into(mut from: impl Read + Send + 'static, into: Arc<Mutex<Vec<u8>>>) -> JoinHandle<()> {
    thread::spawn(move || {
        let mut buf = [0u8; 4096];
        while let Ok(n) = from.read(&mut buf) {
            if n == 0 {
                break;
            }
            if let Ok(mut s) = into.lock() {
                s.extend_from_slice(buf.get(..n).unwrap_or_default());
            }
        }
    })
}

/// mcemu did not start: why, and what it printed (a config error names file, key and reason).
#[derive(Debug)]
pub struct StartError {
    pub command: String,
    pub why: String,
    pub stdout: String,
    pub stderr: String,
}

impl std::fmt::Display for StartError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} did not start: {}\n--- stdout\n{}\n--- stderr\n{}",
            self.command, self.why, self.stdout, self.stderr
        )
    }
}

impl std::error::Error for StartError {}

/// A control-API request that failed: the transport, or an error reply (status and JSON body:
/// `{"code", "message", …}` for engine refusals, `{"error", "detail", …}` for request errors).
#[derive(Debug)]
pub enum ApiError {
    Transport {
        request: String,
        reason: String,
    },
    Reply {
        request: String,
        status: u16,
        body: Value,
    },
}

impl ApiError {
    /// The typed error's code (`limit_active`, `malformed_json` …), for error replies.
    pub fn code(&self) -> Option<&str> {
        match self {
            ApiError::Reply { body, .. } => body["code"].as_str().or(body["error"].as_str()),
            ApiError::Transport { .. } => None,
        }
    }
}

impl std::fmt::Display for ApiError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ApiError::Transport { request, reason } => write!(f, "{request}: {reason}"),
            ApiError::Reply {
                request,
                status,
                body,
            } => write!(f, "{request}: {status} {body}"),
        }
    }
}

impl std::error::Error for ApiError {}

/// How a stopped mcemu ended.
#[derive(Debug)]
pub struct Exit {
    pub status: ExitStatus,
    /// Every line it printed on stdout.
    pub stdout: Vec<String>,
    pub stderr: String,
}

/// A running `mcemu run`, killed on drop.
pub struct Machine {
    child: Child,
    /// `listening:` lines in order: (name, address), e.g. ("modbus-tcp", "127.0.0.1:4711").
    pub listeners: Vec<(String, String)>,
    /// `http://127.0.0.1:PORT/api/v1`.
    pub api: String,
    /// The state directory it was given, if known.
    pub state_dir: Option<PathBuf>,
    agent: ureq::Agent,
    stdout: Arc<Mutex<Vec<String>>>,
    stdout_done: mpsc::Receiver<()>,
    stderr: Arc<Mutex<Vec<u8>>>,
    stderr_reader: Option<JoinHandle<()>>,
    _temp: Option<TempDir>,
}

impl std::fmt::Debug for Machine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Machine")
            .field("pid", &self.child.id())
            .field("listeners", &self.listeners)
            .finish_non_exhaustive()
    }
}

impl Machine {
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Whether it has exited, and how.
    pub fn try_wait(&mut self) -> Option<ExitStatus> {
        self.child.try_wait().ok().flatten()
    }

    /// SIGKILL now and reap it.
    pub fn kill(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    /// The address of the `listening: NAME ADDRESS` line (a pty or socket path for some).
    pub fn address(&self, name: &str) -> Option<&str> {
        self.listeners
            .iter()
            .find(|(p, _)| p == name)
            .map(|(_, a)| a.as_str())
    }

    /// Everything printed on stdout so far.
    pub fn stdout_text(&self) -> String {
        self.stdout.lock().map(|s| s.join("\n")).unwrap_or_default()
    }

    /// Everything printed on stderr so far.
    pub fn stderr_text(&self) -> String {
        self.stderr
            .lock()
            .map(|s| String::from_utf8_lossy(&s).into_owned())
            .unwrap_or_default()
    }

    fn reply(
        &self,
        request: String,
        response: Result<ureq::http::Response<ureq::Body>, ureq::Error>,
    ) -> Result<(u16, Value), ApiError> {
        let transport = |reason: String| ApiError::Transport {
            request: request.clone(),
            reason,
        };
        let mut response = response.map_err(|e| transport(e.to_string()))?;
        let status = response.status().as_u16();
        let body = response
            .body_mut()
            .with_config()
            .limit(MAX_REPLY)
            .read_to_string()
            .map_err(|e| transport(format!("reading the body: {e}")))?;
        let json = serde_json::from_str(&body)
            .map_err(|e| transport(format!("not JSON ({e}): {status} {body}")))?;
        Ok((status, json))
    }

    /// `GET /api/v1PATH`: status and JSON, whatever the status.
    pub fn get_any(&self, path: &str) -> Result<(u16, Value), ApiError> {
        let url = format!("{}{path}", self.api);
        self.reply(format!("GET {url}"), self.agent.get(&url).call())
    }

    /// `POST /api/v1PATH` with a JSON body: status and JSON, whatever the status.
    pub fn post_any(&self, path: &str, body: &Value) -> Result<(u16, Value), ApiError> {
        let url = format!("{}{path}", self.api);
        self.reply(
            format!("POST {url} {body}"),
            self.agent
                .post(&url)
                .header("content-type", "application/json")
                .send(body.to_string()),
        )
    }

    fn ok(request: String, (status, body): (u16, Value)) -> Result<Value, ApiError> {
        if status == 200 {
            Ok(body)
        } else {
            Err(ApiError::Reply {
                request,
                status,
                body,
            })
        }
    }

    /// `GET /api/v1PATH`, which must answer 200.
    pub fn get(&self, path: &str) -> Result<Value, ApiError> {
        Self::ok(format!("GET {path}"), self.get_any(path)?)
    }

    /// `POST /api/v1PATH`, which must answer 200.
    pub fn post(&self, path: &str, body: &Value) -> Result<Value, ApiError> {
        Self::ok(format!("POST {path} {body}"), self.post_any(path, body)?)
    }

    /// `GET /state`.
    pub fn state(&self) -> Result<Value, ApiError> {
        self.get("/state")
    }

    /// `POST /commands`: one command object or an array.
    pub fn command(&self, command: &Value) -> Result<Value, ApiError> {
        self.post("/commands", command)
    }

    /// `POST /time/advance` (virtual clock): `{"ticks": N}` or `{"seconds": S}`, with `until`.
    pub fn advance(&self, body: &Value) -> Result<Value, ApiError> {
        self.post("/time/advance", body)
    }

    /// SIGTERM, then wait (at most [`STOP_TIMEOUT`], then SIGKILL) for the exit; everything it
    /// printed.
    pub fn terminate(mut self) -> std::io::Result<Exit> {
        let pid = self.pid().to_string();
        let sent = Command::new("kill").args(["-TERM", &pid]).status()?;
        if !sent.success() {
            return Err(std::io::Error::other(format!("kill -TERM {pid} failed")));
        }
        let deadline = Instant::now() + STOP_TIMEOUT;
        let status = loop {
            if let Some(status) = self.child.try_wait()? {
                break status;
            }
            if Instant::now() > deadline {
                self.kill();
                return Err(std::io::Error::new(
                    std::io::ErrorKind::TimedOut,
                    format!(
                        "mcemu did not stop within {STOP_TIMEOUT:?} of SIGTERM\n--- stderr\n{}",
                        self.stderr_text()
                    ),
                ));
            }
            thread::sleep(Duration::from_millis(10));
        };
        // Both pipes end with the process.
        let _ = self.stdout_done.recv_timeout(Duration::from_secs(10));
        let _ = self.stderr_reader.take().map(|h| h.join());
        Ok(Exit {
            status,
            stdout: self.stdout.lock().map(|s| s.clone()).unwrap_or_default(),
            stderr: self.stderr_text(),
        })
    }
}

impl Drop for Machine {
    fn drop(&mut self) {
        self.kill();
    }
}

/// A directory under the system's temp directory, removed (with its contents) on drop.
#[derive(Debug)]
pub struct TempDir(PathBuf);

impl TempDir {
    pub fn new(label: &str) -> std::io::Result<TempDir> {
        static N: AtomicUsize = AtomicUsize::new(0);
        let nanos = SystemTime::now()
            .duration_since(SystemTime::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos());
        let path = std::env::temp_dir().join(format!(
            "mcemu-{label}-{}-{}-{nanos}",
            std::process::id(),
            N.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&path).map_err(|e| {
            std::io::Error::new(e.kind(), format!("cannot create {}: {e}", path.display()))
        })?;
        Ok(TempDir(path))
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
