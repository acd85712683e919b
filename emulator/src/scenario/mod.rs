//! Scenarios: scripted, deterministic runs of a machine in virtual time
//! (`mcemu scenario FILE [--trace OUT.csv]`).
//!
//! ```toml
//! config = "../default.toml"   # the machine: a config file, relative to this file …
//! # … or inline: the config file's sections ([machine], [[axes]], [io] …) written here instead
//! end = 5.0                    # seconds of engine time
//!
//! [[step]]
//! at = 0.0                     # seconds; the step runs at the first tick whose time ≥ at
//! command = { type = "enable", axis = 0 }        # any axes::Command
//! [[step]]
//! at = 0.5
//! command = { type = "move_absolute", axis = 0, position = 600.0 }
//! expect_error = "limit_active"                  # optional: the command must be refused so
//! [[step]]
//! at = 1.0
//! force = { axis = 0, input = "limit_pos", value = true }   # no value: release; or { di = 3 }
//! [[step]]
//! at = 4.9
//! expect = { axis = 0, state = "standstill", position = 100.0, tolerance = 1e-6 }
//! ```
//!
//! Timing: the engine starts at tick 0 (time 0). A step with time `at` runs at tick
//! ⌈at / period⌉ (an `at` within rounding of a tick counts as that tick), after the engine has
//! stepped to it; steps of one tick run in file order, so an `expect` sees the commands before it.
//! The run ends at the tick of `end`, after that tick's steps. A trace has one row per axis for
//! every tick from 0 to the end, written after that tick's steps.
//!
//! The `expect` conditions are listed in `docs/decisions.md` ("Scenarios and traces").

mod expect;
mod file;

use std::fmt;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use axes::command::{
    AxisCommand, AxisInput, Command, CommandId, CommandState, ErrorKind, ForceDigitalInput,
    ForceInput, GetCommandState, GroupCommand, Home, MoveAbsolute, MoveRelative, MoveVelocity,
    Reply,
};
use axes::{AxisStatus, Engine, EngineError};

use crate::config::{Config, ConfigError};
use crate::trace::{GroupColumns, TraceWriter};
use expect::{Check, Expectation, Seen};
use file::{ForceSpec, ScenarioFile, StepSpec};

/// A scenario that cannot run: which file, which key, why. (The same shape as a config error;
/// a config error inside an inline config is one of these.)
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub struct ScenarioError {
    pub file: String,
    /// Key path, e.g. `step[3].expect.axis`; empty for the file as a whole.
    pub key: String,
    pub reason: String,
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.key.is_empty() {
            write!(f, "{}: {}", self.file, self.reason)
        } else {
            write!(f, "{}: {}: {}", self.file, self.key, self.reason)
        }
    }
}

impl From<ConfigError> for ScenarioError {
    fn from(e: ConfigError) -> Self {
        ScenarioError {
            file: e.file,
            key: e.key,
            reason: e.reason,
        }
    }
}

/// Longest run, in ticks: over a simulated century at 62.5 µs, far past anything that finishes.
const MAX_TICKS: f64 = 1e14;

/// A checked scenario, ready to run.
#[derive(Clone, Debug)]
pub struct Scenario {
    file: String,
    config: Config,
    end: f64,
    end_tick: u64,
    /// In execution order: by tick, then file order.
    steps: Vec<Step>,
}

#[derive(Clone, Debug)]
struct Step {
    /// Index in the file (`step[index]`).
    index: usize,
    at: f64,
    tick: u64,
    action: StepAction,
}

#[derive(Clone, Debug)]
enum StepAction {
    Command {
        command: Command,
        /// The refusal the step expects, if it expects one.
        refusal: Option<ErrorKind>,
    },
    /// A `force`: a command whose refusal is always a failure.
    Force(Command),
    Expect(Expectation),
}

/// What a run found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Report {
    /// One line per failed condition or unexpected reply: file, step, time, expected, seen.
    pub failures: Vec<String>,
    pub steps: usize,
    pub expectations: usize,
    /// Ticks stepped (the end tick).
    pub ticks: u64,
    /// Trace rows and bytes written, when tracing.
    pub trace_rows: u64,
    pub trace_bytes: u64,
}

impl Report {
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }
}

