//! HIWIN HIMC (digest 004): the `Is*` axis predicates, the 0xCCNNVVVV axis error codes, and the
//! HMPL units (mm or deg, ms); [`group`]: the group motion profiles' ranges and errors.

use axes::command::{EngineError, ErrorKind};
use axes::error::StreamPointProblem;
use axes::param::{ParamId, Unit};
use axes::{AxisFlags, AxisState, AxisStatus};

pub mod constants;
pub mod engine_error;
pub mod group;
pub mod group_errors;
pub mod system;

/// An axis status function of HMPL chapter 5.4, `int Is…(int axis_id)` (digest 004 §2.4 "5.4
/// Axis status").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Predicate {
    IsEnabled,
    IsMoving,
    IsInPos,
    IsErrorStop,
    IsGantry,
    IsGrouped,
    IsSync,
    IsHWLL,
    IsHWRL,
    IsSWLL,
    IsSWRL,
    IsDriveErr,
    IsPosErr,
    IsCompActive,
    IsAcc,
}

/// What the `Is*` functions show that [`AxisStatus`] does not carry: modes the engine does not
/// model yet, set by the caller from its own configuration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AxisExtra {
    /// The axis is in gantry mode (`IsGantry`, §5.4.5).
    pub gantry: bool,
    /// Dynamic error compensation is enabled (`IsCompActive`, §5.4.14).
    pub compensation: bool,
}

impl Predicate {
    /// Every predicate with its HMPL name, in manual order (§5.4.1 … §5.4.15).
    pub const ALL: [(Predicate, &'static str); 15] = [
        (Predicate::IsEnabled, "IsEnabled"),
        (Predicate::IsMoving, "IsMoving"),
        (Predicate::IsInPos, "IsInPos"),
        (Predicate::IsErrorStop, "IsErrorStop"),
        (Predicate::IsGantry, "IsGantry"),
        (Predicate::IsGrouped, "IsGrouped"),
        (Predicate::IsSync, "IsSync"),
        (Predicate::IsHWLL, "IsHWLL"),
        (Predicate::IsHWRL, "IsHWRL"),
        (Predicate::IsSWLL, "IsSWLL"),
        (Predicate::IsSWRL, "IsSWRL"),
        (Predicate::IsDriveErr, "IsDriveErr"),
        (Predicate::IsPosErr, "IsPosErr"),
        (Predicate::IsCompActive, "IsCompActive"),
        (Predicate::IsAcc, "IsAcc"),
    ];

    /// The predicate an HMPL call names (`IsMoving` …), exactly as the manual spells it.
    pub fn by_name(name: &str) -> Option<Predicate> {
        Self::ALL.iter().find(|(_, n)| *n == name).map(|(p, _)| *p)
    }

    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(p, _)| *p == self)
            .map_or("", |(_, n)| n)
    }

    /// Whether the predicate holds (the function returns TRUE). Left is the negative
    /// direction, right the positive (§5.4.8: 0x60FD bit 0 = left = negative limit switch).
    pub fn holds(self, s: &AxisStatus, extra: AxisExtra) -> bool {
        let f = s.flags;
        match self {
            Predicate::IsEnabled => f.contains(AxisFlags::ENABLED),
            Predicate::IsMoving => f.contains(AxisFlags::MOVING),
            Predicate::IsInPos => f.contains(AxisFlags::IN_POSITION),
            Predicate::IsErrorStop => s.state == AxisState::ErrorStop,
            Predicate::IsGantry => extra.gantry,
            Predicate::IsGrouped => f.contains(AxisFlags::IN_GROUP),
            Predicate::IsSync => s.state == AxisState::SynchronizedMotion,
            Predicate::IsHWLL => f.contains(AxisFlags::HW_LIMIT_NEG),
            Predicate::IsHWRL => f.contains(AxisFlags::HW_LIMIT_POS),
            Predicate::IsSWLL => f.contains(AxisFlags::SW_LIMIT_NEG),
            Predicate::IsSWRL => f.contains(AxisFlags::SW_LIMIT_POS),
            Predicate::IsDriveErr => f.contains(AxisFlags::DRIVE_ALARM),
            Predicate::IsPosErr => f.contains(AxisFlags::FE_FAULT),
            Predicate::IsCompActive => extra.compensation,
            Predicate::IsAcc => f.contains(AxisFlags::ACCELERATING),
        }
    }
}

