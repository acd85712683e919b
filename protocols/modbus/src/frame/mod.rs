//! Framing: Modbus TCP (MBAP header) and RTU (address, PDU, CRC-16), sans-IO.

pub mod rtu;
pub mod tcp;
