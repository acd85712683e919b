//! Chapter 14, dynamic error compensation (digest 004 §2.13; TV 61–63) through the engine's
//! grid tables: `SetupComp` reads `num_pt` values of the user table (chapter 11) from
//! `start_idx` into a 1-D `compensation_table` over the reference axis's planned position
//! (linear between points, the end values held beyond), stored switched off; `EnableComp` and
//! `DisableComp` switch it (only while the axis is disabled), `DisableComp` also clears it.
//! `SetCompAlgType(axis, 1)` makes the table a natural cubic spline (the engine's
//! `interpolation: "cubic"`), `0` linear again: for the next `SetupComp`, and for the table
//! already set up, which is sent again with the new interpolation. TV 63: the engine's
//! `compensation_limit` (HCV `max_comp_lim`, 1 mm in `fixtures/himc.toml`) refuses an
//! `EnableComp` over it with `eERR_AXIS_COMP_LIMIT` and stops an axis that goes over it.

use axes::status::AxisFlags;
use serde_json::json;

use super::gear::axis_arg;
use super::table_values::index;
use super::{axis_error, axis_of, engine};
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Axis, Args, Ctx, Function, Plan, Ret, Ty};

/// The axis, refused while enabled (§14.2–14.3, TV 62).
fn disabled_axis(cx: &Ctx<'_>, args: &Args) -> Result<u16, u32> {
    let (a, s) = axis_of(cx, args)?;
    if s.flags.contains(AxisFlags::ENABLED) {
        return Err(axis_error(a, "eERR_AXIS_CMD_INVALID_ENABLED"));
    }
    Ok(a)
}

/// §14.4: `SetupComp(axis_id, start_idx, base_val, interval, num_pt, ref_axis_id)`.
fn setup(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let a = match axis_of(cx, args) {
        Ok((a, _)) => a,
        Err(c) => return Plan::Fail(c),
    };
    let reference = match axis_arg(cx, args, 5) {
        Ok(r) => r,
        Err(c) => return Plan::Fail(c),
    };
    let (base, interval) = (args.double(2), args.double(3));
    let count = u32::try_from(args.int(4)).ok().filter(|&n| n >= 2);
    let start = index(args.int(1)).ok();
    let (Some(count), Some(start)) = (count, start) else {
        return Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_PARAMETER"));
    };
    let grid_ok = base.is_finite() && interval.is_finite() && interval > 0.0;
    if !grid_ok || index(i64::from(start) + i64::from(count) - 1).is_err() {
        return Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_PARAMETER"));
    }
    let values: Vec<f64> = (start..start + count)
        .map(|i| cx.registers.user_table.get(&i).copied().unwrap_or(0.0))
        .collect();
    let table = json!({
        "type": "compensation_table", "axis": a, "references": [{"axis": reference}],
        "start": [base], "step": [interval], "count": [count], "values": values,
        "enable": false, "interpolation": interpolation(cx, a),
    });
    cx.registers.compensation_tables.insert(a, table.clone());
    engine(table)
}

fn interpolation(cx: &Ctx<'_>, axis: u16) -> &'static str {
    if cx.registers.compensation_cubic.contains(&axis) {
        "cubic"
    } else {
        "linear"
    }
}

/// §14.8: 0 first-order linear (the default), 1 cubic spline.
fn set_algorithm(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let a = match axis_of(cx, args) {
        Ok((a, _)) => a,
        Err(c) => return Plan::Fail(c),
    };
    match args.int(1) {
        0 => cx.registers.compensation_cubic.remove(&a),
        1 => cx.registers.compensation_cubic.insert(a),
        _ => return Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_PARAMETER")),
    };
    let algorithm = interpolation(cx, a);
    let enabled = cx.registers.compensating.contains(&a);
    match cx.registers.compensation_tables.get_mut(&a) {
        Some(table) => {
            table["interpolation"] = json!(algorithm);
            table["enable"] = json!(enabled);
            engine(table.clone())
        }
        None => Plan::Done(Outcome::Int(0)),
    }
}

pub static ROWS: &[Function] = &[
    unary(
        "EnableComp",
        "14.2",
        Ret::Int,
        Axis,
        |cx, a| match disabled_axis(cx, a) {
            Ok(x) => {
                cx.registers.compensating.insert(x);
                engine(json!({"type": "compensation_enable", "axis": x}))
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    unary(
        "DisableComp",
        "14.3",
        Ret::Int,
        Axis,
        |cx, a| match disabled_axis(cx, a) {
            Ok(x) => {
                cx.registers.compensating.remove(&x);
                cx.registers.compensation_tables.remove(&x);
                let batch: Result<Vec<axes::Command>, _> =
                    ["compensation_disable", "compensation_clear"]
                        .iter()
                        .map(|t| serde_json::from_value(json!({"type": t, "axis": x})))
                        .collect();
                match batch {
                    Ok(b) => Plan::Engine(b, crate::table::Then::Succeed),
                    Err(_) => Plan::Fail(mcemu_dialects::himc::system::HMPL_INTERNAL_ERROR),
                }
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    row(
        "SetupComp",
        "14.4",
        &[Ty::Int, Ty::Int, Ty::Double, Ty::Double, Ty::Int, Ty::Int],
        Ret::Int,
        Axis,
        setup,
    ),
    // TV 61: the correction sent to the drive.
    unary("GetCompPos", "14.7", Ret::Double, Axis, |cx, a| {
        super::get_status(cx, a, |s| s.compensation)
    }),
    row(
        "SetCompAlgType",
        "14.8",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Axis,
        set_algorithm,
    ),
];
