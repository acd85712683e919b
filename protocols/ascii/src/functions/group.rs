//! Chapter 8, group motion (digest 004 §2.7) through the engine's groups (command family
//! Group). HMPL builds a group one axis at a time (`AddAxisToGrp`, in {X, Y, Z, A, B, C}
//! order); the engine creates a group with its axes at once, so each change of members deletes
//! and re-creates the engine group in one batch, with the group's motion profile set again.
//! The 2-D moves address the first two group coordinates; the others hold their place.

use axes::status::{GroupState, GroupStatus};
use mcemu_dialects::himc::constants::coordinate_system_name;
use mcemu_dialects::himc::group::{Profile, ProfileValues};
use mcemu_dialects::himc::system::HMPL_ARG_OUT_OF_RANGE;
use serde_json::json;

use super::engine;
use super::group_state::{
    apply_profile, command, group_error, group_id, modes, profile_of, regroup, status, target,
};
use crate::reply::Outcome;
use crate::table::{
    row, unary, Addresses::Axis, Addresses::Group, Args, Ctx, Function, Plan, Ret, Then, Ty,
};

/// At most 9 axes in an API-level group (§8.3.1).
const MAX_GROUP_AXES: usize = 9;

const GDD: &[Ty] = &[Ty::Int, Ty::Double, Ty::Double];
const GDDD: &[Ty] = &[Ty::Int, Ty::Double, Ty::Double, Ty::Double];
/// `(group_id, coord_sys, double *out)`: `out` is written `{}`; the values come back in the
/// reply.
const POSE: &[Ty] = &[Ty::Int, Ty::Int, Ty::OutArray6];
const GDDDD: &[Ty] = &[Ty::Int, Ty::Double, Ty::Double, Ty::Double, Ty::Double];

/// §8.3.1, TV 50–51: append an axis; the 10th, or one already in a group, is refused.
fn add_axis(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let axis = match usize::try_from(args.int(1)) {
        Ok(a) if a < cx.snapshot.axes.len() => a as u16,
        _ => return Plan::Fail(HMPL_ARG_OUT_OF_RANGE),
    };
    let in_a_group = cx
        .registers
        .group_members
        .values()
        .any(|m| m.contains(&axis))
        || cx.snapshot.groups.iter().any(|g| {
            g.members
                .iter()
                .take(usize::from(g.axis_count))
                .any(|&m| m == axis)
        });
    if in_a_group {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_AXIS_DUPLICATED"));
    }
    let mut members = cx
        .registers
        .group_members
        .get(&group)
        .cloned()
        .unwrap_or_default();
    if members.len() >= MAX_GROUP_AXES {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_GRP_SIZE_FULL"));
    }
    members.push(axis);
    set_members(cx, group, members)
}

/// Make the group `members`, its InShape following them (§15.8: an axis that joins gets the
/// group's shaper, one that leaves loses it).
fn set_members(cx: &mut Ctx<'_>, group: u16, members: Vec<u16>) -> Plan {
    let shaper = super::filters::follow_members(cx, group, &members)
        .into_iter()
        .map(command)
        .collect::<Result<Vec<_>, u32>>();
    match regroup(cx, group, &members).and_then(|b| Ok([b, shaper?].concat())) {
        Ok(batch) => {
            if members.is_empty() {
                cx.registers.group_members.remove(&group);
            } else {
                cx.registers.group_members.insert(group, members);
            }
            if batch.is_empty() {
                Plan::Done(Outcome::Int(0))
            } else {
                Plan::Engine(batch, Then::Succeed)
            }
        }
        Err(c) => Plan::Fail(c),
    }
}

/// §8.3.2: remove the last axis added.
fn remove_axis(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let mut members = cx
        .registers
        .group_members
        .get(&group)
        .cloned()
        .unwrap_or_default();
    if members.pop().is_none() {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_GRP_SIZE_EMPTY"));
    }
    set_members(cx, group, members)
}

