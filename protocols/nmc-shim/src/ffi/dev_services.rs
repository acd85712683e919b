//! Controller services (digest 001 §2.20, §4.9; rows 0x1240–0x1249): the ID written for the next
//! power-up, system parameters, the RTC, the system password, the power-fail backed variables.

use std::ffi::{c_char, c_long, c_short, c_ulong};

use mcemu_nmc::io_structs::{BackGroup2, NmcTime};
use mcemu_nmc::table;

use super::io_types::{TBackGroup2, TNMCTime};
use super::types::to_long;
use super::{c_string, load, require, served, store, HAND};

/// Strings the manual bounds at 16 bytes (ID, passwords); longer ones are cut here and
/// refused by the server when they reach its limit.
const STR_MAX: usize = 64;

#[no_mangle]
pub extern "C" fn NMC_DevWriteID(devHandle: HAND, pIdStr: *mut c_char) -> c_short {
    require!(table::DEV_WRITE_ID, pIdStr);
    let id = c_string(pIdStr.cast_const(), STR_MAX);
    served(
        &table::DEV_WRITE_ID,
        devHandle,
        |w| {
            w.str(&id);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_DevGetPara(devHandle: HAND, paraID: c_ulong, pValue: *mut c_long) -> c_short {
    require!(table::DEV_GET_PARA, pValue);
    served(
        &table::DEV_GET_PARA,
        devHandle,
        |w| {
            w.u64(u64::from(paraID));
        },
        |r| {
            store(pValue, to_long(r.i64()?));
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_DevSetPara(devHandle: HAND, paraID: c_ulong, value: c_long) -> c_short {
    served(
        &table::DEV_SET_PARA,
        devHandle,
        |w| {
            w.u64(u64::from(paraID)).i64(i64::from(value));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetTime(devHandle: HAND, pTime: *mut TNMCTime) -> c_short {
    require!(table::GET_TIME, pTime);
    served(
        &table::GET_TIME,
        devHandle,
        |_| {},
        |r| {
            store(pTime, TNMCTime::from(NmcTime::read(r)?));
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_SetTime(
    devHandle: HAND,
    pTime: *mut TNMCTime,
    pPassword: *mut c_char,
) -> c_short {
    require!(table::SET_TIME, pTime, pPassword);
    let t = NmcTime::from(load(pTime.cast_const()));
    let password = c_string(pPassword.cast_const(), STR_MAX);
    served(
        &table::SET_TIME,
        devHandle,
        |w| {
            t.write(w);
            w.str(&password);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_VerifyPassword(devHandle: HAND, pPassword: *mut c_char) -> c_short {
    require!(table::VERIFY_PASSWORD, pPassword);
    let password = c_string(pPassword.cast_const(), STR_MAX);
    served(
        &table::VERIFY_PASSWORD,
        devHandle,
        |w| {
            w.str(&password);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_ChangePassword(
    devHandle: HAND,
    pPasswordOld: *mut c_char,
    pPasswordNew: *mut c_char,
) -> c_short {
    require!(table::CHANGE_PASSWORD, pPasswordOld, pPasswordNew);
    let old = c_string(pPasswordOld.cast_const(), STR_MAX);
    let new = c_string(pPasswordNew.cast_const(), STR_MAX);
    served(
        &table::CHANGE_PASSWORD,
        devHandle,
        |w| {
            w.str(&old).str(&new);
        },
        |_| Ok(()),
    )
}

super::setter!(
    NMC_SetBackedVarOnOff,
    table::SET_BACKED_VAR_ON_OFF,
    c_short,
    i16
);
super::getter!(
    NMC_GetBackedVarOnOff,
    table::GET_BACKED_VAR_ON_OFF,
    c_short,
    i16,
    |v| v
);

#[no_mangle]
pub extern "C" fn NMC_GetBackedVarGroup2(devHandle: HAND, pBackVar: *mut TBackGroup2) -> c_short {
    require!(table::GET_BACKED_VAR_GROUP2, pBackVar);
    served(
        &table::GET_BACKED_VAR_GROUP2,
        devHandle,
        |_| {},
        |r| {
            store(pBackVar, TBackGroup2::from(BackGroup2::read(r)?));
            Ok(())
        },
    )
}
