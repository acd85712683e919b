//! Electronic cam "Follow" (digest 001 §2.17): a slave's master, start event, direction, loop
//! count, its two FIFOs, start and switch.

use std::ffi::{c_long, c_short};

use mcemu_nmc::table;

use super::gear::start_with;
use super::types::to_long;
use super::{getter, require, served, setter, store, HAND};

#[no_mangle]
pub extern "C" fn NMC_MtFollowSetMaster(
    axisHandle: HAND,
    masterNo: c_short,
    masterType: c_short,
) -> c_short {
    served(
        &table::MT_FOLLOW_SET_MASTER,
        axisHandle,
        |w| {
            w.i16(masterNo).i16(masterType);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtFollowGetMaster(
    axisHandle: HAND,
    pMasterNo: *mut c_short,
    pMasterType: *mut c_short,
) -> c_short {
    require!(table::MT_FOLLOW_GET_MASTER, pMasterNo, pMasterType);
    served(
        &table::MT_FOLLOW_GET_MASTER,
        axisHandle,
        |_| {},
        |r| {
            store(pMasterNo, r.i16()?);
            store(pMasterType, r.i16()?);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtFollowSetEvent(
    axisHandle: HAND,
    eventType: c_short,
    masterDir: c_short,
    pos: c_long,
) -> c_short {
    served(
        &table::MT_FOLLOW_SET_EVENT,
        axisHandle,
        |w| {
            w.i16(eventType).i16(masterDir).i64(i64::from(pos));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtFollowGetEvent(
    axisHandle: HAND,
    pEventType: *mut c_short,
    pMasterDir: *mut c_short,
    pPos: *mut c_long,
) -> c_short {
    require!(table::MT_FOLLOW_GET_EVENT, pEventType, pMasterDir, pPos);
    served(
        &table::MT_FOLLOW_GET_EVENT,
        axisHandle,
        |_| {},
        |r| {
            store(pEventType, r.i16()?);
            store(pMasterDir, r.i16()?);
            store(pPos, to_long(r.i64()?));
            Ok(())
        },
    )
}

setter!(NMC_MtFollowSetDir, table::MT_FOLLOW_SET_DIR, c_short, i16);
getter!(
    NMC_MtFollowGetDir,
    table::MT_FOLLOW_GET_DIR,
    c_short,
    i16,
    std::convert::identity
);
setter!(
    NMC_MtFollowSetLoopCount,
    table::MT_FOLLOW_SET_LOOP_COUNT,
    c_long,
    i64
);
getter!(
    NMC_MtFollowGetLoopCount,
    table::MT_FOLLOW_GET_LOOP_COUNT,
    c_long,
    i64,
    to_long
);

#[no_mangle]
pub extern "C" fn NMC_MtFollowPushData(
    axisHandle: HAND,
    masterPos: c_long,
    slavePos: f64,
    segType: c_short,
    fifoNo: c_short,
) -> c_short {
    served(
        &table::MT_FOLLOW_PUSH_DATA,
        axisHandle,
        |w| {
            w.i64(i64::from(masterPos))
                .f64(slavePos)
                .i16(segType)
                .i16(fifoNo);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtFollowGetSpace(
    axisHandle: HAND,
    pSpace: *mut c_short,
    fifoNo: c_short,
) -> c_short {
    require!(table::MT_FOLLOW_GET_SPACE, pSpace);
    served(
        &table::MT_FOLLOW_GET_SPACE,
        axisHandle,
        |w| {
            w.i16(fifoNo);
        },
        |r| {
            store(pSpace, r.i16()?);
            Ok(())
        },
    )
}

setter!(NMC_MtFollowClear, table::MT_FOLLOW_CLEAR, c_short, i16);

#[no_mangle]
pub extern "C" fn NMC_MtFollowStart(
    axisHandle: HAND,
    syncAxCnts: c_short,
    pSyncAxArray: *mut c_short,
) -> c_short {
    start_with(
        &table::MT_FOLLOW_START,
        axisHandle,
        syncAxCnts,
        pSyncAxArray,
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtFollowSwitch(
    axisHandle: HAND,
    syncAxCnts: c_short,
    pSyncAxArray: *mut c_short,
) -> c_short {
    start_with(
        &table::MT_FOLLOW_SWITCH,
        axisHandle,
        syncAxCnts,
        pSyncAxArray,
    )
}
