//! The plain I/O aliases (`NMC_GetDI`, `NMC_GetDO`, `NMC_SetDO`), bit inversion, timed
//! outputs, DI filters, DI edge counters and the DIO mapping table (digest 001 §2.8; rows
//! 0x1220–0x1232).

use std::ffi::{c_long, c_short, c_ulong};

use mcemu_nmc::io_structs::DioMapping;
use mcemu_nmc::table::{self, Function};

use super::io_types::TDioMappingCfg;
use super::types::to_ulong;
use super::{load, load_array, reply_list, require, served, store, store_array, HAND};

/// Same as `NMC_GetDIGroup` (digest 001 §2.8).
#[no_mangle]
pub extern "C" fn NMC_GetDI(devHandle: HAND, pInValue: *mut c_long, groupID: c_short) -> c_short {
    group_read(&table::GET_DI, devHandle, pInValue, groupID)
}

/// Same as `NMC_GetDOGroup`.
#[no_mangle]
pub extern "C" fn NMC_GetDO(devHandle: HAND, pDoValue: *mut c_long, groupID: c_short) -> c_short {
    group_read(&table::GET_DO, devHandle, pDoValue, groupID)
}

/// `NMC_GetDOGroup`'s call on another row, its pointer checked.
fn group_read(row: &Function, devHandle: HAND, out: *mut c_long, groupID: c_short) -> c_short {
    require!(*row, out);
    super::io::get_group(row, devHandle, out, groupID)
}

/// Same as `NMC_SetDOGroup`.
#[no_mangle]
pub extern "C" fn NMC_SetDO(devHandle: HAND, value: c_long, groupID: c_short) -> c_short {
    served(
        &table::SET_DO,
        devHandle,
        |w| {
            w.i64(i64::from(value)).i16(groupID);
        },
        |_| Ok(()),
    )
}

/// A request of shorts only.
fn shorts(row: &Function, devHandle: HAND, args: &[c_short]) -> c_short {
    served(
        row,
        devHandle,
        |w| {
            for a in args {
                w.i16(*a);
            }
        },
        |_| Ok(()),
    )
}

