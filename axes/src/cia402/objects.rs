//! The drive's object dictionary: CiA 301 communication objects it needs and the CiA 402
//! (IEC 61800-7-201) objects of the supported modes. Positions are in increments, velocities in
//! increments/s, accelerations in increments/s², torques in ‰ of rated torque (CiA 402 §6.3
//! without a factor group: user units = internal units = increments).

use crate::od::{Access, DataType, EntryDef, Value};

use super::state::OperationMode;
use super::DriveConfig;

/// Object indices.
pub mod obj {
    pub const DEVICE_TYPE: u16 = 0x1000;
    pub const ERROR_REGISTER: u16 = 0x1001;
    pub const DEVICE_NAME: u16 = 0x1008;
    pub const HARDWARE_VERSION: u16 = 0x1009;
    pub const SOFTWARE_VERSION: u16 = 0x100A;
    pub const IDENTITY: u16 = 0x1018;
    /// Manufacturer-specific: a DOMAIN for SDO block transfers (no meaning to the drive).
    pub const DATA_DOMAIN: u16 = 0x2F00;
    pub const ABORT_CONNECTION_OPTION: u16 = 0x6007;
    pub const ERROR_CODE: u16 = 0x603F;
    pub const CONTROLWORD: u16 = 0x6040;
    pub const STATUSWORD: u16 = 0x6041;
    pub const QUICK_STOP_OPTION: u16 = 0x605A;
    pub const SHUTDOWN_OPTION: u16 = 0x605B;
    pub const DISABLE_OPERATION_OPTION: u16 = 0x605C;
    pub const HALT_OPTION: u16 = 0x605D;
    pub const FAULT_REACTION_OPTION: u16 = 0x605E;
    pub const MODES_OF_OPERATION: u16 = 0x6060;
    pub const MODES_OF_OPERATION_DISPLAY: u16 = 0x6061;
    pub const POSITION_DEMAND: u16 = 0x6062;
    pub const POSITION_ACTUAL_INTERNAL: u16 = 0x6063;
    pub const POSITION_ACTUAL: u16 = 0x6064;
    pub const FOLLOWING_ERROR_WINDOW: u16 = 0x6065;
    pub const FOLLOWING_ERROR_TIMEOUT: u16 = 0x6066;
    pub const POSITION_WINDOW: u16 = 0x6067;
    pub const POSITION_WINDOW_TIME: u16 = 0x6068;
    pub const VELOCITY_DEMAND: u16 = 0x606B;
    pub const VELOCITY_ACTUAL: u16 = 0x606C;
    pub const VELOCITY_WINDOW: u16 = 0x606D;
    pub const VELOCITY_WINDOW_TIME: u16 = 0x606E;
    pub const VELOCITY_THRESHOLD: u16 = 0x606F;
    pub const VELOCITY_THRESHOLD_TIME: u16 = 0x6070;
    pub const TARGET_TORQUE: u16 = 0x6071;
    pub const MAX_TORQUE: u16 = 0x6072;
    pub const TORQUE_ACTUAL: u16 = 0x6077;
    pub const TARGET_POSITION: u16 = 0x607A;
    pub const HOME_OFFSET: u16 = 0x607C;
    pub const SOFTWARE_POSITION_LIMIT: u16 = 0x607D;
    pub const MAX_PROFILE_VELOCITY: u16 = 0x607F;
    pub const MAX_MOTOR_SPEED: u16 = 0x6080;
    pub const PROFILE_VELOCITY: u16 = 0x6081;
    pub const PROFILE_ACCELERATION: u16 = 0x6083;
    pub const PROFILE_DECELERATION: u16 = 0x6084;
    pub const QUICK_STOP_DECELERATION: u16 = 0x6085;
    pub const MOTION_PROFILE_TYPE: u16 = 0x6086;
    pub const HOMING_METHOD: u16 = 0x6098;
    pub const HOMING_SPEEDS: u16 = 0x6099;
    pub const HOMING_ACCELERATION: u16 = 0x609A;
    pub const TOUCH_PROBE_FUNCTION: u16 = 0x60B8;
    pub const TOUCH_PROBE_STATUS: u16 = 0x60B9;
    pub const TOUCH_PROBE_1_POSITIVE: u16 = 0x60BA;
    pub const TOUCH_PROBE_1_NEGATIVE: u16 = 0x60BB;
    pub const TOUCH_PROBE_2_POSITIVE: u16 = 0x60BC;
    pub const TOUCH_PROBE_2_NEGATIVE: u16 = 0x60BD;
    pub const INTERPOLATION_TIME_PERIOD: u16 = 0x60C2;
    pub const FOLLOWING_ERROR_ACTUAL: u16 = 0x60F4;
    pub const POSITION_DEMAND_INTERNAL: u16 = 0x60FC;
    pub const DIGITAL_INPUTS: u16 = 0x60FD;
    pub const DIGITAL_OUTPUTS: u16 = 0x60FE;
    pub const TARGET_VELOCITY: u16 = 0x60FF;
    pub const SUPPORTED_DRIVE_MODES: u16 = 0x6502;
}

