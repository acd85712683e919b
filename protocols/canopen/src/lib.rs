//! CANopen CiA 301 slave stack with the CiA 402 binding (ARCHITECTURE §5).
//!
//! The node ([`Node`]) is a sans-IO state machine: transports feed it frames and time and send
//! what it returns; the application (the CiA 402 binding) shares its dictionary through
//! [`Device`] and reacts to [`NodeEvent`]s. [`bus::Bus`] routes frames between nodes and a
//! test master in-process with virtual time.

pub mod bus;
pub mod cia402;
pub mod client;
pub mod device;
pub mod eds;
pub mod emcy;
pub mod events;
pub mod frame;
mod heartbeat;
pub mod lss;
pub mod nmt;
mod node;
pub mod objects;
mod pdo;
pub mod sdo;
pub mod store;
mod sync;

pub use device::Device;
pub use events::{LossCause, NodeEvent};
pub use frame::{CanFrame, FrameError};
pub use nmt::{NmtCommand, NmtState};
pub use node::{Node, NodeCounters, NodeError};
pub use objects::{communication_objects, ErrorBehaviour, Identity, NodeConfig};
pub use sdo::SdoAbort;
pub use store::ParameterGroup;