/// The class byte CC of an axis error code 0xCCNNVVVV (digest 004 §5).
pub const AXIS_CLASS: u8 = 0x83;
/// The class byte of a group error code.
pub const GROUP_CLASS: u8 = 0x82;

/// The full code `CC << 24 | NN << 16 | VVVV` of an error `value` of axis or group `id` in
/// `class` (digest 004 §5: axis 2's 0x07da is 0x830207da). Functions return it as an `int`,
/// so axis and group codes read negative (`as i32`).
pub const fn compose(class: u8, id: u8, value: u16) -> u32 {
    (class as u32) << 24 | (id as u32) << 16 | value as u32
}

/// One row of the axis error table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AxisError {
    /// VVVV, the low word of the code.
    pub value: u16,
    /// The manual's name, verbatim (typos included: `eERR_AXIS_CMD_UNKOWN`).
    pub name: &'static str,
    /// Its meaning, in English (digest 004 §5.2).
    pub meaning: &'static str,
}

impl AxisError {
    /// The row called `name`.
    pub fn by_name(name: &str) -> Option<&'static AxisError> {
        AXIS_ERRORS.iter().find(|e| e.name == name)
    }

    /// The row with low word `value`.
    pub fn by_value(value: u16) -> Option<&'static AxisError> {
        AXIS_ERRORS.iter().find(|e| e.value == value)
    }

    /// This error of axis `axis` as the functions return it: 0x83NNVVVV.
    pub const fn code(&self, axis: u8) -> u32 {
        compose(AXIS_CLASS, axis, self.value)
    }
}

macro_rules! axis_errors {
    ($(($value:literal, $name:literal, $meaning:literal),)*) => {
        /// The axis errors, Table 18.1.2.1 (digest 004 §5.2), in the manual's order.
        pub const AXIS_ERRORS: &[AxisError] = &[
            $(AxisError { value: $value, name: $name, meaning: $meaning },)*
        ];
    };
}

