//! Arguments the synchronised-motion families share: axis numbers passed as values (a master,
//! the other axes of a start), and array arguments (`mcemu_nmc::sync_structs::read_array`).

use mcemu_nmc::sync_structs::read_array;

use crate::nmc::service::{Call, Refusal};

/// The engine axis of NMC axis number `n` (argument `name`): a local axis, or on an `ecat`
/// card a bus drive from 16 (`ecat_bus`, as `NMC_MtOpen` numbers them).
pub fn axis_number(c: &Call<'_>, name: &str, n: i64) -> Result<usize, Refusal> {
    let count = c.snapshot.axes.len();
    let bus = c.service.bus();
    u8::try_from(n)
        .ok()
        .and_then(|a| bus.engine_axis(a, count))
        .ok_or_else(|| Refusal::range(name, n, &bus.numbers_text(count)))
}

/// The engine axes of `mask` (argument `name`, a C type of `bits` bits), bit n = NMC axis n
/// in rising order: local axes, and on an `ecat` card bus drives from bit 16 where the type
/// is wide enough (a `long`; a `short` mask reaches the local axes only). A bit naming no
/// axis, or a negative mask, is refused.
pub fn axes_of_mask(c: &Call<'_>, name: &str, mask: i64, bits: u8) -> Result<Vec<usize>, Refusal> {
    let count = c.snapshot.axes.len();
    let bus = c.service.bus();
    let refuse = || {
        Refusal::range(
            name,
            format!("{mask:#x}"),
            &format!("bits of the axes {}", bus.numbers_text(count)),
        )
    };
    if mask < 0 || (bits < 63 && mask >> bits != 0) {
        return Err(refuse());
    }
    (0..bits.min(63))
        .filter(|b| mask & (1 << b) != 0)
        .map(|b| bus.engine_axis(b, count).ok_or_else(refuse))
        .collect()
}

/// The NMC axis number of engine axis `axis` (as `NMC_MtOpen` numbers it).
pub fn nmc_number(c: &Call<'_>, axis: usize) -> Option<usize> {
    c.service
        .bus()
        .nmc_number(axis, c.snapshot.axes.len())
        .map(usize::from)
}

/// The engine axis `i` NMC numbers after engine axis `first` ("consecutive axes from the
/// handle's", the packs and `NMC_MtGetStsMulti`), if that number exists.
pub fn axis_after(c: &Call<'_>, first: usize, i: usize) -> Option<usize> {
    let n = nmc_number(c, first)?.checked_add(i)?;
    c.service
        .bus()
        .engine_axis(u8::try_from(n).ok()?, c.snapshot.axes.len())
}

/// As [`axis_number`] where the manual bounds the number at `high` (≤ 15): the card's local
/// axes only, a bus drive (16+) refused.
pub fn local_axis_number(c: &Call<'_>, name: &str, n: i64, high: u8) -> Result<usize, Refusal> {
    let count = c.snapshot.axes.len();
    let bus = c.service.bus();
    let local = bus.local_count(count).min(usize::from(high) + 1);
    usize::try_from(n)
        .ok()
        .filter(|a| *a < local)
        .and_then(|a| bus.engine_axis(a as u8, count))
        .ok_or_else(|| Refusal::range(name, n, &format!("[0, {}]", local.saturating_sub(1))))
}

/// The engine axis of NMC axis number `n` stored after `axis_number` accepted it (0 if it no
/// longer names one, which a running device's fixed bus never makes happen).
pub fn stored_axis(c: &Call<'_>, n: i16) -> usize {
    u8::try_from(n)
        .ok()
        .and_then(|a| c.service.bus().engine_axis(a, c.snapshot.axes.len()))
        .unwrap_or(0)
}

/// A count argument `name` in `[low, high]`.
pub fn count_in(name: &str, n: i16, low: i16, high: i16) -> Result<usize, Refusal> {
    if (low..=high).contains(&n) {
        Ok(usize::try_from(n).unwrap_or(0))
    } else {
        Err(Refusal::range(name, n, &format!("[{low}, {high}]")))
    }
}

/// An array of `count` elements (the count argument said how many; the library sends that
/// many).
pub fn array_of<T>(
    c: &mut Call<'_>,
    name: &str,
    count: usize,
    get: impl FnMut(&mut mcemu_nmc::payload::Reader<'_>) -> Result<T, mcemu_nmc::payload::PayloadError>,
) -> Result<Vec<T>, Refusal> {
    let items = read_array(&mut c.input, get)?;
    if items.len() == count {
        Ok(items)
    } else {
        Err(Refusal::new(
            mcemu_nmc::errors::RTN_BAD_PAYLOAD,
            format!(
                "{name} holds {} elements, the count says {count}",
                items.len()
            ),
        ))
    }
}

/// The axis of the handle followed by a count and that many other axes (`MtGearStartMtn`,
/// `MtPtStartMtn`, `MtPvtStartMtn`): all of them, the handle's first, each once.
pub fn axes_to_start(c: &mut Call<'_>) -> Result<Vec<usize>, Refusal> {
    let axis = c.axis()?;
    let count = c.input.i16()?;
    let n = count_in("syncAxCnts", count, 0, 64)?;
    let others = array_of(c, "pSyncAxArray", n, |r| r.i16())?;
    let mut axes = vec![axis];
    for o in others {
        let a = axis_number(c, "pSyncAxArray[i]", i64::from(o))?;
        if !axes.contains(&a) {
            axes.push(a);
        }
    }
    Ok(axes)
}

/// A finite value, else a range refusal naming `name`.
pub fn finite(name: &str, v: f64) -> Result<f64, Refusal> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Refusal::range(name, v, "a finite number"))
    }
}
