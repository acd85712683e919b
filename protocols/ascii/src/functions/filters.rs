//! Chapter 15, command filters (digest 004 §2.14; TV 64–66) through the engine's command
//! filters (`filter_input_shaping`, `filter_vsf`, `filter_disable`). The setters check the
//! manual's ranges and keep the values (a filter already on is re-installed with them);
//! `Enable*` installs the filter, `Disable*` removes it. VSF and InShape exclude each other
//! (§2.14): enabling one while the other is on is refused. `SetGrpInShape`/`EnableGrpInShape`
//! put the shaper in the group slot of each member, and a member added later gets it too
//! (`follow_members`): the engine uses it while the axis is in a group, and the axis slot
//! otherwise (§2.14: "Axis InShape has no effect on coordinated (group) motion"). Never-set
//! shapers use the manual's defaults, 5.5 Hz and 0.03, `SHAPER_NORMAL`.

use axes::status::AxisFlags;
use serde_json::{json, Value};

use super::group_state::{command, group_error, group_id};
use super::{axis_error, axis_of};
use crate::registers::{Filter, FilterSettings};
use crate::reply::Outcome;
use crate::table::{
    row, unary, Addresses::Axis, Addresses::Group, Args, Ctx, Function, Plan, Ret, Ty,
};

/// §15.7, §15.10: the defaults of a shaper never set.
const DEFAULT_SHAPER: FilterSettings = FilterSettings {
    frequency: 5.5,
    damping: 0.03,
    shaper: Some(1),
};

impl Filter {
    /// §15.4: 0.1 ~ 200 Hz, 0.7 ~ 1.5; §15.7: 1.5 ~ 300 Hz, 0 ~ 0.3; §15.10: 3 ~ 300 Hz, 0 ~ 0.3.
    fn ranges(self) -> ((f64, f64), (f64, f64)) {
        match self {
            Filter::AxisVsf => ((0.1, 200.0), (0.7, 1.5)),
            Filter::AxisInShape => ((1.5, 300.0), (0.0, 0.3)),
            Filter::GroupInShape => ((3.0, 300.0), (0.0, 0.3)),
        }
    }
}

/// The engine's shaper for `SHAPER_NORMAL` 1 (ZV) and `SHAPER_ROBUST` 0 (ZVD).
fn shaper_name(shaper: Option<i64>) -> &'static str {
    match shaper {
        Some(0) => "zvd",
        _ => "zv",
    }
}

/// The engine commands that put `filter` of `id` on, with its settings.
fn install(cx: &Ctx<'_>, filter: Filter, id: u16) -> Result<Vec<Value>, u32> {
    let stored = cx.registers.filters.get(&(filter, id)).copied();
    let s = match (filter, stored) {
        (_, Some(s)) => s,
        (Filter::AxisVsf, None) => {
            // §15.4 gives no default frequency: a VSF never set cannot be switched on.
            return Err(axis_error(id, "eERR_AXIS_CMD_INVALID_PARAMETER"));
        }
        (_, None) => DEFAULT_SHAPER,
    };
    Ok(match filter {
        Filter::AxisVsf => vec![json!({
            "type": "filter_vsf", "axis": id, "frequency": s.frequency, "damping": s.damping,
        })],
        Filter::AxisInShape => vec![json!({
            "type": "filter_input_shaping", "axis": id, "shaper": shaper_name(s.shaper),
            "frequency": s.frequency, "damping": s.damping, "slot": "axis",
        })],
        Filter::GroupInShape => members(cx, id)
            .iter()
            .map(|&axis| group_shaper(axis, &s))
            .collect(),
    })
}

/// The group's InShape settings: as set, else the manual's defaults (§15.10).
pub(super) fn group_shaper_settings(cx: &Ctx<'_>, group: u16) -> FilterSettings {
    cx.registers
        .filters
        .get(&(Filter::GroupInShape, group))
        .copied()
        .unwrap_or(DEFAULT_SHAPER)
}

/// The group's shaper `s` in `axis`'s group slot.
fn group_shaper(axis: u16, s: &FilterSettings) -> Value {
    json!({
        "type": "filter_input_shaping", "axis": axis, "shaper": shaper_name(s.shaper),
        "frequency": s.frequency, "damping": s.damping, "slot": "group",
    })
}

