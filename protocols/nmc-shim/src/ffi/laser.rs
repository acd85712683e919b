//! The laser, SHIO and PWM functions (digest 001 §2.12, §3.20), immediate and buffered, and
//! their structs. mcemu stores what they write and echoes it on its I/O image (the server's
//! `handlers::laser` says how; docs/decisions.md "NMC laser, SHIO and PWM").

use std::ffi::{c_long, c_short, c_ulong};

use mcemu_nmc::laser::{LaserPower, ShioPara, TimeArrayPara, LASET_POINT};
use mcemu_nmc::sync_structs::write_array;
use mcemu_nmc::table::{self, Function};

use super::arrays::{bounded, load_slice};
use super::types::to_long;
use super::{load, require, served, store, HAND};

/// `TTimeArrayPara` as the C caller lays it out.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TTimeArrayPara {
    pub pwmEnable: c_short,
    pub outputType: c_short,
    pub outputCh: c_short,
    pub stLevelRevs: c_short,
    pub pwmPeriod: c_long,
    pub pwmWidth: c_long,
    pub gateDistance: c_long,
    pub minFrqFrq: c_long,
    pub posSrc: c_short,
    pub axisMask: c_short,
    pub minFrqEn: c_short,
    pub reserved2: c_short,
}

impl From<TTimeArrayPara> for TimeArrayPara {
    fn from(p: TTimeArrayPara) -> TimeArrayPara {
        TimeArrayPara {
            pwm_enable: p.pwmEnable,
            output_type: p.outputType,
            output_ch: p.outputCh,
            st_level_revs: p.stLevelRevs,
            pwm_period: i64::from(p.pwmPeriod),
            pwm_width: i64::from(p.pwmWidth),
            gate_distance: i64::from(p.gateDistance),
            min_frq_frq: i64::from(p.minFrqFrq),
            pos_src: p.posSrc,
            axis_mask: p.axisMask,
            min_frq_en: p.minFrqEn,
        }
    }
}

/// `TLaserPower`: `LASET_POINT` (40) points.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct TLaserPower {
    pub time: [u16; LASET_POINT],
    pub power: [c_short; LASET_POINT],
    pub count: c_short,
}

impl Default for TLaserPower {
    fn default() -> TLaserPower {
        TLaserPower {
            time: [0; LASET_POINT],
            power: [0; LASET_POINT],
            count: 0,
        }
    }
}

impl From<TLaserPower> for LaserPower {
    /// The first `count` points (none when count is outside [0, 40]: the server refuses it).
    fn from(p: TLaserPower) -> LaserPower {
        let n = bounded(i64::from(p.count), LASET_POINT);
        LaserPower {
            count: p.count,
            points: p.time.iter().copied().zip(p.power).take(n).collect(),
        }
    }
}

/// `TSHIOPara` as the manual lays it out.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TSHIOPara {
    pub isArray: c_short,
    pub outMode: c_short,
    pub posSrc: c_short,
    pub axisMask: c_short,
    pub delay: f64,
    pub gateTime: f64,
    pub gateDistance: c_long,
    pub k: c_long,
    pub startDot: c_long,
    pub lowFrqRange: c_long,
    pub reserved4: c_long,
    pub reserved5: c_long,
}

impl From<TSHIOPara> for ShioPara {
    fn from(p: TSHIOPara) -> ShioPara {
        ShioPara {
            is_array: p.isArray,
            out_mode: p.outMode,
            pos_src: p.posSrc,
            axis_mask: p.axisMask,
            delay: p.delay,
            gate_time: p.gateTime,
            gate_distance: i64::from(p.gateDistance),
            k: i64::from(p.k),
            start_dot: i64::from(p.startDot),
            low_frq_range: i64::from(p.lowFrqRange),
        }
    }
}

/// A function whose arguments after the handle are all in: `put` writes them.
fn call_in(
    f: &Function,
    handle: HAND,
    put: impl FnOnce(&mut mcemu_nmc::payload::Writer),
) -> c_short {
    served(f, handle, put, |_| Ok(()))
}

