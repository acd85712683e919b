//! Frames between the CAN hub (`mcemu_can::WireFrame`) and the CANopen nodes
//! (`mcemu_canopen::CanFrame`): the one conversion every node binding uses.

use mcemu_can::WireFrame;
use mcemu_canopen::CanFrame;

/// A hub frame as a CANopen node sees it.
pub(crate) enum Incoming {
    Frame(CanFrame),
    /// A CAN error frame (counted by the nodes).
    Error,
    /// Not CANopen traffic (29-bit identifiers) or not a frame the node can hold.
    Other,
}

pub(crate) fn from_wire(f: &WireFrame) -> Incoming {
    if f.is_error() {
        return Incoming::Error;
    }
    // CiA 301 uses base frames only; a 29-bit frame is someone else's traffic.
    if f.is_extended() {
        return Incoming::Other;
    }
    let id = f.id().raw() as u16;
    let frame = if f.is_remote() {
        CanFrame::remote(id, f.dlc())
    } else {
        CanFrame::new(id, f.data())
    };
    frame.map_or(Incoming::Other, Incoming::Frame)
}

/// A node's frame as the hub carries it (`None`: not a frame a CAN bus can carry).
pub(crate) fn to_wire(frame: &CanFrame) -> Option<WireFrame> {
    let wire = if frame.is_rtr() {
        mcemu_can::CanId::standard(frame.id())
            .and_then(|id| WireFrame::remote(id, frame.len() as u8))
    } else {
        WireFrame::standard(frame.id(), frame.data())
    };
    wire.ok()
}
