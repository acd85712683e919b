//! The exported `NMC_*` functions, one file per family, each a thin wrapper that checks its
//! pointers, encodes its in arguments as its row of `mcemu_nmc::table` says, and decodes the
//! out arguments of the reply. The pointer helpers here are the only places that touch caller
//! memory.

#![allow(non_snake_case)]
// `long` is 64 bits here and 32 on other targets: the conversions are not useless there.
#![allow(clippy::useless_conversion)]

use std::ffi::{c_char, c_short, CStr};

use mcemu_nmc::errors::{RTN_BAD_PAYLOAD, RTN_INVALID_HANDLE, RTN_NULL_POINTER};
use mcemu_nmc::handle::Handle;
use mcemu_nmc::payload::{PayloadError, Reader, Writer};
use mcemu_nmc::table::Function;

use crate::connection::CallError;
use crate::last_error::report;
use crate::registry;

pub mod aliases;
// The axis-level additions (packed status and moves, E-stop inputs, watchdog).
pub mod analog;
pub mod ax_types;
pub mod axis;
pub mod axis_config;
pub mod axis_ext;
pub mod closed_loop;
pub mod crd;
pub mod crd_buf_io;
pub mod crd_frames;
pub mod crd_lookahead;
pub mod crd_types;
pub mod dev_services;
pub mod device;
pub mod ecat;
pub mod extras;
pub mod follow;
pub mod home;
pub mod io;
pub mod io_ext;
pub mod io_extras;
pub mod io_types;
pub mod laser;
pub mod library;
pub mod motion;
pub mod sys;
pub mod types;
// The synchronised-motion families (gear, PT/PVT, capture, compare, gantry and handwheel,
// compensation) and their arrays and structs.
mod arrays;
pub mod capture;
pub mod compare;
pub mod compensation;
pub mod gang;
pub mod gear;
pub mod pt;
pub mod sync_types;
pub mod user_para;

pub use types::HAND;

/// `RTN_NULL_POINTER` naming argument `name` of `function`.
pub(crate) fn null(function: &Function, name: &str) -> CallError {
    CallError::new(
        RTN_NULL_POINTER,
        format!("{}: {name} is NULL", function.name),
    )
}

/// Fail with `RTN_NULL_POINTER` unless every listed pointer is non-null.
macro_rules! require {
    ($f:expr, $($p:ident),+) => {
        $(
            if $p.is_null() {
                return $crate::last_error::report(Err($crate::ffi::null(&$f, stringify!($p))));
            }
        )+
    };
}
pub(crate) use require;

/// Write `v` through `p`. `p` must be non-null (checked by [`require!`] before the call) and
/// point to a writable `T`, as the manual's prototype asks of the caller.
pub(crate) fn store<T>(p: *mut T, v: T) {
    if !p.is_null() {
        // SAFETY: non-null, checked above; that it points to a writable T is the C caller's
        // contract (the prototype declares it). Unaligned writes tolerate packed callers.
        unsafe { p.write_unaligned(v) }
    }
}

/// Read the `T` at `p` (non-null, checked by [`require!`]; a readable `T` by the C contract).
pub(crate) fn load<T: Default>(p: *const T) -> T {
    if p.is_null() {
        return T::default();
    }
    // SAFETY: non-null, checked above; that it points to a readable, initialised T is the C
    // caller's contract.
    unsafe { p.read_unaligned() }
}

/// The bytes of the C string at `p` (non-null, checked by [`require!`]), at most `max`.
pub(crate) fn c_string(p: *const c_char, max: usize) -> Vec<u8> {
    if p.is_null() {
        return Vec::new();
    }
    // SAFETY: non-null, checked above; a NUL-terminated string by the C contract.
    let s = unsafe { CStr::from_ptr(p) };
    let b = s.to_bytes();
    b.get(..max).unwrap_or(b).to_vec()
}

/// Copy `s` and a NUL into the caller's buffer `p` of at least `capacity` bytes (cut to fit).
pub(crate) fn put_c_string(p: *mut c_char, capacity: usize, s: &str) {
    if p.is_null() || capacity == 0 {
        return;
    }
    let b = s.as_bytes();
    let n = b.len().min(capacity - 1);
    // SAFETY: non-null, checked above; the caller's buffer holds `capacity` bytes (the
    // documented size for this function), and n + 1 ≤ capacity.
    unsafe {
        std::ptr::copy_nonoverlapping(b.as_ptr().cast::<c_char>(), p, n);
        p.add(n).write(0);
    }
}

