//! A classic CAN frame as it travels on a bus (CAN 2.0A/B; CAN FD is off): an 11- or 29-bit
//! identifier, data, remote (RTR) or error frame, 0–8 data bytes.
//!
//! Constructors validate and never panic; a `WireFrame` that exists is always sendable. Its
//! `Display` is can-utils' compact form (`123#DEADBEEF`, `12345678#R4`, `20000004#…`), the
//! one `candump -L` writes and `cansend` reads; `FromStr` reads the same form back.

use std::fmt;
use std::str::FromStr;

/// Largest data length of a classic CAN frame.
pub const MAX_DATA: usize = 8;
/// Largest 11-bit (standard, CAN 2.0A) identifier.
pub const SFF_MAX: u32 = 0x7FF;
/// Largest 29-bit (extended, CAN 2.0B) identifier; also the mask of SocketCAN's error class.
pub const EFF_MAX: u32 = 0x1FFF_FFFF;

/// SocketCAN's identifier-word flags (linux/can.h): extended frame format …
pub const EFF_FLAG: u32 = 0x8000_0000;
/// … remote transmission request …
pub const RTR_FLAG: u32 = 0x4000_0000;
/// … and error frame (`CAN_ERR_FLAG`).
pub const ERR_FLAG: u32 = 0x2000_0000;

/// Why a frame or identifier was refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FrameError {
    #[error("CAN id {id:#X} does not fit {bits} bits")]
    IdTooLarge { id: u32, bits: u8 },
    #[error("a classic CAN frame carries at most 8 data bytes, not {len}")]
    TooMuchData { len: usize },
    #[error("a classic CAN DLC is 0..=8, not {dlc}")]
    DlcTooLarge { dlc: u8 },
    #[error("error class {class:#X} does not fit 29 bits")]
    ErrorClassTooLarge { class: u32 },
    #[error("`{text}` is not a CAN frame in candump form: {reason}")]
    Syntax { text: String, reason: &'static str },
}

/// An 11-bit (standard) or 29-bit (extended) CAN identifier.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct CanId {
    raw: u32,
    extended: bool,
}

impl CanId {
    /// An 11-bit identifier, `0..=0x7FF`.
    pub fn standard(id: u16) -> Result<Self, FrameError> {
        let raw = u32::from(id);
        if raw > SFF_MAX {
            return Err(FrameError::IdTooLarge { id: raw, bits: 11 });
        }
        Ok(Self {
            raw,
            extended: false,
        })
    }

    /// A 29-bit identifier, `0..=0x1FFF_FFFF` (an extended id may be small: `0x00000123` is
    /// not `0x123`).
    pub fn extended(id: u32) -> Result<Self, FrameError> {
        if id > EFF_MAX {
            return Err(FrameError::IdTooLarge { id, bits: 29 });
        }
        Ok(Self {
            raw: id,
            extended: true,
        })
    }

    /// The identifier without format flags.
    pub fn raw(self) -> u32 {
        self.raw
    }

    pub fn is_extended(self) -> bool {
        self.extended
    }
}

impl fmt::Display for CanId {
    /// 3 hex digits for a standard id, 8 for an extended one (can-utils, socketcand).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.extended {
            write!(f, "{:08X}", self.raw)
        } else {
            write!(f, "{:03X}", self.raw)
        }
    }
}

/// What a frame is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FrameKind {
    Data,
    /// A remote transmission request: no data, a requested length (DLC).
    Remote,
    /// A SocketCAN error frame: a controller's report (error class in the id, details in the
    /// 8 data bytes, linux/can/error.h), not something a node transmits.
    Error,
}

/// A classic CAN frame. Invariants (kept by the constructors): id fits its format, `len <= 8`,
/// data bytes past `len` are zero, a remote frame has no data bytes, an error frame has 8.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct WireFrame {
    id: CanId,
    kind: FrameKind,
    len: u8,
    data: [u8; MAX_DATA],
}

impl WireFrame {
    /// A data frame.
    pub fn new(id: CanId, data: &[u8]) -> Result<Self, FrameError> {
        let mut bytes = [0; MAX_DATA];
        bytes
            .get_mut(..data.len())
            .ok_or(FrameError::TooMuchData { len: data.len() })?
            .copy_from_slice(data);
        Ok(Self {
            id,
            kind: FrameKind::Data,
            len: data.len() as u8, // <= 8, checked above
            data: bytes,
        })
    }

    /// A data frame with an 11-bit id.
    pub fn standard(id: u16, data: &[u8]) -> Result<Self, FrameError> {
        Self::new(CanId::standard(id)?, data)
    }

    /// A data frame with a 29-bit id.
    pub fn extended(id: u32, data: &[u8]) -> Result<Self, FrameError> {
        Self::new(CanId::extended(id)?, data)
    }

    /// A remote frame requesting `dlc` bytes.
    pub fn remote(id: CanId, dlc: u8) -> Result<Self, FrameError> {
        if usize::from(dlc) > MAX_DATA {
            return Err(FrameError::DlcTooLarge { dlc });
        }
        Ok(Self {
            id,
            kind: FrameKind::Remote,
            len: dlc,
            data: [0; MAX_DATA],
        })
    }

