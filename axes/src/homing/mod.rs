//! Homing: the CiA 402 (IEC 61800-7-201) homing methods 1–14, 17–30, 33, 34, 35 and 37 as one
//! state machine over the simulated switches and index pulse (ARCHITECTURE §3.7), plus tables
//! mapping vendor modes onto it ([`vendor`]).
//!
//! # Contract (sans-IO)
//!
//! One [`Homing`] value is one homing run. The axis owns it while homing:
//!
//! 1. [`Homing::start`] validates the [`HomingSpec`] against the axis's [`HomingHardware`] and
//!    reads the switch levels of the current tick. Errors here mean "no motion at all".
//! 2. Every servo tick, starting with the tick `start` was called in, the axis calls
//!    [`Homing::step`] with that tick's [`HomingInputs`] (actual position, logical switch
//!    levels, exact in-tick edge and index positions) and executes the returned
//!    [`HomingOutput`]:
//!    - `motion`: a new [`MotionRequest`] for its own profile generator (`None` keeps the
//!      current one). The machine only reverses from rest: it asks for `Stop`, waits for
//!      `motion_done`, then asks for the new direction. A run started while the axis moves
//!      (`velocity` ≠ 0) first stops it.
//!    - `set_home`: redefine the position so that this position (current frame) reads
//!      `spec.offset`, shifting commanded and actual position alike. Inputs from the next tick on
//!      are in the new frame.
//!    - `done`: the run is over and the axis is at rest (after the final stop or return leg).
//!      `Some` exactly once; later calls return an empty output.
//! 3. [`Homing::abort`] stops a run from outside (e.g. NMC_MtHomeStop); keep stepping until
//!    `done`.
//!
//! While homing, the machine handles the limit switches itself (reversal, or an error naming the
//! limit); the axis should still stop on a hard limit, but not fault because of it.
//!
//! # One machine for all methods
//!
//! Every switch method is described by a row of a table (`method.rs`): which input is the
//! reference signal (home switch, a limit switch), the shape of its active region (active above
//! an edge, below it, or a cam with two edges), which edge is the home edge, the direction `A`
//! in which that edge must be crossed (the "approach"), whether the home point is the next index
//! pulse after it, and which limit reverses the search (methods 7–14, 23–30).
//!
//! The machine keeps a region estimate relative to the signal — left of it, inside it, right of
//! it, or unknown (outside a cam, side unknown) — and repeatedly applies one rule: get to the
//! region from which moving in `A` crosses the home edge, then move in `A`. Searching is at
//! `switch_velocity`; moving towards a nearby edge (inside a cam, or just after crossing it) and
//! the index search are at `zero_velocity`; all ramps use `acceleration`. A transition of the
//! signal seen while moving in `A` that enters/leaves the active region the way the home edge
//! does is the home edge. The primitives are: search (velocity) in a direction until the signal
//! changes, stop, search the index, latch, and the final stop/return.

mod machine;
mod method;
pub mod vendor;

#[cfg(test)]
mod sim;
#[cfg(test)]
mod tests;

pub use machine::Homing;

use crate::types::Direction;
use serde::{Deserialize, Serialize};

/// What the axis does once the home point is found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AfterHome {
    /// Decelerate to a stop and stay there (CiA 402 drives).
    #[default]
    Decelerate,
    /// Decelerate, then move back so that the axis ends at the home point, reading the offset
    /// (HMC "decelerate to stop, return to the origin position", digest 000 §5).
    ReturnToHome,
    /// Stop without a ramp (CPU 226H "motor stops immediately", digest 003 §3).
    StopImmediately,
}

/// How the position of a switch edge or an index pulse is taken.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Latch {
    /// The exact position of the event (drive touch probe, FPGA capture, HMC_HomeEx).
    #[default]
    Exact,
    /// The position of the tick in which the machine sees the event (HMC_Home polls once per
    /// servo period, digest 000 §5; CPU 226H scans its switch inputs, digest 003 §2.1 ④).
    Polled,
}

