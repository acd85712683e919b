//! Chapter 5.3, axis settings (digest 004 §2.4 "5.3"): getters read the snapshot, setters
//! check the HIMC's ranges (returning the axis error the manual names) and set the engine
//! parameter. Times are ms in HMPL, seconds in the engine (`himc::value_to_engine`).

use axes::{AxisState, ParamId};

use super::{axis_error, axis_of, get_param, get_status, param, set_param};
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Axis, Args, Ctx, Function, Plan, Ret, Ty};

const AD: &[Ty] = &[Ty::Int, Ty::Double];
const AI: &[Ty] = &[Ty::Int, Ty::Int];

/// A setter's check of its value: `Err(error name)` refuses it.
type Check = fn(f64) -> bool;

fn positive(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

fn finite(v: f64) -> bool {
    v.is_finite()
}

/// Set `id` after `check`; a refused value returns axis error `error`.
fn set_checked(cx: &mut Ctx<'_>, args: &Args, id: ParamId, check: Check, error: &str) -> Plan {
    match axis_of(cx, args) {
        Ok((axis, _)) if check(args.double(1)) => set_param(axis, id, args.double(1)),
        Ok((axis, _)) => Plan::Fail(axis_error(axis, error)),
        Err(code) => Plan::Fail(code),
    }
}

/// `Ignore*(axis, cmd)`: 1 ignores, 0 restores (§5.3.33–35).
fn set_flag(cx: &mut Ctx<'_>, args: &Args, id: ParamId) -> Plan {
    match axis_of(cx, args) {
        Ok((axis, _)) if matches!(args.int(1), 0 | 1) => set_param(axis, id, args.int(1) as f64),
        Ok((axis, _)) => Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_PARAMETER")),
        Err(code) => Plan::Fail(code),
    }
}

const PARAMETER: &str = "eERR_AXIS_CMD_INVALID_PARAMETER";

pub static ROWS: &[Function] = &[
    unary("GetVel", "5.3.1", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::Speed)
    }),
    // TV 24: non-zero positive.
    row("SetVel", "5.3.2", AD, Ret::Int, Axis, |cx, a| {
        set_checked(cx, a, ParamId::Speed, positive, "eERR_AXIS_CMD_INVALID_VEL")
    }),
    unary("GetAcc", "5.3.3", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::Accel)
    }),
    row("SetAcc", "5.3.4", AD, Ret::Int, Axis, |cx, a| {
        set_checked(cx, a, ParamId::Accel, positive, "eERR_AXIS_CMD_INVALID_ACC")
    }),
    row("SetAccTime", "5.3.5", AD, Ret::Int, Axis, |cx, a| {
        set_checked(
            cx,
            a,
            ParamId::AccelTime,
            positive,
            "eERR_AXIS_CMD_INVALID_ACC",
        )
    }),
    unary("GetDec", "5.3.6", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::Decel)
    }),
    row("SetDec", "5.3.7", AD, Ret::Int, Axis, |cx, a| {
        set_checked(cx, a, ParamId::Decel, positive, "eERR_AXIS_CMD_INVALID_DEC")
    }),
    row("SetDecTime", "5.3.8", AD, Ret::Int, Axis, |cx, a| {
        set_checked(
            cx,
            a,
            ParamId::DecelTime,
            positive,
            "eERR_AXIS_CMD_INVALID_DEC",
        )
    }),
    unary("GetKillDec", "5.3.9", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::FastDecel)
    }),
    row("SetKillDec", "5.3.10", AD, Ret::Int, Axis, |cx, a| {
        set_checked(
            cx,
            a,
            ParamId::FastDecel,
            positive,
            "eERR_AXIS_CMD_INVALID_KILL_DEC",
        )
    }),
    unary("GetSWRL", "5.3.11", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::FsLimit)
    }),
    row("SetSWRL", "5.3.12", AD, Ret::Int, Axis, |cx, a| {
        set_checked(cx, a, ParamId::FsLimit, finite, PARAMETER)
    }),
    unary("GetSWLL", "5.3.13", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::RsLimit)
    }),
    row("SetSWLL", "5.3.14", AD, Ret::Int, Axis, |cx, a| {
        set_checked(cx, a, ParamId::RsLimit, finite, PARAMETER)
    }),
    unary("GetSMTime", "5.3.15", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::SmoothTime)
    }),
    row("SetSMTime", "5.3.16", AD, Ret::Int, Axis, set_sm_time),
    // §5.3.17–18, digest 004 §3.7: the last move's profile time and its settling time (profile
    // end → in position), measured on the engine's clock; ms.
    unary("GetMoveTime", "5.3.17", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.move_time * 1000.0)
    }),
    unary("GetSettlingTime", "5.3.18", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.settling_time * 1000.0)
    }),
    row("SetPos", "5.3.19", AD, Ret::Int, Axis, set_pos),
    unary("GetPosFb", "5.3.20", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.act_pos)
    }),
    unary("GetPosFbComp", "5.3.21", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.act_pos + s.compensation)
    }),
    // §5.3.22, digest 004 §3.9: the origin offset `SetPos` moves.
    unary("GetPosOffset", "5.3.22", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.position_offset)
    }),
    unary("GetPosErr", "5.3.23", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.following_error)
    }),
    unary("GetVelFb", "5.3.24", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.act_vel)
    }),
    unary("GetVelErr", "5.3.25", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.cmd_vel - s.act_vel)
    }),
    // §5.3.26: amperes, the drive's torque (a fraction of rated) × the motor's rated current.
    unary(
        "GetCurrFb",
        "5.3.26",
        Ret::Double,
        Axis,
        |cx, a| match axis_of(cx, a) {
            Ok((axis, s)) => {
                let amps = s.torque * param(cx, axis, ParamId::RatedCurrent);
                Plan::Done(Outcome::Double(amps))
            }
            Err(code) => Plan::Fail(code),
        },
    ),
    unary("GetRefPos", "5.3.27", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.cmd_pos)
    }),
    unary("GetRefVel", "5.3.28", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.cmd_vel)
    }),
    unary("GetRefAcc", "5.3.29", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.cmd_acc)
    }),
    unary("GetPosOut", "5.3.30", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.output_pos)
    }),
    unary("GetVelOut", "5.3.31", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.cmd_vel)
    }),
    unary("GetAccOut", "5.3.32", Ret::Double, Axis, |cx, a| {
        get_status(cx, a, |s| s.cmd_acc)
    }),
    row("IgnoreHWL", "5.3.33", AI, Ret::Int, Axis, |cx, a| {
        set_flag(cx, a, ParamId::IgnoreHwLimits)
    }),
    row("IgnoreSWL", "5.3.34", AI, Ret::Int, Axis, |cx, a| {
        set_flag(cx, a, ParamId::IgnoreSwLimits)
    }),
    row("IgnorePE", "5.3.35", AI, Ret::Int, Axis, |cx, a| {
        set_flag(cx, a, ParamId::IgnoreFe)
    }),
    row(
        "GetAxisNum",
        "5.3.36",
        &[],
        Ret::Int,
        crate::table::Addresses::Controller,
        |cx, _| {
            Plan::Done(Outcome::Int(
                i32::try_from(cx.snapshot.axes.len()).unwrap_or(i32::MAX),
            ))
        },
    ),
    // TV 25–26: 0 ~ 100 %.
    row("SetVelScale", "5.3.37", AD, Ret::Int, Axis, |cx, a| {
        set_checked(
            cx,
            a,
            ParamId::VelScale,
            |v| (0.0..=100.0).contains(&v),
            "eERR_AXIS_CMD_INVALID_VEL_SCALE",
        )
    }),
    unary("GetVelScale", "5.3.38", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::VelScale)
    }),
    row("SetRollover", "5.3.39", AD, Ret::Int, Axis, set_rollover),
    // §5.3.40, digest 004 §3.8: whole turns past 0 of the rollover axis's feedback.
    unary(
        "GetRolloverTurns",
        "5.3.40",
        Ret::Int,
        Axis,
        |cx, a| match axis_of(cx, a) {
            Ok((_, s)) => {
                let turns = s
                    .rollover_turns
                    .clamp(i64::from(i32::MIN), i64::from(i32::MAX));
                Plan::Done(Outcome::Int(turns as i32))
            }
            Err(code) => Plan::Fail(code),
        },
    ),
    row("SetOpMode", "5.3.41", AI, Ret::Int, Axis, set_op_mode),
    row(
        "SetBufferMode",
        "5.3.42",
        AI,
        Ret::Int,
        Axis,
        set_buffer_mode,
    ),
    unary(
        "GetBufferMode",
        "5.3.43",
        Ret::Int,
        Axis,
        |cx, a| match axis_of(cx, a) {
            Ok((axis, _)) => {
                let mode = cx.registers.buffer_modes.get(&axis).copied().unwrap_or(0);
                Plan::Done(Outcome::Int(i32::try_from(mode).unwrap_or(0)))
            }
            Err(code) => Plan::Fail(code),
        },
    ),
    unary(
        "GetCmdNum",
        "5.3.44",
        Ret::Int,
        Axis,
        |cx, a| match axis_of(cx, a) {
            Ok((_, s)) => Plan::Done(Outcome::Int(i32::from(s.fifo_len))),
            Err(code) => Plan::Fail(code),
        },
    ),
    row("SetPosWindow", "5.3.45", AD, Ret::Int, Axis, |cx, a| {
        set_checked(cx, a, ParamId::InPositionWindow, positive, PARAMETER)
    }),
    unary("GetPosWindow", "5.3.46", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::InPositionWindow)
    }),
    row("SetPosWindowTime", "5.3.47", AD, Ret::Int, Axis, |cx, a| {
        set_checked(cx, a, ParamId::InPositionTime, positive, PARAMETER)
    }),
    unary("GetPosWindowTime", "5.3.48", Ret::Double, Axis, |cx, a| {
        get_param(cx, a, ParamId::InPositionTime)
    }),
];

