//! Chapter 9, the controller's GPIO (digest 004 §2.8): pins are 1-based (GPI 1 and 4 on → 9),
//! pin N is the machine's digital channel N−1. Setters return 0 / −1; a pin that does not
//! exist returns −1 and latches `eERR_HMPL_ARG_OUT_OF_RANGE`.

use mcemu_dialects::himc::system::HMPL_ARG_OUT_OF_RANGE;
use serde_json::json;

use super::engine;
use crate::reply::Outcome;
use crate::table::{row, Addresses::Controller, Args, Ctx, Function, Plan, Ret, Ty};

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

fn write(cx: &mut Ctx<'_>, args: &Args, value: impl FnOnce(bool) -> bool) -> Plan {
    match channel(&cx.snapshot.io.do_, args) {
        Some(c) => {
            let now = cx.snapshot.io.do_.get(c).copied().unwrap_or(false);
            engine(json!({"type": "write_digital_output", "channel": c, "value": value(now)}))
        }
        None => no_pin(cx),
    }
}

fn read(cx: &mut Ctx<'_>, args: &Args, inputs: bool) -> Plan {
    let io = &cx.snapshot.io;
    let pins = if inputs { &io.di } else { &io.do_ };
    match channel(pins, args).and_then(|c| pins.get(c)) {
        Some(&on) => Plan::Done(Outcome::bool(on)),
        None => no_pin(cx),
    }
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
    row(
        "ToggleGPO",
        "9.2.2",
        &[Ty::Int],
        Ret::Int,
        Controller,
        |cx, a| write(cx, a, |now| !now),
    ),
    row(
        "GetGPI",
        "9.4.1",
        &[Ty::Int],
        Ret::Int,
        Controller,
        |cx, a| read(cx, a, true),
    ),
    row(
        "GetGPO",
        "9.4.2",
        &[Ty::Int],
        Ret::Int,
        Controller,
        |cx, a| read(cx, a, false),
    ),
    // Unmarked (digest 004 §1.6), accepted unless `strict`: pin N = bit N−1 of the mask, every
    // output in one batch.
    row(
        "SetAllGPO",
        "9.2.3",
        &[Ty::Int],
        Ret::Int,
        Controller,
        |cx, a| {
            let mask = a.int(0) as u32;
            let batch: Result<Vec<axes::Command>, _> = (0..cx.snapshot.io.do_.len().min(32))
                .map(|c| {
                    let on = mask >> c & 1 == 1;
                    serde_json::from_value(
                        json!({"type": "write_digital_output", "channel": c, "value": on}),
                    )
                })
                .collect();
            match batch {
                Ok(b) => Plan::Engine(b, crate::table::Then::Succeed),
                Err(_) => Plan::Fail(mcemu_dialects::himc::system::HMPL_INTERNAL_ERROR),
            }
        },
    ),
    // Unmarked (digest 004 §1.6), accepted unless `strict`; TV 8–10.
    row("GetAllGPI", "9.4.3", &[], Ret::Int, Controller, |cx, _| {
        bits(&cx.snapshot.io.di)
    }),
    row("GetAllGPO", "9.4.4", &[], Ret::Int, Controller, |cx, _| {
        bits(&cx.snapshot.io.do_)
    }),
];

/// Pins 1 … 32 as bits 0 … 31.
fn bits(pins: &[bool]) -> Plan {
    let mask = pins
        .iter()
        .take(32)
        .enumerate()
        .filter(|(_, on)| **on)
        .fold(0u32, |m, (i, _)| m | 1 << i);
    Plan::Done(Outcome::Int(mask as i32))
}
