//! Digital inputs and outputs, by group of 32 and by bit (digest 001 §2.8, §4.8).

use std::ffi::{c_long, c_short};

use mcemu_nmc::table::{self, Function};

use super::types::to_long;
use super::{require, served, store, HAND};

#[no_mangle]
pub extern "C" fn NMC_SetDOGroup(devHandle: HAND, value: c_long, groupID: c_short) -> c_short {
    served(
        &table::SET_DO_GROUP,
        devHandle,
        |w| {
            w.i64(i64::from(value)).i16(groupID);
        },
        |_| Ok(()),
    )
}

pub(super) fn get_group(
    row: &Function,
    devHandle: HAND,
    out: *mut c_long,
    groupID: c_short,
) -> c_short {
    served(
        row,
        devHandle,
        |w| {
            w.i16(groupID);
        },
        |r| {
            store(out, to_long(r.i64()?));
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetDOGroup(
    devHandle: HAND,
    pDoValue: *mut c_long,
    groupID: c_short,
) -> c_short {
    require!(table::GET_DO_GROUP, pDoValue);
    get_group(&table::GET_DO_GROUP, devHandle, pDoValue, groupID)
}

#[no_mangle]
pub extern "C" fn NMC_GetDIGroup(
    devHandle: HAND,
    pInValue: *mut c_long,
    groupID: c_short,
) -> c_short {
    require!(table::GET_DI_GROUP, pInValue);
    get_group(&table::GET_DI_GROUP, devHandle, pInValue, groupID)
}

#[no_mangle]
pub extern "C" fn NMC_SetDOBit(devHandle: HAND, bitIndex: c_short, value: c_short) -> c_short {
    served(
        &table::SET_DO_BIT,
        devHandle,
        |w| {
            w.i16(bitIndex).i16(value);
        },
        |_| Ok(()),
    )
}

fn get_bit(row: &Function, devHandle: HAND, bitIndex: c_short, out: *mut c_short) -> c_short {
    served(
        row,
        devHandle,
        |w| {
            w.i16(bitIndex);
        },
        |r| {
            store(out, r.i16()?);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetDOBit(
    devHandle: HAND,
    bitIndex: c_short,
    bitValue: *mut c_short,
) -> c_short {
    require!(table::GET_DO_BIT, bitValue);
    get_bit(&table::GET_DO_BIT, devHandle, bitIndex, bitValue)
}

#[no_mangle]
pub extern "C" fn NMC_GetDIBit(
    devHandle: HAND,
    bitIndex: c_short,
    bitValue: *mut c_short,
) -> c_short {
    require!(table::GET_DI_BIT, bitValue);
    get_bit(&table::GET_DI_BIT, devHandle, bitIndex, bitValue)
}
