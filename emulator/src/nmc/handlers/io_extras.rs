//! The plain I/O aliases, bit inversion, timed outputs, DI filters, DI edge counters and the
//! DIO mapping table (digest 001 §2.8, §3.12, §4.8).
//!
//! - `NMC_GetDI` / `GetDO` / `SetDO` are `NMC_GetDIGroup` / `GetDOGroup` / `SetDOGroup`.
//! - `NMC_SetDIBitRevs` inverts what a general input reads (`GetDIGroup`, `GetDIBit`,
//!   `GetDIEx`; `GetDIRaw` reads the terminal); `NMC_SetDOBitRevs` inverts what the terminal
//!   drives: the output keeps reading what was written, and its terminal flips at once.
//! - `NMC_SetDOBitAutoReverse` and `NMC_DoBitPulseEnable` drive the engine's timed outputs
//!   (`pulse_digital_output`): the DO toggles on the virtual clock, in whole servo periods.
//! - `NMC_GetDiReverseCount` counts the engine's changes of a general input (both edges).
//! - N/A for an emulator, stored and read back: the DI filters (a noiseless machine has nothing
//!   to filter), the inversion of the servo-enable and alarm-clear outputs, the DIO mappings.

use axes::command::{ErrorKind, PulseDigitalOutput};
use mcemu_dialects::nmc::code_for_kind;
use mcemu_nmc::io_structs::DioMapping;
use mcemu_nmc::table::{self, Function};

use super::io::{bit_index, drive, get_di_group, get_do_group, set_do_group};
use super::io_modules::group_start;
use super::sync_args::axis_number;
use crate::nmc::io_state::{DEFAULT_DI_FILTER, MAX_DIO_MAPPING, MAX_NUM_DOBIT_PULSE};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::GET_DI, get_di_group),
    (table::GET_DO, get_do_group),
    (table::SET_DO, set_do_group),
    (table::SET_DI_BIT_REVS, set_di_bit_revs),
    (table::GET_DI_BIT_REVS, get_di_bit_revs),
    (table::SET_DO_BIT_REVS, set_do_bit_revs),
    (table::GET_DO_BIT_REVS, get_do_bit_revs),
    (table::SET_DO_BIT_REVS_EX, set_do_bit_revs_ex),
    (table::GET_DO_BIT_REVS_EX, get_do_bit_revs_ex),
    (table::SET_DO_BIT_AUTO_REVERSE, set_do_bit_auto_reverse),
    (table::DO_BIT_PULSE_ENABLE, do_bit_pulse_enable),
    (table::DO_BIT_PULSE_DISABLE, do_bit_pulse_disable),
    (table::SET_DI_FILTER, set_di_filter),
    (table::GET_DI_FILTER, get_di_filter),
    (table::SET_DI_REVERSE_COUNT, set_di_reverse_count),
    (table::GET_DI_REVERSE_COUNT, get_di_reverse_count),
    (table::SET_DIO_MAPPING, set_dio_mapping),
    (table::GET_ALL_DIO_MAPPING, get_all_dio_mapping),
    (table::CLR_ALL_DIO_MAPPING, clr_all_dio_mapping),
];

pub(super) fn flag(name: &str, v: i16) -> Result<bool, Refusal> {
    match v {
        0 | 1 => Ok(v == 1),
        _ => Err(Refusal::range(name, v, "{0, 1}")),
    }
}

fn set_di_bit_revs(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (bit, revs) = (c.input.i16()?, c.input.i16()?);
    let i = bit_index(c, bit, c.snapshot.io.di.len())?;
    let on = flag("revs", revs)?;
    let mut io = c.service.io();
    if on {
        io.di_revs.insert(i);
    } else {
        io.di_revs.remove(&i);
    }
    Ok(())
}

fn get_di_bit_revs(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let bit = c.input.i16()?;
    let i = bit_index(c, bit, c.snapshot.io.di.len())?;
    let on = c.service.io().di_revs.contains(&i);
    c.output.i16(i16::from(on));
    Ok(())
}

/// Invert general DO `bit`: the terminal flips now so that the bit reads as before.
fn invert_do(c: &mut Call<'_>, bit: usize, on: bool) {
    let was = c.service.io().do_rev(bit);
    if was == on {
        return;
    }
    let reads = c.snapshot.io.do_.get(bit).copied().unwrap_or(false) ^ was;
    {
        let mut io = c.service.io();
        if on {
            io.do_revs.insert(bit);
        } else {
            io.do_revs.remove(&bit);
        }
    }
    drive(c, bit, reads);
}

