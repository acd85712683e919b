//! Chapter 8, the group settings and motions beyond `functions::group` (digest 004 §2.7,
//! §8.2.7–8.2.8, §8.2.16, §8.3.7–8.3.35; TV 44, 49, 53–54, 56–57): jogs, `ArcAngle2D`, the
//! angular profile, the profile's single setters, kinematics, buffer and transition modes,
//! coordinate transforms, look-ahead and queue size. Settings the engine keeps per motion (the
//! modes) or per group creation (queue size) are held in `Registers` and sent with each move
//! or each re-creation of the group.

use axes::status::GroupState;
use mcemu_dialects::himc::constants::{CS_OFFSET, CS_PCS, CS_WCS_SHIFT};
use mcemu_dialects::himc::group::{Profile, ProfileValues};
use serde_json::json;

use super::engine;
use super::group_state::{
    apply_profile, command, group_error, group_id, lookahead_parameter, modes, profile_of, regroup,
    status, target, transition_parameters,
};
use crate::registers::TransitionParameters;
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Group, Args, Ctx, Function, Plan, Ret, Then, Ty};

const GD: &[Ty] = &[Ty::Int, Ty::Double];
const GI: &[Ty] = &[Ty::Int, Ty::Int];
const GID: &[Ty] = &[Ty::Int, Ty::Int, Ty::Double];
const GDDDD: &[Ty] = &[Ty::Int, Ty::Double, Ty::Double, Ty::Double, Ty::Double];

/// §8.1.3: the one kinematics mcemu's groups have, Cartesian (id 1, the default).
const KIN_CARTESIAN: i64 = 1;

/// One value of the linear profile changed (§8.3.11–8.3.19).
fn set_one(cx: &mut Ctx<'_>, args: &Args, change: fn(&mut ProfileValues, f64) -> bool) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let mut values = profile_of(cx, group);
    if !change(&mut values, args.double(1)) {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_INVALID_LIN_ACC"));
    }
    apply_profile(cx, group, Profile::Linear, values)
}

/// A time in ms (> 0) as the acceleration that reaches the profile velocity in it.
fn by_time(values: &ProfileValues, ms: f64) -> Option<f64> {
    (ms.is_finite() && ms > 0.0).then(|| values.velocity / (ms / 1000.0))
}

fn existing(cx: &Ctx<'_>, args: &Args) -> Result<u16, u32> {
    let group = group_id(args)?;
    match status(cx, group) {
        Some(_) => Ok(group),
        None => Err(group_error(group, "eERR_CRD_CMD_GRP_SIZE_EMPTY")),
    }
}