axis_errors! {
    (0x000a, "eERR_AXIS_CMD_UNKOWN", "Unknown command name."),
    (0x001e, "eERR_AXIS_CMD_QUEUE_FULL", "Axis command queue full."),
    (0x0050, "eERR_AXIS_CMD_INVALID_IN_SIM", "Command not usable on the virtual machine (simulator)."),
    (0x0060, "eERR_AXIS_CMD_INVALID_IN_VIRTUAL", "Command not usable on a virtual axis."),
    (0x0064, "eERR_AXIS_CMD_INVALID_STATE", "Axis cannot execute this command in its current state."),
    (0x006e, "eERR_AXIS_CMD_INVALID_ENABLED", "Command not usable while axis is enabled."),
    (0x0078, "eERR_AXIS_CMD_INVALID_DISABLED", "Command not usable while axis is disabled."),
    (0x0082, "eERR_AXIS_CMD_INVALID_MOVING", "Command cannot execute while axis is moving."),
    (0x008c, "eERR_AXIS_CMD_INVALID_STOPPING", "Command cannot execute while axis is stopping."),
    (0x0096, "eERR_AXIS_CMD_INVALID_ERROR_STATE", "Command cannot execute while axis is in error."),
    (0x00a0, "eERR_AXIS_CMD_INVALID_IN_SYNC", "Command invalid while axis is in synchronous motion."),
    (0x00aa, "eERR_AXIS_CMD_INVALID_GEAR_MASTER", "Command invalid while axis is an electronic-gear master."),
    (0x00b4, "eERR_AXIS_CMD_INVALID_PP_MODE", "Command invalid while axis is in PP mode."),
    (0x00be, "eERR_AXIS_CMD_INVALID_MAP_SWITCHING", "Command invalid while axis is switching compensation map."),
    (0x00c8, "eERR_AXIS_CMD_INVALID_INPUTSHAPING_ENABLED", "Command invalid while axis position-command shaping (input shaping) is enabled."),
    (0x00d2, "eERR_AXIS_CMD_INVALID_COMP_ENABLED", "Command invalid while dynamic compensation is enabled."),
    (0x00dc, "eERR_AXIS_CMD_INVALID_GANTRY_MODE", "Command invalid while axis is in gantry mode."),
    (0x00e6, "eERR_AXIS_CMD_INVALID_GROUPED", "Command invalid if axis is already in a group."),
    (0x00f0, "eERR_AXIS_CMD_INVALID_CONTROL_MODE", "Command invalid in the current control mode."),
    (0x00fa, "eERR_AXIS_CMD_INVALID_OP_MODE", "Operation mode invalid."),
    (0x0104, "eERR_AXIS_CMD_INVALID_BUFFER_MODE", "Axis buffer mode invalid."),
    (0x0105, "eERR_AXIS_CMD_INVALID_SETBUFFERMODE", "Cannot use this command while axis has unfinished commands."),
    (0x010e, "eERR_AXIS_CMD_INVALID_TP_ENABLED", "Cannot use this command while Touch Probe is enabled."),
    (0x012c, "eERR_AXIS_CMD_INVALID_PARAMETER", "Command parameter invalid."),
    (0x0136, "eERR_AXIS_CMD_INVALID_POS", "Axis target position out of allowed range."),
    (0x0140, "eERR_AXIS_CMD_INVALID_VEL", "Axis velocity setting out of allowed range."),
    (0x014a, "eERR_AXIS_CMD_INVALID_ACC", "Axis acceleration setting out of allowed range."),
    (0x0154, "eERR_AXIS_CMD_INVALID_DEC", "Axis deceleration setting out of allowed range."),
    (0x015e, "eERR_AXIS_CMD_INVALID_JERK", "Axis jerk setting out of allowed range."),
    (0x0168, "eERR_AXIS_CMD_INVALID_SM_TIME", "Axis smoothing time setting out of allowed range."),
    (0x0172, "eERR_AXIS_CMD_INVALID_KILL_DEC", "Axis emergency (kill) deceleration setting out of allowed range."),
    (0x017c, "eERR_AXIS_CMD_INVALID_VEL_SCALE", "Axis velocity percentage setting out of allowed range."),
    (0x0190, "eERR_AXIS_COMP_NOT_CNFG", "Axis dynamic compensation not properly configured."),
    (0x01c2, "eERR_AXIS_CMD_INVALID_MASTER_SLAVE_CONNECTION", "Master/slave axis relationship setting invalid."),
    (0x01cc, "eERR_AXIS_CMD_INVALID_SLAVE_ID", "Slave axis ID setting invalid."),
    (0x01d6, "eERR_AXIS_CMD_INVALID_GEAR_RATIO", "Slave gear ratio setting out of allowed range."),
    (0x01f4, "eERR_AXIS_CMD_INVALID_ROLLOVER_POS", "Invalid axis rollover (single-turn) position setting; must be positive."),
    (0x01fe, "eERR_AXIS_CMD_INVALID_ROLLOVER_PP_MODE", "Rollover (single-turn) mode not supported in profile position mode; reset rollover value to 0 before switching to profile position mode."),
    (0x0208, "eERR_AXIS_CMD_INVALID_FORCECONST_TRQMODE", "Invalid torque (force) constant in torque mode; set a correct torque constant first."),
    (0x0258, "eERR_AXIS_CMD_INVALID_NO_SPECIFIC_PDO", "PDO must contain specific CoE objects to execute this command."),
    (0x03f2, "eERR_AXIS_DRIVE_FAULT", "Drive fault."),
    (0x03fc, "eERR_AXIS_DRIVE_ABNORMAL_DISABLE", "Drive abnormally disabled."),
    (0x0406, "eERR_AXIS_DRIVE_ENABLE_TOUT", "Enabling drive took too long."),
    (0x0407, "eERR_AXIS_DRIVE_ENABLE_TOUT_RMT", "Enabling drive took too long; check drive Access setting."),
    (0x0410, "eERR_AXIS_DRIVE_CLEAR_ERROR_TOUT", "Clearing drive error took too long."),
    (0x041a, "eERR_AXIS_DRIVE_DISABLE_TOUT", "Disabling drive took too long."),
    (0x0424, "eERR_AXIS_DRIVE_HOME_TOUT", "Axis homing took too long."),
    (0x042e, "eERR_AXIS_DRIVE_HOME_FAILED", "Axis homing error; check drive error code."),
    (0x0456, "eERR_AXIS_VEL_LIMIT", "Axis velocity exceeds velocity limit."),
    (0x4456, "eWRN_AXIS_VEL_LIMIT", "Warning: axis velocity limited by velocity limit."),
    (0x0460, "eERR_AXIS_ACC_LIMIT", "Axis acceleration exceeds acceleration limit."),
    (0x046a, "eERR_AXIS_CURR_LIMIT", "Axis current exceeds current limit."),
    (0x0474, "eERR_AXIS_DAMPINGRATIO_LIMIT", "Axis damping ratio setting out of allowed range."),
    (0x047e, "eERR_AXIS_FREQUENCY_LIMIT", "Axis frequency setting out of allowed range."),
    (0x07da, "eERR_AXIS_SWRL", "Axis position command reached right software limit."),
    (0x07e4, "eERR_AXIS_SWLL", "Axis position command reached left software limit."),
    (0x07ee, "eERR_AXIS_HWRL", "Axis right hardware limit signal triggered."),
    (0x07f8, "eERR_AXIS_HWLL", "Axis left hardware limit signal triggered."),
    (0x0802, "eERR_AXIS_COMP_LIMIT", "Axis error-compensation position exceeds max compensation limit."),
    (0x083e, "eERR_AXIS_PERR", "Axis position error exceeds position error limit; check for mechanical interference."),
    (0x0848, "eERR_AXIS_VERR", "Axis velocity error exceeds velocity error limit; check for mechanical interference."),
    (0x08a2, "eERR_AXIS_PVT_MOTION_VEL_LIMIT", "Axis PVT motion velocity exceeds protection range; check parameters."),
    (0x08ac, "eERR_AXIS_PVT_MOTION_ACC_LIMIT", "Axis PVT motion acceleration exceeds protection range; check parameters."),
    (0x08b6, "eERR_AXIS_PVT_MOTION_INVALID_TIME", "Axis PVT motion timing invalid; check parameters."),
    (0x0bb8, "eERR_AXIS_CTRL_ERR", "Axis internal error."),
    (0x0fa0, "eERR_AXIS_CMD_GEAR_DISABLED", "Electronic-gear command not allowed while electronic gear is disabled."),
    (0x0fa1, "eERR_AXIS_CMD_INVALID_AXIS_IN_CAM", "Electronic-gear command invalid while axis is an electronic cam."),
    (0x1388, "eERR_CAM_CMD_INVALID_ENGAGE_WINDOW", "Cam engage window out of allowed range."),
    (0x1389, "eERR_CAM_CMD_INVALID_ENGAGE_POSITION", "Cam engage position outside cam table range."),
    (0x138a, "eERR_CAM_CMD_INVALID_MASTER_SCALE_FACTOR", "Cam master scale factor out of allowed range."),
    (0x138b, "eERR_CAM_CMD_INVALID_CAM_SCALE_FACTOR", "Cam scale factor out of allowed range."),
    (0x138c, "eERR_CAM_CMD_INVALID_CAMTABLE_ID", "Cam table ID out of allowed range."),
    (0x138d, "eERR_CAM_CMD_INVALID_DISENGAGE_WINDOW", "Cam disengage window out of allowed range."),
    (0x138e, "eERR_CAM_CMD_INVALID_DISENGAGE_POSITION", "Cam disengage position out of allowed range."),
    (0x138f, "eERR_CAM_CMD_INVALID_OPERATION_IN_ENGAGED_STATE", "Cam command invalid in engaged state."),
    (0x1390, "eERR_CAM_CMD_INVALID_START_MODE", "Cam start mode not a valid enumeration value."),
    (0x1391, "eERR_CAM_CMD_INVALID_MOVE_MODE", "Cam move mode not a valid enumeration value."),
    (0x1392, "eERR_CAM_ENGAGED_FAILED", "Window too small; cam master may pass through the engage window."),
    (0x1393, "eERR_CAM_CMD_NOTINUSE", "Termination of trajectory mode currently not supported."),
    (0x1394, "eERR_CAM_CMD_CAM_DISABLED", "Cam command not allowed while cam is disabled."),
    (0x1395, "eERR_CAM_CMD_INVALID_AXIS_NOT_INCAM", "Cam command invalid when axis is not a cam."),
    (0x1396, "eERR_CAM_CMD_INVALID_AXIS_NOT_IN_DISENGAGED", "Cam command invalid when axis is not disengaged."),
    (0x1397, "eERR_CAM_CMD_INVALID_AXIS_IN_GEAR", "Cam command invalid when axis is an electronic gear."),
}