fn moving(state: AxisState) -> bool {
    matches!(
        state,
        AxisState::DiscreteMotion
            | AxisState::ContinuousMotion
            | AxisState::Homing
            | AxisState::Stopping
    )
}

/// §5.3.16, TV 22–23: 0 ~ 500 ms, not while moving.
fn set_sm_time(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let (axis, status) = match axis_of(cx, args) {
        Ok(a) => a,
        Err(code) => return Plan::Fail(code),
    };
    if !mcemu_dialects::himc::SMOOTHING_MS.contains(&args.double(1)) {
        return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_SM_TIME"));
    }
    if moving(status.state) {
        return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_MOVING"));
    }
    set_param(axis, ParamId::SmoothTime, args.double(1))
}

/// §5.3.19, TV 31: redefine the position; not while grouped.
fn set_pos(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let (axis, status) = match axis_of(cx, args) {
        Ok(a) => a,
        Err(code) => return Plan::Fail(code),
    };
    if status.flags.contains(axes::AxisFlags::IN_GROUP) {
        return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_GROUPED"));
    }
    if !args.double(1).is_finite() {
        return Plan::Fail(axis_error(axis, PARAMETER));
    }
    super::engine(serde_json::json!({
        "type": "set_position", "axis": axis, "position": args.double(1),
    }))
}

