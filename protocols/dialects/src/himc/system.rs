//! HIMC system errors, Table 18.1.1.1 (digest 004 §5.1): codes 0x0000VVVV with no class or id
//! byte, which `GetSystemLastErr` returns and the Native ASCII front-end answers a line it
//! cannot call with.

/// One row of the system error table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SystemError {
    /// The whole code (the class and id bytes are 0).
    pub value: u16,
    /// The manual's name, verbatim.
    pub name: &'static str,
    /// Its meaning, in English (digest 004 §5.1).
    pub meaning: &'static str,
}

impl SystemError {
    /// The row called `name`.
    pub fn by_name(name: &str) -> Option<&'static SystemError> {
        SYSTEM_ERRORS.iter().find(|e| e.name == name)
    }

    /// The row with code `value`.
    pub fn by_value(value: u16) -> Option<&'static SystemError> {
        SYSTEM_ERRORS.iter().find(|e| e.value == value)
    }

    /// The code as the functions return it.
    pub const fn code(&self) -> u32 {
        self.value as u32
    }
}

/// `eERR_HCV_ID_NOT_FOUND`: no controller variable with this id (TV 69).
pub const HCV_ID_NOT_FOUND: u32 = 0x0000_0001;
/// `eERR_HCV_IS_READ_ONLY`: a controller variable that cannot be written.
pub const HCV_IS_READ_ONLY: u32 = 0x0000_0003;
/// `eERR_HCV_VALUE_OUT_OF_RANGE`: a value the variable cannot take.
pub const HCV_VALUE_OUT_OF_RANGE: u32 = 0x0000_0004;
/// `eERR_EMERGENCY_STOP`: the E-stop input fired (digest 004 §1.10).
pub const EMERGENCY_STOP: u32 = 0x0000_0064;
/// `eERR_HMPL_INVALID_ARG`: wrong argument count or type.
pub const HMPL_INVALID_ARG: u32 = 0x0000_1388;
/// `eERR_HMPL_STR_TOO_LONG`: a line (or string) over `HMPL_STR_MAX_LEN`.
pub const HMPL_STR_TOO_LONG: u32 = 0x0000_138d;
/// `eERR_HMPL_INVALID_STR_FORMAT`: a line that is not a call.
pub const HMPL_INVALID_STR_FORMAT: u32 = 0x0000_138e;
/// `eERR_HMPL_ARG_OUT_OF_RANGE`: an argument out of its range (an index, a slave …).
pub const HMPL_ARG_OUT_OF_RANGE: u32 = 0x0000_138f;
/// `eERR_HMPL_NOT_SUPPORTED`: a function this controller does not run.
pub const HMPL_NOT_SUPPORTED: u32 = 0x0000_1451;
/// `eERR_HMPL_INTERNAL_ERROR`: the engine did not answer.
pub const HMPL_INTERNAL_ERROR: u32 = 0x0000_176f;

/// `HMPL_STR_MAX_LEN`: the longest string, and the longest Native ASCII line (digest 004 §2.2).
pub const HMPL_STR_MAX_LEN: usize = 512;

macro_rules! system_errors {
    ($(($value:literal, $name:literal, $meaning:literal),)*) => {
        /// The system errors, Table 18.1.1.1 (digest 004 §5.1), in the manual's order.
        pub const SYSTEM_ERRORS: &[SystemError] = &[
            $(SystemError { value: $value, name: $name, meaning: $meaning },)*
        ];
    };
}