/// Vendor behaviour layered on a CiA 402 method. The default is plain CiA 402 drive homing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HomingQuirks {
    pub after_home: AfterHome,
    /// Latch of the home and limit switch edges.
    pub switch_latch: Latch,
    /// Latch of the index pulse.
    pub index_latch: Latch,
    /// Read the home and limit switches only every N ticks (0 and 1: every tick). The index
    /// pulse is not affected (CPU 226H: Z is captured in hardware, digest 003 §2.1 ④, TV-30).
    pub switch_scan_ticks: u32,
    /// Fail with [`HomingError::NotFound`] when one search leg travels farther than this without
    /// finding what it looks for; 0 = unlimited (NMC `safeLen`, home status bit 4).
    pub max_search_distance: f64,
    /// Before searching, move this far opposite to the method's nominal search direction
    /// (NMC `iniRetPos`); 0 = none.
    pub initial_backoff: f64,
    /// Second search (NMC `reScanEn` + `retSwOffset`): the first time the home edge (the index
    /// for methods 33/34) is found, do not take it: stop, move this far back past it, and
    /// approach it again at the zero velocity. `None` = off.
    pub rescan: Option<f64>,
    /// Find the home point but do not redefine the position (NMC_MtTryHome): `set_home` stays
    /// `None`, `home_found` reports the point.
    pub trial: bool,
}

/// One homing run's parameters (CiA 402 0x6098, 0x6099:01/02, 0x609A, 0x607C), in the axis's
/// user units and seconds.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HomingSpec {
    pub method: i16,
    /// Speed while searching for a switch.
    pub switch_velocity: f64,
    /// Speed of the final approach to the edge and of the index search.
    pub zero_velocity: f64,
    /// Acceleration and deceleration of every ramp.
    pub acceleration: f64,
    /// Position the home point reads after homing.
    pub offset: f64,
    /// Seconds until [`HomingError::Timeout`]; 0 = none.
    pub timeout: f64,
    pub quirks: HomingQuirks,
}

/// Which inputs the axis has.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct HomingHardware {
    pub limit_pos: bool,
    pub limit_neg: bool,
    pub home: bool,
    pub index: bool,
}

impl HomingHardware {
    /// An axis with every input.
    pub const ALL: HomingHardware = HomingHardware {
        limit_pos: true,
        limit_neg: true,
        home: true,
        index: true,
    };
}

/// What the axis tells the machine each tick. Positions are in the current frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HomingInputs {
    /// Engine time, s.
    pub time: f64,
    /// Actual position at the end of the tick.
    pub position: f64,
    /// Commanded velocity (its sign is the direction of travel).
    pub velocity: f64,
    /// The last [`MotionRequest`] has finished (at rest, or at its `MoveTo` target). Only read
    /// while a `Stop`, `StopImmediately` or `MoveTo` is in effect, never for `Velocity`.
    pub motion_done: bool,
    /// Logical levels (already inverted and filtered) at the end of the tick.
    pub limit_pos: bool,
    pub limit_neg: bool,
    pub home: bool,
    /// Exact position where the home input changed during this tick.
    pub home_edge: Option<f64>,
    pub limit_pos_edge: Option<f64>,
    pub limit_neg_edge: Option<f64>,
    /// Exact position of an index pulse passed during this tick.
    pub index: Option<f64>,
}

/// Motion the axis executes with its own profile generator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum MotionRequest {
    /// Ramp to this signed velocity and keep it.
    Velocity { velocity: f64, acceleration: f64 },
    /// Ramp down to rest.
    Stop { deceleration: f64 },
    /// Velocity zero now, no ramp.
    StopImmediately,
    /// Move to this position (current frame) and stop there.
    MoveTo {
        position: f64,
        velocity: f64,
        acceleration: f64,
    },
}

/// What the machine asks of the axis this tick.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HomingOutput {
    /// New motion request; `None` keeps the current one.
    pub motion: Option<MotionRequest>,
    /// This position (current frame) must read the spec's offset from now on.
    pub set_home: Option<f64>,
    /// The home point was found at this position (current frame, before `set_home` applies).
    /// Reported in trial runs too; dialects use it for the home error (NMC_MtGetHomeError).
    pub home_found: Option<f64>,
    pub phase: HomingPhase,
    /// The run ended; the axis is at rest.
    pub done: Option<Result<(), HomingError>>,
}