fn drop_group_shaper(axis: u16) -> Value {
    json!({"type": "filter_disable", "axis": axis, "slot": "group"})
}

/// The engine commands that keep a group's InShape on its members when they change
/// (`AddAxisToGrp`, `RemoveAxisFromGrp`, `UngrpAllAxes`): an axis that joins gets the shaper,
/// one that leaves loses it (decisions.md, "Command filters after smoothing"). Nothing while
/// the group's InShape is off.
pub(super) fn follow_members(cx: &Ctx<'_>, group: u16, new: &[u16]) -> Vec<Value> {
    if !cx
        .registers
        .filters_on
        .contains(&(Filter::GroupInShape, group))
    {
        return Vec::new();
    }
    let s = group_shaper_settings(cx, group);
    let old = members(cx, group);
    let left = old.iter().filter(|a| !new.contains(a));
    let joined = new.iter().filter(|a| !old.contains(a));
    left.map(|&a| drop_group_shaper(a))
        .chain(joined.map(|&a| group_shaper(a, &s)))
        .collect()
}

fn members(cx: &Ctx<'_>, group: u16) -> Vec<u16> {
    cx.registers
        .group_members
        .get(&group)
        .cloned()
        .unwrap_or_default()
}

/// The engine commands that take `filter` of `id` off.
fn remove(cx: &Ctx<'_>, filter: Filter, id: u16) -> Vec<Value> {
    match filter {
        Filter::GroupInShape => members(cx, id)
            .iter()
            .map(|&axis| drop_group_shaper(axis))
            .collect(),
        _ => vec![json!({"type": "filter_disable", "axis": id, "slot": "axis"})],
    }
}

fn batch(commands: Vec<Value>) -> Plan {
    if commands.is_empty() {
        return Plan::Done(Outcome::Int(0));
    }
    match commands.into_iter().map(command).collect() {
        Ok(b) => Plan::Engine(b, crate::table::Then::Succeed),
        Err(c) => Plan::Fail(c),
    }
}

fn id_of(cx: &Ctx<'_>, args: &Args, filter: Filter) -> Result<u16, u32> {
    match filter {
        Filter::GroupInShape => group_id(args),
        _ => axis_of(cx, args).map(|(a, _)| a),
    }
}

/// §2.14: "not applicable while the motor is moving": the axis, or any member of the group.
fn moving(cx: &Ctx<'_>, filter: Filter, id: u16) -> Option<u32> {
    let is_moving = |axis: u16| {
        cx.snapshot
            .axes
            .get(usize::from(axis))
            .is_some_and(|s| s.flags.contains(AxisFlags::MOVING))
    };
    match filter {
        Filter::GroupInShape => members(cx, id)
            .into_iter()
            .any(is_moving)
            .then(|| group_error(id, "eERR_CRD_CMD_INVALID_MOVING")),
        _ => is_moving(id).then(|| axis_error(id, "eERR_AXIS_CMD_INVALID_MOVING")),
    }
}

fn set(cx: &mut Ctx<'_>, args: &Args, filter: Filter) -> Plan {
    let id = match id_of(cx, args, filter) {
        Ok(i) => i,
        Err(c) => return Plan::Fail(c),
    };
    let ((f_lo, f_hi), (d_lo, d_hi)) = filter.ranges();
    let (frequency, damping) = (args.double(1), args.double(2));
    let shaper = (filter != Filter::AxisVsf).then(|| args.int(3));
    let fail = |axis_name: &str, group_name: &str| match filter {
        Filter::GroupInShape => Plan::Fail(group_error(id, group_name)),
        _ => Plan::Fail(axis_error(id, axis_name)),
    };
    if !(f_lo..=f_hi).contains(&frequency) {
        return fail(
            "eERR_AXIS_FREQUENCY_LIMIT",
            "eERR CRD_CMD_INVALID_FREQUENCY",
        );
    }
    if !(d_lo..=d_hi).contains(&damping) {
        return fail(
            "eERR_AXIS_DAMPINGRATIO_LIMIT",
            "eERR_CRD_CMD_INVALID_DAMPINGRATIO",
        );
    }
    if shaper.is_some_and(|s| !matches!(s, 0 | 1)) {
        return fail(
            "eERR_AXIS_CMD_INVALID_PARAMETER",
            "eERR_CRD_CMD_INVALID_INPUTSHAPING_PARAMETER_INCOMPLETE",
        );
    }
    let on = cx.registers.filters_on.contains(&(filter, id));
    if let Some(c) = moving(cx, filter, id).filter(|_| on) {
        return Plan::Fail(c);
    }
    cx.registers.filters.insert(
        (filter, id),
        FilterSettings {
            frequency,
            damping,
            shaper,
        },
    );
    if !on {
        return Plan::Done(Outcome::Int(0));
    }
    match install(cx, filter, id) {
        Ok(commands) => batch(commands),
        Err(c) => Plan::Fail(c),
    }
}

