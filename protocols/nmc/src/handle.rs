//! `HAND` values (16 bits, digest 001 §1.2; the encoding is mcemu's, §8 item 2):
//!
//! ```text
//! bits 15-14 kind   1 device, 2 axis, 3 coordinate system
//! bits 13-8  slot   the library's device slot (0-63): which connection
//! bits  7-0  item   the axis number (0-255; EtherCAT axes from 16), the coordinate system
//!                   number (0-1); 0 for a device
//! ```
//!
//! The server sees the whole value but uses only kind and item; the slot is the library's.
//! Handle 0 is never valid, so a zero-initialised `HAND` is refused.

/// What a handle names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HandleKind {
    Device = 1,
    Axis = 2,
    /// A coordinate system (`NMC_CrdOpenEx`, digest 001 §2.2).
    Crd = 3,
}

/// The parts of a handle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Handle {
    pub kind: HandleKind,
    pub slot: u8,
    pub item: u8,
}

/// Device slots the library has (6 bits).
pub const SLOTS: usize = 64;

impl Handle {
    pub fn device(slot: u8) -> Handle {
        Handle {
            kind: HandleKind::Device,
            slot,
            item: 0,
        }
    }

    pub fn axis(slot: u8, item: u8) -> Handle {
        Handle {
            kind: HandleKind::Axis,
            slot,
            item,
        }
    }

    pub fn crd(slot: u8, item: u8) -> Handle {
        Handle {
            kind: HandleKind::Crd,
            slot,
            item,
        }
    }

    pub fn encode(self) -> u16 {
        ((self.kind as u16) << 14) | (u16::from(self.slot & 0x3F) << 8) | u16::from(self.item)
    }

    /// The handle `h` is, if its kind is known.
    pub fn decode(h: u16) -> Option<Handle> {
        let kind = match h >> 14 {
            1 => HandleKind::Device,
            2 => HandleKind::Axis,
            3 => HandleKind::Crd,
            _ => return None,
        };
        Some(Handle {
            kind,
            slot: ((h >> 8) & 0x3F) as u8,
            item: (h & 0xFF) as u8,
        })
    }

    /// The same object through library slot `slot`.
    pub fn in_slot(self, slot: u8) -> Handle {
        Handle { slot, ..self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn handles_round_trip_and_zero_is_invalid() {
        for h in [
            Handle::device(63),
            Handle::axis(5, 17),
            Handle::axis(0, 0),
            Handle::crd(2, 1),
        ] {
            assert_eq!(Handle::decode(h.encode()), Some(h));
            assert_ne!(h.encode(), 0);
        }
        assert_eq!(Handle::decode(0), None);
        assert_eq!(Handle::axis(1, 2).encode(), 0x8102);
    }
}
