//! Chapter 5.4, axis status: the `Is*` predicates of `mcemu_dialects::himc::Predicate` over
//! the snapshot (digest 004 §2.4 "5.4").

use mcemu_dialects::himc::{AxisExtra, Predicate};

use super::axis_of;
use crate::reply::Outcome;
use crate::table::{unary, Addresses::Axis, Args, Ctx, Function, Plan, Ret};

fn holds(cx: &mut Ctx<'_>, args: &Args, p: Predicate) -> Plan {
    let cx: &Ctx<'_> = cx;
    match axis_of(cx, args) {
        Ok((axis, s)) => {
            let extra = AxisExtra {
                gantry: super::gantry::pair_of(cx, axis).is_some(),
                compensation: cx.registers.compensating.contains(&axis) || s.compensation != 0.0,
            };
            Plan::Done(Outcome::bool(p.holds(s, extra)))
        }
        Err(code) => Plan::Fail(code),
    }
}

macro_rules! predicates {
    ($(($name:literal, $section:literal, $p:ident),)*) => {
        pub static ROWS: &[Function] = &[
            $(unary($name, $section, Ret::Int, Axis, |cx, a| holds(cx, a, Predicate::$p)),)*
        ];
    };
}

predicates! {
    ("IsEnabled", "5.4.1", IsEnabled),
    ("IsMoving", "5.4.2", IsMoving),
    ("IsInPos", "5.4.3", IsInPos),
    ("IsErrorStop", "5.4.4", IsErrorStop),
    ("IsGantry", "5.4.5", IsGantry),
    ("IsGrouped", "5.4.6", IsGrouped),
    ("IsSync", "5.4.7", IsSync),
    ("IsHWLL", "5.4.8", IsHWLL),
    ("IsHWRL", "5.4.9", IsHWRL),
    ("IsSWLL", "5.4.10", IsSWLL),
    ("IsSWRL", "5.4.11", IsSWRL),
    ("IsDriveErr", "5.4.12", IsDriveErr),
    ("IsPosErr", "5.4.13", IsPosErr),
    ("IsCompActive", "5.4.14", IsCompActive),
    ("IsAcc", "5.4.15", IsAcc),
}