fn set_do_bit_revs(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (bit, revs) = (c.input.i16()?, c.input.i16()?);
    let i = bit_index(c, bit, c.snapshot.io.do_.len())?;
    let on = flag("revs", revs)?;
    invert_do(c, i, on);
    Ok(())
}

fn get_do_bit_revs(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let bit = c.input.i16()?;
    let i = bit_index(c, bit, c.snapshot.io.do_.len())?;
    let on = c.service.io().do_rev(i);
    c.output.i16(i16::from(on));
    Ok(())
}

/// The output `NMC_Set/GetDOBitRevsEx` name: a general DO bit, or (type, axis) of a
/// servo-enable / alarm-clear output.
enum TypedDo {
    General(usize),
    Axis(i16, usize),
}

fn typed_do(c: &Call<'_>, do_type: i16, group: i16, bit: i16) -> Result<TypedDo, Refusal> {
    let index = usize::try_from(bit).ok().filter(|b| *b < 32);
    match do_type {
        1 | 2 => {
            if group != 0 {
                return Err(Refusal::range("group", group, "{0} (bit k = axis k)"));
            }
            // Bit k = NMC axis k: local, or a bus drive from 16 (within the 32 bits).
            let count = c.snapshot.axes.len();
            let bus = c.service.bus();
            index
                .and_then(|k| bus.engine_axis(k as u8, count))
                .map(|a| TypedDo::Axis(do_type, a))
                .ok_or_else(|| Refusal::range("bitIndex", bit, &bus.numbers_text(count)))
        }
        3 => {
            let start = group_start(c, group, c.snapshot.io.do_.len())?;
            index
                .map(|i| TypedDo::General(start + i))
                .ok_or_else(|| Refusal::range("bitIndex", bit, "[0, 31]"))
        }
        _ => Err(Refusal::range(
            "doType",
            do_type,
            "{1 servo enable, 2 alarm clear, 3 general}",
        )),
    }
}

fn set_do_bit_revs_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (do_type, group) = (c.input.i16()?, c.input.i16()?);
    let (bit, revs) = (c.input.i16()?, c.input.i16()?);
    let target = typed_do(c, do_type, group, bit)?;
    let on = flag("revs", revs)?;
    match target {
        TypedDo::General(i) => invert_do(c, i, on),
        TypedDo::Axis(t, a) => {
            let mut io = c.service.io();
            if on {
                io.do_revs_ex.insert((t, a));
            } else {
                io.do_revs_ex.remove(&(t, a));
            }
        }
    }
    Ok(())
}

fn get_do_bit_revs_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (do_type, group, bit) = (c.input.i16()?, c.input.i16()?, c.input.i16()?);
    let on = match typed_do(c, do_type, group, bit)? {
        TypedDo::General(i) => c.service.io().do_rev(i),
        TypedDo::Axis(t, a) => c.service.io().do_revs_ex.contains(&(t, a)),
    };
    c.output.i16(i16::from(on));
    Ok(())
}

/// `value` now, the opposite after `reverseTime` ms (> 0).
fn set_do_bit_auto_reverse(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (bit, value, time) = (c.input.i16()?, c.input.i16()?, c.input.i16()?);
    let i = bit_index(c, bit, c.snapshot.io.do_.len())?;
    let value = flag("value", value)?;
    if time <= 0 {
        return Err(Refusal::range("reverseTime", time, "[1, 32767] ms"));
    }
    let level = value ^ c.service.io().do_rev(i);
    c.command(PulseDigitalOutput {
        channel: i as u16,
        level,
        level_time: f64::from(time) / 1e3,
        other_time: 0.0,
        toggles: 1,
    });
    Ok(())
}

pub(super) fn pulse_channel(ch: i16) -> Result<usize, Refusal> {
    usize::try_from(ch)
        .ok()
        .filter(|c| *c < MAX_NUM_DOBIT_PULSE)
        .ok_or_else(|| {
            Refusal::range(
                "ch",
                ch,
                &format!("[0, {}] (MAX_NUM_DOBIT_PULSE − 1)", MAX_NUM_DOBIT_PULSE - 1),
            )
        })
}

/// µs in (0, 1e9].
pub(super) fn micros(name: &str, v: i64) -> Result<f64, Refusal> {
    if v > 0 && v <= 1_000_000_000 {
        Ok(v as f64 / 1e6)
    } else {
        Err(Refusal::range(name, v, "[1, 1000000000] µs"))
    }
}

