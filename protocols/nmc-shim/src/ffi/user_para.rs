//! The user parameter areas (digest 001 §2.20): 2 KB written ≤ 256 bytes at a time, 32 KB
//! ≤ 1000 bytes at a time. The server checks the ranges; at most 1024 bytes travel.

use std::ffi::{c_short, c_uchar, c_ulong};

use mcemu_nmc::table::{self, Function};

use super::{load_array, reply_list, require, served, store_array, HAND};

/// Bytes one call moves at most (above every area's per-call limit).
const CHUNK_MAX: usize = 1024;

fn chunk(len: c_ulong) -> usize {
    usize::try_from(len).unwrap_or(usize::MAX).min(CHUNK_MAX)
}

fn write(
    row: &Function,
    devHandle: HAND,
    add: c_ulong,
    len: c_ulong,
    data: *mut c_uchar,
) -> c_short {
    require!(*row, data);
    let bytes = load_array(data.cast_const(), chunk(len));
    served(
        row,
        devHandle,
        |w| {
            w.u64(u64::from(add))
                .u64(u64::from(len))
                .u16(bytes.len() as u16);
            for b in &bytes {
                w.u8(*b);
            }
        },
        |_| Ok(()),
    )
}

fn read(
    row: &Function,
    devHandle: HAND,
    add: c_ulong,
    len: c_ulong,
    data: *mut c_uchar,
) -> c_short {
    require!(*row, data);
    let wanted = chunk(len);
    served(
        row,
        devHandle,
        |w| {
            w.u64(u64::from(add)).u64(u64::from(len));
        },
        |r| {
            let bytes = reply_list(r, wanted, |r| r.u8())?;
            store_array(data, &bytes);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_UserParaWr(
    devHandle: HAND,
    add: c_ulong,
    len: c_ulong,
    pWrData: *mut c_uchar,
) -> c_short {
    write(&table::USER_PARA_WR, devHandle, add, len, pWrData)
}

#[no_mangle]
pub extern "C" fn NMC_UserParaRd(
    devHandle: HAND,
    add: c_ulong,
    len: c_ulong,
    pRdData: *mut c_uchar,
) -> c_short {
    read(&table::USER_PARA_RD, devHandle, add, len, pRdData)
}

#[no_mangle]
pub extern "C" fn NMC_UserParaWrEx(
    devHandle: HAND,
    add: c_ulong,
    len: c_ulong,
    pWrData: *mut c_uchar,
) -> c_short {
    write(&table::USER_PARA_WR_EX, devHandle, add, len, pWrData)
}

#[no_mangle]
pub extern "C" fn NMC_UserParaRdEx(
    devHandle: HAND,
    add: c_ulong,
    len: c_ulong,
    pRdData: *mut c_uchar,
) -> c_short {
    read(&table::USER_PARA_RD_EX, devHandle, add, len, pRdData)
}
