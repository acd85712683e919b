//! What the chapter 8 handlers share (`functions::group`, `functions::group_settings`): the
//! group an argument names, its status and error codes, the controller's view of its profile
//! and modes, and the batch that (re-)creates the engine group with them.

use axes::command::GroupParameter;
use axes::status::GroupStatus;
use axes::Command;
use mcemu_dialects::himc::group::{self as profile, Profile, ProfileValues};
use mcemu_dialects::himc::group_errors::GroupErrorRow;
use mcemu_dialects::himc::system::{HMPL_ARG_OUT_OF_RANGE, HMPL_INTERNAL_ERROR};
use serde_json::{json, Value};

use crate::registers::TransitionParameters;
use crate::reply::Outcome;
use crate::table::{Args, Ctx, Plan, Then};

pub(super) fn group_id(args: &Args) -> Result<u16, u32> {
    u16::try_from(args.int(0)).map_err(|_| HMPL_ARG_OUT_OF_RANGE)
}

pub(super) fn group_error(group: u16, name: &str) -> u32 {
    GroupErrorRow::by_name(name).map_or(HMPL_INTERNAL_ERROR, |e| {
        e.error().code(u8::try_from(group).unwrap_or(u8::MAX))
    })
}

pub(super) fn status<'a>(cx: &'a Ctx<'_>, group: u16) -> Option<&'a GroupStatus> {
    cx.snapshot.groups.iter().find(|g| g.group == group)
}

pub(super) fn command(value: Value) -> Result<Command, u32> {
    serde_json::from_value(value).map_err(|_| HMPL_INTERNAL_ERROR)
}

/// The batch that makes the engine's group `group` have `members` (none: no group), with its
/// motion profile.
pub(super) fn regroup(cx: &Ctx<'_>, group: u16, members: &[u16]) -> Result<Vec<Command>, u32> {
    let mut batch = Vec::new();
    if status(cx, group).is_some() {
        batch.push(command(json!({"type": "group_delete", "group": group}))?);
    }
    if !members.is_empty() {
        // A, B, C (the 4th to 6th axes added) are orientation angles (§8.1, §8.3.7).
        let orientation: Vec<usize> = (3..members.len().min(6)).collect();
        let mut create = json!({"type": "group_create", "group": group, "axes": members});
        if !orientation.is_empty() {
            create["orientation"] = json!(orientation);
        }
        if let Some(n) = cx.registers.group_queue_sizes.get(&group) {
            create["queue_capacity"] = json!(1u32 << n);
        }
        batch.push(command(create)?);
        let values = profile_of(cx, group);
        let angular = angular_of(cx, group);
        for (name, value) in profile::parameters(Profile::Linear, &values)
            .into_iter()
            .chain(profile::parameters(Profile::Angular, &angular))
        {
            batch.push(command(json!({
                "type": "group_set_parameter", "group": group, "name": name, "value": value,
            }))?);
        }
        for (name, value) in lookahead_of(cx, group) {
            batch.push(command(json!({
                "type": "group_set_parameter", "group": group, "name": name, "value": value,
            }))?);
        }
    }
    Ok(batch)
}

pub(super) fn profile_of(cx: &Ctx<'_>, group: u16) -> ProfileValues {
    cx.registers
        .group_profiles
        .get(&group)
        .copied()
        .unwrap_or(profile::defaults(Profile::Linear))
}

/// The group's coordinates, the first `given` replaced (absolute) or added to (relative).
pub(super) fn target(s: &GroupStatus, given: &[f64], relative: bool) -> Vec<f64> {
    let n = usize::from(s.axis_count);
    (0..n)
        .map(|i| match given.get(i) {
            Some(&v) => v,
            None if relative => 0.0,
            None => s.coordinates.get(i).copied().unwrap_or(0.0),
        })
        .collect()
}

pub(super) fn byte(group: u16) -> u8 {
    u8::try_from(group).unwrap_or(u8::MAX)
}