/// `NMC_DoBitPulseEnable`'s arguments after the handle, checked: the train, its channel `ch`
/// and the DO bit (shared with the buffered form).
pub(super) fn pulse_train(c: &mut Call<'_>) -> Result<(PulseDigitalOutput, usize), Refusal> {
    let (do_type, index) = (c.input.i16()?, c.input.i16()?);
    let (high, low, count) = (c.input.i64()?, c.input.i64()?, c.input.i64()?);
    let (initial, ch) = (c.input.i16()?, c.input.i16()?);
    if do_type != 0 {
        return Err(Refusal::range("doType", do_type, "{0 general}"));
    }
    let bit = bit_index(c, index, c.snapshot.io.do_.len())?;
    let (high, low) = (micros("highLevelTime", high)?, micros("lowLevelTime", low)?);
    let toggles = match count {
        0 => u32::MAX,
        1..=1_000_000 => (count * 2) as u32,
        _ => {
            return Err(Refusal::range(
                "outCount",
                count,
                "[0, 1000000] (0: until disabled)",
            ))
        }
    };
    let initial = flag("initialLevel", initial)?;
    let ch = pulse_channel(ch)?;
    let level = initial ^ c.service.io().do_rev(bit);
    let (level_time, other_time) = if initial { (high, low) } else { (low, high) };
    Ok((
        PulseDigitalOutput {
            channel: bit as u16,
            level,
            level_time,
            other_time,
            toggles,
        },
        ch,
    ))
}

/// `outCount` pulses of `highLevelTime` high and `lowLevelTime` low on general DO `doIndex`,
/// starting at `initialLevel` and ending there; `outCount` 0 runs until disabled.
fn do_bit_pulse_enable(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (train, ch) = pulse_train(c)?;
    let bit = usize::from(train.channel);
    c.command(train);
    if let Some(slot) = c.service.io().pulse_channels.get_mut(ch) {
        *slot = Some(bit);
    }
    Ok(())
}

/// Ends channel `ch`'s train; the output keeps its present level.
fn do_bit_pulse_disable(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ch = pulse_channel(c.input.i16()?)?;
    let bit = c
        .service
        .io()
        .pulse_channels
        .get_mut(ch)
        .and_then(Option::take);
    if let Some(bit) = bit {
        c.command(PulseDigitalOutput {
            channel: bit as u16,
            level: false,
            level_time: 0.0,
            other_time: 0.0,
            toggles: 0,
        });
    }
    Ok(())
}

/// The input a filter is set on: general (type 0) by group and index, or an axis's dedicated
/// input (1 − 4: group 0, index = axis).
fn filter_key(c: &mut Call<'_>) -> Result<(i16, i16, i16), Refusal> {
    let (t, group, index) = (c.input.i16()?, c.input.i16()?, c.input.i16()?);
    match t {
        0 => {
            group_start(c, group, c.snapshot.io.di.len())?;
            if !(0..32).contains(&index) {
                return Err(Refusal::range("diIndex", index, "[0, 31]"));
            }
        }
        1..=4 => {
            if group != 0 {
                return Err(Refusal::range("diGroup", group, "{0}"));
            }
            // An axis as NMC numbers it: local, or a bus drive from 16.
            axis_number(c, "diIndex", i64::from(index))?;
        }
        _ => {
            return Err(Refusal::range(
                "diType",
                t,
                "{0 general, 1 negative limit, 2 positive limit, 3 home, 4 Z}",
            ))
        }
    }
    Ok((t, group, index))
}

fn set_di_filter(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let key = filter_key(c)?;
    let ms = c.input.i16()?;
    if !(0..=32).contains(&ms) {
        return Err(Refusal::range("filtTime", ms, "[0, 32] ms"));
    }
    c.service.io().di_filters.insert(key, ms);
    Ok(())
}

fn get_di_filter(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let key = filter_key(c)?;
    let ms = c
        .service
        .io()
        .di_filters
        .get(&key)
        .copied()
        .unwrap_or(DEFAULT_DI_FILTER);
    c.output.i16(ms);
    Ok(())
}

/// Which counters `diType`, `diIndex`, `count` name: general inputs 0 … 15 (diType 0), or the
/// dedicated inputs of local axes 0 … 7 (1 negative limit, 2 positive limit, 3 home, 4 Z: the
/// engine's `AxisStatus::input_edges`; the manual's "others 0~7" leaves the bus drives, from
/// 16, out); count [1, 16] and within those.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Counters {
    General(std::ops::Range<usize>),
    /// The `input_edges` slot (diType − 1) and the engine axes of the local axes named.
    Dedicated(usize, Vec<usize>),
}