/// §5.3.39, TV 29–30: only while disabled; 0 turns it off; negative is refused.
fn set_rollover(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let (axis, status) = match axis_of(cx, args) {
        Ok(a) => a,
        Err(code) => return Plan::Fail(code),
    };
    if status.state != AxisState::Disabled {
        return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_ENABLED"));
    }
    let v = args.double(1);
    if !(v.is_finite() && v >= 0.0) {
        return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_ROLLOVER_POS"));
    }
    set_param(axis, ParamId::Rollover, v)
}

/// §5.3.41, TV 27: 8 CSP, 9 CSV, 10 CST. Kept for the HMPL side; the engine's axes run
/// position control whatever the mode.
fn set_op_mode(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let axis = match axis_of(cx, args) {
        Ok((axis, _)) => axis,
        Err(code) => return Plan::Fail(code),
    };
    if !matches!(args.int(1), 8..=10) {
        return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_OP_MODE"));
    }
    cx.registers.op_modes.insert(axis, args.int(1));
    Plan::Done(Outcome::Int(0))
}

/// §5.3.42, TV 28: 0 immediate, 1 buffered; not with commands pending.
fn set_buffer_mode(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let (axis, status) = match axis_of(cx, args) {
        Ok(a) => a,
        Err(code) => return Plan::Fail(code),
    };
    if !matches!(args.int(1), 0 | 1) {
        return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_BUFFER_MODE"));
    }
    if status.fifo_len > 0 {
        return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_SETBUFFERMODE"));
    }
    cx.registers.buffer_modes.insert(axis, args.int(1));
    Plan::Done(Outcome::Int(0))
}
