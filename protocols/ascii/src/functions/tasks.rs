//! Chapter 16, HMPL tasks (digest 004 §2.15): mcemu runs no HMPL programs, so, as issue 14
//! says, each task function answers `eERR_HMPL_NOT_SUPPORTED` (latched in `GetSystemLastErr`)
//! after its arguments are checked like any other call's. The rows are here so that a task call
//! with wrong arguments gets the argument error a controller gives.

use mcemu_dialects::himc::system::SystemError;

use crate::table::{row, unary, Addresses::Controller, Args, Ctx, Function, Plan, Ret, Ty};

/// Every task function: not supported.
fn not_supported(_: &mut Ctx<'_>, _: &Args) -> Plan {
    Plan::Fail(SystemError::by_name("eERR_HMPL_NOT_SUPPORTED").map_or(0, SystemError::code))
}

pub static ROWS: &[Function] = &[
    unary("StartTask", "16.2", Ret::Int, Controller, not_supported),
    row(
        "StartTaskFunc",
        "16.3",
        &[Ty::Int, Ty::Str],
        Ret::Int,
        Controller,
        not_supported,
    ),
    unary("StopTask", "16.4", Ret::Int, Controller, not_supported),
    // `void` in the manual; `Int` here so that the refusal is answered (a void call replies 0).
    row(
        "StopAllTask",
        "16.5",
        &[],
        Ret::Int,
        Controller,
        not_supported,
    ),
    unary("IsTaskStop", "16.6", Ret::Int, Controller, not_supported),
];

#[cfg(test)]
mod tests {
    use mcemu_dialects::himc::system::SystemError;

    #[test]
    fn the_code_named_here_is_in_the_system_table() {
        assert_eq!(
            SystemError::by_name("eERR_HMPL_NOT_SUPPORTED").map(SystemError::code),
            Some(0x1451)
        );
    }
}
