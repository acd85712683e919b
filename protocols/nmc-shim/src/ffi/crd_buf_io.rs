//! The coordinate-system buffered I/O, stops and packs and the advanced buffered I/O of
//! digest 001 §2.7 (rows 0x1601–0x160E): plain arguments, `TAdvBufIoParam`, and the pack's
//! bytes as the program wrote them (the server reads them with this platform's C layout,
//! `mcemu_nmc::buf_pack`).

use std::ffi::{c_long, c_short, c_uchar};

use mcemu_nmc::buf_pack::{AdvBufIoParam, PACK_MAX_BYTES};
use mcemu_nmc::table;

use super::{load, load_array, require, served, store, HAND};

/// `TAdvBufIoParam` (digest 001 §3.12).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct TAdvBufIoParam {
    pub outType: c_short,
    pub outGroup: c_short,
    pub outIndex: c_short,
    pub outSns: c_short,
    pub pulseMode: c_short,
    pub reserved1: c_short,
    pub pulseOnTime: c_long,
    pub pulseOffTime: c_long,
    pub reserved: [c_uchar; 32],
}

impl Default for TAdvBufIoParam {
    fn default() -> Self {
        TAdvBufIoParam::from(AdvBufIoParam::default())
    }
}

impl From<TAdvBufIoParam> for AdvBufIoParam {
    fn from(p: TAdvBufIoParam) -> AdvBufIoParam {
        AdvBufIoParam {
            out_type: p.outType,
            out_group: p.outGroup,
            out_index: p.outIndex,
            out_sns: p.outSns,
            pulse_mode: p.pulseMode,
            pulse_on_time: i64::from(p.pulseOnTime),
            pulse_off_time: i64::from(p.pulseOffTime),
        }
    }
}

impl From<AdvBufIoParam> for TAdvBufIoParam {
    fn from(p: AdvBufIoParam) -> TAdvBufIoParam {
        TAdvBufIoParam {
            outType: p.out_type,
            outGroup: p.out_group,
            outIndex: p.out_index,
            outSns: p.out_sns,
            pulseMode: p.pulse_mode,
            reserved1: 0,
            pulseOnTime: super::types::to_long(p.pulse_on_time),
            pulseOffTime: super::types::to_long(p.pulse_off_time),
            reserved: [0; 32],
        }
    }
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufOut(
    crdHandle: HAND,
    segNo: c_long,
    group: c_short,
    ch: c_short,
    value: c_long,
) -> c_short {
    served(
        &table::CRD_BUF_OUT,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo))
                .i16(group)
                .i16(ch)
                .i64(i64::from(value));
        },
        |_| Ok(()),
    )
}

/// crdIdx −1: this coordinate system.
#[no_mangle]
pub extern "C" fn NMC_CrdBufStopMtn(crdHandle: HAND, segNo: c_long, crdIdx: c_short) -> c_short {
    served(
        &table::CRD_BUF_STOP_MTN,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo)).i16(crdIdx);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufSetEstopDI(
    crdHandle: HAND,
    segNo: c_long,
    axis: c_short,
    gpiIndex: c_short,
    sense: c_short,
) -> c_short {
    served(
        &table::CRD_BUF_SET_ESTOP_DI,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo)).i16(axis).i16(gpiIndex).i16(sense);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufEstopDIExOnOff(
    crdHandle: HAND,
    segNo: c_long,
    onOff: c_short,
    group: c_short,
) -> c_short {
    served(
        &table::CRD_BUF_ESTOP_DI_EX_ON_OFF,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo)).i16(onOff).i16(group);
        },
        |_| Ok(()),
    )
}