/// The axis error an engine refusal becomes, the table the HIMC register map's `last_err`
/// shows for the last refused command (`fixtures/modbus/himc.toml`, digest 004 §5.2); `None`
/// for refusals the HIMC has no code of its own for.
pub fn code_for(e: &EngineError) -> Option<&'static AxisError> {
    if let EngineError::StreamPoint { problem, .. } = e.innermost() {
        // MovePVT's own codes (digest 004 §5.2.8).
        let name = match problem {
            StreamPointProblem::StartMismatch | StreamPointProblem::TimeNotIncreasing { .. } => {
                Some("eERR_AXIS_PVT_MOTION_INVALID_TIME")
            }
            StreamPointProblem::VelocityLimit { .. } => Some("eERR_AXIS_PVT_MOTION_VEL_LIMIT"),
            StreamPointProblem::AccelerationLimit { .. } => Some("eERR_AXIS_PVT_MOTION_ACC_LIMIT"),
            StreamPointProblem::NotFinite { .. } => None,
        };
        if let Some(name) = name {
            return AxisError::by_name(name);
        }
    }
    if let EngineError::CompensationLimit { .. } = e.innermost() {
        return AxisError::by_name("eERR_AXIS_COMP_LIMIT");
    }
    code_for_kind(e.kind())
}

