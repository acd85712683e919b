//! The axis parameter table (ARCHITECTURE §3.5): name, type, unit, default, range, access.
//!
//! One table drives validation, the control API, register maps and the dialects' Get/Set calls.
//! Every value is stored as `f64` (integers up to 2^53 and booleans as 0/1 are exact); the table's
//! [`Kind`] says how to read it. Defaults are the HMC defaults of digest 000 §2 where the HMC has
//! the parameter, and the other manuals' defaults otherwise; fixtures override them per machine.
//! Names are vendor-neutral snake_case; `aliases` hold the vendors' own names (HMC `Speed`, NMC
//! `estpDec`, HIMC `KillDec` …), matched case-insensitively.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::error::EngineError;
use crate::status::{AxisFlags, AxisStatus};

/// How to read a parameter's `f64`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    Real,
    /// An integer; non-integral values are refused.
    Int,
    /// 0 or 1.
    Bool,
    /// One of the listed codes.
    Enum(&'static [(i64, &'static str)]),
}

/// The unit a parameter is expressed in. User units are the axis's own (mm, deg, pulses …).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Unit {
    None,
    /// user units
    Position,
    /// user units/s
    Velocity,
    /// user units/s²
    Acceleration,
    /// user units/s³
    Jerk,
    Seconds,
    /// servo periods
    Ticks,
    Pulses,
    Counts,
    Percent,
    /// lines (pulses or counts) per user unit
    LinesPerUnit,
    /// DAC counts (±32767 = ±10 V on a direct analog axis)
    Dac,
    /// a controller gain
    Gain,
    /// a bit field
    Bits,
}

/// The values a parameter accepts (beyond its [`Kind`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    Any,
    /// ≥ the bound
    AtLeast(f64),
    /// > the bound
    Above(f64),
    /// within the closed interval
    Between(f64, f64),
    /// ≠ 0
    NonZero,
}

/// Who may write a parameter, and when.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamAccess {
    /// Any time; takes effect in the next tick, also during motion (HMC §3.5).
    ReadWrite,
    /// Only while the axis has no command in its FIFO (HMC setters such as HMC_SetAxisType).
    WriteWhenIdle,
    /// Only while the axis is disabled (HIMC SetRollover).
    WriteWhenDisabled,
    /// Computed by the engine; writes are refused.
    ReadOnly,
}

/// The HMC rule for bad writes to a few motion parameters (HMC §3.5.1–3.5.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lenient {
    /// No lenient form: bad values are always refused.
    No,
    /// Negative → absolute value; zero → the default. Both latch `PARAMETER_ERROR`.
    AbsOrDefault,
    /// Negative → absolute value (zero is valid).
    Abs,
}

/// One row of the table.
#[derive(Debug)]
pub struct ParamDef {
    pub id: ParamId,
    pub name: &'static str,
    pub aliases: &'static [&'static str],
    pub kind: Kind,
    pub unit: Unit,
    pub default: f64,
    pub range: Range,
    pub access: ParamAccess,
    pub lenient: Lenient,
    /// One line for the control API and the generated reference.
    pub doc: &'static str,
}

const AXIS_TYPES: &[(i64, &str)] = &[
    (-1, "unused"),
    (0, "virtual"),
    (10, "stepper"),
    (11, "stepper_cw_ccw"),
    (12, "stepper_ab"),
    (20, "servo_analog"),
    (30, "encoder"),
    (31, "encoder_pulse_dir"),
    (32, "encoder_cw_ccw"),
    (33, "encoder_ssi"),
    (40, "bus_position"),
    (41, "bus_velocity"),
    (42, "bus_torque"),
    (43, "bus_profile_position"),
    (50, "bus_position_ecat"),
    (51, "bus_velocity_ecat"),
    (52, "bus_torque_ecat"),
];
const REP_MODES: &[(i64, &str)] = &[
    (0, "finite"),
    (1, "cyclic_0_to_dist"),
    (2, "cyclic_symmetric"),
];
const MERGE_MODES: &[(i64, &str)] = &[
    (0, "off"),
    (1, "this_speed"),
    (2, "next_speed"),
    (3, "min_speed"),
    (4, "max_speed"),
];
const STOP_MODES: &[(i64, &str)] = &[(0, "command_position"), (1, "following_error")];
const MOVE_ABS_MODES: &[(i64, &str)] = &[
    (0, "no_wrap"),
    (1, "shortest"),
    (2, "positive"),
    (3, "negative"),
    (4, "current_direction"),
];
const CANCEL_MODES: &[(i64, &str)] = &[(0, "decelerate"), (1, "at_cancel_pos"), (2, "immediate")];
const LIMIT_MODES: &[(i64, &str)] = &[(0, "auto_cancel"), (1, "manual_cancel")];
const DATA_TYPES: &[(i64, &str)] = &[
    (0, "none"),
    (1, "usint"),
    (2, "sint"),
    (3, "uint"),
    (4, "int"),
    (5, "udint"),
    (6, "dint"),
    (7, "real"),
    (8, "lreal"),
];
const LIMIT_DECEL_MODES: &[(i64, &str)] = &[(0, "fast_decel"), (1, "max_of_fast_decel_and_decel")];
const OVERSHOOT_MODES: &[(i64, &str)] = &[(0, "reverse"), (1, "jump_to_zero_at_target")];

