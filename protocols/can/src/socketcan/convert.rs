//! `WireFrame` ⇄ `socketcan::CanFrame`, without a socket.

use socketcan::{CanErrorFrame, CanFrame, EmbeddedFrame, ExtendedId, Frame, Id, StandardId};

use crate::frame::{CanId, FrameError, FrameKind, WireFrame};

fn id(id: CanId) -> Option<Id> {
    if id.is_extended() {
        ExtendedId::new(id.raw()).map(Id::Extended)
    } else {
        u16::try_from(id.raw())
            .ok()
            .and_then(StandardId::new)
            .map(Id::Standard)
    }
}

/// The socket's frame for `frame`. `None` cannot happen for a valid `WireFrame` (its
/// constructors enforce what SocketCAN's do); it is there so that no conversion can panic.
pub fn to_socketcan(frame: &WireFrame) -> Option<CanFrame> {
    match frame.kind() {
        FrameKind::Data => CanFrame::new(id(frame.id())?, frame.data()),
        FrameKind::Remote => CanFrame::new_remote(id(frame.id())?, usize::from(frame.dlc())),
        FrameKind::Error => CanErrorFrame::new_error(frame.error_class()?, frame.data())
            .ok()
            .map(CanFrame::Error),
    }
}

/// The `WireFrame` of a frame read from the socket.
pub fn from_socketcan(frame: &CanFrame) -> Result<WireFrame, FrameError> {
    let len = u8::try_from(frame.dlc()).unwrap_or(u8::MAX);
    WireFrame::from_socketcan(frame.id_word(), len, frame.data())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn frames_round_trip_through_the_socketcan_layout() {
        for frame in [
            WireFrame::standard(0x7FF, &[1, 2, 3]).unwrap(),
            WireFrame::standard(0, &[]).unwrap(),
            WireFrame::extended(0x123, &[0xFF; 8]).unwrap(),
            WireFrame::remote(CanId::standard(0x181).unwrap(), 8).unwrap(),
            WireFrame::remote(CanId::extended(0x1FFF_FFFF).unwrap(), 0).unwrap(),
            WireFrame::error(0x4, &[0, 0x10]).unwrap(),
        ] {
            let native = to_socketcan(&frame).unwrap();
            assert_eq!(native.id_word(), frame.socketcan_id(), "{frame}");
            assert_eq!(from_socketcan(&native).unwrap(), frame);
        }
    }
}
