//! Coordinate systems (digest 001 §2.2, §2.7, §4.4): handles, parameters, the buffered
//! segments and commands, control and status. Position arrays have the lengths the manual
//! gives each function (XY arcs 2, XYZ lines 3, XYZA 4, D8 8, an axis mask one per bit); on
//! the wire they are a u16 count and i64s.

use std::ffi::{c_long, c_short};

use mcemu_nmc::crd::{CrdConfig, CrdPara, CrdSafePara, ExtCrdPara, LineD8Unit, D8_PACK_MAX};
use mcemu_nmc::handle::Handle;
use mcemu_nmc::payload::{PayloadError, Writer};
use mcemu_nmc::table::{self, Function};

use super::crd_types::{TCrdConfig, TCrdLineXYZD8Unit, TCrdPara, TCrdSafePara, TExtCrdPara};
use super::types::to_long;
use super::{
    action, getter, load, load_array, reply_list, require, served, setter, store, store_array,
    struct_getter, struct_setter, HAND,
};

/// The coordinate system the server names, in the slot of `devHandle` (its connection).
fn open(row: &Function, devHandle: HAND, itemNo: Option<c_short>, out: *mut HAND) -> c_short {
    let slot = Handle::decode(devHandle).map_or(0, |h| h.slot);
    served(
        row,
        devHandle,
        |w| {
            if let Some(n) = itemNo {
                w.i16(n);
            }
        },
        |r| {
            let h = Handle::decode(r.u16()?).ok_or(PayloadError::Short { at: 0 })?;
            store(out, h.in_slot(slot).encode());
            Ok(())
        },
    )
}

/// Coordinate system 0.
#[no_mangle]
pub extern "C" fn NMC_CrdOpen(devHandle: HAND, pCrdHandle: *mut HAND) -> c_short {
    require!(table::CRD_OPEN, pCrdHandle);
    open(&table::CRD_OPEN, devHandle, None, pCrdHandle)
}

#[no_mangle]
pub extern "C" fn NMC_CrdOpenEx(
    devHandle: HAND,
    itemNo: c_short,
    pCrdHandle: *mut HAND,
) -> c_short {
    require!(table::CRD_OPEN_EX, pCrdHandle);
    open(&table::CRD_OPEN_EX, devHandle, Some(itemNo), pCrdHandle)
}

/// Takes the handle's address (the manual's `PHAND`); the handle reads 0 afterwards.
#[no_mangle]
pub extern "C" fn NMC_CrdClose(pCrdHandle: *mut HAND) -> c_short {
    require!(table::CRD_CLOSE, pCrdHandle);
    let h = load(pCrdHandle.cast_const());
    let rc = served(&table::CRD_CLOSE, h, |_| {}, |_| Ok(()));
    if rc == 0 {
        store(pCrdHandle, 0);
    }
    rc
}

struct_setter!(NMC_CrdConfig, table::CRD_CONFIG, TCrdConfig, CrdConfig);
struct_getter!(
    NMC_CrdGetConfig,
    table::CRD_GET_CONFIG,
    TCrdConfig,
    CrdConfig
);
action!(NMC_CrdDelete, table::CRD_DELETE);
struct_setter!(NMC_CrdSetPara, table::CRD_SET_PARA, TCrdPara, CrdPara);
struct_getter!(NMC_CrdGetPara, table::CRD_GET_PARA, TCrdPara, CrdPara);
struct_setter!(
    NMC_CrdSetExtPara,
    table::CRD_SET_EXT_PARA,
    TExtCrdPara,
    ExtCrdPara
);
struct_getter!(
    NMC_CrdGetExtPara,
    table::CRD_GET_EXT_PARA,
    TExtCrdPara,
    ExtCrdPara
);
struct_setter!(
    NMC_CrdSetSafePara,
    table::CRD_SET_SAFE_PARA,
    TCrdSafePara,
    CrdSafePara
);

pub(super) fn put_longs(w: &mut Writer, values: &[c_long]) {
    w.u16(values.len() as u16);
    for v in values {
        w.i64(i64::from(*v));
    }
}

