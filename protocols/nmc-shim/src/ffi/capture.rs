//! Capture, plain, repeated and advanced (digest 001 §2.18, §3.15).

use std::ffi::{c_long, c_short};

use mcemu_nmc::sync_structs::{read_array, AdvCaptureParam};
use mcemu_nmc::table;

use super::arrays::{bounded, store_slice};
use super::sync_types::TAdvCaptureParam;
use super::types::to_long;
use super::{action, getter, load, require, served, setter, store, HAND};

/// Most positions one `MtGetCaptRepeatPosMulti` reads (count ∈ [1, 32]).
const MAX_REPEAT_READ: usize = 32;

#[no_mangle]
pub extern "C" fn NMC_MtSetCaptSns(
    axisHandle: HAND,
    mode: c_short,
    ioSrc: c_short,
    level: c_short,
) -> c_short {
    served(
        &table::MT_SET_CAPT_SNS,
        axisHandle,
        |w| {
            w.i16(mode).i16(ioSrc).i16(level);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGetCaptSns(
    axisHandle: HAND,
    pMode: *mut c_short,
    pIoSrc: *mut c_short,
    pLevel: *mut c_short,
) -> c_short {
    require!(table::MT_GET_CAPT_SNS, pMode, pIoSrc, pLevel);
    served(
        &table::MT_GET_CAPT_SNS,
        axisHandle,
        |_| {},
        |r| {
            store(pMode, r.i16()?);
            store(pIoSrc, r.i16()?);
            store(pLevel, r.i16()?);
            Ok(())
        },
    )
}

action!(NMC_MtSetCapt, table::MT_SET_CAPT);
getter!(
    NMC_MtGetCaptPos,
    table::MT_GET_CAPT_POS,
    c_long,
    i64,
    to_long
);
action!(NMC_MtClrCaptSts, table::MT_CLR_CAPT_STS);

#[no_mangle]
pub extern "C" fn NMC_MtSetAdvCaptParam(
    devHandle: HAND,
    pParam: *mut TAdvCaptureParam,
    ch: c_short,
) -> c_short {
    require!(table::MT_SET_ADV_CAPT_PARAM, pParam);
    let p = AdvCaptureParam::from(load(pParam.cast_const()));
    served(
        &table::MT_SET_ADV_CAPT_PARAM,
        devHandle,
        |w| {
            p.write(w);
            w.i16(ch);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtClrAdvCaptSts(devHandle: HAND, ch: c_short) -> c_short {
    served(
        &table::MT_CLR_ADV_CAPT_STS,
        devHandle,
        |w| {
            w.i16(ch);
        },
        |_| Ok(()),
    )
}

/// `pPosArray` holds 2 positions: [0] leading edge, [1] trailing edge.
#[no_mangle]
pub extern "C" fn NMC_MtGetAdvCaptPos(
    devHandle: HAND,
    captSts: *mut c_short,
    pPosArray: *mut c_long,
    ch: c_short,
) -> c_short {
    require!(table::MT_GET_ADV_CAPT_POS, captSts, pPosArray);
    served(
        &table::MT_GET_ADV_CAPT_POS,
        devHandle,
        |w| {
            w.i16(ch);
        },
        |r| {
            store(captSts, r.i16()?);
            let pos = read_array(r, |r| r.i64())?;
            store_slice(pPosArray, 2, pos.into_iter().map(to_long));
            Ok(())
        },
    )
}

setter!(NMC_MtSetCaptRepeat, table::MT_SET_CAPT_REPEAT, c_short, i16);
getter!(
    NMC_MtGetCaptRepeatStatus,
    table::MT_GET_CAPT_REPEAT_STATUS,
    c_short,
    i16,
    std::convert::identity
);

#[no_mangle]
pub extern "C" fn NMC_MtGetCaptRepeatPosMulti(
    axisHandle: HAND,
    pPosArray: *mut c_long,
    startNum: c_short,
    count: c_short,
) -> c_short {
    require!(table::MT_GET_CAPT_REPEAT_POS_MULTI, pPosArray);
    let capacity = bounded(i64::from(count), MAX_REPEAT_READ);
    served(
        &table::MT_GET_CAPT_REPEAT_POS_MULTI,
        axisHandle,
        |w| {
            w.i16(startNum).i16(count);
        },
        |r| {
            let pos = read_array(r, |r| r.i64())?;
            store_slice(pPosArray, capacity, pos.into_iter().map(to_long));
            Ok(())
        },
    )
}
