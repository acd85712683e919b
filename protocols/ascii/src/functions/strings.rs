//! Chapter 3, the icon-marked string functions (digest 004 §2.2, TV 85), computed.

use crate::reply::Outcome;
use crate::table::{row, Addresses::Controller, Args, Ctx, Function, Plan, Ret, Ty};

pub static ROWS: &[Function] = &[
    row(
        "StringLen",
        "3.4",
        &[Ty::Str],
        Ret::Int,
        Controller,
        |_, a| int(a.str(0).len()),
    ),
    row(
        "IsStringEqual",
        "3.5",
        &[Ty::Str, Ty::Str],
        Ret::Int,
        Controller,
        |_, a| Plan::Done(Outcome::bool(a.str(0) == a.str(1))),
    ),
    row(
        "StrFindCharEx",
        "3.7",
        &[Ty::Str, Ty::Str, Ty::Int],
        Ret::Int,
        Controller,
        find_char_ex,
    ),
    row(
        "StrFindStr",
        "3.8",
        &[Ty::Str, Ty::Str],
        Ret::Int,
        Controller,
        |_, a| offset(a.str(0).find(a.str(1))),
    ),
    row(
        "StringToDouble",
        "3.13",
        &[Ty::Str],
        Ret::Double,
        Controller,
        |_, a| Plan::Done(Outcome::Double(atof(a.str(0)))),
    ),
];

fn int(n: usize) -> Plan {
    Plan::Done(Outcome::Int(i32::try_from(n).unwrap_or(i32::MAX)))
}

/// A byte offset, or −1 for none.
fn offset(at: Option<usize>) -> Plan {
    at.map_or(Plan::Done(Outcome::Int(-1)), int)
}

/// §3.7: the first character in the set (`complement_set` = 0) or not in it (≠ 0).
fn find_char_ex(_: &mut Ctx<'_>, a: &Args) -> Plan {
    let (s, set, complement) = (a.str(0).as_bytes(), a.str(1).as_bytes(), a.int(2) != 0);
    offset(s.iter().position(|c| set.contains(c) != complement))
}

/// C's `atof`: the longest leading number, 0 when there is none.
fn atof(s: &str) -> f64 {
    let s = s.trim_start();
    (1..=s.len())
        .rev()
        .filter(|&end| s.is_char_boundary(end))
        .find_map(|end| s.get(..end).and_then(|p| p.parse::<f64>().ok()))
        .filter(|d| d.is_finite())
        .unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atof_reads_the_leading_number() {
        assert_eq!(atof("1.234"), 1.234);
        assert_eq!(atof("  -2.5e1xyz"), -25.0);
        assert_eq!(atof("abc"), 0.0);
    }
}
