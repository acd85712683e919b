//! SocketCAN transport (Linux): bridges a CAN interface (`vcan0`, `can0`) to a [`crate::Hub`]
//! both ways, classic frames only (CAN FD off).
//!
//! - [`open`]: opens the interface, or says exactly why not, naming it: no CAN in this kernel,
//!   no such interface, not a CAN interface, interface down.
//! - [`SocketCanBridge`]: frames the hub's endpoints send go out on the interface; frames read
//!   from it go to the endpoints. Error frames are received (all classes), counted and passed
//!   to the hub; the hub's error frames are not written out. When the interface goes down or
//!   disappears the bridge reports it ([`LinkState::Down`]), drops (and counts) outgoing frames,
//!   and reopens the interface when it is back.
//! - [`convert`]: `WireFrame` ⇄ the `socketcan` crate's `CanFrame`, pure.

mod bridge;
pub mod convert;
mod open;

pub use bridge::{LinkState, SocketCanBridge, SocketCanConfig, SocketCanStats};
pub use open::{open, SocketCanError};