/// §8.2.7, TV 54: jog along X … C of the MCS (`carte_dir` 0 ~ 5).
fn jog(cx: &mut Ctx<'_>, args: &Args, per_axis: bool) -> Plan {
    let group = match existing(cx, args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let count = status(cx, group).map_or(0, |s| usize::from(s.axis_count));
    let velocity = args.double(2);
    let which = usize::try_from(args.int(1)).ok();
    let valid = match which {
        Some(i) if per_axis => i < count,
        Some(i) => i < 6.min(count),
        None => false,
    };
    if !valid || !velocity.is_finite() {
        let name = if per_axis {
            "eERR_CRD_CMD_GRP_AXIS_INVALID"
        } else {
            "eERR_CRD_CMD_COORD_INVALID_PARAM"
        };
        return Plan::Fail(group_error(group, name));
    }
    let i = which.unwrap_or(0);
    if per_axis {
        engine(json!({"type": "group_jog_axis", "group": group, "member": i, "velocity": velocity}))
    } else {
        engine(json!({
            "type": "group_jog", "group": group, "coordinate": i, "velocity": velocity,
            "coordinate_system": "mcs",
        }))
    }
}

/// §8.2.16, TV 44: an arc about a centre through `angle` degrees (> 0 CCW).
fn arc_angle(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match existing(cx, args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let Some(s) = status(cx, group) else {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_GRP_SIZE_EMPTY"));
    };
    let (cx_, cy, angle) = (args.double(1), args.double(2), args.double(3));
    if s.axis_count < 2 || ![cx_, cy, angle].iter().all(|v| v.is_finite()) || angle == 0.0 {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_CIRC_INVALID_PARAM"));
    }
    let mut move_ = json!({
        "type": "move_circular_angle", "group": group,
        "center": target(s, &[cx_, cy], false), "angle": angle,
    });
    modes(cx, group, &mut move_);
    engine(move_)
}

/// The one link of the frame chain a `CS_*` mask names (§8.3.30–31): `CS_OFFSET`, `CS_WCSn`
/// or `CS_PCS` alone.
fn frame_name(mask: i64) -> Option<String> {
    let wcs = mask >> CS_WCS_SHIFT;
    match mask {
        CS_PCS => Some("pcs".into()),
        CS_OFFSET => Some("offset".into()),
        m if m & 0xf == 0 && (1..=15).contains(&wcs) => Some(format!("wcs{wcs}")),
        _ => None,
    }
}

/// §8.3.31, TV 56: place a frame; kept for `GetGrpCoordTrans` (TV 57).
fn set_transform(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match existing(cx, args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let mask = args.int(1);
    let Some(frame) = frame_name(mask) else {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_COORD_SYS_UNKNOWN"));
    };
    let pose = args.array(2);
    if pose.iter().any(|v| !v.is_finite()) {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_COORD_INVALID_PARAM"));
    }
    cx.registers.group_transforms.insert((group, mask), pose);
    engine(json!({
        "type": "group_set_coordinate_transform", "group": group, "frame": frame, "pose": pose,
    }))
}

fn get_transform(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let mask = args.int(1);
    if frame_name(mask).is_none() {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_COORD_SYS_UNKNOWN"));
    }
    let pose = cx
        .registers
        .group_transforms
        .get(&(group, mask))
        .copied()
        .unwrap_or([0.0; 6]);
    Plan::Done(Outcome::Array(0, pose))
}

/// §8.3.26, Table 8.3.26.1: each > 0; trans_vel < 5000, trans_curv < 10⁷ (the bounds that
/// depend on the corner are the planner's). In `TransitionParameters` order: the bound and
/// the error.
const TRANSITION_CHECKS: [(f64, &str); 4] = [
    (5000.0, "eERR_CRD_CMD_INVALID_TRANS_VEL"),
    (f64::MAX, "eERR_CRD_CMD_INVALID_TRANS_DIS"),
    (f64::MAX, "eERR_CRD_CMD_INVALID_TRANS_DEV"),
    (1e7, "eERR_CRD_CMD_INVALID_TRANS_CURVE"),
];

impl TransitionParameters {
    fn values(&self) -> [f64; 4] {
        [self.velocity, self.distance, self.deviation, self.curvature]
    }

    fn from_values([velocity, distance, deviation, curvature]: [f64; 4]) -> Self {
        TransitionParameters {
            velocity,
            distance,
            deviation,
            curvature,
        }
    }
}

/// The error of transition parameter `k` (`TransitionParameters` order) for `value`, if out of
/// range.
fn transition_error(group: u16, k: usize, value: f64) -> Option<u32> {
    let (max, name) = TRANSITION_CHECKS[k];
    (!(value.is_finite() && value > 0.0 && value < max)).then(|| group_error(group, name))
}

fn set_transition_parameters(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let values: [f64; 4] = std::array::from_fn(|k| args.double(k + 1));
    if let Some(c) = (0..4).find_map(|k| transition_error(group, k, values[k])) {
        return Plan::Fail(c);
    }
    cx.registers
        .group_transition_parameters
        .insert(group, TransitionParameters::from_values(values));
    Plan::Done(Outcome::Int(0))
}

/// One transition parameter (`k` in `TransitionParameters` order; `SetConfigVar` of
/// `grp_trans_vel` … `grp_trans_curvature`), checked as §8.3.26 checks it; the others keep
/// their values.
pub(super) fn set_transition_parameter(cx: &mut Ctx<'_>, group: u16, k: usize, value: f64) -> Plan {
    if let Some(c) = transition_error(group, k, value) {
        return Plan::Fail(c);
    }
    let mut values = transition_parameters(cx, group).values();
    values[k] = value;
    cx.registers
        .group_transition_parameters
        .insert(group, TransitionParameters::from_values(values));
    Plan::Done(Outcome::Int(0))
}

/// §8.3.35, TV 53: 2ⁿ entries, n 0 ~ 10, with the queue empty; an existing group is re-created
/// with it (enabled again if it was).
fn set_queue_size(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let group = match group_id(args) {
        Ok(g) => g,
        Err(c) => return Plan::Fail(c),
    };
    let n = match u8::try_from(args.int(1)) {
        Ok(n) if n <= 10 => n,
        _ => return Plan::Fail(group_error(group, "eERR_CRD_CMD_INVALID_QUEUE_SIZE")),
    };
    let (busy, enabled) = status(cx, group).map_or((false, false), |s| {
        (
            s.queue_used > 0 || s.state == GroupState::Moving,
            s.state != GroupState::Disabled,
        )
    });
    if busy {
        return Plan::Fail(group_error(group, "eERR_CRD_CMD_QUEUE_IS_NOT_EMPTY"));
    }
    cx.registers.group_queue_sizes.insert(group, n);
    let Some(members) = cx.registers.group_members.get(&group).cloned() else {
        return Plan::Done(Outcome::Int(0));
    };
    match regroup(cx, group, &members) {
        Ok(mut batch) => {
            if enabled {
                match command(json!({"type": "group_enable", "group": group})) {
                    Ok(c) => batch.push(c),
                    Err(c) => return Plan::Fail(c),
                }
            }
            Plan::Engine(batch, Then::Succeed)
        }
        Err(c) => Plan::Fail(c),
    }
}

fn int_register(cx: &mut Ctx<'_>, args: &Args, get: fn(&Ctx<'_>, u16) -> i64) -> Plan {
    match group_id(args) {
        Ok(g) => Plan::Done(Outcome::Int(i32::try_from(get(cx, g)).unwrap_or(0))),
        Err(c) => Plan::Fail(c),
    }
}

pub static ROWS: &[Function] = &[
    row("JogGroup", "8.2.7", GID, Ret::Int, Group, |cx, a| {
        jog(cx, a, false)
    }),
    row("JogGroupAxis", "8.2.8", GID, Ret::Int, Group, |cx, a| {
        jog(cx, a, true)
    }),
    row(
        "ArcAngle2D",
        "8.2.16",
        &[Ty::Int, Ty::Double, Ty::Double, Ty::Double],
        Ret::Int,
        Group,
        arc_angle,
    ),
    // TV 49.
    row(
        "SetGrpAngMotionProfile",
        "8.3.7",
        GDDDD,
        Ret::Int,
        Group,
        |cx, a| match group_id(a) {
            Ok(g) => {
                let values = ProfileValues {
                    velocity: a.double(1),
                    acceleration: a.double(2),
                    deceleration: a.double(3),
                    smooth_ms: a.double(4),
                };
                apply_profile(cx, g, Profile::Angular, values)
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    unary("GetGrpKin", "8.3.8", Ret::Int, Group, |cx, a| {
        int_register(cx, a, |_, _| KIN_CARTESIAN)
    }),
    // Only the Cartesian kinematics: another id is eERR_CRD_CMD_INVALID_KIN_SETTING.
    row(
        "SetGrpKin",
        "8.3.9",
        GI,
        Ret::Int,
        Group,
        |_, a| match group_id(a) {
            Ok(_) if a.int(1) == KIN_CARTESIAN => Plan::Done(Outcome::Int(0)),
            Ok(g) => Plan::Fail(group_error(g, "eERR_CRD_CMD_INVALID_KIN_SETTING")),
            Err(c) => Plan::Fail(c),
        },
    ),
    row(
        "SetGrpVel",
        "8.3.11",
        GD,
        Ret::Int,
        Group,
        |cx, a| match group_id(a) {
            Ok(g) => {
                let mut values = profile_of(cx, g);
                values.velocity = a.double(1);
                apply_profile(cx, g, Profile::Linear, values)
            }
            Err(c) => Plan::Fail(c),
        },
    ),
    row("SetGrpAcc", "8.3.13", GD, Ret::Int, Group, |cx, a| {
        set_one(cx, a, |p, v| {
            p.acceleration = v;
            true
        })
    }),
    row("SetGrpAccTime", "8.3.14", GD, Ret::Int, Group, |cx, a| {
        set_one(cx, a, |p, ms| {
            by_time(p, ms).map(|acc| p.acceleration = acc).is_some()
        })
    }),
    row("SetGrpDec", "8.3.16", GD, Ret::Int, Group, |cx, a| {
        set_one(cx, a, |p, v| {
            p.deceleration = v;
            true
        })
    }),
    row("SetGrpDecTime", "8.3.17", GD, Ret::Int, Group, |cx, a| {
        set_one(cx, a, |p, ms| {
            by_time(p, ms).map(|dec| p.deceleration = dec).is_some()
        })
    }),
    row("SetGrpSMTime", "8.3.19", GD, Ret::Int, Group, |cx, a| {
        set_one(cx, a, |p, v| {
            p.smooth_ms = v;
            true
        })
    }),
    unary("GetGrpBufferMode", "8.3.22", Ret::Int, Group, |cx, a| {
        int_register(cx, a, |cx, g| {
            cx.registers
                .group_buffer_modes
                .get(&g)
                .copied()
                .unwrap_or(0)
        })
    }),
    // BM_BUFF … BM_HIGH (0 ~ 5); the group's later moves join with it.
    row(
        "SetGrpBufferMode",
        "8.3.23",
        GI,
        Ret::Int,
        Group,
        |cx, a| match group_id(a) {
            Ok(g) if (0..=5).contains(&a.int(1)) => {
                cx.registers.group_buffer_modes.insert(g, a.int(1));
                Plan::Done(Outcome::Int(0))
            }
            Ok(g) => Plan::Fail(group_error(g, "eERR_CRD_CMD_BLEND_MODE_UNKNOWN")),
            Err(c) => Plan::Fail(c),
        },
    ),
    unary("GetGrpTransMode", "8.3.24", Ret::Int, Group, |cx, a| {
        int_register(cx, a, |cx, g| {
            cx.registers
                .group_transition_modes
                .get(&g)
                .copied()
                .unwrap_or(0)
        })
    }),
    // TM_NONE, TM_CORNER_DIST, TM_MAX_CORNER_DEV: the engine's transitions. TM_START_VEL and
    // TM_CONST_VEL have no engine counterpart: refused (decisions.md).
    row(
        "SetGrpTransMode",
        "8.3.25",
        GI,
        Ret::Int,
        Group,
        |cx, a| match group_id(a) {
            Ok(g) if matches!(a.int(1), 0 | 3 | 4) => {
                cx.registers.group_transition_modes.insert(g, a.int(1));
                Plan::Done(Outcome::Int(0))
            }
            Ok(g) => Plan::Fail(group_error(g, "eERR_CRD_CMD_TRANS_MODE_UNKNOWN")),
            Err(c) => Plan::Fail(c),
        },
    ),
    row(
        "SetGrpTransPrm",
        "8.3.26",
        GDDDD,
        Ret::Int,
        Group,
        set_transition_parameters,
    ),
    row(
        "GetGrpCoordTrans",
        "8.3.30",
        &[Ty::Int, Ty::Int, Ty::OutArray6],
        Ret::Array6,
        Group,
        get_transform,
    ),
    row(
        "SetGrpCoordTrans",
        "8.3.31",
        &[Ty::Int, Ty::Int, Ty::Array6],
        Ret::Int,
        Group,
        set_transform,
    ),
    // prm_id 0 corner max acc, 1 arc max acc, 2 max chord error; each ≥ 0 (0 = off).
    row(
        "SetGrpLookAheadPrm",
        "8.3.34",
        GID,
        Ret::Int,
        Group,
        |cx, a| {
            let group = match group_id(a) {
                Ok(g) => g,
                Err(c) => return Plan::Fail(c),
            };
            let value = a.double(2);
            let id = u8::try_from(a.int(1))
                .ok()
                .filter(|&i| lookahead_parameter(i).is_some());
            let Some(id) = id.filter(|_| value.is_finite() && value >= 0.0) else {
                return Plan::Fail(group_error(group, "eERR_CRD_CMD_LOOKAHEAD_INVALID_PARAM"));
            };
            cx.registers.group_lookahead.insert((group, id), value);
            match (status(cx, group), lookahead_parameter(id)) {
                (Some(_), Some(name)) => engine(json!({
                    "type": "group_set_parameter", "group": group, "name": name, "value": value,
                })),
                _ => Plan::Done(Outcome::Int(0)),
            }
        },
    ),
    row(
        "SetGrpQueueSize",
        "8.3.35",
        GI,
        Ret::Int,
        Group,
        set_queue_size,
    ),
];
