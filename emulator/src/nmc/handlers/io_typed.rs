//! Digital I/O by type (digest 001 §2.8, §3.10, §4.8): `NMC_GetDIEx` / `NMC_GetDIRaw` read
//! the general inputs (type 0, by group as `NMC_GetDIGroup`) or an axis's dedicated ones (1
//! negative limit, 2 positive limit, 3 home, 4 encoder Z: group 0, bit k = axis k);
//! `NMC_GetDOEx` / `NMC_SetDOMask` the outputs (1 servo enable, 2 alarm clear, 3 general, 4
//! high-speed). Levels: 1 = high / open (§2.8); a dedicated input reads 1 while its switch is
//! active, as `NMC_MtGetMotionIO`'s raw bits do.

use axes::command::{Disable, Enable, WriteDigitalOutput};
use axes::AxisFlags;
use mcemu_nmc::table::{self, Function};

use super::io_modules::{group_start, word};
use super::sync_args::nmc_number;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::GET_DI_EX, get_di_ex),
    (table::GET_DI_RAW, get_di_raw),
    (table::GET_DO_EX, get_do_ex),
    (table::SET_DO_MASK, set_do_mask),
];

const DI_TYPES: &str = "{0 general, 1 negative limit, 2 positive limit, 3 home, 4 Z}";
const DO_TYPES: &str = "{1 servo enable, 2 alarm clear, 3 general, 4 high-speed}";

/// The axis flag a dedicated input type reads.
fn dedicated(di_type: i16) -> Option<AxisFlags> {
    match di_type {
        1 => Some(AxisFlags::HW_LIMIT_NEG),
        2 => Some(AxisFlags::HW_LIMIT_POS),
        3 => Some(AxisFlags::HOME_SWITCH),
        4 => Some(AxisFlags::INDEX),
        _ => None,
    }
}

/// Group 0 of a per-axis type: bit k = axis k (at most 32 axes).
fn axis_group(group: i16) -> Result<(), Refusal> {
    if group == 0 {
        Ok(())
    } else {
        Err(Refusal::range("groupID", group, "{0} (bit k = axis k)"))
    }
}

/// Bit k set where axis k has `flag` in `flags`.
fn axis_bits(c: &Call<'_>, pick: impl Fn(&axes::AxisStatus) -> bool) -> i64 {
    // Bit n = NMC axis n: bus drives from bit 16 on an `ecat` card.
    c.snapshot
        .axes
        .iter()
        .enumerate()
        .filter(|(_, s)| pick(s))
        .filter_map(|(a, _)| nmc_number(c, a).filter(|n| *n < 32))
        .fold(0i64, |v, n| v | (1 << n))
}

/// The inputs of `diType` in `groupID`; `inverted`: with `NMC_SetDIBitRevs` applied.
fn read_di(c: &mut Call<'_>, inverted: bool) -> Result<(), Refusal> {
    c.device()?;
    let (di_type, group) = (c.input.i16()?, c.input.i16()?);
    let value = if di_type == 0 {
        let start = group_start(c, group, c.snapshot.io.di.len())?;
        let raw = word(&c.snapshot.io.di, start);
        let revs = if inverted {
            c.service.io().di_revs_word(start)
        } else {
            0
        };
        i64::from(raw ^ revs)
    } else {
        let flag = dedicated(di_type).ok_or_else(|| Refusal::range("diType", di_type, DI_TYPES))?;
        axis_group(group)?;
        axis_bits(c, |s| s.flags.contains(flag))
    };
    c.output.i64(value);
    Ok(())
}

fn get_di_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    read_di(c, true)
}

/// The levels at the terminals: before the inversion of `NMC_SetDIBitRevs` (the manual's
/// "raw"; the DI filter has nothing to remove in a noiseless machine).
fn get_di_raw(c: &mut Call<'_>) -> Result<(), Refusal> {
    read_di(c, false)
}

fn get_do_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (do_type, group) = (c.input.i16()?, c.input.i16()?);
    let value = match do_type {
        1 => {
            axis_group(group)?;
            axis_bits(c, |s| s.flags.contains(AxisFlags::ENABLED))
        }
        2 => {
            axis_group(group)?;
            // The bits of the axes that exist (bit n = NMC axis n, bus drives from 16).
            let mask = axis_bits(c, |_| true) as u32;
            i64::from(c.service.io().alarm_clear & mask)
        }
        3 => {
            let start = group_start(c, group, c.snapshot.io.do_.len())?;
            let revs = c.service.io().do_revs_word(start);
            i64::from(word(&c.snapshot.io.do_, start) ^ revs)
        }
        4 => {
            axis_group(group)?;
            i64::from(c.service.io().hsio)
        }
        _ => return Err(Refusal::range("doType", do_type, DO_TYPES)),
    };
    c.output.i64(value);
    Ok(())
}

/// The bits of `outValue` that `outMask` selects; the others keep their level. Servo enable
/// switches the axes' servos (as `NMC_MtSetSvOn` / `Off`); alarm clear and the high-speed
/// outputs are stored (the machine's drives have no clear input, it has no HSIO).
fn set_do_mask(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (mask, value) = (c.input.i64()?, c.input.i64()?);
    let (do_type, group) = (c.input.i16()?, c.input.i16()?);
    let selected = |i: usize| mask & (1 << i) != 0;
    let high = |i: usize| value & (1 << i) != 0;
    match do_type {
        1 => {
            axis_group(group)?;
            let count = c.snapshot.axes.len();
            for bit in (0..32u8).filter(|b| selected(usize::from(*b))) {
                let Some(axis) = c.service.bus().engine_axis(bit, count) else {
                    continue;
                };
                let axis = axis as u16;
                if high(usize::from(bit)) {
                    c.command(Enable { axis });
                } else {
                    c.command(Disable { axis });
                }
            }
        }
        2 | 4 => {
            axis_group(group)?;
            let (mask, value) = (mask as u32, value as u32);
            let mut io = c.service.io();
            let word = if do_type == 2 {
                &mut io.alarm_clear
            } else {
                &mut io.hsio
            };
            *word = (*word & !mask) | (value & mask);
        }
        3 => {
            let count = c.snapshot.io.do_.len();
            let start = group_start(c, group, count)?;
            for i in (0..32.min(count.saturating_sub(start))).filter(|i| selected(*i)) {
                let level = high(i) ^ c.service.io().do_rev(start + i);
                c.command(WriteDigitalOutput {
                    channel: (start + i) as u16,
                    value: level,
                });
            }
        }
        _ => return Err(Refusal::range("doType", do_type, DO_TYPES)),
    }
    Ok(())
}
