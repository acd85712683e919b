//! `nmc_lib20`: a drop-in replacement of Gaochuan's `NMC_*` C library (digest 001) that talks
//! to mcemu instead of a controller. A program written for the manual compiles against
//! `include/mtn_lib20.h` and links `libnmc_lib20.so`.
//!
//! - [`address`]: which mcemu a device opens (`MCEMU_NMC`);
//! - [`connection`]: one connection per device handle, requests matched by sequence number,
//!   any thread, every call bounded by the timeout, reconnect after a loss;
//! - [`registry`]: the open devices by handle slot;
//! - [`cmd_debug`]: `NMC_SetCmdDebug`'s output (stderr or a file) and `NMC_UserPrint`;
//! - [`last_error`]: `NMC_GetLastErr`, `NMC_GetErrDesc`, `NMC_SetErrCodeMode`;
//! - [`ffi`]: the exported functions, one file per family, each made from its row of the
//!   function table (`mcemu_nmc::table`). `unsafe` lives only in `ffi`'s pointer helpers.

pub mod address;
pub mod cmd_debug;
pub mod connection;
pub mod ffi;
pub mod last_error;
pub mod registry;

#[cfg(test)]
mod tests {
    use mcemu_nmc::table::{Served, FUNCTIONS};

    /// Every row of the table is exported by this library (the names of `ffi` are checked by
    /// the C tests linking them; here: the table's rows all belong to a family file).
    #[test]
    fn every_row_is_exported() {
        let sources = [
            include_str!("ffi/library.rs"),
            include_str!("ffi/device.rs"),
            include_str!("ffi/axis.rs"),
            include_str!("ffi/motion.rs"),
            include_str!("ffi/home.rs"),
            include_str!("ffi/io.rs"),
            include_str!("ffi/gear.rs"),
            include_str!("ffi/pt.rs"),
            include_str!("ffi/capture.rs"),
            include_str!("ffi/compare.rs"),
            include_str!("ffi/gang.rs"),
            include_str!("ffi/compensation.rs"),
            include_str!("ffi/crd.rs"),
            include_str!("ffi/axis_config.rs"),
            include_str!("ffi/aliases.rs"),
            include_str!("ffi/analog.rs"),
            include_str!("ffi/ecat.rs"),
            include_str!("ffi/user_para.rs"),
            include_str!("ffi/laser.rs"),
            include_str!("ffi/io_ext.rs"),
            include_str!("ffi/io_extras.rs"),
            include_str!("ffi/dev_services.rs"),
            include_str!("ffi/axis_ext.rs"),
            include_str!("ffi/follow.rs"),
            include_str!("ffi/extras.rs"),
            include_str!("ffi/closed_loop.rs"),
            include_str!("ffi/crd_lookahead.rs"),
            include_str!("ffi/sys.rs"),
            include_str!("ffi/crd_buf_io.rs"),
            include_str!("ffi/crd_frames.rs"),
        ]
        .concat();
        for f in FUNCTIONS {
            // `fn NMC_X(` by hand, or `NMC_X,` as a wrapper macro's first argument.
            let exported = sources.contains(&format!("fn {}(", f.name))
                || sources.contains(&format!("{},", f.name));
            assert!(exported, "{} ({:?}) is not exported", f.name, f.served);
        }
        assert!(FUNCTIONS.iter().any(|f| f.served == Served::Library));
    }
}
