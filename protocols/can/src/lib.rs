//! mcemu's CAN bus layer, which knows nothing of CANopen (ARCHITECTURE §5: the CANopen node
//! talks to it through a binding that converts frames).
//!
//! - [`WireFrame`]: a classic CAN frame (11/29-bit id, data, RTR, error), candump text form.
//! - [`Hub`]: the in-process bus. Endpoints attach ([`Hub::attach`]) and get a sender and a
//!   receiver; bounded queues, counted drops, [`BusCounters`].
//! - [`timing`] and [`model`]: the optional bit-rate model (bit times with stuffing,
//!   arbitration by id, bus load), sans-IO on a caller-supplied `now`.
//! - [`log`]: a `candump -L` log of every frame, written off the bus's path.
//! - [`socketcand`]: the socketcand ASCII protocol: a sans-IO codec and session, and a tokio
//!   TCP server that serves hubs by bus name (python-can's `socketcand` interface).
//! - `socketcan` (Linux): bridges a SocketCAN interface (`vcan0`, `can0`) to a hub.

pub mod clock;
pub mod counters;
pub mod endpoint;
pub mod frame;
pub mod hub;
pub mod log;
pub mod model;
#[cfg(target_os = "linux")]
pub mod socketcan;
pub mod socketcand;
pub mod timing;

pub use clock::{Clock, Timestamp};
pub use counters::{BusCounters, EndpointCounters};
pub use frame::{CanId, FrameError, FrameKind, WireFrame};
pub use hub::{
    Delivery, Endpoint, EndpointId, EndpointOptions, FrameReceiver, FrameSender, Hub, HubConfig,
};
pub use log::CandumpLog;
pub use model::TxQueueFull;
pub use timing::{BitTiming, Stuffing};