/// Value of `fh_limit_in`, `rh_limit_in` and `home_in` that selects the axis's own simulated switch.
pub const DEDICATED_INPUT: f64 = 64.0;

macro_rules! param_table {
    ($( $id:ident {
        $name:literal, [$($alias:literal),*], $kind:expr, $unit:expr, $default:expr, $range:expr,
        $access:expr, $lenient:expr, $doc:literal
    } )*) => {
        /// A parameter of the table. Serialized as its name.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        #[repr(u16)]
        pub enum ParamId { $($id),* }

        /// Number of rows, as a constant so parameter sets are plain arrays.
        const PARAM_COUNT: usize = [$(ParamId::$id),*].len();

        /// The table, indexed by `ParamId as usize`.
        pub static PARAMS: &[ParamDef] = &[
            $( ParamDef {
                id: ParamId::$id, name: $name, aliases: &[$($alias),*], kind: $kind, unit: $unit,
                default: $default, range: $range, access: $access, lenient: $lenient, doc: $doc,
            } ),*
        ];
    };
}

use Kind::{Bool, Enum, Int, Real};
use Lenient::{Abs, AbsOrDefault as AOD, No};
use ParamAccess::{ReadOnly as RO, ReadWrite as RW, WriteWhenDisabled as WD, WriteWhenIdle as WI};
use Range::{Above, Any, AtLeast, Between, NonZero};