impl Scenario {
    /// Read and check a scenario file.
    pub fn load(path: &Path) -> Result<Scenario, ScenarioError> {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| ScenarioError {
            file: file.clone(),
            key: String::new(),
            reason: format!("cannot read it: {e}"),
        })?;
        let base = path.parent().unwrap_or(Path::new(""));
        Scenario::parse(&text, &file, base)
    }

    /// Parse and check scenario text; `file` names it in errors, `base` is the directory a
    /// `config` path is relative to.
    pub fn parse(text: &str, file: &str, base: &Path) -> Result<Scenario, ScenarioError> {
        let error = |key: &str, reason: String| ScenarioError {
            file: file.to_string(),
            key: key.to_string(),
            reason,
        };
        let deserializer = toml::Deserializer::parse(text)
            .map_err(|e| error("", e.to_string().trim_end().to_string()))?;
        let parsed: ScenarioFile = serde_path_to_error::deserialize(deserializer).map_err(|e| {
            let key = match e.path().to_string() {
                p if p == "." => String::new(),
                p => p,
            };
            error(&key, e.inner().to_string().trim_end().to_string())
        })?;
        let config = match (&parsed.config_path, parsed.inline_sections.first()) {
            (Some(_), Some(section)) => {
                return Err(error(
                    section,
                    "the machine is given twice: `config = \"path\"` and inline sections; \
                     keep one"
                        .into(),
                ))
            }
            (Some(path), None) => {
                let full: PathBuf = base.join(path);
                Config::load(&full).map_err(|e| error("config", e.to_string()))?
            }
            (None, Some(_)) => {
                parsed.inline.check(file)?;
                parsed.inline
            }
            (None, None) => {
                return Err(error(
                    "config",
                    "no machine: set `config = \"path/to/machine.toml\"` or write the config \
                     sections ([machine], [[axes]] …) in the scenario"
                        .into(),
                ))
            }
        };
        let period = config.machine.period;
        let end = parsed.end.ok_or_else(|| {
            error(
                "end",
                "missing: the scenario's length in seconds of engine time".into(),
            )
        })?;
        let end_tick = tick_of(end, period).map_err(|why| error("end", why))?;
        let machine = Machine::of(&config);
        let mut steps = Vec::with_capacity(parsed.steps.len());
        for (index, spec) in parsed.steps.into_iter().enumerate() {
            let key = format!("step[{index}]");
            let at = spec.at;
            let tick = tick_of(at, period).map_err(|why| error(&format!("{key}.at"), why))?;
            if at > end {
                return Err(error(
                    &format!("{key}.at"),
                    format!("{at} s is after the end ({end} s)"),
                ));
            }
            let action =
                action(spec, &machine).map_err(|(k, why)| error(&format!("{key}{k}"), why))?;
            steps.push(Step {
                index,
                at,
                tick,
                action,
            });
        }
        // Stable: steps of one tick keep their file order.
        steps.sort_by_key(|s| s.tick);
        check_command_refs(&steps).map_err(|(k, why)| error(&k, why))?;
        Ok(Scenario {
            file: file.to_string(),
            config,
            end,
            end_tick,
            steps,
        })
    }

    pub fn config(&self) -> &Config {
        &self.config
    }

    /// Engine time at which the run ends, seconds.
    pub fn end(&self) -> f64 {
        self.end
    }

    /// The tick the run ends at.
    pub fn end_tick(&self) -> u64 {
        self.end_tick
    }

    /// Run the scenario; with `trace`, write the CSV trace to it. `Err` only for an engine that
    /// cannot be built or a trace that cannot be written.
    pub fn run(&self, trace: Option<&mut dyn Write>) -> Result<Report, ScenarioError> {
        let mut engine = Engine::new(&self.config.engine_config()).map_err(|e| ScenarioError {
            file: self.file.clone(),
            key: e.key,
            reason: e.reason,
        })?;
        let trace_error = |e: io::Error| ScenarioError {
            file: self.file.clone(),
            key: String::new(),
            reason: format!("cannot write the trace: {e}"),
        };
        let mut trace = trace.map(|out| TraceWriter::new(out, self.config.machine.period));
        let mut run = Run {
            scenario: self,
            ids: vec![Issued::NotYet; self.steps.len()],
            report: Report {
                steps: self.steps.len(),
                ..Report::default()
            },
        };
        let mut statuses = vec![AxisStatus::default(); engine.axis_count()];
        let mut groups: Vec<Option<GroupColumns>> = vec![None; engine.axis_count()];
        let mut next = 0;
        let mut tick = 0;
        loop {
            while let Some(step) = self.steps.get(next).filter(|s| s.tick == tick) {
                run.execute(step, &mut engine);
                next += 1;
            }
            if let Some(trace) = trace.as_mut() {
                for (i, (status, group)) in statuses.iter_mut().zip(&mut groups).enumerate() {
                    if let Some(axis) = engine.axis(i) {
                        axis.status_into(status);
                    }
                    *group = GroupColumns::of(&engine, i);
                }
                let rows = statuses.iter().zip(groups.iter().map(Option::as_ref));
                trace.write_tick(tick, rows).map_err(trace_error)?;
            }
            if tick == self.end_tick {
                break;
            }
            // Without a trace, nothing is looked at until the next step: step straight to it.
            let until = match trace {
                Some(_) => tick + 1,
                None => self.steps.get(next).map_or(self.end_tick, |s| s.tick),
            };
            while tick < until {
                engine.step();
                tick += 1;
            }
        }
        run.report.ticks = tick;
        if let Some(trace) = trace {
            run.report.trace_rows = trace.rows();
            let (_, bytes) = trace.finish().map_err(trace_error)?;
            run.report.trace_bytes = bytes;
        }
        Ok(run.report)
    }
}

