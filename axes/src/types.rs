//! Leaf types of the engine: indices, ids and kinds that every layer names (status, homing,
//! errors, commands). This module imports nothing from the crate, so it can sit at the bottom of
//! the module chain (docs/architecture.md); `command` re-exports each type under its old path.

use serde::{Deserialize, Serialize};

/// Index of an axis in the machine, from 0.
pub type AxisIndex = u16;

/// Number of an axis group, chosen by the user at `group_create` (issue 11).
pub type GroupId = u16;

/// Most axes in one group (HIMC: 9, digest 004 §3; `path::MAX_AXES`).
pub const MAX_GROUP_AXES: usize = 9;

/// Identifier of a queued motion command. Engine-wide, increasing from 1; 0 is never used.
pub type CommandId = u32;

/// What kind of command occupies a FIFO slot; reported in status (HMC MCmdType/NCmdType).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CommandKind {
    MoveAbsolute,
    MoveRelative,
    MoveVelocity,
    Home,
    /// A drive-driven or externally streamed setpoint (CSP/CSV/CST, HMC_SetDposSwitch).
    External,
    /// A PT or PVT stream (NMC MtPtStartMtn / MtPvtStartMtn, HIMC MovePVT; issue 12 item 3).
    Stream,
}

impl CommandKind {
    /// Stable numeric code used where a status word carries the kind (0 = idle).
    pub const fn code(self) -> u16 {
        match self {
            CommandKind::MoveAbsolute => 1,
            CommandKind::MoveRelative => 2,
            CommandKind::MoveVelocity => 3,
            CommandKind::Home => 4,
            CommandKind::External => 5,
            CommandKind::Stream => 6,
        }
    }
}

/// How an axis's PT/PVT buffer holds its points (NMC `MtPtSetStatic`, `TPvtPara.dataMode`,
/// digest 001 §2.13–2.14).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StreamMode {
    /// NMC 数据刷新 (the default): two FIFOs of 32 points; a FIFO's space comes back once all
    /// its points have run, so a host refills the stream while it runs.
    #[default]
    Refresh,
    /// NMC 数据驻存: one buffer of 32 points, kept after the run and replayed `loop_count`
    /// times.
    Static,
    /// HIMC `MovePVT`: up to 50 points run once (set by `pvt_move`, not by `stream_config`).
    Once,
}

impl StreamMode {
    pub const fn name(self) -> &'static str {
        match self {
            StreamMode::Refresh => "refresh",
            StreamMode::Static => "static",
            StreamMode::Once => "once",
        }
    }
}

/// Which value of the master a slave follows (NMC master types 1–3, digest 001 §2.16).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MasterSource {
    /// The master's planned (commanded) position: NMC type 1, HIMC GearIn.
    #[default]
    Commanded,
    /// The master's actual position from its feedback: NMC type 2, HMC (ΔDposS = ΔMposM ·
    /// ratio, digest 000 §4.3).
    Actual,
    /// The master's encoder reading (counts in user units, without `set_position`'s offset):
    /// NMC type 3, an encoder input such as an encoder-only axis.
    Encoder,
}

/// Direction of travel or of a limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    Positive,
    Negative,
}

impl std::fmt::Display for Direction {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Direction::Positive => "positive",
            Direction::Negative => "negative",
        })
    }
}

/// The name of an [`EngineError`](crate::error::EngineError) variant without its data: `Copy`, so
/// it fits in status records and traces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorKind {
    InvalidAxis,
    UnknownParameter,
    InvalidParameter,
    ReadOnlyParameter,
    InvalidArgument,
    AxisDisabled,
    AxisInError,
    LimitActive,
    QueueFull,
    Unsupported,
    InvalidState,
    CauseStillPresent,
    UnknownCommand,
    Homing,
    Object,
    InvalidSlave,
    InvalidChannel,
    /// Not a refusal: a running command ended because a limit was reached.
    LimitReached,
    /// Not a refusal: a running command ended because of a fault (following error, alarm …).
    Fault,
    /// No such group, or a group definition that cannot be (issue 11).
    InvalidGroup,
    /// The group's state (or a member's) does not allow the command.
    GroupState,
}

