//! The `mcemu` binary's parts (ARCHITECTURE §6): the config file, running a machine with its
//! front-ends, scenarios and traces, and the HTTP control API.

pub mod ascii;
pub mod canopen;
pub mod config;
pub mod control;
pub mod dashboard;
pub mod frontend;
pub mod listener;
pub mod modbus;
pub mod nmc;
pub mod reference;
pub mod run;
pub mod scenario;
pub mod state_dir;
pub mod trace;
