//! Modbus TCP, RTU and RTU-over-TCP front-end (ARCHITECTURE §5): a sans-IO codec (`pdu`,
//! `frame`), declarative register maps, a service from requests to engine commands and
//! snapshot reads, and thin tokio transports.
//!
//! The wire side:
//! - [`server::Server`] handles one request PDU for a unit: unit filtering and broadcast,
//!   FC 8 diagnostics and listen-only mode, FC 17 and FC 43/14 from the model's identity,
//!   fault injection, counting; data requests go to a [`model::DataModel`];
//! - [`state::FrontendState`] is what a front-end shares with the control API: counters
//!   ([`counters`]), faults ([`faults`]), the last engine refusal, a JSON snapshot;
//! - [`transport`]: [`transport::tcp::serve_tcp`], [`transport::rtu::serve_rtu`] (on an
//!   [`transport::rtu::RtuLine`]) and [`transport::rtu_over_tcp::serve_rtu_over_tcp`], set up
//!   by the structs of [`config`];
//! - [`memory::MemoryModel`]: a plain in-memory model for tests and benchmarks.
//!
//! The data side: [`map`], register maps from TOML compiled for a machine, served over the
//! engine by [`map::MapModel`].

pub mod config;
pub mod counters;
pub mod faults;
pub mod frame;
pub mod framing;
pub mod map;
pub mod memory;
pub mod model;
pub mod pdu;
pub mod server;
pub mod state;
pub mod tables;
pub mod transport;
