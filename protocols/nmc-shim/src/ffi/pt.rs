//! PT and PVT streams (digest 001 §2.13–2.14).

use std::ffi::{c_long, c_short};

use mcemu_nmc::sync_structs::{write_array, PtPara, PvtPara};
use mcemu_nmc::table;

use super::arrays::{bounded, load_slice};
use super::gear::start_with;
use super::sync_types::{TPtPara, TPvtPara};
use super::types::to_long;
use super::{action, require, served, store, struct_getter, struct_setter, HAND};

/// Most points of one push (count ∈ [1, 32], TV56).
const MAX_PUSH: usize = 32;

#[no_mangle]
pub extern "C" fn NMC_MtPtSetStatic(
    axisHandle: HAND,
    onOff: c_short,
    loopCount: c_long,
) -> c_short {
    served(
        &table::MT_PT_SET_STATIC,
        axisHandle,
        |w| {
            w.i16(onOff).i64(i64::from(loopCount));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtPtGetStatic(
    axisHandle: HAND,
    pOnOff: *mut c_short,
    pLoopCount: *mut c_long,
) -> c_short {
    require!(table::MT_PT_GET_STATIC, pOnOff, pLoopCount);
    served(
        &table::MT_PT_GET_STATIC,
        axisHandle,
        |_| {},
        |r| {
            store(pOnOff, r.i16()?);
            store(pLoopCount, to_long(r.i64()?));
            Ok(())
        },
    )
}

/// Two `short` outs (`MtPtGetSpace`, `MtPvtBufGetSpace`).
fn two_shorts(
    row: &mcemu_nmc::table::Function,
    handle: HAND,
    a: *mut c_short,
    b: *mut c_short,
) -> c_short {
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

#[no_mangle]
pub extern "C" fn NMC_MtPtGetSpace(
    axisHandle: HAND,
    pSpace: *mut c_short,
    pUsed: *mut c_short,
) -> c_short {
    two_shorts(&table::MT_PT_GET_SPACE, axisHandle, pSpace, pUsed)
}

#[no_mangle]
pub extern "C" fn NMC_MtPtPush(
    axisHandle: HAND,
    count: c_short,
    pPosArray: *mut f64,
    pTimeArray: *mut c_long,
    pTypeArray: *mut c_short,
) -> c_short {
    require!(table::MT_PT_PUSH, pPosArray, pTimeArray, pTypeArray);
    let n = bounded(i64::from(count), MAX_PUSH);
    let pos = load_slice(pPosArray.cast_const(), n);
    let time = load_slice(pTimeArray.cast_const(), n);
    let kind = load_slice(pTypeArray.cast_const(), n);
    served(
        &table::MT_PT_PUSH,
        axisHandle,
        |w| {
            w.i16(count);
            write_array(w, &pos, |w, v| {
                w.f64(*v);
            });
            write_array(w, &time, |w, v| {
                w.i64(i64::from(*v));
            });
            write_array(w, &kind, |w, v| {
                w.i16(*v);
            });
        },
        |_| Ok(()),
    )
}

action!(NMC_MtPtBufClr, table::MT_PT_BUF_CLR);

#[no_mangle]
pub extern "C" fn NMC_MtPtStartMtn(
    axisHandle: HAND,
    otherSynAxCnts: c_short,
    pOtherSynAxArray: *mut c_short,
) -> c_short {
    start_with(
        &table::MT_PT_START_MTN,
        axisHandle,
        otherSynAxCnts,
        pOtherSynAxArray,
    )
}

struct_setter!(NMC_MtPtSetPara, table::MT_PT_SET_PARA, TPtPara, PtPara);
struct_setter!(NMC_MtPvtSetPara, table::MT_PVT_SET_PARA, TPvtPara, PvtPara);
struct_getter!(NMC_MtPvtGetPara, table::MT_PVT_GET_PARA, TPvtPara, PvtPara);

#[no_mangle]
pub extern "C" fn NMC_MtPvtData(
    axisHandle: HAND,
    count: c_short,
    pPosArray: *mut f64,
    pTimeArray: *mut f64,
    pVelArray: *mut f64,
) -> c_short {
    require!(table::MT_PVT_DATA, pPosArray, pTimeArray, pVelArray);
    let n = bounded(i64::from(count), MAX_PUSH);
    let arrays = [pPosArray, pTimeArray, pVelArray].map(|p| load_slice(p.cast_const(), n));
    served(
        &table::MT_PVT_DATA,
        axisHandle,
        |w| {
            w.i16(count);
            for a in &arrays {
                write_array(w, a, |w, v| {
                    w.f64(*v);
                });
            }
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtPvtBufGetSpace(
    axisHandle: HAND,
    pFreeSpace: *mut c_short,
    pUsedSpace: *mut c_short,
) -> c_short {
    two_shorts(
        &table::MT_PVT_BUF_GET_SPACE,
        axisHandle,
        pFreeSpace,
        pUsedSpace,
    )
}

action!(NMC_MtPvtBufClr, table::MT_PVT_BUF_CLR);

#[no_mangle]
pub extern "C" fn NMC_MtPvtStartMtn(
    axisHandle: HAND,
    otherSynAxCnts: c_short,
    pOtherSynAxArray: *mut c_short,
) -> c_short {
    start_with(
        &table::MT_PVT_START_MTN,
        axisHandle,
        otherSynAxCnts,
        pOtherSynAxArray,
    )
}