/// ⌈seconds / period⌉, forgiving binary rounding: 0.3 s at 0.1 s is tick 3, not 4.
fn tick_of(seconds: f64, period: f64) -> Result<u64, String> {
    if !seconds.is_finite() || seconds < 0.0 {
        return Err(format!("{seconds}: must be a finite time ≥ 0 s"));
    }
    let exact = seconds / period;
    // The decimal time and period are rounded in binary (and divided): forgive a few ulps, and
    // at least 1e-9 of a tick, before rounding up.
    let slack = (exact * 1e-15).max(1e-9);
    let ticks = (exact - slack).ceil().max(0.0);
    if ticks > MAX_TICKS {
        return Err(format!(
            "{seconds} s is {ticks:e} ticks of {period} s; at most {MAX_TICKS:e}"
        ));
    }
    Ok(ticks as u64)
}

/// What steps are checked against.
struct Machine {
    axes: usize,
    digital_inputs: u16,
    digital_outputs: u16,
}

impl Machine {
    fn of(config: &Config) -> Machine {
        Machine {
            axes: config.axes.len(),
            digital_inputs: config.io.digital_inputs,
            digital_outputs: config.io.digital_outputs,
        }
    }

    fn axis(&self, axis: u16) -> Result<(), String> {
        if (axis as usize) < self.axes {
            Ok(())
        } else {
            Err(format!(
                "axis {axis} does not exist (the machine has {} axes)",
                self.axes
            ))
        }
    }

    fn channel(&self, channel: u16, count: u16, kind: &str) -> Result<(), String> {
        if channel < count {
            Ok(())
        } else {
            Err(format!(
                "channel {channel} does not exist (the machine has {count} {kind})"
            ))
        }
    }
}

/// A refusal while checking a step: the key below `step[i]` (e.g. `.expect.axis`) and why.
type StepError = (String, String);

/// The one action of a step, checked against the machine.
fn action(spec: StepSpec, machine: &Machine) -> Result<StepAction, StepError> {
    let given: Vec<&str> = [
        ("command", spec.command.is_some()),
        ("force", spec.force.is_some()),
        ("expect", spec.expect.is_some()),
    ]
    .into_iter()
    .filter_map(|(name, present)| present.then_some(name))
    .collect();
    if given.len() != 1 {
        let why = if given.is_empty() {
            "no action: give one of `command`, `force` or `expect`".to_string()
        } else {
            format!(
                "{} actions ({}): a step has exactly one; split it into steps with the same `at`",
                given.len(),
                given.join(", ")
            )
        };
        return Err((String::new(), why));
    }
    if spec.expect_error.is_some() && spec.command.is_none() {
        return Err((
            ".expect_error".into(),
            "applies to a `command` step only".into(),
        ));
    }
    if let Some(command) = spec.command {
        let refusal = match spec.expect_error.as_deref() {
            Some(code) => {
                Some(expect::error_kind(code).map_err(|e| (".expect_error".to_string(), e))?)
            }
            None => None,
        };
        // An expected refusal may be the point (`invalid_axis`); otherwise a typo in an axis
        // index is a scenario error, found before anything runs.
        if let (Some(axis), None) = (command.axis(), refusal) {
            machine
                .axis(axis)
                .map_err(|e| (".command.axis".to_string(), e))?;
        }
        return Ok(StepAction::Command { command, refusal });
    }
    if let Some(force) = spec.force {
        return force_command(force, machine)
            .map(StepAction::Force)
            .map_err(|(k, why)| (format!(".force.{k}"), why));
    }
    let Some(spec) = spec.expect else {
        return Err((String::new(), "no action".into()));
    };
    let e = Expectation::from_spec(spec).map_err(|(k, why)| {
        let key = if k == "expect" {
            ".expect".to_string()
        } else {
            format!(".expect.{k}")
        };
        (key, why)
    })?;
    if let Some(axis) = e.axis {
        machine
            .axis(axis)
            .map_err(|why| (".expect.axis".to_string(), why))?;
    }
    for check in &e.checks {
        let (key, result) = match check {
            Check::Di { channel, .. } => (
                ".expect.di",
                machine.channel(*channel, machine.digital_inputs, "digital inputs"),
            ),
            Check::Do { channel, .. } => (
                ".expect.do",
                machine.channel(*channel, machine.digital_outputs, "digital outputs"),
            ),
            _ => continue,
        };
        result.map_err(|why| (key.to_string(), why))?;
    }
    Ok(StepAction::Expect(e))
}

