//! The axis-level additions (id family 0x13xx; digest 001 §2.3–§2.5, §2.8, §2.20): packed
//! status and moves, positions, the home and alarm-clear levels, E-stop inputs, the planning
//! period and the watchdog.

use std::ffi::{c_long, c_short, c_ulong};

use mcemu_nmc::ax_structs::{AxisStsPack12Ex, EstopExParam, MovePtpPack8};
use mcemu_nmc::table;

use super::arrays::{bounded, store_slice};
use super::ax_types::{TAxisStsPack12Ex, TEstopExParam, TMovePtpPack8};
use super::types::{to_long, to_ulong};
use super::{
    action, getter, load, require, served, setter, store, struct_getter, struct_setter, HAND,
};

/// Most axes `NMC_MtGetStsMulti` reads: more than any device has.
const MAX_STS_AXES: usize = 64;

/// `count` status words from the first axis on, and the controller clock (125 µs ticks).
#[no_mangle]
pub extern "C" fn NMC_MtGetStsMulti(
    firstAxisHandle: HAND,
    pStsArray: *mut c_short,
    count: c_short,
    pClock: *mut c_ulong,
) -> c_short {
    require!(table::MT_GET_STS_MULTI, pStsArray, pClock);
    let capacity = bounded(i64::from(count), MAX_STS_AXES);
    served(
        &table::MT_GET_STS_MULTI,
        firstAxisHandle,
        |w| {
            w.i16(count);
        },
        |r| {
            let words = mcemu_nmc::sync_structs::read_array(r, |r| r.i16())?;
            store_slice(pStsArray, capacity, words);
            store(pClock, to_ulong(r.u64()?));
            Ok(())
        },
    )
}

struct_getter!(
    NMC_MtGetStsPack12Ex,
    table::MT_GET_STS_PACK12_EX,
    TAxisStsPack12Ex,
    AxisStsPack12Ex
);
struct_setter!(
    NMC_MtMovePtpAbsPack8,
    table::MT_MOVE_PTP_ABS_PACK8,
    TMovePtpPack8,
    MovePtpPack8
);
struct_setter!(
    NMC_MtMovePtpRelPack8,
    table::MT_MOVE_PTP_REL_PACK8,
    TMovePtpPack8,
    MovePtpPack8
);

setter!(NMC_MtSetAxisPos, table::MT_SET_AXIS_POS, c_long, i64);
setter!(NMC_MtSetEncPos, table::MT_SET_ENC_POS, c_long, i64);
action!(NMC_MtZeroPos, table::MT_ZERO_POS);
setter!(NMC_MtSetSvClr, table::MT_SET_SV_CLR, c_short, i16);
setter!(NMC_MtHomeSns, table::MT_HOME_SNS, c_short, i16);

#[no_mangle]
pub extern "C" fn NMC_MtSetEstopDI(axisHandle: HAND, gpiIndex: c_short, sense: c_short) -> c_short {
    served(
        &table::MT_SET_ESTOP_DI,
        axisHandle,
        |w| {
            w.i16(gpiIndex).i16(sense);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGetEstopDI(
    axisHandle: HAND,
    gpiIndex: *mut c_short,
    sense: *mut c_short,
) -> c_short {
    require!(table::MT_GET_ESTOP_DI, gpiIndex, sense);
    served(
        &table::MT_GET_ESTOP_DI,
        axisHandle,
        |_| {},
        |r| {
            store(gpiIndex, r.i16()?);
            store(sense, r.i16()?);
            Ok(())
        },
    )
}

getter!(
    NMC_MtGetMotionIOLogical,
    table::MT_GET_MOTION_IO_LOGICAL,
    c_long,
    i64,
    to_long
);
setter!(
    NMC_SetProfilePeriod,
    table::SET_PROFILE_PERIOD,
    c_short,
    i16
);
getter!(
    NMC_GetProfilePeriod,
    table::GET_PROFILE_PERIOD,
    c_short,
    i16,
    std::convert::identity
);

#[no_mangle]
pub extern "C" fn NMC_SetWatchDog(
    devHandle: HAND,
    timeout: c_long,
    stopMode: c_short,
    groupID: c_short,
    doValue: c_long,
) -> c_short {
    served(
        &table::SET_WATCH_DOG,
        devHandle,
        |w| {
            w.i64(i64::from(timeout))
                .i16(stopMode)
                .i16(groupID)
                .i64(i64::from(doValue));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_SetEstopDIEx(
    devHandle: HAND,
    pParam: *mut TEstopExParam,
    group: c_short,
) -> c_short {
    require!(table::SET_ESTOP_DI_EX, pParam);
    let p = EstopExParam::from(load(pParam.cast_const()));
    served(
        &table::SET_ESTOP_DI_EX,
        devHandle,
        |w| {
            p.write(w);
            w.i16(group);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetEstopDIEx(
    devHandle: HAND,
    pParam: *mut TEstopExParam,
    group: c_short,
) -> c_short {
    require!(table::GET_ESTOP_DI_EX, pParam);
    served(
        &table::GET_ESTOP_DI_EX,
        devHandle,
        |w| {
            w.i16(group);
        },
        |r| {
            store(pParam, TEstopExParam::from(EstopExParam::read(r)?));
            Ok(())
        },
    )
}

setter!(NMC_ClrEstopDIEx, table::CLR_ESTOP_DI_EX, c_short, i16);
