//! The socketcand protocol (linux-can/socketcand), server side: python-can's `socketcand`
//! interface and other socketcand clients reach an emulated bus over TCP.
//!
//! - [`codec`]: bytes ⇄ elements (`< send 123 2 11 22 >`), sans-IO, total, bounded.
//! - [`session`]: one connection's modes (no bus, BCM, raw, control), sans-IO.
//! - [`server`]: the tokio TCP transport, serving [`crate::Hub`]s by bus name.

pub mod codec;
pub mod server;
pub mod session;

pub use codec::{Command, CommandError, Decoder};
pub use mcemu_frontend::bound::AtLimit;
pub use server::{SocketcandConfig, SocketcandError, SocketcandServer, SocketcandStats};
pub use session::{Mode, Session, SessionAction};