/// `(handle, short, short)`: mode and channel, onOff and channel …
macro_rules! shorts2 {
    ($name:ident, $row:expr, $a:ident, $b:ident) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, $a: c_short, $b: c_short) -> c_short {
            call_in(&$row, handle, |w| {
                w.i16($a).i16($b);
            })
        }
    };
}

/// `(handle, short, short, short)`.
macro_rules! shorts3 {
    ($name:ident, $row:expr, $a:ident, $b:ident, $c:ident) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, $a: c_short, $b: c_short, $c: c_short) -> c_short {
            call_in(&$row, handle, |w| {
                w.i16($a).i16($b).i16($c);
            })
        }
    };
}

/// `(handle, short ch)`.
macro_rules! short1 {
    ($name:ident, $row:expr) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, ch: c_short) -> c_short {
            call_in(&$row, handle, |w| {
                w.i16(ch);
            })
        }
    };
}

/// `(handle, long segNo, short ch)`.
macro_rules! buf_short1 {
    ($name:ident, $row:expr) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, segNo: c_long, ch: c_short) -> c_short {
            call_in(&$row, handle, |w| {
                w.i64(i64::from(segNo)).i16(ch);
            })
        }
    };
}

/// `(handle, long value, short ch)`.
macro_rules! long_short {
    ($name:ident, $row:expr, $a:ident) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, $a: c_long, ch: c_short) -> c_short {
            call_in(&$row, handle, |w| {
                w.i64(i64::from($a)).i16(ch);
            })
        }
    };
}

/// `(handle, long segNo, long value, short ch)`.
macro_rules! buf_long_short {
    ($name:ident, $row:expr, $a:ident) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, segNo: c_long, $a: c_long, ch: c_short) -> c_short {
            call_in(&$row, handle, |w| {
                w.i64(i64::from(segNo)).i64(i64::from($a)).i16(ch);
            })
        }
    };
}

/// `(handle, [long segNo,] double, double, long, short ch)`: the pulse trains.
macro_rules! pulse {
    ($name:ident, $row:expr, $t:ident, $f:ident) => {
        #[no_mangle]
        pub extern "C" fn $name(
            handle: HAND,
            $t: f64,
            $f: f64,
            outCount: c_long,
            ch: c_short,
        ) -> c_short {
            call_in(&$row, handle, |w| {
                w.f64($t).f64($f).i64(i64::from(outCount)).i16(ch);
            })
        }
    };
}

// ---- laser, immediate ----
shorts2!(NMC_LaserSetMode, table::LASER_SET_MODE, mode, ch);
shorts2!(NMC_LaserSetModes, table::LASER_SET_MODES, mode, ch);
shorts2!(NMC_LaserOnOff, table::LASER_ON_OFF, onOff, ch);
short1!(NMC_StopLaserPowerComp, table::STOP_LASER_POWER_COMP);