fn force_command(f: ForceSpec, machine: &Machine) -> Result<Command, (&'static str, String)> {
    match (f.axis, f.input, f.di) {
        (Some(axis), Some(input), None) => {
            machine.axis(axis).map_err(|why| ("axis", why))?;
            Ok(Command::from(ForceInput {
                axis,
                input,
                value: f.value,
            }))
        }
        (None, None, Some(channel)) => {
            machine
                .channel(channel, machine.digital_inputs, "digital inputs")
                .map_err(|why| ("di", why))?;
            Ok(Command::from(ForceDigitalInput {
                channel,
                value: f.value,
            }))
        }
        (_, _, Some(_)) => Err((
            "di",
            "give either `axis` and `input`, or `di`, not both".into(),
        )),
        (Some(_), None, None) => Err((
            "input",
            format!("missing: one of {}", AXIS_INPUTS.join(", ")),
        )),
        (None, Some(_), None) => Err(("axis", "missing: the axis whose input is forced".into())),
        (None, None, None) => Err((
            "axis",
            "missing: force an axis input (`axis`, `input`) or a digital input (`di`)".into(),
        )),
    }
}

const AXIS_INPUTS: [&str; 6] = [
    "limit_pos",
    "limit_neg",
    "home",
    "index",
    "drive_alarm",
    "encoder_loss",
];

// Keep the list in the message in step with the engine's inputs.
const _: fn(AxisInput) = |i| match i {
    AxisInput::LimitPos
    | AxisInput::LimitNeg
    | AxisInput::Home
    | AxisInput::Index
    | AxisInput::DriveAlarm
    | AxisInput::EncoderLoss => {}
};

