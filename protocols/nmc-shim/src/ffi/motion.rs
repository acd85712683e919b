//! Profile modes, PTP, JOG and stops (digest 001 §2.5).

use std::ffi::{c_long, c_short};

use mcemu_nmc::structs::{JogPara, PtpPara};
use mcemu_nmc::table;

use super::types::{to_long, TJogPara, TPtpPara};
use super::{action, getter, served, setter, struct_getter, struct_setter, HAND};

setter!(NMC_MtSetPrfMode, table::MT_SET_PRF_MODE, c_short, i16);
getter!(
    NMC_MtGetPrfMode,
    table::MT_GET_PRF_MODE,
    c_short,
    i16,
    std::convert::identity
);

struct_setter!(NMC_MtSetPtpPara, table::MT_SET_PTP_PARA, TPtpPara, PtpPara);
struct_getter!(NMC_MtGetPtpPara, table::MT_GET_PTP_PARA, TPtpPara, PtpPara);
setter!(NMC_MtSetPtpTgtPos, table::MT_SET_PTP_TGT_POS, c_long, i64);
getter!(
    NMC_MtGetPtpTgtPos,
    table::MT_GET_PTP_TGT_POS,
    c_long,
    i64,
    to_long
);
setter!(NMC_MtSetVel, table::MT_SET_VEL, f64, f64);
getter!(
    NMC_MtGetVel,
    table::MT_GET_VEL,
    f64,
    f64,
    std::convert::identity
);

struct_setter!(NMC_MtSetJogPara, table::MT_SET_JOG_PARA, TJogPara, JogPara);
struct_getter!(NMC_MtGetJogPara, table::MT_GET_JOG_PARA, TJogPara, JogPara);
action!(NMC_MtUpdate, table::MT_UPDATE);
setter!(NMC_MtUpdateMulti, table::MT_UPDATE_MULTI, c_long, i64);
action!(NMC_MtStop, table::MT_STOP);
action!(NMC_MtAbruptStop, table::MT_ABRUPT_STOP);
setter!(NMC_MtStopMulti, table::MT_STOP_MULTI, c_long, i64);
action!(NMC_MtEstp, table::MT_ESTP);

#[allow(clippy::too_many_arguments)]
fn move_ptp(
    row: &mcemu_nmc::table::Function,
    axisHandle: HAND,
    kinematics: [f64; 5],
    smoothCoef: c_short,
    pos: c_long,
) -> c_short {
    served(
        row,
        axisHandle,
        |w| {
            for k in kinematics {
                w.f64(k);
            }
            w.i16(smoothCoef).i64(i64::from(pos));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_MtMovePtpAbs(
    axisHandle: HAND,
    acc: f64,
    dec: f64,
    startVel: f64,
    endVel: f64,
    maxVel: f64,
    smoothCoef: c_short,
    tgtPos: c_long,
) -> c_short {
    let k = [acc, dec, startVel, endVel, maxVel];
    move_ptp(&table::MT_MOVE_PTP_ABS, axisHandle, k, smoothCoef, tgtPos)
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_MtMovePtpRel(
    axisHandle: HAND,
    acc: f64,
    dec: f64,
    startVel: f64,
    endVel: f64,
    maxVel: f64,
    smoothCoef: c_short,
    relPos: c_long,
) -> c_short {
    let k = [acc, dec, startVel, endVel, maxVel];
    move_ptp(&table::MT_MOVE_PTP_REL, axisHandle, k, smoothCoef, relPos)
}

#[no_mangle]
pub extern "C" fn NMC_MtMoveJog(
    axisHandle: HAND,
    acc: f64,
    dec: f64,
    maxVel: f64,
    smoothCoef: c_short,
    clrStsFlag: c_short,
) -> c_short {
    served(
        &table::MT_MOVE_JOG,
        axisHandle,
        |w| {
            w.f64(acc)
                .f64(dec)
                .f64(maxVel)
                .i16(smoothCoef)
                .i16(clrStsFlag);
        },
        |_| Ok(()),
    )
}
