//! Chapter 5.2, axis motion control (digest 004 §2.4 "5.2"): each call becomes its engine
//! command and replies as soon as the engine accepted it. The axis buffer mode (§5.3.42)
//! decides whether a move aborts (0) or queues (1).

use serde_json::{json, Value};

use super::{axis_of, engine};
use crate::table::{row, Addresses::Axis, Args, Ctx, Function, Plan, Ret, Ty};

const A: &[Ty] = &[Ty::Int];
const AD: &[Ty] = &[Ty::Int, Ty::Double];

pub static ROWS: &[Function] = &[
    row("Enable", "5.2.1", A, Ret::Int, Axis, |cx, a| {
        simple(cx, a, "enable")
    }),
    // §5.2.2: de-energizes and clears the planned path (the engine's disable clears the FIFO).
    row("Disable", "5.2.2", A, Ret::Int, Axis, |cx, a| {
        simple(cx, a, "disable")
    }),
    row("Reset", "5.2.3", A, Ret::Int, Axis, |cx, a| {
        simple(cx, a, "reset")
    }),
    row("MoveAbs", "5.2.4", AD, Ret::Int, Axis, |cx, a| {
        motion(
            cx,
            a,
            json!({"type": "move_absolute", "position": a.double(1)}),
        )
    }),
    row("MoveRel", "5.2.5", AD, Ret::Int, Axis, |cx, a| {
        motion(
            cx,
            a,
            json!({"type": "move_relative", "distance": a.double(1)}),
        )
    }),
    row("MoveVel", "5.2.6", AD, Ret::Int, Axis, |cx, a| {
        motion(
            cx,
            a,
            json!({"type": "move_velocity", "velocity": a.double(1)}),
        )
    }),
    // §5.2.9: stops and clears the plan, with the profile deceleration (digest 004 §3.4).
    row("Stop", "5.2.9", A, Ret::Int, Axis, |cx, a| {
        simple(cx, a, "stop")
    }),
    // §5.2.10–11: pause with the plan kept, and go on.
    row("Halt", "5.2.10", A, Ret::Int, Axis, |cx, a| {
        simple(cx, a, "halt")
    }),
    row("Resume", "5.2.11", A, Ret::Int, Axis, |cx, a| {
        simple(cx, a, "resume")
    }),
];

fn simple(cx: &mut Ctx<'_>, args: &Args, kind: &str) -> Plan {
    match axis_of(cx, args) {
        Ok((axis, _)) => engine(json!({"type": kind, "axis": axis})),
        Err(code) => Plan::Fail(code),
    }
}

fn motion(cx: &mut Ctx<'_>, args: &Args, mut command: Value) -> Plan {
    let axis = match axis_of(cx, args) {
        Ok((axis, _)) => axis,
        Err(code) => return Plan::Fail(code),
    };
    let buffered = cx.registers.buffer_modes.get(&axis) == Some(&1);
    if let Value::Object(fields) = &mut command {
        fields.insert("axis".into(), json!(axis));
        let mode = if buffered { "buffered" } else { "aborting" };
        fields.insert("buffer_mode".into(), json!(mode));
    }
    engine(command)
}