#[allow(clippy::too_many_arguments)]
#[no_mangle]
pub extern "C" fn NMC_CrdBufDoBitPulseEnable(
    crdHandle: HAND,
    segNo: c_long,
    doType: c_short,
    doIndex: c_short,
    highLevelTime: c_long,
    lowLevelTime: c_long,
    outCount: c_long,
    initialLevel: c_short,
    ch: c_short,
) -> c_short {
    served(
        &table::CRD_BUF_DO_BIT_PULSE_ENABLE,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo))
                .i16(doType)
                .i16(doIndex)
                .i64(i64::from(highLevelTime))
                .i64(i64::from(lowLevelTime))
                .i64(i64::from(outCount))
                .i16(initialLevel)
                .i16(ch);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufDoBitPulseDisable(
    crdHandle: HAND,
    segNo: c_long,
    ch: c_short,
) -> c_short {
    served(
        &table::CRD_BUF_DO_BIT_PULSE_DISABLE,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo)).i16(ch);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdBufBeforeAxSyncMove(
    crdHandle: HAND,
    segNo: c_long,
    axis: c_short,
    relDistance: c_long,
    vel: f64,
) -> c_short {
    served(
        &table::CRD_BUF_BEFORE_AX_SYNC_MOVE,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo))
                .i16(axis)
                .i64(i64::from(relDistance))
                .f64(vel);
        },
        |_| Ok(()),
    )
}

/// `dataLen` bytes of `pBufData` travel (at most one more than the manual's 1000, so the
/// server can say the pack is too long); a negative length sends none (the server refuses).
#[no_mangle]
pub extern "C" fn NMC_CrdBufDataPack(
    crdHandle: HAND,
    pBufData: *mut c_uchar,
    dataLen: c_short,
) -> c_short {
    require!(table::CRD_BUF_DATA_PACK, pBufData);
    let n = usize::try_from(dataLen)
        .unwrap_or(0)
        .min(PACK_MAX_BYTES + 1);
    let bytes = load_array(pBufData.cast_const(), n);
    served(
        &table::CRD_BUF_DATA_PACK,
        crdHandle,
        |w| {
            w.u16(bytes.len() as u16);
            for b in &bytes {
                w.u8(*b);
            }
            w.i16(dataLen);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_AdvBufIoSetParam(
    devHandle: HAND,
    pPrm: *mut TAdvBufIoParam,
    ch: c_short,
) -> c_short {
    require!(table::ADV_BUF_IO_SET_PARAM, pPrm);
    let p = AdvBufIoParam::from(load(pPrm.cast_const()));
    served(
        &table::ADV_BUF_IO_SET_PARAM,
        devHandle,
        |w| {
            p.write(w);
            w.i16(ch);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_AdvBufIoGetParam(
    devHandle: HAND,
    pPrm: *mut TAdvBufIoParam,
    ch: c_short,
) -> c_short {
    require!(table::ADV_BUF_IO_GET_PARAM, pPrm);
    served(
        &table::ADV_BUF_IO_GET_PARAM,
        devHandle,
        |w| {
            w.i16(ch);
        },
        |r| {
            store(pPrm, TAdvBufIoParam::from(AdvBufIoParam::read(r)?));
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_AdvBufIoOut(devHandle: HAND, value: c_long, ch: c_short) -> c_short {
    served(
        &table::ADV_BUF_IO_OUT,
        devHandle,
        |w| {
            w.i64(i64::from(value)).i16(ch);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_AdvBufIoGetPulseCnt(
    devHandle: HAND,
    pOutCout: *mut c_long,
    ch: c_short,
) -> c_short {
    require!(table::ADV_BUF_IO_GET_PULSE_CNT, pOutCout);
    served(
        &table::ADV_BUF_IO_GET_PULSE_CNT,
        devHandle,
        |w| {
            w.i16(ch);
        },
        |r| {
            store(pOutCout, super::types::to_long(r.i64()?));
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdAdvBufIoOnAfterLen(
    crdHandle: HAND,
    segNo: c_long,
    outLength: c_long,
    value: c_long,
    ch: c_short,
) -> c_short {
    served(
        &table::CRD_ADV_BUF_IO_ON_AFTER_LEN,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo))
                .i64(i64::from(outLength))
                .i64(i64::from(value))
                .i16(ch);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_CrdAdvBufIoOffBeforeLen(
    crdHandle: HAND,
    segNo: c_long,
    outLength: c_long,
    ch: c_short,
) -> c_short {
    served(
        &table::CRD_ADV_BUF_IO_OFF_BEFORE_LEN,
        crdHandle,
        |w| {
            w.i64(i64::from(segNo)).i64(i64::from(outLength)).i16(ch);
        },
        |_| Ok(()),
    )
}
