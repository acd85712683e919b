//! One axis: command FIFO, PLCopen state machine, limits, and the per-tick pipeline
//! (ARCHITECTURE §3.3–§3.5).
