//! Basic axis configuration (digest 001 §2.3, §2.20): alarm and limit inputs, soft limits, pulse
//! mode, encoder mode, safety limits, following error, filters, arrival band.

#![allow(non_snake_case)]

use std::ffi::{c_long, c_short, c_uchar, c_ushort};

use mcemu_nmc::axis_config::SafePara;
use mcemu_nmc::table::{self, Function};

use super::types::to_long;
use super::{getter, require, served, setter, store, struct_getter, struct_setter, HAND};

/// `TSafePara` with the C layout of `mtn_lib20.h` (digest 001 §3.6).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TSafePara {
    pub estpDec: f64,
    pub maxVel: f64,
    pub maxAcc: f64,
}

impl From<TSafePara> for SafePara {
    fn from(p: TSafePara) -> SafePara {
        SafePara {
            estp_dec: p.estpDec,
            max_vel: p.maxVel,
            max_acc: p.maxAcc,
        }
    }
}

impl From<SafePara> for TSafePara {
    fn from(p: SafePara) -> TSafePara {
        TSafePara {
            estpDec: p.estp_dec,
            maxVel: p.max_vel,
            maxAcc: p.max_acc,
        }
    }
}

/// A handle and two `short`s in.
fn two_shorts(row: &Function, handle: HAND, a: c_short, b: c_short) -> c_short {
    served(
        row,
        handle,
        |w| {
            w.i16(a).i16(b);
        },
        |_| Ok(()),
    )
}

/// A handle in, two `short`s out.
fn get_two_shorts(row: &Function, handle: HAND, a: *mut c_short, b: *mut c_short) -> c_short {
    require!(*row, a, b);
    served(
        row,
        handle,
        |_| {},
        |r| {
            store(a, r.i16()?);
            store(b, r.i16()?);
            Ok(())
        },
    )
}

/// A handle and two `long`s in.
fn two_longs(row: &Function, handle: HAND, a: c_long, b: c_long) -> c_short {
    served(
        row,
        handle,
        |w| {
            w.i64(i64::from(a)).i64(i64::from(b));
        },
        |_| Ok(()),
    )
}

