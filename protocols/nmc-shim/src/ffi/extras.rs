//! PT started by an input edge and its parameters read back, the PTP compare, the 2-D compare
//! status under its comment name, the damping compensation (digest 001 §2.3, §2.5, §2.8,
//! §2.11, §2.13; Appendix A).

use std::ffi::{c_long, c_short};

use mcemu_nmc::sync_structs::PtPara;
use mcemu_nmc::table;

use super::sync_types::{TComp2DimensSts, TPtPara};
use super::{require, served, store, struct_getter, HAND};

impl From<PtPara> for TPtPara {
    fn from(p: PtPara) -> TPtPara {
        TPtPara {
            smoothDec: p.smooth_dec,
            abruptDec: p.abrupt_dec,
            ..TPtPara::default()
        }
    }
}

#[no_mangle]
pub extern "C" fn NMC_MtPtStartMtnEx(
    axisHandle: HAND,
    diIndex: c_short,
    diSns: c_short,
) -> c_short {
    served(
        &table::MT_PT_START_MTN_EX,
        axisHandle,
        |w| {
            w.i16(diIndex).i16(diSns);
        },
        |_| Ok(()),
    )
}

struct_getter!(NMC_MtPtGetPara, table::MT_PT_GET_PARA, TPtPara, PtPara);

#[no_mangle]
pub extern "C" fn NMC_MtSetPtpComparePara(
    axisHandle: HAND,
    dir: c_short,
    comparaPos: c_long,
    upDateVel: f64,
) -> c_short {
    served(
        &table::MT_SET_PTP_COMPARE_PARA,
        axisHandle,
        |w| {
            w.i16(dir).i64(i64::from(comparaPos)).f64(upDateVel);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGetPtpCompareSts(
    axisHandle: HAND,
    pIsCompareActive: *mut c_short,
    pIsCompareOut: *mut c_short,
) -> c_short {
    require!(
        table::MT_GET_PTP_COMPARE_STS,
        pIsCompareActive,
        pIsCompareOut
    );
    served(
        &table::MT_GET_PTP_COMPARE_STS,
        axisHandle,
        |_| {},
        |r| {
            store(pIsCompareActive, r.i16()?);
            store(pIsCompareOut, r.i16()?);
            Ok(())
        },
    )
}

/// The manual's comments call `NMC_Comp2DimensStatusEx` so (digest 001 Appendix A): the same
/// call.
#[no_mangle]
pub extern "C" fn NMC_Comp2DimensStatus(
    devHandle: HAND,
    group: c_short,
    pStatus: *mut TComp2DimensSts,
    chn: c_short,
) -> c_short {
    super::compare::NMC_Comp2DimensStatusEx(devHandle, group, pStatus, chn)
}

#[no_mangle]
pub extern "C" fn NMC_MtSetAxisDampCompParam(
    axisHandle: HAND,
    enable: c_short,
    param1: c_short,
    param2: c_short,
) -> c_short {
    served(
        &table::MT_SET_AXIS_DAMP_COMP_PARAM,
        axisHandle,
        |w| {
            w.i16(enable).i16(param1).i16(param2);
        },
        |_| Ok(()),
    )
}
