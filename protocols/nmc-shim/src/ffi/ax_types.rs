//! The C layout of the axis-level additions' structs (`mtn_lib20.h`, digest 001 §3.4, §3.6)
//! and their conversions to the wire's (`mcemu_nmc::ax_structs`).

#![allow(non_snake_case)]

use std::ffi::{c_long, c_short};

use mcemu_nmc::ax_structs::{AxisStsPack12Ex, DacMotor, EstopExParam, MovePtpPack8, PidPara};

use super::types::to_long;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TMovePtpPack8 {
    pub axisMask: c_short,
    pub clrStsFlag: c_short,
    pub reserved: [c_short; 2],
    pub acc: [f64; 8],
    pub dec: [f64; 8],
    pub startVel: [f64; 8],
    pub endVel: [f64; 8],
    pub maxVel: [f64; 8],
    pub smoothCoef: [c_short; 8],
    pub tgtPos: [c_long; 8],
}

impl From<TMovePtpPack8> for MovePtpPack8 {
    fn from(p: TMovePtpPack8) -> MovePtpPack8 {
        MovePtpPack8 {
            axis_mask: p.axisMask,
            clr_sts_flag: p.clrStsFlag,
            acc: p.acc,
            dec: p.dec,
            start_vel: p.startVel,
            end_vel: p.endVel,
            max_vel: p.maxVel,
            smooth_coef: p.smoothCoef,
            tgt_pos: p.tgtPos.map(i64::from),
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TAxisStsPack12Ex {
    pub mtSts: [c_short; 12],
    pub mtMio: [c_short; 12],
    pub mtMioLog: [c_short; 12],
    pub mtPrfPos: [c_long; 12],
    pub mtEncPos: [c_long; 12],
    pub mtPrfVel: [f32; 12],
    pub crdSts: [c_short; 2],
    pub crdPrfVel: [f32; 2],
    pub crdUserSeg: [c_long; 2],
    pub crdFreeSpace: [c_long; 2],
    pub crdUsedSpace: [c_long; 2],
    pub gpi: c_long,
    pub gpo: c_long,
    pub crdLeftLen: [c_long; 2],
    pub crdAllCmdCnt: [c_long; 2],
    pub extDi: [c_long; 6],
    pub extDo: [c_long; 6],
    pub adc: [c_short; 4],
    pub adcAux: [c_short; 2],
    pub dac: [c_short; 4],
    pub dacAux: [c_short; 2],
    pub reserved: [c_long; 10],
}

impl From<AxisStsPack12Ex> for TAxisStsPack12Ex {
    fn from(p: AxisStsPack12Ex) -> TAxisStsPack12Ex {
        // `float` in C: the velocities narrow on purpose.
        let narrow = |v: f64| v as f32;
        TAxisStsPack12Ex {
            mtSts: p.mt_sts,
            mtMio: p.mt_mio,
            mtMioLog: p.mt_mio_log,
            mtPrfPos: p.mt_prf_pos.map(to_long),
            mtEncPos: p.mt_enc_pos.map(to_long),
            mtPrfVel: p.mt_prf_vel.map(narrow),
            crdSts: p.crd_sts,
            crdPrfVel: p.crd_prf_vel.map(narrow),
            crdUserSeg: p.crd_user_seg.map(to_long),
            crdFreeSpace: p.crd_free_space.map(to_long),
            crdUsedSpace: p.crd_used_space.map(to_long),
            gpi: to_long(p.gpi),
            gpo: to_long(p.gpo),
            crdLeftLen: p.crd_left_len.map(to_long),
            crdAllCmdCnt: p.crd_all_cmd_cnt.map(to_long),
            extDi: p.ext_di.map(to_long),
            extDo: p.ext_do.map(to_long),
            adc: p.adc,
            adcAux: p.adc_aux,
            dac: p.dac,
            dacAux: p.dac_aux,
            reserved: [0; 10],
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TEstopExParam {
    pub axMask: c_short,
    pub diType: c_short,
    pub diIndex: c_short,
    pub filter: c_short,
    pub diSense: c_long,
    pub reserved: [c_long; 3],
}

impl From<TEstopExParam> for EstopExParam {
    fn from(p: TEstopExParam) -> EstopExParam {
        EstopExParam {
            ax_mask: p.axMask,
            di_type: p.diType,
            di_index: p.diIndex,
            filter: p.filter,
            di_sense: i64::from(p.diSense),
        }
    }
}

impl From<EstopExParam> for TEstopExParam {
    fn from(p: EstopExParam) -> TEstopExParam {
        TEstopExParam {
            axMask: p.ax_mask,
            diType: p.di_type,
            diIndex: p.di_index,
            filter: p.filter,
            diSense: to_long(p.di_sense),
            reserved: [0; 3],
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TDacMotor {
    pub inverse: c_short,
    pub bias: c_short,
    pub dacLmt: c_short,
}

impl From<TDacMotor> for DacMotor {
    fn from(p: TDacMotor) -> DacMotor {
        DacMotor {
            inverse: p.inverse,
            bias: p.bias,
            dac_lmt: p.dacLmt,
        }
    }
}

impl From<DacMotor> for TDacMotor {
    fn from(p: DacMotor) -> TDacMotor {
        TDacMotor {
            inverse: p.inverse,
            bias: p.bias,
            dacLmt: p.dac_lmt,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TPidPara {
    pub kp: f32,
    pub ki: f32,
    pub kd: f32,
    pub kvff: f32,
    pub integralLimit: c_long,
    pub derivativeLimit: c_long,
    pub outLimit: c_short,
}

impl From<TPidPara> for PidPara {
    fn from(p: TPidPara) -> PidPara {
        PidPara {
            kp: f64::from(p.kp),
            ki: f64::from(p.ki),
            kd: f64::from(p.kd),
            kvff: f64::from(p.kvff),
            integral_limit: i64::from(p.integralLimit),
            derivative_limit: i64::from(p.derivativeLimit),
            out_limit: p.outLimit,
        }
    }
}

impl From<PidPara> for TPidPara {
    fn from(p: PidPara) -> TPidPara {
        // `float` in C: the gains narrow on purpose.
        TPidPara {
            kp: p.kp as f32,
            ki: p.ki as f32,
            kd: p.kd as f32,
            kvff: p.kvff as f32,
            integralLimit: to_long(p.integral_limit),
            derivativeLimit: to_long(p.derivative_limit),
            outLimit: p.out_limit,
        }
    }
}