/// A handle in, two `long`s out.
fn get_two_longs(row: &Function, handle: HAND, a: *mut c_long, b: *mut c_long) -> c_short {
    require!(*row, a, b);
    served(
        row,
        handle,
        |_| {},
        |r| {
            store(a, to_long(r.i64()?));
            store(b, to_long(r.i64()?));
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtSetAlarmCfg(
    axisHandle: HAND,
    alarmEnable: c_short,
    alarmSns: c_short,
) -> c_short {
    two_shorts(&table::MT_SET_ALARM_CFG, axisHandle, alarmEnable, alarmSns)
}

getter!(
    NMC_MtGetAlarmOnOff,
    table::MT_GET_ALARM_ON_OFF,
    c_short,
    i16,
    std::convert::identity
);
getter!(
    NMC_MtGetAlarmSns,
    table::MT_GET_ALARM_SNS,
    c_short,
    i16,
    std::convert::identity
);

#[no_mangle]
pub extern "C" fn NMC_MtSetLmtCfg(
    axisHandle: HAND,
    posLmtEnable: c_short,
    negLmtEnable: c_short,
    posLmtSns: c_short,
    negLmtSns: c_short,
) -> c_short {
    served(
        &table::MT_SET_LMT_CFG,
        axisHandle,
        |w| {
            w.i16(posLmtEnable)
                .i16(negLmtEnable)
                .i16(posLmtSns)
                .i16(negLmtSns);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGetLmtOnOff(
    axisHandle: HAND,
    posEn: *mut c_short,
    negEn: *mut c_short,
) -> c_short {
    get_two_shorts(&table::MT_GET_LMT_ON_OFF, axisHandle, posEn, negEn)
}

#[no_mangle]
pub extern "C" fn NMC_MtGetLmtSns(
    axisHandle: HAND,
    posSwt: *mut c_short,
    negSwt: *mut c_short,
) -> c_short {
    get_two_shorts(&table::MT_GET_LMT_SNS, axisHandle, posSwt, negSwt)
}

setter!(NMC_MtSwLmtOnOff, table::MT_SW_LMT_ON_OFF, c_short, i16);
getter!(
    NMC_MtGetSwLmtOnOff,
    table::MT_GET_SW_LMT_ON_OFF,
    c_short,
    i16,
    std::convert::identity
);

#[no_mangle]
pub extern "C" fn NMC_MtSwLmtValue(axisHandle: HAND, posLmt: c_long, negLmt: c_long) -> c_short {
    two_longs(&table::MT_SW_LMT_VALUE, axisHandle, posLmt, negLmt)
}

#[no_mangle]
pub extern "C" fn NMC_MtGetSwLmtValue(
    axisHandle: HAND,
    posLmt: *mut c_long,
    negLmt: *mut c_long,
) -> c_short {
    get_two_longs(&table::MT_GET_SW_LMT_VALUE, axisHandle, posLmt, negLmt)
}

#[no_mangle]
pub extern "C" fn NMC_MtSetStepMode(axisHandle: HAND, inv: c_short, mode: c_short) -> c_short {
    two_shorts(&table::MT_SET_STEP_MODE, axisHandle, inv, mode)
}

#[no_mangle]
pub extern "C" fn NMC_MtGetStepMode(
    axisHandle: HAND,
    pInv: *mut c_short,
    pMode: *mut c_short,
) -> c_short {
    get_two_shorts(&table::MT_GET_STEP_MODE, axisHandle, pInv, pMode)
}

#[no_mangle]
pub extern "C" fn NMC_SetEncMode(devHandle: HAND, encId: c_uchar, encMode: c_ushort) -> c_short {
    served(
        &table::SET_ENC_MODE,
        devHandle,
        |w| {
            w.u8(encId).u16(encMode);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetEncMode(
    devHandle: HAND,
    encId: c_uchar,
    encMode: *mut c_ushort,
) -> c_short {
    require!(table::GET_ENC_MODE, encMode);
    served(
        &table::GET_ENC_MODE,
        devHandle,
        |w| {
            w.u8(encId);
        },
        |r| {
            store(encMode, r.u16()?);
            Ok(())
        },
    )
}

struct_setter!(
    NMC_MtSetSafePara,
    table::MT_SET_SAFE_PARA,
    TSafePara,
    SafePara
);
struct_getter!(
    NMC_MtGetSafePara,
    table::MT_GET_SAFE_PARA,
    TSafePara,
    SafePara
);
setter!(NMC_MtSetPosErrLmt, table::MT_SET_POS_ERR_LMT, c_long, i64);
getter!(
    NMC_MtGetPosErrLmt,
    table::MT_GET_POS_ERR_LMT,
    c_long,
    i64,
    to_long
);
setter!(
    NMC_MtSetAxisVelFilter,
    table::MT_SET_AXIS_VEL_FILTER,
    c_short,
    i16
);
getter!(
    NMC_MtGetAxisVelFilter,
    table::MT_GET_AXIS_VEL_FILTER,
    c_short,
    i16,
    std::convert::identity
);
setter!(
    NMC_MtSetStepFilter,
    table::MT_SET_STEP_FILTER,
    c_ushort,
    u16
);
getter!(
    NMC_MtGetStepFilter,
    table::MT_GET_STEP_FILTER,
    c_ushort,
    u16,
    std::convert::identity
);
setter!(
    NMC_MtSetPosErrAction,
    table::MT_SET_POS_ERR_ACTION,
    c_short,
    i16
);
getter!(
    NMC_MtGetPosErrAction,
    table::MT_GET_POS_ERR_ACTION,
    c_short,
    i16,
    std::convert::identity
);

#[no_mangle]
pub extern "C" fn NMC_MtSetAxisArrivalPara(
    axisHandle: HAND,
    arrivalBand: c_long,
    stableTime: c_long,
) -> c_short {
    two_longs(
        &table::MT_SET_AXIS_ARRIVAL_PARA,
        axisHandle,
        arrivalBand,
        stableTime,
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGetAxisArrivalPara(
    axisHandle: HAND,
    pArrivalBand: *mut c_long,
    pStableTime: *mut c_long,
) -> c_short {
    get_two_longs(
        &table::MT_GET_AXIS_ARRIVAL_PARA,
        axisHandle,
        pArrivalBand,
        pStableTime,
    )
}
