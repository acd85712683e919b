//! Classic CAN frames with 11-bit identifiers (CiA 301 uses the base frame format only).

use std::fmt;

/// Largest 11-bit identifier.
pub const MAX_ID: u16 = 0x7FF;

/// A classic CAN base frame: 11-bit identifier, up to 8 data bytes, RTR flag.
///
/// An RTR frame carries no data but a requested length (its DLC), which [`CanFrame::len`]
/// reports.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct CanFrame {
    id: u16,
    len: u8,
    rtr: bool,
    data: [u8; 8],
}

/// A frame that cannot be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FrameError {
    #[error("CAN identifier {0:#x} does not fit in 11 bits")]
    IdTooLarge(u32),
    #[error("a classic CAN frame carries at most 8 data bytes, not {0}")]
    TooLong(usize),
}

impl CanFrame {
    /// A data frame. Refuses identifiers above 0x7FF and more than 8 bytes.
    pub fn new(id: u16, data: &[u8]) -> Result<CanFrame, FrameError> {
        if id > MAX_ID {
            return Err(FrameError::IdTooLarge(u32::from(id)));
        }
        let mut bytes = [0; 8];
        bytes
            .get_mut(..data.len())
            .ok_or(FrameError::TooLong(data.len()))?
            .copy_from_slice(data);
        Ok(CanFrame {
            id,
            len: data.len() as u8,
            rtr: false,
            data: bytes,
        })
    }

    /// A remote transmission request for `len` bytes (0–8).
    pub fn remote(id: u16, len: u8) -> Result<CanFrame, FrameError> {
        if id > MAX_ID {
            return Err(FrameError::IdTooLarge(u32::from(id)));
        }
        if len > 8 {
            return Err(FrameError::TooLong(usize::from(len)));
        }
        Ok(CanFrame {
            id,
            len,
            rtr: true,
            data: [0; 8],
        })
    }

    /// An 8-byte data frame from parts the stack has already checked (identifier masked).
    pub(crate) const fn full(id: u16, data: [u8; 8]) -> CanFrame {
        CanFrame {
            id: id & MAX_ID,
            len: 8,
            rtr: false,
            data,
        }
    }

    /// A data frame of the first `len` bytes of `data` (identifier masked, length clamped).
    pub(crate) fn short(id: u16, data: [u8; 8], len: usize) -> CanFrame {
        CanFrame {
            id: id & MAX_ID,
            len: len.min(8) as u8,
            rtr: false,
            data,
        }
    }

    pub const fn id(&self) -> u16 {
        self.id
    }

    /// The data bytes (empty for an RTR frame).
    pub fn data(&self) -> &[u8] {
        if self.rtr {
            &[]
        } else {
            self.data.get(..usize::from(self.len)).unwrap_or(&[])
        }
    }

    /// The data length code: the data length, or the requested length of an RTR frame.
    pub const fn len(&self) -> usize {
        self.len as usize
    }

    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    pub const fn is_rtr(&self) -> bool {
        self.rtr
    }

    /// All eight data bytes, zero beyond the length (what SDO parsing reads).
    pub(crate) const fn padded(&self) -> [u8; 8] {
        self.data
    }
}

/// `candump -L` notation: `701#7F`, `701#R`.
impl fmt::Display for CanFrame {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:03X}#", self.id)?;
        if self.rtr {
            return if self.len == 0 {
                f.write_str("R")
            } else {
                write!(f, "R{}", self.len)
            };
        }
        self.data().iter().try_for_each(|b| write!(f, "{b:02X}"))
    }
}

impl fmt::Debug for CanFrame {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn construction_refuses_long_data_and_wide_ids() {
        assert_eq!(CanFrame::new(0x123, &[0; 9]), Err(FrameError::TooLong(9)));
        assert_eq!(
            CanFrame::new(0x800, &[]),
            Err(FrameError::IdTooLarge(0x800))
        );
        assert_eq!(CanFrame::remote(0x701, 9), Err(FrameError::TooLong(9)));
        let f = CanFrame::new(0x701, &[0x7F]).unwrap();
        assert_eq!(
            (f.id(), f.data(), f.len(), f.is_rtr()),
            (0x701, &[0x7F][..], 1, false)
        );
        assert_eq!(f.to_string(), "701#7F");
        let r = CanFrame::remote(0x701, 1).unwrap();
        assert_eq!((r.data(), r.len(), r.is_rtr()), (&[][..], 1, true));
        assert_eq!(r.to_string(), "701#R1");
    }
}
