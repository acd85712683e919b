//! The device's identity (digest 001 §2.20, §3.18): its ID string, unique serial and firmware
//! version.

use mcemu_nmc::io_structs::LibVersion;
use mcemu_nmc::structs::chars;
use mcemu_nmc::table::{self, Function};

use crate::nmc::config::NmcDevice;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::DEV_READ_ID, dev_read_id),
    (table::GET_UID, get_uid),
    (table::GET_MT_LIB_VERSION, get_mt_lib_version),
];

/// The device's unique serial (`TCardInfo.uid`, `NMC_GetUID` = uid[0]): FNV-1a of its ID and
/// IP, so that two configured devices differ and one device keeps its serial across restarts.
pub fn device_uid(d: &NmcDevice) -> [u64; 4] {
    let hash = |seed: u64| {
        d.id.bytes()
            .chain(d.ip.octets())
            .fold(0xcbf2_9ce4_8422_2325 ^ seed, |h, b| {
                (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
            })
            & 0xFFFF_FFFF
    };
    [hash(0), hash(1), hash(2), hash(3)]
}

/// The ID the device holds: the configured one, or the one `NMC_DevWriteID` wrote (digest 001
/// §4.9: it takes effect for `NMC_DevOpenByID` after a power cycle).
fn dev_read_id(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let written = c.service.io().written_id.clone();
    let id = written.unwrap_or_else(|| c.service.device.id.clone());
    c.output.str(id.as_bytes());
    Ok(())
}

/// 32 bits (an `unsigned long` is 32 bits on the manual's platform).
fn get_uid(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let [uid, ..] = device_uid(&c.service.device);
    c.output.u64(uid);
    Ok(())
}

/// mcemu's version (`TmLibVersion` is mcemu's, digest 001 §8 item 3).
fn get_mt_lib_version(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let number = |s: &str| s.parse::<i16>().unwrap_or(0);
    let v = LibVersion {
        str_ver: chars(concat!("mcemu ", env!("CARGO_PKG_VERSION"))),
        major: number(env!("CARGO_PKG_VERSION_MAJOR")),
        minor: number(env!("CARGO_PKG_VERSION_MINOR")),
        patch: number(env!("CARGO_PKG_VERSION_PATCH")),
    };
    v.write(c.output);
    Ok(())
}
