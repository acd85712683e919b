//! Homing: every CiA 402 method (1–35, 37) as one state machine over the simulated switches and
//! index pulse (ARCHITECTURE §3.7), plus tables mapping vendor modes onto it (`vendor`).
//!
//! The state machine is sans-IO: each tick the axis hands it [`HomingInputs`] and executes the
//! [`HomingOutput`] it returns (a motion request, a redefinition of the position, completion).

pub mod vendor;

use serde::{Deserialize, Serialize};

/// Vendor behaviour layered on a CiA 402 method. The default is plain CiA 402 drive homing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HomingQuirks {}

/// Why homing could not start or did not finish.
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize, Deserialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum HomingError {
    #[error("method {method} is not a supported homing method")]
    UnsupportedMethod { method: i16 },
}

/// A homing run as the axis starts it (placeholder until the state machine lands).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HomingSpec {
    pub method: i16,
    pub switch_velocity: f64,
    pub zero_velocity: f64,
    pub acceleration: f64,
    pub offset: f64,
    pub timeout: f64,
    pub quirks: HomingQuirks,
}

/// A running homing state machine (placeholder until the state machine lands).
#[derive(Clone, Debug, PartialEq)]
pub struct Homing {}
