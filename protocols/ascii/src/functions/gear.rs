//! Chapter 6, the electronic gear (digest 004 §2.5, §6.2–6.9; TV 34–35) through the engine's
//! couplings (`gear_in`, `gear_set_ratio`, `gear_out`). HIMC links a master and a slave first
//! (`EnableGear`, both enabled), then engages with a ratio (`GearIn`); a gear command on a
//! slave that is not linked is `eERR_AXIS_CMD_GEAR_DISABLED`. The links are the controller's
//! (`Registers::gear_links`); the engagement and the ratio are the engine's.

use axes::status::{AxisFlags, CouplingKind, CouplingStatus};
use mcemu_dialects::himc::system::HMPL_ARG_OUT_OF_RANGE;
use serde_json::json;

use super::{axis_error, engine};
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Axis, Args, Ctx, Function, Plan, Ret, Ty};

const AA: &[Ty] = &[Ty::Int, Ty::Int];

/// Argument `i` as an existing axis.
pub(crate) fn axis_arg(cx: &Ctx<'_>, args: &Args, i: usize) -> Result<u16, u32> {
    u16::try_from(args.int(i))
        .ok()
        .filter(|&a| usize::from(a) < cx.snapshot.axes.len())
        .ok_or(HMPL_ARG_OUT_OF_RANGE)
}

pub(crate) fn enabled(cx: &Ctx<'_>, axis: u16) -> bool {
    cx.snapshot
        .axes
        .get(usize::from(axis))
        .is_some_and(|s| s.flags.contains(AxisFlags::ENABLED))
}

/// The engaged gear whose slave `axis` is.
fn gear_of<'a>(cx: &'a Ctx<'_>, axis: u16) -> Option<&'a CouplingStatus> {
    cx.snapshot
        .couplings
        .iter()
        .find(|c| c.slave == axis && c.kind == CouplingKind::Gear)
}

/// §6.2, TV 35: link `master` and `slave`; both must be enabled.
fn enable_gear(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let (master, slave) = match (axis_arg(cx, args, 0), axis_arg(cx, args, 1)) {
        (Ok(m), Ok(s)) => (m, s),
        (Err(c), _) | (_, Err(c)) => return Plan::Fail(c),
    };
    if master == slave {
        return Plan::Fail(axis_error(slave, "eERR_AXIS_CMD_INVALID_SLAVE_ID"));
    }
    for axis in [master, slave] {
        if !enabled(cx, axis) {
            return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_DISABLED"));
        }
    }
    match cx.registers.gear_links.get(&slave) {
        Some(&m) if m != master => Plan::Fail(axis_error(
            slave,
            "eERR_AXIS_CMD_INVALID_MASTER_SLAVE_CONNECTION",
        )),
        _ => {
            cx.registers.gear_links.insert(slave, master);
            Plan::Done(Outcome::Int(0))
        }
    }
}

/// The master `slave` is linked to, or the gear-disabled code.
fn linked(cx: &Ctx<'_>, slave: u16) -> Result<u16, u32> {
    cx.registers
        .gear_links
        .get(&slave)
        .copied()
        .ok_or(axis_error(slave, "eERR_AXIS_CMD_GEAR_DISABLED"))
}

/// §6.4, TV 34: engage (or change the ratio of an engaged gear), any finite non-zero ratio.
fn gear_in(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let (master, slave) = match (axis_arg(cx, args, 0), axis_arg(cx, args, 1)) {
        (Ok(m), Ok(s)) => (m, s),
        (Err(c), _) | (_, Err(c)) => return Plan::Fail(c),
    };
    match linked(cx, slave) {
        Ok(m) if m == master => {}
        Ok(_) => {
            return Plan::Fail(axis_error(
                slave,
                "eERR_AXIS_CMD_INVALID_MASTER_SLAVE_CONNECTION",
            ))
        }
        Err(c) => return Plan::Fail(c),
    }
    let ratio = args.double(2);
    if !ratio.is_finite() || ratio == 0.0 {
        return Plan::Fail(axis_error(slave, "eERR_AXIS_CMD_INVALID_GEAR_RATIO"));
    }
    cx.registers.gear_ratios.insert(slave, ratio);
    if gear_of(cx, slave).is_some() {
        engine(
            json!({"type": "gear_set_ratio", "slave": slave, "numerator": ratio, "denominator": 1.0}),
        )
    } else {
        engine(json!({
            "type": "gear_in", "master": master, "slave": slave,
            "numerator": ratio, "denominator": 1.0,
        }))
    }
}

/// §6.5: disengage; the slave keeps its velocity and ramps to rest (the engine's `gear_out`).
fn gear_out(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let slave = match axis_arg(cx, args, 0) {
        Ok(s) => s,
        Err(c) => return Plan::Fail(c),
    };
    if let Err(c) = linked(cx, slave) {
        return Plan::Fail(c);
    }
    if gear_of(cx, slave).is_none() {
        return Plan::Fail(axis_error(slave, "eERR_AXIS_CMD_INVALID_STATE"));
    }
    engine(json!({"type": "gear_out", "slave": slave}))
}

/// §6.3: unlink, disengaging first.
fn disable_gear(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let slave = match axis_arg(cx, args, 0) {
        Ok(s) => s,
        Err(c) => return Plan::Fail(c),
    };
    if let Err(c) = linked(cx, slave) {
        return Plan::Fail(c);
    }
    cx.registers.gear_links.remove(&slave);
    if gear_of(cx, slave).is_some() {
        engine(json!({"type": "gear_out", "slave": slave}))
    } else {
        Plan::Done(Outcome::Int(0))
    }
}

fn axis_bool(cx: &mut Ctx<'_>, args: &Args, f: fn(&Ctx<'_>, u16) -> bool) -> Plan {
    match axis_arg(cx, args, 0) {
        Ok(a) => Plan::Done(Outcome::bool(f(cx, a))),
        Err(c) => Plan::Fail(c),
    }
}

pub static ROWS: &[Function] = &[
    row("EnableGear", "6.2", AA, Ret::Int, Axis, enable_gear),
    unary("DisableGear", "6.3", Ret::Int, Axis, disable_gear),
    row(
        "GearIn",
        "6.4",
        &[Ty::Int, Ty::Int, Ty::Double],
        Ret::Int,
        Axis,
        gear_in,
    ),
    unary("GearOut", "6.5", Ret::Int, Axis, gear_out),
    // The engaged ratio, else the last one given, else 0.
    unary(
        "GetGearRatio",
        "6.6",
        Ret::Double,
        Axis,
        |cx, a| match axis_arg(cx, a, 0) {
            Ok(s) => {
                let ratio = gear_of(cx, s)
                    .map(|c| c.ratio)
                    .or_else(|| cx.registers.gear_ratios.get(&s).copied())
                    .unwrap_or(0.0);
                Plan::Done(Outcome::Double(ratio))
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    unary("IsInGear", "6.7", Ret::Int, Axis, |cx, a| {
        axis_bool(cx, a, |cx, s| gear_of(cx, s).is_some())
    }),
    unary("IsGearMaster", "6.8", Ret::Int, Axis, |cx, a| {
        axis_bool(cx, a, |cx, m| {
            cx.registers.gear_links.values().any(|&x| x == m)
                || cx
                    .snapshot
                    .couplings
                    .iter()
                    .any(|c| c.master == m && c.kind == CouplingKind::Gear)
        })
    }),
    unary("IsGearSlave", "6.9", Ret::Int, Axis, |cx, a| {
        axis_bool(cx, a, |cx, s| {
            cx.registers.gear_links.contains_key(&s) || gear_of(cx, s).is_some()
        })
    }),
];
