//! Chapter 10, slave analog I/O (digest 004 §2.9; TV 15–17) on the analog module after the
//! drives (`functions::slave`): AI/AO n (1-based, as the GPIO pins) is the machine's analog
//! channel n−1, which holds the raw 16-bit count the slave's PDO carries. The conversion type
//! (`HMPL_DAC_*`, table 10.1.1) maps a raw count to volts or mA over the full 2¹⁶ scale:
//! unsigned `low + raw/65536·span`, signed (`HMPL_DAC_SIGNED`) `mid + raw/32768·span/2`, so
//! 32768 (signed: 0) is the middle exactly and the top count reads one step below the top
//! (65535 → 9.9997 V; the manual's tables need a tolerance either way, digest 004 §7.3).
//! The AO monitor binding (§10.4) is kept as settings; the engine has no per-cycle binding of an
//! output to a controller variable, so enabling it is refused (decisions.md).

use mcemu_dialects::himc::constants::DAC_SIGNED;
use mcemu_dialects::himc::system::{HMPL_ARG_OUT_OF_RANGE, HMPL_NOT_SUPPORTED};
use serde_json::json;

use super::engine;
use super::slave::{slave, Slave};
use crate::reply::Outcome;
use crate::table::{row, Addresses::Controller, Args, Ctx, Function, Plan, Ret, Ty};

/// Full scale of a 16-bit converter.
const FULL_SCALE: f64 = 65536.0;

/// The range of a conversion type (without `HMPL_DAC_SIGNED`); `None` for `HMPL_DAC_NONE` and
/// unknown types.
fn range(kind: i64) -> Option<(f64, f64)> {
    match kind & !DAC_SIGNED {
        1 => Some((-10.0, 10.0)),
        2 => Some((0.0, 10.0)),
        3 => Some((-5.0, 5.0)),
        4 => Some((0.0, 5.0)),
        5 => Some((0.0, 20.0)),
        6 => Some((4.0, 20.0)),
        7 => Some((-20.0, 20.0)),
        _ => None,
    }
}

fn valid_type(kind: i64) -> bool {
    kind & !DAC_SIGNED == 0 || range(kind).is_some()
}

fn signed(kind: i64) -> bool {
    kind & DAC_SIGNED != 0
}

/// The value a raw count reads as under `kind`.
pub fn to_value(kind: i64, raw: f64) -> Option<f64> {
    let (low, high) = range(kind)?;
    Some(if signed(kind) {
        (low + high) / 2.0 + raw / (FULL_SCALE / 2.0) * (high - low) / 2.0
    } else {
        low + raw / FULL_SCALE * (high - low)
    })
}

/// The raw count that gives `value` under `kind`, clamped to the converter; `None` outside
/// the type's range.
pub fn to_raw(kind: i64, value: f64) -> Option<f64> {
    let (low, high) = range(kind)?;
    if !(low..=high).contains(&value) {
        return None;
    }
    Some(if signed(kind) {
        let mid = (low + high) / 2.0;
        ((value - mid) / ((high - low) / 2.0) * (FULL_SCALE / 2.0))
            .round()
            .clamp(-32768.0, 32767.0)
    } else {
        ((value - low) / (high - low) * FULL_SCALE)
            .round()
            .clamp(0.0, 65535.0)
    })
}

/// Channel `args[1]` (1-based) of the analog module `args[0]`, of `channels` channels.
fn channel(cx: &Ctx<'_>, args: &Args, outputs: bool) -> Result<u16, u32> {
    if slave(cx, args.int(0))? != Slave::AnalogModule {
        return Err(HMPL_ARG_OUT_OF_RANGE);
    }
    let count = if outputs {
        cx.snapshot.io.ao.len()
    } else {
        cx.snapshot.io.ai.len()
    };
    usize::try_from(args.int(1))
        .ok()
        .and_then(|n| n.checked_sub(1))
        .filter(|&c| c < count)
        .and_then(|c| u16::try_from(c).ok())
        .ok_or(HMPL_ARG_OUT_OF_RANGE)
}

fn kind_of(cx: &Ctx<'_>, outputs: bool, ch: u16) -> i64 {
    let types = if outputs {
        &cx.registers.ao_types
    } else {
        &cx.registers.ai_types
    };
    types.get(&ch).copied().unwrap_or(0)
}