param_table! {
    // ---- Basic (HMC §2.1) ----
    AxisType { "axis_type", ["AxisType"], Enum(AXIS_TYPES), Unit::None, 0.0, Any, WI, No,
        "axis type (HMC EmAxisType): decides the output stage and feedback" }
    Units { "units", ["Units"], Real, Unit::LinesPerUnit, 1.0, Above(0.0), WI, No,
        "lines (pulses/counts) per user unit; with Ks/Ke gives the output and feedback scales" }
    KsNumerator { "ks_numerator", ["KsNumerator"], Int, Unit::None, 1.0, NonZero, WI, No,
        "pulse output scale numerator: pulses = user units × units × Ks (same sign as denominator)" }
    KsDenominator { "ks_denominator", ["KsDenominator"], Int, Unit::None, 1.0, NonZero, WI, No,
        "pulse output scale denominator" }
    KeNumerator { "ke_numerator", ["KeNumerator"], Int, Unit::None, 1.0, NonZero, WI, No,
        "encoder scale numerator: position = counts × Ke / units (negative inverts)" }
    KeDenominator { "ke_denominator", ["KeDenominator"], Int, Unit::None, 1.0, NonZero, WI, No,
        "encoder scale denominator" }
    // ---- Status (HMC §2.2), computed ----
    CurrentCommand { "current_command", ["MCmdType"], Int, Unit::None, 0.0, Any, RO, No,
        "kind code of the running command (0 idle; CommandKind::code)" }
    NextCommand { "next_command", ["NCmdType"], Int, Unit::None, 0.0, Any, RO, No,
        "kind code of the next queued command (0 none)" }
    AxisStatusWord { "axis_status", ["AxisStatus"], Int, Unit::Bits, 0.0, Any, RO, No,
        "bit 0 FE fault, 1 FE warning, 2 parameter error, 3 limit, 4 bus error (HMC table 2)" }
    AxisErrMask { "axis_err_mask", ["AxisErrMask"], Int, Unit::Bits, 1.0, Between(0.0, 4294967295.0), RW, No,
        "axis_status bits that switch the drive off (HMC §3.3.4)" }
    LimitState { "limit_state", ["LimitState"], Int, Unit::Bits, 0.0, Any, RO, No,
        "bit 0 hw+, 1 hw−, 2 sw+, 3 sw−, 4 soft-limit parameter error, 5 both (HMC §3.3)" }
    // ---- Positions (HMC §2.3) ----
    ActualPosition { "actual_position", ["MPos", "encPos", "PosFb"], Real, Unit::Position, 0.0, Any, RO, No,
        "measured position" }
    CommandedPosition { "commanded_position", ["DPos", "prfPos", "RefPos"], Real, Unit::Position, 0.0, Any, RO, No,
        "commanded position from the planner" }
    FollowingError { "following_error", ["FE", "PosErr"], Real, Unit::Position, 0.0, Any, RO, No,
        "commanded − actual position" }
    StopFeTol { "stop_fe_tol", ["StopFETol"], Real, Unit::Position, 10.0, Above(0.0), RW, No,
        "|FE| window that completes a command when cmd_stop_mode = 1" }
    RepMode { "rep_mode", ["RepMode"], Enum(REP_MODES), Unit::None, 2.0, Any, RW, No,
        "0 finite travel (limits apply), 1 cyclic [0, rep_dist), 2 cyclic [−rep_dist, rep_dist)" }
    RepDist { "rep_dist", ["RepDist"], Real, Unit::Position, 1e10, Above(0.0), RW, No,
        "cyclic length" }
    Rollover { "rollover", ["Rollover"], Real, Unit::Position, 0.0, AtLeast(0.0), WD, No,
        "HIMC single-turn length; > 0 sets rep_mode 1 with rep_dist = value, 0 sets rep_mode 0" }
    TargetPosition { "target_position", ["EndPos"], Real, Unit::Position, 0.0, Any, RO, No,
        "target of the running command" }
    Remain { "remain", ["Remain"], Real, Unit::Position, 0.0, Any, RO, No,
        "target_position − commanded_position" }
    // ---- Velocity profile (HMC §2.4, NMC TPtpPara, HIMC §5.3, CPU 226H) ----
    Speed { "speed", ["Speed", "Vel", "maxVel", "MAX_SPEED"], Real, Unit::Velocity, 2000.0, AtLeast(0.0), RW, Abs,
        "profile velocity" }
    Accel { "accel", ["Accel", "Acc"], Real, Unit::Acceleration, 200000.0, Above(0.0), RW, AOD,
        "profile acceleration (|v| increasing)" }
    Decel { "decel", ["Decel", "Dec"], Real, Unit::Acceleration, 200000.0, Above(0.0), RW, AOD,
        "profile deceleration (|v| decreasing)" }
    ActualVelocity { "actual_velocity", ["MpSpeed", "VelFb"], Real, Unit::Velocity, 0.0, Any, RO, No,
        "measured velocity, signed" }
    CommandedSpeed { "commanded_speed", ["VpSpeed"], Real, Unit::Velocity, 0.0, Any, RO, No,
        "magnitude of the commanded velocity" }
    MotionDirection { "direction", ["Direction"], Int, Unit::None, 1.0, Any, RO, No,
        "+1 or −1: direction of the last commanded motion" }
    Merge { "merge", ["Merge"], Enum(MERGE_MODES), Unit::None, 0.0, Any, RW, No,
        "HMC merge (blending) mode; used by the multi-axis planner" }
    CreepSpeed { "creep_speed", ["CreepSpeed"], Real, Unit::Velocity, 200.0, AtLeast(0.0), RW, Abs,
        "HMC homing creep speed" }
    FastDecel { "fast_decel", ["FastDecel", "estpDec", "KillDec", "kill_decel"], Real, Unit::Acceleration, 5e6, Above(0.0), RW, AOD,
        "emergency deceleration: limit stops, abrupt and emergency stops" }
    Jerk { "jerk", ["Jerk"], Real, Unit::Jerk, 5e9, Above(0.0), RW, AOD,
        "jerk limit of the S-curve (jerk_mode = 1)" }
    JerkMode { "jerk_mode", ["JerkMode"], Bool, Unit::None, 0.0, Any, RW, No,
        "0 trapezoid, 1 jerk-limited S-curve" }
    SmoothTime { "smooth_time", ["smoothCoef", "SMTime"], Real, Unit::Seconds, 0.0, Between(0.0, 0.5), RW, No,
        "moving-average smoothing of the commanded velocity (NMC smoothCoef, HIMC SMTime)" }
    StartVelocity { "start_velocity", ["startVel", "MIN_SPEED"], Real, Unit::Velocity, 0.0, AtLeast(0.0), RW, No,
        "velocity a move jumps to at start (NMC startVel, CPU 226H MIN_SPEED)" }
    EndVelocity { "end_velocity", ["endVel"], Real, Unit::Velocity, 0.0, AtLeast(0.0), RW, No,
        "velocity at the target, from which the move ends with a jump to zero (NMC endVel)" }
    AccelTime { "accel_time", ["AccTime", "TA"], Real, Unit::Seconds, 0.0, AtLeast(0.0), RW, No,
        "> 0: accel = (speed − start_velocity)/accel_time, capped by max_accel (CPU 226H tip 3, HIMC SetAccTime)" }
    DecelTime { "decel_time", ["DecTime", "TD"], Real, Unit::Seconds, 0.0, AtLeast(0.0), RW, No,
        "> 0: decel = (speed − start_velocity)/decel_time, capped by max_accel" }
    MaxAccel { "max_accel", ["MC_SET_MAX_ACCELE", "maxAcc"], Real, Unit::Acceleration, 0.0, AtLeast(0.0), RW, No,
        "cap on acceleration and deceleration; 0 = none (CPU 226H MC_SET_MAX_ACCELE, NMC TSafePara.maxAcc)" }
    MaxVelocity { "max_velocity", ["safe_maxVel", "vel_lim"], Real, Unit::Velocity, 0.0, AtLeast(0.0), RW, No,
        "cap on commanded velocity, requests above are clamped; 0 = none (NMC TSafePara.maxVel)" }
    VelScale { "vel_scale", ["VelScale"], Real, Unit::Percent, 100.0, Between(0.0, 100.0), RW, No,
        "velocity override in percent of the programmed speed (HIMC SetVelScale)" }
    CmdStopMode { "cmd_stop_mode", ["CmdStopMode"], Enum(STOP_MODES), Unit::None, 0.0, Any, RW, No,
        "0 a command is done when the commanded position arrives; 1 also waits for |FE| < stop_fe_tol" }
    CmdStopMaxTime { "cmd_stop_max_time", ["CmdStopMaxTime"], Real, Unit::Seconds, 0.5, AtLeast(0.0), RW, No,
        "longest extra wait of cmd_stop_mode 1 (HMC_SetCmdStopMaxTime, 500 ms)" }
    MoveAbsMode { "move_abs_mode", ["MoveAbsMode"], Enum(MOVE_ABS_MODES), Unit::None, 0.0, Any, RW, No,
        "direction of absolute moves on cyclic axes" }
    CancelMode { "cancel_mode", ["CancelMode"], Enum(CANCEL_MODES), Unit::None, 0.0, Any, RW, No,
        "how cancel stops: decelerate, at cancel_pos (cyclic jog), immediate (linked commands)" }
    CancelPos { "cancel_pos", ["CancelPos"], Real, Unit::Position, 0.0, Any, RW, No,
        "stop position for cancel_mode 1" }
    OvershootMode { "overshoot_mode", [], Enum(OVERSHOOT_MODES), Unit::None, 0.0, Any, RW, No,
        "when a target can no longer be reached without overshoot: 0 reverse onto it; 1 keep decelerating and jump to zero at the target (HMC §2.3.1)" }
    // ---- Gains (HMC §2.5) ----
    Kp { "kp", ["Kp"], Real, Unit::Gain, 1.0, Any, RW, No, "proportional gain (DAC counts per user unit of FE)" }
    Ki { "ki", ["Ki"], Real, Unit::Gain, 0.0, Any, RW, No, "integral gain" }
    Kd { "kd", ["Kd"], Real, Unit::Gain, 0.0, Any, RW, No, "derivative gain" }
    Kov { "kov", ["Kov"], Real, Unit::Gain, 0.0, Any, RW, No, "measured-velocity gain (subtracted)" }
    Kvff { "kvff", ["Kvff"], Real, Unit::Gain, 0.0, Any, RW, No, "velocity feed-forward" }
    Kaff { "kaff", ["Kaff"], Real, Unit::Gain, 0.0, Any, RW, No, "acceleration feed-forward" }
    Ko { "ko", ["Ko"], Real, Unit::Gain, 1.0, Any, RW, No, "output scale of the loop" }
    // ---- Limits (HMC §2.6, NMC §3.2, HIMC §5.3) ----
    FeLimit { "fe_limit", ["FELimit", "FELimits", "PosErrLmt", "max_pos_err"], Real, Unit::Position, 1000.0, AtLeast(0.0), RW, No,
        "following-error limit; 0 disables the check (NMC)" }
    CompensationLimit { "compensation_limit", ["max_comp_lim"], Real, Unit::Position, 0.0, AtLeast(0.0), RW, No,
        "largest |compensation| the axis may output; over it COMPENSATION_LIMIT stops the axis; 0 unlimited (HIMC max_comp_lim, 1 mm)" }
    FeFaultCycles { "fe_fault_cycles", [], Int, Unit::Ticks, 10.0, Between(1.0, 1e9), RW, No,
        "consecutive ticks over fe_limit that latch FE_FAULT (HMC: 10)" }
    FeWarningClearCycles { "fe_warning_clear_cycles", [], Int, Unit::Ticks, 1000.0, Between(1.0, 1e9), RW, No,
        "consecutive ticks within fe_limit that clear FE_WARNING (HMC: 1000)" }
    FeAction { "fe_action", ["posErrAction"], Int, Unit::Bits, 0.0, Between(0.0, 3.0), RW, No,
        "on FE fault: bit 0 disable the drive, bit 1 stop the axis (NMC_MtSetPosErrAction); axis_err_mask also applies" }
    IgnoreFe { "ignore_fe", ["IgnorePE"], Bool, Unit::None, 0.0, Any, RW, No,
        "1: FE faults are flagged but have no reaction (HIMC IgnorePE)" }
    FsLimitMode { "fs_limit_mode", ["FsLimitMode"], Enum(LIMIT_MODES), Unit::None, 0.0, Between(0.0, 0.0), RW, No,
        "0 auto-cancel on the positive limit; 1 (manual) is not supported by the HMC either" }
    RsLimitMode { "rs_limit_mode", ["RsLimitMode"], Enum(LIMIT_MODES), Unit::None, 0.0, Between(0.0, 0.0), RW, No,
        "0 auto-cancel on the negative limit" }
    FhLimitIn { "fh_limit_in", ["FHLimitIn"], Int, Unit::None, DEDICATED_INPUT, Between(-1.0, 64.0), RW, No,
        "positive hard limit input: −1 none, 0–63 a DI channel, 64 the axis's own switch" }
    RhLimitIn { "rh_limit_in", ["RHLimitIn"], Int, Unit::None, DEDICATED_INPUT, Between(-1.0, 64.0), RW, No,
        "negative hard limit input: −1 none, 0–63 a DI channel, 64 the axis's own switch" }
    LimitPosInvert { "limit_pos_invert", [], Bool, Unit::None, 0.0, Any, RW, No,
        "1: the positive limit is active low" }
    LimitNegInvert { "limit_neg_invert", [], Bool, Unit::None, 0.0, Any, RW, No,
        "1: the negative limit is active low" }
    IgnoreHwLimits { "ignore_hw_limits", ["IgnoreHWL"], Bool, Unit::None, 0.0, Any, RW, No,
        "1: hard limits are reported but do not stop or block motion (HIMC IgnoreHWL)" }
    FsLimit { "fs_limit", ["FSLimit", "SWRL", "posLmt"], Real, Unit::Position, 1e100, Any, RW, No,
        "positive soft limit on the commanded position" }
    RsLimit { "rs_limit", ["RSLimit", "SWLL", "negLmt"], Real, Unit::Position, -1e100, Any, RW, No,
        "negative soft limit on the commanded position" }
    IgnoreSwLimits { "ignore_sw_limits", ["IgnoreSWL"], Bool, Unit::None, 0.0, Any, RW, No,
        "1: soft limits off (HIMC IgnoreSWL; NMC_MtSwLmtOnOff(0))" }
    SwLimitRejectTargets { "sw_limit_reject_targets", [], Bool, Unit::None, 0.0, Any, RW, No,
        "1: refuse position moves whose target lies beyond a soft limit (HIMC eERR_AXIS_CMD_INVALID_POS)" }
    LimitLatch { "limit_latch", [], Bool, Unit::None, 0.0, Any, RW, No,
        "1: limit flags stay set until a reset after the input clears (NMC); 0: they follow the input (HMC)" }
    LimitDecelMode { "limit_decel_mode", [], Enum(LIMIT_DECEL_MODES), Unit::None, 1.0, Any, RW, No,
        "deceleration of a limit stop: fast_decel, or max(fast_decel, decel) (HMC §3.3.5)" }
    DacLimitHigh { "dac_limit_high", ["DACLimitHigh"], Int, Unit::Dac, 32767.0, Between(-2147483648.0, 2147483647.0), RW, No,
        "upper clamp of the servo output" }
    DacLimitLow { "dac_limit_low", ["DACLimitLow"], Int, Unit::Dac, -32768.0, Between(-2147483648.0, 2147483647.0), RW, No,
        "lower clamp of the servo output" }
    DriveAlarmEnable { "drive_alarm_enable", ["alarmEnable"], Bool, Unit::None, 1.0, Any, RW, No,
        "1: the drive alarm input faults the axis (NMC default is 0)" }
    DriveAlarmInvert { "drive_alarm_invert", [], Bool, Unit::None, 0.0, Any, RW, No,
        "1: the alarm input is active low" }
    // ---- In position (NMC arrival band, HIMC pos window) ----
    InPositionWindow { "in_position_window", ["arrivalBand", "PosWindow", "pos_tr"], Real, Unit::Position, 0.0, AtLeast(0.0), RW, No,
        "|FE| window for IN_POSITION" }
    InPositionTime { "in_position_time", ["stableTime", "PosWindowTime", "pos_tr_t"], Real, Unit::Seconds, 0.0, AtLeast(0.0), RW, No,
        "time |FE| must stay in the window" }
    // ---- Home & hold (HMC §2.7, HIMC ch. 20) ----
    HomeState { "home_state", ["HomeState"], Int, Unit::None, 0.0, Any, RO, No,
        "homing phase, 0 idle" }
    HomeIn { "home_in", ["HomeIn"], Int, Unit::None, DEDICATED_INPUT, Between(-1.0, 64.0), RW, No,
        "home switch input: −1 none, 0–63 a DI channel, 64 the axis's own switch" }
    HomeInvert { "home_invert", [], Bool, Unit::None, 0.0, Any, RW, No,
        "1: the home switch is active low" }
    HomeCapIn { "home_cap_in", ["HomeCapIn"], Int, Unit::None, -1.0, Any, RO, No,
        "capture channel of HMC_HomeEx, −1 none" }
    HoldSpeed { "hold_speed", ["HoldSpeed"], Real, Unit::Velocity, 0.0, AtLeast(0.0), RW, No,
        "speed while the hold input is on (HMC_HoldConfig)" }
    HoldIn { "hold_in", ["HoldIn"], Int, Unit::None, -1.0, Between(-1.0, 63.0), RW, No,
        "hold input DI channel, −1 off" }
    HomeMethod { "home_method", ["home_method"], Int, Unit::None, 33.0, Between(-128.0, 37.0), RW, No,
        "CiA 402 homing method used when a home command names none (HIMC default 33)" }
    HomeSwitchVelocity { "home_switch_velocity", ["home_fast_vel", "HomeSwitchVel"], Real, Unit::Velocity, 20.0, Above(0.0), RW, No,
        "speed while searching for a switch (CiA 402 0x6099:01)" }
    HomeZeroVelocity { "home_zero_velocity", ["home_slow_vel", "HomeZeroVel"], Real, Unit::Velocity, 5.0, Above(0.0), RW, No,
        "speed while searching for the zero (CiA 402 0x6099:02)" }
    HomeAcceleration { "home_acceleration", ["home_acc", "HomeAcc"], Real, Unit::Acceleration, 2000.0, Above(0.0), RW, No,
        "homing acceleration (CiA 402 0x609A)" }
    HomeOffset { "home_offset", ["HomeOffset"], Real, Unit::Position, 0.0, Any, RW, No,
        "position of the home point after homing (CiA 402 0x607C)" }
    HomeTimeout { "home_timeout", ["HomeTimeout"], Real, Unit::Seconds, 120.0, AtLeast(0.0), RW, No,
        "homing gives up after this long; 0 = never" }
    // ---- Input (HMC §2.8) ----
    EncoderValue { "encoder_value", ["EncoderValue"], Int, Unit::Counts, 0.0, Any, RO, No,
        "encoder counter" }
    FeedbackSrcMode { "feedback_src_mode", ["FeedBackSrcMode"], Enum(&[(0, "physical"), (1, "user")]), Unit::None, 0.0, Any, RW, No,
        "0 encoder feedback, 1 a user source" }
    FeedbackSrcValue { "feedback_src_value", ["FeedBackSrcValue"], Real, Unit::None, 0.0, Any, RO, No,
        "live value of the user feedback source" }
    FeedbackDataType { "feedback_data_type", ["FeedBackDataType"], Enum(DATA_TYPES), Unit::None, 0.0, Any, RO, No,
        "data type of the user feedback source" }
    // ---- Output (HMC §2.9) ----
    PulseNum { "pulse_num", ["PulseNum"], Int, Unit::Pulses, 0.0, Any, RO, No,
        "pulses output in the last servo period" }
    ServoLoop { "servo_loop", ["ServoLoop"], Bool, Unit::None, 0.0, Any, RW, No,
        "closed-loop types: 1 close the position loop, 0 output `dac` and let DPos track MPos" }
    Dac { "dac", ["DAC"], Int, Unit::Dac, 0.0, Between(-2147483648.0, 2147483647.0), RW, No,
        "servo output while servo_loop = 0" }
    DacOut { "dac_out", ["DACOut"], Int, Unit::Dac, 0.0, Any, RO, No,
        "servo output" }
    PosOffset { "pos_offset", ["PosOffset"], Int, Unit::Dac, 0.0, Between(-2147483648.0, 2147483647.0), RW, No,
        "added to a positive servo output (dead band)" }
    NegOffset { "neg_offset", ["NegOffset"], Int, Unit::Dac, 0.0, Between(-2147483648.0, 2147483647.0), RW, No,
        "added to a negative servo output (dead band)" }
    ZeroWindow { "zero_window", ["ZeroWindow"], Int, Unit::Dac, 0.0, Between(0.0, 2147483647.0), RW, No,
        "outputs within ±zero_window become (pos_offset + neg_offset)/2" }
    OutDstMode { "out_dst_mode", ["OutDstMode"], Enum(&[(0, "physical"), (1, "user")]), Unit::None, 0.0, Any, RW, No,
        "0 drive the output, 1 write a user variable" }
    OutDstValue { "out_dst_value", ["OutDstValue"], Real, Unit::None, 0.0, Any, RO, No,
        "live value of the user output target" }
    OutDstDataType { "out_dst_data_type", ["OutDstDataType"], Enum(DATA_TYPES), Unit::None, 0.0, Any, RO, No,
        "data type of the user output target" }
    // ---- Motor (HIMC §5.2.7 MoveTrq, §5.3.26 GetCurrFb) ----
    RatedTorque { "rated_torque", [], Real, Unit::None, 1.27, Above(0.0), RW, No,
        "motor rated (continuous) torque, N·m: a torque setpoint of 1.0 is this (HIMC MoveTrq)" }
    RatedCurrent { "rated_current", [], Real, Unit::None, 2.6, Above(0.0), RW, No,
        "motor current at rated torque, A (HIMC GetCurrFb)" }
    // ---- Reserved (HMC §2.10) ----
    SystemValue0 { "system_value0", ["SystemValue0"], Int, Unit::None, 0.0, Any, RO, No, "diagnostic value (HMC §1.4)" }
    SystemValue1 { "system_value1", ["SystemValue1"], Int, Unit::None, 0.0, Any, RO, No, "diagnostic value (HMC §1.4)" }
    SystemValue2 { "system_value2", ["SystemValue2"], Real, Unit::None, 0.0, Any, RO, No, "diagnostic value" }
    SystemValue3 { "system_value3", ["SystemValue3"], Real, Unit::None, 0.0, Any, RO, No, "diagnostic value" }
}