/// [`code_for`] by error kind (what a status record keeps of the last refusal).
pub fn code_for_kind(kind: ErrorKind) -> Option<&'static AxisError> {
    let name = match kind {
        ErrorKind::QueueFull => "eERR_AXIS_CMD_QUEUE_FULL",
        ErrorKind::AxisDisabled => "eERR_AXIS_CMD_INVALID_DISABLED",
        ErrorKind::AxisInError => "eERR_AXIS_CMD_INVALID_ERROR_STATE",
        ErrorKind::InvalidState => "eERR_AXIS_CMD_INVALID_STATE",
        ErrorKind::InvalidParameter | ErrorKind::InvalidArgument => {
            "eERR_AXIS_CMD_INVALID_PARAMETER"
        }
        ErrorKind::Unsupported => "eERR_AXIS_CMD_UNKOWN",
        _ => return None,
    };
    AxisError::by_name(name)
}

/// An axis controller variable (HCV) of Table 17.1.1.2, read and written with
/// `GetConfigVar`/`SetConfigVar` as id 0x83NNAAAA (digest 004 §1.11).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AxisVariable {
    /// AAAA, the variable address.
    pub address: u16,
    /// The manual's name.
    pub name: &'static str,
    /// The engine parameter it is, where the engine has one.
    pub param: Option<ParamId>,
}

macro_rules! axis_variables {
    ($(($address:literal, $name:literal, $param:expr),)*) => {
        /// The axis variables, Table 17.1.1.2 (digest 004 §1.11), in the manual's order.
        pub const AXIS_VARIABLES: &[AxisVariable] = &[
            $(AxisVariable { address: $address, name: $name, param: $param },)*
        ];
    };
}

