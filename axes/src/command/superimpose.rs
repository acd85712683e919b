//! Couplings with two masters (issue 12 item 9): superimposed motion (HMC SuperimposeEx) and the
//! tangential axis (HMC MoveTang). Part of the coupling family; the per-tick work is
//! `crate::coupling::superimpose` and `crate::coupling::tangential`.

use serde::{Deserialize, Serialize};

use super::{AxisIndex, GroupId, MasterSource};

/// Couple `slave` to two masters: slave travel = `ratios[0]` × travel of `masters[0]` +
/// `ratios[1]` × travel of `masters[1]` (HMC_SuperimposeEx, digest 000 §4.4; HMC_Superimpose is
/// ratios [1, 1]). The slave starts from where it stands: the law is on increments, so engaging
/// never moves it. JSON `type`: `superimpose_in`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuperimposeIn {
    pub slave: AxisIndex,
    /// Two different axes, neither the slave.
    pub masters: [AxisIndex; 2],
    /// k1, k2 (HMC: N0/D0, N1/D1); finite, within ±1e12.
    pub ratios: [f64; 2],
    /// Which position of the masters is followed (HMC: actual; default commanded, as a gear).
    #[serde(default)]
    pub master_source: MasterSource,
}

/// Change the ratios of a running superimposed coupling (HMC_SetSuperimposeRatio). The slave
/// keeps its position: the new ratios apply to master travel from now on (digest 000 TV 22).
/// JSON `type`: `superimpose_set_ratios`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuperimposeSetRatios {
    pub slave: AxisIndex,
    pub ratios: [f64; 2],
}

/// Decouple a superimposed slave: as `gear_out`, it keeps its velocity and decelerates to rest
/// with its `decel`. JSON `type`: `superimpose_out`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuperimposeOut {
    pub slave: AxisIndex,
}

fn plane() -> [u8; 2] {
    [0, 1]
}

fn is_plane(c: &[u8; 2]) -> bool {
    *c == [0, 1]
}

fn turn() -> f64 {
    360.0
}

fn is_turn(v: &f64) -> bool {
    *v == 360.0
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// Make `axis` track the tangent angle of group `group`'s path in the plane of its coordinates
/// `coordinates` (default [0, 1], the XY plane) plus `offset` (HMC_MoveTang, digest 000 §4.4).
/// The angle is in the axis's units, `units_per_turn` to a full turn (default 360: degrees;
/// HMC's C axis with RepDist R has 2R), unwrapped: it runs on continuously past a full turn. The
/// axis turns the shortest way at a jump of the tangent (a corner), within its own velocity and
/// acceleration limits, and holds while the path stands. JSON `type`: `tangential_in`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TangentialIn {
    pub axis: AxisIndex,
    pub group: GroupId,
    #[serde(default = "plane", skip_serializing_if = "is_plane")]
    pub coordinates: [u8; 2],
    #[serde(default, skip_serializing_if = "is_zero")]
    pub offset: f64,
    #[serde(default = "turn", skip_serializing_if = "is_turn")]
    pub units_per_turn: f64,
}

/// Stop tracking: the axis decelerates to rest with its `decel`. JSON `type`: `tangential_out`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TangentialOut {
    pub axis: AxisIndex,
}

/// How a tangential axis handles corners (HMC_MoveTangConfigCornerMode `ucCornerMode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TangentialCornerModeKind {
    /// 0, no lift: a jump of the tangent is turned the shortest way while the path runs on.
    #[default]
    None,
    /// 1, manual lift: the path stops at every junction that turns by more than
    /// `angle_limit` and waits for `tangential_corner_continue`.
    Manual,
    /// 2, auto lift: at such a junction the path stops, `z_axis` lifts to the safe position,
    /// the tangential axis turns to the next motion's direction, `z_axis` comes back and the
    /// path goes on, all by itself.
    Auto,
}

/// How the auto lift's `safe_z` is read (HMC `ucSafePosZMode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SafeZMode {
    /// 0: lift by `safe_z` from where Z stands at the corner.
    #[default]
    Incremental,
    /// 1: lift to `safe_z`.
    Absolute,
}

fn is_incremental(m: &SafeZMode) -> bool {
    *m == SafeZMode::Incremental
}

/// Set a tangential axis's corner mode (HMC_MoveTangConfigCornerMode, manual §4.4.9.2): with
/// `manual`, the group stops exactly at each junction of two motions whose direction in the
/// tracked plane turns by more than `angle_limit` radians (judged when the second motion is
/// queued; a buffered non-motion command between them means no stop), and waits there. The
/// rule applies to motions queued afterwards. With `auto` (mode 2) the group stops at the same
/// junctions and the engine lifts `z_axis` to `safe_z` (its own move, with its own `speed`,
/// `accel` and `decel`), turns the tangential axis to the next motion's direction, lowers
/// `z_axis` back to where it was and lets the path go on. `z_axis` must be another axis than
/// the tangential axis and not a member of the tracked group. JSON `type`:
/// `tangential_corner_mode`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TangentialCornerMode {
    pub axis: AxisIndex,
    pub mode: TangentialCornerModeKind,
    /// Radians, [0, π] (HMC dCornerAngleLimit).
    #[serde(default)]
    pub angle_limit: f64,
    /// Auto lift only: the axis that lifts (HMC ucAxisZ).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z_axis: Option<AxisIndex>,
    /// Auto lift only: the lift (incremental) or the safe position (absolute) (HMC dSafePosZ).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub safe_z: f64,
    #[serde(default, skip_serializing_if = "is_incremental")]
    pub safe_z_mode: SafeZMode,
}

/// At a corner stop: turn the tangential axis (within its own limits) to the direction the
/// next motion starts in (HMC_MoveTangCornerFollowNextCmd). JSON `type`:
/// `tangential_corner_follow_next`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TangentialCornerFollowNext {
    pub axis: AxisIndex,
}

/// At a corner stop: let the group's path go on (HMC_MoveTangCornerContinue). JSON `type`:
/// `tangential_corner_continue`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TangentialCornerContinue {
    pub axis: AxisIndex,
}
