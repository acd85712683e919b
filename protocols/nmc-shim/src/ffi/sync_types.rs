//! The C layout of the synchronised-motion structs (`mtn_lib20.h`, digest 001 §3.15–§3.17)
//! and their conversions to the wire's (`mcemu_nmc::sync_structs`).

#![allow(non_snake_case)]

use std::ffi::{c_long, c_short};

use mcemu_nmc::sync_structs::{
    AdvCaptureParam, Comp2D, Comp2DTable, Comp2DimensParam, Comp2DimensSts, CompData, PtPara,
    PvtPara,
};

use super::types::to_long;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TPtPara {
    pub smoothDec: f64,
    pub abruptDec: f64,
    pub reserved1: [f64; 2],
    pub reserved2: [c_long; 4],
}

impl From<TPtPara> for PtPara {
    fn from(p: TPtPara) -> PtPara {
        PtPara {
            smooth_dec: p.smoothDec,
            abrupt_dec: p.abruptDec,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TPvtPara {
    pub smoothDec: f64,
    pub abruptDec: f64,
    pub reserved1: [f64; 2],
    pub dataMode: c_long,
    pub loopCount: c_long,
    pub reserved2: [c_long; 4],
}

impl From<TPvtPara> for PvtPara {
    fn from(p: TPvtPara) -> PvtPara {
        PvtPara {
            smooth_dec: p.smoothDec,
            abrupt_dec: p.abruptDec,
            data_mode: i64::from(p.dataMode),
            loop_count: i64::from(p.loopCount),
        }
    }
}

impl From<PvtPara> for TPvtPara {
    fn from(p: PvtPara) -> TPvtPara {
        TPvtPara {
            smoothDec: p.smooth_dec,
            abruptDec: p.abrupt_dec,
            dataMode: to_long(p.data_mode),
            loopCount: to_long(p.loop_count),
            ..TPvtPara::default()
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TAdvCaptureParam {
    pub capPosIndex: c_short,
    pub trigSrc: c_short,
    pub trigIndex: c_short,
    pub filter: c_short,
    pub trigValue: c_long,
}

impl From<TAdvCaptureParam> for AdvCaptureParam {
    fn from(p: TAdvCaptureParam) -> AdvCaptureParam {
        AdvCaptureParam {
            cap_pos_index: p.capPosIndex,
            trig_src: p.trigSrc,
            trig_index: p.trigIndex,
            filter: p.filter,
            trig_value: i64::from(p.trigValue),
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TComp2DimensParamEx {
    pub outputChn: c_short,
    pub outputType: c_short,
    pub chnType: c_short,
    pub dir1No: c_short,
    pub dir2No: c_short,
    pub posSrc: c_short,
    pub stLevel: c_short,
    pub errZone: c_short,
    pub directOutZone: c_short,
    pub vibrateRange: c_short,
    pub gateTime: c_long,
    pub minIntervalTime: c_long,
    pub reserved: [c_long; 8],
}

impl From<TComp2DimensParamEx> for Comp2DimensParam {
    fn from(p: TComp2DimensParamEx) -> Comp2DimensParam {
        Comp2DimensParam {
            output_chn: p.outputChn,
            output_type: p.outputType,
            chn_type: p.chnType,
            dir1_no: p.dir1No,
            dir2_no: p.dir2No,
            pos_src: p.posSrc,
            st_level: p.stLevel,
            err_zone: p.errZone,
            direct_out_zone: p.directOutZone,
            vibrate_range: p.vibrateRange,
            gate_time: i64::from(p.gateTime),
            min_interval_time: i64::from(p.minIntervalTime),
        }
    }
}

impl From<Comp2DimensParam> for TComp2DimensParamEx {
    fn from(p: Comp2DimensParam) -> TComp2DimensParamEx {
        TComp2DimensParamEx {
            outputChn: p.output_chn,
            outputType: p.output_type,
            chnType: p.chn_type,
            dir1No: p.dir1_no,
            dir2No: p.dir2_no,
            posSrc: p.pos_src,
            stLevel: p.st_level,
            errZone: p.err_zone,
            directOutZone: p.direct_out_zone,
            vibrateRange: p.vibrate_range,
            gateTime: to_long(p.gate_time),
            minIntervalTime: to_long(p.min_interval_time),
            reserved: [0; 8],
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TComp2DimensSts {
    pub sts: c_short,
    pub reserved1: c_short,
    pub freeSpace: c_long,
    pub usedSpace: c_long,
    pub outCount: c_long,
    pub reserved2: [c_long; 4],
}

impl From<Comp2DimensSts> for TComp2DimensSts {
    fn from(s: Comp2DimensSts) -> TComp2DimensSts {
        TComp2DimensSts {
            sts: s.sts,
            freeSpace: to_long(s.free_space),
            usedSpace: to_long(s.used_space),
            outCount: to_long(s.out_count),
            ..TComp2DimensSts::default()
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct T2DCompensationTable {
    pub count: [c_short; 2],
    pub reserved: [c_short; 2],
    pub posBegin: [c_long; 2],
    pub step: [c_long; 2],
    pub angle: f64,
}

impl From<T2DCompensationTable> for Comp2DTable {
    fn from(t: T2DCompensationTable) -> Comp2DTable {
        Comp2DTable {
            count: t.count,
            pos_begin: t.posBegin.map(i64::from),
            step: t.step.map(i64::from),
            angle: t.angle,
        }
    }
}

impl From<Comp2DTable> for T2DCompensationTable {
    fn from(t: Comp2DTable) -> T2DCompensationTable {
        T2DCompensationTable {
            count: t.count,
            reserved: [0; 2],
            posBegin: t.pos_begin.map(to_long),
            step: t.step.map(to_long),
            angle: t.angle,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TCompData {
    pub xDirComp: c_long,
    pub yDirComp: c_long,
    pub zDirComp: c_long,
}

impl From<TCompData> for CompData {
    fn from(d: TCompData) -> CompData {
        CompData {
            x: i64::from(d.xDirComp),
            y: i64::from(d.yDirComp),
            z: i64::from(d.zDirComp),
        }
    }
}

impl From<CompData> for TCompData {
    fn from(d: CompData) -> TCompData {
        TCompData {
            xDirComp: to_long(d.x),
            yDirComp: to_long(d.y),
            zDirComp: to_long(d.z),
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct T2DCompensation {
    pub enable: c_short,
    pub tableIndex: c_short,
    pub axisType: [c_short; 2],
    pub axisIndex: [c_short; 3],
}

impl From<T2DCompensation> for Comp2D {
    fn from(c: T2DCompensation) -> Comp2D {
        Comp2D {
            enable: c.enable,
            table_index: c.tableIndex,
            axis_type: c.axisType,
            axis_index: c.axisIndex,
        }
    }
}

impl From<Comp2D> for T2DCompensation {
    fn from(c: Comp2D) -> T2DCompensation {
        T2DCompensation {
            enable: c.enable,
            tableIndex: c.table_index,
            axisType: c.axis_type,
            axisIndex: c.axis_index,
        }
    }
}