impl ParamId {
    pub const COUNT: usize = PARAM_COUNT;

    pub fn def(self) -> &'static ParamDef {
        // The table is built from the enum by one macro, so every id has its row.
        &PARAMS[self as usize]
    }

    pub fn name(self) -> &'static str {
        self.def().name
    }

    /// Look a parameter up by name or alias, ignoring case.
    pub fn from_name(name: &str) -> Option<ParamId> {
        PARAMS
            .iter()
            .find(|d| {
                d.name.eq_ignore_ascii_case(name)
                    || d.aliases.iter().any(|a| a.eq_ignore_ascii_case(name))
            })
            .map(|d| d.id)
    }

    pub fn all() -> impl Iterator<Item = ParamId> {
        PARAMS.iter().map(|d| d.id)
    }
}

impl std::fmt::Display for ParamId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl Serialize for ParamId {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for ParamId {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = std::borrow::Cow::<str>::deserialize(d)?;
        ParamId::from_name(&name)
            .ok_or_else(|| serde::de::Error::custom(format!("unknown parameter `{name}`")))
    }
}

impl ParamDef {
    /// Check a value against kind and range. Returns the value to store.
    pub fn validate(&self, value: f64) -> Result<f64, EngineError> {
        let refuse = |reason: String| EngineError::InvalidParameter {
            name: self.name,
            value,
            reason,
        };
        if value.is_nan() {
            return Err(refuse("not a number".into()));
        }
        // "No limit" is spelled with a huge finite value (HMC soft limits: ±1e100).
        if value.is_infinite() {
            return Err(refuse("must be finite".into()));
        }
        match self.kind {
            Kind::Real => {}
            Kind::Int => {
                if value.fract() != 0.0 {
                    return Err(refuse("must be an integer".into()));
                }
            }
            Kind::Bool => {
                if value != 0.0 && value != 1.0 {
                    return Err(refuse("must be 0 or 1".into()));
                }
            }
            Kind::Enum(values) => {
                if !values.iter().any(|(code, _)| *code as f64 == value) {
                    let list: Vec<String> = values
                        .iter()
                        .map(|(code, name)| format!("{code} ({name})"))
                        .collect();
                    return Err(refuse(format!("must be one of {}", list.join(", "))));
                }
            }
        }
        match self.range {
            Range::Any => {}
            Range::AtLeast(min) if value < min => {
                return Err(refuse(format!("must be at least {min}")))
            }
            Range::Above(min) if value <= min => {
                return Err(refuse(format!("must be greater than {min}")))
            }
            Range::Between(min, max) if value < min || value > max => {
                return Err(refuse(if min == max {
                    format!("only {min} is supported")
                } else {
                    format!("must be between {min} and {max}")
                }))
            }
            Range::NonZero if value == 0.0 => return Err(refuse("must not be zero".into())),
            _ => {}
        }
        Ok(value)
    }

