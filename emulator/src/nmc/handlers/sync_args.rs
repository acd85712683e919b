//! Arguments the synchronised-motion families share: axis numbers passed as values (a master,
//! the other axes of a start), and array arguments (`mcemu_nmc::sync_structs::read_array`).

use mcemu_nmc::sync_structs::read_array;

use crate::nmc::service::{Call, Refusal};

/// Axis number `n` (argument `name`) of the device.
pub fn axis_number(c: &Call<'_>, name: &str, n: i64) -> Result<usize, Refusal> {
    let count = c.snapshot.axes.len();
    usize::try_from(n)
        .ok()
        .filter(|a| *a < count)
        .ok_or_else(|| {
            Refusal::range(
                name,
                n,
                &format!("[0, {}] (the device's axes)", count.saturating_sub(1)),
            )
        })
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
