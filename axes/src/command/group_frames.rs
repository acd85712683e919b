//! Group commands on frames and between groups (issue 11 item 1): HIMC's coordinate
//! transforms and selection (digest 004 §2.7, §8.3.20–8.3.31), NMC's rotary transforms
//! (digest 001 §2.10 C3§10.5) and NMC's interference protection between two coordinate
//! systems (`NMC_SetMvProtect`, `TmvProtectPara`, digest 001 §2.5 and §3.7).

use serde::{Deserialize, Serialize};

use super::{AxisIndex, CoordinateSystem, GroupId};

/// Set one link of the group's frame chain (HIMC `SetGrpCoordTrans`, §8.3.31): `frame` is
/// `"offset"`, `"wcs1"`…`"wcs15"` or `"pcs"`; `pose` is `{X, Y, Z, A, B, C}`, lengths and
/// degrees, the frame's placement in its parent with `R = Rz(C)·Ry(B)·Rx(A)` (TV 56). Moves
/// already queued keep the positions they were accepted with.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetCoordinateTransform {
    pub group: GroupId,
    pub frame: CoordinateSystem,
    pub pose: [f64; 6],
}

/// The coordinate system of moves that name none, and of the status's `frame_position` (HIMC
/// `SetGrpCoordSys`, §8.3.21).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetCoordinateSystem {
    pub group: GroupId,
    pub coordinate_system: CoordinateSystem,
}

/// Define the `"rotary"` system (NMC `CrdSetTransRotate(crd, rotAxisNo, angleRadEqual,
/// firstAxisInitPos, secAxisInitPos)`): the workpiece sits on a table, axis `rotary_axis` (not
/// a member), turning `rad_per_unit` radians per unit of that axis about `center` of the
/// plane `plane` (group coordinates, default `[0, 1]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetRotaryTransform {
    pub group: GroupId,
    pub rotary_axis: AxisIndex,
    pub rad_per_unit: f64,
    pub center: [f64; 2],
    #[serde(default)]
    pub plane: Option<[usize; 2]>,
}

/// Define the `"xyza"` system (NMC `CrdSetXYZAPara(crd, pulse2Rad, toolX, toolY)` with
/// `CrdSetTransXYZA(crd, {0, 1, 2, 3})`): group coordinates 0–3 are X, Y, Z, A; the tool tip
/// is `tool` (X, Y) away from the A axis's centre line at A = 0; A turns `rad_per_unit` per
/// unit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetXyzaTransform {
    pub group: GroupId,
    pub rad_per_unit: f64,
    pub tool: [f64; 2],
}

/// Delete the group's NMC transform (`CrdDelTransRotate`, `CrdDelTransXYZA`); a selection of
/// it returns to `"mcs"`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupDeleteTransform {
    pub group: GroupId,
}

/// NMC's polar machine (`CrdSetTransPolar(crd, rotAxNo, transAxNo, rotEquiv)`, digest 001
/// C3§10.5 "极坐标转换"): the program is Cartesian in the group coordinates `plane` (X, Y;
/// default `[0, 1]`), the machine one rotary and one feed axis, the members of those two
/// coordinates. Each tick the program point (X, Y) (origin included) is fed to `rotary` as
/// θ = atan2(Y, X) × `rotary_units_per_radian`, unwrapped from the rotary axis's position, and
/// to `feed` as r = √(X² + Y²) (the feed axis's units, which X and Y are in). Accepted only
/// while the group holds no motion; motions accepted afterwards are transformed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSetPolarTransform {
    pub group: GroupId,
    pub rotary: AxisIndex,
    pub feed: AxisIndex,
    /// The rotary axis's units per radian (NMC: 1 / rotEquiv pulses).
    pub rotary_units_per_radian: f64,
    #[serde(default)]
    pub plane: Option<[usize; 2]>,
}

/// Back to Cartesian members (`CrdDelTransPolar`): accepted only while the group holds no
/// motion.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupDeletePolarTransform {
    pub group: GroupId,
}

/// What a move protection does when the two groups would come too close (NMC
/// `NMC_SetMvProtect` mode).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ProtectionMode {
    /// Mode 0: both groups stop.
    #[default]
    BothStop,
    /// Mode 1 (NMC's "laser" mode): `stop_group` stops and its protected axis retreats to
    /// `safe_wait_position`; the other group goes on.
    Retreat,
}

/// Guard two groups against each other (NMC `NMC_SetMvProtect` + `SetMvProtectMode01Para`,
/// `TmvProtectPara`): the distance between coordinate `axes[0]` of `groups[0]` and coordinate
/// `axes[1]` of `groups[1]` is `origin_distance − Σ move_direction[k]·position[k]` (group
/// coordinates); it must stay ≥ `protection_distance`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveProtectionEnable {
    /// NMC `groupNo` (NMC has one, 0).
    pub protection: u16,
    /// `crdNo[2]`.
    pub groups: [GroupId; 2],
    /// `crdAxNo[2]`: the group coordinate (0 = X, 1 = Y, 2 = Z …) of each.
    pub axes: [usize; 2],
    /// `moveDir[2]`: the direction (1 or −1) in which each axis closes the distance.
    pub move_direction: [i8; 2],
    /// `orgDis`: the distance with both axes at 0.
    pub origin_distance: f64,
    /// `mvProtectDis`.
    pub protection_distance: f64,
    #[serde(default)]
    pub mode: ProtectionMode,
    /// `stopCrdNo` (retreat mode).
    #[serde(default)]
    pub stop_group: Option<GroupId>,
    /// `safeWaitPos` (retreat mode): where the stopped group's protected axis goes.
    #[serde(default)]
    pub safe_wait_position: Option<f64>,
    /// `mvToSafeVel`, `mvToSafeAcc` (retreat mode; default: the group's parameters).
    #[serde(default)]
    pub retreat_velocity: Option<f64>,
    #[serde(default)]
    pub retreat_acceleration: Option<f64>,
}

/// Stop guarding (NMC `NMC_DelMvProtect`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoveProtectionDisable {
    pub protection: u16,
}
