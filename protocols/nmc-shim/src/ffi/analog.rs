//! Analog outputs and inputs (digest 001 §2.8, §4.8): modes, raw values, bias and limits,
//! voltages of several channels.

use std::ffi::c_short;

use mcemu_nmc::table::{self, Function};

use super::{load_array, reply_list, require, served, store, store_array, HAND};

/// Channels a voltage call handles at once (`count` ∈ [1, 8]).
const MULTI_MAX: usize = 8;

/// A device handle, a channel and `n` shorts in.
fn shorts_in(row: &Function, devHandle: HAND, ch: c_short, values: &[c_short]) -> c_short {
    served(
        row,
        devHandle,
        |w| {
            w.i16(ch);
            for v in values {
                w.i16(*v);
            }
        },
        |_| Ok(()),
    )
}

/// A device handle and a channel in, the shorts at `outs` out.
fn shorts_out(row: &Function, devHandle: HAND, ch: c_short, outs: &[*mut c_short]) -> c_short {
    if let Some(p) = outs.iter().find(|p| p.is_null()) {
        require!(*row, p);
    }
    served(
        row,
        devHandle,
        |w| {
            w.i16(ch);
        },
        |r| {
            for p in outs {
                store(*p, r.i16()?);
            }
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_SetDacMode(devHandle: HAND, ch: c_short, mode: c_short) -> c_short {
    shorts_in(&table::SET_DAC_MODE, devHandle, ch, &[mode])
}

#[no_mangle]
pub extern "C" fn NMC_GetDacMode(devHandle: HAND, ch: c_short, pMode: *mut c_short) -> c_short {
    shorts_out(&table::GET_DAC_MODE, devHandle, ch, &[pMode])
}

#[no_mangle]
pub extern "C" fn NMC_SetAdcMode(
    devHandle: HAND,
    ch: c_short,
    range: c_short,
    filterCoe: c_short,
) -> c_short {
    shorts_in(&table::SET_ADC_MODE, devHandle, ch, &[range, filterCoe])
}

#[no_mangle]
pub extern "C" fn NMC_GetAdcMode(
    devHandle: HAND,
    ch: c_short,
    pRange: *mut c_short,
    pFilterCoe: *mut c_short,
) -> c_short {
    shorts_out(&table::GET_ADC_MODE, devHandle, ch, &[pRange, pFilterCoe])
}

#[no_mangle]
pub extern "C" fn NMC_SetDac(devHandle: HAND, ch: c_short, dacValue: c_short) -> c_short {
    shorts_in(&table::SET_DAC, devHandle, ch, &[dacValue])
}

#[no_mangle]
pub extern "C" fn NMC_GetDac(devHandle: HAND, ch: c_short, pDacValue: *mut c_short) -> c_short {
    shorts_out(&table::GET_DAC, devHandle, ch, &[pDacValue])
}

#[no_mangle]
pub extern "C" fn NMC_GetAdc(devHandle: HAND, ch: c_short, pAdcValue: *mut c_short) -> c_short {
    shorts_out(&table::GET_ADC, devHandle, ch, &[pAdcValue])
}

#[no_mangle]
pub extern "C" fn NMC_SetDacBias(devHandle: HAND, ch: c_short, bias: c_short) -> c_short {
    shorts_in(&table::SET_DAC_BIAS, devHandle, ch, &[bias])
}

#[no_mangle]
pub extern "C" fn NMC_GetDacBias(devHandle: HAND, ch: c_short, pBias: *mut c_short) -> c_short {
    shorts_out(&table::GET_DAC_BIAS, devHandle, ch, &[pBias])
}

#[no_mangle]
pub extern "C" fn NMC_SetDacLmt(
    devHandle: HAND,
    ch: c_short,
    maxVal: c_short,
    minVal: c_short,
) -> c_short {
    shorts_in(&table::SET_DAC_LMT, devHandle, ch, &[maxVal, minVal])
}

#[no_mangle]
pub extern "C" fn NMC_GetDacLmt(
    devHandle: HAND,
    ch: c_short,
    pMaxVal: *mut c_short,
    pMinVal: *mut c_short,
) -> c_short {
    shorts_out(&table::GET_DAC_LMT, devHandle, ch, &[pMaxVal, pMinVal])
}

/// `count` clamped to what the array may be read for: out of [1, 8] none is read and the
/// server names the range.
fn multi(count: c_short) -> usize {
    usize::try_from(count)
        .ok()
        .filter(|n| (1..=MULTI_MAX).contains(n))
        .unwrap_or(0)
}

fn get_volts(
    row: &Function,
    devHandle: HAND,
    ch: c_short,
    count: c_short,
    out: *mut f64,
) -> c_short {
    require!(*row, out);
    let wanted = multi(count);
    served(
        row,
        devHandle,
        |w| {
            w.i16(ch).i16(count);
        },
        |r| {
            let values = reply_list(r, wanted, |r| r.f64())?;
            store_array(out, &values);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetAdcVoltageMulti(
    devHandle: HAND,
    ch: c_short,
    count: c_short,
    pAdcVolArray: *mut f64,
) -> c_short {
    get_volts(
        &table::GET_ADC_VOLTAGE_MULTI,
        devHandle,
        ch,
        count,
        pAdcVolArray,
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetDacVoltageMulti(
    devHandle: HAND,
    ch: c_short,
    count: c_short,
    pDacVolArray: *mut f64,
) -> c_short {
    get_volts(
        &table::GET_DAC_VOLTAGE_MULTI,
        devHandle,
        ch,
        count,
        pDacVolArray,
    )
}

#[no_mangle]
pub extern "C" fn NMC_SetDacVoltageMulti(
    devHandle: HAND,
    ch: c_short,
    count: c_short,
    pDacVolArray: *mut f64,
) -> c_short {
    require!(table::SET_DAC_VOLTAGE_MULTI, pDacVolArray);
    let values = load_array(pDacVolArray.cast_const(), multi(count));
    served(
        &table::SET_DAC_VOLTAGE_MULTI,
        devHandle,
        |w| {
            w.i16(ch).i16(count).u16(values.len() as u16);
            for v in values {
                w.f64(v);
            }
        },
        |_| Ok(()),
    )
}