fn set_type(cx: &mut Ctx<'_>, args: &Args, outputs: bool) -> Plan {
    let ch = match channel(cx, args, outputs) {
        Ok(c) => c,
        Err(c) => return Plan::Fail(c),
    };
    let kind = args.int(2);
    if !valid_type(kind) {
        return Plan::Fail(HMPL_ARG_OUT_OF_RANGE);
    }
    let types = if outputs {
        &mut cx.registers.ao_types
    } else {
        &mut cx.registers.ai_types
    };
    types.insert(ch, kind);
    Plan::Done(Outcome::Int(0))
}

fn get_type(cx: &mut Ctx<'_>, args: &Args, outputs: bool) -> Plan {
    match channel(cx, args, outputs) {
        Ok(ch) => Plan::Done(Outcome::Int(
            i32::try_from(kind_of(cx, outputs, ch)).unwrap_or(0),
        )),
        Err(c) => Plan::Fail(c),
    }
}

fn raw_of(cx: &Ctx<'_>, outputs: bool, ch: u16) -> f64 {
    let values = if outputs {
        &cx.snapshot.io.ao
    } else {
        &cx.snapshot.io.ai
    };
    values.get(usize::from(ch)).copied().unwrap_or(0.0)
}

fn get_raw(cx: &mut Ctx<'_>, args: &Args, outputs: bool) -> Plan {
    match channel(cx, args, outputs) {
        Ok(ch) => {
            let raw = raw_of(cx, outputs, ch);
            Plan::Done(Outcome::Int(raw.clamp(-32768.0, 65535.0) as i32))
        }
        Err(c) => Plan::Fail(c),
    }
}

/// TV 15–16: the converted value; a channel without a conversion type fails.
fn get_value(cx: &mut Ctx<'_>, args: &Args, outputs: bool) -> Plan {
    match channel(cx, args, outputs) {
        Ok(ch) => match to_value(kind_of(cx, outputs, ch), raw_of(cx, outputs, ch)) {
            Some(v) => Plan::Done(Outcome::Double(v)),
            None => Plan::Fail(HMPL_ARG_OUT_OF_RANGE),
        },
        Err(c) => Plan::Fail(c),
    }
}

fn write(ch: u16, raw: f64) -> Plan {
    engine(json!({"type": "write_analog_output", "channel": ch, "value": raw}))
}

const SS: &[Ty] = &[Ty::Int, Ty::Int];
const SSI: &[Ty] = &[Ty::Int, Ty::Int, Ty::Int];

