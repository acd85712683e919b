//! Digital I/O by type (general, limits, home, Z, servo enable, alarm clear), masked DO
//! writes, encoder channels, extension I/O modules and the device's identity (digest 001 §2.8,
//! §2.20, §4.8; rows 0x12xx).

use std::ffi::{c_char, c_double, c_long, c_short, c_uchar, c_ulong, c_ushort};

use mcemu_nmc::io_structs::LibVersion;
use mcemu_nmc::table::{self, Function};

use super::io_types::TmLibVersion;
use super::types::{to_long, to_ulong};
use super::{put_c_string, require, served, store, HAND};

/// `(devHandle, short type, short group, long *out)`.
fn typed_read(
    row: &Function,
    devHandle: HAND,
    kind: c_short,
    group: c_short,
    out: *mut c_long,
) -> c_short {
    require!(*row, out);
    served(
        row,
        devHandle,
        |w| {
            w.i16(kind).i16(group);
        },
        |r| {
            store(out, to_long(r.i64()?));
            Ok(())
        },
    )
}

/// DI bits of `diType` (0 general, 1 negative limit, 2 positive limit, 3 home, 4 Z) in group
/// `groupID`, after inversion (`NMC_SetDIBitRevs`); 1 = high level / open (digest 001 §2.8).
#[no_mangle]
pub extern "C" fn NMC_GetDIEx(
    devHandle: HAND,
    diType: c_short,
    groupID: c_short,
    pDiValue: *mut c_long,
) -> c_short {
    typed_read(&table::GET_DI_EX, devHandle, diType, groupID, pDiValue)
}

/// As `NMC_GetDIEx`, the levels at the terminals: before inversion.
#[no_mangle]
pub extern "C" fn NMC_GetDIRaw(
    devHandle: HAND,
    diType: c_short,
    groupID: c_short,
    pDiValue: *mut c_long,
) -> c_short {
    typed_read(&table::GET_DI_RAW, devHandle, diType, groupID, pDiValue)
}

/// DO bits of `doType` (1 servo enable, 2 alarm clear, 3 general) in group `groupID`.
#[no_mangle]
pub extern "C" fn NMC_GetDOEx(
    devHandle: HAND,
    doType: c_short,
    groupID: c_short,
    pOutValue: *mut c_long,
) -> c_short {
    typed_read(&table::GET_DO_EX, devHandle, doType, groupID, pOutValue)
}

/// Write the bits of `outValue` that `outMask` selects, leaving the others.
#[no_mangle]
pub extern "C" fn NMC_SetDOMask(
    devHandle: HAND,
    outMask: c_long,
    outValue: c_long,
    doType: c_short,
    groupID: c_short,
) -> c_short {
    served(
        &table::SET_DO_MASK,
        devHandle,
        |w| {
            w.i64(i64::from(outMask))
                .i64(i64::from(outValue))
                .i16(doType)
                .i16(groupID);
        },
        |_| Ok(()),
    )
}

/// Encoder channel `encId`: an axis's [0, n), or 256 / 257 the external encoders.
#[no_mangle]
pub extern "C" fn NMC_GetEncPos(devHandle: HAND, encId: c_short, pPos: *mut c_long) -> c_short {
    require!(table::GET_ENC_POS, pPos);
    served(
        &table::GET_ENC_POS,
        devHandle,
        |w| {
            w.i16(encId);
        },
        |r| {
            store(pPos, to_long(r.i64()?));
            Ok(())
        },
    )
}