    /// Apply the HMC rule for bad values (HMC §3.5.1–3.5.3): returns the value to store and
    /// whether it was corrected (which latches `PARAMETER_ERROR`).
    pub fn lenient(&self, value: f64) -> Result<(f64, bool), EngineError> {
        match self.lenient {
            Lenient::AbsOrDefault if value == 0.0 => Ok((self.default, true)),
            Lenient::AbsOrDefault | Lenient::Abs if value < 0.0 => {
                Ok((self.validate(-value)?, true))
            }
            _ => Ok((self.validate(value)?, false)),
        }
    }
}

/// The values of one axis's parameters, indexed by `ParamId`. A fixed array: every id is in
/// range by construction, so a read is one load (this runs dozens of times per tick per axis).
#[derive(Clone, Debug, PartialEq)]
pub struct ParamSet {
    values: [f64; PARAM_COUNT],
}

impl Default for ParamSet {
    fn default() -> Self {
        let mut values = [0.0; PARAM_COUNT];
        for (v, d) in values.iter_mut().zip(PARAMS) {
            *v = d.default;
        }
        ParamSet { values }
    }
}

impl ParamSet {
    #[inline]
    pub fn get(&self, id: ParamId) -> f64 {
        self.values[id as usize]
    }

    #[inline]
    pub fn flag(&self, id: ParamId) -> bool {
        self.get(id) != 0.0
    }

