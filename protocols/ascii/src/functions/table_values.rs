//! Chapter 11, the user table (digest 004 §2.10; TV 59–60): 512 000 doubles in the
//! controller's RAM (`Registers::user_table`, sparse: unset entries are 0), and a saved copy
//! standing in for the HIMC's disk, which `SaveUserTable` writes and `LoadUserTable` reads back.
//! Compensation tables (chapter 14) take their values from it.

use std::collections::BTreeMap;

use mcemu_dialects::himc::system::HMPL_ARG_OUT_OF_RANGE;

use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Controller, Args, Function, Plan, Ret, Ty};

/// Entries of the user table (§11.1: `system_user_table[512000]`).
pub const USER_TABLE_LEN: u32 = 512_000;

/// Entry `i` of the table, if it exists.
pub(crate) fn index(i: i64) -> Result<u32, u32> {
    u32::try_from(i)
        .ok()
        .filter(|&i| i < USER_TABLE_LEN)
        .ok_or(HMPL_ARG_OUT_OF_RANGE)
}

/// Entries `start … start + n − 1`, if they all exist and n ≥ 1.
pub(crate) fn span(args: &Args) -> Result<std::ops::Range<u32>, u32> {
    let start = index(args.int(0))?;
    let n = u32::try_from(args.int(1))
        .ok()
        .filter(|&n| n >= 1 && n <= USER_TABLE_LEN - start)
        .ok_or(HMPL_ARG_OUT_OF_RANGE)?;
    Ok(start..start + n)
}

pub static ROWS: &[Function] = &[
    row(
        "SetTableValue",
        "11.4",
        &[Ty::Int, Ty::Double],
        Ret::Int,
        Controller,
        |cx, a| match index(a.int(0)) {
            Ok(i) if a.double(1).is_finite() => {
                cx.registers.user_table.insert(i, a.double(1));
                Plan::Done(Outcome::Int(0))
            }
            Ok(_) => Plan::Fail(HMPL_ARG_OUT_OF_RANGE),
            Err(c) => Plan::Fail(c),
        },
    ),
    // TV 59.
    unary(
        "GetTableValue",
        "11.5",
        Ret::Double,
        Controller,
        |cx, a| match index(a.int(0)) {
            Ok(i) => Plan::Done(Outcome::Double(
                cx.registers.user_table.get(&i).copied().unwrap_or(0.0),
            )),
            Err(c) => Plan::Fail(c),
        },
    ),
    // TV 60: save a span, overwrite it, load it back.
    row(
        "SaveUserTable",
        "11.6",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Controller,
        |cx, a| {
            let r = &mut *cx.registers;
            copy_span(a, &r.user_table, &mut r.saved_user_table)
        },
    ),
    row(
        "LoadUserTable",
        "11.7",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Controller,
        |cx, a| {
            let r = &mut *cx.registers;
            copy_span(a, &r.saved_user_table, &mut r.user_table)
        },
    ),
];

/// Make entries `args[0] … + args[1]` of `to` those of `from` (absent ones absent: 0).
fn copy_span(args: &Args, from: &BTreeMap<u32, f64>, to: &mut BTreeMap<u32, f64>) -> Plan {
    match span(args) {
        Ok(r) => {
            to.retain(|i, _| !r.contains(i));
            to.extend(from.range(r).map(|(&i, &v)| (i, v)));
            Plan::Done(Outcome::Int(0))
        }
        Err(c) => Plan::Fail(c),
    }
}
