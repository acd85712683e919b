//! Read sources and write targets: the paths a map names (`axis.act_pos`, `axis.param.speed`,
//! `do.3`, `machine.error` …), parsed once when the map is compiled and evaluated on a snapshot
//! for every read.

use axes::command::ErrorKind;
use axes::filter::FilterStatus;
use axes::param::{parameter_value, ParamId};
use axes::status::{flag_by_name, AxisState, AxisStatus, CouplingKind, Snapshot};
use axes::AxisFlags;

/// What the machine has, for checking that a map's paths exist.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MachineShape {
    pub axes: usize,
    pub digital_inputs: usize,
    pub digital_outputs: usize,
    pub analog_inputs: usize,
    pub analog_outputs: usize,
    /// Slaves (CiA 402 drives) by slave number: the axis each moves.
    pub slaves: Vec<u16>,
}

/// A field of the axis status.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisField {
    /// The machine's number of the axis (HMC AxisID).
    Index,
    /// The PLCopen state: its position in [`AXIS_STATES`], or its name in a `values` lookup.
    State,
    Flags,
    Latched,
    CmdPos,
    CmdVel,
    CmdAcc,
    ActPos,
    ActVel,
    FollowingError,
    TargetPos,
    Remaining,
    Pulses,
    PulsesLastTick,
    PulseFrequency,
    EncoderCounts,
    DacOut,
    FifoLen,
    HomingPhase,
    MotionDirection,
    /// The last error: 0 for none, else its kind's position in the engine's list plus one, or
    /// its name in a `values` lookup.
    LastError,
}

const AXIS_FIELDS: &[(&str, AxisField)] = &[
    ("index", AxisField::Index),
    ("state", AxisField::State),
    ("flags", AxisField::Flags),
    ("latched", AxisField::Latched),
    ("cmd_pos", AxisField::CmdPos),
    ("cmd_vel", AxisField::CmdVel),
    ("cmd_acc", AxisField::CmdAcc),
    ("act_pos", AxisField::ActPos),
    ("act_vel", AxisField::ActVel),
    ("following_error", AxisField::FollowingError),
    ("target_pos", AxisField::TargetPos),
    ("remaining", AxisField::Remaining),
    ("pulses", AxisField::Pulses),
    ("pulses_last_tick", AxisField::PulsesLastTick),
    ("pulse_frequency", AxisField::PulseFrequency),
    ("encoder_counts", AxisField::EncoderCounts),
    ("dac_out", AxisField::DacOut),
    ("fifo_len", AxisField::FifoLen),
    ("homing_phase", AxisField::HomingPhase),
    ("motion_direction", AxisField::MotionDirection),
    ("last_error", AxisField::LastError),
];

/// The PLCopen states in the order `axis.state` numbers them.
pub const AXIS_STATES: [AxisState; 8] = [
    AxisState::Disabled,
    AxisState::Standstill,
    AxisState::Homing,
    AxisState::DiscreteMotion,
    AxisState::ContinuousMotion,
    AxisState::SynchronizedMotion,
    AxisState::Stopping,
    AxisState::ErrorStop,
];

/// A machine-wide value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MachineField {
    Tick,
    /// Engine time, seconds.
    Time,
    AxisCount,
    /// 1 when any axis is in ErrorStop.
    Error,
    /// 1 when any axis is moving.
    Moving,
}

/// One bit of a composed status word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BitSource {
    Flag { flag: AxisFlags, latched: bool },
    State(AxisState),
    Mode(AxisMode),
}

/// What an axis is part of or runs, beyond its flags (`mode.NAME`; HIMC motion_status bits
/// 5–8, digest 004 Table 5.1.1.5).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisMode {
    /// Master or slave of an engaged gantry.
    Gantry,
    /// The slave of a gear.
    Gear,
    /// Its active command filter is an input shaper.
    InputShaping,
    /// Its active command filter is a VSF.
    Vsf,
}

const AXIS_MODES: &[(&str, AxisMode)] = &[
    ("gantry", AxisMode::Gantry),
    ("gear", AxisMode::Gear),
    ("input_shaping", AxisMode::InputShaping),
    ("vsf", AxisMode::Vsf),
];

