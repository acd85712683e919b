//! Chapter 9, the controller's GPIO (digest 004 §2.8): pins are 1-based (GPI 1 and 4 on → 9),
//! pin N is the machine's digital channel N−1. Setters return 0 / −1; a pin that does not
//! exist returns −1 and latches `eERR_HMPL_ARG_OUT_OF_RANGE`.
//!
//! Inversion (§9.2.4–5) sits between the wire and HMPL: the machine's I/O image holds the
//! electrical levels (what the control API forces and shows), every HMPL read and write of an
//! inverted pin sees the opposite level, the E-stop input included (`crate::estop`).

use mcemu_dialects::himc::system::HMPL_ARG_OUT_OF_RANGE;
use serde_json::json;

use super::engine;
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Controller, Args, Ctx, Function, Plan, Ret, Ty};

/// Channel of pin `args[0]` in `pins`, or `None`.
fn channel(pins: &[bool], args: &Args) -> Option<usize> {
    usize::try_from(args.int(0))
        .ok()
        .and_then(|pin| pin.checked_sub(1))
        .filter(|&c| c < pins.len())
}

fn no_pin(cx: &mut Ctx<'_>) -> Plan {
    cx.registers.latch(HMPL_ARG_OUT_OF_RANGE);
    Plan::Done(Outcome::Int(-1))
}

/// Output `c`'s level as HMPL sees it, given its electrical level `on`.
fn output_level(cx: &Ctx<'_>, c: usize, on: bool) -> bool {
    on != cx.registers.gpo_inverted.contains(&(c + 1))
}

fn input_level(cx: &Ctx<'_>, c: usize, on: bool) -> bool {
    on != cx.registers.gpi_inverted.contains(&(c + 1))
}

/// Set output pin `args[0]` to `value(its HMPL level now)` (an inverted pin: the opposite
/// electrical level).
fn write(cx: &mut Ctx<'_>, args: &Args, value: impl FnOnce(bool) -> bool) -> Plan {
    match channel(&cx.snapshot.io.do_, args) {
        Some(c) => {
            let wire = cx.snapshot.io.do_.get(c).copied().unwrap_or(false);
            let level = value(output_level(cx, c, wire));
            let wire = output_level(cx, c, level);
            engine(json!({"type": "write_digital_output", "channel": c, "value": wire}))
        }
        None => no_pin(cx),
    }
}

fn read(cx: &mut Ctx<'_>, args: &Args, inputs: bool) -> Plan {
    let io = &cx.snapshot.io;
    let pins = if inputs { &io.di } else { &io.do_ };
    match channel(pins, args).and_then(|c| Some((c, *pins.get(c)?))) {
        Some((c, on)) if inputs => Plan::Done(Outcome::bool(input_level(cx, c, on))),
        Some((c, on)) => Plan::Done(Outcome::bool(output_level(cx, c, on))),
        None => no_pin(cx),
    }
}

/// `invert` (§9.2.4–5): 1 inverted, 0 normal; anything else is out of range.
fn invert_flag(args: &Args) -> Option<bool> {
    match args.int(1) {
        0 => Some(false),
        1 => Some(true),
        _ => None,
    }
}

/// `SetGPIInvert`: kept in the registers; every later read of the pin sees it.
fn set_gpi_invert(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let (Some(c), Some(invert)) = (channel(&cx.snapshot.io.di, args), invert_flag(args)) else {
        return no_pin(cx);
    };
    if invert {
        cx.registers.gpi_inverted.insert(c + 1);
    } else {
        cx.registers.gpi_inverted.remove(&(c + 1));
    }
    Plan::Done(Outcome::Int(0))
}

/// `SetGPOInvert`: the output keeps its HMPL level, so a change of inversion flips the wire.
fn set_gpo_invert(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let (Some(c), Some(invert)) = (channel(&cx.snapshot.io.do_, args), invert_flag(args)) else {
        return no_pin(cx);
    };
    let was = cx.registers.gpo_inverted.contains(&(c + 1));
    if invert == was {
        return Plan::Done(Outcome::Int(0));
    }
    let wire = cx.snapshot.io.do_.get(c).copied().unwrap_or(false);
    if invert {
        cx.registers.gpo_inverted.insert(c + 1);
    } else {
        cx.registers.gpo_inverted.remove(&(c + 1));
    }
    engine(json!({"type": "write_digital_output", "channel": c, "value": !wire}))
}