    /// Store a value that has already been validated.
    #[inline]
    #[allow(dead_code)] // used by the axis core
    pub(crate) fn set_unchecked(&mut self, id: ParamId, value: f64) {
        self.values[id as usize] = value;
    }
}

/// The value `GetParameter` reads: the stored value, or for the live read-only parameters
/// (positions, status words, FIFO contents …) the value derived from the axis status. A pure
/// function of the two, so front-ends compute it from a snapshot exactly as the engine does.
pub fn parameter_value(id: ParamId, status: &AxisStatus, params: &ParamSet) -> f64 {
    let s = status;
    match id {
        ParamId::CurrentCommand => s.current_command.map_or(0, |c| c.kind.code()) as f64,
        ParamId::NextCommand => s.next_command.map_or(0, |c| c.kind.code()) as f64,
        ParamId::AxisStatusWord => axis_status_word(s.flags) as f64,
        ParamId::LimitState => limit_state_word(s.flags) as f64,
        ParamId::ActualPosition => s.act_pos,
        ParamId::CommandedPosition => s.cmd_pos,
        ParamId::FollowingError => s.following_error,
        ParamId::TargetPosition => s.target_pos,
        ParamId::Remain => s.remaining,
        ParamId::ActualVelocity => s.act_vel,
        ParamId::CommandedSpeed => s.cmd_vel.abs(),
        ParamId::MotionDirection => f64::from(s.motion_direction),
        ParamId::HomeState => f64::from(s.homing_phase),
        ParamId::EncoderValue => s.encoder_counts as f64,
        ParamId::PulseNum => f64::from(s.pulses_last_tick),
        ParamId::DacOut => s.dac_out.round(),
        _ => params.get(id),
    }
}