/// The angular profile (absent: the defaults, TV 49).
pub(super) fn angular_of(cx: &Ctx<'_>, group: u16) -> ProfileValues {
    cx.registers
        .group_angular_profiles
        .get(&group)
        .copied()
        .unwrap_or(profile::defaults(Profile::Angular))
}

/// The HCV addresses of a profile's velocity, acceleration and deceleration limits
/// (Table 17.1.1.3: `grp_lin_vel_lim` …, `grp_ang_vel_lim` …).
pub(super) const fn limit_addresses(which: Profile) -> [u16; 3] {
    match which {
        Profile::Linear => [0x00ca, 0x00cb, 0x00cc],
        Profile::Angular => [0x00d4, 0x00d5, 0x00d6],
    }
}

/// The group's limits on a profile: as `SetConfigVar` set them, else the manual's maxima.
pub(super) fn limits_of(cx: &Ctx<'_>, group: u16, which: Profile) -> [f64; 3] {
    let maxima = profile::maxima(which);
    let addresses = limit_addresses(which);
    std::array::from_fn(|k| {
        cx.registers
            .group_limits
            .get(&(group, addresses[k]))
            .copied()
            .unwrap_or(maxima[k])
    })
}

/// The look-ahead parameters set (§8.3.34), as engine group parameters.
pub(super) fn lookahead_of(cx: &Ctx<'_>, group: u16) -> Vec<(GroupParameter, f64)> {
    cx.registers
        .group_lookahead
        .range((group, 0)..=(group, u8::MAX))
        .filter_map(|(&(_, id), &v)| Some((lookahead_parameter(id)?, v)))
        .collect()
}

pub(super) fn lookahead_parameter(id: u8) -> Option<GroupParameter> {
    match id {
        0 => Some(GroupParameter::CornerAcceleration),
        1 => Some(GroupParameter::ArcAcceleration),
        2 => Some(GroupParameter::ChordError),
        _ => None,
    }
}

/// The group's buffer and transition modes (§8.3.23, §8.3.25) on a move's JSON.
pub(super) fn modes(cx: &Ctx<'_>, group: u16, move_: &mut Value) {
    let bm = cx.registers.group_buffer_modes.get(&group).copied();
    let buffer_mode = match bm.unwrap_or(0) {
        1 => "aborting",
        2 => "blending_low",
        3 => "blending_previous",
        4 => "blending_next",
        5 => "blending_high",
        _ => "buffered",
    };
    let p = transition_parameters(cx, group);
    let transition = match cx.registers.group_transition_modes.get(&group) {
        Some(3) => json!({"corner_distance": p.distance}),
        Some(4) => json!({"corner_deviation": p.deviation}),
        _ => json!("none"),
    };
    move_["buffer_mode"] = json!(buffer_mode);
    move_["transition"] = transition;
}

/// The transition parameters as set (§8.3.26; never set: 0 each, which a move takes only with
/// a transition mode that uses them).
pub(super) fn transition_parameters(cx: &Ctx<'_>, group: u16) -> TransitionParameters {
    cx.registers
        .group_transition_parameters
        .get(&group)
        .copied()
        .unwrap_or_default()
}

/// Check, keep and (for an existing group) send a profile (§8.3.6–8.3.7, TV 47, 49).
pub(super) fn apply_profile(
    cx: &mut Ctx<'_>,
    group: u16,
    which: Profile,
    values: ProfileValues,
) -> Plan {
    if let Err(e) = profile::check_within(which, &values, limits_of(cx, group, which)) {
        return Plan::Fail(e.code(byte(group)));
    }
    match which {
        Profile::Linear => cx.registers.group_profiles.insert(group, values),
        Profile::Angular => cx.registers.group_angular_profiles.insert(group, values),
    };
    if status(cx, group).is_none() {
        return Plan::Done(Outcome::Int(0));
    }
    let batch: Result<Vec<_>, u32> = profile::parameters(which, &values)
        .into_iter()
        .map(|(name, value)| {
            command(json!({"type": "group_set_parameter", "group": group, "name": name, "value": value}))
        })
        .collect();
    match batch {
        Ok(b) => Plan::Engine(b, Then::Succeed),
        Err(c) => Plan::Fail(c),
    }
}
