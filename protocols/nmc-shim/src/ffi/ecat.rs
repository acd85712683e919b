//! EtherCAT master, drive homing and SDO access (digest 001 §2.1).

use std::ffi::{c_char, c_int, c_long, c_short, c_uchar, c_uint, c_ushort};

use mcemu_nmc::payload::{PayloadError, Reader, Writer};
use mcemu_nmc::table::{self, Function};

use crate::last_error::report;

use super::types::to_long;
use super::{
    action, c_string, call, getter, load_array, reply_list, require, served, store, store_array,
    HAND,
};

/// A file name the manual bounds at no length: at most this many bytes travel.
const PATH_MAX: usize = 4096;

/// SDO data a call moves at most (the frame limit leaves room for it).
const SDO_MAX: usize = 1024;

#[no_mangle]
pub extern "C" fn NMC_EcatLoadConfigFromFile(
    devHandle: HAND,
    gmlFileName: *mut c_char,
    masterIdx: c_short,
) -> c_short {
    require!(table::ECAT_LOAD_CONFIG_FROM_FILE, gmlFileName);
    let name = c_string(gmlFileName.cast_const(), PATH_MAX);
    served(
        &table::ECAT_LOAD_CONFIG_FROM_FILE,
        devHandle,
        |w| {
            w.str(&name).i16(masterIdx);
        },
        |_| Ok(()),
    )
}

action!(NMC_EcatStart, table::ECAT_START);
action!(NMC_EcatStop, table::ECAT_STOP);
getter!(
    NMC_EcatGetSts,
    table::ECAT_GET_STS,
    c_ushort,
    u16,
    std::convert::identity
);

#[no_mangle]
pub extern "C" fn NMC_EcatGetResource(
    devHandle: HAND,
    pSlaveCnt: *mut c_short,
    pDriverCnt: *mut c_short,
    pIoCnt: *mut c_short,
) -> c_short {
    require!(table::ECAT_GET_RESOURCE, pSlaveCnt, pDriverCnt, pIoCnt);
    served(
        &table::ECAT_GET_RESOURCE,
        devHandle,
        |_| {},
        |r| {
            store(pSlaveCnt, r.i16()?);
            store(pDriverCnt, r.i16()?);
            store(pIoCnt, r.i16()?);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_EcatStartHome(
    axisHandle: HAND,
    method: c_int,
    velSwitch: c_int,
    velZero: c_int,
    acc: c_int,
    prmEx: c_int,
) -> c_short {
    served(
        &table::ECAT_START_HOME,
        axisHandle,
        |w| {
            w.i32(method)
                .i32(velSwitch)
                .i32(velZero)
                .i32(acc)
                .i32(prmEx);
        },
        |_| Ok(()),
    )
}

getter!(
    NMC_EcatGetHomeSts,
    table::ECAT_GET_HOME_STS,
    c_uchar,
    u8,
    std::convert::identity
);
action!(NMC_EcatStopHome, table::ECAT_STOP_HOME);

/// [`served`] for an SDO: a call the slave aborted still writes `abort_code` (the manual:
/// "指令出错时返回详细错误代码"), read from the refusal's text (`mcemu_nmc::sdo`); other
/// failures leave it as it was.
fn sdo_served(
    row: &Function,
    abort_code: *mut c_uint,
    handle: HAND,
    input: impl FnOnce(&mut Writer),
    output: impl FnOnce(&mut Reader<'_>) -> Result<(), PayloadError>,
) -> c_short {
    let result = call(row, handle, input, output);
    if let Some(code) = result
        .as_ref()
        .err()
        .and_then(|e| mcemu_nmc::sdo::abort_in(&e.description))
    {
        store(abort_code, code);
    }
    report(result)
}

fn sdo_len(len: c_uint) -> usize {
    usize::try_from(len).unwrap_or(usize::MAX).min(SDO_MAX)
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_EcatSdoRead(
    devHandle: HAND,
    devId: c_short,
    idx: c_ushort,
    sub_idx: c_uchar,
    len: c_uint,
    val: *mut c_uchar,
    abort_code: *mut c_uint,
) -> c_short {
    let row: &Function = &table::ECAT_SDO_READ;
    require!(*row, val, abort_code);
    let wanted = sdo_len(len);
    sdo_served(
        row,
        abort_code,
        devHandle,
        |w| {
            w.i16(devId).u16(idx).u8(sub_idx).u32(len);
        },
        |r| {
            let bytes = reply_list(r, wanted, |r| r.u8())?;
            store_array(val, &bytes);
            store(abort_code, r.u32()?);
            Ok(())
        },
    )
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_EcatSdoWrite(
    devHandle: HAND,
    devId: c_short,
    idx: c_ushort,
    sub_idx: c_uchar,
    len: c_uint,
    val: *mut c_uchar,
    abort_code: *mut c_uint,
) -> c_short {
    let row: &Function = &table::ECAT_SDO_WRITE;
    require!(*row, val, abort_code);
    let bytes = load_array(val.cast_const(), sdo_len(len));
    sdo_served(
        row,
        abort_code,
        devHandle,
        |w| {
            w.i16(devId)
                .u16(idx)
                .u8(sub_idx)
                .u32(len)
                .u16(bytes.len() as u16);
            for b in &bytes {
                w.u8(*b);
            }
        },
        |r| {
            store(abort_code, r.u32()?);
            Ok(())
        },
    )
}

getter!(
    NMC_EcatAxisGetErrorCode,
    table::ECAT_AXIS_GET_ERROR_CODE,
    c_ushort,
    u16,
    std::convert::identity
);
getter!(
    NMC_EcatAxisGetDi,
    table::ECAT_AXIS_GET_DI,
    c_long,
    i64,
    to_long
);
