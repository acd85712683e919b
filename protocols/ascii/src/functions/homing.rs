//! Chapter 20, homing (digest 004 §2.19, §4): the parameters are the engine's homing
//! parameters (defaults 33 / 20 / 5 / 2000 / 0 / 120 000 ms, TV 74); `MoveHome` is the engine's
//! `home` command and replies once accepted (or, with `move_home_waits`, once homing ends).

use axes::{AxisFlags, AxisState, ParamId};
use serde_json::json;

use super::{axis_error, axis_of, engine_then, set_param};
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Axis, Args, Ctx, Function, Plan, Ret, Then, Ty};

const AD: &[Ty] = &[Ty::Int, Ty::Double];
const AI: &[Ty] = &[Ty::Int, Ty::Int];

/// §20.3: the methods the HIMC supports (not 3–6, 19–22, 35), TV 75.
fn supported(method: i64) -> bool {
    matches!(method, 1 | 2 | 7..=14 | 17 | 18 | 23..=30 | 33 | 34 | 37)
}

fn set_positive(cx: &mut Ctx<'_>, args: &Args, id: ParamId, hmpl: f64) -> Plan {
    match axis_of(cx, args) {
        Ok((axis, _)) if hmpl.is_finite() && hmpl > 0.0 => set_param(axis, id, hmpl),
        Ok((axis, _)) => Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_PARAMETER")),
        Err(c) => Plan::Fail(c),
    }
}

fn move_home(cx: &mut Ctx<'_>, args: &Args, wait: bool) -> Plan {
    let axis = match axis_of(cx, args) {
        Ok((axis, _)) => axis,
        Err(c) => return Plan::Fail(c),
    };
    // A new homing decides the homed flag again.
    cx.registers.homed.remove(&axis);
    let then = if wait {
        Then::AwaitHoming(axis)
    } else {
        Then::Succeed
    };
    engine_then(json!({"type": "home", "axis": axis}), then)
}

fn predicate(
    cx: &mut Ctx<'_>,
    args: &Args,
    f: fn(&Ctx<'_>, u16, &axes::AxisStatus) -> bool,
) -> Plan {
    match axis_of(cx, args) {
        Ok((axis, s)) => Plan::Done(Outcome::bool(f(cx, axis, s))),
        Err(c) => Plan::Fail(c),
    }
}

pub static ROWS: &[Function] = &[
    unary("MoveHome", "20.2", Ret::Int, Axis, |cx, a| {
        move_home(cx, a, false)
    }),
    row(
        "SetHomeMethod",
        "20.3",
        AI,
        Ret::Int,
        Axis,
        |cx, a| match axis_of(cx, a) {
            Ok((axis, _)) if supported(a.int(1)) => {
                set_param(axis, ParamId::HomeMethod, a.int(1) as f64)
            }
            Ok((axis, _)) => Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_PARAMETER")),
            Err(c) => Plan::Fail(c),
        },
    ),
    row("SetHomeSwitchVel", "20.4", AD, Ret::Int, Axis, |cx, a| {
        set_positive(cx, a, ParamId::HomeSwitchVelocity, a.double(1))
    }),
    row("SetHomeZeroVel", "20.5", AD, Ret::Int, Axis, |cx, a| {
        set_positive(cx, a, ParamId::HomeZeroVelocity, a.double(1))
    }),
    row("SetHomeAcc", "20.6", AD, Ret::Int, Axis, |cx, a| {
        set_positive(cx, a, ParamId::HomeAcceleration, a.double(1))
    }),
    row(
        "SetHomeOffset",
        "20.7",
        AD,
        Ret::Int,
        Axis,
        |cx, a| match axis_of(cx, a) {
            Ok((axis, _)) if a.double(1).is_finite() => {
                set_param(axis, ParamId::HomeOffset, a.double(1))
            }
            Ok((axis, _)) => Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_PARAMETER")),
            Err(c) => Plan::Fail(c),
        },
    ),
    // An `int` of ms (the engine keeps seconds).
    row("SetHomeTimeout", "20.8", AI, Ret::Int, Axis, |cx, a| {
        set_positive(cx, a, ParamId::HomeTimeout, a.int(1) as f64)
    }),
    // TV 78.
    row(
        "SetHomedStatus",
        "20.9",
        AI,
        Ret::Int,
        Axis,
        |cx, a| match axis_of(cx, a) {
            Ok((axis, _)) => {
                cx.registers.homed.insert(axis, a.int(1) != 0);
                Plan::Done(Outcome::Int(0))
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    unary("IsHomed", "20.10", Ret::Int, Axis, |cx, a| {
        predicate(cx, a, |cx, axis, s| {
            cx.registers
                .homed
                .get(&axis)
                .copied()
                .unwrap_or(s.flags.contains(AxisFlags::HOMED))
        })
    }),
    unary("IsHoming", "20.11", Ret::Int, Axis, |cx, a| {
        predicate(cx, a, |_, _, s| s.state == AxisState::Homing)
    }),
    unary("IsHomeSwitch", "20.12", Ret::Int, Axis, |cx, a| {
        predicate(cx, a, |_, _, s| s.flags.contains(AxisFlags::HOME_SWITCH))
    }),
];

/// `MoveHome` answering once homing has ended (`move_home_waits`).
pub static WAITING_MOVE_HOME: Function = unary("MoveHome", "20.2", Ret::Int, Axis, |cx, a| {
    move_home(cx, a, true)
});
