//! The user parameter areas (digest 001 §2.20, TV66): 2048 bytes written at most 256 at a
//! time (`NMC_UserParaWr/Rd`), 32768 bytes at most 1000 at a time (`…Ex`). Non-volatile, as
//! the manual's: every write is saved in the state directory (`user_para_file`) before it is
//! acknowledged, and the areas are there again after a restart (decisions.md).

use axes::command::ErrorKind;
use mcemu_dialects::nmc::code_for_kind;
use mcemu_nmc::table::{self, Function};

use crate::nmc::service::{Call, Handler, Refusal};
use crate::nmc::stored::Stored;
use crate::nmc::user_para_file::{self, AreaFile};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::USER_PARA_WR, user_para_wr),
    (table::USER_PARA_RD, user_para_rd),
    (table::USER_PARA_WR_EX, user_para_wr_ex),
    (table::USER_PARA_RD_EX, user_para_rd_ex),
];

/// An area: its size, the bytes one call moves at most, where it lives and its file.
struct Area {
    size: usize,
    per_call: usize,
    bytes: fn(&mut Stored) -> &mut Vec<u8>,
    file: AreaFile,
}

const AREA: Area = Area {
    size: AreaFile::Basic.size(),
    per_call: 256,
    bytes: |s| &mut s.user_para,
    file: AreaFile::Basic,
};

const AREA_EX: Area = Area {
    size: AreaFile::Extended.size(),
    per_call: 1000,
    bytes: |s| &mut s.user_para_ex,
    file: AreaFile::Extended,
};

/// add and len within the area and the per-call limit: the byte range.
fn span(area: &Area, add: u64, len: u64) -> Result<std::ops::Range<usize>, Refusal> {
    let len = usize::try_from(len)
        .ok()
        .filter(|l| *l <= area.per_call)
        .ok_or_else(|| {
            Refusal::range(
                "len",
                len,
                &format!("[0, {}] bytes per call", area.per_call),
            )
        })?;
    let add = usize::try_from(add)
        .ok()
        .filter(|a| a.saturating_add(len) <= area.size)
        .ok_or_else(|| {
            Refusal::range(
                "add",
                add,
                &format!("[0, {} − len] (a {}-byte area)", area.size, area.size),
            )
        })?;
    Ok(add..add + len)
}

fn write(c: &mut Call<'_>, area: &Area) -> Result<(), Refusal> {
    c.device()?;
    let (add, len) = (c.input.u64()?, c.input.u64()?);
    let n = usize::from(c.input.u16()?);
    let mut data = Vec::with_capacity(n.min(1024));
    for _ in 0..n {
        data.push(c.input.u8()?);
    }
    let range = span(area, add, len)?;
    if data.len() != range.len() {
        return Err(Refusal::range("pWrData", data.len(), "len bytes"));
    }
    let mut stored = c.service.stored();
    let bytes = (area.bytes)(&mut stored);
    bytes.resize(area.size, 0);
    if let Some(dest) = bytes.get_mut(range) {
        dest.copy_from_slice(&data);
    }
    let whole = bytes.clone();
    drop(stored);
    // Written through, as to the controller's flash: acknowledged once it is on disk.
    user_para_file::save(c.service, area.file, &whole)
        .map_err(|e| Refusal::new(code_for_kind(ErrorKind::Fault), e))
}

fn read(c: &mut Call<'_>, area: &Area) -> Result<(), Refusal> {
    c.device()?;
    let (add, len) = (c.input.u64()?, c.input.u64()?);
    let range = span(area, add, len)?;
    let mut stored = c.service.stored();
    let bytes = (area.bytes)(&mut stored);
    bytes.resize(area.size, 0);
    let out = bytes.get(range).unwrap_or(&[]).to_vec();
    drop(stored);
    c.output.u16(out.len() as u16);
    for b in out {
        c.output.u8(b);
    }
    Ok(())
}

fn user_para_wr(c: &mut Call<'_>) -> Result<(), Refusal> {
    write(c, &AREA)
}

fn user_para_rd(c: &mut Call<'_>) -> Result<(), Refusal> {
    read(c, &AREA)
}

fn user_para_wr_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    write(c, &AREA_EX)
}

fn user_para_rd_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    read(c, &AREA_EX)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// TV66: 257 bytes at once, or past the end of the 2 KB area, are refused.
    #[test]
    fn tv66_ranges() {
        assert!(span(&AREA, 0, 257).is_err());
        assert!(span(&AREA, 2000, 100).is_err());
        assert_eq!(span(&AREA, 1792, 256), Ok(1792..2048));
        assert!(span(&AREA_EX, 0, 1001).is_err());
        assert_eq!(span(&AREA_EX, 31768, 1000), Ok(31768..32768));
        assert!(span(&AREA, u64::MAX, 1).is_err());
    }
}
