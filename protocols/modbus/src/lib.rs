//! Modbus TCP, RTU and RTU-over-TCP front-end (ARCHITECTURE §5): a sans-IO codec (`pdu`,
//! `frame`), declarative register maps, a service from requests to engine commands and
//! snapshot reads, and thin tokio transports.

pub mod frame;
pub mod map;
pub mod model;
pub mod pdu;
