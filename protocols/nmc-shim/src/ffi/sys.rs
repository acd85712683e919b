//! The system family (0x18xx; digest 001 §2.7, §2.20, §3.19): data collection, users, the
//! configuration file on the host, the execution-time calculation, command debugging and
//! `NMC_UserPrint`.

use std::ffi::{c_char, c_long, c_short, c_uchar, c_ulong};

use mcemu_nmc::errors::{RTN_FILE, RTN_INVALID_HANDLE, RTN_INVALID_STATE};
use mcemu_nmc::handle::Handle;
use mcemu_nmc::sys::{CollectCfg, CollectTrig, COLLECT_DATA_MAX, COLLECT_LIST_MAX};
use mcemu_nmc::table::{self, Function};

use super::types::{to_long, to_ulong};
use super::{
    action, c_string, call, load, put_c_string, reply_list, require, served, setter, store,
    store_array, HAND,
};
use crate::cmd_debug;
use crate::connection::CallError;
use crate::last_error::report;
use crate::registry;

/// `TCollectCfg` (mtn_lib20.h).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TCollectCfg {
    pub count: c_short,
    pub interval: c_short,
    pub address: [c_ulong; COLLECT_LIST_MAX],
    pub length: [c_short; COLLECT_LIST_MAX],
}

impl From<TCollectCfg> for CollectCfg {
    fn from(c: TCollectCfg) -> CollectCfg {
        CollectCfg {
            count: c.count,
            interval: c.interval,
            address: c.address.map(u64::from),
            length: c.length,
        }
    }
}

/// `TCollectTrig` (mtn_lib20.h).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TCollectTrig {
    pub mode: c_short,
    pub source1: c_short,
    pub source2: c_short,
    pub startDelay: c_short,
    pub value: f64,
}

impl From<TCollectTrig> for CollectTrig {
    fn from(t: TCollectTrig) -> CollectTrig {
        CollectTrig {
            mode: t.mode,
            source1: t.source1,
            source2: t.source2,
            start_delay: t.startDelay,
            value: t.value,
        }
    }
}

/// User names and passwords are ≤ 15 bytes (the server refuses longer ones); longer strings
/// are cut here so that the refusal names their real start.
const STR_MAX: usize = 64;
/// A file path's bytes at most.
const PATH_MAX: usize = 4096;

