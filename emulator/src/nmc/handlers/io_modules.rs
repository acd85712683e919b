//! Extension I/O modules (digest 001 §2.8, §4.8, §8 item 32): module `k` (2 … 9) is DI/DO
//! group `k`, bits 64 + 32·(k − 2) … + 31 of the machine's I/O image. The machine has the
//! modules its `[io]` channel counts reach beyond the 64 local bits (the Gaochuan fixture: one,
//! id 2, an IOMODULE_TYPE_IO64); a module is read and written once `NMC_IOModuleSetEn` enabled
//! it as that type.

use axes::command::ErrorKind;
use axes::command::WriteDigitalOutput;
use mcemu_dialects::nmc::code_for_kind;
use mcemu_nmc::table::{self, Function};

use crate::nmc::io_state::{
    IOMODULE_TYPE_IO32_DA, IOMODULE_TYPE_IO64, LOCAL_BITS, MODULE_FIRST, MODULE_LAST,
};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::IO_MODULE_SET_EN, io_module_set_en),
    (table::IO_MODULE_GET_TYPE, io_module_get_type),
    (table::IO_MODULE_RD_16BIT, rd16),
    (table::IO_MODULE_RD_32BIT, rd32),
    (table::IO_MODULE_RD_OUT_16BIT, rd_out16),
    (table::IO_MODULE_RD_OUT_32BIT, rd_out32),
    (table::IO_MODULE_WR_16BIT, wr16),
    (table::IO_MODULE_WR_32BIT, wr32),
    (table::GET_IO_MODULE_STS, get_io_module_sts),
];

/// The first bit of module `id`.
pub fn module_start(id: u8) -> usize {
    LOCAL_BITS + 32 * usize::from(id.saturating_sub(MODULE_FIRST))
}

/// Whether the machine has module `id`: its 32 DI and 32 DO channels exist.
fn present(c: &Call<'_>, id: u8) -> bool {
    let end = module_start(id) + 32;
    c.snapshot.io.di.len() >= end && c.snapshot.io.do_.len() >= end
}

fn module_id(id: u8) -> Result<u8, Refusal> {
    if (MODULE_FIRST..=MODULE_LAST).contains(&id) {
        Ok(id)
    } else {
        Err(Refusal::range(
            "chDevId",
            id,
            &format!("[{MODULE_FIRST}, {MODULE_LAST}]"),
        ))
    }
}

/// Module `id`, enabled as an IO64 the machine has: its first bit.
fn usable(c: &Call<'_>, id: u8) -> Result<usize, Refusal> {
    let id = module_id(id)?;
    let kind = c.service.io().module_type(id);
    if kind != IOMODULE_TYPE_IO64 {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidState),
            format!("module {id} is not enabled as IOMODULE_TYPE_IO64 (NMC_IOModuleSetEn)"),
        ));
    }
    if !present(c, id) {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidChannel),
            format!(
                "the machine has no module {id} (its [io] counts end before bit {})",
                module_start(id) + 32
            ),
        ));
    }
    Ok(module_start(id))
}

/// The first bit of DI/DO group `group` of a machine with `count` bits: groups 0 and 1 the
/// local bits, 2 … 9 an enabled extension module (digest 001 §2.8). Used by the group and by
/// the typed functions.
pub fn group_start(c: &Call<'_>, group: i16, count: usize) -> Result<usize, Refusal> {
    let local_groups = count.min(LOCAL_BITS).div_ceil(32);
    let ok_local = usize::try_from(group).ok().filter(|g| *g < local_groups);
    if let Some(g) = ok_local {
        return Ok(g * 32);
    }
    let module = u8::try_from(group)
        .ok()
        .filter(|g| (MODULE_FIRST..=MODULE_LAST).contains(g));
    let enabled = module.filter(|id| {
        c.service.io().module_type(*id) == IOMODULE_TYPE_IO64 && count >= module_start(*id) + 32
    });
    enabled.map(module_start).ok_or_else(|| {
        Refusal::range(
            "groupID",
            group,
            &format!(
                "[0, {}] ({count} bits) or an extension module enabled by NMC_IOModuleSetEn",
                local_groups.saturating_sub(1)
            ),
        )
    })
}

/// The 32 bits from `start` (1 = high, digest 001 §4.8).
pub fn word(bits: &[bool], start: usize) -> u32 {
    bits.iter()
        .skip(start)
        .take(32)
        .enumerate()
        .filter(|(_, on)| **on)
        .fold(0u32, |v, (i, _)| v | (1 << i))
}

