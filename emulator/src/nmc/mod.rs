//! The NMC front-end (issue 13): mcemu's side of the `nmc_lib20` library. A program written
//! for Gaochuan's `NMC_*` API (digest 001), linked with mcemu's `libnmc_lib20.so`, reaches it
//! over TCP (`[frontends.nmc]`, network controllers) or a Unix socket (`[frontends.nmc_local]`,
//! PCIe/GCE cards).
//!
//! - `config`: the two sections and the device identity;
//! - `faults`: what `POST /api/v1/faults` injects (delay, no reply, close, corrupt, wrong
//!   sequence);
//! - `service`: one request → reply payload + engine commands; the per-axis NMC settings;
//! - `sync_state`: what the gear, PT, capture, compare, gantry, handwheel and compensation
//!   families keep between calls;
//! - `crd`: the coordinate systems' state the engine's groups do not keep;
//! - `crd_frames`: the transforms, arc sections, break points and move protection as the
//!   manual's calls wrote them (family 0x17xx);
//! - `handlers`: one file per family of the function table (`mcemu_nmc::table`);
//! - `ax_state`: the axis-level additions' settings (family 0x13xx); the watchdog, E-stop
//!   inputs and PTP compares they arm are the engine's guards, judged on the tick;
//! - `user_para_file`: the user parameter areas in the state directory;
//! - `saved_config`: `NMC_SaveMotionConfig`'s file in the state directory, applied at start
//!   and on `NMC_DevReset`;
//! - `io_state`: extension modules, dedicated outputs and the written ID (0x12xx families);
//! - `ecat_bus`: an `ecat` card's EtherCAT bus: NMC axis numbers (local, bus drives from 16)
//!   → engine axes, SDO slaves, the drive homings it started;
//! - `stored`: settings the engine has no model of, kept and read back;
//! - `sys_state`: the system family's data collection, user login and execution-time
//!   calculation (0x18xx);
//! - `laser_state`: the laser, SHIO and PWM settings (kept in `stored`);
//! - `serve`: the transports (the kit's bounded accept loop on TCP, the same table on the Unix
//!   socket), the connection loop over `mcemu_nmc::session`, the control-API handle.

pub mod ax_state;
pub mod config;
pub mod crd;
pub mod crd_frames;
pub mod crd_length;
pub mod ecat_bus;
pub mod faults;
mod handlers;
pub mod io_state;
pub mod laser_state;
pub mod saved_config;
pub mod serve;
pub mod service;
pub mod stored;
pub mod sync_state;
pub mod sys_state;
pub mod user_para_file;
