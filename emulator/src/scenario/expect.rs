//! Expectations: conditions on an axis, an axis group, a command or the I/O image, checked at
//! one tick.

use std::fmt::Write as _;

use axes::command::{CommandState, ErrorKind};
use axes::status::{CouplingKind, CouplingPhase, CouplingStatus, GroupState, GroupStatus};
use axes::{AxisFlags, AxisState, AxisStatus};
use serde::de::IntoDeserializer;
use serde::Deserialize;

use super::file::ExpectSpec;

/// One checked `expect`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Expectation {
    pub axis: Option<u16>,
    pub group: Option<u16>,
    pub tolerance: f64,
    pub checks: Vec<Check>,
}

#[derive(Clone, Debug, PartialEq)]
pub(super) enum Check {
    State(AxisState),
    Number(Quantity, f64),
    /// All of these flags set.
    Flags(AxisFlags),
    /// None of these flags set.
    NotFlags(AxisFlags),
    /// The axis's last error (`None`: no error).
    Error(Option<ErrorKind>),
    /// The phase of the coupling whose slave the axis is (`None`: it is no slave).
    Coupling(Option<CouplingPhase>),
    /// The kind of that coupling (`None`: it is no slave).
    CouplingKind(Option<CouplingKind>),
    /// The tangent angle a tangential axis tracks, within the tolerance.
    TangentAngle(f64),
    /// A count of the axis's PT/PVT stream (`stream_space`, `stream_used`, `stream_underruns`).
    StreamCount(StreamCount, u32),
    StreamRunning(bool),
    /// The state of the command the step with this index issued.
    CommandState {
        step: usize,
        state: ExpectedState,
    },
    Di {
        channel: u16,
        value: bool,
    },
    Do {
        channel: u16,
        value: bool,
    },
    GroupState(GroupState),
    /// Each coordinate within the tolerance.
    GroupPosition(Vec<f64>),
    GroupInPosition(bool),
    GroupUserSegment(u32),
}

/// The counts of an axis's PT/PVT stream an expectation can check.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum StreamCount {
    Space,
    Used,
    Underruns,
}

impl StreamCount {
    fn name(self) -> &'static str {
        match self {
            StreamCount::Space => "stream_space",
            StreamCount::Used => "stream_used",
            StreamCount::Underruns => "stream_underruns",
        }
    }

    fn of(self, s: &AxisStatus) -> u32 {
        match self {
            StreamCount::Space => u32::from(s.stream.space),
            StreamCount::Used => u32::from(s.stream.used),
            StreamCount::Underruns => s.stream.underruns,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Quantity {
    Position,
    Velocity,
    CommandPosition,
    CommandVelocity,
    FollowingError,
    /// Edges latched by the axis's capture channels (issue 12 item 4).
    Captures,
    /// The newest latch's actual position.
    CapturePosition,
    /// Outputs fired by the axis's compare channels (issue 12 item 5).
    CompareOutputs,
    /// The position sent to the drive (compensation included).
    OutputPosition,
    /// The correction of compensation after the planner.
    Compensation,
    /// A gantry axis's deviation from its master (issue 12 item 6).
    GantryDeviation,
    /// Seconds the last finished move's command changed (HIMC GetMoveTime, digest 004 §3.7).
    MoveTime,
    /// Seconds from its end until in position (HIMC GetSettlingTime).
    SettlingTime,
    /// The user frame's origin offset (HIMC GetPosOffset, TV 32).
    PositionOffset,
    /// Whole turns of a rollover axis (HIMC GetRolloverTurns).
    RolloverTurns,
    /// The drive's torque, a fraction of rated torque (HIMC MoveTrq, GetCurrFb).
    Torque,
    /// The Z-phase output's level, 0 or 1 (HMC SwitchTZ).
    ZOutput,
    /// The HMC position-compensation offset.
    CompensationOffset,
    /// The HMC add axis, 255 for none (HMC_GetAddAxis).
    AddAxis,
}

impl Quantity {
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Position => "position",
            Quantity::Velocity => "velocity",
            Quantity::CommandPosition => "command_position",
            Quantity::CommandVelocity => "command_velocity",
            Quantity::FollowingError => "following_error",
            Quantity::Captures => "captures",
            Quantity::CapturePosition => "capture_position",
            Quantity::CompareOutputs => "compare_outputs",
            Quantity::OutputPosition => "output_position",
            Quantity::Compensation => "compensation",
            Quantity::GantryDeviation => "gantry_deviation",
            Quantity::MoveTime => "move_time",
            Quantity::SettlingTime => "settling_time",
            Quantity::PositionOffset => "position_offset",
            Quantity::RolloverTurns => "rollover_turns",
            Quantity::Torque => "torque",
            Quantity::ZOutput => "z_output",
            Quantity::CompensationOffset => "compensation_offset",
            Quantity::AddAxis => "add_axis",
        }
    }

    fn of(self, s: &AxisStatus) -> f64 {
        match self {
            Quantity::Position => s.act_pos,
            Quantity::Velocity => s.act_vel,
            Quantity::CommandPosition => s.cmd_pos,
            Quantity::CommandVelocity => s.cmd_vel,
            Quantity::FollowingError => s.following_error,
            Quantity::Captures => f64::from(s.captures),
            Quantity::CapturePosition => s.capture_position,
            Quantity::CompareOutputs => f64::from(s.compare_outputs),
            Quantity::OutputPosition => s.output_pos,
            Quantity::Compensation => s.compensation,
            Quantity::GantryDeviation => s.gantry_deviation,
            Quantity::MoveTime => s.move_time,
            Quantity::SettlingTime => s.settling_time,
            Quantity::PositionOffset => s.position_offset,
            Quantity::RolloverTurns => s.rollover_turns as f64,
            Quantity::Torque => s.torque,
            Quantity::ZOutput => f64::from(u8::from(s.z_output)),
            Quantity::CompensationOffset => s.compensation_offset,
            Quantity::AddAxis => s.add_axis.map_or(255.0, f64::from),
        }
    }
}