/// `Enable*` installs the filter, `Disable*` removes it (a filter that is off: nothing to do).
fn switch(cx: &mut Ctx<'_>, args: &Args, filter: Filter, on: bool) -> Plan {
    let id = match id_of(cx, args, filter) {
        Ok(i) => i,
        Err(c) => return Plan::Fail(c),
    };
    if let Some(c) = moving(cx, filter, id) {
        return Plan::Fail(c);
    }
    if !on {
        if !cx.registers.filters_on.remove(&(filter, id)) {
            return Plan::Done(Outcome::Int(0));
        }
        return batch(remove(cx, filter, id));
    }
    // §2.14: VSF and InShape are mutually exclusive.
    let other = match filter {
        Filter::AxisVsf => Some((
            Filter::AxisInShape,
            "eERR_AXIS_CMD_INVALID_INPUTSHAPING_ENABLED",
        )),
        Filter::AxisInShape => Some((Filter::AxisVsf, "eERR_AXIS_CMD_INVALID_PARAMETER")),
        Filter::GroupInShape => None,
    };
    if let Some((other, error)) = other {
        if cx.registers.filters_on.contains(&(other, id)) {
            return Plan::Fail(axis_error(id, error));
        }
    }
    match install(cx, filter, id) {
        Ok(commands) => {
            cx.registers.filters_on.insert((filter, id));
            batch(commands)
        }
        Err(c) => Plan::Fail(c),
    }
}

const SHAPER: &[Ty] = &[Ty::Int, Ty::Double, Ty::Double, Ty::Int];

pub static ROWS: &[Function] = &[
    unary("EnableAxisVsf", "15.2", Ret::Int, Axis, |cx, a| {
        switch(cx, a, Filter::AxisVsf, true)
    }),
    unary("DisableAxisVsf", "15.3", Ret::Int, Axis, |cx, a| {
        switch(cx, a, Filter::AxisVsf, false)
    }),
    // TV 65.
    row(
        "SetAxisVsf",
        "15.4",
        &[Ty::Int, Ty::Double, Ty::Double],
        Ret::Int,
        Axis,
        |cx, a| set(cx, a, Filter::AxisVsf),
    ),
    unary("EnableAxisInShape", "15.5", Ret::Int, Axis, |cx, a| {
        switch(cx, a, Filter::AxisInShape, true)
    }),
    unary("DisableAxisInShape", "15.6", Ret::Int, Axis, |cx, a| {
        switch(cx, a, Filter::AxisInShape, false)
    }),
    // TV 64.
    row("SetAxisInShape", "15.7", SHAPER, Ret::Int, Axis, |cx, a| {
        set(cx, a, Filter::AxisInShape)
    }),
    unary("EnableGrpInShape", "15.8", Ret::Int, Group, |cx, a| {
        switch(cx, a, Filter::GroupInShape, true)
    }),
    unary("DisableGrpInShape", "15.9", Ret::Int, Group, |cx, a| {
        switch(cx, a, Filter::GroupInShape, false)
    }),
    // TV 66.
    row(
        "SetGrpInShape",
        "15.10",
        SHAPER,
        Ret::Int,
        Group,
        |cx, a| set(cx, a, Filter::GroupInShape),
    ),
];