/// pulse/ms. `encId` is `unsigned char` as the manual writes it (so 256 cannot be passed).
#[no_mangle]
pub extern "C" fn NMC_GetEncVel(devHandle: HAND, encId: c_uchar, vel: *mut c_double) -> c_short {
    require!(table::GET_ENC_VEL, vel);
    served(
        &table::GET_ENC_VEL,
        devHandle,
        |w| {
            w.u8(encId);
        },
        |r| {
            store(vel, r.f64()?);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_SetEncPos(devHandle: HAND, encId: c_short, encPos: c_long) -> c_short {
    served(
        &table::SET_ENC_POS,
        devHandle,
        |w| {
            w.i16(encId).i64(i64::from(encPos));
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_IOModuleSetEn(
    devHandle: HAND,
    chDevId: c_uchar,
    chDevType: c_short,
) -> c_short {
    served(
        &table::IO_MODULE_SET_EN,
        devHandle,
        |w| {
            w.u8(chDevId).i16(chDevType);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_IOModuleGetType(
    devHandle: HAND,
    chDevId: c_uchar,
    pChDevType: *mut c_short,
) -> c_short {
    require!(table::IO_MODULE_GET_TYPE, pChDevType);
    served(
        &table::IO_MODULE_GET_TYPE,
        devHandle,
        |w| {
            w.u8(chDevId);
        },
        |r| {
            store(pChDevType, r.i16()?);
            Ok(())
        },
    )
}

fn module_read16(
    row: &Function,
    devHandle: HAND,
    id: c_uchar,
    offset: c_uchar,
    out: *mut c_ushort,
) -> c_short {
    require!(*row, out);
    served(
        row,
        devHandle,
        |w| {
            w.u8(id).u8(offset);
        },
        |r| {
            store(out, r.u16()?);
            Ok(())
        },
    )
}

fn module_read32(
    row: &Function,
    devHandle: HAND,
    id: c_uchar,
    offset: c_uchar,
    out: *mut c_ulong,
) -> c_short {
    require!(*row, out);
    served(
        row,
        devHandle,
        |w| {
            w.u8(id).u8(offset);
        },
        |r| {
            store(out, to_ulong(r.u64()?));
            Ok(())
        },
    )
}

/// Inputs of module `chDevId`: offset 0 the low 16 bits, 1 the high.
#[no_mangle]
pub extern "C" fn NMC_IOModuleRd16Bit(
    devHandle: HAND,
    chDevId: c_uchar,
    offset: c_uchar,
    pData: *mut c_ushort,
) -> c_short {
    module_read16(
        &table::IO_MODULE_RD_16BIT,
        devHandle,
        chDevId,
        offset,
        pData,
    )
}

#[no_mangle]
pub extern "C" fn NMC_IOModuleRd32Bit(
    devHandle: HAND,
    chDevId: c_uchar,
    offset: c_uchar,
    pData: *mut c_ulong,
) -> c_short {
    module_read32(
        &table::IO_MODULE_RD_32BIT,
        devHandle,
        chDevId,
        offset,
        pData,
    )
}

/// Outputs of module `chDevId` read back.
#[no_mangle]
pub extern "C" fn NMC_IOModuleRdOut16Bit(
    devHandle: HAND,
    chDevId: c_uchar,
    offset: c_uchar,
    pData: *mut c_ushort,
) -> c_short {
    module_read16(
        &table::IO_MODULE_RD_OUT_16BIT,
        devHandle,
        chDevId,
        offset,
        pData,
    )
}

#[no_mangle]
pub extern "C" fn NMC_IOModuleRdOut32Bit(
    devHandle: HAND,
    chDevId: c_uchar,
    offset: c_uchar,
    pData: *mut c_ulong,
) -> c_short {
    module_read32(
        &table::IO_MODULE_RD_OUT_32BIT,
        devHandle,
        chDevId,
        offset,
        pData,
    )
}

#[no_mangle]
pub extern "C" fn NMC_IOModuleWr16Bit(
    devHandle: HAND,
    chDevId: c_uchar,
    offset: c_uchar,
    data: c_ushort,
) -> c_short {
    served(
        &table::IO_MODULE_WR_16BIT,
        devHandle,
        |w| {
            w.u8(chDevId).u8(offset).u16(data);
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_IOModuleWr32Bit(
    devHandle: HAND,
    chDevId: c_uchar,
    offset: c_uchar,
    data: c_ulong,
) -> c_short {
    served(
        &table::IO_MODULE_WR_32BIT,
        devHandle,
        |w| {
            w.u8(chDevId).u8(offset).u64(u64::from(data));
        },
        |_| Ok(()),
    )
}

/// Bit k: module k + 2 enabled and answering.
#[no_mangle]
pub extern "C" fn NMC_GetIOModuleSts(devHandle: HAND, sts: *mut c_ulong) -> c_short {
    require!(table::GET_IO_MODULE_STS, sts);
    served(
        &table::GET_IO_MODULE_STS,
        devHandle,
        |_| {},
        |r| {
            store(sts, to_ulong(r.u64()?));
            Ok(())
        },
    )
}

/// The ID string into the caller's buffer ("> 16 B": 16 written at most, NUL included).
#[no_mangle]
pub extern "C" fn NMC_DevReadID(devHandle: HAND, pIdStr: *mut c_char) -> c_short {
    require!(table::DEV_READ_ID, pIdStr);
    served(
        &table::DEV_READ_ID,
        devHandle,
        |_| {},
        |r| {
            put_c_string(pIdStr, 16, &String::from_utf8_lossy(r.str()?));
            Ok(())
        },
    )
}

/// The device's unique serial: one `unsigned long` (TCardInfo.uid[0]).
#[no_mangle]
pub extern "C" fn NMC_GetUID(devHandle: HAND, pUID: *mut c_ulong) -> c_short {
    require!(table::GET_UID, pUID);
    served(
        &table::GET_UID,
        devHandle,
        |_| {},
        |r| {
            store(pUID, to_ulong(r.u64()?));
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_GetMtLibVersion(devHandle: HAND, pVersion: *mut TmLibVersion) -> c_short {
    require!(table::GET_MT_LIB_VERSION, pVersion);
    served(
        &table::GET_MT_LIB_VERSION,
        devHandle,
        |_| {},
        |r| {
            store(pVersion, TmLibVersion::from(LibVersion::read(r)?));
            Ok(())
        },
    )
}