/// Where a read comes from, with the axis resolved.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// The point's own memory cell.
    Memory,
    Axis {
        axis: usize,
        field: AxisField,
    },
    /// A flag or state of an axis as 0/1; `invert` for `!name`.
    AxisBit {
        axis: usize,
        bit: BitSource,
        invert: bool,
    },
    Param {
        axis: usize,
        id: ParamId,
    },
    DigitalInput(usize),
    DigitalOutput(usize),
    AnalogInput(usize),
    AnalogOutput(usize),
    /// A CiA 402 drive's statusword (0x6041), mode display (0x6061) or error code (0x603F).
    Drive {
        slave: usize,
        field: DriveField,
    },
    Machine(MachineField),
    /// A word composed of bits.
    Bits {
        axis: usize,
        bits: Vec<(u8, BitSource, bool)>,
    },
    /// The first case that holds on the first axis (in order) where one does.
    Select {
        axes: Vec<usize>,
        cases: Vec<(Case, f64)>,
    },
}

/// A condition of a `first` table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Case {
    Bit { bit: BitSource, invert: bool },
    LastError(ErrorKind),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DriveField {
    Statusword,
    Mode,
    ErrorCode,
}

/// Where a write goes.
#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    /// The point's own memory cell.
    Memory,
    Param {
        axis: usize,
        id: ParamId,
    },
    DigitalOutput(usize),
    AnalogOutput(usize),
}

/// What a read gives before the point's lookup and scale: a number, and a name where the
/// source has one (states, error kinds), so lookups can be written by name.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Datum {
    pub number: f64,
    pub name: Option<&'static str>,
    /// The axis the value belongs to, where it has one (for `axis_code`).
    pub axis: Option<usize>,
}

impl Datum {
    fn number(number: f64) -> Datum {
        Datum {
            number,
            name: None,
            axis: None,
        }
    }
}

/// Resolves the axis of a path: `axis.x` is the block's axis (or, outside blocks, the first
/// axis the front-end serves), `axis[N].x` machine axis N.
pub struct Scope<'a> {
    pub machine: &'a MachineShape,
    /// The axis `axis.` means, if any.
    pub axis: Option<usize>,
}

fn index(text: &str, what: &str, count: usize) -> Result<usize, String> {
    let n: usize = text
        .parse()
        .map_err(|_| format!("`{text}` is not a {what} number"))?;
    if n >= count {
        return Err(format!(
            "{what} {n} does not exist (the machine has {count})"
        ));
    }
    Ok(n)
}

/// Split `axis.rest` or `axis[N].rest` into the axis and the rest.
fn axis_path<'p>(path: &'p str, scope: &Scope<'_>) -> Result<Option<(usize, &'p str)>, String> {
    if let Some(rest) = path.strip_prefix("axis.") {
        let axis = scope.axis.ok_or_else(|| {
            "`axis.` needs an axis: use it in a block, give the front-end an axis, or write \
             `axis[N].`"
                .to_string()
        })?;
        return Ok(Some((axis, rest)));
    }
    if let Some(rest) = path.strip_prefix("axis[") {
        let (n, rest) = rest
            .split_once("].")
            .ok_or_else(|| format!("`{path}`: expected `axis[N].field`"))?;
        return Ok(Some((index(n, "axis", scope.machine.axes)?, rest)));
    }
    Ok(None)
}

fn bit_source(name: &str) -> Result<(BitSource, bool), String> {
    let (invert, name) = match name.strip_prefix('!') {
        Some(n) => (true, n),
        None => (false, name),
    };
    if let Some(state) = name.strip_prefix("state.") {
        let s = AXIS_STATES
            .iter()
            .find(|s| s.name() == state)
            .ok_or_else(|| format!("`{state}` is not an axis state ({})", state_names()))?;
        return Ok((BitSource::State(*s), invert));
    }
    if let Some(mode) = name.strip_prefix("mode.") {
        let m = AXIS_MODES.iter().find(|(n, _)| *n == mode).ok_or_else(|| {
            format!("`{mode}` is not an axis mode (gantry, gear, input_shaping, vsf)")
        })?;
        return Ok((BitSource::Mode(m.1), invert));
    }
    let (latched, flag) = match name.strip_prefix("latched.") {
        Some(f) => (true, f),
        None => (false, name),
    };
    let flag = flag_by_name(flag).ok_or_else(|| format!("`{flag}` is not an axis flag"))?;
    Ok((BitSource::Flag { flag, latched }, invert))
}