/// `waiting`, `running`, `done`, `aborted`, `error` (any error) or `error:<code>`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ExpectedState {
    Exactly(CommandState),
    AnyError,
}

impl ExpectedState {
    fn parse(s: &str) -> Result<ExpectedState, String> {
        Ok(match s {
            "waiting" => ExpectedState::Exactly(CommandState::Waiting),
            "running" => ExpectedState::Exactly(CommandState::Running),
            "done" => ExpectedState::Exactly(CommandState::Done),
            "aborted" => ExpectedState::Exactly(CommandState::Aborted),
            "error" => ExpectedState::AnyError,
            _ => match s.strip_prefix("error:") {
                Some(code) => ExpectedState::Exactly(CommandState::Error(error_kind(code)?)),
                None => {
                    return Err(format!(
                        "`{s}` is not a command state: use waiting, running, done, aborted, \
                         error or error:<code>"
                    ))
                }
            },
        })
    }

    pub fn matches(self, state: CommandState) -> bool {
        match self {
            ExpectedState::Exactly(s) => s == state,
            ExpectedState::AnyError => matches!(state, CommandState::Error(_)),
        }
    }
}

impl std::fmt::Display for ExpectedState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ExpectedState::Exactly(s) => f.write_str(&command_state_name(*s)),
            ExpectedState::AnyError => f.write_str("error"),
        }
    }
}

pub(super) fn command_state_name(s: CommandState) -> String {
    match s {
        CommandState::Waiting => "waiting".into(),
        CommandState::Running => "running".into(),
        CommandState::Done => "done".into(),
        CommandState::Aborted => "aborted".into(),
        CommandState::Error(kind) => format!("error:{}", kind.name()),
    }
}

/// An engine error code by name (`limit_active`, `axis_disabled` …).
pub(super) fn error_kind(name: &str) -> Result<ErrorKind, String> {
    ErrorKind::deserialize(name.into_deserializer())
        .map_err(|e: serde::de::value::Error| format!("`{name}` is not an error code: {e}"))
}

/// A set of flags by their snake_case names (`homed`, `hw_limit_pos` …).
fn flags(names: &[String]) -> Result<AxisFlags, String> {
    let mut out = AxisFlags::empty();
    for name in names {
        let flag = AxisFlags::from_name(&name.to_ascii_uppercase()).ok_or_else(|| {
            format!(
                "`{name}` is not an axis flag: use one of {}",
                all_flag_names()
            )
        })?;
        out |= flag;
    }
    Ok(out)
}

