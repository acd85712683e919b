//! The C layout of the 0x12xx families' structs (`mcemu_nmc::io_header`) and their conversions
//! to the wire's (`mcemu_nmc::io_structs`).

#![allow(non_snake_case)]

use std::ffi::{c_char, c_long, c_short};

use mcemu_nmc::io_structs::{BackGroup2, DioMapping, LibVersion, NmcTime};

use super::types::to_long;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TmLibVersion {
    pub strVer: [c_char; 16],
    pub major: c_short,
    pub minor: c_short,
    pub patch: c_short,
    pub reserved: c_short,
}

impl From<LibVersion> for TmLibVersion {
    fn from(v: LibVersion) -> TmLibVersion {
        TmLibVersion {
            strVer: v.str_ver.map(|b| b as c_char),
            major: v.major,
            minor: v.minor,
            patch: v.patch,
            reserved: 0,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TDioMappingCfg {
    pub enable: u8,
    pub pinGrp: u8,
    pub pinIndex: u8,
    pub outEnable: u8,
    pub newGrp: u8,
    pub newIndex: u8,
}

impl From<TDioMappingCfg> for DioMapping {
    fn from(c: TDioMappingCfg) -> DioMapping {
        DioMapping {
            enable: c.enable,
            pin_grp: c.pinGrp,
            pin_index: c.pinIndex,
            out_enable: c.outEnable,
            new_grp: c.newGrp,
            new_index: c.newIndex,
        }
    }
}

impl From<DioMapping> for TDioMappingCfg {
    fn from(m: DioMapping) -> TDioMappingCfg {
        TDioMappingCfg {
            enable: m.enable,
            pinGrp: m.pin_grp,
            pinIndex: m.pin_index,
            outEnable: m.out_enable,
            newGrp: m.new_grp,
            newIndex: m.new_index,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TNMCTime {
    pub ear: c_short,
    pub mon: c_short,
    pub day: c_short,
    pub hour: c_short,
    pub min: c_short,
    pub second: c_short,
}

impl From<TNMCTime> for NmcTime {
    fn from(t: TNMCTime) -> NmcTime {
        NmcTime([t.ear, t.mon, t.day, t.hour, t.min, t.second])
    }
}

impl From<NmcTime> for TNMCTime {
    fn from(NmcTime([ear, mon, day, hour, min, second]): NmcTime) -> TNMCTime {
        TNMCTime {
            ear,
            mon,
            day,
            hour,
            min,
            second,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TBackGroup2 {
    pub crdSegNo: [c_long; 2],
    pub crdPrfPos: [[c_long; 3]; 2],
    pub axPrfPos: [c_long; 12],
    pub axisPos: [c_long; 12],
    pub encPos: [c_long; 12],
}

impl From<BackGroup2> for TBackGroup2 {
    fn from(b: BackGroup2) -> TBackGroup2 {
        let mut t = TBackGroup2::default();
        let fields = t
            .crdSegNo
            .iter_mut()
            .chain(t.crdPrfPos.iter_mut().flatten())
            .chain(t.axPrfPos.iter_mut())
            .chain(t.axisPos.iter_mut())
            .chain(t.encPos.iter_mut());
        for (f, v) in fields.zip(b.0) {
            *f = to_long(v);
        }
        t
    }
}