fn state_names() -> String {
    AXIS_STATES
        .iter()
        .map(|s| s.name())
        .collect::<Vec<_>>()
        .join(", ")
}

fn param(name: &str) -> Result<ParamId, String> {
    ParamId::from_name(name).ok_or_else(|| format!("`{name}` is not a parameter"))
}

/// Parse a read path.
pub fn parse_source(path: &str, scope: &Scope<'_>) -> Result<Source, String> {
    let m = scope.machine;
    if path == "memory" {
        return Ok(Source::Memory);
    }
    if let Some((axis, rest)) = axis_path(path, scope)? {
        if let Some(name) = rest.strip_prefix("param.") {
            return Ok(Source::Param {
                axis,
                id: param(name)?,
            });
        }
        if let Some(field) = AXIS_FIELDS.iter().find(|(n, _)| *n == rest) {
            return Ok(Source::Axis {
                axis,
                field: field.1,
            });
        }
        if let Some(name) = rest.strip_prefix("drive.") {
            let slave = m
                .slaves
                .iter()
                .position(|&a| usize::from(a) == axis)
                .ok_or_else(|| format!("axis {axis} has no CiA 402 drive"))?;
            let field = match name {
                "statusword" => DriveField::Statusword,
                "mode" => DriveField::Mode,
                "error_code" => DriveField::ErrorCode,
                _ => {
                    return Err(format!(
                        "`{name}` is not a drive field (statusword, mode, error_code)"
                    ))
                }
            };
            return Ok(Source::Drive { slave, field });
        }
        let (bit, invert) = bit_source(rest).map_err(|_| {
            format!(
                "`{rest}` is not an axis field ({}), `param.NAME`, `drive.FIELD`, a flag or `state.NAME`",
                AXIS_FIELDS.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
            )
        })?;
        return Ok(Source::AxisBit { axis, bit, invert });
    }
    if let Some((kind, n)) = path.split_once('.') {
        return match kind {
            "di" => Ok(Source::DigitalInput(index(
                n,
                "digital input",
                m.digital_inputs,
            )?)),
            "do" => Ok(Source::DigitalOutput(index(
                n,
                "digital output",
                m.digital_outputs,
            )?)),
            "ai" => Ok(Source::AnalogInput(index(
                n,
                "analog input",
                m.analog_inputs,
            )?)),
            "ao" => Ok(Source::AnalogOutput(index(
                n,
                "analog output",
                m.analog_outputs,
            )?)),
            "machine" => Ok(Source::Machine(match n {
                "tick" => MachineField::Tick,
                "time" => MachineField::Time,
                "axis_count" => MachineField::AxisCount,
                "error" => MachineField::Error,
                "moving" => MachineField::Moving,
                _ => {
                    return Err(format!(
                        "`{n}` is not a machine field (tick, time, axis_count, error, moving)"
                    ))
                }
            })),
            _ => Err(unknown(path)),
        };
    }
    Err(unknown(path))
}

fn unknown(path: &str) -> String {
    format!(
        "`{path}` is not a source: use `memory`, `axis.FIELD`, `axis.param.NAME`, `axis.FLAG`, \
         `di.N`, `do.N`, `ai.N`, `ao.N` or `machine.FIELD`"
    )
}

/// Parse a `{ bits = { N = "flag" … } }` table.
pub fn parse_bits<'b>(
    bits: impl IntoIterator<Item = (&'b String, &'b String)>,
    width: u8,
    scope: &Scope<'_>,
) -> Result<Source, String> {
    let axis = scope.axis.ok_or_else(|| {
        "a bit table needs an axis: use it in a block or give the front-end an axis".to_string()
    })?;
    let mut out = Vec::new();
    for (bit, name) in bits {
        let n: u8 = bit
            .parse()
            .ok()
            .filter(|n| *n < width)
            .ok_or_else(|| format!("bit `{bit}` is not a bit number below {width}"))?;
        let (source, invert) = bit_source(name)?;
        out.push((n, source, invert));
    }
    Ok(Source::Bits { axis, bits: out })
}