/// Call served function `f` on the device of `handle`: the handle first, then what `input`
/// writes; `output` reads the reply's out arguments. The return code.
pub(crate) fn served(
    f: &Function,
    handle: HAND,
    input: impl FnOnce(&mut Writer),
    output: impl FnOnce(&mut Reader<'_>) -> Result<(), PayloadError>,
) -> c_short {
    report(call(f, handle, input, output))
}

pub(crate) fn call(
    f: &Function,
    handle: HAND,
    input: impl FnOnce(&mut Writer),
    output: impl FnOnce(&mut Reader<'_>) -> Result<(), PayloadError>,
) -> Result<(), CallError> {
    let result = call_device(f, handle, input, output);
    if crate::cmd_debug::on() {
        let code = result.as_ref().map_or_else(|e| e.code, |()| 0);
        crate::cmd_debug::write_line(&format!("{}({handle:#06x}) = {code}", f.name), false);
    }
    result
}

fn call_device(
    f: &Function,
    handle: HAND,
    input: impl FnOnce(&mut Writer),
    output: impl FnOnce(&mut Reader<'_>) -> Result<(), PayloadError>,
) -> Result<(), CallError> {
    let invalid = || {
        CallError::new(
            RTN_INVALID_HANDLE,
            format!("{}: handle {handle:#06x} is not open", f.name),
        )
    };
    let h = Handle::decode(handle).ok_or_else(invalid)?;
    let conn = registry::get(h.slot).ok_or_else(invalid)?;
    let mut w = Writer::new();
    w.u16(handle);
    input(&mut w);
    let reply = conn.call(f.id, &w.bytes)?;
    let mut r = Reader::new(&reply);
    output(&mut r)
        .and_then(|()| r.finish())
        .map_err(|e| CallError::new(RTN_BAD_PAYLOAD, format!("{}: reply: {e}", f.name)))
}

/// A function of one handle and nothing else (`NMC_MtClrError(axisHandle)`).
macro_rules! action {
    ($name:ident, $row:expr) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND) -> c_short {
            $crate::ffi::served(&$row, handle, |_| {}, |_| Ok(()))
        }
    };
}
pub(crate) use action;

/// A handle and one value in (`NMC_MtSetVel(axisHandle, vel)`).
macro_rules! setter {
    ($name:ident, $row:expr, $ty:ty, $put:ident) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, value: $ty) -> c_short {
            $crate::ffi::served(
                &$row,
                handle,
                |w| {
                    w.$put(value.into());
                },
                |_| Ok(()),
            )
        }
    };
}
pub(crate) use setter;

/// A handle in, one value out through a pointer (`NMC_MtGetSts(axisHandle, &sts)`); `$conv`
/// turns the wire value into the C one.
macro_rules! getter {
    ($name:ident, $row:expr, $ty:ty, $get:ident, $conv:expr) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, out: *mut $ty) -> c_short {
            $crate::ffi::require!($row, out);
            $crate::ffi::served(
                &$row,
                handle,
                |_| {},
                |r| {
                    $crate::ffi::store(out, $conv(r.$get()?));
                    Ok(())
                },
            )
        }
    };
}
pub(crate) use getter;

/// A handle and one of the manual's structs in (`NMC_MtSetPtpPara(axisHandle, &para)`): `$c` is
/// the C struct, `$wire` its wire form (`From<$c>` plus `write`).
macro_rules! struct_setter {
    ($name:ident, $row:expr, $c:ty, $wire:ty) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, para: *mut $c) -> c_short {
            $crate::ffi::require!($row, para);
            let p = <$wire>::from($crate::ffi::load(para.cast_const()));
            $crate::ffi::served(&$row, handle, |w| p.write(w), |_| Ok(()))
        }
    };
}
pub(crate) use struct_setter;

/// A handle in, one of the manual's structs out (`NMC_MtGetPtpPara(axisHandle, &para)`): the
/// wire form's `read`, then `$c::from`.
macro_rules! struct_getter {
    ($name:ident, $row:expr, $c:ty, $wire:ty) => {
        #[no_mangle]
        pub extern "C" fn $name(handle: HAND, para: *mut $c) -> c_short {
            $crate::ffi::require!($row, para);
            $crate::ffi::served(
                &$row,
                handle,
                |_| {},
                |r| {
                    $crate::ffi::store(para, <$c>::from(<$wire>::read(r)?));
                    Ok(())
                },
            )
        }
    };
}
pub(crate) use struct_getter;

/// The `n` values of the caller's array at `p` (non-null, checked by [`require!`]).
pub(crate) fn load_array<T: Copy + Default>(p: *const T, n: usize) -> Vec<T> {
    if p.is_null() {
        return Vec::new();
    }
    // SAFETY: non-null, checked above; that the array holds `n` readable, initialised `T`s is
    // the C caller's contract (the manual's length for this argument: the coordinate system's
    // coordinates, a mask's bits or `count`).
    (0..n)
        .map(|i| unsafe { p.add(i).read_unaligned() })
        .collect()
}

/// Write `values` to the caller's array at `p` (non-null, checked by [`require!`]; room for
/// `values.len()` elements by the C contract).
pub(crate) fn store_array<T: Copy>(p: *mut T, values: &[T]) {
    if p.is_null() {
        return;
    }
    for (i, v) in values.iter().enumerate() {
        // SAFETY: non-null, checked above; the caller's array has room for the count it asked
        // for, and `values` is never longer than that count.
        unsafe { p.add(i).write_unaligned(*v) }
    }
}

/// A reply's array: u16 count, then `count` elements read by `one` (at most `max` kept).
pub(crate) fn reply_list<T>(
    r: &mut Reader<'_>,
    max: usize,
    mut one: impl FnMut(&mut Reader<'_>) -> Result<T, PayloadError>,
) -> Result<Vec<T>, PayloadError> {
    let n = usize::from(r.u16()?);
    let mut values = Vec::with_capacity(n.min(max));
    for _ in 0..n {
        let v = one(r)?;
        if values.len() < max {
            values.push(v);
        }
    }
    Ok(values)
}