#[no_mangle]
pub extern "C" fn NMC_LaserSetOutputTypeEx(
    devHandle: HAND,
    outputType: c_short,
    index: c_short,
    optionVal: f64,
    ch: c_short,
) -> c_short {
    call_in(&table::LASER_SET_OUTPUT_TYPE_EX, devHandle, |w| {
        w.i16(outputType).i16(index).f64(optionVal).i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_LaserSetOutputType(
    devHandle: HAND,
    outputType: c_short,
    index: c_short,
    optionVal: c_long,
    ch: c_short,
) -> c_short {
    call_in(&table::LASER_SET_OUTPUT_TYPE, devHandle, |w| {
        w.i16(outputType)
            .i16(index)
            .i64(i64::from(optionVal))
            .i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_LaserSetParam(
    devHandle: HAND,
    onDelay: c_long,
    offDelay: c_long,
    minValue: c_long,
    maxValue: c_long,
    standbyPower: c_long,
    ch: c_short,
) -> c_short {
    call_in(&table::LASER_SET_PARAM, devHandle, |w| {
        for v in [onDelay, offDelay, minValue, maxValue, standbyPower] {
            w.i64(i64::from(v));
        }
        w.i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_LaserGetParam(
    devHandle: HAND,
    pOnDelay: *mut c_long,
    pOffDelay: *mut c_long,
    pMinValue: *mut c_long,
    pMaxValue: *mut c_long,
    pStandbyPower: *mut c_long,
    ch: c_short,
) -> c_short {
    require!(
        table::LASER_GET_PARAM,
        pOnDelay,
        pOffDelay,
        pMinValue,
        pMaxValue,
        pStandbyPower
    );
    served(
        &table::LASER_GET_PARAM,
        devHandle,
        |w| {
            w.i16(ch);
        },
        |r| {
            for p in [pOnDelay, pOffDelay, pMinValue, pMaxValue, pStandbyPower] {
                store(p, to_long(r.i64()?));
            }
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_LaserSetPowerEx(devHandle: HAND, outVal: f64, ch: c_short) -> c_short {
    call_in(&table::LASER_SET_POWER_EX, devHandle, |w| {
        w.f64(outVal).i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_LaserGetPower(devHandle: HAND, pVal: *mut f64, ch: c_short) -> c_short {
    require!(table::LASER_GET_POWER, pVal);
    served(
        &table::LASER_GET_POWER,
        devHandle,
        |w| {
            w.i16(ch);
        },
        |r| {
            store(pVal, r.f64()?);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_LaserGetOnOff(
    devHandle: HAND,
    pOnOffState: *mut c_short,
    ch: c_short,
) -> c_short {
    require!(table::LASER_GET_ON_OFF, pOnOffState);
    served(
        &table::LASER_GET_ON_OFF,
        devHandle,
        |w| {
            w.i16(ch);
        },
        |r| {
            store(pOnOffState, r.i16()?);
            Ok(())
        },
    )
}

/// The longest side of a compensation table (xCount, yCount ∈ [2, 10]).
const CMP_SIDE_MAX: usize = 10;

#[no_mangle]
pub extern "C" fn NMC_SetLaserPowerCmpTable(
    devHandle: HAND,
    tableNo: c_short,
    pXCmpPos: *mut c_long,
    pYCmpPos: *mut c_long,
    xCount: c_short,
    yCount: c_short,
    powerMin: c_ulong,
    powerMax: c_ulong,
    pLaserCmpPower: *mut c_ulong,
    ch: c_short,
) -> c_short {
    let (nx, ny) = (
        bounded(i64::from(xCount), CMP_SIDE_MAX),
        bounded(i64::from(yCount), CMP_SIDE_MAX),
    );
    if nx > 0 && ny > 0 {
        require!(
            table::SET_LASER_POWER_CMP_TABLE,
            pXCmpPos,
            pYCmpPos,
            pLaserCmpPower
        );
    }
    let x = load_slice(pXCmpPos.cast_const(), nx);
    let y = load_slice(pYCmpPos.cast_const(), ny);
    let power = load_slice(pLaserCmpPower.cast_const(), nx * ny);
    call_in(&table::SET_LASER_POWER_CMP_TABLE, devHandle, |w| {
        w.i16(tableNo);
        write_array(w, &x, |w, v| {
            w.i64(i64::from(*v));
        });
        write_array(w, &y, |w, v| {
            w.i64(i64::from(*v));
        });
        w.i16(xCount)
            .i16(yCount)
            .u64(u64::from(powerMin))
            .u64(u64::from(powerMax));
        write_array(w, &power, |w, v| {
            w.u64(u64::from(*v));
        });
        w.i16(ch);
    })
}

/// pAxisNo: two axes, X then Y.
#[no_mangle]
pub extern "C" fn NMC_StartLaserPowerComp(
    devHandle: HAND,
    pAxisNo: *mut c_short,
    ch: c_short,
) -> c_short {
    require!(table::START_LASER_POWER_COMP, pAxisNo);
    let axes = load_slice(pAxisNo.cast_const(), 2);
    call_in(&table::START_LASER_POWER_COMP, devHandle, |w| {
        write_array(w, &axes, |w, v| {
            w.i16(*v);
        });
        w.i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_LaserSetTimeArrayPara(
    devHandle: HAND,
    pPara: *mut TTimeArrayPara,
    ch: c_short,
) -> c_short {
    require!(table::LASER_SET_TIME_ARRAY_PARA, pPara);
    let p = TimeArrayPara::from(load(pPara.cast_const()));
    call_in(&table::LASER_SET_TIME_ARRAY_PARA, devHandle, |w| {
        p.write(w);
        w.i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_LaserSetTimeArrayPower(
    devHandle: HAND,
    group: c_short,
    pLaserPower: *mut TLaserPower,
) -> c_short {
    require!(table::LASER_SET_TIME_ARRAY_POWER, pLaserPower);
    let p = LaserPower::from(load(pLaserPower.cast_const()));
    call_in(&table::LASER_SET_TIME_ARRAY_POWER, devHandle, |w| {
        w.i16(group);
        p.write(w);
    })
}

shorts2!(
    NMC_LaserTimeArrayExe,
    table::LASER_TIME_ARRAY_EXE,
    group,
    ch
);
shorts3!(
    NMC_LaserSetFollowParam,
    table::LASER_SET_FOLLOW_PARAM,
    powerFilter,
    followAdvMode,
    ch
);
shorts3!(
    NMC_SetPwmToGate,
    table::SET_PWM_TO_GATE,
    pwmCh,
    gateCh,
    onOff
);
shorts3!(NMC_SetPWMPort, table::SET_PWM_PORT, portType, portIdx, ch);

// ---- SHIO and PWM ----
#[no_mangle]
pub extern "C" fn NMC_SHIOConfigPara(
    devHandle: HAND,
    pSHIOPara: *mut TSHIOPara,
    ch: c_short,
) -> c_short {
    require!(table::SHIO_CONFIG_PARA, pSHIOPara);
    let p = ShioPara::from(load(pSHIOPara.cast_const()));
    call_in(&table::SHIO_CONFIG_PARA, devHandle, |w| {
        p.write(w);
        w.i16(ch);
    })
}

long_short!(NMC_SHIOEnableMinFrq, table::SHIO_ENABLE_MIN_FRQ, minFrq);
short1!(NMC_SHIODisableMinFrq, table::SHIO_DISABLE_MIN_FRQ);
long_short!(NMC_SHIOEnableMinFrg, table::SHIO_ENABLE_MIN_FRG, minFrq);
short1!(NMC_SHIODisableMinFrg, table::SHIO_DISABLE_MIN_FRG);
shorts2!(
    NMC_SHIOChangeAxisMask,
    table::SHIO_CHANGE_AXIS_MASK,
    axisMask,
    ch
);
short1!(NMC_SHIOGateOn, table::SHIO_GATE_ON);
short1!(NMC_SHIOGateOff, table::SHIO_GATE_OFF);
short1!(NMC_SHIOTriggerOff, table::SHIO_TRIGGER_OFF);
pulse!(NMC_SHIOGatePulse, table::SHIO_GATE_PULSE, gateTime, gateFrq);
pulse!(NMC_PwmPulseOut, table::PWM_PULSE_OUT, onTime, pwmFrq);

#[no_mangle]
pub extern "C" fn NMC_SHIOTriggerOn(
    devHandle: HAND,
    freq: f64,
    width: f64,
    ch: c_short,
) -> c_short {
    call_in(&table::SHIO_TRIGGER_ON, devHandle, |w| {
        w.f64(freq).f64(width).i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_GetPWMPort(
    devHandle: HAND,
    pPortType: *mut c_short,
    pGpoIdx: *mut c_short,
    ch: c_short,
) -> c_short {
    require!(table::GET_PWM_PORT, pPortType, pGpoIdx);
    served(
        &table::GET_PWM_PORT,
        devHandle,
        |w| {
            w.i16(ch);
        },
        |r| {
            store(pPortType, r.i16()?);
            store(pGpoIdx, r.i16()?);
            Ok(())
        },
    )
}

// ---- buffered ----
#[no_mangle]
pub extern "C" fn NMC_CrdBufLaserOnOff(
    crdHandle: HAND,
    segNo: c_long,
    onOff: c_short,
    ch: c_short,
) -> c_short {
    call_in(&table::CRD_BUF_LASER_ON_OFF, crdHandle, |w| {
        w.i64(i64::from(segNo)).i16(onOff).i16(ch);
    })
}

buf_long_short!(NMC_CrdBufLaserPower, table::CRD_BUF_LASER_POWER, power);

#[no_mangle]
pub extern "C" fn NMC_CrdBufLaserSetFollow(
    crdHandle: HAND,
    segNo: c_long,
    overRide: f64,
    followType: c_short,
    ch: c_short,
) -> c_short {
    call_in(&table::CRD_BUF_LASER_SET_FOLLOW, crdHandle, |w| {
        w.i64(i64::from(segNo))
            .f64(overRide)
            .i16(followType)
            .i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufLaserSetParam(
    crdHandle: HAND,
    segment: c_long,
    onDelay: c_long,
    offDelay: c_long,
    minValue: c_long,
    maxValue: c_long,
    standbyPower: c_long,
    ch: c_short,
) -> c_short {
    call_in(&table::CRD_BUF_LASER_SET_PARAM, crdHandle, |w| {
        for v in [segment, onDelay, offDelay, minValue, maxValue, standbyPower] {
            w.i64(i64::from(v));
        }
        w.i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufLaserTimeArrayExe(
    crdHandle: HAND,
    segNo: c_long,
    group: c_short,
    ch: c_short,
) -> c_short {
    call_in(&table::CRD_BUF_LASER_TIME_ARRAY_EXE, crdHandle, |w| {
        w.i64(i64::from(segNo)).i16(group).i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufSHIOGatePulse(
    crdHandle: HAND,
    segNo: c_long,
    gateTime: f64,
    gateFrq: f64,
    outCount: c_long,
    ch: c_short,
) -> c_short {
    call_in(&table::CRD_BUF_SHIO_GATE_PULSE, crdHandle, |w| {
        w.i64(i64::from(segNo))
            .f64(gateTime)
            .f64(gateFrq)
            .i64(i64::from(outCount))
            .i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufSHIOSetParam(
    crdHandle: HAND,
    segment: c_long,
    delay: f64,
    gateTime: f64,
    gateDistance: f64,
    ch: c_short,
) -> c_short {
    call_in(&table::CRD_BUF_SHIO_SET_PARAM, crdHandle, |w| {
        w.i64(i64::from(segment))
            .f64(delay)
            .f64(gateTime)
            .f64(gateDistance)
            .i16(ch);
    })
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufSHIOChangeAxisMask(
    crdHandle: HAND,
    segment: c_long,
    axisMask: c_short,
    ch: c_short,
) -> c_short {
    call_in(&table::CRD_BUF_SHIO_CHANGE_AXIS_MASK, crdHandle, |w| {
        w.i64(i64::from(segment)).i16(axisMask).i16(ch);
    })
}

buf_long_short!(
    NMC_CrdBufSHIOSetMinFrq,
    table::CRD_BUF_SHIO_SET_MIN_FRQ,
    minFrq
);
buf_short1!(NMC_CrdBufSHIOClrMinFrq, table::CRD_BUF_SHIO_CLR_MIN_FRQ);
buf_long_short!(
    NMC_CrdBufSHIOSetMinFrg,
    table::CRD_BUF_SHIO_SET_MIN_FRG,
    minFrq
);
buf_short1!(NMC_CrdBufSHIOClrMinFrg, table::CRD_BUF_SHIO_CLR_MIN_FRG);
buf_short1!(NMC_BufSHIOGateOn, table::BUF_SHIO_GATE_ON);
buf_short1!(NMC_BufSHIOGateOff, table::BUF_SHIO_GATE_OFF);
