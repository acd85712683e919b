//! Gantry and handwheel (digest 001 §2.9–2.10).

use std::ffi::{c_long, c_short};

use mcemu_nmc::table;

use super::{action, served, setter, HAND};

setter!(NMC_SetGantryMaster, table::SET_GANTRY_MASTER, c_short, i16);

#[no_mangle]
pub extern "C" fn NMC_SetGantrySlave(
    axisHandle: HAND,
    group: c_short,
    gantryErrLmt: c_long,
) -> c_short {
    served(
        &table::SET_GANTRY_SLAVE,
        axisHandle,
        |w| {
            w.i16(group).i64(i64::from(gantryErrLmt));
        },
        |_| Ok(()),
    )
}

setter!(NMC_DelGantryGroup, table::DEL_GANTRY_GROUP, c_short, i16);

#[no_mangle]
pub extern "C" fn NMC_SetHandWheel(
    devHandle: HAND,
    axis: c_short,
    ratio: f64,
    acc: f64,
    vel: f64,
) -> c_short {
    served(
        &table::SET_HAND_WHEEL,
        devHandle,
        |w| {
            w.i16(axis).f64(ratio).f64(acc).f64(vel);
        },
        |_| Ok(()),
    )
}

setter!(
    NMC_SetHandWheelInput,
    table::SET_HAND_WHEEL_INPUT,
    c_short,
    i16
);
setter!(NMC_SetHandWheelRatio, table::SET_HAND_WHEEL_RATIO, f64, f64);
action!(NMC_ClrHandWheel, table::CLR_HAND_WHEEL);
