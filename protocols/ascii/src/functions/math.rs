//! Chapter 4, math functions (digest 004 §2.3, TV 88), computed as C's libm does.

use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Controller, Function, Plan, Ret, Ty};

const D: &[Ty] = &[Ty::Double];
const DD: &[Ty] = &[Ty::Double, Ty::Double];

fn d(x: f64) -> Plan {
    Plan::Done(Outcome::Double(x))
}

/// `ldexp(x, y)` = x·2^y, `y` an int (§4.12, printed "Idexp").
fn ldexp(x: f64, y: i64) -> f64 {
    x * 2f64.powi(i32::try_from(y.clamp(-2000, 2000)).unwrap_or(0))
}

pub static ROWS: &[Function] = &[
    row("sin", "4.1", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).sin())
    }),
    row("cos", "4.2", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).cos())
    }),
    row("tan", "4.3", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).tan())
    }),
    row("asin", "4.4", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).asin())
    }),
    row("acos", "4.5", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).acos())
    }),
    row("atan", "4.6", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).atan())
    }),
    row("atan2", "4.7", DD, Ret::Double, Controller, |_, a| {
        d(a.double(0).atan2(a.double(1)))
    }),
    unary("abs", "4.8", Ret::Int, Controller, |_, a| {
        Plan::Done(Outcome::Int((a.int(0) as i32).wrapping_abs()))
    }),
    row("fabs", "4.9", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).abs())
    }),
    row("ceil", "4.10", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).ceil())
    }),
    row("floor", "4.11", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).floor())
    }),
    row(
        "ldexp",
        "4.12",
        &[Ty::Double, Ty::Int],
        Ret::Double,
        Controller,
        |_, a| d(ldexp(a.double(0), a.int(1))),
    ),
    row(
        "Idexp",
        "4.12",
        &[Ty::Double, Ty::Int],
        Ret::Double,
        Controller,
        |_, a| d(ldexp(a.double(0), a.int(1))),
    ),
    // §4.13, §4.14: the largest double on overflow.
    row("exp", "4.13", D, Ret::Double, Controller, |_, a| {
        d(finite_or_max(a.double(0).exp()))
    }),
    row("pow", "4.14", DD, Ret::Double, Controller, |_, a| {
        d(finite_or_max(a.double(0).powf(a.double(1))))
    }),
    row("log", "4.15", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).ln())
    }),
    row("log10", "4.16", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).log10())
    }),
    row("sqrt", "4.17", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).sqrt())
    }),
    row("cbrt", "4.18", D, Ret::Double, Controller, |_, a| {
        d(a.double(0).cbrt())
    }),
    row("hypot", "4.19", DD, Ret::Double, Controller, |_, a| {
        d(finite_or_max(a.double(0).hypot(a.double(1))))
    }),
];

fn finite_or_max(x: f64) -> f64 {
    if x == f64::INFINITY {
        f64::MAX
    } else if x == f64::NEG_INFINITY {
        -f64::MAX
    } else {
        x
    }
}