// `acc_lim`/`dec_lim` are both the engine's `max_accel`, which caps acceleration and
// deceleration together (decisions.md, "What still answers 5201"). `home_status` is the HIMC's
// own homing status word, not the engine's homing phase.
axis_variables! {
    (0x0015, "HCV_ID_motion_type", None),
    (0x0033, "HCV_ID_pos_tr", Some(ParamId::InPositionWindow)),
    (0x0034, "HCV_ID_pos_tr_t", Some(ParamId::InPositionTime)),
    (0x0065, "HCV_ID_sw_RL", Some(ParamId::FsLimit)),
    (0x0066, "HCV_ID_sw_LL", Some(ParamId::RsLimit)),
    (0x0067, "HCV_ID_vel_lim", Some(ParamId::MaxVelocity)),
    (0x0068, "HCV_ID_acc_lim", Some(ParamId::MaxAccel)),
    (0x0069, "HCV_ID_dec_lim", Some(ParamId::MaxAccel)),
    (0x0079, "HCV_ID_max_pos_err", Some(ParamId::FeLimit)),
    (0x007a, "HCV_ID_max_comp_lim", Some(ParamId::CompensationLimit)),
    (0x00a0, "HCV_ID_home_status", None),
    (0x00a1, "HCV_ID_home_method", Some(ParamId::HomeMethod)),
    (0x00a2, "HCV_ID_home_fast_vel", Some(ParamId::HomeSwitchVelocity)),
    (0x00a3, "HCV_ID_home_slow_vel", Some(ParamId::HomeZeroVelocity)),
    (0x00a4, "HCV_ID_home_timeout", Some(ParamId::HomeTimeout)),
    (0x00a5, "HCV_ID_home_acc", Some(ParamId::HomeAcceleration)),
    (0x00a6, "HCV_ID_home_offset", Some(ParamId::HomeOffset)),
    (0x00d3, "HCV_ID_max_vel", Some(ParamId::Speed)),
    (0x00d4, "HCV_ID_max_acc", Some(ParamId::Accel)),
    (0x00d5, "HCV_ID_max_dec", Some(ParamId::Decel)),
    (0x00d7, "HCV_ID_sm_factor", Some(ParamId::SmoothTime)),
    (0x00db, "HCV_ID_vel_scale", Some(ParamId::VelScale)),
    (0x00dd, "HCV_ID_p2p_del", None),
    (0x00de, "HCV_ID_p2p_pos1", None),
    (0x00df, "HCV_ID_p2p_pos2", None),
    (0x00e0, "HCV_ID_p2p_repeat", None),
    (0x00e1, "HCV_ID_rlt_dist", None),
    (0x00e2, "HCV_ID_en_motionManager", None),
    (0x00e3, "HCV_ID_acc_time", Some(ParamId::AccelTime)),
    (0x00e4, "HCV_ID_dec_time", Some(ParamId::DecelTime)),
    (0x00e9, "HCV_ID_map_io_type", None),
    (0x0117, "HCV_ID_rollover_turns", None),
    (0x0119, "HCV_ID_rollover_val", Some(ParamId::Rollover)),
    (0x0193, "HCV_ID_gant_pair", None),
    (0x01f7, "HCV_ID_en_delay", None),
    (0x01ff, "HCV_ID_fb_ratio_pos", None),
    (0x0200, "HCV_ID_fb_ratio_cnt", None),
    (0x0209, "HCV_ID_fb_curr_ratio_curr", None),
    (0x020a, "HCV_ID_fb_curr_ratio_cnt", None),
    (0x0213, "HCV_ID_rotor_inertia", None),
    (0x0214, "HCV_ID_force_constant", None),
    (0x0263, "HCV_ID_last_err", None),
    (0x03c2, "HCV_ID_gear_ratio", None),
}

impl AxisVariable {
    /// The variable at address AAAA.
    pub fn by_address(address: u16) -> Option<&'static AxisVariable> {
        AXIS_VARIABLES.iter().find(|v| v.address == address)
    }

    /// The variable called `name` (`HCV_ID_max_vel`).
    pub fn by_name(name: &str) -> Option<&'static AxisVariable> {
        AXIS_VARIABLES.iter().find(|v| v.name == name)
    }
}

