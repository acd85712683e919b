//! The C layout of the 0x12xx families' structs (`mcemu_nmc::io_header`) and their conversions
//! to the wire's (`mcemu_nmc::io_structs`).

#![allow(non_snake_case)]

use std::ffi::{c_char, c_short};

use mcemu_nmc::io_structs::LibVersion;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct TmLibVersion {
    pub strVer: [c_char; 16],
    pub major: c_short,
    pub minor: c_short,
    pub patch: c_short,
    pub reserved: c_short,
}

impl From<LibVersion> for TmLibVersion {
    fn from(v: LibVersion) -> TmLibVersion {
        TmLibVersion {
            strVer: v.str_ver.map(|b| b as c_char),
            major: v.major,
            minor: v.minor,
            patch: v.patch,
            reserved: 0,
        }
    }
}