fn io_module_set_en(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (id, kind) = (c.input.u8()?, c.input.i16()?);
    let id = module_id(id)?;
    if ![IOMODULE_TYPE_IO64, IOMODULE_TYPE_IO32_DA].contains(&kind) {
        return Err(Refusal::range(
            "chDevType",
            kind,
            "{1 (IOMODULE_TYPE_IO64), 2 (IOMODULE_TYPE_IO32_DA)}",
        ));
    }
    if let Some(t) = c
        .service
        .io()
        .modules
        .get_mut(usize::from(id - MODULE_FIRST))
    {
        *t = kind;
    }
    Ok(())
}

fn io_module_get_type(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let id = module_id(c.input.u8()?)?;
    let kind = c.service.io().module_type(id);
    c.output.i16(kind);
    Ok(())
}

/// `offset` of a 16-bit access: 0 the low half, 1 the high.
fn half(offset: u8) -> Result<u32, Refusal> {
    match offset {
        0 | 1 => Ok(u32::from(offset) * 16),
        _ => Err(Refusal::range(
            "offset",
            offset,
            "{0 (low 16 bits), 1 (high)}",
        )),
    }
}

fn whole(offset: u8) -> Result<(), Refusal> {
    if offset == 0 {
        Ok(())
    } else {
        Err(Refusal::range("offset", offset, "{0}"))
    }
}

/// Module `id`'s inputs (`outputs` false) or outputs read back.
fn module_word(c: &mut Call<'_>, outputs: bool) -> Result<(u32, u8), Refusal> {
    c.device()?;
    let (id, offset) = (c.input.u8()?, c.input.u8()?);
    let start = usable(c, id)?;
    let bits = if outputs {
        &c.snapshot.io.do_
    } else {
        &c.snapshot.io.di
    };
    Ok((word(bits, start), offset))
}

fn read16(c: &mut Call<'_>, outputs: bool) -> Result<(), Refusal> {
    let (w, offset) = module_word(c, outputs)?;
    let shift = half(offset)?;
    c.output.u16((w >> shift) as u16);
    Ok(())
}

fn read32(c: &mut Call<'_>, outputs: bool) -> Result<(), Refusal> {
    let (w, offset) = module_word(c, outputs)?;
    whole(offset)?;
    c.output.u64(u64::from(w));
    Ok(())
}

fn rd16(c: &mut Call<'_>) -> Result<(), Refusal> {
    read16(c, false)
}

fn rd32(c: &mut Call<'_>) -> Result<(), Refusal> {
    read32(c, false)
}

fn rd_out16(c: &mut Call<'_>) -> Result<(), Refusal> {
    read16(c, true)
}

fn rd_out32(c: &mut Call<'_>) -> Result<(), Refusal> {
    read32(c, true)
}

/// Drive `width` outputs of a module from bit `shift` with `value`.
fn write(c: &mut Call<'_>, start: usize, shift: u32, width: u32, value: u32) {
    for i in 0..width {
        c.command(WriteDigitalOutput {
            channel: (start + (shift + i) as usize) as u16,
            value: value & (1 << i) != 0,
        });
    }
}

fn wr16(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (id, offset, data) = (c.input.u8()?, c.input.u8()?, c.input.u16()?);
    let start = usable(c, id)?;
    let shift = half(offset)?;
    write(c, start, shift, 16, u32::from(data));
    Ok(())
}

fn wr32(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (id, offset, data) = (c.input.u8()?, c.input.u8()?, c.input.u64()?);
    let start = usable(c, id)?;
    whole(offset)?;
    if data > u64::from(u32::MAX) {
        return Err(Refusal::range("data", data, "[0, 0xFFFFFFFF]"));
    }
    write(c, start, 0, 32, data as u32);
    Ok(())
}

/// Bit k: module k + 2 enabled as the type the machine has and answering (the manual gives
/// no bit meanings, digest 001 §8 item 32).
fn get_io_module_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let types = c.service.io().modules;
    let sts = (MODULE_FIRST..=MODULE_LAST)
        .zip(types)
        .filter(|(id, t)| *t == IOMODULE_TYPE_IO64 && present(c, *id))
        .fold(0u64, |v, (id, _)| v | 1 << (id - MODULE_FIRST));
    c.output.u64(sts);
    Ok(())
}

/// The controller's own outputs (the first 64 of the machine's; extension modules follow):
/// the dedicated pins counted from the end (HSIO, the laser switches) are counted from here.
pub(super) fn local_outputs(c: &Call<'_>) -> usize {
    c.snapshot.io.do_.len().min(LOCAL_BITS)
}
