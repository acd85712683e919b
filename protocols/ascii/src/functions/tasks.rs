//! Chapter 16, HMPL tasks (digest 004 §2.15): mcemu loads no HMPL programs, so the controller's
//! 64 tasks (0–63) are all empty and stopped. Each function answers what the HIMC answers for
//! an empty task: `StartTask` → `eERR_TASK_EMPTY`, `StartTaskFunc` → `eERR_FUNC_NOT_IN_TASK`,
//! `StopTask` → `eERR_TASK_NOT_RUNNING`, `IsTaskStop` → TRUE, `StopAllTask` does nothing; a
//! task id outside 0–63 is `eERR_NOT_VALID_TASKID`.

use mcemu_dialects::himc::system::SystemError;

use crate::reply::Outcome;
use crate::table::{row, Addresses::Controller, Args, Ctx, Function, Plan, Ret, Ty};

/// §16.1: 64 tasks.
const TASKS: i64 = 64;

/// The code of system error `name` (a name from the table: 0 would be a bug the tests catch).
fn code(name: &str) -> u32 {
    SystemError::by_name(name).map_or(0, SystemError::code)
}

/// `Err(eERR_NOT_VALID_TASKID)` unless argument 0 names one of the 64 tasks.
fn task(args: &Args) -> Result<i64, u32> {
    let id = args.int(0);
    if (0..TASKS).contains(&id) {
        Ok(id)
    } else {
        Err(code("eERR_NOT_VALID_TASKID"))
    }
}

/// A valid task fails with `empty_task`, as every task here is empty.
fn fails_with(args: &Args, empty_task: &str) -> Plan {
    Plan::Fail(task(args).map_or_else(|c| c, |_| code(empty_task)))
}

pub static ROWS: &[Function] = &[
    row(
        "StartTask",
        "16.2",
        &[Ty::Int],
        Ret::Int,
        Controller,
        |_, a| fails_with(a, "eERR_TASK_EMPTY"),
    ),
    row(
        "StartTaskFunc",
        "16.3",
        &[Ty::Int, Ty::Str],
        Ret::Int,
        Controller,
        |_, a| fails_with(a, "eERR_FUNC_NOT_IN_TASK"),
    ),
    row(
        "StopTask",
        "16.4",
        &[Ty::Int],
        Ret::Int,
        Controller,
        |_, a| fails_with(a, "eERR_TASK_NOT_RUNNING"),
    ),
    row("StopAllTask", "16.5", &[], Ret::Void, Controller, |_, _| {
        Plan::Done(Outcome::Void)
    }),
    row(
        "IsTaskStop",
        "16.6",
        &[Ty::Int],
        Ret::Int,
        Controller,
        is_task_stop,
    ),
];

fn is_task_stop(_: &mut Ctx<'_>, args: &Args) -> Plan {
    match task(args) {
        Ok(_) => Plan::Done(Outcome::bool(true)),
        Err(c) => Plan::Fail(c),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_named_here_is_in_the_system_table() {
        for name in [
            "eERR_NOT_VALID_TASKID",
            "eERR_TASK_EMPTY",
            "eERR_FUNC_NOT_IN_TASK",
            "eERR_TASK_NOT_RUNNING",
        ] {
            assert_ne!(code(name), 0, "{name}");
        }
    }
}
