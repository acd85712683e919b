//! Digital inputs and outputs by group of 32 and by bit (digest 001 §2.8, §4.8): group 0 is
//! bits 0–31, group 1 bits 32–63, and so on over the machine's I/O image.

use axes::command::WriteDigitalOutput;
use mcemu_nmc::table::{self, Function};

use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::SET_DO_GROUP, set_do_group),
    (table::GET_DO_GROUP, get_do_group),
    (table::SET_DO_BIT, set_do_bit),
    (table::GET_DO_BIT, get_do_bit),
    (table::GET_DI_GROUP, get_di_group),
    (table::GET_DI_BIT, get_di_bit),
];

/// The first bit of group `group` of `count` bits.
fn group_start(group: i16, count: usize) -> Result<usize, Refusal> {
    let groups = count.div_ceil(32);
    usize::try_from(group)
        .ok()
        .filter(|g| *g < groups)
        .map(|g| g * 32)
        .ok_or_else(|| {
            Refusal::range(
                "groupID",
                group,
                &format!("[0, {}] ({count} bits)", groups.saturating_sub(1)),
            )
        })
}

fn bit_index(bit: i16, count: usize) -> Result<usize, Refusal> {
    usize::try_from(bit)
        .ok()
        .filter(|b| *b < count)
        .ok_or_else(|| {
            Refusal::range(
                "bitIndex",
                bit,
                &format!("[0, {}]", count.saturating_sub(1)),
            )
        })
}

/// The 32 bits of a group, bit 0 the group's first (1 = high, digest 001 §4.8).
pub(super) fn group_value(bits: &[bool], start: usize) -> i64 {
    bits.iter()
        .skip(start)
        .take(32)
        .enumerate()
        .filter(|(_, on)| **on)
        .fold(0i64, |v, (i, _)| v | (1 << i))
}

pub(super) fn set_do_group(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (value, group) = (c.input.i64()?, c.input.i16()?);
    let count = c.snapshot.io.do_.len();
    let start = group_start(group, count)?;
    for i in 0..32.min(count - start) {
        c.command(WriteDigitalOutput {
            channel: (start + i) as u16,
            value: value & (1 << i) != 0,
        });
    }
    Ok(())
}

pub(super) fn get_do_group(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let group = c.input.i16()?;
    let start = group_start(group, c.snapshot.io.do_.len())?;
    c.output.i64(group_value(&c.snapshot.io.do_, start));
    Ok(())
}

fn get_di_group(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let group = c.input.i16()?;
    let start = group_start(group, c.snapshot.io.di.len())?;
    c.output.i64(group_value(&c.snapshot.io.di, start));
    Ok(())
}

fn set_do_bit(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (bit, value) = (c.input.i16()?, c.input.i16()?);
    let channel = bit_index(bit, c.snapshot.io.do_.len())?;
    if !(0..=1).contains(&value) {
        return Err(Refusal::range("value", value, "{0, 1}"));
    }
    c.command(WriteDigitalOutput {
        channel: channel as u16,
        value: value == 1,
    });
    Ok(())
}

fn get_do_bit(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let bit = c.input.i16()?;
    let i = bit_index(bit, c.snapshot.io.do_.len())?;
    let on = c.snapshot.io.do_.get(i).copied().unwrap_or(false);
    c.output.i16(i16::from(on));
    Ok(())
}

fn get_di_bit(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let bit = c.input.i16()?;
    let i = bit_index(bit, c.snapshot.io.di.len())?;
    let on = c.snapshot.io.di.get(i).copied().unwrap_or(false);
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
        assert_eq!(group_start(1, 64), Ok(32));
        assert!(group_start(2, 64).is_err());
        assert!(group_start(-1, 64).is_err());
        assert!(bit_index(64, 64).is_err());
    }
}
