//! Chapter 18, error functions (digest 004 §2.17, TV 71–73). An axis's last error is its
//! standing fault if it has one (a software-limit hit, TV 71: 0x830207da), else the last code
//! a call latched, else the engine's last refusal of that axis (from any front-end).

use axes::AxisFlags;
use mcemu_dialects::himc::code_for_kind;

use super::{axis_error, axis_of};
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses, Args, Ctx, Function, Plan, Ret};

fn code(c: u32) -> Plan {
    Plan::Done(Outcome::code(c))
}

/// The standing fault's code, in the order the HIMC reports them (§3.6).
fn fault_code(axis: u16, flags: AxisFlags) -> Option<u32> {
    let faults = [
        (AxisFlags::DRIVE_ALARM, "eERR_AXIS_DRIVE_FAULT"),
        (AxisFlags::FE_FAULT, "eERR_AXIS_PERR"),
        (AxisFlags::COMPENSATION_LIMIT, "eERR_AXIS_COMP_LIMIT"),
        (AxisFlags::SW_LIMIT_POS, "eERR_AXIS_SWRL"),
        (AxisFlags::SW_LIMIT_NEG, "eERR_AXIS_SWLL"),
        (AxisFlags::HW_LIMIT_POS, "eERR_AXIS_HWRL"),
        (AxisFlags::HW_LIMIT_NEG, "eERR_AXIS_HWLL"),
    ];
    faults
        .iter()
        .find(|(f, _)| flags.contains(*f))
        .map(|(_, name)| axis_error(axis, name))
}

fn axis_last(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let (axis, s) = match axis_of(cx, args) {
        Ok(a) => a,
        Err(c) => return Plan::Fail(c),
    };
    let standing = fault_code(axis, s.flags | s.latched);
    let latched = cx.registers.axis_errors.get(&axis).copied();
    let engine = s
        .last_error
        .and_then(code_for_kind)
        .map(|e| e.code(u8::try_from(axis).unwrap_or(u8::MAX)));
    code(standing.or(latched).or(engine).unwrap_or(0))
}

pub static ROWS: &[Function] = &[
    row(
        "GetSystemLastErr",
        "18.2",
        &[],
        Ret::Int,
        Addresses::Controller,
        |cx, _| code(cx.registers.system_error),
    ),
    unary(
        "GetAxisLastErr",
        "18.3",
        Ret::Int,
        Addresses::Axis,
        axis_last,
    ),
    unary(
        "ClearAxisLastErr",
        "18.4",
        Ret::Int,
        Addresses::Axis,
        |cx, a| match axis_of(cx, a) {
            Ok((axis, _)) => {
                cx.registers.axis_errors.remove(&axis);
                code(0)
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    unary(
        "GetGrpLastErr",
        "18.5",
        Ret::Int,
        Addresses::Group,
        |cx, a| {
            let group = u16::try_from(a.int(0)).unwrap_or(u16::MAX);
            code(cx.registers.group_errors.get(&group).copied().unwrap_or(0))
        },
    ),
    unary(
        "ClearGrpLastErr",
        "18.6",
        Ret::Int,
        Addresses::Group,
        |cx, a| {
            let group = u16::try_from(a.int(0)).unwrap_or(u16::MAX);
            cx.registers.group_errors.remove(&group);
            code(0)
        },
    ),
    // The drive's own code (0x603F) where the axis has a CiA 402 drive, else 0.
    unary(
        "GetDriveErr",
        "18.7",
        Ret::Int,
        Addresses::Axis,
        |cx, a| match axis_of(cx, a) {
            Ok((axis, _)) => {
                let drive = cx.snapshot.drives.iter().find(|d| d.axis == axis);
                code(drive.map_or(0, |d| u32::from(d.error_code)))
            }
            Err(c) => Plan::Fail(c),
        },
    ),
];
