//! The names of digest 001 Appendix A that real programs use, each calling the function it
//! misspells through its own row.

use std::ffi::{c_long, c_short};

use mcemu_nmc::table;

use super::types::to_long;
use super::{require, served, store, HAND};

/// `NMC_SetDOGroup` as the summary table spells it.
#[no_mangle]
pub extern "C" fn NMC_SetDOGGroup(devHandle: HAND, value: c_long, groupID: c_short) -> c_short {
    served(
        &table::SET_DOG_GROUP,
        devHandle,
        |w| {
            w.i64(i64::from(value)).i16(groupID);
        },
        |_| Ok(()),
    )
}

/// `NMC_GetDOGroup` as the summary table spells it.
#[no_mangle]
pub extern "C" fn NMC_GetDOGGroup(
    devHandle: HAND,
    pDoValue: *mut c_long,
    groupID: c_short,
) -> c_short {
    require!(table::GET_DOG_GROUP, pDoValue);
    served(
        &table::GET_DOG_GROUP,
        devHandle,
        |w| {
            w.i16(groupID);
        },
        |r| {
            store(pDoValue, to_long(r.i64()?));
            Ok(())
        },
    )
}
