//! Coordinate systems, family 0x14xx (digest 001 §2.7, §3.4, §3.9): the look-ahead parameters,
//! the packed status, the buffered position wait, full circles and the pushed path length;
//! the C structs and their conversions to the wire's (`mcemu_nmc::crd_lookahead`).

use std::ffi::{c_long, c_short};

use mcemu_nmc::crd_lookahead::{LookaheadPara, PackedCrdSts4, CRD_MAX_DIMENSION};
use mcemu_nmc::table;

use super::crd::{put_longs, segment, through, Tail};
use super::types::to_long;
use super::{
    getter, load_array, require, served, setter, store, struct_getter, struct_setter, HAND,
};

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TLookaheadPara {
    pub lookAheadSwitch: c_short,
    pub centAccEn: c_short,
    pub crossEn: c_short,
    pub eventTime: c_short,
    pub accMax: f64,
    pub T: f64,
    pub slowAng: f64,
    pub stopAng: f64,
    pub crossProp: f64,
    pub centAcc: f64,
    pub dvMax: [f64; CRD_MAX_DIMENSION],
    pub daMax: [f64; CRD_MAX_DIMENSION],
    pub radiusCoef: f64,
    pub radiusErr: f64,
    pub radiusAng: f64,
    pub radiusAngMax: f64,
    pub radiusAngMin: f64,
    pub axPropTimeUnitProp: c_short,
    pub preHandleEn: c_short,
    pub reserved: c_short,
    pub preHandleDisAngMin: f32,
    pub preHandleDisAngMax: f32,
    pub preHandleTol: f32,
    pub minCornerVel: f32,
    pub axProp: [f32; CRD_MAX_DIMENSION],
}

impl From<TLookaheadPara> for LookaheadPara {
    fn from(p: TLookaheadPara) -> LookaheadPara {
        LookaheadPara {
            look_ahead_switch: p.lookAheadSwitch,
            cent_acc_en: p.centAccEn,
            cross_en: p.crossEn,
            event_time: p.eventTime,
            acc_max: p.accMax,
            t: p.T,
            slow_ang: p.slowAng,
            stop_ang: p.stopAng,
            cross_prop: p.crossProp,
            cent_acc: p.centAcc,
            dv_max: p.dvMax,
            da_max: p.daMax,
            radius_coef: p.radiusCoef,
            radius_err: p.radiusErr,
            radius_ang: p.radiusAng,
            radius_ang_max: p.radiusAngMax,
            radius_ang_min: p.radiusAngMin,
            ax_prop_time_unit_prop: p.axPropTimeUnitProp,
            pre_handle_en: p.preHandleEn,
            pre_handle_dis_ang_min: f64::from(p.preHandleDisAngMin),
            pre_handle_dis_ang_max: f64::from(p.preHandleDisAngMax),
            pre_handle_tol: f64::from(p.preHandleTol),
            min_corner_vel: f64::from(p.minCornerVel),
            ax_prop: p.axProp.map(f64::from),
        }
    }
}