/// The 0x603F error codes the drive reports (CiA 402 Annex / CiA 301 §7.2.7.1 emergency error
/// code ranges; 0xFFxx is the manufacturer-specific range).
pub mod error_code {
    pub const NO_ERROR: u16 = 0x0000;
    /// Axis FE_FAULT: following error (DS402 0x8611, positioning controller).
    pub const FOLLOWING_ERROR: u16 = 0x8611;
    /// Axis ENCODER_LOSS: incremental sensor 1 fault (DS402 0x7305).
    pub const ENCODER: u16 = 0x7305;
    /// Axis ESTOP: the emergency-stop contact (DS402 0x5441 "contact 1", manufacturer-specific
    /// meaning; mcemu's is the e-stop chain).
    pub const EMERGENCY_STOP: u16 = 0x5441;
    /// Life guard / heartbeat consumer error (CiA 301 0x8130), raised by
    /// [`Cia402Drive::connection_lost`](super::Cia402Drive::connection_lost) with 0x6007 = 1.
    pub const CONNECTION_LOST: u16 = 0x8130;
    /// Axis DRIVE_ALARM: an injected drive alarm whose cause the simulation does not model.
    pub const DRIVE_ALARM: u16 = 0xFF00;
    /// The engine refused to power the axis (`Enable` refused).
    pub const ENABLE_REFUSED: u16 = 0xFF01;
    /// The axis lost power while the drive had it enabled (disabled from outside the drive).
    pub const POWER_LOST: u16 = 0xFF02;
}

/// 0x6502: the supported modes.
pub fn supported_drive_modes() -> u32 {
    OperationMode::ALL
        .iter()
        .fold(0, |bits, m| bits | m.supported_bit())
}