/// Shorts in, one short out.
fn shorts_get(row: &Function, devHandle: HAND, args: &[c_short], out: *mut c_short) -> c_short {
    require!(*row, out);
    served(
        row,
        devHandle,
        |w| {
            for a in args {
                w.i16(*a);
            }
        },
        |r| {
            store(out, r.i16()?);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_SetDIBitRevs(devHandle: HAND, bitIndex: c_short, revs: c_short) -> c_short {
    shorts(&table::SET_DI_BIT_REVS, devHandle, &[bitIndex, revs])
}

#[no_mangle]
pub extern "C" fn NMC_GetDIBitRevs(
    devHandle: HAND,
    bitIndex: c_short,
    pRevs: *mut c_short,
) -> c_short {
    shorts_get(&table::GET_DI_BIT_REVS, devHandle, &[bitIndex], pRevs)
}

#[no_mangle]
pub extern "C" fn NMC_SetDOBitRevs(devHandle: HAND, bitIndex: c_short, revs: c_short) -> c_short {
    shorts(&table::SET_DO_BIT_REVS, devHandle, &[bitIndex, revs])
}

#[no_mangle]
pub extern "C" fn NMC_GetDOBitRevs(
    devHandle: HAND,
    bitIndex: c_short,
    pRevs: *mut c_short,
) -> c_short {
    shorts_get(&table::GET_DO_BIT_REVS, devHandle, &[bitIndex], pRevs)
}

#[no_mangle]
pub extern "C" fn NMC_SetDOBitRevsEx(
    devHandle: HAND,
    doType: c_short,
    group: c_short,
    bitIndex: c_short,
    revs: c_short,
) -> c_short {
    shorts(
        &table::SET_DO_BIT_REVS_EX,
        devHandle,
        &[doType, group, bitIndex, revs],
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetDOBitRevsEx(
    devHandle: HAND,
    doType: c_short,
    group: c_short,
    bitIndex: c_short,
    pRevs: *mut c_short,
) -> c_short {
    shorts_get(
        &table::GET_DO_BIT_REVS_EX,
        devHandle,
        &[doType, group, bitIndex],
        pRevs,
    )
}

/// Set DO `bitIndex` to `value`, and back after `reverseTime` ms (the virtual clock).
#[no_mangle]
pub extern "C" fn NMC_SetDOBitAutoReverse(
    devHandle: HAND,
    bitIndex: c_short,
    value: c_short,
    reverseTime: c_short,
) -> c_short {
    shorts(
        &table::SET_DO_BIT_AUTO_REVERSE,
        devHandle,
        &[bitIndex, value, reverseTime],
    )
}

/// A pulse train on a general DO: times in µs, `outCount` pulses (0: until disabled).
#[allow(clippy::too_many_arguments)]
#[no_mangle]
pub extern "C" fn NMC_DoBitPulseEnable(
    devHandle: HAND,
    doType: c_short,
    doIndex: c_short,
    highLevelTime: c_long,
    lowLevelTime: c_long,
    outCount: c_long,
    initialLevel: c_short,
    ch: c_short,
) -> c_short {
    served(
        &table::DO_BIT_PULSE_ENABLE,
        devHandle,
        |w| {
            w.i16(doType)
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
pub extern "C" fn NMC_DoBitPulseDisable(devHandle: HAND, ch: c_short) -> c_short {
    shorts(&table::DO_BIT_PULSE_DISABLE, devHandle, &[ch])
}

#[no_mangle]
pub extern "C" fn NMC_SetDIFilter(
    devHandle: HAND,
    diType: c_short,
    diGroup: c_short,
    diIndex: c_short,
    filtTime: c_short,
) -> c_short {
    shorts(
        &table::SET_DI_FILTER,
        devHandle,
        &[diType, diGroup, diIndex, filtTime],
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetDIFilter(
    devHandle: HAND,
    diType: c_short,
    diGroup: c_short,
    diIndex: c_short,
    pFiltTime: *mut c_short,
) -> c_short {
    shorts_get(
        &table::GET_DI_FILTER,
        devHandle,
        &[diType, diGroup, diIndex],
        pFiltTime,
    )
}

/// Counters beyond 16 are never asked for (`count` ∈ [1, 16]): the server refuses them.
const COUNTERS_MAX: usize = 16;

fn counters(count: c_short) -> usize {
    usize::try_from(count).unwrap_or(0).min(COUNTERS_MAX)
}

#[no_mangle]
pub extern "C" fn NMC_SetDiReverseCount(
    devHandle: HAND,
    diType: c_short,
    diIndex: c_short,
    pReverseCountArray: *mut c_ulong,
    count: c_short,
) -> c_short {
    require!(table::SET_DI_REVERSE_COUNT, pReverseCountArray);
    let values = load_array(pReverseCountArray.cast_const(), counters(count));
    served(
        &table::SET_DI_REVERSE_COUNT,
        devHandle,
        |w| {
            w.i16(diType).i16(diIndex).u16(values.len() as u16);
            for v in &values {
                w.u64(u64::from(*v));
            }
            w.i16(count);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetDiReverseCount(
    devHandle: HAND,
    diType: c_short,
    diIndex: c_short,
    pReverseCountArray: *mut c_ulong,
    count: c_short,
) -> c_short {
    require!(table::GET_DI_REVERSE_COUNT, pReverseCountArray);
    let wanted = counters(count);
    served(
        &table::GET_DI_REVERSE_COUNT,
        devHandle,
        |w| {
            w.i16(diType).i16(diIndex).i16(count);
        },
        |r| {
            let values: Vec<c_ulong> = reply_list(r, wanted, |r| r.u64().map(to_ulong))?;
            store_array(pReverseCountArray, &values);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_SetDioMapping(devHandle: HAND, pDioCfg: *mut TDioMappingCfg) -> c_short {
    require!(table::SET_DIO_MAPPING, pDioCfg);
    let m = DioMapping::from(load(pDioCfg.cast_const()));
    served(
        &table::SET_DIO_MAPPING,
        devHandle,
        |w| m.write(w),
        |_| Ok(()),
    )
}

/// The caller's array holds the 8 mappings (MAX_DIO_MAPPING); unused ones read as zeros.
#[no_mangle]
pub extern "C" fn NMC_GetAllDioMapping(devHandle: HAND, pDioCfg: *mut TDioMappingCfg) -> c_short {
    require!(table::GET_ALL_DIO_MAPPING, pDioCfg);
    served(
        &table::GET_ALL_DIO_MAPPING,
        devHandle,
        |_| {},
        |r| {
            let list: Vec<TDioMappingCfg> =
                reply_list(r, 8, |r| DioMapping::read(r).map(TDioMappingCfg::from))?;
            store_array(pDioCfg, &list);
            Ok(())
        },
    )
}

super::action!(NMC_ClrAllDioMapping, table::CLR_ALL_DIO_MAPPING);