    /// An error frame: `class` is the `CAN_ERR_*` class bits, `data` the details (padded with
    /// zeros to 8 bytes, as SocketCAN does).
    pub fn error(class: u32, data: &[u8]) -> Result<Self, FrameError> {
        if class > EFF_MAX {
            return Err(FrameError::ErrorClassTooLarge { class });
        }
        let mut frame = Self::new(
            CanId {
                raw: class,
                extended: false,
            },
            data,
        )?;
        frame.kind = FrameKind::Error;
        frame.len = MAX_DATA as u8;
        Ok(frame)
    }

    /// From SocketCAN's layout: the id word with its `EFF`/`RTR`/`ERR` flags, the length
    /// (the DLC of a remote frame) and the data bytes (ignored for a remote frame).
    pub fn from_socketcan(id_word: u32, len: u8, data: &[u8]) -> Result<Self, FrameError> {
        if id_word & ERR_FLAG != 0 {
            return Self::error(
                id_word & EFF_MAX,
                data.get(..usize::from(len)).unwrap_or(data),
            );
        }
        let id = if id_word & EFF_FLAG != 0 {
            CanId::extended(id_word & EFF_MAX)?
        } else {
            let raw = id_word & EFF_MAX;
            if raw > SFF_MAX {
                return Err(FrameError::IdTooLarge { id: raw, bits: 11 });
            }
            CanId {
                raw,
                extended: false,
            }
        };
        if id_word & RTR_FLAG != 0 {
            return Self::remote(id, len);
        }
        let data = data
            .get(..usize::from(len))
            .ok_or(FrameError::TooMuchData {
                len: usize::from(len),
            })?;
        Self::new(id, data)
    }

    /// SocketCAN's id word: the id with `EFF`, `RTR` or `ERR` flags.
    pub fn socketcan_id(&self) -> u32 {
        match self.kind {
            FrameKind::Error => ERR_FLAG | self.id.raw,
            FrameKind::Remote => self.format_flag() | RTR_FLAG | self.id.raw,
            FrameKind::Data => self.format_flag() | self.id.raw,
        }
    }

    fn format_flag(&self) -> u32 {
        if self.id.extended {
            EFF_FLAG
        } else {
            0
        }
    }

    /// The identifier. For an error frame: its error class, as a 29-bit value marked standard
    /// (see [`WireFrame::error_class`]).
    pub fn id(&self) -> CanId {
        self.id
    }

    pub fn kind(&self) -> FrameKind {
        self.kind
    }

    pub fn is_extended(&self) -> bool {
        self.kind != FrameKind::Error && self.id.extended
    }

    pub fn is_remote(&self) -> bool {
        self.kind == FrameKind::Remote
    }

    pub fn is_error(&self) -> bool {
        self.kind == FrameKind::Error
    }

    /// The `CAN_ERR_*` class bits of an error frame.
    pub fn error_class(&self) -> Option<u32> {
        (self.kind == FrameKind::Error).then_some(self.id.raw)
    }

    /// The DLC: the data length, or the requested length of a remote frame.
    pub fn dlc(&self) -> u8 {
        self.len
    }

    /// The data bytes (none for a remote frame).
    pub fn data(&self) -> &[u8] {
        match self.kind {
            FrameKind::Remote => &[],
            _ => self.data.get(..usize::from(self.len)).unwrap_or(&[]),
        }
    }
}

impl fmt::Display for WireFrame {
    /// can-utils' compact form (lib.c): `123#DEADBEEF`, `12345678#`, `123#R`, `123#R4`, and
    /// for an error frame the id word with `CAN_ERR_FLAG` in 8 digits and the 8 data bytes.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind {
            FrameKind::Error => write!(f, "{:08X}#", ERR_FLAG | self.id.raw)?,
            _ => write!(f, "{}#", self.id)?,
        }
        if self.kind == FrameKind::Remote {
            f.write_str("R")?;
            if self.len > 0 {
                write!(f, "{}", self.len)?;
            }
            return Ok(());
        }
        for byte in self.data() {
            write!(f, "{byte:02X}")?;
        }
        Ok(())
    }
}

impl fmt::Debug for WireFrame {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "WireFrame({self})")
    }
}

impl FromStr for WireFrame {
    type Err = FrameError;