impl From<LookaheadPara> for TLookaheadPara {
    fn from(p: LookaheadPara) -> TLookaheadPara {
        TLookaheadPara {
            lookAheadSwitch: p.look_ahead_switch,
            centAccEn: p.cent_acc_en,
            crossEn: p.cross_en,
            eventTime: p.event_time,
            accMax: p.acc_max,
            T: p.t,
            slowAng: p.slow_ang,
            stopAng: p.stop_ang,
            crossProp: p.cross_prop,
            centAcc: p.cent_acc,
            dvMax: p.dv_max,
            daMax: p.da_max,
            radiusCoef: p.radius_coef,
            radiusErr: p.radius_err,
            radiusAng: p.radius_ang,
            radiusAngMax: p.radius_ang_max,
            radiusAngMin: p.radius_ang_min,
            axPropTimeUnitProp: p.ax_prop_time_unit_prop,
            preHandleEn: p.pre_handle_en,
            reserved: 0,
            preHandleDisAngMin: p.pre_handle_dis_ang_min as f32,
            preHandleDisAngMax: p.pre_handle_dis_ang_max as f32,
            preHandleTol: p.pre_handle_tol as f32,
            minCornerVel: p.min_corner_vel as f32,
            axProp: p.ax_prop.map(|v| v as f32),
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TPackedCrdSts4 {
    pub crdSts: c_short,
    pub axSts: [c_short; 4],
    pub prfPos: [c_long; 4],
    pub axisPos: [c_long; 4],
    pub encPos: [c_long; 4],
    pub userSeg: c_long,
    pub prfVel: f64,
    pub gpDi: c_long,
    pub gpDo: c_long,
    pub motDi: [c_short; 4],
    pub reserved: c_short,
    pub crdFreeSpace: c_long,
    pub crdUsedSpace: c_long,
}

impl From<PackedCrdSts4> for TPackedCrdSts4 {
    fn from(p: PackedCrdSts4) -> TPackedCrdSts4 {
        TPackedCrdSts4 {
            crdSts: p.crd_sts,
            axSts: p.ax_sts,
            prfPos: p.prf_pos.map(to_long),
            axisPos: p.axis_pos.map(to_long),
            encPos: p.enc_pos.map(to_long),
            userSeg: to_long(p.user_seg),
            prfVel: p.prf_vel,
            gpDi: to_long(p.gp_di),
            gpDo: to_long(p.gp_do),
            motDi: p.mot_di,
            reserved: 0,
            crdFreeSpace: to_long(p.crd_free_space),
            crdUsedSpace: to_long(p.crd_used_space),
        }
    }
}

struct_setter!(
    NMC_CrdSetLookaheadPara,
    table::CRD_SET_LOOKAHEAD_PARA,
    TLookaheadPara,
    LookaheadPara
);

/// defaultFlag 1 reads the manual's defaults, 0 the current values.
#[no_mangle]
pub extern "C" fn NMC_CrdGetLookaheadPara(
    crdHandle: HAND,
    lkhPara: *mut TLookaheadPara,
    defaultFlag: c_short,
) -> c_short {
    require!(table::CRD_GET_LOOKAHEAD_PARA, lkhPara);
    served(
        &table::CRD_GET_LOOKAHEAD_PARA,
        crdHandle,
        |w| {
            w.i16(defaultFlag);
        },
        |r| {
            store(lkhPara, TLookaheadPara::from(LookaheadPara::read(r)?));
            Ok(())
        },
    )
}

struct_getter!(
    NMC_CrdGetStsPack4,
    table::CRD_GET_STS_PACK4,
    TPackedCrdSts4,
    PackedCrdSts4
);

/// condition 0: pos ≤, 1: ≥; posSrc 0 encoder, 1 planned; overTime ms (0: no limit).
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdBufWaitPos(
    crdHandle: HAND,
    segNo: c_long,
    axisNo: c_short,
    condition: c_short,
    pos: c_long,
    posSrc: c_short,
    overTime: c_long,
) -> c_short {
    served(
        &table::CRD_BUF_WAIT_POS,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo))
                .i16(axisNo)
                .i16(condition)
                .i64(i64::from(pos))
                .i16(posSrc)
                .i64(i64::from(overTime));
        },
        |_| Ok(()),
    )
}

/// The full circle through the start, `pMidPos` and `pTgPos` (XYZ, 3 values each).
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdCircle3DEx(
    crdHandle: HAND,
    segNo: c_long,
    pMidPos: *mut c_long,
    pTgPos: *mut c_long,
    velEnd: f64,
    vel: f64,
    synAcc: f64,
    lookaheadDis: c_short,
) -> c_short {
    let tail = Tail {
        end_vel: velEnd,
        vel,
        syn_acc: synAcc,
        lookahead_dis: lookaheadDis,
    };
    let row = &table::CRD_CIRCLE_3D_EX;
    through(row, crdHandle, segNo, pMidPos, pTgPos, 3, tail, true)
}

/// The full circle through three XY points (2 values each), from and back to `pStPos`.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdCirclePPP(
    crdHandle: HAND,
    segNo: c_long,
    planeIdx: c_short,
    pStPos: *mut c_long,
    pMidPosArray: *mut c_long,
    pTgPosArray: *mut c_long,
    endVel: f64,
    vel: f64,
    synAcc: f64,
    lookaheadDis: c_short,
) -> c_short {
    let row = &table::CRD_CIRCLE_PPP;
    require!(*row, pStPos, pMidPosArray, pTgPosArray);
    let points = [pStPos, pMidPosArray, pTgPosArray].map(|p| load_array(p.cast_const(), 2));
    let tail = Tail {
        end_vel: endVel,
        vel,
        syn_acc: synAcc,
        lookahead_dis: lookaheadDis,
    };
    segment(
        row,
        crdHandle,
        segNo,
        |w| {
            w.i16(planeIdx);
            for p in &points {
                put_longs(w, p);
            }
        },
        Some(tail),
        true,
    )
}

setter!(
    NMC_CrdSetBufLengthFlag,
    table::CRD_SET_BUF_LENGTH_FLAG,
    c_short,
    i16
);
getter!(
    NMC_CrdGetBufLength,
    table::CRD_GET_BUF_LENGTH,
    f64,
    f64,
    std::convert::identity
);
