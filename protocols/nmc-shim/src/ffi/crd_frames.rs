//! Coordinate transforms, arc sections, the break point and move protection, family 0x17xx
//! (digest 001 §2.7, §2.20 C3§10.5, §3.7); the C structs and their conversions to the wire's
//! (`mcemu_nmc::crd_frames`).

use std::ffi::{c_long, c_short};

use mcemu_nmc::crd::CRD_MAX_AXES;
use mcemu_nmc::crd_frames::{ArcSecSetting, MvProtectPara, MAX_ERR_TABLE_SECTION};
use mcemu_nmc::table;

use super::crd::put_longs;
use super::types::to_long;
use super::{
    action, load, load_array, require, served, setter, store, struct_getter, struct_setter, HAND,
};

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TArcSecSetting {
    pub minSectionLen: f64,
    pub maxArcDiff: f64,
    pub r: [f64; MAX_ERR_TABLE_SECTION],
    pub err: [f64; MAX_ERR_TABLE_SECTION + 1],
}

impl From<TArcSecSetting> for ArcSecSetting {
    fn from(s: TArcSecSetting) -> ArcSecSetting {
        ArcSecSetting {
            min_section_len: s.minSectionLen,
            max_arc_diff: s.maxArcDiff,
            r: s.r,
            err: s.err,
        }
    }
}

impl From<ArcSecSetting> for TArcSecSetting {
    fn from(s: ArcSecSetting) -> TArcSecSetting {
        TArcSecSetting {
            minSectionLen: s.min_section_len,
            maxArcDiff: s.max_arc_diff,
            r: s.r,
            err: s.err,
        }
    }
}

/// `TmvProtectPara` (the manual also spells it `TMvProtectPara`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TmvProtectPara {
    pub crdNo: [c_short; 2],
    pub crdAxNo: [c_short; 2],
    pub moveDir: [c_short; 2],
    pub orgDis: c_long,
    pub mvProtectDis: c_long,
    pub safeWaitPos: c_long,
    pub mvToSafeAcc: f64,
    pub mvToSafeVel: f64,
    pub stopCrdNo: c_short,
    pub reserved: [c_short; 3],
}

impl From<TmvProtectPara> for MvProtectPara {
    fn from(p: TmvProtectPara) -> MvProtectPara {
        MvProtectPara {
            crd_no: p.crdNo,
            crd_ax_no: p.crdAxNo,
            move_dir: p.moveDir,
            org_dis: i64::from(p.orgDis),
            mv_protect_dis: i64::from(p.mvProtectDis),
            safe_wait_pos: i64::from(p.safeWaitPos),
            mv_to_safe_acc: p.mvToSafeAcc,
            mv_to_safe_vel: p.mvToSafeVel,
            stop_crd_no: p.stopCrdNo,
        }
    }
}

impl From<MvProtectPara> for TmvProtectPara {
    fn from(p: MvProtectPara) -> TmvProtectPara {
        TmvProtectPara {
            crdNo: p.crd_no,
            crdAxNo: p.crd_ax_no,
            moveDir: p.move_dir,
            orgDis: to_long(p.org_dis),
            mvProtectDis: to_long(p.mv_protect_dis),
            safeWaitPos: to_long(p.safe_wait_pos),
            mvToSafeAcc: p.mv_to_safe_acc,
            mvToSafeVel: p.mv_to_safe_vel,
            stopCrdNo: p.stop_crd_no,
            reserved: [0; 3],
        }
    }
}

/// The rotary table's axis, its radians per pulse and the centre of rotation (X, Y pulses).
#[no_mangle]
pub extern "C" fn NMC_CrdSetTransRotate(
    crdHandle: HAND,
    rotAxisNo: c_short,
    angleRadEqual: f64,
    firstAxisInitPos: c_long,
    secAxisInitPos: c_long,
) -> c_short {
    served(
        &table::CRD_SET_TRANS_ROTATE,
        crdHandle,
        |w| {
            w.i16(rotAxisNo)
                .f64(angleRadEqual)
                .i64(i64::from(firstAxisInitPos))
                .i64(i64::from(secAxisInitPos));
        },
        |_| Ok(()),
    )
}

