//! Closed loop and profile configuration (digest 001 §2.15, §2.20) and the saved motion
//! configuration (§1.5, §2.2).

use std::ffi::{c_long, c_short};

use mcemu_nmc::ax_structs::{DacMotor, PidPara};
use mcemu_nmc::table;

use super::ax_types::{TDacMotor, TPidPara};
use super::types::to_long;
use super::{getter, load, require, served, setter, store, struct_getter, struct_setter, HAND};

setter!(NMC_MtSetCtrlMode, table::MT_SET_CTRL_MODE, c_short, i16);
getter!(
    NMC_MtGetCtrlMode,
    table::MT_GET_CTRL_MODE,
    c_short,
    i16,
    std::convert::identity
);

#[no_mangle]
pub extern "C" fn NMC_MtSetPIDPara(
    axisHandle: HAND,
    index: c_short,
    pidPara: *mut TPidPara,
) -> c_short {
    require!(table::MT_SET_PID_PARA, pidPara);
    let p = PidPara::from(load(pidPara.cast_const()));
    served(
        &table::MT_SET_PID_PARA,
        axisHandle,
        |w| {
            w.i16(index);
            p.write(w);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGetPIDPara(
    axisHandle: HAND,
    index: c_short,
    pPidPara: *mut TPidPara,
) -> c_short {
    require!(table::MT_GET_PID_PARA, pPidPara);
    served(
        &table::MT_GET_PID_PARA,
        axisHandle,
        |w| {
            w.i16(index);
        },
        |r| {
            store(pPidPara, TPidPara::from(PidPara::read(r)?));
            Ok(())
        },
    )
}

setter!(NMC_MtSetPIDIndex, table::MT_SET_PID_INDEX, c_short, i16);
getter!(
    NMC_MtGetPIDIndex,
    table::MT_GET_PID_INDEX,
    c_short,
    i16,
    std::convert::identity
);
struct_setter!(
    NMC_MtSetCloseLoopDac,
    table::MT_SET_CLOSE_LOOP_DAC,
    TDacMotor,
    DacMotor
);
struct_getter!(
    NMC_MtGetCloseLoopDac,
    table::MT_GET_CLOSE_LOOP_DAC,
    TDacMotor,
    DacMotor
);

/// The manual's text names `NMC_MtSetCloseLoopDac` so (digest 001 Appendix A): the same call.
#[no_mangle]
pub extern "C" fn NMC_SetCloseLoopDac(axisHandle: HAND, pDacPara: *mut TDacMotor) -> c_short {
    NMC_MtSetCloseLoopDac(axisHandle, pDacPara)
}

#[no_mangle]
pub extern "C" fn NMC_MtPrfConfig(
    axisHandle: HAND,
    mapAxisNo: c_short,
    port: c_short,
    startPos: c_long,
) -> c_short {
    served(
        &table::MT_PRF_CONFIG,
        axisHandle,
        |w| {
            w.i16(mapAxisNo).i16(port).i64(i64::from(startPos));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGetPrfConfig(
    axisHandle: HAND,
    mapAxisNo: *mut c_short,
    port: *mut c_short,
    startPos: *mut c_long,
) -> c_short {
    require!(table::MT_GET_PRF_CONFIG, mapAxisNo, port, startPos);
    served(
        &table::MT_GET_PRF_CONFIG,
        axisHandle,
        |_| {},
        |r| {
            store(mapAxisNo, r.i16()?);
            store(port, r.i16()?);
            store(startPos, to_long(r.i64()?));
            Ok(())
        },
    )
}

setter!(NMC_MtSetPrfCoe, table::MT_SET_PRF_COE, f64, f64);
getter!(
    NMC_MtGetPrfCoe,
    table::MT_GET_PRF_COE,
    f64,
    f64,
    std::convert::identity
);
setter!(NMC_MtSetEncCoe, table::MT_SET_ENC_COE, f64, f64);
getter!(
    NMC_MtGetEncCoe,
    table::MT_GET_ENC_COE,
    f64,
    f64,
    std::convert::identity
);
setter!(
    NMC_SaveMotionConfig,
    table::SAVE_MOTION_CONFIG,
    c_short,
    i16
);
