//! Coordinated paths in up to [`MAX_AXES`] dimensions (issue 11).
//!
//! - [`geometry`]: segments (lines, circular arcs and helices, curves through points) with
//!   their length, and position, unit tangent and curvature vector at any path length `s`;
//!   corner blends.
//! - [`frames`]: rigid transforms between program and machine coordinates (HIMC's frame
//!   chain with roll-pitch-yaw poses, NMC's origin offset and rotary transforms).
//! - [`planner`]: [`planner::PathPlanner`], which moves a point along a queue of segments one
//!   servo period per call, under the segments' path limits and every axis's own limits, with
//!   look-ahead and blending.
//!
//! Pure and deterministic: no clock, no I/O, no threads, and no allocation per tick once the
//! queue has grown. The engine (`axes`) owns one planner per axis group and feeds its axes
//! from it.

mod checks;
pub mod frames;
pub mod geometry;
pub mod planner;

/// Most axes one path moves (HIMC groups: ≤ 9, digest 004 §3).
pub const MAX_AXES: usize = 9;

/// A point or vector of a path. Components past the path's dimension count are 0.
pub type Point = [f64; MAX_AXES];
