//! Axis handles, status, positions and servo (digest 001 §2.2, §2.4, §2.8).

use std::ffi::{c_long, c_short};

use mcemu_nmc::handle::Handle;
use mcemu_nmc::payload::PayloadError;
use mcemu_nmc::table;

use super::types::to_long;
use super::{action, getter, require, served, setter, store, HAND};

/// The axis handle the server names, in the slot of `devHandle` (the same connection).
#[no_mangle]
pub extern "C" fn NMC_MtOpen(devHandle: HAND, itemNo: c_short, pAxisHandle: *mut HAND) -> c_short {
    require!(table::MT_OPEN, pAxisHandle);
    let slot = Handle::decode(devHandle).map_or(0, |h| h.slot);
    served(
        &table::MT_OPEN,
        devHandle,
        |w| {
            w.i16(itemNo);
        },
        |r| {
            let h = Handle::decode(r.u16()?).ok_or(PayloadError::Short { at: 0 })?;
            store(pAxisHandle, h.in_slot(slot).encode());
            Ok(())
        },
    )
}

getter!(
    NMC_MtGetSts,
    table::MT_GET_STS,
    c_short,
    i16,
    std::convert::identity
);
getter!(
    NMC_MtGetStsEx,
    table::MT_GET_STS_EX,
    c_short,
    i16,
    std::convert::identity
);
action!(NMC_MtClrError, table::MT_CLR_ERROR);
setter!(NMC_MtClrStsByBits, table::MT_CLR_STS_BY_BITS, c_short, i16);
getter!(NMC_MtGetPrfPos, table::MT_GET_PRF_POS, c_long, i64, to_long);
getter!(
    NMC_MtGetPrfVel,
    table::MT_GET_PRF_VEL,
    f64,
    f64,
    std::convert::identity
);
getter!(
    NMC_MtGetAxisPos,
    table::MT_GET_AXIS_POS,
    c_long,
    i64,
    to_long
);
getter!(NMC_MtGetCmdPos, table::MT_GET_CMD_POS, c_long, i64, to_long);
getter!(NMC_MtGetEncPos, table::MT_GET_ENC_POS, c_long, i64, to_long);
action!(NMC_MtSetSvOn, table::MT_SET_SV_ON);
action!(NMC_MtSetSvOff, table::MT_SET_SV_OFF);
getter!(
    NMC_MtGetMotionIO,
    table::MT_GET_MOTION_IO,
    c_long,
    i64,
    to_long
);