fn all_flag_names() -> String {
    AxisFlags::all()
        .iter_names()
        .map(|(n, _)| n.to_ascii_lowercase())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Flags as snake_case names, `none` when empty.
pub(super) fn flag_names(f: AxisFlags) -> String {
    if f.is_empty() {
        return "none".into();
    }
    f.iter_names()
        .map(|(n, _)| n.to_ascii_lowercase())
        .collect::<Vec<_>>()
        .join(", ")
}

/// A refusal at load time: the key inside `expect` and why.
pub(super) type SpecError = (&'static str, String);

impl Expectation {
    /// Check an `expect` table's shape (not yet against the machine).
    pub fn from_spec(spec: ExpectSpec) -> Result<Expectation, SpecError> {
        let mut checks = Vec::new();
        if let Some(s) = spec.state {
            checks.push(Check::State(s));
        }
        for (q, v) in [
            (Quantity::Position, spec.position),
            (Quantity::Velocity, spec.velocity),
            (Quantity::CommandPosition, spec.command_position),
            (Quantity::CommandVelocity, spec.command_velocity),
            (Quantity::FollowingError, spec.following_error),
            (Quantity::Captures, spec.captures),
            (Quantity::CapturePosition, spec.capture_position),
            (Quantity::CompareOutputs, spec.compare_outputs),
            (Quantity::OutputPosition, spec.output_position),
            (Quantity::Compensation, spec.compensation),
            (Quantity::GantryDeviation, spec.gantry_deviation),
            (Quantity::MoveTime, spec.move_time),
            (Quantity::SettlingTime, spec.settling_time),
            (Quantity::PositionOffset, spec.position_offset),
            (Quantity::RolloverTurns, spec.rollover_turns),
            (Quantity::Torque, spec.torque),
            (Quantity::ZOutput, spec.z_output),
            (Quantity::CompensationOffset, spec.compensation_offset),
            (Quantity::AddAxis, spec.add_axis),
        ] {
            if let Some(v) = v {
                if !v.is_finite() {
                    return Err((q.name(), format!("{v} is not a finite number")));
                }
                checks.push(Check::Number(q, v));
            }
        }
        if let Some(v) = spec.tangent_angle {
            if !v.is_finite() {
                return Err(("tangent_angle", format!("{v} is not a finite number")));
            }
            checks.push(Check::TangentAngle(v));
        }
        let tolerance = spec.tolerance.unwrap_or(0.0);
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err((
                "tolerance",
                format!("{tolerance}: must be a finite number ≥ 0"),
            ));
        }
        let group_checks = group_checks(&spec)?;
        if spec.tolerance.is_some()
            && !checks
                .iter()
                .any(|c| matches!(c, Check::Number(..) | Check::TangentAngle(_)))
            && !group_checks
                .iter()
                .any(|c| matches!(c, Check::GroupPosition(_)))
        {
            return Err((
                "tolerance",
                "applies to position, velocity, command_position, command_velocity, \
                 following_error, captures, capture_position, compare_outputs, output_position, \
                 compensation, tangent_angle, gantry_deviation, move_time, settling_time, \
                 position_offset, rollover_turns, torque, z_output, compensation_offset, \
                 add_axis or group_position, and none is given"
                    .into(),
            ));
        }
        if !spec.flags.is_empty() {
            checks.push(Check::Flags(flags(&spec.flags).map_err(|e| ("flags", e))?));
        }
        if !spec.not_flags.is_empty() {
            checks.push(Check::NotFlags(
                flags(&spec.not_flags).map_err(|e| ("not_flags", e))?,
            ));
        }
        if let Some(e) = &spec.error {
            let kind = match e.as_str() {
                "" => None,
                name => Some(error_kind(name).map_err(|e| ("error", e))?),
            };
            checks.push(Check::Error(kind));
        }
        if let Some(name) = &spec.coupling {
            let phase = match name.as_str() {
                "none" => None,
                "waiting" => Some(CouplingPhase::Waiting),
                "engaging" => Some(CouplingPhase::Engaging),
                "in_sync" => Some(CouplingPhase::InSync),
                other => {
                    return Err((
                        "coupling",
                        format!("unknown phase `{other}`: one of none, waiting, engaging, in_sync"),
                    ))
                }
            };
            checks.push(Check::Coupling(phase));
        }
        if let Some(name) = &spec.coupling_kind {
            let kind = [
                CouplingKind::Gear,
                CouplingKind::Cam,
                CouplingKind::Superimpose,
                CouplingKind::Tangential,
                CouplingKind::Follow,
            ]
            .into_iter()
            .find(|k| k.name() == name);
            match (name.as_str(), kind) {
                ("none", _) => checks.push(Check::CouplingKind(None)),
                (_, Some(k)) => checks.push(Check::CouplingKind(Some(k))),
                (other, None) => {
                    return Err((
                        "coupling_kind",
                        format!(
                            "unknown kind `{other}`: one of none, gear, cam, superimpose, \
                             tangential, follow"
                        ),
                    ))
                }
            }
        }
        for (count, v) in [
            (StreamCount::Space, spec.stream_space.map(u32::from)),
            (StreamCount::Used, spec.stream_used.map(u32::from)),
            (StreamCount::Underruns, spec.stream_underruns),
        ] {
            if let Some(v) = v {
                checks.push(Check::StreamCount(count, v));
            }
        }
        if let Some(v) = spec.stream_running {
            checks.push(Check::StreamRunning(v));
        }
        let axis_checks = !checks.is_empty();
        if axis_checks && spec.axis.is_none() {
            return Err(("axis", "missing: these conditions are about an axis".into()));
        }
        if spec.axis.is_some() && !axis_checks {
            return Err((
                "axis",
                "no condition on it: give state, position, velocity, command_position, \
                 command_velocity, following_error, captures, capture_position, \
                 compare_outputs, output_position, compensation, gantry_deviation, move_time, \
                 settling_time, position_offset, rollover_turns, torque, z_output, compensation_offset, add_axis, flags, not_flags, error, coupling, coupling_kind, tangent_angle, stream_space, \
                 stream_used, stream_running or stream_underruns"
                    .into(),
            ));
        }
        match (spec.group, group_checks.is_empty()) {
            (None, false) => {
                return Err((
                    "group",
                    "missing: these conditions are about a group".into(),
                ))
            }
            (Some(_), true) => {
                return Err((
                    "group",
                    "no condition on it: give group_state, group_position, in_position or \
                     user_segment"
                        .into(),
                ))
            }
            _ => checks.extend(group_checks),
        }
        match (spec.step, &spec.command_state) {
            (Some(step), Some(state)) => checks.push(Check::CommandState {
                step,
                state: ExpectedState::parse(state).map_err(|e| ("command_state", e))?,
            }),
            (Some(_), None) => {
                return Err(("command_state", "missing: `step` needs it".into()));
            }
            (None, Some(_)) => {
                return Err((
                    "step",
                    "missing: the index of the step whose command is meant".into(),
                ));
            }
            (None, None) => {}
        }
        match (spec.di, spec.do_, spec.value) {
            (Some(_), Some(_), _) => {
                return Err(("do", "give `di` or `do`, not both".into()));
            }
            (Some(channel), None, Some(value)) => checks.push(Check::Di { channel, value }),
            (None, Some(channel), Some(value)) => checks.push(Check::Do { channel, value }),
            (Some(_), None, None) | (None, Some(_), None) => {
                return Err(("value", "missing: the level `di`/`do` must have".into()));
            }
            (None, None, Some(_)) => {
                return Err((
                    "value",
                    "applies to `di` or `do`, and neither is given".into(),
                ));
            }
            (None, None, None) => {}
        }
        if checks.is_empty() {
            return Err((
                "expect",
                "no condition: give an axis with state, position, …, a step with \
                 command_state, or di/do with value"
                    .into(),
            ));
        }
        Ok(Expectation {
            axis: spec.axis,
            group: spec.group,
            tolerance,
            checks,
        })
    }
}

/// The conditions of an `expect` about a group.
fn group_checks(spec: &ExpectSpec) -> Result<Vec<Check>, SpecError> {
    let mut checks = Vec::new();
    if let Some(name) = &spec.group_state {
        let state = GroupState::from_name(name).ok_or((
            "group_state",
            format!(
                "unknown state `{name}`: one of disabled, standby, moving, halted, stopping, \
                 error_stop"
            ),
        ))?;
        checks.push(Check::GroupState(state));
    }
    if let Some(p) = &spec.group_position {
        if let Some(v) = p.iter().find(|v| !v.is_finite()) {
            return Err(("group_position", format!("{v} is not a finite number")));
        }
        checks.push(Check::GroupPosition(p.clone()));
    }
    if let Some(v) = spec.in_position {
        checks.push(Check::GroupInPosition(v));
    }
    if let Some(v) = spec.user_segment {
        checks.push(Check::GroupUserSegment(v));
    }
    Ok(checks)
}

/// What an expectation sees at its tick.
pub(super) struct Seen<'a> {
    pub axis: Option<&'a AxisStatus>,
    pub group: Option<&'a GroupStatus>,
    /// The coupling whose slave the expectation's axis is, if any.
    pub coupling: Option<&'a CouplingStatus>,
    pub di: &'a [bool],
    pub do_: &'a [bool],
    /// The state of the command step `k` issued: `Err` says why there is none.
    pub command_state: &'a dyn Fn(usize) -> Result<CommandState, String>,
}

