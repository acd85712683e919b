//! The open devices, by library slot (the `slot` bits of a handle, `mcemu_nmc::handle`).

use std::sync::{Arc, Mutex, PoisonError};

use mcemu_nmc::handle::SLOTS;

use crate::connection::Connection;

static DEVICES: Mutex<[Option<Arc<Connection>>; SLOTS]> = Mutex::new([const { None }; SLOTS]);

/// Keep `c`; its slot, `None` when all 64 are taken.
pub fn insert(c: Connection) -> Option<u8> {
    let mut d = DEVICES.lock().unwrap_or_else(PoisonError::into_inner);
    let slot = d.iter().position(Option::is_none)?;
    *d.get_mut(slot)? = Some(Arc::new(c));
    u8::try_from(slot).ok()
}

pub fn get(slot: u8) -> Option<Arc<Connection>> {
    let d = DEVICES.lock().unwrap_or_else(PoisonError::into_inner);
    d.get(usize::from(slot)).cloned().flatten()
}

/// Forget slot `slot`; whether it was open. Calls in flight finish on their own reference.
pub fn remove(slot: u8) -> bool {
    let mut d = DEVICES.lock().unwrap_or_else(PoisonError::into_inner);
    d.get_mut(usize::from(slot))
        .and_then(Option::take)
        .is_some()
}

/// The open slots, in order (`NMC_CrdStartExeTimeCalc` asks every open device).
pub fn open_slots() -> Vec<u8> {
    let d = DEVICES.lock().unwrap_or_else(PoisonError::into_inner);
    (0..SLOTS)
        .filter(|s| d.get(*s).is_some_and(Option::is_some))
        .filter_map(|s| u8::try_from(s).ok())
        .collect()
}