/// An HMPL value of parameter `id` in engine units: times (the engine's seconds) are ms in
/// HMPL; lengths, velocities and accelerations are the axis's mm or deg already (digest 004
/// §1.2).
pub fn value_to_engine(id: ParamId, hmpl: f64) -> f64 {
    match id.def().unit {
        Unit::Seconds => ms_to_seconds(hmpl),
        _ => hmpl,
    }
}

/// The engine's value of parameter `id` in HMPL units (the inverse of [`value_to_engine`]).
pub fn value_from_engine(id: ParamId, engine: f64) -> f64 {
    match id.def().unit {
        Unit::Seconds => seconds_to_ms(engine),
        _ => engine,
    }
}

/// HMPL units against the engine's (digest 004 §1.2): lengths in mm or deg are the engine's
/// user units as the axes are configured; times, including the smoothing time, are in ms where
/// the engine counts seconds.
pub fn ms_to_seconds(ms: f64) -> f64 {
    ms / 1e3
}

pub fn seconds_to_ms(s: f64) -> f64 {
    s * 1e3
}

/// The smoothing time range, 0 … 500 ms everywhere it is set (digest 004 §1.2).
pub const SMOOTHING_MS: std::ops::RangeInclusive<f64> = 0.0..=500.0;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_status::status;

    #[test]
    fn each_predicate_reads_its_flag_or_state() {
        let none = AxisExtra::default();
        for (p, flag) in [
            (Predicate::IsEnabled, AxisFlags::ENABLED),
            (Predicate::IsMoving, AxisFlags::MOVING),
            (Predicate::IsInPos, AxisFlags::IN_POSITION),
            (Predicate::IsGrouped, AxisFlags::IN_GROUP),
            (Predicate::IsHWLL, AxisFlags::HW_LIMIT_NEG),
            (Predicate::IsHWRL, AxisFlags::HW_LIMIT_POS),
            (Predicate::IsSWLL, AxisFlags::SW_LIMIT_NEG),
            (Predicate::IsSWRL, AxisFlags::SW_LIMIT_POS),
            (Predicate::IsDriveErr, AxisFlags::DRIVE_ALARM),
            (Predicate::IsPosErr, AxisFlags::FE_FAULT),
            (Predicate::IsAcc, AxisFlags::ACCELERATING),
        ] {
            assert!(p.holds(&status(AxisState::Standstill, flag), none), "{p:?}");
            let others = AxisFlags::all().difference(flag);
            assert!(
                !p.holds(&status(AxisState::Standstill, others), none),
                "{p:?}"
            );
        }
        assert!(
            Predicate::IsErrorStop.holds(&status(AxisState::ErrorStop, AxisFlags::empty()), none)
        );
        assert!(!Predicate::IsErrorStop.holds(&status(AxisState::Stopping, AxisFlags::all()), none));
        let sync = status(AxisState::SynchronizedMotion, AxisFlags::empty());
        assert!(Predicate::IsSync.holds(&sync, none));
        let gantry = AxisExtra {
            gantry: true,
            compensation: false,
        };
        assert!(Predicate::IsGantry.holds(&sync, gantry));
        assert!(!Predicate::IsCompActive.holds(&sync, gantry));
    }

    #[test]
    fn predicates_are_found_by_their_hmpl_names() {
        for (p, name) in Predicate::ALL {
            assert_eq!(Predicate::by_name(name), Some(p));
            assert_eq!(p.name(), name);
        }
        assert_eq!(Predicate::by_name("ismoving"), None);
    }

    #[test]
    fn the_axis_table_is_the_manuals() {
        assert_eq!(AXIS_ERRORS.len(), 83, "digest 004 §5: 83 axis entries");
        let mut values: Vec<u16> = AXIS_ERRORS.iter().map(|e| e.value).collect();
        values.sort_unstable();
        values.dedup();
        assert_eq!(values.len(), AXIS_ERRORS.len(), "values are unique");
        // Digest 004 §5: axis 2 "position command reached right software limit" = 0x830207da.
        let swrl = AxisError::by_name("eERR_AXIS_SWRL").map(|e| e.code(2));
        assert_eq!(swrl, Some(0x8302_07da));
        assert_eq!(0x8302_07da_u32 as i32, -2_097_018_918);
        assert_eq!(
            AxisError::by_value(0x0406).map(|e| e.name),
            Some("eERR_AXIS_DRIVE_ENABLE_TOUT")
        );
    }

    #[test]
    fn refusals_map_as_the_himc_register_map_did() {
        // The literal values `fixtures/modbus/himc.toml` had for its `last_error.*` cases.
        for (kind, value) in [
            (ErrorKind::QueueFull, 0x001e),
            (ErrorKind::AxisDisabled, 0x0078),
            (ErrorKind::AxisInError, 0x0096),
            (ErrorKind::InvalidState, 0x0064),
            (ErrorKind::InvalidParameter, 0x012c),
            (ErrorKind::InvalidArgument, 0x012c),
            (ErrorKind::Unsupported, 0x000a),
        ] {
            assert_eq!(
                code_for_kind(kind).map(|e| e.value),
                Some(value),
                "{kind:?}"
            );
        }
        assert_eq!(code_for_kind(ErrorKind::InvalidAxis), None);
        let e = EngineError::AxisDisabled { axis: 1 };
        assert_eq!(code_for(&e).map(|e| e.code(1)), Some(0x8301_0078));
    }

    #[test]
    fn move_pvt_refusals_have_their_own_codes() {
        let point = |problem| EngineError::StreamPoint {
            axis: 0,
            point: 2,
            problem,
        };
        for (problem, value) in [
            (
                StreamPointProblem::VelocityLimit {
                    velocity: 2.0,
                    limit: 1.0,
                },
                0x08a2,
            ),
            (
                StreamPointProblem::AccelerationLimit {
                    acceleration: 2.0,
                    limit: 1.0,
                },
                0x08ac,
            ),
            (
                StreamPointProblem::TimeNotIncreasing {
                    time_ms: 1.0,
                    previous_ms: 2.0,
                },
                0x08b6,
            ),
        ] {
            assert_eq!(code_for(&point(problem)).map(|e| e.value), Some(value));
        }
        let nan = point(StreamPointProblem::NotFinite {
            name: "position",
            value: f64::NAN,
        });
        assert_eq!(code_for(&nan).map(|e| e.value), Some(0x012c));
    }

    #[test]
    fn times_are_milliseconds() {
        assert_eq!(ms_to_seconds(250.0), 0.25);
        assert_eq!(seconds_to_ms(0.25), 250.0);
        assert!(SMOOTHING_MS.contains(&500.0) && !SMOOTHING_MS.contains(&501.0));
    }

    #[test]
    fn axis_variables_are_table_17_1_1_2() {
        assert_eq!(AXIS_VARIABLES.len(), 43);
        let v = AxisVariable::by_address(0x00d3);
        assert_eq!(
            v.map(|v| (v.name, v.param)),
            Some(("HCV_ID_max_vel", Some(ParamId::Speed)))
        );
        assert_eq!(
            AxisVariable::by_name("HCV_ID_en_delay").map(|v| v.address),
            Some(0x01f7)
        );
        // The id of axis 1's variable uses the same layout as the error codes (digest 004 §1.11).
        assert_eq!(compose(AXIS_CLASS, 1, 0x01f7), 0x8301_01f7);
        // Where the engine already knows the HCV name as an alias, both tables agree.
        for v in AXIS_VARIABLES {
            let short = v.name.trim_start_matches("HCV_ID_");
            if let (Some(alias), Some(param)) = (ParamId::from_name(short), v.param) {
                assert_eq!(alias, param, "{}", v.name);
            }
        }
    }

    #[test]
    fn hmpl_times_are_ms_and_lengths_pass_through() {
        assert_eq!(value_to_engine(ParamId::SmoothTime, 20.0), 0.02);
        assert_eq!(value_from_engine(ParamId::InPositionTime, 0.005), 5.0);
        assert_eq!(value_to_engine(ParamId::Speed, 250.0), 250.0);
        assert_eq!(value_from_engine(ParamId::FsLimit, 99.5), 99.5);
    }
}
