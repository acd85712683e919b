//! Modbus TCP, RTU and RTU-over-TCP front-end (ARCHITECTURE §5). Filled by the Modbus issue.