/// A group command that names only the group.
fn simple(cx: &mut Ctx<'_>, args: &Args, kind: &str) -> Plan {
    match group_id(args) {
        Ok(group) if status(cx, group).is_some() => engine(json!({"type": kind, "group": group})),
        Ok(group) => Plan::Fail(group_error(group, "eERR_CRD_CMD_GRP_SIZE_EMPTY")),
        Err(c) => Plan::Fail(c),
    }
}

fn line(cx: &mut Ctx<'_>, args: &Args, dims: usize, relative: bool) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let Some(s) = status(cx, group) else {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_GRP_SIZE_EMPTY"));
    };
    let given: Vec<f64> = (1..=dims).map(|i| args.double(i)).collect();
    if usize::from(s.axis_count) < dims || given.iter().any(|v| !v.is_finite()) {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_LIN_INVALID_PARAM"));
    }
    let point = target(s, &given, relative);
    let mut move_ = if relative {
        json!({"type": "move_linear_relative", "group": group, "distance": point})
    } else {
        json!({"type": "move_linear_absolute", "group": group, "position": point})
    };
    modes(cx, group, &mut move_);
    engine(move_)
}

/// An arc in the XY plane: `mode` `center` or `border` through `aux`, to `end`.
fn arc(cx: &mut Ctx<'_>, args: &Args, mode: &str, direction: &str, turns: u32) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let Some(s) = status(cx, group) else {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_GRP_SIZE_EMPTY"));
    };
    let values = [
        args.double(1),
        args.double(2),
        args.double(3),
        args.double(4),
    ];
    if s.axis_count < 2 || values.iter().any(|v| !v.is_finite()) {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_CIRC_INVALID_PARAM"));
    }
    let mut move_ = json!({
        "type": "move_circular_absolute",
        "group": group,
        "mode": mode,
        "aux_point": target(s, &values[..2], false),
        "end_point": target(s, &values[2..], false),
        "direction": direction,
        "turns": turns,
    });
    modes(cx, group, &mut move_);
    engine(move_)
}

/// §8.2.17, TV 45–46: `turns` ≥ 0 CCW, < 0 CW; 0 and ±1 sweep less than a turn, each further
/// unit adds one.
fn circle(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let turns = args.int(5);
    let direction = if turns >= 0 { "ccw" } else { "cw" };
    let extra = u32::try_from(turns.unsigned_abs().saturating_sub(1)).unwrap_or(u32::MAX);
    arc(cx, args, "center", direction, extra)
}

fn group_bool(cx: &mut Ctx<'_>, args: &Args, f: fn(&GroupStatus) -> bool) -> Plan {
    match group_id(args) {
        Ok(group) => Plan::Done(Outcome::bool(status(cx, group).is_some_and(f))),
        Err(c) => Plan::Fail(c),
    }
}

/// §8.3.6, TV 47: the HIMC's ranges, then the engine's group parameters.
fn motion_profile(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let values = ProfileValues {
        velocity: args.double(1),
        acceleration: args.double(2),
        deceleration: args.double(3),
        smooth_ms: args.double(4),
    };
    apply_profile(cx, group, Profile::Linear, values)
}

fn profile_get(cx: &mut Ctx<'_>, args: &Args, field: fn(&ProfileValues) -> f64) -> Plan {
    match group_id(args) {
        Ok(group) => Plan::Done(Outcome::Double(field(&profile_of(cx, group)))),
        Err(c) => Plan::Fail(c),
    }
}

/// §8.3.28: the feed override, 0 ~ 100 %.
fn set_vel_scale(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let scale = args.double(1);
    if !(0.0..=100.0).contains(&scale) {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_INVALID_VEL_SCALE"));
    }
    if status(cx, group).is_none() {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_GRP_SIZE_EMPTY"));
    }
    engine(json!({"type": "group_set_override", "group": group, "factor": scale / 100.0}))
}

/// §8.3.21: the frame later moves are given in (`CS_MCS`, `CS_WCS1 | CS_PCS` …).
fn set_coordinate_system(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let mask = args.int(1);
    let Some(name) = coordinate_system_name(mask) else {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_COORD_SYS_UNKNOWN"));
    };
    if status(cx, group).is_none() {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_GRP_SIZE_EMPTY"));
    }
    cx.registers.group_coordinate_systems.insert(group, mask);
    engine(
        json!({"type": "group_set_coordinate_system", "group": group, "coordinate_system": name}),
    )
}

