//! What the library answers alone (digest 001 §2.20, §7): its version, the communication
//! timeout, the last error and its text, the code mode, the device search and close.

use std::ffi::{c_char, c_short, c_ulong, c_ushort};
use std::time::Duration;

use mcemu_nmc::errors::{RTN_ARG_RANGE, RTN_INVALID_HANDLE};
use mcemu_nmc::handle::{Handle, HandleKind};
use mcemu_nmc::payload::Reader;
use mcemu_nmc::structs::CardInfo;
use mcemu_nmc::table;

use super::types::TDevInfo;
use super::{put_c_string, require, store, HAND};
use crate::address::Resolver;
use crate::connection::{CallError, Connection};
use crate::last_error::{self, report};
use crate::registry;

/// Bytes `NMC_GetDllVersion` writes at most (NUL included); the manual gives no size.
pub const VERSION_CAPACITY: usize = 32;
/// Bytes `NMC_GetErrDesc` writes at most (NUL included); the manual gives no size.
pub const ERR_DESC_CAPACITY: usize = 256;
/// Entries `NMC_DevSearch` writes at most; the manual gives no size.
pub const SEARCH_CAPACITY: usize = 16;
/// A search asks each address this long at most.
const SEARCH_TIMEOUT: Duration = Duration::from_secs(1);

#[no_mangle]
pub extern "C" fn NMC_GetDllVersion(pVersion: *mut c_char) -> c_short {
    require!(table::GET_DLL_VERSION, pVersion);
    let v = concat!("mcemu nmc_lib20 ", env!("CARGO_PKG_VERSION"));
    put_c_string(pVersion, VERSION_CAPACITY, v);
    report(Ok(()))
}

/// `waitTimeInUs` bounds every later call on this device (connecting, queueing behind other
/// threads, the reply); `retryTimes` is accepted and not used (a lost call is not repeated:
/// motion commands are not idempotent; docs/decisions.md).
#[no_mangle]
pub extern "C" fn NMC_SetCommPara(
    devHandle: HAND,
    waitTimeInUs: c_ulong,
    retryTimes: c_ulong,
) -> c_short {
    let _ = retryTimes;
    let f = &table::SET_COMM_PARA;
    let result = (|| {
        let conn = Handle::decode(devHandle)
            .filter(|h| h.kind == HandleKind::Device)
            .and_then(|h| registry::get(h.slot))
            .ok_or_else(|| {
                CallError::new(
                    RTN_INVALID_HANDLE,
                    format!("{}: {devHandle:#06x} is not an open device handle", f.name),
                )
            })?;
        if waitTimeInUs == 0 {
            return Err(CallError::new(
                RTN_ARG_RANGE,
                format!("{}: waitTimeInUs 0 is outside [1, 2^32) µs", f.name),
            ));
        }
        conn.set_timeout(Duration::from_micros(u64::from(waitTimeInUs)));
        Ok(())
    })();
    report(result)
}

#[no_mangle]
pub extern "C" fn NMC_GetLastErr() -> c_short {
    last_error::last_code()
}

/// Writes at most [`ERR_DESC_CAPACITY`] bytes.
#[no_mangle]
pub extern "C" fn NMC_GetErrDesc(errCode: c_short, errDesc: *mut c_char) -> c_short {
    require!(table::GET_ERR_DESC, errDesc);
    put_c_string(
        errDesc,
        ERR_DESC_CAPACITY,
        &last_error::description(errCode),
    );
    0
}

#[no_mangle]
pub extern "C" fn NMC_SetErrCodeMode(mode: c_short) -> c_short {
    if !(0..=1).contains(&mode) {
        return report(Err(CallError::new(
            RTN_ARG_RANGE,
            format!("NMC_SetErrCodeMode: mode {mode} is outside [0, 1]"),
        )));
    }
    last_error::set_mode(mode);
    report(Ok(()))
}

/// Asks every address `MCEMU_NMC` names for its identity; writes at most [`SEARCH_CAPACITY`]
/// entries. `mode` is ignored, as the manual says any value works.
#[no_mangle]
pub extern "C" fn NMC_DevSearch(
    mode: std::ffi::c_int,
    pDevNo: *mut c_ushort,
    pInfoList: *mut TDevInfo,
) -> c_short {
    let _ = mode;
    require!(table::DEV_SEARCH, pDevNo, pInfoList);
    let mut found: u16 = 0;
    for address in Resolver::from_env().all() {
        if usize::from(found) >= SEARCH_CAPACITY {
            break;
        }
        let desc = format!("mcemu at {address}");
        let conn = Connection::new(address);
        conn.set_timeout(SEARCH_TIMEOUT);
        let device = Handle::device(0).encode().to_le_bytes();
        let Ok(reply) = conn.call(table::GET_CARD_INFO.id, &device) else {
            continue;
        };
        let Ok(card) = CardInfo::read(&mut Reader::new(&reply)) else {
            continue;
        };
        let mut info = TDevInfo {
            address: found,
            idStr: card.id_str.map(|b| b as c_char),
            description: [0; 64],
            ID: 0,
        };
        put_c_string(info.description.as_mut_ptr(), 64, &desc);
        store(pInfoList.wrapping_add(usize::from(found)), info);
        found += 1;
    }
    store(pDevNo, found);
    report(Ok(()))
}

/// mcemu's addition (`mtn_lib20_ext.h`): close the device's connection; its handles (and its
/// axes') become invalid, and `*pDevHandle` is set to 0.
#[no_mangle]
pub extern "C" fn NMC_DevClose(pDevHandle: *mut HAND) -> c_short {
    require!(table::DEV_CLOSE, pDevHandle);
    let h = super::load(pDevHandle.cast_const());
    let closed = Handle::decode(h)
        .filter(|d| d.kind == HandleKind::Device)
        .is_some_and(|d| registry::remove(d.slot));
    if !closed {
        return report(Err(CallError::new(
            RTN_INVALID_HANDLE,
            format!("NMC_DevClose: {h:#06x} is not an open device handle"),
        )));
    }
    store(pDevHandle, 0);
    report(Ok(()))
}
