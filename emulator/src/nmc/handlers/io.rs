//! Digital inputs and outputs by group of 32 and by bit (digest 001 §2.8, §4.8): group 0 is
//! bits 0–31, group 1 bits 32–63, 2 … 9 the extension modules (`io_modules`). Reads and
//! writes go through the bit inversions of `NMC_SetDIBitRevs` / `NMC_SetDOBitRevs` (`io_extras`).

use axes::command::WriteDigitalOutput;
use mcemu_nmc::table::{self, Function};

use super::io_modules::{group_start, word};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::SET_DO_GROUP, set_do_group),
    (table::GET_DO_GROUP, get_do_group),
    (table::SET_DO_BIT, set_do_bit),
    (table::GET_DO_BIT, get_do_bit),
    (table::GET_DI_GROUP, get_di_group),
    (table::GET_DI_BIT, get_di_bit),
];

/// Bit `bit` of `count`: a local bit, or one of an enabled extension module (its group is
/// bit / 32, digest 001 §2.8).
pub(super) fn bit_index(c: &Call<'_>, bit: i16, count: usize) -> Result<usize, Refusal> {
    let refusal = || {
        Refusal::range(
            "bitIndex",
            bit,
            &format!(
                "[0, {}] or a bit of an enabled extension module",
                count
                    .min(crate::nmc::io_state::LOCAL_BITS)
                    .saturating_sub(1)
            ),
        )
    };
    let i = usize::try_from(bit)
        .ok()
        .filter(|b| *b < count)
        .ok_or_else(refusal)?;
    group_start(c, (i / 32) as i16, count).map_err(|_| refusal())?;
    Ok(i)
}

/// The 32 bits of a group, bit 0 the group's first (1 = high, digest 001 §4.8).
pub(super) fn group_value(bits: &[bool], start: usize) -> i64 {
    i64::from(word(bits, start))
}

/// What a program reads of DO group `start`: the terminals' levels, un-inverted where
/// `NMC_SetDOBitRevs` inverts them (the terminal drives the opposite of what was written).
fn do_logical(c: &Call<'_>, start: usize) -> i64 {
    group_value(&c.snapshot.io.do_, start) ^ i64::from(c.service.io().do_revs_word(start))
}

/// What a program reads of DI group `start`: inverted where `NMC_SetDIBitRevs` says.
pub(super) fn di_logical(c: &Call<'_>, start: usize) -> i64 {
    group_value(&c.snapshot.io.di, start) ^ i64::from(c.service.io().di_revs_word(start))
}

/// Drive DO `channel` so that it reads `value` (inverted at the terminal if so set).
pub(super) fn drive(c: &mut Call<'_>, channel: usize, value: bool) {
    let level = value ^ c.service.io().do_rev(channel);
    c.command(WriteDigitalOutput {
        channel: channel as u16,
        value: level,
    });
}

pub(super) fn set_do_group(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (value, group) = (c.input.i64()?, c.input.i16()?);
    let count = c.snapshot.io.do_.len();
    let start = group_start(c, group, count)?;
    for i in 0..32.min(count.saturating_sub(start)) {
        drive(c, start + i, value & (1 << i) != 0);
    }
    Ok(())
}

pub(super) fn get_do_group(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let group = c.input.i16()?;
    let start = group_start(c, group, c.snapshot.io.do_.len())?;
    let v = do_logical(c, start);
    c.output.i64(v);
    Ok(())
}

pub(super) fn get_di_group(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let group = c.input.i16()?;
    let start = group_start(c, group, c.snapshot.io.di.len())?;
    let v = di_logical(c, start);
    c.output.i64(v);
    Ok(())
}

fn set_do_bit(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (bit, value) = (c.input.i16()?, c.input.i16()?);
    let channel = bit_index(c, bit, c.snapshot.io.do_.len())?;
    if !(0..=1).contains(&value) {
        return Err(Refusal::range("value", value, "{0, 1}"));
    }
    drive(c, channel, value == 1);
    Ok(())
}

fn get_do_bit(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let bit = c.input.i16()?;
    let i = bit_index(c, bit, c.snapshot.io.do_.len())?;
    let on = c.snapshot.io.do_.get(i).copied().unwrap_or(false) ^ c.service.io().do_rev(i);
    c.output.i16(i16::from(on));
    Ok(())
}

fn get_di_bit(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let bit = c.input.i16()?;
    let i = bit_index(c, bit, c.snapshot.io.di.len())?;
    let on =
        c.snapshot.io.di.get(i).copied().unwrap_or(false) ^ c.service.io().di_revs.contains(&i);
    c.output.i16(i16::from(on));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_are_32_bits_from_bit_32_g() {
        let mut bits = vec![false; 64];
        bits[0] = true;
        bits[33] = true;
        assert_eq!(group_value(&bits, 0), 1);
        assert_eq!(group_value(&bits, 32), 2);
    }
}
