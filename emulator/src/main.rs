//! `mcemu`: run a machine (`run`), check configs (`validate`), script it (`scenario`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use mcemu::config::{ClockSetting, Config, DEFAULT_CONFIG_NAME};
use mcemu::scenario::Scenario;
use mcemu::state_dir::StateDir;

#[derive(Parser)]
#[command(
    name = "mcemu",
    version,
    about = "A networked motion-controller emulator"
)]
struct Cli {
    #[command(subcommand)]
    command: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Run a machine and serve its front-ends until SIGINT/SIGTERM.
    Run {
        /// Machine config (TOML); without it (and without --machine), the embedded default
        /// machine.
        #[arg(long)]
        config: Option<PathBuf>,
        /// A shipped machine by name, embedded in the binary: default, cia402-can, cpu226h,
        /// gaochuan-gcn, gaochuan-gcn-ecat, himc, hollysys-mc (the files of `fixtures/`).
        #[arg(long, conflicts_with = "config")]
        machine: Option<String>,
        /// Override the config's clock: realtime, virtual or scaled:K.
        #[arg(long)]
        clock: Option<ClockSetting>,
        /// Override the servo period: seconds, or with a unit (250us, 1ms, 0.002s).
        #[arg(long, value_parser = parse_period)]
        period: Option<f64>,
        /// Keep persisted state (Modbus memory areas marked `persist`) in this directory
        /// instead of the config's `machine.state_dir` or ~/.local/state/mcemu/<machine>.
        #[arg(long)]
        state_dir: Option<PathBuf>,
        /// Override one config key: `--set frontends.modbus_tcp.bind=127.0.0.1:0`. The value is
        /// TOML (numbers, booleans, strings); repeat for more keys.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Bind every TCP listener of the config to a free port on its host (port 0); the
        /// `listening:` lines say which. For test harnesses; `--set` still overrides a bind.
        #[arg(long)]
        any_port: bool,
    },
    /// Check config files without running them.
    Validate {
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
    /// Run a scenario in virtual time; exits non-zero if an expectation fails.
    Scenario {
        file: PathBuf,
        /// Write a CSV trace (one row per tick per axis).
        #[arg(long)]
        trace: Option<PathBuf>,
    },
    /// Print the configuration reference (Markdown): every config key and every axis parameter.
    Reference,
}

/// `0.001`, `1ms`, `250us`, `62.5us`, `0.002s`.
fn parse_period(s: &str) -> Result<f64, String> {
    let (number, scale) = if let Some(n) = s.strip_suffix("us") {
        (n, 1e-6)
    } else if let Some(n) = s.strip_suffix("ms") {
        (n, 1e-3)
    } else if let Some(n) = s.strip_suffix('s') {
        (n, 1.0)
    } else {
        (s, 1.0)
    };
    number
        .trim()
        .parse::<f64>()
        .map(|v| v * scale)
        .map_err(|_| format!("`{s}` is not a period (e.g. 1ms, 250us, 0.002)"))
}

fn main() -> ExitCode {
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env()
                .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("warn")),
        )
        .with_writer(std::io::stderr)
        .init();
    let cli = Cli::parse();
    match cli.command {
        Cmd::Run {
            config,
            machine,
            clock,
            period,
            state_dir,
            set,
            any_port,
        } => {
            let source = match (&config, &machine) {
                (Some(path), _) => std::fs::read_to_string(path)
                    .map(|text| (text, path.display().to_string()))
                    .map_err(|e| mcemu::config::ConfigError {
                        file: path.display().to_string(),
                        key: String::new(),
                        reason: format!("cannot read it: {e}"),
                    }),
                (None, Some(name)) => mcemu::config::shipped_machine(name)
                    .map(|(text, file)| (text.to_string(), file)),
                (None, None) => Ok((
                    mcemu::config::DEFAULT_CONFIG.to_string(),
                    DEFAULT_CONFIG_NAME.to_string(),
                )),
            };
            let (text, file) = match source {
                Ok(s) => s,
                Err(e) => return fail(&e),
            };
            let loaded = Config::parse_for_run(&text, &file, any_port, &set);
            let mut config = match loaded {
                Ok(c) => c,
                Err(e) => return fail(&e),
            };
            if let Some(clock) = clock {
                config.machine.clock = clock;
            }
            if let Some(period) = period {
                config.machine.period = period;
                if let Err(e) = config.check(&format!("{file} with --period")) {
                    return fail(&e);
                }
            }
            let state_dir = StateDir::resolve(&config, &file, state_dir.as_deref());
            match mcemu::run::run(config, &file, state_dir) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => fail(&e),
            }
        }
        Cmd::Validate { files } => {
            let mut ok = true;
            for file in files {
                match Config::load(&file) {
                    Ok(c) => println!(
                        "{}: ok ({} axes, {} drives)",
                        file.display(),
                        c.axes.len(),
                        c.drives.len()
                    ),
                    Err(e) => {
                        eprintln!("mcemu: {e}");
                        ok = false;
                    }
                }
            }
            if ok {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Cmd::Reference => {
            print!("{}", mcemu::reference::markdown());
            ExitCode::SUCCESS
        }
        Cmd::Scenario { file, trace } => scenario(&file, trace.as_deref()),
    }
}

/// `mcemu scenario`: exit 0 when every expectation holds, 1 when one fails or a command is
/// refused unexpectedly, 2 when the scenario cannot run (file, config, trace output).
fn scenario(file: &Path, trace: Option<&Path>) -> ExitCode {
    const CANNOT_RUN: u8 = 2;
    let scenario = match Scenario::load(file) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("mcemu: {e}");
            return ExitCode::from(CANNOT_RUN);
        }
    };
    let mut out = match trace.map(|path| (path, std::fs::File::create(path))) {
        None => None,
        Some((_, Ok(file))) => Some(file),
        Some((path, Err(e))) => {
            eprintln!("mcemu: cannot create the trace {}: {e}", path.display());
            return ExitCode::from(CANNOT_RUN);
        }
    };
    let report = match scenario.run(out.as_mut().map(|f| f as &mut dyn std::io::Write)) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("mcemu: {e}");
            return ExitCode::from(CANNOT_RUN);
        }
    };
    for failure in &report.failures {
        eprintln!("mcemu: {failure}");
    }
    let verdict = if report.passed() { "ok" } else { "FAILED" };
    println!(
        "{}: {verdict}: {} steps, {} expectations, {} failures; {} s of engine time in {} ticks",
        file.display(),
        report.steps,
        report.expectations,
        report.failures.len(),
        scenario.end(),
        report.ticks,
    );
    if let Some(path) = trace {
        println!(
            "trace: {} ({} rows, {} bytes)",
            path.display(),
            report.trace_rows,
            report.trace_bytes
        );
    }
    if report.passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn fail(e: &dyn std::fmt::Display) -> ExitCode {
    eprintln!("mcemu: {e}");
    ExitCode::FAILURE
}