#[no_mangle]
pub extern "C" fn NMC_GetCollectDataAddr(
    devHandle: HAND,
    index: c_short,
    dataType: c_short,
    pAddr: *mut c_ulong,
    pDataLen: *mut c_short,
) -> c_short {
    require!(table::GET_COLLECT_DATA_ADDR, pAddr, pDataLen);
    served(
        &table::GET_COLLECT_DATA_ADDR,
        devHandle,
        |w| {
            w.i16(index).i16(dataType);
        },
        |r| {
            store(pAddr, to_ulong(r.u64()?));
            store(pDataLen, r.i16()?);
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_ConfigCollect(
    devHandle: HAND,
    pCollect: *mut TCollectCfg,
    pTrig: *mut TCollectTrig,
) -> c_short {
    require!(table::CONFIG_COLLECT, pCollect, pTrig);
    let cfg = CollectCfg::from(load(pCollect.cast_const()));
    let trig = CollectTrig::from(load(pTrig.cast_const()));
    served(
        &table::CONFIG_COLLECT,
        devHandle,
        |w| {
            cfg.write(w);
            trig.write(w);
        },
        |_| Ok(()),
    )
}

setter!(NMC_CollectOnOff, table::COLLECT_ON_OFF, c_short, i16);

#[no_mangle]
pub extern "C" fn NMC_GetCollectSts(
    devHandle: HAND,
    pSts: *mut c_short,
    pDataLen: *mut c_long,
) -> c_short {
    require!(table::GET_COLLECT_STS, pSts, pDataLen);
    served(
        &table::GET_COLLECT_STS,
        devHandle,
        |_| {},
        |r| {
            store(pSts, r.i16()?);
            store(pDataLen, to_long(r.i64()?));
            Ok(())
        },
    )
}

/// Writes at most `len` bytes (≤ 1440; the server refuses more).
#[no_mangle]
pub extern "C" fn NMC_GetCollectData(
    devHandle: HAND,
    len: c_short,
    pData: *mut c_uchar,
) -> c_short {
    require!(table::GET_COLLECT_DATA, pData);
    let wanted = usize::try_from(len).unwrap_or(0).min(COLLECT_DATA_MAX);
    served(
        &table::GET_COLLECT_DATA,
        devHandle,
        |w| {
            w.i16(len);
        },
        |r| {
            let bytes = reply_list(r, wanted, |r| r.u8())?;
            store_array(pData, &bytes);
            Ok(())
        },
    )
}

action!(NMC_ClearCollectSts, table::CLEAR_COLLECT_STS);

/// A device call with string arguments `strings` (each cut at [`STR_MAX`]).
fn strings(row: &Function, devHandle: HAND, strings: &[*mut c_char]) -> c_short {
    if strings.iter().any(|p| p.is_null()) {
        return report(Err(super::null(row, "a string argument")));
    }
    let values: Vec<Vec<u8>> = strings
        .iter()
        .map(|p| c_string(p.cast_const(), STR_MAX))
        .collect();
    served(
        row,
        devHandle,
        |w| {
            for v in &values {
                w.str(v);
            }
        },
        |_| Ok(()),
    )
}

#[no_mangle]
pub extern "C" fn NMC_UserSetPassword(
    devHandle: HAND,
    pUserName: *mut c_char,
    pPasswordOld: *mut c_char,
    pPasswordNew: *mut c_char,
) -> c_short {
    require!(
        table::USER_SET_PASSWORD,
        pUserName,
        pPasswordOld,
        pPasswordNew
    );
    strings(
        &table::USER_SET_PASSWORD,
        devHandle,
        &[pUserName, pPasswordOld, pPasswordNew],
    )
}

#[no_mangle]
pub extern "C" fn NMC_UserLogin(
    devHandle: HAND,
    pUserName: *mut c_char,
    pPassword: *mut c_char,
) -> c_short {
    require!(table::USER_LOGIN, pUserName, pPassword);
    strings(&table::USER_LOGIN, devHandle, &[pUserName, pPassword])
}

#[no_mangle]
pub extern "C" fn NMC_UserLogout(devHandle: HAND, pUserName: *mut c_char) -> c_short {
    require!(table::USER_LOGOUT, pUserName);
    strings(&table::USER_LOGOUT, devHandle, &[pUserName])
}

/// 0 off; 1, 3, 4 to stderr (the host's one debug channel: no GCS or DebugView here); 2
/// appended to `debugOutputFile`. A file that cannot be opened is `RTN_FILE`.
#[no_mangle]
pub extern "C" fn NMC_SetCmdDebug(enable: c_short, debugOutputFile: *mut c_char) -> c_short {
    if enable == 2 {
        require!(table::SET_CMD_DEBUG, debugOutputFile);
    }
    let path = c_string(debugOutputFile.cast_const(), PATH_MAX);
    let f = &table::SET_CMD_DEBUG;
    report(cmd_debug::set(enable, &path).map_err(|e| {
        let code = if (0..=4).contains(&enable) {
            RTN_FILE
        } else {
            mcemu_nmc::errors::RTN_ARG_RANGE
        };
        CallError::new(code, format!("{}: {e}", f.name))
    }))
}

/// To the command debug output if one is on, else to stderr.
#[no_mangle]
pub extern "C" fn NMC_UserPrint(msg: *mut c_char) -> c_short {
    require!(table::USER_PRINT, msg);
    let text = c_string(msg.cast_const(), usize::MAX);
    cmd_debug::write_line(&String::from_utf8_lossy(&text), true);
    report(Ok(()))
}

fn file_error(f: &Function, what: String) -> CallError {
    CallError::new(RTN_FILE, format!("{}: {what}", f.name))
}

/// The path as the host's file system takes it (relative to the program's directory).
fn host_path(f: &Function, p: *mut c_char) -> Result<std::path::PathBuf, CallError> {
    let bytes = c_string(p.cast_const(), PATH_MAX);
    let s =
        std::str::from_utf8(&bytes).map_err(|_| file_error(f, "the path is not UTF-8".into()))?;
    if s.is_empty() {
        return Err(file_error(f, "the path is empty".into()));
    }
    Ok(std::path::PathBuf::from(s))
}

/// The device's configuration (`NMC_DevGetConfigText`) written to the host file `pFilePath`.
#[no_mangle]
pub extern "C" fn NMC_SaveConfigToFile(devHandle: HAND, pFilePath: *mut c_char) -> c_short {
    require!(table::SAVE_CONFIG_TO_FILE, pFilePath);
    let f = &table::SAVE_CONFIG_TO_FILE;
    let result = (|| {
        let path = host_path(f, pFilePath)?;
        let mut text = Vec::new();
        call(
            &table::DEV_GET_CONFIG_TEXT,
            devHandle,
            |_| {},
            |r| {
                text = r.str()?.to_vec();
                Ok(())
            },
        )?;
        std::fs::write(&path, &text)
            .map_err(|e| file_error(f, format!("cannot write {}: {e}", path.display())))
    })();
    report(result)
}

/// The host file `pFilePath` (as `NMC_SaveConfigToFile` writes it) applied to the device.
#[no_mangle]
pub extern "C" fn NMC_LoadConfigFromFile(devHandle: HAND, pFilePath: *mut c_char) -> c_short {
    require!(table::LOAD_CONFIG_FROM_FILE, pFilePath);
    let f = &table::LOAD_CONFIG_FROM_FILE;
    let result = (|| {
        let path = host_path(f, pFilePath)?;
        let text = std::fs::read(&path)
            .map_err(|e| file_error(f, format!("cannot read {}: {e}", path.display())))?;
        if text.len() > mcemu_nmc::sys::CONFIG_TEXT_MAX {
            return Err(file_error(
                f,
                format!(
                    "{} is {} bytes: not a configuration",
                    path.display(),
                    text.len()
                ),
            ));
        }
        call(
            &table::DEV_SET_CONFIG_TEXT,
            devHandle,
            |w| {
                w.str(&text);
            },
            |_| Ok(()),
        )
    })();
    report(result)
}

/// Writes at most `NMC_CONFIG_TEXT_MAX` bytes and a NUL.
#[no_mangle]
pub extern "C" fn NMC_DevGetConfigText(devHandle: HAND, pText: *mut c_char) -> c_short {
    require!(table::DEV_GET_CONFIG_TEXT, pText);
    served(
        &table::DEV_GET_CONFIG_TEXT,
        devHandle,
        |_| {},
        |r| {
            let text = r.str()?;
            put_c_string(
                pText,
                mcemu_nmc::sys::CONFIG_TEXT_MAX + 1,
                &String::from_utf8_lossy(text),
            );
            Ok(())
        },
    )
}

#[no_mangle]
pub extern "C" fn NMC_DevSetConfigText(devHandle: HAND, pText: *mut c_char) -> c_short {
    require!(table::DEV_SET_CONFIG_TEXT, pText);
    let text = c_string(pText.cast_const(), mcemu_nmc::sys::CONFIG_TEXT_MAX + 1);
    served(
        &table::DEV_SET_CONFIG_TEXT,
        devHandle,
        |w| {
            w.str(&text);
        },
        |_| Ok(()),
    )
}

action!(NMC_CrdStartExeTimeCalcEx, table::CRD_START_EXE_TIME_CALC_EX);

#[no_mangle]
pub extern "C" fn NMC_CrdGetExeTimeEx(devHandle: HAND, pTime: *mut f64) -> c_short {
    require!(table::CRD_GET_EXE_TIME_EX, pTime);
    served(
        &table::CRD_GET_EXE_TIME_EX,
        devHandle,
        |_| {},
        |r| {
            store(pTime, r.f64()?);
            Ok(())
        },
    )
}

/// The open devices' handles.
fn open_devices(f: &Function) -> Result<Vec<HAND>, CallError> {
    let devices: Vec<HAND> = registry::open_slots()
        .into_iter()
        .map(|s| Handle::device(s).encode())
        .collect();
    if devices.is_empty() {
        return Err(CallError::new(
            RTN_INVALID_HANDLE,
            format!("{}: no device is open", f.name),
        ));
    }
    Ok(devices)
}

/// Starts the calculation on every open device (the manual's one host look-ahead).
#[no_mangle]
pub extern "C" fn NMC_CrdStartExeTimeCalc() -> c_short {
    let f = &table::CRD_START_EXE_TIME_CALC;
    let result = open_devices(f).and_then(|devices| {
        devices
            .into_iter()
            .try_for_each(|d| call(&table::CRD_START_EXE_TIME_CALC_EX, d, |_| {}, |_| Ok(())))
    });
    report(result)
}

/// The sum over the open devices that run a calculation, which stops; ms.
fn get_exe_time(f: &Function, pTime: *mut f64) -> c_short {
    let result = (|| {
        let mut total = 0.0;
        let mut any = false;
        for d in open_devices(f)? {
            let mut t = 0.0;
            match call(
                &table::CRD_GET_EXE_TIME_EX,
                d,
                |_| {},
                |r| {
                    t = r.f64()?;
                    Ok(())
                },
            ) {
                Ok(()) => {
                    total += t;
                    any = true;
                }
                // A device opened after the start runs none: not counted.
                Err(e) if e.code == RTN_INVALID_STATE => {}
                Err(e) => return Err(e),
            }
        }
        if !any {
            return Err(CallError::new(
                RTN_INVALID_STATE,
                format!(
                    "{}: no calculation running (NMC_CrdStartExeTimeCalc first)",
                    f.name
                ),
            ));
        }
        store(pTime, total);
        Ok(())
    })();
    report(result)
}

#[no_mangle]
pub extern "C" fn NMC_CrdGetExeTime(pTime: *mut f64) -> c_short {
    require!(table::CRD_GET_EXE_TIME, pTime);
    get_exe_time(&table::CRD_GET_EXE_TIME, pTime)
}

/// As the detailed text prints it (digest 001 App. A).
#[no_mangle]
pub extern "C" fn _NMC_CrdGetExeTime(pTime: *mut f64) -> c_short {
    require!(table::CRD_GET_EXE_TIME_SIC, pTime);
    get_exe_time(&table::CRD_GET_EXE_TIME_SIC, pTime)
}