/// Parse a `{ first = [...] }` table for the scope's axis, or for `axes` in turn.
pub fn parse_select<'c>(
    cases: impl IntoIterator<Item = (&'c str, f64)>,
    axes: Vec<usize>,
) -> Result<Source, String> {
    if axes.is_empty() {
        return Err(
            "a `first` table needs an axis: use it in a block or give the front-end an axis".into(),
        );
    }
    let mut out = Vec::new();
    for (when, value) in cases {
        let case = match when.strip_prefix("last_error.") {
            Some(kind) => {
                let kind: ErrorKind =
                    serde_json::from_value(serde_json::Value::String(kind.into()))
                        .map_err(|_| format!("`{kind}` is not an engine error kind"))?;
                Case::LastError(kind)
            }
            None => {
                let (bit, invert) = bit_source(when)?;
                Case::Bit { bit, invert }
            }
        };
        out.push((case, value));
    }
    Ok(Source::Select { axes, cases: out })
}

/// Parse a write target.
pub fn parse_target(path: &str, scope: &Scope<'_>) -> Result<Target, String> {
    let m = scope.machine;
    if path == "memory" {
        return Ok(Target::Memory);
    }
    if let Some((axis, rest)) = axis_path(path, scope)? {
        if let Some(name) = rest.strip_prefix("param.") {
            let id = param(name)?;
            if id.def().access == axes::param::ParamAccess::ReadOnly {
                return Err(format!("parameter `{}` is read-only", id.name()));
            }
            return Ok(Target::Param { axis, id });
        }
        return Err(format!(
            "`{path}`: an axis takes writes through `axis.param.NAME` or `on_write` commands"
        ));
    }
    match path.split_once('.') {
        Some(("do", n)) => Ok(Target::DigitalOutput(index(
            n,
            "digital output",
            m.digital_outputs,
        )?)),
        Some(("ao", n)) => Ok(Target::AnalogOutput(index(
            n,
            "analog output",
            m.analog_outputs,
        )?)),
        _ => Err(format!(
            "`{path}` is not a write target: use `memory`, `axis.param.NAME`, `do.N` or `ao.N`"
        )),
    }
}

fn bit_value(snapshot: &Snapshot, axis: usize, status: &AxisStatus, bit: BitSource) -> bool {
    match bit {
        BitSource::Mode(mode) => mode_holds(snapshot, axis, status, mode),
        BitSource::Flag {
            flag,
            latched: false,
        } => status.flags.contains(flag),
        BitSource::Flag {
            flag,
            latched: true,
        } => status.latched.contains(flag),
        BitSource::State(s) => status.state == s,
    }
}

fn mode_holds(snapshot: &Snapshot, axis: usize, status: &AxisStatus, mode: AxisMode) -> bool {
    match mode {
        AxisMode::Gantry => {
            status.coupling == Some(CouplingKind::Gantry)
                || snapshot
                    .couplings
                    .iter()
                    .any(|c| c.kind == CouplingKind::Gantry && usize::from(c.master) == axis)
        }
        AxisMode::Gear => status.coupling == Some(CouplingKind::Gear),
        AxisMode::InputShaping => matches!(
            status.command_filter,
            Some(FilterStatus::InputShaping { .. })
        ),
        AxisMode::Vsf => matches!(status.command_filter, Some(FilterStatus::Vsf { .. })),
    }
}

fn flag(on: bool) -> f64 {
    if on {
        1.0
    } else {
        0.0
    }
}