impl Expectation {
    /// Each condition that does not hold, described.
    pub fn failures(&self, seen: &Seen) -> Vec<String> {
        let mut out = Vec::new();
        let axis = self.axis.unwrap_or(0);
        let group = self.group.unwrap_or(0);
        for check in &self.checks {
            let mut msg = String::new();
            // Writing to a String cannot fail.
            let _ = match (check, seen.axis) {
                (Check::State(want), Some(s)) if s.state != *want => {
                    write!(msg, "axis {axis} state: expected {want}, saw {}", s.state)
                }
                (Check::Number(q, want), Some(s)) => {
                    let got = q.of(s);
                    if (got - want).abs() <= self.tolerance {
                        continue;
                    }
                    write!(
                        msg,
                        "axis {axis} {}: expected {want} ± {}, saw {got} (off by {})",
                        q.name(),
                        self.tolerance,
                        got - want
                    )
                }
                (Check::Flags(want), Some(s)) if !s.flags.contains(*want) => write!(
                    msg,
                    "axis {axis} flags: expected {} set, missing {} (set: {})",
                    flag_names(*want),
                    flag_names(*want - s.flags),
                    flag_names(s.flags)
                ),
                (Check::NotFlags(want), Some(s)) if s.flags.intersects(*want) => write!(
                    msg,
                    "axis {axis} flags: expected {} clear, set: {}",
                    flag_names(*want),
                    flag_names(*want & s.flags)
                ),
                (Check::Error(want), Some(s)) if s.last_error != *want => write!(
                    msg,
                    "axis {axis} error: expected {}, saw {}",
                    want.map_or("none", |e| e.name()),
                    s.last_error.map_or("none", |e| e.name())
                ),
                (Check::Coupling(want), Some(_)) => {
                    let got = seen.coupling.map(|c| c.phase);
                    if got == *want {
                        continue;
                    }
                    let name = |p: Option<CouplingPhase>| p.map_or("none", CouplingPhase::name);
                    write!(
                        msg,
                        "axis {axis} coupling: expected {}, saw {}",
                        name(*want),
                        name(got)
                    )
                }
                (Check::CouplingKind(want), Some(s)) if s.coupling != *want => write!(
                    msg,
                    "axis {axis} coupling_kind: expected {}, saw {}",
                    want.map_or("none", CouplingKind::name),
                    s.coupling.map_or("none", CouplingKind::name)
                ),
                (Check::TangentAngle(want), Some(_)) => {
                    let got = seen
                        .coupling
                        .filter(|c| c.kind == CouplingKind::Tangential)
                        .map(|c| c.angle);
                    match got {
                        Some(got) if (got - want).abs() <= self.tolerance => continue,
                        Some(got) => write!(
                            msg,
                            "axis {axis} tangent_angle: expected {want} ± {}, saw {got}",
                            self.tolerance
                        ),
                        None => write!(
                            msg,
                            "axis {axis} tangent_angle: expected {want}, but it is no \
                             tangential axis"
                        ),
                    }
                }
                (Check::StreamCount(count, want), Some(s)) if count.of(s) != *want => write!(
                    msg,
                    "axis {axis} {}: expected {want}, saw {}",
                    count.name(),
                    count.of(s)
                ),
                (Check::StreamRunning(want), Some(s)) if s.stream.running != *want => write!(
                    msg,
                    "axis {axis} stream_running: expected {want}, saw {}",
                    s.stream.running
                ),
                (Check::CommandState { step, state }, _) => match (seen.command_state)(*step) {
                    Ok(got) if state.matches(got) => continue,
                    Ok(got) => write!(
                        msg,
                        "command of step[{step}]: expected {state}, saw {}",
                        command_state_name(got)
                    ),
                    Err(why) => write!(msg, "command of step[{step}]: expected {state}, but {why}"),
                },
                (Check::Di { channel, value }, _) => {
                    let got = seen.di.get(*channel as usize).copied().unwrap_or(false);
                    if got == *value {
                        continue;
                    }
                    write!(msg, "di[{channel}]: expected {value}, saw {got}")
                }
                (Check::Do { channel, value }, _) => {
                    let got = seen.do_.get(*channel as usize).copied().unwrap_or(false);
                    if got == *value {
                        continue;
                    }
                    write!(msg, "do[{channel}]: expected {value}, saw {got}")
                }
                (
                    Check::GroupState(_)
                    | Check::GroupPosition(_)
                    | Check::GroupInPosition(_)
                    | Check::GroupUserSegment(_),
                    _,
                ) => {
                    let Some(g) = seen.group else {
                        out.push(format!("group {group}: it does not exist"));
                        continue;
                    };
                    match group_failure(check, g, self.tolerance) {
                        Some(m) => write!(msg, "group {group} {m}"),
                        None => continue,
                    }
                }
                _ => continue,
            };
            out.push(msg);
        }
        out
    }
}

