//! Electronic gear (digest 001 §2.16): the slave's settings and its start.

use std::ffi::{c_long, c_short};

use mcemu_nmc::table;

use super::arrays::{bounded, load_slice};
use super::types::to_long;
use super::{getter, require, served, setter, store, HAND};

/// Most other axes a start call names (`pSyncAxArray`): more than any device has.
pub(crate) const MAX_SYNC_AXES: usize = 64;

setter!(NMC_MtGearSetDir, table::MT_GEAR_SET_DIR, c_short, i16);
getter!(
    NMC_MtGearGetDir,
    table::MT_GEAR_GET_DIR,
    c_short,
    i16,
    std::convert::identity
);

#[no_mangle]
pub extern "C" fn NMC_MtGearSetMaster(
    axisHandle: HAND,
    masterNo: c_short,
    masterType: c_short,
) -> c_short {
    served(
        &table::MT_GEAR_SET_MASTER,
        axisHandle,
        |w| {
            w.i16(masterNo).i16(masterType);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGearGetMaster(
    axisHandle: HAND,
    pmasterNo: *mut c_short,
    pmasterType: *mut c_short,
) -> c_short {
    require!(table::MT_GEAR_GET_MASTER, pmasterNo, pmasterType);
    served(
        &table::MT_GEAR_GET_MASTER,
        axisHandle,
        |_| {},
        |r| {
            store(pmasterNo, r.i16()?);
            store(pmasterType, r.i16()?);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGearSetRatio(
    axisHandle: HAND,
    masterEven: c_long,
    slaveEven: c_long,
    masterSlope: c_long,
) -> c_short {
    served(
        &table::MT_GEAR_SET_RATIO,
        axisHandle,
        |w| {
            w.i64(i64::from(masterEven))
                .i64(i64::from(slaveEven))
                .i64(i64::from(masterSlope));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGearGetRatio(
    axisHandle: HAND,
    pMasterEven: *mut c_long,
    pSlaveEven: *mut c_long,
    pMasterSlope: *mut c_long,
) -> c_short {
    require!(
        table::MT_GEAR_GET_RATIO,
        pMasterEven,
        pSlaveEven,
        pMasterSlope
    );
    served(
        &table::MT_GEAR_GET_RATIO,
        axisHandle,
        |_| {},
        |r| {
            store(pMasterEven, to_long(r.i64()?));
            store(pSlaveEven, to_long(r.i64()?));
            store(pMasterSlope, to_long(r.i64()?));
            Ok(())
        },
    )
}

/// A start call with other axes (`MtGearStartMtn`, `MtPtStartMtn`, `MtPvtStartMtn`): the
/// count, then the array of that many axis numbers (NULL allowed when the count is 0).
pub(crate) fn start_with(
    row: &mcemu_nmc::table::Function,
    axisHandle: HAND,
    count: c_short,
    axes: *mut c_short,
) -> c_short {
    let n = bounded(i64::from(count), MAX_SYNC_AXES);
    if n > 0 {
        require!(*row, axes);
    }
    let others = load_slice(axes.cast_const(), n);
    served(
        row,
        axisHandle,
        |w| {
            w.i16(count);
            mcemu_nmc::sync_structs::write_array(w, &others, |w, a| {
                w.i16(*a);
            });
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGearStartMtn(
    axisHandle: HAND,
    syncAxCnts: c_short,
    pSyncAxArray: *mut c_short,
) -> c_short {
    start_with(
        &table::MT_GEAR_START_MTN,
        axisHandle,
        syncAxCnts,
        pSyncAxArray,
    )
}