system_errors! {
    (0x0001, "eERR_HCV_ID_NOT_FOUND", "Variable ID not found."),
    (0x0002, "eERR_DATA_EXCEEDED", "Requested data out of range."),
    (0x0003, "eERR_HCV_IS_READ_ONLY", "Parameter is read-only."),
    (0x0004, "eERR_HCV_VALUE_OUT_OF_RANGE", "Input value out of range limit."),
    (0x0050, "eERR_EWM_CALLBACK_BUSY", "EWM callback function is busy."),
    (0x0064, "eERR_EMERGENCY_STOP", "Controller is emergency-stopped."),
    (0x0107, "eERR_NOT_VALID_TASKID", "This task ID is invalid."),
    (0x0108, "eERR_TASK_IS_RUNNING", "This task is running."),
    (0x0109, "eERR_FUNC_NOT_IN_TASK", "This task does not contain this function."),
    (0x010a, "eERR_TASK_EMPTY", "This task has no content."),
    (0x010b, "eERR_TASK_NOT_RUNNING", "This task is not running."),
    (0x012c, "eERR_NIC_INIT_TOUT", "Fieldbus network not ready."),
    (0x012d, "eERR_HARDWARE_MISMATCH", "Unrecognized hardware."),
    (0x012e, "eERR_SLAVE_NUM_MISMATCH", "Number of slaves does not match configuration."),
    (0x0130, "eERR_INVALID_MCK_CNFG", "Motion kernel configuration invalid."),
    (0x0138, "eERR_HIMC_LOAD_CONFIG_FAIL", "Cannot load configuration from SSD; save again."),
    (0x0139, "eERR_HIMC_SAVE_CONFIG_FAIL", "Cannot save configuration to HIMC; save again."),
    (0x013a, "eERR_HIMC_SAVE_CONFIG_COPY_FAIL", "Cannot save configuration to HIMC; cannot save file to SAVE folder."),
    (0x013c, "eERR_ETHERCAT_LICENSE_MISMATCH", "EtherCAT license mismatch."),
    (0x01f4, "eERR_ISR_NOT_STABLE", "Interrupt period unstable."),
    (0x41f4, "eWRN_ISR_NOT_STABLE", "Interrupt period unstable (early warning)."),
    (0x01f5, "eERR_MCK_OVERLOAD", "Motion kernel overload."),
    (0xc1f5, "eDBG_MCK_OVERLOAD", "Motion kernel overload (early warning)."),
    (0x01f6, "eERR_ISR_OVERLOAD", "CPU overload."),
    (0xc1f6, "eDBG_ISR_OVERLOAD", "CPU overload (early warning)."),
    (0x1388, "eERR_HMPL_INVALID_ARG", "Invalid argument in HMPL."),
    (0x1389, "eERR_HMPL_INVALID_PTR", "Invalid pointer in HMPL."),
    (0x138a, "eERR_HMPL_STACK_OVERFLOW", "Stack overflow in HMPL."),
    (0x138b, "eERR_HMPL_ILLEGAL_MEM_OP", "This memory operation is illegal in HMPL."),
    (0x138c, "eERR_HMPL_MOTION_NOT_READY", "Controller state not ready; cannot execute this HMPL."),
    (0x138d, "eERR_HMPL_STR_TOO_LONG", "String length exceeds limit."),
    (0x138e, "eERR_HMPL_INVALID_STR_FORMAT", "String format error."),
    (0x138f, "eERR_HMPL_ARG_OUT_OF_RANGE", "Input argument out of range."),
    (0x1392, "eERR_HMPL_ASCII_AGENT_RUNNING", "ASCII agent running; cannot run multiple ASCII agents at once."),
    (0x139c, "eERR_HMPL_CANNOT_RUN_IN_DEBUG", "This HMPL function cannot run in debug mode."),
    (0x13a6, "eERR_HMPL_TOO_MANY_BRK_POINT", "This task has too many breakpoints."),
    (0x13ec, "eERR_HMPL_MUTEX_LOCK_TWICE", "Locking an already-locked mutex again."),
    (0x1450, "eERR_HMPL_INVALID_SYS_TIME_MEMORY", "Memory too small, at least 30 Bytes required."),
    (0x1451, "eERR_HMPL_NOT_SUPPORTED", "This HMPL function is not supported on this platform."),
    (0x1452, "eERR_HMPL_CLIENT_NOT_CONNECTED", "Cannot connect to client."),
    (0x14b4, "eERR_HMPL_NOT_IN_OP_MODE", "This HMPL function cannot run in non-synchronous (non-operational) state."),
    (0x176f, "eERR_HMPL_INTERNAL_ERROR", "HMPL internal error."),
    (0x1770, "eERR_HMPL_EXEC_FAILED", "HMPL execution failed."),
    (0x1771, "eERR_HMPL_ASM_LOAD_FAILED", "HMPL compile failed; assembly file missing or not generated."),
    (0x1772, "eERR_HMPL_STARTTASK_TIMEOUT", "HMPL StartTask function timed out."),
    (0x1773, "eERR_HMPL_STOPTASK_TIMEOUT", "HMPL StopTask function timed out."),
    (0x17d4, "eERR_ASCII_CONNECT_TIMEOUT", "ASCII client connect timeout."),
    (0x17d5, "eERR_ASCII_CONNECT_FAILED", "ASCII client connect failed; check ip and port."),
    (0x17d6, "eERR_ASCII_MULTI_CONNECTING", "Multiple ASCII clients connecting simultaneously."),
    (0x17d7, "eERR_ASCII_MULTI_DISCONNECTING", "Multiple ASCII clients disconnecting simultaneously."),
    (0x17d8, "eERR_ASCII_DISCONNECT_TIMEOUT", "ASCII client disconnect timeout."),
    (0x17de, "eERR_ASCII_RECV_TIMEOUT", "ASCII client receive timeout; retry later."),
    (0x17df, "eERR_ASCII_RECV_FAIL", "ASCII client receive failed; check connection."),
    (0x17e0, "eERR_ASCII_MULTI_RECVING", "Multiple ASCII clients receiving simultaneously."),
    (0x17e8, "eERR_ASCII_SEND_TIMEOUT", "ASCII client send timeout; retry later."),
    (0x17e9, "eERR_ASCII_SEND_FAIL", "ASCII client send failed; check connection."),
    (0x17ea, "eERR_ASCII_MULTI_SENDING", "Multiple ASCII clients sending simultaneously."),
    (0x1838, "eERR_MODBUS_CONNECT_TIMEOUT", "Modbus client connect timeout."),
    (0x1839, "eERR_MODBUS_CONNECT_FAILED", "Modbus client connect failed; check ip."),
    (0x183a, "eERR_MODBUS_MULTI_CONNECTING", "Multiple Modbus clients connecting simultaneously."),
    (0x183b, "eERR_MODBUS_MULTI_DISCONNECTING", "Multiple Modbus clients disconnecting simultaneously."),
    (0x183c, "eERR_MODBUS_DISCONNECT_TIMEOUT", "Modbus client disconnect timeout."),
    (0x183d, "eERR_MODBUS_DATALENGTH_ERR", "Modbus client read/write data count exceeds the limit."),
    (0x183e, "eERR_MODBUS_SOCKET_BUSY", "Modbus client handling two or more commands at once."),
    (0x183f, "eERR_MODBUS_JOB_TIMEOUT", "Modbus client job timeout; retry later."),
    (0x1840, "eERR_MODBUS_JOB_FAIL", "Modbus client job failed; check connection."),
    (0xb037, "eMSG_HIMC_SET_DEFAULT", "Restore factory defaults."),
    (0xb038, "eMSG_HIMC_REBOOT", "Reboot controller."),
    (0xb039, "eMSG_HIMC_BOOT", "Controller boot."),
    (0xb03a, "eMSG_HIMC_INFO", "Controller information."),
    (0xb03b, "eMSG_HIMC_STORE_CONFIG", "Store controller configuration."),
    (0xb03e, "eMSG_API_MAIN_ID_CHANGE_GET", "Acquire access priority."),
    (0xb03f, "eMSG_API_MAIN_ID_CHANGE_RELEASE", "Release access priority."),
    (0xb2c8, "eMSG_START_HMI_SCOPE", "Start scope (HMI) monitoring."),
    (0xb2c9, "eMSG_STOP_HMI_SCOPE", "Stop scope (HMI) monitoring."),
    (0x3fff, "eERR_SYS_LOG", "Controller error (log)."),
    (0x7fff, "eWRN_SYS_LOG", "Controller warning (log)."),
    (0xbfff, "eMSG_SYS_LOG", "Controller message (log)."),
    (0xffff, "eDBG_SYS_LOG", "Controller debug (log)."),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_system_table_is_the_manuals() {
        assert_eq!(SYSTEM_ERRORS.len(), 79, "digest 004 §5: 79 system entries");
        let mut values: Vec<u16> = SYSTEM_ERRORS.iter().map(|e| e.value).collect();
        values.sort_unstable();
        values.dedup();
        assert_eq!(values.len(), SYSTEM_ERRORS.len(), "values are unique");
        for (code, name) in [
            (HCV_ID_NOT_FOUND, "eERR_HCV_ID_NOT_FOUND"),
            (HMPL_INVALID_ARG, "eERR_HMPL_INVALID_ARG"),
            (HMPL_STR_TOO_LONG, "eERR_HMPL_STR_TOO_LONG"),
            (HMPL_INVALID_STR_FORMAT, "eERR_HMPL_INVALID_STR_FORMAT"),
            (HMPL_ARG_OUT_OF_RANGE, "eERR_HMPL_ARG_OUT_OF_RANGE"),
            (HMPL_NOT_SUPPORTED, "eERR_HMPL_NOT_SUPPORTED"),
            (HMPL_INTERNAL_ERROR, "eERR_HMPL_INTERNAL_ERROR"),
        ] {
            assert_eq!(
                SystemError::by_name(name).map(SystemError::code),
                Some(code)
            );
        }
    }
}
