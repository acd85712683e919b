//! `NMC_CrdBufDataPack` (digest 001 §2.7, §3.11; row 0x1608): several buffered commands in one
//! call. The pack is decoded by `mcemu_nmc::buf_pack` into the calls it stands for; each is
//! served by its own function's handler, in order, as if called one by one. All or none: a
//! refused entry leaves the coordinate system's buffer as it was before the pack (its code is
//! the reply's), so a program can retry the whole pack.

use mcemu_nmc::buf_pack::{decode, PackError};
use mcemu_nmc::errors::RTN_ARG_RANGE;
use mcemu_nmc::payload::{Reader, Writer};
use mcemu_nmc::table::{self, Function};

use super::crd::{crd, state, update};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[(table::CRD_BUF_DATA_PACK, crd_buf_data_pack)];

/// The handle, the bytes (u16 count, then each), dataLen (the count must be dataLen).
fn crd_buf_data_pack(c: &mut Call<'_>) -> Result<(), Refusal> {
    let h = c.input.u16()?;
    let count = usize::from(c.input.u16()?);
    let mut bytes = Vec::with_capacity(count);
    for _ in 0..count {
        bytes.push(c.input.u8()?);
    }
    let len = c.input.i16()?;
    if usize::try_from(len).ok() != Some(count) {
        return Err(Refusal::range(
            "dataLen",
            len,
            &format!(
                "[0, {}] (the bytes of the pack)",
                mcemu_nmc::buf_pack::PACK_MAX_BYTES
            ),
        ));
    }
    let entries =
        decode(&bytes).map_err(|e: PackError| Refusal::new(RTN_ARG_RANGE, e.to_string()))?;
    // The coordinate system the handle names (checked as every crd function checks it).
    let handle_bytes = h.to_le_bytes();
    let n = {
        let mut sub = Call {
            service: c.service,
            snapshot: c.snapshot.clone(),
            input: Reader::new(&handle_bytes),
            output: &mut Writer::new(),
            plan: &mut *c.plan,
        };
        crd(&mut sub)?
    };
    let before = state(c, n);
    let commands_before = c.plan.commands.len();
    for (k, e) in entries.iter().enumerate() {
        let result = serve_entry(c, h, e).map_err(|r| {
            Refusal::new(
                r.code,
                format!("entry {k} ({}): {}", e.kind.macro_name, r.text),
            )
        });
        if let Err(r) = result {
            update(c, n, |s| *s = before);
            c.plan.commands.truncate(commands_before);
            return Err(r);
        }
    }
    Ok(())
}

/// One entry as its function's call: the handle, then its payload (`BUF_XYZD8` as a pack of
/// one unit; `BUF_SHIOMINFRQ` clears with a frequency ≤ 0; `BUF_SHIOGATEONOFF` picks on or off).
fn serve_entry(c: &mut Call<'_>, h: u16, e: &mcemu_nmc::buf_pack::Entry) -> Result<(), Refusal> {
    let mut w = Writer::new();
    w.u16(h);
    let mut row = e.kind.function;
    match e.kind.cmd_type {
        15 => {
            w.i16(1).u16(1);
            w.bytes.extend_from_slice(&e.wire);
        }
        16 => {
            let mut r = Reader::new(&e.wire);
            let (seg, frq, ch) = (r.i64()?, r.i64()?, r.i16()?);
            if frq <= 0 {
                row = table::CRD_BUF_SHIO_CLR_MIN_FRQ;
                w.i64(seg).i16(ch);
            } else {
                w.bytes.extend_from_slice(&e.wire);
            }
        }
        18 => {
            let mut r = Reader::new(&e.wire);
            let (seg, on, ch) = (r.i64()?, r.i16()?, r.i16()?);
            row = match on {
                1 => table::BUF_SHIO_GATE_ON,
                0 => table::BUF_SHIO_GATE_OFF,
                v => return Err(Refusal::range("onOff", v, "{0, 1}")),
            };
            w.i64(seg).i16(ch);
        }
        _ => w.bytes.extend_from_slice(&e.wire),
    }
    let handler = super::find(row.id).ok_or_else(|| {
        Refusal::new(
            mcemu_nmc::errors::RTN_UNSUPPORTED,
            format!("{} has no handler", row.name),
        )
    })?;
    // Outputs of the entries (none: they are all commands) are dropped.
    let mut output = Writer::new();
    let mut sub = Call {
        service: c.service,
        snapshot: c.snapshot.clone(),
        input: Reader::new(&w.bytes),
        output: &mut output,
        plan: &mut *c.plan,
    };
    handler(&mut sub)
}