/// The flags [`axis_status_word`] reads: without any of them the word is 0.
pub const AXIS_STATUS_WORD_FLAGS: AxisFlags = AxisFlags::FE_FAULT
    .union(AxisFlags::FE_WARNING)
    .union(AxisFlags::PARAMETER_ERROR)
    .union(AxisFlags::HW_LIMIT_POS)
    .union(AxisFlags::HW_LIMIT_NEG)
    .union(AxisFlags::SW_LIMIT_POS)
    .union(AxisFlags::SW_LIMIT_NEG);

/// The value of the `AxisStatus` parameter: the HMC-layout axis status word (HMC §3.3 table 2,
/// digest 000 §2.2), which `AxisErrMask` masks (supervision). Front-ends name it
/// `mcemu_dialects::hmc::axis_status`.
pub fn axis_status_word(flags: AxisFlags) -> u32 {
    let mut w = 0;
    if flags.contains(AxisFlags::FE_FAULT) {
        w |= 1;
    }
    if flags.contains(AxisFlags::FE_WARNING) {
        w |= 2;
    }
    if flags.contains(AxisFlags::PARAMETER_ERROR) {
        w |= 4;
    }
    if flags.intersects(
        AxisFlags::HW_LIMIT_POS
            | AxisFlags::HW_LIMIT_NEG
            | AxisFlags::SW_LIMIT_POS
            | AxisFlags::SW_LIMIT_NEG,
    ) {
        w |= 8;
    }
    w
}