/// What a running machine is doing. `code()` is the value for `AxisStatus::homing_phase`
/// (0 is reserved for "not homing").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[repr(u8)]
pub enum HomingPhase {
    /// Initial back-off move.
    Backoff = 1,
    /// Searching the reference switch at the switch velocity.
    #[default]
    Search = 2,
    /// Decelerating to reverse.
    Reversing = 3,
    /// Moving towards a nearby home edge at the zero velocity.
    Approach = 4,
    /// Backing off the edge for the second search.
    Rescan = 5,
    /// Searching the index pulse (after the edge, or alone for 33/34).
    Index = 6,
    /// Home found; decelerating or stopping.
    Stopping = 7,
    /// Moving back to the home point.
    Returning = 8,
    /// Failed or aborted; stopping.
    Aborting = 9,
}

impl HomingPhase {
    pub fn code(self) -> u8 {
        self as u8
    }
}

/// Homing as the status words see it: for vendor status mappings.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "state", content = "detail", rename_all = "snake_case")]
pub enum HomingStatus {
    /// No homing has run (or its result was cleared).
    #[default]
    Idle,
    Running(HomingPhase),
    Succeeded,
    Failed(HomingError),
}

/// An input a homing method uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HomingInput {
    NegativeLimit,
    PositiveLimit,
    HomeSwitch,
    Index,
}

impl std::fmt::Display for HomingInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            HomingInput::NegativeLimit => "negative limit switch",
            HomingInput::PositiveLimit => "positive limit switch",
            HomingInput::HomeSwitch => "home switch",
            HomingInput::Index => "index pulse",
        })
    }
}

/// Why homing could not start or did not finish.
#[derive(Clone, Debug, PartialEq, thiserror::Error, Serialize, Deserialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum HomingError {
    #[error("method {method} is not a supported homing method")]
    UnsupportedMethod { method: i16 },
    /// The method needs an input the axis does not have (HIMC: "fails if no negative limit is
    /// assigned", digest 004 §4.3).
    #[error("homing method {method} needs a {input}, and the axis has none")]
    MissingInput { method: i16, input: HomingInput },
    /// A speed, acceleration or distance that cannot produce the motion (NMC home status bit 3).
    #[error("homing parameter {name} = {value}: {requirement}")]
    BadParameter {
        name: String,
        value: f64,
        requirement: String,
    },
    #[error("homing did not find the home point within {seconds} s")]
    Timeout { seconds: f64 },
    /// A search leg ended without the input it looked for: the maximum search distance was
    /// exhausted, or a cam search swept from limit to limit (NMC home status bit 4).
    #[error("{input} not found (searched {distance})")]
    NotFound { input: HomingInput, distance: f64 },
    /// A limit switch was reached that the method does not use.
    #[error("{direction} limit switch reached while homing")]
    LimitHit { direction: Direction },
    #[error("homing aborted")]
    Aborted,
}

/// What ended a failed homing, without its details: `Copy`, so the axis status keeps it
/// (vendor status words tell a parameter error from a switch never found, NMC §3.13).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HomingFailure {
    UnsupportedMethod,
    MissingInput,
    BadParameter,
    Timeout,
    NotFound,
    LimitHit,
    Aborted,
}

impl HomingError {
    pub fn failure(&self) -> HomingFailure {
        match self {
            HomingError::UnsupportedMethod { .. } => HomingFailure::UnsupportedMethod,
            HomingError::MissingInput { .. } => HomingFailure::MissingInput,
            HomingError::BadParameter { .. } => HomingFailure::BadParameter,
            HomingError::Timeout { .. } => HomingFailure::Timeout,
            HomingError::NotFound { .. } => HomingFailure::NotFound,
            HomingError::LimitHit { .. } => HomingFailure::LimitHit,
            HomingError::Aborted => HomingFailure::Aborted,
        }
    }
}
