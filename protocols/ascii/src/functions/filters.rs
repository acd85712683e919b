//! Chapter 15, command filters (digest 004 §2.14; TV 64–66). The engine has no vibration
//! suppression filter (VSF) and no input shaper, so the setters check the manual's ranges and
//! keep the values, the `Disable*` functions succeed (the filter is off), and the `Enable*`
//! functions answer `eERR_HMPL_NOT_SUPPORTED` rather than pretend (decisions.md).

use mcemu_dialects::himc::system::HMPL_NOT_SUPPORTED;

use super::group_state::{group_error, group_id};
use super::{axis_error, axis_of};
use crate::registers::{Filter, FilterSettings};
use crate::reply::Outcome;
use crate::table::{row, Addresses::Axis, Addresses::Group, Args, Ctx, Function, Plan, Ret, Ty};

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

fn set(cx: &mut Ctx<'_>, args: &Args, filter: Filter) -> Plan {
    let id = match filter {
        Filter::GroupInShape => group_id(args),
        _ => axis_of(cx, args).map(|(a, _)| a),
    };
    let id = match id {
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
    cx.registers.filters.insert(
        (filter, id),
        FilterSettings {
            frequency,
            damping,
            shaper,
        },
    );
    Plan::Done(Outcome::Int(0))
}

/// `Enable*`: not in the engine. `Disable*`: the filter is off.
fn switch(cx: &mut Ctx<'_>, args: &Args, group: bool, on: bool) -> Plan {
    let id = if group {
        group_id(args)
    } else {
        axis_of(cx, args).map(|(a, _)| a)
    };
    match id {
        Ok(_) if on => Plan::Fail(HMPL_NOT_SUPPORTED),
        Ok(_) => Plan::Done(Outcome::Int(0)),
        Err(c) => Plan::Fail(c),
    }
}

const ONE: &[Ty] = &[Ty::Int];
const SHAPER: &[Ty] = &[Ty::Int, Ty::Double, Ty::Double, Ty::Int];

pub static ROWS: &[Function] = &[
    row("EnableAxisVsf", "15.2", ONE, Ret::Int, Axis, |cx, a| {
        switch(cx, a, false, true)
    }),
    row("DisableAxisVsf", "15.3", ONE, Ret::Int, Axis, |cx, a| {
        switch(cx, a, false, false)
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
    row("EnableAxisInShape", "15.5", ONE, Ret::Int, Axis, |cx, a| {
        switch(cx, a, false, true)
    }),
    row(
        "DisableAxisInShape",
        "15.6",
        ONE,
        Ret::Int,
        Axis,
        |cx, a| switch(cx, a, false, false),
    ),
    // TV 64.
    row("SetAxisInShape", "15.7", SHAPER, Ret::Int, Axis, |cx, a| {
        set(cx, a, Filter::AxisInShape)
    }),
    row("EnableGrpInShape", "15.8", ONE, Ret::Int, Group, |cx, a| {
        switch(cx, a, true, true)
    }),
    row(
        "DisableGrpInShape",
        "15.9",
        ONE,
        Ret::Int,
        Group,
        |cx, a| switch(cx, a, true, false),
    ),
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
