//! Position compare, 1-D and 2-D (digest 001 §2.11, §3.16).

use std::ffi::{c_long, c_short};

use mcemu_nmc::sync_structs::{write_array, Comp2DimensParam, Comp2DimensSts};
use mcemu_nmc::table;

use super::arrays::{bounded, load_slice};
use super::sync_types::{TComp2DimensParamEx, TComp2DimensSts};
use super::{load, require, served, store, HAND};

/// Most longs one request carries (16 KiB frames, i64 each): a longer `SetData` is sent in
/// parts, which the server appends in order (docs/decisions.md).
const LONGS_PER_REQUEST: usize = 1024;
/// `count` ≤ 32896 points, as (X, Y) pairs (digest 001 §2.11).
const MAX_POINTS: usize = 32896;

#[no_mangle]
pub extern "C" fn NMC_Comp2DimensSetParamEx(
    devHandle: HAND,
    group: c_short,
    param: *mut TComp2DimensParamEx,
    chn: c_short,
) -> c_short {
    require!(table::COMP_2DIMENS_SET_PARAM_EX, param);
    let p = Comp2DimensParam::from(load(param.cast_const()));
    served(
        &table::COMP_2DIMENS_SET_PARAM_EX,
        devHandle,
        |w| {
            w.i16(group);
            p.write(w);
            w.i16(chn);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_Comp2DimensGetParamEx(
    devHandle: HAND,
    group: c_short,
    param: *mut TComp2DimensParamEx,
    chn: c_short,
) -> c_short {
    require!(table::COMP_2DIMENS_GET_PARAM_EX, param);
    served(
        &table::COMP_2DIMENS_GET_PARAM_EX,
        devHandle,
        |w| {
            w.i16(group).i16(chn);
        },
        |r| {
            store(param, TComp2DimensParamEx::from(Comp2DimensParam::read(r)?));
            Ok(())
        },
    )
}

/// `pArrayPos` holds `count` (X, Y) pairs, or `count` positions when the group's compare is
/// 1-D (`dir2No` = −1); the server says which by the length it expects. The library sends
/// 2 × `count` values when they fit the caller's pairs, split into parts the server appends.
#[no_mangle]
pub extern "C" fn NMC_Comp2DimensSetData(
    devHandle: HAND,
    group: c_short,
    pArrayPos: *mut c_long,
    count: c_short,
    chn: c_short,
) -> c_short {
    let n = bounded(i64::from(count), MAX_POINTS);
    if n > 0 {
        require!(table::COMP_2DIMENS_SET_DATA, pArrayPos);
    }
    // Ask the server how many values a point has: one (1-D) or two.
    let mut dims = 2usize;
    let mut para = TComp2DimensParamEx::default();
    if n > 0 && NMC_Comp2DimensGetParamEx(devHandle, group, &mut para, chn) == 0 && para.dir2No < 0
    {
        dims = 1;
    }
    let values = load_slice(pArrayPos.cast_const(), n * dims);
    let mut parts: Vec<&[c_long]> = values.chunks(LONGS_PER_REQUEST).collect();
    if parts.is_empty() {
        parts.push(&[]);
    }
    for part in parts {
        let points = part.len() / dims;
        let sent_count = if n == 0 { count } else { points as c_short };
        let rc = served(
            &table::COMP_2DIMENS_SET_DATA,
            devHandle,
            |w| {
                w.i16(group);
                write_array(w, part, |w, v| {
                    w.i64(i64::from(*v));
                });
                w.i16(sent_count).i16(chn);
            },
            |_| Ok(()),
        );
        if rc != 0 {
            return rc;
        }
    }
    0
}

#[no_mangle]
pub extern "C" fn NMC_Comp2DimensOnoff(
    devHandle: HAND,
    group: c_short,
    onOff: c_short,
    chn: c_short,
) -> c_short {
    served(
        &table::COMP_2DIMENS_ONOFF,
        devHandle,
        |w| {
            w.i16(group).i16(onOff).i16(chn);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_Comp2DimensStatusEx(
    devHandle: HAND,
    group: c_short,
    pStatus: *mut TComp2DimensSts,
    chn: c_short,
) -> c_short {
    require!(table::COMP_2DIMENS_STATUS_EX, pStatus);
    served(
        &table::COMP_2DIMENS_STATUS_EX,
        devHandle,
        |w| {
            w.i16(group).i16(chn);
        },
        |r| {
            store(pStatus, TComp2DimensSts::from(Comp2DimensSts::read(r)?));
            Ok(())
        },
    )
}
