//! The served HMPL functions, one module per manual chapter, each with its `ROWS`: the table
//! [`all`] gathers. Helpers shared by the handlers live here.

use axes::command::Command;
use axes::status::AxisStatus;
use axes::ParamId;
use mcemu_dialects::himc::system::HMPL_ARG_OUT_OF_RANGE;
use mcemu_dialects::himc::{value_from_engine, value_to_engine, AxisError};

use crate::reply::Outcome;
use crate::table::{Args, Ctx, Function, Plan, Then};

pub mod analog;
pub mod axis;
pub mod compensation;
pub mod config_var;
pub mod errors;
pub mod filters;
pub mod gantry;
pub mod gear;
pub mod gpio;
pub mod group;
pub mod group_settings;
pub mod group_state;
pub mod homing;
pub mod math;
pub mod sdo;
pub mod settings;
pub mod slave;
pub mod status;
pub mod strings;
pub mod system;
pub mod table_values;
pub mod tasks;
pub mod trigger;

/// Every served function, in manual order.
pub fn all() -> impl Iterator<Item = &'static Function> {
    [
        system::ROWS,
        strings::ROWS,
        math::ROWS,
        axis::ROWS,
        settings::ROWS,
        status::ROWS,
        gear::ROWS,
        gantry::ROWS,
        group::ROWS,
        group_settings::ROWS,
        gpio::ROWS,
        slave::ROWS,
        analog::ROWS,
        table_values::ROWS,
        trigger::ROWS,
        compensation::ROWS,
        filters::ROWS,
        tasks::ROWS,
        sdo::ROWS,
        config_var::ROWS,
        errors::ROWS,
        homing::ROWS,
    ]
    .into_iter()
    .flatten()
}

/// The axis argument 0 names and its status; a missing axis is `eERR_HMPL_ARG_OUT_OF_RANGE`.
pub(crate) fn axis_of<'a>(cx: &'a Ctx<'_>, args: &Args) -> Result<(u16, &'a AxisStatus), u32> {
    let id = args.int(0);
    usize::try_from(id)
        .ok()
        .and_then(|i| cx.snapshot.axes.get(i))
        .and_then(|s| Some((u16::try_from(id).ok()?, s)))
        .ok_or(HMPL_ARG_OUT_OF_RANGE)
}

/// Axis `axis`'s error called `name`, as the function returns it.
pub(crate) fn axis_error(axis: u16, name: &str) -> u32 {
    AxisError::by_name(name).map_or(HMPL_ARG_OUT_OF_RANGE, |e| {
        e.code(u8::try_from(axis).unwrap_or(u8::MAX))
    })
}

/// One engine command from its JSON form (the scenario and control-API form); success: 0.
pub(crate) fn engine(command: serde_json::Value) -> Plan {
    engine_then(command, Then::Succeed)
}

pub(crate) fn engine_then(command: serde_json::Value, then: Then) -> Plan {
    match serde_json::from_value::<Command>(command) {
        Ok(c) => Plan::Engine(vec![c], then),
        // A handler's own JSON: a bug here, reported as the HMPL internal error.
        Err(_) => Plan::Fail(mcemu_dialects::himc::system::HMPL_INTERNAL_ERROR),
    }
}

/// Parameter `id` of axis `axis` in HMPL units (ms for times).
pub(crate) fn param(cx: &Ctx<'_>, axis: u16, id: ParamId) -> f64 {
    let value = cx
        .snapshot
        .params
        .get(usize::from(axis))
        .map_or(id.def().default, |p| p.get(id));
    value_from_engine(id, value)
}

/// Set parameter `id` of axis `axis` to `hmpl` (HMPL units).
pub(crate) fn set_param(axis: u16, id: ParamId, hmpl: f64) -> Plan {
    engine(serde_json::json!({
        "type": "set_parameter",
        "axis": axis,
        "name": id.name(),
        "value": value_to_engine(id, hmpl),
    }))
}

/// The `double` getter of parameter `id`.
pub(crate) fn get_param(cx: &mut Ctx<'_>, args: &Args, id: ParamId) -> Plan {
    match axis_of(cx, args) {
        Ok((axis, _)) => Plan::Done(Outcome::Double(param(cx, axis, id))),
        Err(code) => Plan::Fail(code),
    }
}

/// The `double` getter of a status field.
pub(crate) fn get_status(cx: &mut Ctx<'_>, args: &Args, field: fn(&AxisStatus) -> f64) -> Plan {
    match axis_of(cx, args) {
        Ok((_, s)) => Plan::Done(Outcome::Double(field(s))),
        Err(code) => Plan::Fail(code),
    }
}