/// `BindEMO` (§9.2.6): a GPI of the controller, or 0 for none.
fn bind_emo(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let pin = args.int(0);
    if pin != 0 && channel(&cx.snapshot.io.di, args).is_none() {
        return no_pin(cx);
    }
    cx.registers.emo_pin = usize::try_from(pin).ok();
    Plan::Done(Outcome::Int(0))
}

/// Pins 1 … 32 of `set` as bits 0 … 31.
fn pin_bits(set: &std::collections::BTreeSet<usize>) -> Plan {
    let mask = set.range(1..=32).fold(0u32, |m, pin| m | 1 << (pin - 1));
    Plan::Done(Outcome::Int(mask as i32))
}

pub static ROWS: &[Function] = &[
    // TV 11.
    row(
        "SetGPO",
        "9.2.1",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Controller,
        |cx, a| {
            let on = a.int(1) != 0;
            write(cx, a, |_| on)
        },
    ),
    unary("ToggleGPO", "9.2.2", Ret::Int, Controller, |cx, a| {
        write(cx, a, |now| !now)
    }),
    unary("GetGPI", "9.4.1", Ret::Int, Controller, |cx, a| {
        read(cx, a, true)
    }),
    unary("GetGPO", "9.4.2", Ret::Int, Controller, |cx, a| {
        read(cx, a, false)
    }),
    // Unmarked (digest 004 §1.6), accepted unless `strict`: pin N = bit N−1 of the mask, every
    // output in one batch.
    unary("SetAllGPO", "9.2.3", Ret::Int, Controller, |cx, a| {
        let mask = a.int(0) as u32;
        let batch: Result<Vec<axes::Command>, _> = (0..cx.snapshot.io.do_.len().min(32))
            .map(|c| {
                let on = output_level(cx, c, mask >> c & 1 == 1);
                serde_json::from_value(
                    json!({"type": "write_digital_output", "channel": c, "value": on}),
                )
            })
            .collect();
        match batch {
            Ok(b) => Plan::Engine(b, crate::table::Then::Succeed),
            Err(_) => Plan::Fail(mcemu_dialects::himc::system::HMPL_INTERNAL_ERROR),
        }
    }),
    // Unmarked (digest 004 §1.6), accepted unless `strict`; TV 8–10.
    row("GetAllGPI", "9.4.3", &[], Ret::Int, Controller, |cx, _| {
        let levels = cx.snapshot.io.di.iter().enumerate();
        bits(levels.map(|(c, &on)| input_level(cx, c, on)))
    }),
    row("GetAllGPO", "9.4.4", &[], Ret::Int, Controller, |cx, _| {
        let levels = cx.snapshot.io.do_.iter().enumerate();
        bits(levels.map(|(c, &on)| output_level(cx, c, on)))
    }),
    // Unmarked (digest 004 §1.6), accepted unless `strict`. TV 14: GPI 1 and 4 inverted → 9.
    row(
        "SetGPIInvert",
        "9.2.4",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Controller,
        set_gpi_invert,
    ),
    row(
        "SetGPOInvert",
        "9.2.5",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Controller,
        set_gpo_invert,
    ),
    unary("BindEMO", "9.2.6", Ret::Int, Controller, bind_emo),
    row(
        "GetAllGPIInvertSt",
        "9.4.5",
        &[],
        Ret::Int,
        Controller,
        |cx, _| pin_bits(&cx.registers.gpi_inverted),
    ),
    row(
        "GetAllGPOInvertSt",
        "9.4.6",
        &[],
        Ret::Int,
        Controller,
        |cx, _| pin_bits(&cx.registers.gpo_inverted),
    ),
];

/// HMPL levels of pins 1 … 32 as bits 0 … 31.
fn bits(levels: impl Iterator<Item = bool>) -> Plan {
    let mask = levels
        .take(32)
        .enumerate()
        .filter(|(_, on)| *on)
        .fold(0u32, |m, (i, _)| m | 1 << i);
    Plan::Done(Outcome::Int(mask as i32))
}