/// endVel, vel, synAcc and (the Ex forms) lookaheadDis: the tail of every segment.
#[derive(Clone, Copy)]
pub(super) struct Tail {
    pub(super) end_vel: f64,
    pub(super) vel: f64,
    pub(super) syn_acc: f64,
    pub(super) lookahead_dis: c_short,
}

impl Tail {
    fn put(self, w: &mut Writer) {
        w.f64(self.end_vel).f64(self.vel).f64(self.syn_acc);
    }
}

/// A segment call: the handle and segNo, then what `body` writes, then the tail.
pub(super) fn segment(
    row: &Function,
    crdHandle: HAND,
    segNo: c_long,
    body: impl FnOnce(&mut Writer),
    tail: Option<Tail>,
    lookahead: bool,
) -> c_short {
    served(
        row,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo));
            body(w);
            if let Some(t) = tail {
                t.put(w);
                if lookahead {
                    w.i16(t.lookahead_dis);
                }
            }
        },
        |_| Ok(()),
    )
}

#[allow(clippy::too_many_arguments)]
fn line(
    row: &Function,
    crdHandle: HAND,
    segNo: c_long,
    mask: c_short,
    target: *mut c_long,
    n: usize,
    tail: Tail,
    lookahead: bool,
) -> c_short {
    require!(*row, target);
    let t = load_array(target.cast_const(), n);
    segment(
        row,
        crdHandle,
        segNo,
        |w| {
            w.i16(mask);
            put_longs(w, &t);
        },
        Some(tail),
        lookahead,
    )
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdLineXYZEx(
    crdHandle: HAND,
    segNo: c_long,
    crdAxMask: c_short,
    pTgPosArray: *mut c_long,
    endVel: f64,
    vel: f64,
    synAcc: f64,
    lookaheadDis: c_short,
) -> c_short {
    let tail = Tail {
        end_vel: endVel,
        vel,
        syn_acc: synAcc,
        lookahead_dis: lookaheadDis,
    };
    let row = &table::CRD_LINE_XYZ_EX;
    line(row, crdHandle, segNo, crdAxMask, pTgPosArray, 3, tail, true)
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdLineXYZA(
    crdHandle: HAND,
    segNo: c_long,
    crdAxMask: c_short,
    pTgPosArray: *mut c_long,
    endVel: f64,
    vel: f64,
    synAcc: f64,
    lookaheadDis: c_short,
) -> c_short {
    let tail = Tail {
        end_vel: endVel,
        vel,
        syn_acc: synAcc,
        lookahead_dis: lookaheadDis,
    };
    let row = &table::CRD_LINE_XYZA;
    line(row, crdHandle, segNo, crdAxMask, pTgPosArray, 4, tail, true)
}

/// The examples' legacy form without lookaheadDis (digest 001 §2.7, S-CRD-FULL).
#[no_mangle]
pub extern "C" fn NMC_CrdLineXYZ(
    crdHandle: HAND,
    segNo: c_long,
    crdAxMask: c_short,
    pTgPosArray: *mut c_long,
    endVel: f64,
    vel: f64,
    synAcc: f64,
) -> c_short {
    let tail = Tail {
        end_vel: endVel,
        vel,
        syn_acc: synAcc,
        lookahead_dis: 0,
    };
    let row = &table::CRD_LINE_XYZ;
    line(
        row,
        crdHandle,
        segNo,
        crdAxMask,
        pTgPosArray,
        3,
        tail,
        false,
    )
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdLineXYZD8(
    crdHandle: HAND,
    segNo: c_long,
    crdAxmask: c_long,
    extAxMask: c_long,
    pTgPosArray: *mut c_long,
    endVel: f64,
    vel: f64,
    synAcc: f64,
    lookaheadDis: c_short,
) -> c_short {
    require!(table::CRD_LINE_XYZ_D8, pTgPosArray);
    let t = load_array(pTgPosArray.cast_const(), 8);
    let tail = Tail {
        end_vel: endVel,
        vel,
        syn_acc: synAcc,
        lookahead_dis: lookaheadDis,
    };
    segment(
        &table::CRD_LINE_XYZ_D8,
        crdHandle,
        segNo,
        |w| {
            w.i64(i64::from(crdAxmask)).i64(i64::from(extAxMask));
            put_longs(w, &t);
        },
        Some(tail),
        true,
    )
}

/// `count` ∈ [1, 18] (TV53); outside it the array is not read.
#[no_mangle]
pub extern "C" fn NMC_CrdLineXYZD8Pack(
    crdHandle: HAND,
    count: c_short,
    pCmdArray: *mut TCrdLineXYZD8Unit,
) -> c_short {
    require!(table::CRD_LINE_XYZ_D8_PACK, pCmdArray);
    let n = usize::try_from(count)
        .ok()
        .filter(|n| (1..=D8_PACK_MAX).contains(n))
        .unwrap_or(0);
    let units = load_array(pCmdArray.cast_const(), n);
    served(
        &table::CRD_LINE_XYZ_D8_PACK,
        crdHandle,
        |w| {
            w.i16(count).u16(units.len() as u16);
            for u in units {
                LineD8Unit::from(u).write(w);
            }
        },
        |_| Ok(()),
    )
}

#[allow(clippy::too_many_arguments)]
fn arc_center(
    row: &Function,
    crdHandle: HAND,
    segNo: c_long,
    target: *mut c_long,
    center: *mut c_long,
    dir: c_short,
    tail: Tail,
    lookahead: bool,
) -> c_short {
    require!(*row, target, center);
    let (t, c) = (
        load_array(target.cast_const(), 2),
        load_array(center.cast_const(), 2),
    );
    segment(
        row,
        crdHandle,
        segNo,
        |w| {
            put_longs(w, &t);
            put_longs(w, &c);
            w.i16(dir);
        },
        Some(tail),
        lookahead,
    )
}

macro_rules! arc_center_ex {
    ($name:ident, $row:expr) => {
        #[no_mangle]
        #[allow(clippy::too_many_arguments)]
        pub extern "C" fn $name(
            crdHandle: HAND,
            segNo: c_long,
            pTgPos: *mut c_long,
            pCenterPos: *mut c_long,
            circleDir: c_short,
            endVel: f64,
            vel: f64,
            synAcc: f64,
            lookaheadDis: c_short,
        ) -> c_short {
            let tail = Tail {
                end_vel: endVel,
                vel,
                syn_acc: synAcc,
                lookahead_dis: lookaheadDis,
            };
            arc_center(
                &$row, crdHandle, segNo, pTgPos, pCenterPos, circleDir, tail, true,
            )
        }
    };
}

arc_center_ex!(NMC_CrdArcCenterEx, table::CRD_ARC_CENTER_EX);
arc_center_ex!(NMC_CrdArcCenterYZEx, table::CRD_ARC_CENTER_YZ_EX);
arc_center_ex!(NMC_CrdArcCenterZXEx, table::CRD_ARC_CENTER_ZX_EX);

/// The examples' legacy XY form without lookaheadDis (S-CRD-FULL).
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdArcCenter(
    crdHandle: HAND,
    segNo: c_long,
    pTgPosArray: *mut c_long,
    pCenterPosArray: *mut c_long,
    circleDir: c_short,
    endVel: f64,
    vel: f64,
    synAcc: f64,
) -> c_short {
    let tail = Tail {
        end_vel: endVel,
        vel,
        syn_acc: synAcc,
        lookahead_dis: 0,
    };
    let row = &table::CRD_ARC_CENTER;
    arc_center(
        row,
        crdHandle,
        segNo,
        pTgPosArray,
        pCenterPosArray,
        circleDir,
        tail,
        false,
    )
}

macro_rules! arc_radius_ex {
    ($name:ident, $row:expr) => {
        #[no_mangle]
        #[allow(clippy::too_many_arguments)]
        pub extern "C" fn $name(
            crdHandle: HAND,
            segNo: c_long,
            pTgPos: *mut c_long,
            radius: f64,
            circleDir: c_short,
            endVel: f64,
            vel: f64,
            synAcc: f64,
            lookaheadDis: c_short,
        ) -> c_short {
            require!($row, pTgPos);
            let t = load_array(pTgPos.cast_const(), 2);
            let tail = Tail {
                end_vel: endVel,
                vel,
                syn_acc: synAcc,
                lookahead_dis: lookaheadDis,
            };
            segment(
                &$row,
                crdHandle,
                segNo,
                |w| {
                    put_longs(w, &t);
                    w.f64(radius).i16(circleDir);
                },
                Some(tail),
                true,
            )
        }
    };
}

arc_radius_ex!(NMC_CrdArcRadiusEx, table::CRD_ARC_RADIUS_EX);
arc_radius_ex!(NMC_CrdArcRadiusYZEx, table::CRD_ARC_RADIUS_YZ_EX);
arc_radius_ex!(NMC_CrdArcRadiusZXEx, table::CRD_ARC_RADIUS_ZX_EX);

#[allow(clippy::too_many_arguments)]
pub(super) fn through(
    row: &Function,
    crdHandle: HAND,
    segNo: c_long,
    mid: *mut c_long,
    target: *mut c_long,
    n: usize,
    tail: Tail,
    lookahead: bool,
) -> c_short {
    require!(*row, mid, target);
    let (m, t) = (
        load_array(mid.cast_const(), n),
        load_array(target.cast_const(), n),
    );
    segment(
        row,
        crdHandle,
        segNo,
        |w| {
            put_longs(w, &m);
            put_longs(w, &t);
        },
        Some(tail),
        lookahead,
    )
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdArcPPPEx(
    crdHandle: HAND,
    segNo: c_long,
    pMidPosArray: *mut c_long,
    pTgPosArray: *mut c_long,
    endVel: f64,
    vel: f64,
    synAcc: f64,
    lookaheadDis: c_short,
) -> c_short {
    let tail = Tail {
        end_vel: endVel,
        vel,
        syn_acc: synAcc,
        lookahead_dis: lookaheadDis,
    };
    let row = &table::CRD_ARC_PPP_EX;
    through(
        row,
        crdHandle,
        segNo,
        pMidPosArray,
        pTgPosArray,
        2,
        tail,
        true,
    )
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdArc3DEx(
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
    let row = &table::CRD_ARC_3D_EX;
    through(row, crdHandle, segNo, pMidPos, pTgPos, 3, tail, true)
}

/// The examples' legacy form without lookaheadDis (S-CRD-3DARC).
#[no_mangle]
pub extern "C" fn NMC_CrdArc3D(
    crdHandle: HAND,
    segNo: c_long,
    pMidPos: *mut c_long,
    pTgPos: *mut c_long,
    velEnd: f64,
    vel: f64,
    synAcc: f64,
) -> c_short {
    let tail = Tail {
        end_vel: velEnd,
        vel,
        syn_acc: synAcc,
        lookahead_dis: 0,
    };
    let row = &table::CRD_ARC_3D;
    through(row, crdHandle, segNo, pMidPos, pTgPos, 3, tail, false)
}

#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdHelixCenterEx(
    crdHandle: HAND,
    segNo: c_long,
    pTgPosArray: *mut c_long,
    pCenterPosArray: *mut c_long,
    circleDir: c_short,
    rounds: f64,
    endVel: f64,
    vel: f64,
    synAcc: f64,
    lookaheadDis: c_short,
) -> c_short {
    let row = &table::CRD_HELIX_CENTER_EX;
    require!(*row, pTgPosArray, pCenterPosArray);
    let (t, c) = (
        load_array(pTgPosArray.cast_const(), 3),
        load_array(pCenterPosArray.cast_const(), 2),
    );
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
            put_longs(w, &t);
            put_longs(w, &c);
            w.i16(circleDir).f64(rounds);
        },
        Some(tail),
        true,
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdEllipse(
    crdHandle: HAND,
    segNo: c_long,
    abRatio: f64,
    pCenterPos: *mut c_long,
    ellipseDir: c_short,
    vel: f64,
    synAcc: f64,
) -> c_short {
    let row = &table::CRD_ELLIPSE;
    require!(*row, pCenterPos);
    let c = load_array(pCenterPos.cast_const(), 2);
    segment(
        row,
        crdHandle,
        segNo,
        |w| {
            w.f64(abRatio);
            put_longs(w, &c);
            w.i16(ellipseDir).f64(vel).f64(synAcc);
        },
        None,
        false,
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufDo(
    crdHandle: HAND,
    segNo: c_long,
    doType: c_short,
    ch: c_long,
    value: c_long,
) -> c_short {
    segment(
        &table::CRD_BUF_DO,
        crdHandle,
        segNo,
        |w| {
            w.i16(doType).i64(i64::from(ch)).i64(i64::from(value));
        },
        None,
        false,
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufDoEx(
    crdHandle: HAND,
    segNo: c_long,
    group: c_short,
    doMask: c_long,
    doValue: c_long,
) -> c_short {
    segment(
        &table::CRD_BUF_DO_EX,
        crdHandle,
        segNo,
        |w| {
            w.i16(group).i64(i64::from(doMask)).i64(i64::from(doValue));
        },
        None,
        false,
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufDelay(
    crdHandle: HAND,
    segNo: c_long,
    scale: c_short,
    count: c_long,
) -> c_short {
    segment(
        &table::CRD_BUF_DELAY,
        crdHandle,
        segNo,
        |w| {
            w.i16(scale).i64(i64::from(count));
        },
        None,
        false,
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufWaitDI(
    crdHandle: HAND,
    segNo: c_long,
    index: c_short,
    diValue: c_short,
    waitLastTime: c_long,
) -> c_short {
    segment(
        &table::CRD_BUF_WAIT_DI,
        crdHandle,
        segNo,
        |w| {
            w.i16(index).i16(diValue).i64(i64::from(waitLastTime));
        },
        None,
        false,
    )
}

/// `pTgPos` holds one target per bit of `axisMask`, lowest axis first (S-CRD-BUFIO passes
/// `{10000}` for mask 0x8).
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn NMC_CrdBufAxMoveEx(
    crdHandle: HAND,
    segNo: c_long,
    axisMask: c_short,
    pTgPos: *mut c_long,
    vel: f64,
    acc: f64,
    blockEn: c_short,
    synEn: c_short,
) -> c_short {
    require!(table::CRD_BUF_AX_MOVE_EX, pTgPos);
    let n = (axisMask as u16).count_ones() as usize;
    let t = load_array(pTgPos.cast_const(), n);
    segment(
        &table::CRD_BUF_AX_MOVE_EX,
        crdHandle,
        segNo,
        |w| {
            w.i16(axisMask);
            put_longs(w, &t);
            w.f64(vel).f64(acc).i16(blockEn).i16(synEn);
        },
        None,
        false,
    )
}

action!(NMC_CrdStartMtn, table::CRD_START_MTN);
action!(NMC_CrdEndMtn, table::CRD_END_MTN);
action!(NMC_CrdStopMtn, table::CRD_STOP_MTN);
action!(NMC_CrdEstopMtn, table::CRD_ESTOP_MTN);
action!(NMC_CrdClrError, table::CRD_CLR_ERROR);
action!(NMC_CrdBufClr, table::CRD_BUF_CLR);
setter!(NMC_CrdSetOverride, table::CRD_SET_OVERRIDE, f64, f64);
getter!(
    NMC_CrdGetOverride,
    table::CRD_GET_OVERRIDE,
    f64,
    f64,
    std::convert::identity
);
setter!(NMC_CrdSetOverRide, table::CRD_SET_OVER_RIDE, f64, f64);
getter!(
    NMC_CrdGetOverRide,
    table::CRD_GET_OVER_RIDE,
    f64,
    f64,
    std::convert::identity
);
getter!(
    NMC_CrdGetSts,
    table::CRD_GET_STS,
    c_short,
    i16,
    std::convert::identity
);
getter!(
    NMC_CrdGetInnerSts,
    table::CRD_GET_INNER_STS,
    c_long,
    i64,
    to_long
);
getter!(
    NMC_CrdGetVel,
    table::CRD_GET_VEL,
    f64,
    f64,
    std::convert::identity
);
getter!(
    NMC_CrdBufGetFree,
    table::CRD_BUF_GET_FREE,
    c_long,
    i64,
    to_long
);
getter!(
    NMC_CrdBufGetUsed,
    table::CRD_BUF_GET_USED,
    c_long,
    i64,
    to_long
);
getter!(
    NMC_CrdGetUserSegNo,
    table::CRD_GET_USER_SEG_NO,
    c_long,
    i64,
    to_long
);
getter!(
    NMC_CrdGetBufAllCmdCnt,
    table::CRD_GET_BUF_ALL_CMD_CNT,
    c_long,
    i64,
    to_long
);
getter!(
    NMC_CrdGetBufLeftLength,
    table::CRD_GET_BUF_LEFT_LENGTH,
    f64,
    f64,
    std::convert::identity
);

#[no_mangle]
pub extern "C" fn NMC_CrdGetStsEx(
    crdHandle: HAND,
    pSts: *mut c_short,
    pUserSeg: *mut c_long,
) -> c_short {
    require!(table::CRD_GET_STS_EX, pSts, pUserSeg);
    served(
        &table::CRD_GET_STS_EX,
        crdHandle,
        |_| {},
        |r| {
            store(pSts, r.i16()?);
            store(pUserSeg, to_long(r.i64()?));
            Ok(())
        },
    )
}

/// The first `cnts` coordinates (the server answers the coordinate system's; at most `cnts`
/// are written).
fn positions(row: &Function, crdHandle: HAND, cnts: c_short, out: *mut c_long) -> c_short {
    require!(*row, out);
    served(
        row,
        crdHandle,
        |w| {
            w.i16(cnts);
        },
        |r| {
            let wanted = usize::try_from(cnts).unwrap_or(0);
            let values = reply_list(r, wanted, |r| r.i64().map(to_long))?;
            store_array(out, &values);
            Ok(())
        },
    )
}

macro_rules! positions {
    ($name:ident, $row:expr) => {
        #[no_mangle]
        pub extern "C" fn $name(crdHandle: HAND, cnts: c_short, pPosArray: *mut c_long) -> c_short {
            positions(&$row, crdHandle, cnts, pPosArray)
        }
    };
}

positions!(NMC_CrdGetPrfPos, table::CRD_GET_PRF_POS);
positions!(NMC_CrdGePrftPos, table::CRD_GE_PRFT_POS);
positions!(NMC_CrdGetAxisPos, table::CRD_GET_AXIS_POS);
positions!(NMC_CrdGetEncPos, table::CRD_GET_ENC_POS);

#[no_mangle]
pub extern "C" fn NMC_CrdSetLookAheadCentriAcc(
    crdHandle: HAND,
    isUsingSetAcc: c_short,
    centriAcc: f64,
) -> c_short {
    served(
        &table::CRD_SET_LOOK_AHEAD_CENTRI_ACC,
        crdHandle,
        |w| {
            w.i16(isUsingSetAcc).f64(centriAcc);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufWaitEncInPosition(
    crdHandle: HAND,
    segNo: c_long,
    axisMask: c_long,
    overTime: c_long,
) -> c_short {
    segment(
        &table::CRD_BUF_WAIT_ENC_IN_POSITION,
        crdHandle,
        segNo,
        |w| {
            w.i64(i64::from(axisMask)).i64(i64::from(overTime));
        },
        None,
        false,
    )
}

/// `soomthCoef` [sic] as the manual spells it.
#[no_mangle]
pub extern "C" fn NMC_CrdBufSetPtpMovePara(
    crdHandle: HAND,
    segNo: c_long,
    axisNo: c_short,
    vel: f64,
    acc: f64,
    soomthCoef: c_short,
) -> c_short {
    segment(
        &table::CRD_BUF_SET_PTP_MOVE_PARA,
        crdHandle,
        segNo,
        |w| {
            w.i16(axisNo).f64(vel).f64(acc).i16(soomthCoef);
        },
        None,
        false,
    )
}

/// `pRelPos` holds one distance per bit of `axisMask`, lowest axis first.
#[no_mangle]
pub extern "C" fn NMC_CrdBufAxMoveRel(
    crdHandle: HAND,
    segNo: c_long,
    axisMask: c_short,
    pRelPos: *mut c_long,
    blockEn: c_short,
    synEn: c_short,
) -> c_short {
    require!(table::CRD_BUF_AX_MOVE_REL, pRelPos);
    let n = (axisMask as u16).count_ones() as usize;
    let d = load_array(pRelPos.cast_const(), n);
    segment(
        &table::CRD_BUF_AX_MOVE_REL,
        crdHandle,
        segNo,
        |w| {
            w.i16(axisMask);
            put_longs(w, &d);
            w.i16(blockEn).i16(synEn);
        },
        None,
        false,
    )
}