/// The value of the `LimitState` parameter: the HMC-layout limit state (HMC §3.3, digest 000
/// §2.2).
pub fn limit_state_word(flags: AxisFlags) -> u32 {
    let mut w = 0;
    for (flag, bit) in [
        (AxisFlags::HW_LIMIT_POS, 1),
        (AxisFlags::HW_LIMIT_NEG, 2),
        (AxisFlags::SW_LIMIT_POS, 4),
        (AxisFlags::SW_LIMIT_NEG, 8),
        (AxisFlags::SW_LIMIT_CONFIG, 16),
        (AxisFlags::BOTH_LIMITS, 32),
    ] {
        if flags.contains(flag) {
            w |= bit;
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_rows_match_their_ids_and_names_are_unique() {
        assert_eq!(PARAMS.len(), ParamId::COUNT);
        for (i, def) in PARAMS.iter().enumerate() {
            assert_eq!(def.id as usize, i);
            assert!(
                def.validate(def.default).is_ok() || def.access == ParamAccess::ReadOnly,
                "default of {} is outside its own range",
                def.name
            );
        }
        // An alias may repeat its own row's name in vendor case; across rows names are unique.
        let mut names: Vec<String> = PARAMS
            .iter()
            .flat_map(|d| {
                let mut own: Vec<String> = std::iter::once(d.name)
                    .chain(d.aliases.iter().copied())
                    .map(|n| n.to_ascii_lowercase())
                    .collect();
                own.sort();
                own.dedup();
                own
            })
            .collect();
        let before = names.len();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), before, "a name or alias is used twice");
    }

    #[test]
    fn lookup_by_vendor_alias_ignores_case() {
        assert_eq!(ParamId::from_name("Speed"), Some(ParamId::Speed));
        assert_eq!(ParamId::from_name("FELIMITS"), Some(ParamId::FeLimit));
        assert_eq!(ParamId::from_name("estpDec"), Some(ParamId::FastDecel));
        assert_eq!(ParamId::from_name("no_such_thing"), None);
    }

    #[test]
    fn hmc_defaults_are_the_manual_ones() {
        // Digest 000 §2.4–2.6.
        let p = ParamSet::default();
        assert_eq!(p.get(ParamId::Speed), 2000.0);
        assert_eq!(p.get(ParamId::Accel), 200_000.0);
        assert_eq!(p.get(ParamId::Decel), 200_000.0);
        assert_eq!(p.get(ParamId::CreepSpeed), 200.0);
        assert_eq!(p.get(ParamId::FastDecel), 5e6);
        assert_eq!(p.get(ParamId::Jerk), 5e9);
        assert_eq!(p.get(ParamId::FeLimit), 1000.0);
        assert_eq!(p.get(ParamId::StopFeTol), 10.0);
        assert_eq!(p.get(ParamId::RepMode), 2.0);
        assert_eq!(p.get(ParamId::RepDist), 1e10);
        assert_eq!(p.get(ParamId::AxisErrMask), 1.0);
        assert_eq!(p.get(ParamId::Kp), 1.0);
        assert_eq!(p.get(ParamId::Ko), 1.0);
        assert_eq!(p.get(ParamId::DacLimitHigh), 32767.0);
        assert_eq!(p.get(ParamId::DacLimitLow), -32768.0);
    }

    #[test]
    fn bad_values_are_refused_with_name_value_and_reason() {
        let err = ParamId::Accel.def().validate(-5.0).unwrap_err();
        match err {
            EngineError::InvalidParameter {
                name,
                value,
                reason,
            } => {
                assert_eq!(name, "accel");
                assert_eq!(value, -5.0);
                assert!(reason.contains("greater than 0"), "{reason}");
            }
            other => panic!("unexpected {other:?}"),
        }
        assert!(ParamId::Speed.def().validate(f64::NAN).is_err());
        assert!(ParamId::Speed.def().validate(f64::INFINITY).is_err());
        assert!(ParamId::JerkMode.def().validate(2.0).is_err());
        assert!(ParamId::RepMode.def().validate(3.0).is_err());
        assert!(ParamId::KsNumerator.def().validate(1.5).is_err());
        assert!(ParamId::KsNumerator.def().validate(0.0).is_err());
        assert!(ParamId::FsLimitMode.def().validate(1.0).is_err());
    }

    #[test]
    fn hmc_lenient_rule() {
        // HMC §3.5.1: Speed := −500 reads 500 with bit 2; Accel := 0 reads the default.
        assert_eq!(ParamId::Speed.def().lenient(-500.0).unwrap(), (500.0, true));
        assert_eq!(
            ParamId::Accel.def().lenient(0.0).unwrap(),
            (200_000.0, true)
        );
        assert_eq!(ParamId::Accel.def().lenient(10.0).unwrap(), (10.0, false));
        assert!(ParamId::Kp.def().lenient(f64::NAN).is_err());
    }

    #[test]
    fn serde_uses_names_and_aliases() {
        let id: ParamId = serde_json::from_str("\"FastDecel\"").unwrap();
        assert_eq!(id, ParamId::FastDecel);
        assert_eq!(serde_json::to_string(&id).unwrap(), "\"fast_decel\"");
        assert!(serde_json::from_str::<ParamId>("\"bogus\"").is_err());
    }
}
