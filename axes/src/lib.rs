//! mcemu's motion engine (ARCHITECTURE §3–§4): deterministic, no I/O, no async.
//!
//! The [`engine::Engine`] owns the axes, the machine I/O and the slaves and advances only by
//! [`engine::Engine::step`], one servo period at a time. Front-ends change it only through
//! [`command::Command`] values and read it through [`status::Snapshot`]s; the
//! [`runtime`] runs it on a servo thread behind a cloneable [`runtime::EngineHandle`].

pub mod axis;
pub mod cia402;
pub mod command;
pub mod compensation;
pub mod config;
pub mod coupling;
pub mod engine;
pub mod error;
pub mod filter;
pub mod group;
pub mod guard;
pub mod homing;
pub mod hw;
pub mod od;
pub mod param;
/// One-dimensional profiles, the `profile` crate (re-exported so that `axes::profile::…` paths
/// stay as they were).
pub use profile;
pub mod rng;
pub mod runtime;
pub mod sampling;
pub mod status;
pub mod trigger;
pub mod types;

pub use command::{AxisIndex, Command, CommandId, EngineError, Reply};
pub use config::EngineConfig;
pub use engine::Engine;
pub use param::ParamId;
pub use status::{AxisFlags, AxisState, AxisStatus, Snapshot};
