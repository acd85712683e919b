//! Chapter 5.2, axis motion control (digest 004 §2.4 "5.2"): each call becomes its engine
//! command and replies as soon as the engine accepted it. The axis buffer mode (§5.3.42)
//! decides whether a move aborts (0) or queues (1).

use serde_json::{json, Value};

use super::{axis_of, engine};
use crate::table::{row, unary, Addresses::Axis, Args, Ctx, Function, Plan, Ret, Ty};

const AD: &[Ty] = &[Ty::Int, Ty::Double];

pub static ROWS: &[Function] = &[
    // §7.1.1, TV 39: either axis of a gantry pair enables both.
    unary("Enable", "5.2.1", Ret::Int, Axis, |cx, a| {
        paired(cx, a, "enable")
    }),
    // §5.2.2: de-energizes and clears the planned path (the engine's disable clears the FIFO).
    unary("Disable", "5.2.2", Ret::Int, Axis, |cx, a| {
        paired(cx, a, "disable")
    }),
    unary("Reset", "5.2.3", Ret::Int, Axis, |cx, a| {
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
    // §5.2.7 (digest 004 §2.4, §3.10): torque mode only (op mode 10, the torque mode
    // `SetOpMode` can select); N·m over the motor's rated torque, clamped to it, as the engine's
    // torque setpoint (a fraction of rated torque). `Stop` ends it.
    row("MoveTrq", "5.2.7", AD, Ret::Int, Axis, move_torque),
    // §5.2.9: stops and clears the plan, with the profile deceleration (digest 004 §3.4).
    unary("Stop", "5.2.9", Ret::Int, Axis, |cx, a| {
        simple(cx, a, "stop")
    }),
    // §5.2.10–11: pause with the plan kept, and go on.
    unary("Halt", "5.2.10", Ret::Int, Axis, |cx, a| {
        simple(cx, a, "halt")
    }),
    unary("Resume", "5.2.11", Ret::Int, Axis, |cx, a| {
        simple(cx, a, "resume")
    }),
];

fn simple(cx: &mut Ctx<'_>, args: &Args, kind: &str) -> Plan {
    match axis_of(cx, args) {
        Ok((axis, _)) => engine(json!({"type": kind, "axis": axis})),
        Err(code) => Plan::Fail(code),
    }
}

/// `kind` on the axis, and on its gantry partner if it has one (RHS first).
fn paired(cx: &mut Ctx<'_>, args: &Args, kind: &str) -> Plan {
    let axis = match axis_of(cx, args) {
        Ok((axis, _)) => axis,
        Err(code) => return Plan::Fail(code),
    };
    let axes = match super::gantry::pair_of(cx, axis) {
        Some((rhs, lhs)) => vec![rhs, lhs],
        None => vec![axis],
    };
    let batch: Result<Vec<axes::Command>, _> = axes
        .into_iter()
        .map(|a| serde_json::from_value(json!({"type": kind, "axis": a})))
        .collect();
    match batch {
        Ok(b) => Plan::Engine(b, crate::table::Then::Succeed),
        Err(_) => Plan::Fail(mcemu_dialects::himc::system::HMPL_INTERNAL_ERROR),
    }
}

fn motion(cx: &mut Ctx<'_>, args: &Args, mut command: Value) -> Plan {
    let axis = match axis_of(cx, args) {
        Ok((axis, _)) => axis,
        Err(code) => return Plan::Fail(code),
    };
    // §7.1: a gantry pair moves through its RHS axis; the engine's gantry is engaged with the
    // first move once both axes are enabled.
    let mut batch = Vec::new();
    if let Some((rhs, lhs)) = super::gantry::pair_of(cx, axis) {
        if axis == lhs {
            return Plan::Fail(super::axis_error(axis, "eERR_AXIS_CMD_INVALID_GANTRY_MODE"));
        }
        let both = [rhs, lhs].iter().all(|&a| super::gear::enabled(cx, a));
        if both && !super::gantry::engaged(cx, rhs) {
            match serde_json::from_value(
                json!({"type": "gantry_enable", "master": rhs, "slaves": [lhs]}),
            ) {
                Ok(c) => batch.push(c),
                Err(_) => return Plan::Fail(mcemu_dialects::himc::system::HMPL_INTERNAL_ERROR),
            }
        }
    }
    let buffered = cx.registers.buffer_modes.get(&axis) == Some(&1);
    if let Value::Object(fields) = &mut command {
        fields.insert("axis".into(), json!(axis));
        let mode = if buffered { "buffered" } else { "aborting" };
        fields.insert("buffer_mode".into(), json!(mode));
    }
    match serde_json::from_value(command) {
        Ok(c) => {
            batch.push(c);
            Plan::Engine(batch, crate::table::Then::Succeed)
        }
        Err(_) => Plan::Fail(mcemu_dialects::himc::system::HMPL_INTERNAL_ERROR),
    }
}

fn move_torque(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let axis = match axis_of(cx, args) {
        Ok((axis, _)) => axis,
        Err(code) => return Plan::Fail(code),
    };
    if cx.registers.op_modes.get(&axis) != Some(&10) {
        return Plan::Fail(super::axis_error(axis, "eERR_AXIS_CMD_INVALID_OP_MODE"));
    }
    let rated = super::param(cx, axis, axes::ParamId::RatedTorque);
    if !(rated.is_finite() && rated > 0.0) {
        return Plan::Fail(super::axis_error(
            axis,
            "eERR_AXIS_CMD_INVALID_FORCECONST_TRQMODE",
        ));
    }
    let torque = args.double(1);
    if !torque.is_finite() {
        return Plan::Fail(super::axis_error(axis, "eERR_AXIS_CMD_INVALID_PARAMETER"));
    }
    let fraction = (torque / rated).clamp(-1.0, 1.0);
    engine(json!({
        "type": "setpoint", "axis": axis, "setpoint": {"mode": "torque", "torque": fraction},
    }))
}