fn counters(c: &Call<'_>, t: i16, index: i16, count: i16) -> Result<Counters, Refusal> {
    let (limit, present) = match t {
        0 => (16, c.snapshot.io.di.len()),
        1..=4 => (8, c.service.bus().local_count(c.snapshot.axes.len())),
        _ => {
            return Err(Refusal::range(
                "diType",
                t,
                "{0 general, 1 negative limit, 2 positive limit, 3 home, 4 Z}",
            ))
        }
    };
    if !(1..=16).contains(&count) {
        return Err(Refusal::range("count", count, "[1, 16]"));
    }
    let n = count as usize;
    let first = usize::try_from(index)
        .ok()
        .filter(|i| i + n <= limit && i + n <= present)
        .ok_or_else(|| {
            Refusal::range(
                "diIndex",
                index,
                &format!(
                    "[0, {}] (diIndex + count ≤ {})",
                    limit.min(present).saturating_sub(n),
                    limit.min(present)
                ),
            )
        })?;
    let range = first..first + n;
    Ok(match t {
        0 => Counters::General(range),
        _ => {
            let (bus, count) = (c.service.bus(), c.snapshot.axes.len());
            let axes = range
                .filter_map(|n| bus.engine_axis(n as u8, count))
                .collect();
            Counters::Dedicated(t as usize - 1, axes)
        }
    })
}

/// The engine's change count of each counter, and where each counter's 0 is.
fn counts(c: &Call<'_>, which: &Counters) -> Vec<(u32, u32)> {
    match which {
        Counters::General(bits) => bits
            .clone()
            .map(|bit| {
                let edges = c.snapshot.io.di_edges.get(bit).copied().unwrap_or(0);
                let base = c.service.io().edge_base.get(&bit).copied().unwrap_or(0);
                (edges, base)
            })
            .collect(),
        Counters::Dedicated(k, axes) => axes
            .iter()
            .map(|&a| {
                let edges = c
                    .status(a)
                    .and_then(|s| s.input_edges.get(*k).copied())
                    .unwrap_or(0);
                let base = c
                    .service
                    .sys()
                    .dedicated_edge_base
                    .get(&(*k, a))
                    .copied()
                    .unwrap_or(0);
                (edges, base)
            })
            .collect(),
    }
}

fn set_di_reverse_count(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (t, index) = (c.input.i16()?, c.input.i16()?);
    let n = usize::from(c.input.u16()?);
    let mut values = Vec::with_capacity(n.min(16));
    for _ in 0..n {
        values.push(c.input.u64()?);
    }
    let count = c.input.i16()?;
    let which = counters(c, t, index, count)?;
    let now = counts(c, &which);
    match which {
        Counters::General(bits) => {
            let mut io = c.service.io();
            for ((bit, v), (edges, _)) in bits.zip(values).zip(now) {
                io.edge_base.insert(bit, edges.wrapping_sub(v as u32));
            }
        }
        Counters::Dedicated(k, axes) => {
            let mut sys = c.service.sys();
            for ((a, v), (edges, _)) in axes.into_iter().zip(values).zip(now) {
                sys.dedicated_edge_base
                    .insert((k, a), edges.wrapping_sub(v as u32));
            }
        }
    }
    Ok(())
}

fn get_di_reverse_count(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (t, index, count) = (c.input.i16()?, c.input.i16()?, c.input.i16()?);
    let which = counters(c, t, index, count)?;
    let now = counts(c, &which);
    c.output.u16(now.len() as u16);
    for (edges, base) in now {
        c.output.u64(u64::from(edges.wrapping_sub(base)));
    }
    Ok(())
}

fn set_dio_mapping(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let m = DioMapping::read(&mut c.input)?;
    let mut io = c.service.io();
    if io.dio_mappings.len() >= MAX_DIO_MAPPING {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::QueueFull),
            format!("{MAX_DIO_MAPPING} DIO mappings are set already (NMC_ClrAllDioMapping)"),
        ));
    }
    io.dio_mappings.push(m);
    Ok(())
}

/// Always [`MAX_DIO_MAPPING`] entries, the unused ones zero.
fn get_all_dio_mapping(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let list = c.service.io().dio_mappings.clone();
    c.output.u16(MAX_DIO_MAPPING as u16);
    for i in 0..MAX_DIO_MAPPING {
        list.get(i).copied().unwrap_or_default().write(c.output);
    }
    Ok(())
}

fn clr_all_dio_mapping(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    c.service.io().dio_mappings.clear();
    Ok(())
}
