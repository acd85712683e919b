//! Chapter 2, system functions (digest 004 §2.1). mcemu's machine is always in operation with
//! its EtherCAT (its drives) in Operation: `IsSystemOper` is 1, `GetECATSt` 8.

use serde_json::json;

use super::engine;
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Controller, Args, Ctx, Function, Plan, Ret};
use mcemu_dialects::himc::system::HMPL_ARG_OUT_OF_RANGE;

/// EtherCAT state Operation (§2.5: 1 Init, 2 Pre-Op, 4 Safe-Op, 8 Op).
const ECAT_OP: i32 = 8;

pub static ROWS: &[Function] = &[
    row("IsSystemInit", "2.1", &[], Ret::Int, Controller, |_, _| {
        done(0)
    }),
    row("IsSystemOper", "2.2", &[], Ret::Int, Controller, |_, _| {
        done(1)
    }),
    row("IsSystemPreOp", "2.3", &[], Ret::Int, Controller, |_, _| {
        done(0)
    }),
    row("IsSystemError", "2.4", &[], Ret::Int, Controller, |_, _| {
        done(0)
    }),
    row("GetECATSt", "2.5", &[], Ret::Int, Controller, |_, _| {
        done(ECAT_OP)
    }),
    unary("GetSlvECATSt", "2.6", Ret::Int, Controller, slave_state),
    row("DisableAll", "2.7", &[], Ret::Int, Controller, |_, _| {
        engine(json!({"type": "disable_all"}))
    }),
    // §2.8: the kill deceleration, axes stay enabled.
    row("StopAll", "2.8", &[], Ret::Int, Controller, |_, _| {
        engine(json!({"type": "stop_all", "mode": "abrupt"}))
    }),
    row("EStop", "2.9", &[], Ret::Void, Controller, |_, _| {
        engine(json!({"type": "emergency_stop_all"}))
    }),
    row("GetSlaveNum", "2.10", &[], Ret::Int, Controller, |cx, _| {
        done(i32::try_from(super::slave::slave_count(cx)).unwrap_or(i32::MAX))
    }),
    row("ScanNetwork", "2.16", &[], Ret::Int, Controller, |_, _| {
        done(0)
    }),
    unary("SetHMIScope", "2.17", Ret::Int, Controller, |_, _| done(0)),
    unary("SendEvent", "2.19", Ret::Int, Controller, |_, _| done(0)),
    row(
        "RunScheduler",
        "2.21",
        &[],
        Ret::Void,
        Controller,
        |_, _| Plan::Done(Outcome::Void),
    ),
];

fn done(i: i32) -> Plan {
    Plan::Done(Outcome::Int(i))
}

fn slave_state(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let exists = super::slave::slave(cx, args.int(0)).is_ok();
    if exists {
        done(ECAT_OP)
    } else {
        Plan::Fail(HMPL_ARG_OUT_OF_RANGE)
    }
}
