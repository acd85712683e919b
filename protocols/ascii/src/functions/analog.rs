//! Chapter 10, slave analog I/O (digest 004 §2.9; TV 15–17) on the analog module after the
//! drives (`functions::slave`): AI/AO n (1-based, as the GPIO pins) is the machine's analog
//! channel n−1, which holds the raw 16-bit count the slave's PDO carries. The conversion type
//! (`HMPL_DAC_*`, table 10.1.1) maps a raw count to volts or mA over the full 2¹⁶ scale:
//! unsigned `low + raw/65536·span`, signed (`HMPL_DAC_SIGNED`) `mid + raw/32768·span/2`, so
//! 32768 (signed: 0) is the middle exactly and the top count reads one step below the top
//! (65535 → 9.9997 V; the manual's tables need a tolerance either way, digest 004 §7.3).
//! The AO monitor binding (§10.4): `SetSlvAOParam` with `ao_en_bind` 1 binds the output to its
//! `SetSlvAOMonitor` variable in the engine (`bind_analog_output`), AO = variable × scale +
//! offset in the output's unit (its conversion type's V or mA, else the raw count), held
//! within the converter (decisions.md).

use axes::ParamId;
use mcemu_dialects::himc::constants::{AXIS_VAR_SHIFT, DAC_SIGNED};
use mcemu_dialects::himc::system::HMPL_ARG_OUT_OF_RANGE;
use serde_json::{json, Value};

use super::slave::{slave, Slave};
use super::{engine, param};
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
    if outputs {
        return rebind(cx, ch);
    }
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

/// The engine source of an `HMPL_REF_POS` … `HMPL_CUR_FB` variable (§10.4.1).
fn source(variable: i64) -> Option<&'static str> {
    Some(match variable {
        1 => "cmd_pos",
        2 => "cmd_vel",
        3 => "cmd_acc",
        4 => "act_pos",
        5 => "act_vel",
        6 => "act_acc",
        7 => "torque",
        _ => return None,
    })
}

/// The engine binding of bound output `ch`: its monitor variable × scale + offset, taken to
/// the raw count the channel holds (a conversion type is linear: raw = k·value + c) and held
/// within the converter. No monitor variable, or one of an axis that does not exist:
/// `eERR_HMPL_ARG_OUT_OF_RANGE`.
fn binding(cx: &Ctx<'_>, ch: u16) -> Result<Value, u32> {
    let var = *cx
        .registers
        .ao_monitors
        .get(&ch)
        .ok_or(HMPL_ARG_OUT_OF_RANGE)?;
    let axis = u16::try_from(var >> AXIS_VAR_SHIFT).map_err(|_| HMPL_ARG_OUT_OF_RANGE)?;
    if usize::from(axis) >= cx.snapshot.axes.len() {
        return Err(HMPL_ARG_OUT_OF_RANGE);
    }
    let variable = var & ((1 << AXIS_VAR_SHIFT) - 1);
    let source = source(variable).ok_or(HMPL_ARG_OUT_OF_RANGE)?;
    let (mut scale, mut offset) = cx
        .registers
        .ao_scales
        .get(&ch)
        .copied()
        .unwrap_or((1.0, 0.0));
    if variable == 7 {
        // GetCurrFb's amperes: the engine's torque is a fraction of rated current.
        scale *= param(cx, axis, ParamId::RatedCurrent);
    }
    let kind = kind_of(cx, true, ch);
    let (min, max) = match range(kind) {
        Some((low, high)) => {
            let k = FULL_SCALE / (high - low);
            let zero = if signed(kind) {
                (low + high) / 2.0
            } else {
                low
            };
            (scale, offset) = (scale * k, (offset - zero) * k);
            if signed(kind) {
                (-32768.0, 32767.0)
            } else {
                (0.0, 65535.0)
            }
        }
        None => (-32768.0, 65535.0),
    };
    Ok(json!({
        "type": "bind_analog_output", "channel": ch, "axis": axis, "source": source,
        "scale": scale, "offset": offset, "min": min, "max": max,
    }))
}

/// After a change of a bound output's settings: bind it again with them.
fn rebind(cx: &Ctx<'_>, ch: u16) -> Plan {
    if !cx.registers.ao_bound.contains(&ch) {
        return Plan::Done(Outcome::Int(0));
    }
    match binding(cx, ch) {
        Ok(b) => engine(b),
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
                    rebind(cx, ch)
                }
                Ok(_) => Plan::Fail(HMPL_ARG_OUT_OF_RANGE),
                Err(c) => Plan::Fail(c),
            }
        },
    ),
    // Scale and offset kept; ao_en_bind 1 binds the output to its monitor variable, 0
    // releases it (the output keeps its last value).
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
            let before = cx.registers.ao_scales.insert(ch, (scale, offset));
            if bind == 1 {
                cx.registers.ao_bound.insert(ch);
                let bound = rebind(cx, ch);
                if matches!(bound, Plan::Fail(_)) {
                    cx.registers.ao_bound.remove(&ch);
                    match before {
                        Some(b) => cx.registers.ao_scales.insert(ch, b),
                        None => cx.registers.ao_scales.remove(&ch),
                    };
                }
                return bound;
            }
            if cx.registers.ao_bound.remove(&ch) {
                return engine(json!({"type": "bind_analog_output", "channel": ch}));
            }
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
    row(
        "IsSlvAOBound",
        "10.4.5",
        SS,
        Ret::Int,
        Controller,
        |cx, a| match channel(cx, a, true) {
            Ok(ch) => Plan::Done(Outcome::bool(cx.registers.ao_bound.contains(&ch))),
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
