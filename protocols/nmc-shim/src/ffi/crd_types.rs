//! The coordinate-system structs with the C layout of `mtn_lib20.h` (digest 001 §3.7; `long`
//! the platform's) and their conversions to the wire's (`mcemu_nmc::crd`).

#![allow(non_snake_case)]

use std::ffi::{c_long, c_short};

use mcemu_nmc::crd::{CrdConfig, CrdPara, CrdSafePara, ExtCrdPara, LineD8Unit};

use super::types::to_long;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TCrdConfig {
    pub axCnts: c_short,
    pub reserved: [c_short; 3],
    pub pAxArray: [c_short; 4],
    pub port: [c_short; 4],
}

impl From<TCrdConfig> for CrdConfig {
    fn from(c: TCrdConfig) -> CrdConfig {
        CrdConfig {
            ax_cnts: c.axCnts,
            ax: c.pAxArray,
        }
    }
}

impl From<CrdConfig> for TCrdConfig {
    fn from(c: CrdConfig) -> TCrdConfig {
        TCrdConfig {
            axCnts: c.ax_cnts,
            reserved: [0; 3],
            pAxArray: c.ax,
            port: [0; 4],
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TCrdPara {
    pub orgFlag: c_short,
    pub reserved: [c_short; 3],
    pub offset: [c_long; 4],
    pub synAccMax: f64,
    pub synVelMax: f64,
}

impl From<TCrdPara> for CrdPara {
    fn from(p: TCrdPara) -> CrdPara {
        CrdPara {
            org_flag: p.orgFlag,
            offset: p.offset.map(i64::from),
            syn_acc_max: p.synAccMax,
            syn_vel_max: p.synVelMax,
        }
    }
}

impl From<CrdPara> for TCrdPara {
    fn from(p: CrdPara) -> TCrdPara {
        TCrdPara {
            orgFlag: p.org_flag,
            reserved: [0; 3],
            offset: p.offset.map(to_long),
            synAccMax: p.syn_acc_max,
            synVelMax: p.syn_vel_max,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TExtCrdPara {
    pub startVel: f64,
    pub T: f64,
    pub smoothDec: f64,
    pub abruptDec: f64,
    pub lookAheadSwitch: c_short,
    pub eventTime: c_short,
    pub reserved: [c_short; 2],
}

impl From<TExtCrdPara> for ExtCrdPara {
    fn from(p: TExtCrdPara) -> ExtCrdPara {
        ExtCrdPara {
            start_vel: p.startVel,
            t: p.T,
            smooth_dec: p.smoothDec,
            abrupt_dec: p.abruptDec,
            look_ahead_switch: p.lookAheadSwitch,
            event_time: p.eventTime,
        }
    }
}

impl From<ExtCrdPara> for TExtCrdPara {
    fn from(p: ExtCrdPara) -> TExtCrdPara {
        TExtCrdPara {
            startVel: p.start_vel,
            T: p.t,
            smoothDec: p.smooth_dec,
            abruptDec: p.abrupt_dec,
            lookAheadSwitch: p.look_ahead_switch,
            eventTime: p.event_time,
            reserved: [0; 2],
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TCrdSafePara {
    pub estpDec: f64,
    pub maxAcc: f64,
    pub maxVel: f64,
}

impl From<TCrdSafePara> for CrdSafePara {
    fn from(p: TCrdSafePara) -> CrdSafePara {
        CrdSafePara {
            estp_dec: p.estpDec,
            max_acc: p.maxAcc,
            max_vel: p.maxVel,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TCrdLineXYZD8Unit {
    pub segNo: c_long,
    pub crdAxMask: c_short,
    pub extAxMask: c_short,
    pub tgPos: [c_long; 8],
    pub vel: f32,
    pub endVel: f32,
    pub acc: f32,
    pub lookaheadDis: c_short,
    pub reserved: c_short,
}

impl From<TCrdLineXYZD8Unit> for LineD8Unit {
    fn from(u: TCrdLineXYZD8Unit) -> LineD8Unit {
        LineD8Unit {
            seg_no: i64::from(u.segNo),
            crd_ax_mask: u.crdAxMask,
            ext_ax_mask: u.extAxMask,
            tg_pos: u.tgPos.map(i64::from),
            vel: f64::from(u.vel),
            end_vel: f64::from(u.endVel),
            acc: f64::from(u.acc),
            lookahead_dis: u.lookaheadDis,
        }
    }
}
