//! The NMC front-end (issue 13): mcemu's side of the `nmc_lib20` library. A program written
//! for Gaochuan's `NMC_*` API (digest 001), linked with mcemu's `libnmc_lib20.so`, reaches it
//! over TCP (`[frontends.nmc]`, network controllers) or a Unix socket (`[frontends.nmc_local]`,
//! PCIe/GCE cards).
//!
//! - `config`: the two sections and the device identity;
//! - `service`: one request → reply payload + engine commands; the per-axis NMC settings;
//! - `crd`: the coordinate systems' state the engine's groups do not keep;
//! - `handlers`: one file per family of the function table (`mcemu_nmc::table`);
//! - `stored`: settings the engine has no model of, kept and read back;
//! - `serve`: the transports (the kit's bounded accept loop on TCP, the same table on the Unix
//!   socket), the connection loop over `mcemu_nmc::session`, the control-API handle.

pub mod config;
pub mod crd;
mod handlers;
pub mod serve;
pub mod service;
pub mod stored;