/// §8.3.32–33: the pose as six values {X, Y, Z, A, B, C} (coordinates beyond the group's
/// axes are 0), in MCS or in the group's own coordinate system; the array reply.
fn pose(cx: &mut Ctx<'_>, args: &Args, feedback: bool) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let Some(s) = status(cx, group) else {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_GRP_SIZE_EMPTY"));
    };
    let mask = args.int(1);
    let own = cx
        .registers
        .group_coordinate_systems
        .get(&group)
        .copied()
        .unwrap_or(0);
    let source: Vec<f64> = match (mask, feedback) {
        (0, false) => s.coordinates.to_vec(),
        (0, true) => s
            .members
            .iter()
            .map(|&a| {
                cx.snapshot
                    .axes
                    .get(usize::from(a))
                    .map_or(0.0, |st| st.act_pos)
            })
            .collect(),
        (m, false) if m == own => s.frame_position.to_vec(),
        _ => return Plan::Fail(group_error(group, "eERR_CRD_CMD_COORD_SYS_UNKNOWN")),
    };
    let mut out = [0.0; 6];
    for (i, v) in out.iter_mut().enumerate().take(usize::from(s.axis_count)) {
        *v = source.get(i).copied().unwrap_or(0.0);
    }
    Plan::Done(Outcome::Array(0, out))
}