pub static ROWS: &[Function] = &[
    row(
        "SetSlvAIType",
        "10.2.1",
        SSI,
        Ret::Int,
        Controller,
        |cx, a| set_type(cx, a, false),
    ),
    row(
        "SetSlvAOType",
        "10.2.2",
        SSI,
        Ret::Int,
        Controller,
        |cx, a| set_type(cx, a, true),
    ),
    // TV 17: a raw count, −32768 … 65535.
    row(
        "SetSlvAORaw",
        "10.2.3",
        SSI,
        Ret::Int,
        Controller,
        |cx, a| match channel(cx, a, true) {
            Ok(ch) if (-32768..=65535).contains(&a.int(2)) => write(ch, a.int(2) as f64),
            Ok(_) => Plan::Fail(HMPL_ARG_OUT_OF_RANGE),
            Err(c) => Plan::Fail(c),
        },
    ),
    row(
        "SetSlvAO",
        "10.2.4",
        &[Ty::Int, Ty::Int, Ty::Double],
        Ret::Int,
        Controller,
        |cx, a| match channel(cx, a, true) {
            Ok(ch) => match to_raw(kind_of(cx, true, ch), a.double(2)) {
                Some(raw) => write(ch, raw),
                None => Plan::Fail(HMPL_ARG_OUT_OF_RANGE),
            },
            Err(c) => Plan::Fail(c),
        },
    ),
    row(
        "GetSlvAIType",
        "10.3.1",
        SS,
        Ret::Int,
        Controller,
        |cx, a| get_type(cx, a, false),
    ),
    row(
        "GetSlvAOType",
        "10.3.2",
        SS,
        Ret::Int,
        Controller,
        |cx, a| get_type(cx, a, true),
    ),
    row(
        "GetSlvAIRaw",
        "10.3.3",
        SS,
        Ret::Int,
        Controller,
        |cx, a| get_raw(cx, a, false),
    ),
    row(
        "GetSlvAI",
        "10.3.4",
        SS,
        Ret::Double,
        Controller,
        |cx, a| get_value(cx, a, false),
    ),
    row(
        "GetSlvAORaw",
        "10.3.5",
        SS,
        Ret::Int,
        Controller,
        |cx, a| get_raw(cx, a, true),
    ),
    row(
        "GetSlvAO",
        "10.3.6",
        SS,
        Ret::Double,
        Controller,
        |cx, a| get_value(cx, a, true),
    ),
    // var_id = HMPL_AXIS_n | HMPL_REF_POS … HMPL_CUR_FB (n 0 ~ 15), kept.
    row(
        "SetSlvAOMonitor",
        "10.4.1",
        SSI,
        Ret::Int,
        Controller,
        |cx, a| {
            let var = a.int(2);
            match channel(cx, a, true) {
                Ok(ch) if (1..=7).contains(&(var & 0xff)) && (0..=0xfff).contains(&var) => {
                    cx.registers.ao_monitors.insert(ch, var);
                    Plan::Done(Outcome::Int(0))
                }
                Ok(_) => Plan::Fail(HMPL_ARG_OUT_OF_RANGE),
                Err(c) => Plan::Fail(c),
            }
        },
    ),
    // Scale and offset kept; binding on (ao_en_bind = 1) needs a per-cycle binding the engine
    // does not have: eERR_HMPL_NOT_SUPPORTED.
    row(
        "SetSlvAOParam",
        "10.4.2",
        &[Ty::Int, Ty::Int, Ty::Int, Ty::Double, Ty::Double],
        Ret::Int,
        Controller,
        |cx, a| {
            let ch = match channel(cx, a, true) {
                Ok(c) => c,
                Err(c) => return Plan::Fail(c),
            };
            let (bind, scale, offset) = (a.int(2), a.double(3), a.double(4));
            if !matches!(bind, 0 | 1) || !scale.is_finite() || !offset.is_finite() {
                return Plan::Fail(HMPL_ARG_OUT_OF_RANGE);
            }
            if bind == 1 {
                return Plan::Fail(HMPL_NOT_SUPPORTED);
            }
            cx.registers.ao_scales.insert(ch, (scale, offset));
            Plan::Done(Outcome::Int(0))
        },
    ),
    row(
        "GetSlvAOScale",
        "10.4.3",
        SS,
        Ret::Double,
        Controller,
        |cx, a| match channel(cx, a, true) {
            Ok(ch) => Plan::Done(Outcome::Double(
                cx.registers.ao_scales.get(&ch).map_or(1.0, |s| s.0),
            )),
            Err(c) => Plan::Fail(c),
        },
    ),
    row(
        "GetSlvAOOffset",
        "10.4.4",
        SS,
        Ret::Double,
        Controller,
        |cx, a| match channel(cx, a, true) {
            Ok(ch) => Plan::Done(Outcome::Double(
                cx.registers.ao_scales.get(&ch).map_or(0.0, |s| s.1),
            )),
            Err(c) => Plan::Fail(c),
        },
    ),
    // Never bound (see SetSlvAOParam).
    row(
        "IsSlvAOBound",
        "10.4.5",
        SS,
        Ret::Int,
        Controller,
        |cx, a| match channel(cx, a, true) {
            Ok(_) => Plan::Done(Outcome::bool(false)),
            Err(c) => Plan::Fail(c),
        },
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tv15_tv16_conversions() {
        let n10 = 1;
        for (raw, v) in [
            (49152.0, 5.0),
            (32768.0, 0.0),
            (16384.0, -5.0),
            (0.0, -10.0),
        ] {
            assert_eq!(to_value(n10, raw), Some(v));
            assert_eq!(to_raw(n10, v), Some(raw));
        }
        assert!((to_value(n10, 65535.0).unwrap_or(0.0) - 10.0).abs() < 1e-3);
        let s = DAC_SIGNED | n10;
        for (raw, v) in [
            (16384.0, 5.0),
            (0.0, 0.0),
            (-16384.0, -5.0),
            (-32768.0, -10.0),
        ] {
            assert_eq!(to_value(s, raw), Some(v));
            assert_eq!(to_raw(s, v), Some(raw));
        }
        assert!((to_value(s, 32767.0).unwrap_or(0.0) - 10.0).abs() < 1e-3);
        assert_eq!(to_raw(s, 10.0), Some(32767.0));
        assert_eq!(to_raw(n10, 10.5), None);
        assert_eq!(to_value(0, 5.0), None);
    }
}