    /// The classic part of can-utils' `parse_canframe`: 3 id digits (standard) or 8 (extended,
    /// or an error frame when `CAN_ERR_FLAG` is set), `#`, then `R[dlc]` or up to 8 bytes as
    /// hex pairs with optional `.` separators. CAN FD (`##`) and raw DLCs (`_`) are refused.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let syntax = |reason| FrameError::Syntax {
            text: text.chars().take(64).collect(),
            reason,
        };
        let (id_text, rest) = text.split_once('#').ok_or(syntax("no `#`"))?;
        let id_word = parse_hex_u32(id_text).ok_or(syntax("the id is not hex"))?;
        let id = match id_text.len() {
            3 => CanId {
                raw: id_word & SFF_MAX,
                extended: false,
            }
            .checked(id_word)?,
            8 if id_word & ERR_FLAG != 0 => {
                let payload = parse_data(rest).ok_or(syntax("bad data bytes"))?;
                return Self::error(id_word & EFF_MAX, &payload.bytes[..payload.len]);
            }
            8 => CanId::extended(id_word)?,
            _ => return Err(syntax("the id takes 3 or 8 hex digits")),
        };
        if rest.starts_with('#') {
            return Err(syntax("CAN FD frames are not supported (CAN FD is off)"));
        }
        if let Some(dlc) = rest.strip_prefix(['R', 'r']) {
            let dlc = match dlc.as_bytes() {
                [] => 0,
                [digit] if digit.is_ascii_digit() => digit - b'0',
                _ => return Err(syntax("a remote frame takes `R` and an optional DLC 0-8")),
            };
            return Self::remote(id, dlc);
        }
        let payload = parse_data(rest).ok_or(syntax("bad data bytes"))?;
        Self::new(id, &payload.bytes[..payload.len])
    }
}

impl CanId {
    /// `self` if it is the whole of `word` (nothing masked away).
    fn checked(self, word: u32) -> Result<Self, FrameError> {
        if word == self.raw {
            Ok(self)
        } else {
            Err(FrameError::IdTooLarge { id: word, bits: 11 })
        }
    }
}

fn parse_hex_u32(text: &str) -> Option<u32> {
    if text.is_empty() || text.len() > 8 || !text.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    u32::from_str_radix(text, 16).ok()
}

struct Payload {
    bytes: [u8; MAX_DATA],
    len: usize,
}

/// Hex pairs with optional `.` between bytes, at most 8 bytes.
fn parse_data(text: &str) -> Option<Payload> {
    let mut payload = Payload {
        bytes: [0; MAX_DATA],
        len: 0,
    };
    let mut digits = text.bytes().filter(|&b| b != b'.');
    loop {
        let Some(high) = digits.next() else {
            return Some(payload);
        };
        let low = digits.next()?;
        let byte = (hex_value(high)? << 4) | hex_value(low)?;
        *payload.bytes.get_mut(payload.len)? = byte;
        payload.len += 1;
    }
}

fn hex_value(digit: u8) -> Option<u8> {
    char::from(digit).to_digit(16).map(|v| v as u8)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn constructors_refuse_bad_input() {
        assert!(CanId::standard(0x800).is_err());
        assert!(CanId::extended(0x2000_0000).is_err());
        assert_eq!(
            WireFrame::standard(1, &[0; 9]),
            Err(FrameError::TooMuchData { len: 9 })
        );
        assert!(WireFrame::remote(CanId::standard(1).unwrap(), 9).is_err());
        assert!(WireFrame::error(0x2000_0000, &[]).is_err());
        assert!(WireFrame::from_socketcan(0x800, 0, &[]).is_err());
        assert!(WireFrame::from_socketcan(0x123, 9, &[0; 8]).is_err());
    }

    #[test]
    fn candump_form() {
        let cases = [
            (
                WireFrame::standard(0x123, &[0xDE, 0xAD, 0xBE, 0xEF]).unwrap(),
                "123#DEADBEEF",
            ),
            (WireFrame::standard(0, &[]).unwrap(), "000#"),
            (WireFrame::extended(0x123, &[1]).unwrap(), "00000123#01"),
            (
                WireFrame::remote(CanId::standard(0x7FF).unwrap(), 0).unwrap(),
                "7FF#R",
            ),
            (
                WireFrame::remote(CanId::extended(0x1ABCDEF0).unwrap(), 4).unwrap(),
                "1ABCDEF0#R4",
            ),
            (
                WireFrame::error(0x4, &[0, 0x10]).unwrap(),
                "20000004#0010000000000000",
            ),
        ];
        for (frame, text) in cases {
            assert_eq!(frame.to_string(), text);
            assert_eq!(text.parse::<WireFrame>().unwrap(), frame, "{text}");
        }
        assert_eq!(
            "123#DE.AD".parse::<WireFrame>().unwrap().data(),
            [0xDE, 0xAD]
        );
        for bad in [
            "123",
            "12#",
            "1234#",
            "123#D",
            "123#0102030405060708090A",
            "123##0",
            "123#R9",
            "80000000#",
            "G23#",
            "FFF#",
        ] {
            assert!(bad.parse::<WireFrame>().is_err(), "{bad}");
        }
    }

    #[test]
    fn socketcan_layout_round_trips() {
        for frame in [
            WireFrame::standard(0x7FF, &[1, 2, 3]).unwrap(),
            WireFrame::extended(0x1FFF_FFFF, &[0; 8]).unwrap(),
            WireFrame::remote(CanId::extended(5).unwrap(), 8).unwrap(),
            WireFrame::error(0x20, &[1, 2, 3, 4, 5, 6, 7, 8]).unwrap(),
        ] {
            let back = WireFrame::from_socketcan(frame.socketcan_id(), frame.dlc(), frame.data());
            assert_eq!(back.unwrap(), frame);
        }
    }
}
