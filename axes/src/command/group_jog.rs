//! Group jogs (issue 11; HIMC JogGroup and JogGroupAxis, digest 004 §8.2.7–8.2.8): continuous
//! motion of a whole group along one coordinate, with the group's acceleration and
//! deceleration, until `group_stop`, `group_halt`, a jog with velocity 0, or a member's
//! trouble. A new jog while one runs changes its velocity (a ramp from the present one).

use serde::{Deserialize, Serialize};

use super::{CoordinateSystem, GroupId};

/// Jog the group along coordinate `coordinate` (0 = X, 1 = Y, 2 = Z, 3–5 = A, B, C …) of
/// `coordinate_system` (default: the group's selected system; HIMC JogGroup jogs in the MCS)
/// at the signed `velocity` (units/s; 0 ramps the jog down to rest).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupJog {
    pub group: GroupId,
    pub coordinate: usize,
    pub velocity: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coordinate_system: Option<CoordinateSystem>,
}

/// Jog one member of the group (`member`: its place in the group's `axes`, 0–8; HIMC
/// JogGroupAxis) at the signed `velocity`; the other members stand.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupJogAxis {
    pub group: GroupId,
    pub member: usize,
    pub velocity: f64,
}
