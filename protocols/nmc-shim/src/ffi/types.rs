//! The manual's structs with the C layout of `mtn_lib20.h` (`long` the platform's), and their
//! conversions to the wire's (`mcemu_nmc::structs`).

#![allow(non_snake_case)]

use std::ffi::{c_char, c_long, c_short, c_uchar, c_ulong, c_ushort};

use mcemu_nmc::structs::{CardInfo, HomeSetting, JogPara, PtpPara};

pub type HAND = c_ushort;

/// `long` from the wire's i64, saturated where the platform's `long` is 32 bits.
pub fn to_long(v: i64) -> c_long {
    c_long::try_from(v).unwrap_or(if v < 0 { c_long::MIN } else { c_long::MAX })
}

pub fn to_ulong(v: u64) -> c_ulong {
    c_ulong::try_from(v).unwrap_or(c_ulong::MAX)
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TPtpPara {
    pub acc: f64,
    pub dec: f64,
    pub startVel: f64,
    pub endVel: f64,
    pub smoothCoef: c_short,
    pub reserved: [c_short; 3],
}

impl From<TPtpPara> for PtpPara {
    fn from(p: TPtpPara) -> PtpPara {
        PtpPara {
            acc: p.acc,
            dec: p.dec,
            start_vel: p.startVel,
            end_vel: p.endVel,
            smooth_coef: p.smoothCoef,
        }
    }
}

impl From<PtpPara> for TPtpPara {
    fn from(p: PtpPara) -> TPtpPara {
        TPtpPara {
            acc: p.acc,
            dec: p.dec,
            startVel: p.start_vel,
            endVel: p.end_vel,
            smoothCoef: p.smooth_coef,
            reserved: [0; 3],
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TJogPara {
    pub acc: f64,
    pub dec: f64,
    pub smoothCoef: f64,
}

impl From<TJogPara> for JogPara {
    fn from(p: TJogPara) -> JogPara {
        JogPara {
            acc: p.acc,
            dec: p.dec,
            smooth_coef: p.smoothCoef,
        }
    }
}

impl From<JogPara> for TJogPara {
    fn from(p: JogPara) -> TJogPara {
        TJogPara {
            acc: p.acc,
            dec: p.dec,
            smoothCoef: p.smooth_coef,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct THomeSetting {
    pub mode: c_short,
    pub dir: c_short,
    pub offset: c_long,
    pub scan1stVel: f64,
    pub scan2ndVel: f64,
    pub acc: f64,
    pub reScanEn: c_uchar,
    pub homeEdge: c_uchar,
    pub lmtEdge: c_uchar,
    pub zEdge: c_uchar,
    pub iniRetPos: c_ulong,
    pub retSwOffset: c_ulong,
    pub safeLen: c_ulong,
    pub usePreSetPtpPara: c_uchar,
    pub reserved: [c_uchar; 3],
    pub reserved2: c_long,
}

impl From<THomeSetting> for HomeSetting {
    fn from(h: THomeSetting) -> HomeSetting {
        HomeSetting {
            mode: h.mode,
            dir: h.dir,
            offset: i64::from(h.offset),
            scan1st_vel: h.scan1stVel,
            scan2nd_vel: h.scan2ndVel,
            acc: h.acc,
            re_scan_en: h.reScanEn,
            home_edge: h.homeEdge,
            lmt_edge: h.lmtEdge,
            z_edge: h.zEdge,
            ini_ret_pos: u64::from(h.iniRetPos),
            ret_sw_offset: u64::from(h.retSwOffset),
            safe_len: u64::from(h.safeLen),
            use_pre_set_ptp_para: h.usePreSetPtpPara,
        }
    }
}

impl From<HomeSetting> for THomeSetting {
    fn from(h: HomeSetting) -> THomeSetting {
        THomeSetting {
            mode: h.mode,
            dir: h.dir,
            offset: to_long(h.offset),
            scan1stVel: h.scan1st_vel,
            scan2ndVel: h.scan2nd_vel,
            acc: h.acc,
            reScanEn: h.re_scan_en,
            homeEdge: h.home_edge,
            lmtEdge: h.lmt_edge,
            zEdge: h.z_edge,
            iniRetPos: to_ulong(h.ini_ret_pos),
            retSwOffset: to_ulong(h.ret_sw_offset),
            safeLen: to_ulong(h.safe_len),
            usePreSetPtpPara: h.use_pre_set_ptp_para,
            reserved: [0; 3],
            reserved2: 0,
        }
    }
}

fn c_chars<const N: usize>(b: [u8; N]) -> [c_char; N] {
    b.map(|b| b as c_char)
}

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct TCardInfo {
    pub strVer: [c_char; 16],
    pub strOemVer: [c_char; 16],
    pub time: [c_short; 6],
    pub axisNum: c_short,
    pub encNum: c_short,
    pub diNum: c_short,
    pub doNum: c_short,
    pub daNum: c_short,
    pub adNum: c_short,
    pub shioNum: c_short,
    pub reserved: c_short,
    pub ipv4: [c_char; 4],
    pub idStr: [c_char; 16],
    pub uid: [c_ulong; 4],
}

impl From<CardInfo> for TCardInfo {
    fn from(c: CardInfo) -> TCardInfo {
        TCardInfo {
            strVer: c_chars(c.str_ver),
            strOemVer: c_chars(c.str_oem_ver),
            time: c.time,
            axisNum: c.axis_num,
            encNum: c.enc_num,
            diNum: c.di_num,
            doNum: c.do_num,
            daNum: c.da_num,
            adNum: c.ad_num,
            shioNum: c.shio_num,
            reserved: 0,
            ipv4: c_chars(c.ipv4),
            idStr: c_chars(c.id_str),
            uid: c.uid.map(to_ulong),
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct TDevInfo {
    pub address: c_ushort,
    pub idStr: [c_char; 16],
    pub description: [c_char; 64],
    pub ID: c_ushort,
}