impl ErrorKind {
    pub const fn name(self) -> &'static str {
        match self {
            ErrorKind::InvalidAxis => "invalid_axis",
            ErrorKind::UnknownParameter => "unknown_parameter",
            ErrorKind::InvalidParameter => "invalid_parameter",
            ErrorKind::ReadOnlyParameter => "read_only_parameter",
            ErrorKind::InvalidArgument => "invalid_argument",
            ErrorKind::AxisDisabled => "axis_disabled",
            ErrorKind::AxisInError => "axis_in_error",
            ErrorKind::LimitActive => "limit_active",
            ErrorKind::QueueFull => "queue_full",
            ErrorKind::Unsupported => "unsupported",
            ErrorKind::InvalidState => "invalid_state",
            ErrorKind::CauseStillPresent => "cause_still_present",
            ErrorKind::UnknownCommand => "unknown_command",
            ErrorKind::Homing => "homing",
            ErrorKind::Object => "object",
            ErrorKind::InvalidSlave => "invalid_slave",
            ErrorKind::InvalidChannel => "invalid_channel",
            ErrorKind::LimitReached => "limit_reached",
            ErrorKind::Fault => "fault",
            ErrorKind::InvalidGroup => "invalid_group",
            ErrorKind::GroupState => "group_state",
        }
    }
}

/// The coordinate system a group's positions are given in (issue 11 item 1).
///
/// JSON: a string. `"mcs"` (machine coordinates, the default); HIMC's frame links joined by
/// `|` as `coord_sys` combines them (digest 004 §2.7 Table 8.1.2.1, §8.3.21): `"pcs"`,
/// `"wcs1|pcs"`, `"offset|wcs2|pcs"`; or an NMC transform once set (digest 001 §2.10):
/// `"rotary"` (`CrdSetTransRotate`), `"xyza"` (`CrdSetTransXYZA`). A WCS number is parsed as any
/// `u8`; the engine refuses one outside 1–15 as an undefined system (a typed error, not a JSON
/// one).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum CoordinateSystem {
    /// HIMC's chain: the links a position goes through to reach the MCS; none is the MCS.
    Chain {
        offset: bool,
        wcs: Option<u8>,
        pcs: bool,
    },
    /// NMC `CrdSetTransRotate`: the workpiece on a rotary table.
    Rotary,
    /// NMC `CrdSetTransXYZA`: the tool on a rotary A axis.
    Xyza,
}

impl Default for CoordinateSystem {
    fn default() -> Self {
        CoordinateSystem::MCS
    }
}

impl CoordinateSystem {
    /// `CS_MCS`: machine coordinates.
    pub const MCS: CoordinateSystem = CoordinateSystem::Chain {
        offset: false,
        wcs: None,
        pcs: false,
    };

    pub fn is_machine(self) -> bool {
        self == CoordinateSystem::MCS
    }
}

impl std::fmt::Display for CoordinateSystem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            CoordinateSystem::Rotary => f.write_str("rotary"),
            CoordinateSystem::Xyza => f.write_str("xyza"),
            CoordinateSystem::Chain { offset, wcs, pcs } => {
                let mut parts = Vec::new();
                if offset {
                    parts.push("offset".to_string());
                }
                if let Some(n) = wcs {
                    parts.push(format!("wcs{n}"));
                }
                if pcs {
                    parts.push("pcs".to_string());
                }
                if parts.is_empty() {
                    f.write_str("mcs")
                } else {
                    f.write_str(&parts.join("|"))
                }
            }
        }
    }
}

impl std::str::FromStr for CoordinateSystem {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "mcs" => return Ok(CoordinateSystem::MCS),
            "rotary" => return Ok(CoordinateSystem::Rotary),
            "xyza" => return Ok(CoordinateSystem::Xyza),
            _ => {}
        }
        let (mut offset, mut wcs, mut pcs) = (false, None, false);
        let bad = || {
            format!(
                "coordinate system `{s}`: expected \"mcs\", \"rotary\", \"xyza\" or links \
                 \"offset\", \"wcs1\"…\"wcs15\", \"pcs\" joined by '|' (each once)"
            )
        };
        for part in s.split('|') {
            match part.trim() {
                "offset" if !offset => offset = true,
                "pcs" if !pcs => pcs = true,
                w => {
                    let n = w
                        .strip_prefix("wcs")
                        .and_then(|n| n.parse::<u8>().ok())
                        .ok_or_else(bad)?;
                    if wcs.replace(n).is_some() {
                        return Err(bad());
                    }
                }
            }
        }
        Ok(CoordinateSystem::Chain { offset, wcs, pcs })
    }
}

impl TryFrom<String> for CoordinateSystem {
    type Error = String;

    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

impl From<CoordinateSystem> for String {
    fn from(c: CoordinateSystem) -> String {
        c.to_string()
    }
}
