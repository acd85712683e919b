//! Chapters 12–13, position trigger (PT) and touch probes (digest 004 §2.11–2.12) through the
//! engine's compare and capture channels.
//!
//! PT: axis n's PT is compare channel n on the actual position, from `SetPT_StartPos` every
//! `SetPT_Interval` to `SetPT_EndPos`, pulsing the controller's output channel n (GPO n+1; the
//! HIWIN drive's own PT pin is not modelled) for `SetPT_PulseWidth` ns, rounded up to a servo
//! period. The manual's conditions: the axis homed, the three positions given.
//!
//! Touch probe 1/2 of axis n is capture channel 0/1 of axis n, latching the actual position;
//! `tp_input` 0 (external) is the drive's probe-1 input, its home switch (as mcemu's CiA 402
//! drive wires it; probe 2 has no external input), 1 the encoder index (Z).

use axes::status::{AxisFlags, CompareState};
use serde_json::json;

use super::{axis_error, axis_of, engine};
use crate::registers::{ProbeFunction, PtSettings};
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Axis, Args, Ctx, Function, Plan, Ret, Ty};

fn axis(cx: &Ctx<'_>, args: &Args) -> Result<u16, u32> {
    axis_of(cx, args).map(|(a, _)| a)
}

fn homed(cx: &Ctx<'_>, axis: u16) -> bool {
    cx.registers.homed.get(&axis).copied().unwrap_or_else(|| {
        cx.snapshot
            .axes
            .get(usize::from(axis))
            .is_some_and(|s| s.flags.contains(AxisFlags::HOMED))
    })
}

/// §12.5–12.8: keep one PT setting (finite; interval > 0; width 20 … 80 000 ns).
fn set_pt(cx: &mut Ctx<'_>, args: &Args, set: fn(&mut PtSettings, &Args) -> bool) -> Plan {
    let a = match axis(cx, args) {
        Ok(a) => a,
        Err(c) => return Plan::Fail(c),
    };
    let mut s = cx.registers.pt.get(&a).copied().unwrap_or_default();
    if !set(&mut s, args) {
        return Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_PARAMETER"));
    }
    cx.registers.pt.insert(a, s);
    Plan::Done(Outcome::Int(0))
}

fn finite(args: &Args) -> Option<f64> {
    Some(args.double(1)).filter(|v| v.is_finite())
}

/// §12.2: start the trigger; needs the three positions and a homed axis.
fn enable_pt(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let a = match axis(cx, args) {
        Ok(a) => a,
        Err(c) => return Plan::Fail(c),
    };
    let s = cx.registers.pt.get(&a).copied().unwrap_or_default();
    let (Some(start), Some(end), Some(interval)) = (s.start, s.end, s.interval) else {
        return Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_PARAMETER"));
    };
    if !homed(cx, a) {
        return Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_STATE"));
    }
    let width = s.pulse_ns.map_or(0.0, |ns| ns as f64 * 1e-9);
    engine(json!({
        "type": "compare_start", "channel": a, "axis": a, "source": "actual",
        "start": start, "interval": interval, "end": end,
        "output": a, "mode": "pulse", "pulse_width": width,
    }))
}

fn compare_running(cx: &Ctx<'_>, a: u16) -> bool {
    cx.snapshot
        .compares
        .iter()
        .any(|c| u16::from(c.channel) == a && c.state == CompareState::Running)
}

/// §13.2–13.5: arm or clear probe `probe` (0, 1).
fn probe(cx: &mut Ctx<'_>, args: &Args, probe: u8, on: bool) -> Plan {
    let a = match axis(cx, args) {
        Ok(a) => a,
        Err(c) => return Plan::Fail(c),
    };
    if !on {
        return engine(json!({"type": "capture_clear", "axis": a, "channel": probe}));
    }
    let f = cx
        .registers
        .probe_functions
        .get(&(a, probe))
        .copied()
        .unwrap_or_default();
    let source = match (f.input, probe) {
        (1, _) => "index",
        (0, 0) => "home",
        _ => return Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_PARAMETER")),
    };
    let edge = if f.falling { "falling" } else { "rising" };
    engine(json!({
        "type": "capture_arm", "axis": a, "channel": probe, "source": source, "edge": edge,
        "continuous": f.continuous,
    }))
}

/// §13.12–13.13: tp_input 0/1, cont_trigger 0/1, detect_edge 0/1; not while enabled.
fn probe_function(cx: &mut Ctx<'_>, args: &Args, probe: u8) -> Plan {
    let a = match axis(cx, args) {
        Ok(a) => a,
        Err(c) => return Plan::Fail(c),
    };
    let (input, cont, edge) = (args.int(1), args.int(2), args.int(3));
    if ![input, cont, edge].iter().all(|v| matches!(v, 0 | 1)) || (probe == 1 && input == 0) {
        return Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_PARAMETER"));
    }
    if probe_armed(cx, a, probe) {
        return Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_TP_ENABLED"));
    }
    cx.registers.probe_functions.insert(
        (a, probe),
        ProbeFunction {
            input,
            continuous: cont == 1,
            falling: edge == 1,
        },
    );
    Plan::Done(Outcome::Int(0))
}

fn probe_armed(cx: &Ctx<'_>, a: u16, probe: u8) -> bool {
    cx.snapshot
        .captures
        .iter()
        .any(|c| c.axis == a && c.channel == probe)
}

