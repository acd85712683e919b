//! Opening a device (digest 001 §1.2, §2.2) and the device-wide queries (§2.20).

use std::ffi::{c_char, c_short, c_uchar, c_ulong};

use mcemu_nmc::errors::{RTN_BAD_PAYLOAD, RTN_NO_DEVICE};
use mcemu_nmc::handle::{Handle, HandleKind};
use mcemu_nmc::payload::{Reader, Writer};
use mcemu_nmc::structs::CardInfo;
use mcemu_nmc::table::{self, Function};

use super::types::{to_ulong, TCardInfo};
use super::{action, c_string, load, require, served, store, HAND};
use crate::address::{DeviceKey, Resolver};
use crate::connection::{CallError, Connection};
use crate::last_error::report;
use crate::registry;

/// Open a new connection to the device `key` names, ask it with `f` (whose in arguments
/// `input` writes), and keep it under a new slot: its handle.
fn open(f: &Function, key: DeviceKey, input: impl FnOnce(&mut Writer)) -> Result<HAND, CallError> {
    let address = Resolver::from_env().resolve(&key).ok_or_else(|| {
        CallError::new(
            RTN_NO_DEVICE,
            format!("{}: MCEMU_NMC names no address for {key:?}", f.name),
        )
    })?;
    let conn = Connection::new(address);
    let mut w = Writer::new();
    input(&mut w);
    let reply = conn.call(f.id, &w.bytes)?;
    let mut r = Reader::new(&reply);
    let bad = |what: &str| CallError::new(RTN_BAD_PAYLOAD, format!("{}: reply: {what}", f.name));
    let h = r.u16().map_err(|e| bad(&e.to_string()))?;
    match Handle::decode(h) {
        Some(d) if d.kind == HandleKind::Device => {}
        _ => return Err(bad("not a device handle")),
    }
    let slot = registry::insert(conn).ok_or_else(|| {
        CallError::new(
            RTN_NO_DEVICE,
            format!("{}: 64 devices are open already", f.name),
        )
    })?;
    Ok(Handle::device(slot).encode())
}

fn open_into(
    f: &Function,
    key: DeviceKey,
    input: impl FnOnce(&mut Writer),
    out: *mut HAND,
) -> c_short {
    report(open(f, key, input).map(|h| store(out, h)))
}

#[no_mangle]
pub extern "C" fn NMC_DevOpen(devNo: c_short, pDevHandle: *mut HAND) -> c_short {
    require!(table::DEV_OPEN, pDevHandle);
    open_into(
        &table::DEV_OPEN,
        DeviceKey::Index(devNo),
        |w| {
            w.i16(devNo);
        },
        pDevHandle,
    )
}

/// `idStr` is at most 16 bytes with its NUL (digest 001 §1.2).
#[no_mangle]
pub extern "C" fn NMC_DevOpenByID(idStr: *mut c_char, pDevHandle: *mut HAND) -> c_short {
    require!(table::DEV_OPEN_BY_ID, idStr, pDevHandle);
    let id = c_string(idStr, 64);
    let key = DeviceKey::Id(String::from_utf8_lossy(&id).into_owned());
    open_into(
        &table::DEV_OPEN_BY_ID,
        key,
        |w| {
            w.str(&id);
        },
        pDevHandle,
    )
}

#[no_mangle]
pub extern "C" fn NMC_DevOpenByIP(pIPv4Array: *mut c_uchar, pDevHandle: *mut HAND) -> c_short {
    require!(table::DEV_OPEN_BY_IP, pIPv4Array, pDevHandle);
    let ip: [u8; 4] = load(pIPv4Array.cast::<[u8; 4]>().cast_const());
    open_into(
        &table::DEV_OPEN_BY_IP,
        DeviceKey::Ip(ip),
        |w| {
            for b in ip {
                w.u8(b);
            }
        },
        pDevHandle,
    )
}

action!(NMC_DevReset, table::DEV_RESET);

#[no_mangle]
pub extern "C" fn NMC_GetCardInfo(devHandle: HAND, pInfo: *mut TCardInfo) -> c_short {
    require!(table::GET_CARD_INFO, pInfo);
    served(
        &table::GET_CARD_INFO,
        devHandle,
        |_| {},
        |r| {
            store(pInfo, TCardInfo::from(CardInfo::read(r)?));
            Ok(())
        },
    )
}

/// `pClock` in 125 µs ticks, `pLoop` servo cycles, both since mcemu started (digest 001 §1.4).
#[no_mangle]
pub extern "C" fn NMC_GetClock(
    devHandle: HAND,
    pClock: *mut c_ulong,
    pLoop: *mut c_ulong,
) -> c_short {
    require!(table::GET_CLOCK, pClock, pLoop);
    served(
        &table::GET_CLOCK,
        devHandle,
        |_| {},
        |r| {
            let (clock, cycles) = (r.u64()?, r.u64()?);
            store(pClock, to_ulong(clock));
            store(pLoop, to_ulong(cycles));
            Ok(())
        },
    )
}