impl Source {
    /// Evaluate on a snapshot. `None` for `Memory` (the caller reads its cell) and for an
    /// index the snapshot does not have (cannot happen for a map compiled for this machine).
    pub fn read(&self, snapshot: &Snapshot) -> Option<Datum> {
        let io = &snapshot.io;
        Some(match self {
            Source::Memory => return None,
            Source::Axis {
                axis,
                field: AxisField::Index,
            } => Datum::number(*axis as f64),
            Source::Axis { axis, field } => axis_field(snapshot.axes.get(*axis)?, *field),
            Source::AxisBit { axis, bit, invert } => {
                let status = snapshot.axes.get(*axis)?;
                Datum::number(flag(bit_value(snapshot, *axis, status, *bit) != *invert))
            }
            Source::Param { axis, id } => Datum::number(parameter_value(
                *id,
                snapshot.axes.get(*axis)?,
                snapshot.params.get(*axis)?,
            )),
            Source::DigitalInput(n) => Datum::number(flag(*io.di.get(*n)?)),
            Source::DigitalOutput(n) => Datum::number(flag(*io.do_.get(*n)?)),
            Source::AnalogInput(n) => Datum::number(*io.ai.get(*n)?),
            Source::AnalogOutput(n) => Datum::number(*io.ao.get(*n)?),
            Source::Drive { slave, field } => {
                let d = snapshot.drives.get(*slave)?;
                Datum::number(match field {
                    DriveField::Statusword => f64::from(d.statusword),
                    DriveField::Mode => f64::from(d.mode),
                    DriveField::ErrorCode => f64::from(d.error_code),
                })
            }
            Source::Machine(field) => Datum::number(match field {
                MachineField::Tick => snapshot.tick as f64,
                MachineField::Time => snapshot.time(),
                MachineField::AxisCount => snapshot.axes.len() as f64,
                MachineField::Error => flag(
                    snapshot
                        .axes
                        .iter()
                        .any(|a| a.state == AxisState::ErrorStop),
                ),
                MachineField::Moving => flag(
                    snapshot
                        .axes
                        .iter()
                        .any(|a| a.flags.contains(AxisFlags::MOVING)),
                ),
            }),
            Source::Bits { axis, bits } => {
                let status = snapshot.axes.get(*axis)?;
                let word = bits
                    .iter()
                    .filter(|(_, bit, invert)| bit_value(snapshot, *axis, status, *bit) != *invert)
                    .fold(0u64, |w, (n, _, _)| w | 1 << n);
                Datum::number(word as f64)
            }
            Source::Select { axes, cases } => {
                for &axis in axes {
                    let status = snapshot.axes.get(axis)?;
                    let hit = cases.iter().find(|(case, _)| match case {
                        Case::Bit { bit, invert } => {
                            bit_value(snapshot, axis, status, *bit) != *invert
                        }
                        Case::LastError(kind) => status.last_error == Some(*kind),
                    });
                    if let Some((_, value)) = hit {
                        return Some(Datum {
                            number: *value,
                            name: None,
                            axis: Some(axis),
                        });
                    }
                }
                Datum::number(0.0)
            }
        })
        .map(|d| match (d.axis, self.axis()) {
            (None, Some(axis)) => Datum {
                axis: Some(axis),
                ..d
            },
            _ => d,
        })
    }

    /// The axis a per-axis source reads.
    fn axis(&self) -> Option<usize> {
        match self {
            Source::Axis { axis, .. }
            | Source::AxisBit { axis, .. }
            | Source::Param { axis, .. }
            | Source::Bits { axis, .. } => Some(*axis),
            _ => None,
        }
    }
}