action!(NMC_CrdDelTransRotate, table::CRD_DEL_TRANS_ROTATE);

#[no_mangle]
pub extern "C" fn NMC_CrdSetTransPolar(
    crdHandle: HAND,
    rotAxNo: c_short,
    transAxNo: c_short,
    rotEquiv: f64,
) -> c_short {
    served(
        &table::CRD_SET_TRANS_POLAR,
        crdHandle,
        |w| {
            w.i16(rotAxNo).i16(transAxNo).f64(rotEquiv);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdRunToPolarPos(
    crdHandle: HAND,
    xPos: f64,
    yPos: f64,
    rotVel: f64,
    transVel: f64,
) -> c_short {
    served(
        &table::CRD_RUN_TO_POLAR_POS,
        crdHandle,
        |w| {
            w.f64(xPos).f64(yPos).f64(rotVel).f64(transVel);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdRunToPolarTheta(
    crdHandle: HAND,
    theta: f64,
    vel: f64,
    clrRoundFlag: c_short,
) -> c_short {
    served(
        &table::CRD_RUN_TO_POLAR_THETA,
        crdHandle,
        |w| {
            w.f64(theta).f64(vel).i16(clrRoundFlag);
        },
        |_| Ok(()),
    )
}

action!(NMC_CrdDelTransPolar, table::CRD_DEL_TRANS_POLAR);

/// `pAxisMapArray[0..4]`: the axes of X, Y, Z and A.
#[no_mangle]
pub extern "C" fn NMC_CrdSetTransXYZA(crdHandle: HAND, pAxisMapArray: *mut c_short) -> c_short {
    require!(table::CRD_SET_TRANS_XYZA, pAxisMapArray);
    let map = load_array(pAxisMapArray.cast_const(), CRD_MAX_AXES);
    served(
        &table::CRD_SET_TRANS_XYZA,
        crdHandle,
        |w| {
            w.u16(map.len() as u16);
            for a in &map {
                w.i16(*a);
            }
        },
        |_| Ok(()),
    )
}

action!(NMC_CrdDelTransXYZA, table::CRD_DEL_TRANS_XYZA);

/// The tool offset from a turn of `deltaTheta` and the XY move that brought the tip back.
#[no_mangle]
pub extern "C" fn NMC_CrdSetXYZAToolCalc(
    crdHandle: HAND,
    deltaTheta: f64,
    deltaX: c_long,
    deltaY: c_long,
    pToolX: *mut c_long,
    pToolY: *mut c_long,
) -> c_short {
    require!(table::CRD_SET_XYZA_TOOL_CALC, pToolX, pToolY);
    served(
        &table::CRD_SET_XYZA_TOOL_CALC,
        crdHandle,
        |w| {
            w.f64(deltaTheta)
                .i64(i64::from(deltaX))
                .i64(i64::from(deltaY));
        },
        |r| {
            store(pToolX, to_long(r.i64()?));
            store(pToolY, to_long(r.i64()?));
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdSetXYZAPara(
    crdHandle: HAND,
    pulse2Rad: f64,
    toolX: c_long,
    toolY: c_long,
) -> c_short {
    served(
        &table::CRD_SET_XYZA_PARA,
        crdHandle,
        |w| {
            w.f64(pulse2Rad).i64(i64::from(toolX)).i64(i64::from(toolY));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdGetXYZAPara(
    crdHandle: HAND,
    pPulse2Rad: *mut f64,
    ToolX: *mut c_long,
    pToolY: *mut c_long,
) -> c_short {
    require!(table::CRD_GET_XYZA_PARA, pPulse2Rad, ToolX, pToolY);
    served(
        &table::CRD_GET_XYZA_PARA,
        crdHandle,
        |_| {},
        |r| {
            store(pPulse2Rad, r.f64()?);
            store(ToolX, to_long(r.i64()?));
            store(pToolY, to_long(r.i64()?));
            Ok(())
        },
    )
}

/// `count` ∈ [1, 4]; outside it the array is not read.
#[no_mangle]
pub extern "C" fn NMC_CrdSetOffset(
    crdHandle: HAND,
    count: c_short,
    pOffsetArray: *mut c_long,
) -> c_short {
    require!(table::CRD_SET_OFFSET, pOffsetArray);
    let n = usize::try_from(count)
        .ok()
        .filter(|n| (1..=CRD_MAX_AXES).contains(n))
        .unwrap_or(0);
    let offsets = load_array(pOffsetArray.cast_const(), n);
    served(
        &table::CRD_SET_OFFSET,
        crdHandle,
        |w| {
            w.i16(count);
            put_longs(w, &offsets);
        },
        |_| Ok(()),
    )
}

struct_setter!(
    NMC_CrdSetArcSecPara,
    table::CRD_SET_ARC_SEC_PARA,
    TArcSecSetting,
    ArcSecSetting
);
struct_getter!(
    NMC_CrdGetArcSecPara,
    table::CRD_GET_ARC_SEC_PARA,
    TArcSecSetting,
    ArcSecSetting
);
setter!(
    NMC_CrdSetFourthAxisToTurnVel,
    table::CRD_SET_FOURTH_AXIS_TO_TURN_VEL,
    f64,
    f64
);

#[no_mangle]
pub extern "C" fn NMC_CrdGotoBreak(crdHandle: HAND, acc: f64, vel: f64) -> c_short {
    served(
        &table::CRD_GOTO_BREAK,
        crdHandle,
        |w| {
            w.f64(acc).f64(vel);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_SetMvProtect(devHandle: HAND, groupNo: c_short, mode: c_short) -> c_short {
    served(
        &table::SET_MV_PROTECT,
        devHandle,
        |w| {
            w.i16(groupNo).i16(mode);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_DelMvProtect(devHandle: HAND, groupNo: c_short) -> c_short {
    served(
        &table::DEL_MV_PROTECT,
        devHandle,
        |w| {
            w.i16(groupNo);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_SetMvProtectMode01Para(
    devHandle: HAND,
    groupNo: c_short,
    pMvProtectPara: *mut TmvProtectPara,
) -> c_short {
    require!(table::SET_MV_PROTECT_MODE01_PARA, pMvProtectPara);
    let p = MvProtectPara::from(load(pMvProtectPara.cast_const()));
    served(
        &table::SET_MV_PROTECT_MODE01_PARA,
        devHandle,
        |w| {
            w.i16(groupNo);
            p.write(w);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetMvProtectMode01Para(
    devHandle: HAND,
    groupNo: c_short,
    pMvProtectPara: *mut TmvProtectPara,
) -> c_short {
    require!(table::GET_MV_PROTECT_MODE01_PARA, pMvProtectPara);
    served(
        &table::GET_MV_PROTECT_MODE01_PARA,
        devHandle,
        |w| {
            w.i16(groupNo);
        },
        |r| {
            store(
                pMvProtectPara,
                TmvProtectPara::from(MvProtectPara::read(r)?),
            );
            Ok(())
        },
    )
}

/// 0 not enabled, 1 no interference, 2 interference.
#[no_mangle]
pub extern "C" fn NMC_GetMvProtectSts(
    devHandle: HAND,
    groupNo: c_short,
    pSts: *mut c_short,
) -> c_short {
    require!(table::GET_MV_PROTECT_STS, pSts);
    served(
        &table::GET_MV_PROTECT_STS,
        devHandle,
        |w| {
            w.i16(groupNo);
        },
        |r| {
            store(pSts, r.i16()?);
            Ok(())
        },
    )
}