pub static ROWS: &[Function] = &[
    unary("EnableGroup", "8.2.1", Ret::Int, Group, |cx, a| {
        simple(cx, a, "group_enable")
    }),
    unary("DisableGroup", "8.2.2", Ret::Int, Group, |cx, a| {
        simple(cx, a, "group_disable")
    }),
    unary("ResetGroup", "8.2.3", Ret::Int, Group, |cx, a| {
        simple(cx, a, "group_reset")
    }),
    unary("StopGroup", "8.2.4", Ret::Int, Group, |cx, a| {
        simple(cx, a, "group_stop")
    }),
    unary("HaltGroup", "8.2.5", Ret::Int, Group, |cx, a| {
        simple(cx, a, "group_halt")
    }),
    unary("ResumeGroup", "8.2.6", Ret::Int, Group, |cx, a| {
        simple(cx, a, "group_continue")
    }),
    row("LineAbs2D", "8.2.9", GDD, Ret::Int, Group, |cx, a| {
        line(cx, a, 2, false)
    }),
    row("LineAbs3D", "8.2.10", GDDD, Ret::Int, Group, |cx, a| {
        line(cx, a, 3, false)
    }),
    row("LineRel2D", "8.2.11", GDD, Ret::Int, Group, |cx, a| {
        line(cx, a, 2, true)
    }),
    row("LineRel3D", "8.2.12", GDDD, Ret::Int, Group, |cx, a| {
        line(cx, a, 3, true)
    }),
    row("Arc2D", "8.2.13", GDDDD, Ret::Int, Group, |cx, a| {
        arc(cx, a, "border", "ccw", 0)
    }),
    row("ArcCW2D", "8.2.14", GDDDD, Ret::Int, Group, |cx, a| {
        arc(cx, a, "center", "cw", 0)
    }),
    row("ArcCCW2D", "8.2.15", GDDDD, Ret::Int, Group, |cx, a| {
        arc(cx, a, "center", "ccw", 0)
    }),
    row(
        "Circle2D",
        "8.2.17",
        &[
            Ty::Int,
            Ty::Double,
            Ty::Double,
            Ty::Double,
            Ty::Double,
            Ty::Int,
        ],
        Ret::Int,
        Group,
        circle,
    ),
    row(
        "AddAxisToGrp",
        "8.3.1",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Group,
        add_axis,
    ),
    unary("RemoveAxisFromGrp", "8.3.2", Ret::Int, Group, remove_axis),
    unary(
        "UngrpAllAxes",
        "8.3.4",
        Ret::Int,
        Group,
        |cx, a| match group_id(a) {
            Ok(group) => set_members(cx, group, Vec::new()),
            Err(c) => Plan::Fail(c),
        },
    ),
    // TV 52: −1 for an axis in no group.
    unary("GetGroupID", "8.3.5", Ret::Int, Axis, |cx, a| {
        let axis = u16::try_from(a.int(0)).unwrap_or(u16::MAX);
        let id = cx
            .registers
            .group_members
            .iter()
            .find(|(_, m)| m.contains(&axis))
            .map_or(-1, |(g, _)| i32::from(*g));
        Plan::Done(Outcome::Int(id))
    }),
    row(
        "SetGrpMotionProfile",
        "8.3.6",
        &[Ty::Int, Ty::Double, Ty::Double, Ty::Double, Ty::Double],
        Ret::Int,
        Group,
        motion_profile,
    ),
    // TV 48: a fresh group's profile is [100, 5000, 5000, 50].
    unary("GetGrpVel", "8.3.10", Ret::Double, Group, |cx, a| {
        profile_get(cx, a, |p| p.velocity)
    }),
    unary("GetGrpAcc", "8.3.12", Ret::Double, Group, |cx, a| {
        profile_get(cx, a, |p| p.acceleration)
    }),
    unary("GetGrpDec", "8.3.15", Ret::Double, Group, |cx, a| {
        profile_get(cx, a, |p| p.deceleration)
    }),
    unary("GetGrpSMTime", "8.3.18", Ret::Double, Group, |cx, a| {
        profile_get(cx, a, |p| p.smooth_ms)
    }),
    unary(
        "GetGrpCmdNum",
        "8.3.27",
        Ret::Int,
        Group,
        |cx, a| match group_id(a) {
            Ok(group) => {
                let used = status(cx, group).map_or(0, |s| s.queue_used);
                Plan::Done(Outcome::Int(i32::try_from(used).unwrap_or(i32::MAX)))
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    unary(
        "GetGrpCoordSys",
        "8.3.20",
        Ret::Int,
        Group,
        |cx, a| match group_id(a) {
            Ok(group) => {
                let mask = cx.registers.group_coordinate_systems.get(&group).copied();
                Plan::Done(Outcome::Int(i32::try_from(mask.unwrap_or(0)).unwrap_or(0)))
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    row(
        "SetGrpCoordSys",
        "8.3.21",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Group,
        set_coordinate_system,
    ),
    row(
        "SetGrpVelScale",
        "8.3.28",
        &[Ty::Int, Ty::Double],
        Ret::Int,
        Group,
        set_vel_scale,
    ),
    unary(
        "GetGrpVelScale",
        "8.3.29",
        Ret::Double,
        Group,
        |cx, a| match group_id(a) {
            Ok(group) => {
                let factor = status(cx, group).map_or(1.0, |s| s.override_factor);
                Plan::Done(Outcome::Double(factor * 100.0))
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    row(
        "GetGrpPoseCmd",
        "8.3.32",
        POSE,
        Ret::Array6,
        Group,
        |cx, a| pose(cx, a, false),
    ),
    row(
        "GetGrpPoseFb",
        "8.3.33",
        POSE,
        Ret::Array6,
        Group,
        |cx, a| pose(cx, a, true),
    ),
    unary("IsGrpEnabled", "8.4.1", Ret::Int, Group, |cx, a| {
        group_bool(cx, a, |s| s.state != GroupState::Disabled)
    }),
    unary("IsGrpMoving", "8.4.2", Ret::Int, Group, |cx, a| {
        group_bool(cx, a, |s| s.state == GroupState::Moving)
    }),
    unary("IsGrpInPos", "8.4.3", Ret::Int, Group, |cx, a| {
        group_bool(cx, a, |s| s.in_position)
    }),
    unary("IsGrpErrorStop", "8.4.4", Ret::Int, Group, |cx, a| {
        group_bool(cx, a, |s| s.state == GroupState::ErrorStop)
    }),
];