/// What a group condition saw, when it does not hold.
fn group_failure(check: &Check, g: &GroupStatus, tolerance: f64) -> Option<String> {
    match check {
        Check::GroupState(want) if g.state != *want => {
            Some(format!("state: expected {want}, saw {}", g.state))
        }
        Check::GroupPosition(want) => {
            let got = g.position();
            let close = got.len() == want.len()
                && got
                    .iter()
                    .zip(want)
                    .all(|(a, b)| (a - b).abs() <= tolerance);
            (!close).then(|| format!("position: expected {want:?} ± {tolerance}, saw {got:?}"))
        }
        Check::GroupInPosition(want) if g.in_position != *want => Some(format!(
            "in_position: expected {want}, saw {}",
            g.in_position
        )),
        Check::GroupUserSegment(want) if g.user_segment != *want => Some(format!(
            "user_segment: expected {want}, saw {}",
            g.user_segment
        )),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> ExpectSpec {
        ExpectSpec::default()
    }

    #[test]
    fn shapes_are_checked() {
        let e = Expectation::from_spec(ExpectSpec {
            axis: Some(1),
            state: Some(AxisState::Standstill),
            position: Some(100.0),
            tolerance: Some(1e-6),
            flags: vec!["homed".into(), "IN_POSITION".into()],
            error: Some(String::new()),
            ..spec()
        })
        .unwrap();
        assert_eq!(e.checks.len(), 4);
        assert_eq!(
            e.checks[2],
            Check::Flags(AxisFlags::HOMED | AxisFlags::IN_POSITION)
        );
        assert_eq!(e.checks[3], Check::Error(None));
        let err = |s: ExpectSpec| Expectation::from_spec(s).unwrap_err();
        assert_eq!(err(spec()).0, "expect");
        assert_eq!(
            err(ExpectSpec {
                position: Some(1.0),
                ..spec()
            })
            .0,
            "axis"
        );
        let (key, why) = err(ExpectSpec {
            axis: Some(0),
            flags: vec!["homd".into()],
            ..spec()
        });
        assert_eq!(key, "flags");
        assert!(why.contains("homed"), "{why}");
        assert_eq!(
            err(ExpectSpec {
                axis: Some(0),
                error: Some("limit".into()),
                ..spec()
            })
            .0,
            "error"
        );
        assert_eq!(
            err(ExpectSpec {
                di: Some(3),
                ..spec()
            })
            .0,
            "value"
        );
        assert_eq!(
            err(ExpectSpec {
                step: Some(3),
                ..spec()
            })
            .0,
            "command_state"
        );
        assert_eq!(
            err(ExpectSpec {
                axis: Some(0),
                state: Some(AxisState::Standstill),
                tolerance: Some(0.1),
                ..spec()
            })
            .0,
            "tolerance"
        );
    }

    #[test]
    fn a_coupling_phase_is_an_axis_condition_and_says_what_it_saw() {
        let err = |s: ExpectSpec| Expectation::from_spec(s).unwrap_err();
        assert_eq!(
            err(ExpectSpec {
                axis: Some(1),
                coupling: Some("geared".into()),
                ..spec()
            })
            .0,
            "coupling"
        );
        assert_eq!(
            err(ExpectSpec {
                coupling: Some("in_sync".into()),
                ..spec()
            })
            .0,
            "axis"
        );
        let e = Expectation::from_spec(ExpectSpec {
            axis: Some(1),
            coupling: Some("in_sync".into()),
            ..spec()
        })
        .unwrap();
        let none = |_: usize| Err("unused".to_string());
        let status = AxisStatus::default();
        let engaging = CouplingStatus {
            phase: CouplingPhase::Engaging,
            ..CouplingStatus::default()
        };
        let seen = Seen {
            axis: Some(&status),
            group: None,
            coupling: Some(&engaging),
            di: &[],
            do_: &[],
            command_state: &none,
        };
        assert_eq!(
            e.failures(&seen),
            ["axis 1 coupling: expected in_sync, saw engaging"]
        );
        let free = Seen {
            coupling: None,
            ..seen
        };
        assert_eq!(
            e.failures(&free),
            ["axis 1 coupling: expected in_sync, saw none"]
        );
    }

    #[test]
    fn a_coupling_kind_and_a_tangent_angle_are_axis_conditions() {
        let err = |s: ExpectSpec| Expectation::from_spec(s).unwrap_err();
        let kind = |k: &str| ExpectSpec {
            axis: Some(2),
            coupling_kind: Some(k.into()),
            ..spec()
        };
        assert_eq!(err(kind("belt")).0, "coupling_kind");
        assert_eq!(
            err(ExpectSpec {
                tangent_angle: Some(f64::NAN),
                ..kind("tangential")
            })
            .0,
            "tangent_angle"
        );
        let e = Expectation::from_spec(ExpectSpec {
            tangent_angle: Some(90.0),
            tolerance: Some(0.5),
            ..kind("tangential")
        })
        .unwrap();
        let none = |_: usize| Err("unused".to_string());
        let status = AxisStatus {
            coupling: Some(CouplingKind::Superimpose),
            ..AxisStatus::default()
        };
        let superimposed = CouplingStatus {
            kind: CouplingKind::Superimpose,
            ..CouplingStatus::default()
        };
        let seen = Seen {
            axis: Some(&status),
            group: None,
            coupling: Some(&superimposed),
            di: &[],
            do_: &[],
            command_state: &none,
        };
        assert_eq!(
            e.failures(&seen),
            [
                "axis 2 tangent_angle: expected 90, but it is no tangential axis",
                "axis 2 coupling_kind: expected tangential, saw superimpose"
            ]
        );
        let tangential = AxisStatus {
            coupling: Some(CouplingKind::Tangential),
            ..AxisStatus::default()
        };
        let at = |angle: f64| CouplingStatus {
            kind: CouplingKind::Tangential,
            angle,
            ..CouplingStatus::default()
        };
        let (near, far) = (at(90.4), at(91.0));
        let seen = Seen {
            axis: Some(&tangential),
            coupling: Some(&near),
            ..seen
        };
        assert!(e.failures(&seen).is_empty());
        let seen = Seen {
            coupling: Some(&far),
            ..seen
        };
        assert_eq!(
            e.failures(&seen),
            ["axis 2 tangent_angle: expected 90 ± 0.5, saw 91"]
        );
    }

    #[test]
    fn command_states_parse() {
        assert_eq!(
            ExpectedState::parse("error:limit_reached").unwrap(),
            ExpectedState::Exactly(CommandState::Error(ErrorKind::LimitReached))
        );
        assert!(ExpectedState::parse("error")
            .unwrap()
            .matches(CommandState::Error(ErrorKind::Fault)));
        assert!(ExpectedState::parse("finished").is_err());
        assert!(ExpectedState::parse("error:nope").is_err());
    }

    #[test]
    fn failures_say_what_was_expected_and_seen() {
        let e = Expectation {
            axis: Some(2),
            group: None,
            tolerance: 0.5,
            checks: vec![
                Check::State(AxisState::Standstill),
                Check::Number(Quantity::Position, 10.0),
                Check::Flags(AxisFlags::HOMED),
                Check::Di {
                    channel: 1,
                    value: true,
                },
            ],
        };
        let status = AxisStatus {
            state: AxisState::DiscreteMotion,
            act_pos: 10.4,
            flags: AxisFlags::ENABLED,
            ..AxisStatus::default()
        };
        let none = |_: usize| Err::<CommandState, String>("no".into());
        let seen = Seen {
            axis: Some(&status),
            group: None,
            coupling: None,
            di: &[false, false],
            do_: &[],
            command_state: &none,
        };
        let f = e.failures(&seen);
        assert_eq!(
            f,
            [
                "axis 2 state: expected standstill, saw discrete_motion",
                "axis 2 flags: expected homed set, missing homed (set: enabled)",
                "di[1]: expected true, saw false",
            ]
        );
    }

    #[test]
    fn stream_conditions_say_what_they_saw() {
        let e = Expectation::from_spec(ExpectSpec {
            axis: Some(1),
            stream_space: Some(32),
            stream_used: Some(0),
            stream_running: Some(true),
            stream_underruns: Some(0),
            ..spec()
        })
        .unwrap();
        assert_eq!(e.checks.len(), 4);
        let mut status = AxisStatus::default();
        status.stream.space = 29;
        status.stream.used = 3;
        let none = |_: usize| Err::<CommandState, String>("no".into());
        let seen = Seen {
            axis: Some(&status),
            group: None,
            di: &[],
            do_: &[],
            command_state: &none,
            coupling: None,
        };
        assert_eq!(
            e.failures(&seen),
            [
                "axis 1 stream_space: expected 32, saw 29",
                "axis 1 stream_used: expected 0, saw 3",
                "axis 1 stream_running: expected true, saw false",
            ]
        );
    }

    #[test]
    fn group_conditions_need_a_group_and_say_what_they_saw() {
        let spec = ExpectSpec {
            group_state: Some("moving".into()),
            ..ExpectSpec::default()
        };
        assert_eq!(Expectation::from_spec(spec).unwrap_err().0, "group");
        let spec = ExpectSpec {
            group: Some(1),
            group_state: Some("gliding".into()),
            ..ExpectSpec::default()
        };
        assert_eq!(Expectation::from_spec(spec).unwrap_err().0, "group_state");
        let e = Expectation::from_spec(ExpectSpec {
            group: Some(1),
            group_state: Some("standby".into()),
            group_position: Some(vec![1.0, 2.0]),
            tolerance: Some(0.1),
            in_position: Some(true),
            user_segment: Some(4),
            ..ExpectSpec::default()
        })
        .unwrap();
        let mut g = GroupStatus {
            group: 1,
            state: GroupState::Moving,
            axis_count: 2,
            user_segment: 4,
            ..GroupStatus::default()
        };
        g.coordinates[0] = 1.05;
        g.coordinates[1] = 2.5;
        let none = |_: usize| Err::<CommandState, String>("no".into());
        let seen = Seen {
            axis: None,
            group: Some(&g),
            coupling: None,
            di: &[],
            do_: &[],
            command_state: &none,
        };
        assert_eq!(
            e.failures(&seen),
            [
                "group 1 state: expected standby, saw moving",
                "group 1 position: expected [1.0, 2.0] ± 0.1, saw [1.05, 2.5]",
                "group 1 in_position: expected true, saw false",
            ]
        );
        let gone = Seen {
            group: None,
            ..seen
        };
        assert_eq!(e.failures(&gone).len(), 4);
    }
}