/// The drive's object table. Defaults are documented in `docs/decisions.md` (CiA 402 drive).
pub fn object_table(config: &DriveConfig) -> Vec<EntryDef> {
    use obj::*;
    use Access::{Const, Ro, Rw, Rww};
    use Value::{String as S, I16, I32, I8, U16, U32, U8};
    let e = EntryDef::new;
    vec![
        // ---- CiA 301 communication profile ----
        // Device type: profile 402 (bits 0–15), servo drive (bits 16–23 = 0x02).
        e(DEVICE_TYPE, 0, "Device type", Const, U32(0x0002_0192)),
        e(ERROR_REGISTER, 0, "Error register", Ro, U8(0)).pdo(),
        e(
            DEVICE_NAME,
            0,
            "Manufacturer device name",
            Const,
            S(config.name.clone()),
        ),
        e(
            HARDWARE_VERSION,
            0,
            "Manufacturer hardware version",
            Const,
            S(config.hardware_version.clone()),
        ),
        e(
            SOFTWARE_VERSION,
            0,
            "Manufacturer software version",
            Const,
            S(config.software_version.clone()),
        ),
        e(
            IDENTITY,
            0,
            "Identity object: highest sub-index",
            Const,
            U8(4),
        ),
        e(IDENTITY, 1, "Vendor-ID", Ro, U32(config.vendor_id)),
        e(IDENTITY, 2, "Product code", Ro, U32(config.product_code)),
        e(IDENTITY, 3, "Revision number", Ro, U32(config.revision)),
        e(IDENTITY, 4, "Serial number", Ro, U32(config.serial)),
        // ---- Manufacturer-specific ----
        // Any bytes a master wants to move (SDO block transfers without a user EDS), up to the
        // dictionary's bound for variable-length values, `od::MAX_VARIABLE_LEN` (1 MiB); longer
        // downloads get 0x06070012. Held in memory only: a DOMAIN is not a stored parameter
        // (docs/decisions.md, "CiA 402 drive").
        e(DATA_DOMAIN, 0, "Data domain", Rw, Value::Bytes(Vec::new())).data_type(DataType::Domain),
        // ---- CiA 402 device control ----
        e(
            ABORT_CONNECTION_OPTION,
            0,
            "Abort connection option code",
            Rw,
            I16(1),
        )
        .range(I16(0), I16(3)),
        e(ERROR_CODE, 0, "Error code", Ro, U16(0)).pdo(),
        e(CONTROLWORD, 0, "Controlword", Rww, U16(0)).pdo(),
        e(STATUSWORD, 0, "Statusword", Ro, U16(0)).pdo(),
        e(QUICK_STOP_OPTION, 0, "Quick stop option code", Rw, I16(2)).range(I16(0), I16(8)),
        e(SHUTDOWN_OPTION, 0, "Shutdown option code", Rw, I16(0)).range(I16(0), I16(1)),
        e(
            DISABLE_OPERATION_OPTION,
            0,
            "Disable operation option code",
            Rw,
            I16(1),
        )
        .range(I16(0), I16(1)),
        e(HALT_OPTION, 0, "Halt option code", Rw, I16(1)).range(I16(1), I16(4)),
        e(
            FAULT_REACTION_OPTION,
            0,
            "Fault reaction option code",
            Rw,
            I16(2),
        )
        .range(I16(0), I16(4)),
        e(MODES_OF_OPERATION, 0, "Modes of operation", Rww, I8(0)).pdo(),
        e(
            MODES_OF_OPERATION_DISPLAY,
            0,
            "Modes of operation display",
            Ro,
            I8(0),
        )
        .pdo(),
        e(
            SUPPORTED_DRIVE_MODES,
            0,
            "Supported drive modes",
            Const,
            U32(supported_drive_modes()),
        )
        .pdo(),
        // ---- Position ----
        e(POSITION_DEMAND, 0, "Position demand value", Ro, I32(0)).pdo(),
        e(
            POSITION_ACTUAL_INTERNAL,
            0,
            "Position actual internal value",
            Ro,
            I32(0),
        )
        .pdo(),
        e(POSITION_ACTUAL, 0, "Position actual value", Ro, I32(0)).pdo(),
        e(
            FOLLOWING_ERROR_WINDOW,
            0,
            "Following error window",
            Rw,
            U32(10_000),
        )
        .pdo(),
        e(
            FOLLOWING_ERROR_TIMEOUT,
            0,
            "Following error time out",
            Rw,
            U16(10),
        )
        .pdo(),
        e(POSITION_WINDOW, 0, "Position window", Rw, U32(100)).pdo(),
        e(POSITION_WINDOW_TIME, 0, "Position window time", Rw, U16(0)).pdo(),
        e(TARGET_POSITION, 0, "Target position", Rww, I32(0)).pdo(),
        // CiA 402 §6.3.4: the cycle of CSP/CSV/CST set-points, value × 10^index s (1 ms). The
        // drive interpolates CSP targets linearly over it.
        e(
            INTERPOLATION_TIME_PERIOD,
            0,
            "Interpolation time period: highest sub-index",
            Const,
            U8(2),
        ),
        e(
            INTERPOLATION_TIME_PERIOD,
            1,
            "Interpolation time period value",
            Rw,
            U8(1),
        ),
        e(
            INTERPOLATION_TIME_PERIOD,
            2,
            "Interpolation time index",
            Rw,
            I8(-3),
        )
        .range(I8(-6), I8(0)),
        e(HOME_OFFSET, 0, "Home offset", Rw, I32(0)).pdo(),
        e(
            SOFTWARE_POSITION_LIMIT,
            0,
            "Software position limit: highest sub-index",
            Const,
            U8(2),
        ),
        e(
            SOFTWARE_POSITION_LIMIT,
            1,
            "Min position limit",
            Rw,
            I32(i32::MIN),
        )
        .pdo(),
        e(
            SOFTWARE_POSITION_LIMIT,
            2,
            "Max position limit",
            Rw,
            I32(i32::MAX),
        )
        .pdo(),
        e(
            FOLLOWING_ERROR_ACTUAL,
            0,
            "Following error actual value",
            Ro,
            I32(0),
        )
        .pdo(),
        e(
            POSITION_DEMAND_INTERNAL,
            0,
            "Position demand internal value",
            Ro,
            I32(0),
        )
        .pdo(),
        // ---- Velocity ----
        e(VELOCITY_DEMAND, 0, "Velocity demand value", Ro, I32(0)).pdo(),
        e(VELOCITY_ACTUAL, 0, "Velocity actual value", Ro, I32(0)).pdo(),
        e(VELOCITY_WINDOW, 0, "Velocity window", Rw, U16(100)).pdo(),
        e(VELOCITY_WINDOW_TIME, 0, "Velocity window time", Rw, U16(0)).pdo(),
        e(VELOCITY_THRESHOLD, 0, "Velocity threshold", Rw, U16(100)).pdo(),
        e(
            VELOCITY_THRESHOLD_TIME,
            0,
            "Velocity threshold time",
            Rw,
            U16(0),
        )
        .pdo(),
        e(
            MAX_PROFILE_VELOCITY,
            0,
            "Max profile velocity",
            Rw,
            U32(u32::MAX),
        )
        .pdo(),
        e(MAX_MOTOR_SPEED, 0, "Max motor speed", Rw, U32(u32::MAX)).pdo(),
        e(PROFILE_VELOCITY, 0, "Profile velocity", Rww, U32(10_000)).pdo(),
        e(
            PROFILE_ACCELERATION,
            0,
            "Profile acceleration",
            Rww,
            U32(100_000),
        )
        .pdo(),
        e(
            PROFILE_DECELERATION,
            0,
            "Profile deceleration",
            Rww,
            U32(100_000),
        )
        .pdo(),
        e(
            QUICK_STOP_DECELERATION,
            0,
            "Quick stop deceleration",
            Rw,
            U32(1_000_000),
        )
        .pdo(),
        e(MOTION_PROFILE_TYPE, 0, "Motion profile type", Rw, I16(0)).range(I16(0), I16(3)),
        e(TARGET_VELOCITY, 0, "Target velocity", Rww, I32(0)).pdo(),
        // ---- Torque ----
        e(TARGET_TORQUE, 0, "Target torque", Rww, I16(0)).pdo(),
        e(MAX_TORQUE, 0, "Max torque", Rw, U16(3000)).pdo(),
        e(TORQUE_ACTUAL, 0, "Torque actual value", Ro, I16(0)).pdo(),
        // ---- Homing ----
        e(HOMING_METHOD, 0, "Homing method", Rw, I8(37)).pdo(),
        e(
            HOMING_SPEEDS,
            0,
            "Homing speeds: highest sub-index",
            Const,
            U8(2),
        ),
        e(
            HOMING_SPEEDS,
            1,
            "Speed during search for switch",
            Rw,
            U32(10_000),
        )
        .pdo(),
        e(
            HOMING_SPEEDS,
            2,
            "Speed during search for zero",
            Rw,
            U32(1_000),
        )
        .pdo(),
        e(
            HOMING_ACCELERATION,
            0,
            "Homing acceleration",
            Rw,
            U32(100_000),
        )
        .pdo(),
        // ---- Touch probe ----
        e(TOUCH_PROBE_FUNCTION, 0, "Touch probe function", Rww, U16(0)).pdo(),
        e(TOUCH_PROBE_STATUS, 0, "Touch probe status", Ro, U16(0)).pdo(),
        e(
            TOUCH_PROBE_1_POSITIVE,
            0,
            "Touch probe pos1 pos value",
            Ro,
            I32(0),
        )
        .pdo(),
        e(
            TOUCH_PROBE_1_NEGATIVE,
            0,
            "Touch probe pos1 neg value",
            Ro,
            I32(0),
        )
        .pdo(),
        e(
            TOUCH_PROBE_2_POSITIVE,
            0,
            "Touch probe pos2 pos value",
            Ro,
            I32(0),
        )
        .pdo(),
        e(
            TOUCH_PROBE_2_NEGATIVE,
            0,
            "Touch probe pos2 neg value",
            Ro,
            I32(0),
        )
        .pdo(),
        // ---- I/O ----
        e(DIGITAL_INPUTS, 0, "Digital inputs", Ro, U32(0)).pdo(),
        e(
            DIGITAL_OUTPUTS,
            0,
            "Digital outputs: highest sub-index",
            Const,
            U8(2),
        ),
        e(DIGITAL_OUTPUTS, 1, "Physical outputs", Rww, U32(0)).pdo(),
        e(DIGITAL_OUTPUTS, 2, "Bit mask", Rw, U32(0)),
    ]
}
