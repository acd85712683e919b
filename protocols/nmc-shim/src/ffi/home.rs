//! Homing (digest 001 §2.6, §3.13).

use std::ffi::{c_long, c_short, c_ushort};

use mcemu_nmc::structs::HomeSetting;
use mcemu_nmc::table;

use super::types::{to_long, THomeSetting};
use super::{action, getter, load, require, served, store, HAND};

#[no_mangle]
pub extern "C" fn NMC_MtSetHomePara(axisHandle: HAND, pHomePara: *mut THomeSetting) -> c_short {
    require!(table::MT_SET_HOME_PARA, pHomePara);
    let h = HomeSetting::from(load(pHomePara.cast_const()));
    served(
        &table::MT_SET_HOME_PARA,
        axisHandle,
        |w| h.write(w),
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGetHomePara(axisHandle: HAND, pHomePara: *mut THomeSetting) -> c_short {
    require!(table::MT_GET_HOME_PARA, pHomePara);
    served(
        &table::MT_GET_HOME_PARA,
        axisHandle,
        |_| {},
        |r| {
            store(pHomePara, THomeSetting::from(HomeSetting::read(r)?));
            Ok(())
        },
    )
}

action!(NMC_MtHome, table::MT_HOME);
action!(NMC_MtTryHome, table::MT_TRY_HOME);
action!(NMC_MtHomeStop, table::MT_HOME_STOP);
getter!(
    NMC_MtGetHomeSts,
    table::MT_GET_HOME_STS,
    c_ushort,
    u16,
    std::convert::identity
);
getter!(
    NMC_MtGetHomeError,
    table::MT_GET_HOME_ERROR,
    c_long,
    i64,
    to_long
);