fn probe_bool(cx: &mut Ctx<'_>, args: &Args, probe: u8, triggered: bool) -> Plan {
    match axis(cx, args) {
        Ok(a) => {
            Plan::Done(Outcome::bool(cx.snapshot.captures.iter().any(|c| {
                c.axis == a && c.channel == probe && (!triggered || c.count > 0)
            })))
        }
        Err(c) => Plan::Fail(c),
    }
}

/// §13.10–13.11 (unmarked: accepted unless `strict`): the actual position the probe latched
/// last, `code,position`; a probe that has latched nothing since it was enabled is
/// `eERR_AXIS_CMD_INVALID_STATE` (the manual names no code).
fn probe_position(cx: &mut Ctx<'_>, args: &Args, probe: u8) -> Plan {
    let a = match axis(cx, args) {
        Ok(a) => a,
        Err(c) => return Plan::Fail(c),
    };
    let latched = cx
        .snapshot
        .captures
        .iter()
        .filter(|c| c.axis == a && c.channel == probe)
        .find_map(|c| c.latches.last());
    match latched {
        Some(l) => Plan::Done(Outcome::WithStatus(0, l.act_pos)),
        None => Plan::Fail(axis_error(a, "eERR_AXIS_CMD_INVALID_STATE")),
    }
}

const AO: &[Ty] = &[Ty::Int, Ty::Out];
const AD: &[Ty] = &[Ty::Int, Ty::Double];
const FUNC: &[Ty] = &[Ty::Int, Ty::Int, Ty::Int, Ty::Int];

pub static ROWS: &[Function] = &[
    unary("EnablePT", "12.2", Ret::Int, Axis, enable_pt),
    unary("DisablePT", "12.3", Ret::Int, Axis, |cx, a| {
        match axis(cx, a) {
            Ok(x)
                if cx
                    .snapshot
                    .compares
                    .iter()
                    .any(|c| u16::from(c.channel) == x) =>
            {
                engine(json!({"type": "compare_stop", "channel": x}))
            }
            Ok(_) => Plan::Done(Outcome::Int(0)),
            Err(c) => Plan::Fail(c),
        }
    }),
    unary("IsPTEnabled", "12.4", Ret::Int, Axis, |cx, a| {
        match axis(cx, a) {
            Ok(x) => Plan::Done(Outcome::bool(compare_running(cx, x))),
            Err(c) => Plan::Fail(c),
        }
    }),
    row("SetPT_StartPos", "12.5", AD, Ret::Int, Axis, |cx, a| {
        set_pt(cx, a, |s, a| finite(a).map(|v| s.start = Some(v)).is_some())
    }),
    row("SetPT_EndPos", "12.6", AD, Ret::Int, Axis, |cx, a| {
        set_pt(cx, a, |s, a| finite(a).map(|v| s.end = Some(v)).is_some())
    }),
    row("SetPT_Interval", "12.7", AD, Ret::Int, Axis, |cx, a| {
        set_pt(cx, a, |s, a| {
            finite(a)
                .filter(|&v| v > 0.0)
                .map(|v| s.interval = Some(v))
                .is_some()
        })
    }),
    // E1 drives: 20 … 80 000 ns.
    row(
        "SetPT_PulseWidth",
        "12.8",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Axis,
        |cx, a| {
            set_pt(cx, a, |s, a| {
                let ns = a.int(1);
                (20..=80_000).contains(&ns) && {
                    s.pulse_ns = Some(ns);
                    true
                }
            })
        },
    ),
    unary("EnableTouchProbe1", "13.2", Ret::Int, Axis, |cx, a| {
        probe(cx, a, 0, true)
    }),
    unary("EnableTouchProbe2", "13.3", Ret::Int, Axis, |cx, a| {
        probe(cx, a, 1, true)
    }),
    unary("DisableTouchProbe1", "13.4", Ret::Int, Axis, |cx, a| {
        probe(cx, a, 0, false)
    }),
    unary("DisableTouchProbe2", "13.5", Ret::Int, Axis, |cx, a| {
        probe(cx, a, 1, false)
    }),
    unary("IsTouchProbe1Enabled", "13.6", Ret::Int, Axis, |cx, a| {
        probe_bool(cx, a, 0, false)
    }),
    unary("IsTouchProbe2Enabled", "13.7", Ret::Int, Axis, |cx, a| {
        probe_bool(cx, a, 1, false)
    }),
    unary("IsTouchProbe1Triggered", "13.8", Ret::Int, Axis, |cx, a| {
        probe_bool(cx, a, 0, true)
    }),
    unary("IsTouchProbe2Triggered", "13.9", Ret::Int, Axis, |cx, a| {
        probe_bool(cx, a, 1, true)
    }),
    row(
        "GetTouchProbe1Pos",
        "13.10",
        AO,
        Ret::IntWithValue,
        Axis,
        |cx, a| probe_position(cx, a, 0),
    ),
    row(
        "GetTouchProbe2Pos",
        "13.11",
        AO,
        Ret::IntWithValue,
        Axis,
        |cx, a| probe_position(cx, a, 1),
    ),
    row(
        "SetTouchProbe1Func",
        "13.12",
        FUNC,
        Ret::Int,
        Axis,
        |cx, a| probe_function(cx, a, 0),
    ),
    row(
        "SetTouchProbe2Func",
        "13.13",
        FUNC,
        Ret::Int,
        Axis,
        |cx, a| probe_function(cx, a, 1),
    ),
];