/// `command_state` conditions must name an earlier motion command (one that gets an id).
fn check_command_refs(steps: &[Step]) -> Result<(), (String, String)> {
    for (order, step) in steps.iter().enumerate() {
        let StepAction::Expect(e) = &step.action else {
            continue;
        };
        for check in &e.checks {
            let Check::CommandState { step: target, .. } = check else {
                continue;
            };
            let key = format!("step[{}].expect.step", step.index);
            let Some(pos) = steps.iter().position(|s| s.index == *target) else {
                return Err((key, format!("there is no step[{target}]")));
            };
            let Some(Step {
                action: StepAction::Command { command, refusal },
                ..
            }) = steps.get(pos)
            else {
                return Err((key, format!("step[{target}] is not a `command` step")));
            };
            if pos > order {
                return Err((
                    key,
                    format!("step[{target}] runs after this one: its command has no state yet"),
                ));
            }
            if refusal.is_some() {
                return Err((
                    key,
                    format!("step[{target}]'s command is expected to be refused: it has no id"),
                ));
            }
            if !matches!(
                command,
                Command::Axis(AxisCommand::MoveAbsolute(MoveAbsolute { .. }))
                    | Command::Axis(AxisCommand::MoveRelative(MoveRelative { .. }))
                    | Command::Axis(AxisCommand::MoveVelocity(MoveVelocity { .. }))
                    | Command::Axis(AxisCommand::Home(Home { .. }))
                    | Command::Group(
                        GroupCommand::MoveLinearAbsolute(_)
                            | GroupCommand::MoveLinearRelative(_)
                            | GroupCommand::MoveCircularAbsolute(_)
                            | GroupCommand::MoveCircularRelative(_)
                            | GroupCommand::MoveSpline(_)
                            | GroupCommand::MoveEllipse(_)
                            | GroupCommand::MoveCircularAngle(_)
                            | GroupCommand::SetOutput(_)
                            | GroupCommand::Dwell(_)
                            | GroupCommand::WaitInput(_)
                            | GroupCommand::WaitPosition(_)
                            | GroupCommand::AxisMove(_)
                            | GroupCommand::Jog(_)
                            | GroupCommand::JogAxis(_)
                    )
            ) {
                return Err((
                    key,
                    format!(
                        "step[{target}]'s command ({}) is not a motion command: it has no id",
                        command_name(command)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The `type` of a command, as written in the file.
fn command_name(c: &Command) -> String {
    serde_json::to_value(c)
        .ok()
        .and_then(|v| v.get("type").and_then(|t| t.as_str()).map(str::to_owned))
        .unwrap_or_else(|| "command".into())
}

/// What a command step got back.
#[derive(Clone, Copy, Debug)]
enum Issued {
    NotYet,
    Id(CommandId),
    NoId,
    Refused(ErrorKind),
}

struct Run<'s> {
    scenario: &'s Scenario,
    /// By file index.
    ids: Vec<Issued>,
    report: Report,
}

impl Run<'_> {
    fn execute(&mut self, step: &Step, engine: &mut Engine) {
        let at = format!(
            "{}: step[{}] at {} s",
            self.scenario.file, step.index, step.at
        );
        match &step.action {
            StepAction::Command { command, refusal } => {
                let result = engine.apply(command.clone());
                let issued = match &result {
                    Ok(Reply::Accepted { id }) => Issued::Id(*id),
                    Ok(_) => Issued::NoId,
                    Err(e) => Issued::Refused(e.kind()),
                };
                if let Some(slot) = self.ids.get_mut(step.index) {
                    *slot = issued;
                }
                let name = command_name(command);
                match (result, refusal) {
                    (Ok(_), None) => {}
                    (Err(e), Some(want)) if e.kind() == *want => {}
                    (Ok(_), Some(want)) => self.report.failures.push(format!(
                        "{at}: {name}: expected refusal {}, but it was accepted",
                        want.name()
                    )),
                    (Err(e), want) => self.report.failures.push(refused(&at, &name, &e, *want)),
                }
            }
            StepAction::Force(command) => {
                if let Err(e) = engine.apply(command.clone()) {
                    let failure = refused(&at, "force", &e, None);
                    self.report.failures.push(failure);
                }
            }
            StepAction::Expect(e) => {
                self.report.expectations += 1;
                let states: Vec<(usize, Result<CommandState, String>)> = e
                    .checks
                    .iter()
                    .filter_map(|c| match c {
                        Check::CommandState { step, .. } => Some(*step),
                        _ => None,
                    })
                    .map(|k| (k, self.command_state(k, engine)))
                    .collect();
                let command_state = |k: usize| {
                    states
                        .iter()
                        .find(|(step, _)| *step == k)
                        .map_or_else(|| Err("it has not run".to_string()), |(_, s)| s.clone())
                };
                let status = e.axis.and_then(|a| engine.axis_status(a as usize));
                let group = e.group.and_then(|id| engine.group_status(id));
                let coupling = e.axis.and_then(|a| engine.couplings().status_of(a));
                let seen = Seen {
                    axis: status.as_ref(),
                    group: group.as_ref(),
                    coupling: coupling.as_ref(),
                    di: &engine.io().di,
                    do_: &engine.io().do_,
                    command_state: &command_state,
                };
                for f in e.failures(&seen) {
                    self.report.failures.push(format!("{at}: {f}"));
                }
            }
        }
    }

    /// The state of the command step `k` issued, or why there is none.
    fn command_state(&self, k: usize, engine: &mut Engine) -> Result<CommandState, String> {
        match self.ids.get(k).copied().unwrap_or(Issued::NotYet) {
            // A read: `command_state` changes nothing in the engine.
            Issued::Id(id) => match engine.apply(Command::from(GetCommandState { id })) {
                Ok(Reply::CommandState { state, .. }) => Ok(state),
                Ok(other) => Err(format!("the engine answered {other:?}")),
                Err(e) => Err(format!("the engine answered: {e}")),
            },
            Issued::Refused(kind) => Err(format!("it was refused ({})", kind.name())),
            Issued::NoId => Err("it got no command id".into()),
            Issued::NotYet => Err("it has not run".into()),
        }
    }
}

fn refused(at: &str, name: &str, e: &EngineError, want: Option<ErrorKind>) -> String {
    match want {
        Some(want) => format!(
            "{at}: {name}: expected refusal {}, but it was refused with {}: {e}",
            want.name(),
            e.kind().name()
        ),
        None => format!("{at}: {name} refused ({}): {e}", e.kind().name()),
    }
}

#[cfg(test)]
mod tests;