fn axis_field(s: &AxisStatus, field: AxisField) -> Datum {
    let n = |v: f64| Datum::number(v);
    match field {
        // Resolved by the caller, which knows the axis.
        AxisField::Index => n(0.0),
        AxisField::State => Datum {
            number: AXIS_STATES.iter().position(|x| *x == s.state).unwrap_or(0) as f64,
            name: Some(s.state.name()),
            axis: None,
        },
        AxisField::Flags => n(f64::from(s.flags.bits())),
        AxisField::Latched => n(f64::from(s.latched.bits())),
        AxisField::CmdPos => n(s.cmd_pos),
        AxisField::CmdVel => n(s.cmd_vel),
        AxisField::CmdAcc => n(s.cmd_acc),
        AxisField::ActPos => n(s.act_pos),
        AxisField::ActVel => n(s.act_vel),
        AxisField::FollowingError => n(s.following_error),
        AxisField::TargetPos => n(s.target_pos),
        AxisField::Remaining => n(s.remaining),
        AxisField::Pulses => n(s.pulses as f64),
        AxisField::PulsesLastTick => n(f64::from(s.pulses_last_tick)),
        AxisField::PulseFrequency => n(s.pulse_frequency),
        AxisField::EncoderCounts => n(s.encoder_counts as f64),
        AxisField::DacOut => n(s.dac_out),
        AxisField::FifoLen => n(f64::from(s.fifo_len)),
        AxisField::HomingPhase => n(f64::from(s.homing_phase)),
        AxisField::MotionDirection => n(f64::from(s.motion_direction)),
        AxisField::LastError => match s.last_error {
            None => Datum {
                number: 0.0,
                name: Some("none"),
                axis: None,
            },
            Some(kind) => Datum {
                number: f64::from(kind as u8) + 1.0,
                name: Some(kind.name()),
                axis: None,
            },
        },
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn machine() -> MachineShape {
        MachineShape {
            axes: 2,
            digital_inputs: 4,
            digital_outputs: 4,
            analog_inputs: 1,
            analog_outputs: 1,
            slaves: vec![1],
        }
    }

    fn parse(path: &str, axis: Option<usize>) -> Result<Source, String> {
        let m = machine();
        parse_source(path, &Scope { machine: &m, axis })
    }

    #[test]
    fn paths_resolve_to_their_axis_and_bad_ones_say_why() {
        assert_eq!(
            parse("axis.act_pos", Some(1)).unwrap(),
            Source::Axis {
                axis: 1,
                field: AxisField::ActPos
            }
        );
        assert_eq!(
            parse("axis[0].param.Speed", None).unwrap(),
            Source::Param {
                axis: 0,
                id: ParamId::Speed
            }
        );
        assert_eq!(
            parse("axis.drive.statusword", Some(1)).unwrap(),
            Source::Drive {
                slave: 0,
                field: DriveField::Statusword
            }
        );
        assert!(matches!(
            parse("axis.!homed", Some(0)).unwrap(),
            Source::AxisBit { invert: true, .. }
        ));
        for (path, axis, says) in [
            ("axis.act_pos", None, "needs an axis"),
            ("axis[2].act_pos", None, "axis 2 does not exist"),
            ("axis.param.nope", Some(0), "`nope` is not a parameter"),
            (
                "axis.drive.statusword",
                Some(0),
                "axis 0 has no CiA 402 drive",
            ),
            ("axis.velocity", Some(0), "is not an axis field"),
            ("di.4", None, "digital input 4 does not exist"),
            ("machine.mood", None, "not a machine field"),
            ("registers", None, "is not a source"),
        ] {
            let e = parse(path, axis).unwrap_err();
            assert!(e.contains(says), "{path}: {e}");
        }
        let m = machine();
        let scope = Scope {
            machine: &m,
            axis: Some(0),
        };
        assert!(parse_target("axis.param.MPos", &scope)
            .unwrap_err()
            .contains("read-only"));
        assert_eq!(
            parse_target("do.3", &scope).unwrap(),
            Target::DigitalOutput(3)
        );
    }

    #[test]
    fn sources_read_the_snapshot() {
        let mut snapshot = Snapshot {
            axes: vec![AxisStatus::default(); 2],
            params: std::sync::Arc::new(vec![Default::default(); 2]),
            ..Snapshot::default()
        };
        snapshot.io.do_ = vec![false, true];
        let a = &mut snapshot.axes[1];
        a.act_pos = 12.5;
        a.state = AxisState::ErrorStop;
        a.flags = AxisFlags::ENABLED | AxisFlags::HOMED;
        a.last_error = Some(ErrorKind::LimitActive);
        let read = |path: &str| parse(path, Some(1)).unwrap().read(&snapshot).unwrap();
        assert_eq!(read("axis.act_pos").number, 12.5);
        assert_eq!(read("axis.state").number, 7.0);
        assert_eq!(read("axis.state").name, Some("error_stop"));
        assert_eq!(read("axis.last_error").name, Some("limit_active"));
        assert_eq!(read("axis.homed").number, 1.0);
        assert_eq!(read("axis.!enabled").number, 0.0);
        assert_eq!(read("axis.state.error_stop").number, 1.0);
        assert_eq!(
            read("axis.param.speed").number,
            ParamId::Speed.def().default
        );
        assert_eq!(read("do.1").number, 1.0);
        assert_eq!(read("machine.error").number, 1.0);
        let m = machine();
        let bits = [
            ("0".to_string(), "enabled".to_string()),
            ("3".to_string(), "!moving".to_string()),
            ("11".to_string(), "homed".to_string()),
        ];
        let word = parse_bits(
            bits.iter().map(|(a, b)| (a, b)),
            16,
            &Scope {
                machine: &m,
                axis: Some(1),
            },
        )
        .unwrap();
        assert_eq!(
            word.read(&snapshot).unwrap().number,
            f64::from(1 | 1 << 3 | 1 << 11)
        );
    }
}
