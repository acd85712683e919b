//! Mechanical compensation: lead screw, backlash, 2-D table (digest 001 §2.19, §3.17).

use std::ffi::{c_long, c_short};

use mcemu_nmc::sync_structs::{read_array, write_array, Comp2D, Comp2DTable, CompData};
use mcemu_nmc::table;

use super::arrays::{bounded, load_slice, store_slice};
use super::sync_types::{T2DCompensation, T2DCompensationTable, TCompData};
use super::types::to_long;
use super::{load, require, served, setter, store, struct_getter, struct_setter, HAND};

/// num ∈ [2, 128] points per lead-screw table.
const MAX_LEAD_SCREW_POINTS: usize = 128;
/// X·Y·3 ≤ 3000 values: at most 1000 grid points.
const MAX_GRID_POINTS: usize = 1000;

#[no_mangle]
pub extern "C" fn NMC_MtSetLeadScrewCompPara(
    axisHandle: HAND,
    num: c_short,
    startPos: c_long,
    cmpLen: c_long,
    pCompPos: *mut c_short,
    pCompNeg: *mut c_short,
) -> c_short {
    require!(table::MT_SET_LEAD_SCREW_COMP_PARA, pCompPos, pCompNeg);
    let n = bounded(i64::from(num), MAX_LEAD_SCREW_POINTS);
    let pos = load_slice(pCompPos.cast_const(), n);
    let neg = load_slice(pCompNeg.cast_const(), n);
    served(
        &table::MT_SET_LEAD_SCREW_COMP_PARA,
        axisHandle,
        |w| {
            w.i16(num).i64(i64::from(startPos)).i64(i64::from(cmpLen));
            for a in [&pos, &neg] {
                write_array(w, a, |w, v| {
                    w.i16(*v);
                });
            }
        },
        |_| Ok(()),
    )
}

setter!(
    NMC_MtEnableLeadScrew,
    table::MT_ENABLE_LEAD_SCREW,
    c_short,
    i16
);

#[no_mangle]
pub extern "C" fn NMC_MtSetBacklash(
    axisHandle: HAND,
    compValue: c_long,
    compDelta: f64,
    compDir: c_long,
) -> c_short {
    served(
        &table::MT_SET_BACKLASH,
        axisHandle,
        |w| {
            w.i64(i64::from(compValue))
                .f64(compDelta)
                .i64(i64::from(compDir));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_MtGetBacklash(
    axisHandle: HAND,
    pCompValue: *mut c_long,
    pCompDelta: *mut f64,
    pCompDir: *mut c_long,
) -> c_short {
    require!(table::MT_GET_BACKLASH, pCompValue, pCompDelta, pCompDir);
    served(
        &table::MT_GET_BACKLASH,
        axisHandle,
        |_| {},
        |r| {
            store(pCompValue, to_long(r.i64()?));
            store(pCompDelta, r.f64()?);
            store(pCompDir, to_long(r.i64()?));
            Ok(())
        },
    )
}

/// The grid points a table of `t` has (0 when its counts are outside their ranges: the
/// server then refuses them).
fn grid_points(t: &T2DCompensationTable) -> usize {
    let x = bounded(i64::from(t.count[0]), MAX_GRID_POINTS);
    let y = bounded(i64::from(t.count[1]), MAX_GRID_POINTS);
    Some(x * y).filter(|n| *n <= MAX_GRID_POINTS).unwrap_or(0)
}

/// `pData` holds count[0] × count[1] points, X varying fastest.
#[no_mangle]
pub extern "C" fn NMC_Set2DCompensationTable(
    devHandle: HAND,
    tableIndex: c_short,
    pTable: *mut T2DCompensationTable,
    pData: *mut TCompData,
) -> c_short {
    require!(table::SET_2D_COMPENSATION_TABLE, pTable, pData);
    let t = load(pTable.cast_const());
    let data: Vec<CompData> = load_slice(pData.cast_const(), grid_points(&t))
        .into_iter()
        .map(CompData::from)
        .collect();
    served(
        &table::SET_2D_COMPENSATION_TABLE,
        devHandle,
        |w| {
            w.i16(tableIndex);
            Comp2DTable::from(t).write(w);
            write_array(w, &data, |w, d| d.write(w));
        },
        |_| Ok(()),
    )
}

/// Writes count[0] × count[1] points into `pData` (the caller sized it from its table).
#[no_mangle]
pub extern "C" fn NMC_Get2DCompensationTable(
    devHandle: HAND,
    tableIndex: c_short,
    pTable: *mut T2DCompensationTable,
    pData: *mut TCompData,
) -> c_short {
    require!(table::GET_2D_COMPENSATION_TABLE, pTable, pData);
    served(
        &table::GET_2D_COMPENSATION_TABLE,
        devHandle,
        |w| {
            w.i16(tableIndex);
        },
        |r| {
            let t = T2DCompensationTable::from(Comp2DTable::read(r)?);
            let data = read_array(r, CompData::read)?;
            store(pTable, t);
            store_slice(
                pData,
                grid_points(&t),
                data.into_iter().map(TCompData::from),
            );
            Ok(())
        },
    )
}

struct_setter!(
    NMC_Set2DCompensation,
    table::SET_2D_COMPENSATION,
    T2DCompensation,
    Comp2D
);
struct_getter!(
    NMC_Get2DCompensation,
    table::GET_2D_COMPENSATION,
    T2DCompensation,
    Comp2D
);
