//! `SetConfigVar` (§17.3.2) and `GetConfigVar` (§17.3.1, digest 004 §1.11): a controller
//! variable by its HCV id `0xCCNNAAAA` (CC class, NN axis or group, AAAA address). A variable
//! an HMPL setter also writes goes through that setter, so its checks and codes are the
//! setter's (TV 68: `SetConfigVar(0x83000065, 0.0)` is `SetSWRL(0, 0.0)`), and is read by the
//! getter of the same name where there is one, else from the engine parameter it is (TV 74:
//! the homing parameters, which have no getter); the free variables `ltest0…9` and `dtest0…9`
//! are kept in the registers. A group variable that one setter sets with others (the angular
//! profile, the transition parameters, the group shaper) is written alone through that setter,
//! the others kept; the group limits cap the profile setters (`GroupVariable`). Unmarked
//! (digest 004 §1.6): accepted unless `strict`.
//!
//! Codes: an id of no listed variable → `eERR_HCV_ID_NOT_FOUND` (TV 69); a status variable
//! (clock, homing status, last error …) written → `eERR_HCV_IS_READ_ONLY`; a listed variable
//! mcemu does not model (P2P settings, drive resolutions …) → `eERR_HMPL_NOT_SUPPORTED`; a value
//! an `int` setter cannot take (not integral, out of `int`) → `eERR_HCV_VALUE_OUT_OF_RANGE`.
//! `GetConfigVar` replies `result,value` (`0,2000`; failed: `-1,0`, the code latched).

use axes::ParamId;
use mcemu_dialects::himc::group::{self as profile, Profile};
use mcemu_dialects::himc::system::{
    HCV_ID_NOT_FOUND, HCV_IS_READ_ONLY, HCV_VALUE_OUT_OF_RANGE, HMPL_INTERNAL_ERROR,
    HMPL_NOT_SUPPORTED,
};
use mcemu_dialects::himc::{AxisVariable, AXIS_CLASS, GROUP_CLASS};

use super::{axis_of, group_state, param, set_param};
use crate::reply::Outcome;
use crate::table::{row, Addresses, Args, Ctx, Function, Plan, Ret, Ty, Value};

/// What an HCV address is to `SetConfigVar`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Variable {
    /// Written by this HMPL setter of (axis or group, value).
    Setter(&'static str),
    /// An axis parameter with no HMPL setter of its own.
    Param(ParamId),
    ReadOnly,
    /// Listed by the manual, not modelled.
    Unmodelled,
    /// A group setting with no setter of its own (`group_variable`).
    Group(GroupVariable),
}

/// The group variables of Table 17.1.1.3 that one HMPL setter sets together with others, or
/// none does: written one at a time, the others kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum GroupVariable {
    /// `grp_{lin,ang}_{vel,acc,dec}_lim`: the most a profile's value `k` may be (velocity,
    /// acceleration, deceleration); the manual's range maximum until set lower.
    Limit(Profile, usize),
    /// `grp_ang_vel`, `_acc`, `_dec`, `_sf`, `_acc_time`, `_dec_time` (§8.3.7's profile).
    Angular(usize),
    /// `grp_trans_vel`, `_dis`, `_dev`, `_curvature` (§8.3.26).
    Transition(usize),
    /// `grp_shaper_fr`, `grp_shaper_xi` (§15.10).
    ShaperFrequency,
    ShaperDamping,
}

/// Table 17.1.1.2, axis variables `0x83NNAAAA`.
const AXIS: &[(u16, Variable)] = &[
    (0x0015, Variable::ReadOnly), // motion_type
    (0x0033, Variable::Setter("SetPosWindow")),
    (0x0034, Variable::Setter("SetPosWindowTime")),
    (0x0065, Variable::Setter("SetSWRL")),
    (0x0066, Variable::Setter("SetSWLL")),
    (0x0067, Variable::Param(ParamId::MaxVelocity)), // vel_lim
    // acc_lim, dec_lim: the engine's one cap on both (decisions.md).
    (0x0068, Variable::Param(ParamId::MaxAccel)),
    (0x0069, Variable::Param(ParamId::MaxAccel)),
    (0x0079, Variable::Param(ParamId::FeLimit)), // max_pos_err
    (0x007a, Variable::Param(ParamId::CompensationLimit)), // max_comp_lim
    (0x00a0, Variable::ReadOnly),                // home_status
    (0x00a1, Variable::Setter("SetHomeMethod")),
    (0x00a2, Variable::Setter("SetHomeSwitchVel")),
    (0x00a3, Variable::Setter("SetHomeZeroVel")),
    (0x00a4, Variable::Setter("SetHomeTimeout")),
    (0x00a5, Variable::Setter("SetHomeAcc")),
    (0x00a6, Variable::Setter("SetHomeOffset")),
    (0x00d3, Variable::Setter("SetVel")),
    (0x00d4, Variable::Setter("SetAcc")),
    (0x00d5, Variable::Setter("SetDec")),
    (0x00d7, Variable::Setter("SetSMTime")),
    (0x00db, Variable::Setter("SetVelScale")),
    (0x00dd, Variable::Unmodelled), // p2p_del … en_motionManager: iA Studio's P2P panel
    (0x00de, Variable::Unmodelled),
    (0x00df, Variable::Unmodelled),
    (0x00e0, Variable::Unmodelled),
    (0x00e1, Variable::Unmodelled),
    (0x00e2, Variable::Unmodelled),
    (0x00e3, Variable::Setter("SetAccTime")),
    (0x00e4, Variable::Setter("SetDecTime")),
    (0x00e9, Variable::Unmodelled), // map_io_type
    (0x0117, Variable::ReadOnly),   // rollover_turns
    (0x0119, Variable::Setter("SetRollover")),
    (0x0193, Variable::ReadOnly),   // gant_pair
    (0x01f7, Variable::Unmodelled), // en_delay
    (0x01ff, Variable::Unmodelled), // fb_ratio_pos …
    (0x0200, Variable::Unmodelled),
    (0x0209, Variable::Unmodelled),
    (0x020a, Variable::Unmodelled),
    (0x0213, Variable::Unmodelled), // rotor_inertia
    (0x0214, Variable::Unmodelled), // force_constant
    (0x0263, Variable::ReadOnly),   // last_err
    (0x03c2, Variable::ReadOnly),   // gear_ratio: GearIn sets it
];

/// Table 17.1.1.3, group variables `0x82NNAAAA`.
const GROUP: &[(u16, Variable)] = &[
    (0x0002, Variable::ReadOnly), // grp_num_axis
    (
        0x00ca,
        Variable::Group(GroupVariable::Limit(Profile::Linear, 0)),
    ),
    (
        0x00cb,
        Variable::Group(GroupVariable::Limit(Profile::Linear, 1)),
    ),
    (
        0x00cc,
        Variable::Group(GroupVariable::Limit(Profile::Linear, 2)),
    ),
    (
        0x00d4,
        Variable::Group(GroupVariable::Limit(Profile::Angular, 0)),
    ),
    (
        0x00d5,
        Variable::Group(GroupVariable::Limit(Profile::Angular, 1)),
    ),
    (
        0x00d6,
        Variable::Group(GroupVariable::Limit(Profile::Angular, 2)),
    ),
    (0x00dd, Variable::Setter("SetGrpVel")),
    (0x00de, Variable::Setter("SetGrpAcc")),
    (0x00df, Variable::Setter("SetGrpDec")),
    (0x00e0, Variable::Setter("SetGrpSMTime")),
    (0x00e1, Variable::Setter("SetGrpAccTime")),
    (0x00e2, Variable::Setter("SetGrpDecTime")),
    (0x00e7, Variable::Group(GroupVariable::Angular(0))),
    (0x00e8, Variable::Group(GroupVariable::Angular(1))),
    (0x00e9, Variable::Group(GroupVariable::Angular(2))),
    (0x00ea, Variable::Group(GroupVariable::Angular(3))),
    (0x00eb, Variable::Group(GroupVariable::Angular(4))),
    (0x00ec, Variable::Group(GroupVariable::Angular(5))),
    (0x00f1, Variable::Setter("SetGrpCoordSys")),
    (0x00f2, Variable::Setter("SetGrpBufferMode")),
    (0x00f3, Variable::Setter("SetGrpTransMode")),
    (0x00f4, Variable::Group(GroupVariable::Transition(0))),
    (0x00f5, Variable::Group(GroupVariable::Transition(1))),
    (0x00f6, Variable::Group(GroupVariable::Transition(2))),
    (0x00f7, Variable::Group(GroupVariable::Transition(3))),
    (0x0104, Variable::Setter("SetGrpVelScale")),
    (0x0119, Variable::Group(GroupVariable::ShaperFrequency)),
    (0x011a, Variable::Group(GroupVariable::ShaperDamping)),
    (0x038f, Variable::ReadOnly), // grp_last_err
];

/// Table 17.1.1.1: `HCV_ID_ltest0…9` (ints), `HCV_ID_dtest0…9` (doubles).
const LTEST: std::ops::RangeInclusive<u32> = 0x2328..=0x2331;
const DTEST: std::ops::RangeInclusive<u32> = 0x235a..=0x2363;
/// fclk, timeInMs; the user table and mtest arrays (written element-wise elsewhere).
const SYSTEM_READ_ONLY: &[u32] = &[0x012c, 0x012e];
const SYSTEM_ARRAYS: &[u32] = &[0x07d0, 0x238c];

fn lookup(table: &[(u16, Variable)], address: u16) -> Option<Variable> {
    table.iter().find(|(a, _)| *a == address).map(|(_, v)| *v)
}

/// `value` as an `int` argument, if it is one.
fn as_int(value: f64) -> Option<i64> {
    let in_int = (f64::from(i32::MIN)..=f64::from(i32::MAX)).contains(&value);
    (in_int && value.fract() == 0.0).then_some(value as i64)
}

/// Call setter `name` with (`id`, `value`).
fn call_setter(cx: &mut Ctx<'_>, name: &str, id: u8, value: f64) -> Plan {
    let Some(f) = super::all().find(|f| f.name == name) else {
        return Plan::Fail(HMPL_NOT_SUPPORTED);
    };
    let value = match f.params.get(1) {
        Some(Ty::Int) => match as_int(value) {
            Some(v) => Value::Int(v),
            None => return Plan::Fail(HCV_VALUE_OUT_OF_RANGE),
        },
        _ => Value::Double(value),
    };
    (f.handler)(cx, &Args(vec![Value::Int(i64::from(id)), value]))
}

fn set_config_var(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    let hcv = args.int(0) as u32;
    let value = args.double(1);
    let [class, id, hi, lo] = hcv.to_be_bytes();
    let address = u16::from_be_bytes([hi, lo]);
    let variable = match class {
        AXIS_CLASS => lookup(AXIS, address),
        GROUP_CLASS => lookup(GROUP, address),
        0 if id == 0 => {
            if LTEST.contains(&hcv) || DTEST.contains(&hcv) {
                let v = if LTEST.contains(&hcv) {
                    // An int variable: C's conversion, toward zero, within `int`.
                    match as_int(value.trunc()) {
                        Some(v) => v as f64,
                        None => return Plan::Fail(HCV_VALUE_OUT_OF_RANGE),
                    }
                } else {
                    value
                };
                cx.registers.free_variables.insert(hcv, v);
                return Plan::Done(Outcome::Int(0));
            }
            if SYSTEM_READ_ONLY.contains(&hcv) {
                Some(Variable::ReadOnly)
            } else if SYSTEM_ARRAYS.contains(&hcv) {
                Some(Variable::Unmodelled)
            } else {
                None
            }
        }
        _ => None,
    };
    match variable {
        None => Plan::Fail(HCV_ID_NOT_FOUND),
        Some(Variable::ReadOnly) => Plan::Fail(HCV_IS_READ_ONLY),
        Some(Variable::Unmodelled) => Plan::Fail(HMPL_NOT_SUPPORTED),
        Some(Variable::Setter(name)) => call_setter(cx, name, id, value),
        Some(Variable::Group(v)) => write_group(cx, u16::from(id), v, value),
        Some(Variable::Param(p)) => {
            let axis_args = Args(vec![Value::Int(i64::from(id))]);
            match axis_of(cx, &axis_args) {
                Ok(_) if !(value.is_finite() && value >= 0.0) => Plan::Fail(HCV_VALUE_OUT_OF_RANGE),
                Ok((axis, _)) => set_param(axis, p, value),
                Err(code) => Plan::Fail(code),
            }
        }
    }
}

/// A group variable of one value: through the setter of all of them, the others as they are.
fn write_group(cx: &mut Ctx<'_>, group: u16, v: GroupVariable, value: f64) -> Plan {
    match v {
        GroupVariable::Limit(which, k) => {
            // A limit is positive, at most the manual's range, and not below the value in force
            // (it caps the setters; it does not change the profile).
            let current = match which {
                Profile::Linear => group_state::profile_of(cx, group),
                Profile::Angular => group_state::angular_of(cx, group),
            };
            let in_force = [current.velocity, current.acceleration, current.deceleration][k];
            let max = profile::maxima(which)[k];
            if !(value > 0.0 && value <= max && value >= in_force) {
                return Plan::Fail(HCV_VALUE_OUT_OF_RANGE);
            }
            let address = group_state::limit_addresses(which)[k];
            cx.registers.group_limits.insert((group, address), value);
            Plan::Done(Outcome::Int(0))
        }
        GroupVariable::Angular(k) => {
            let mut p = group_state::angular_of(cx, group);
            let by_time = |ms: f64| (ms.is_finite() && ms > 0.0).then(|| p.velocity / (ms / 1e3));
            match k {
                0 => p.velocity = value,
                1 => p.acceleration = value,
                2 => p.deceleration = value,
                3 => p.smooth_ms = value,
                _ => match by_time(value) {
                    Some(a) if k == 4 => p.acceleration = a,
                    Some(d) => p.deceleration = d,
                    None => return Plan::Fail(HCV_VALUE_OUT_OF_RANGE),
                },
            }
            group_state::apply_profile(cx, group, Profile::Angular, p)
        }
        GroupVariable::Transition(k) => {
            super::group_settings::set_transition_parameter(cx, group, k, value)
        }
        GroupVariable::ShaperFrequency | GroupVariable::ShaperDamping => {
            let mut s = super::filters::group_shaper_settings(cx, group);
            if v == GroupVariable::ShaperFrequency {
                s.frequency = value;
            } else {
                s.damping = value;
            }
            let Some(f) = super::all().find(|f| f.name == "SetGrpInShape") else {
                return Plan::Fail(HMPL_INTERNAL_ERROR);
            };
            let args = Args(vec![
                Value::Int(i64::from(group)),
                Value::Double(s.frequency),
                Value::Double(s.damping),
                Value::Int(s.shaper.unwrap_or(1)),
            ]);
            (f.handler)(cx, &args)
        }
    }
}

/// A group variable of `write_group` as it stands.
fn read_group_variable(cx: &Ctx<'_>, group: u16, v: GroupVariable) -> f64 {
    match v {
        GroupVariable::Limit(which, k) => group_state::limits_of(cx, group, which)[k],
        GroupVariable::Angular(k) => {
            let p = group_state::angular_of(cx, group);
            let time = |a: f64| p.velocity / a * 1e3;
            [
                p.velocity,
                p.acceleration,
                p.deceleration,
                p.smooth_ms,
                time(p.acceleration),
                time(p.deceleration),
            ][k]
        }
        GroupVariable::Transition(k) => {
            let t = group_state::transition_parameters(cx, group);
            [t.velocity, t.distance, t.deviation, t.curvature][k]
        }
        GroupVariable::ShaperFrequency => {
            super::filters::group_shaper_settings(cx, group).frequency
        }
        GroupVariable::ShaperDamping => super::filters::group_shaper_settings(cx, group).damping,
    }
}

/// `GetConfigVar(hcv_id, {})`: `0,value`, or `-1,0` with the code latched.
fn get_config_var(cx: &mut Ctx<'_>, args: &Args) -> Plan {
    match read(cx, args.int(0) as u32) {
        Ok(value) => Plan::Done(Outcome::WithStatus(0, value)),
        Err(code) => Plan::Fail(code),
    }
}

fn read(cx: &mut Ctx<'_>, hcv: u32) -> Result<f64, u32> {
    let [class, id, hi, lo] = hcv.to_be_bytes();
    let address = u16::from_be_bytes([hi, lo]);
    match class {
        AXIS_CLASS => read_axis(cx, id, address),
        GROUP_CLASS => read_group(cx, id, address),
        0 if id == 0 => read_system(cx, hcv),
        _ => Err(HCV_ID_NOT_FOUND),
    }
}

/// Table 17.1.1.1: the free variables, the clocks (on the engine's virtual clock).
fn read_system(cx: &Ctx<'_>, hcv: u32) -> Result<f64, u32> {
    let seconds = cx.snapshot.tick as f64 * cx.snapshot.period;
    match hcv {
        _ if LTEST.contains(&hcv) || DTEST.contains(&hcv) => Ok(cx
            .registers
            .free_variables
            .get(&hcv)
            .copied()
            .unwrap_or(0.0)),
        // fclk: +1 every 250 µs.
        0x012c => Ok((seconds / 250e-6).round()),
        0x012e => Ok((seconds * 1e3).round()),
        _ if SYSTEM_ARRAYS.contains(&hcv) => Err(HMPL_NOT_SUPPORTED),
        _ => Err(HCV_ID_NOT_FOUND),
    }
}

/// Table 17.1.1.2: the states through their getters, the settings from the engine parameter
/// each is (`himc::AXIS_VARIABLES`).
fn read_axis(cx: &mut Ctx<'_>, id: u8, address: u16) -> Result<f64, u32> {
    let axis = axis_of(cx, &Args(vec![Value::Int(i64::from(id))]))?.0;
    let getter = match address {
        0x00a0 => Some("IsHomed"),
        0x0117 => Some("GetRolloverTurns"),
        0x0263 => Some("GetAxisLastErr"),
        0x03c2 => Some("GetGearRatio"),
        _ => None,
    };
    if let Some(name) = getter {
        return call_getter(cx, name, id);
    }
    if address == 0x0193 {
        // A pair's id is its RHS axis (decisions.md, HIMC gantry); −1: not paired.
        return Ok(super::gantry::pair_of(cx, axis).map_or(-1.0, |(rhs, _)| f64::from(rhs)));
    }
    match AxisVariable::by_address(address) {
        Some(AxisVariable { param: Some(p), .. }) => Ok(param(cx, axis, *p)),
        Some(_) => Err(HMPL_NOT_SUPPORTED),
        None => Err(HCV_ID_NOT_FOUND),
    }
}

/// Table 17.1.1.3: through the group getters, or from what the registers keep.
fn read_group(cx: &mut Ctx<'_>, id: u8, address: u16) -> Result<f64, u32> {
    let group = u16::from(id);
    let linear = group_state::profile_of(cx, group);
    let time = |a: f64| linear.velocity / a * 1e3;
    match address {
        0x0002 => Ok(cx.registers.group_members.get(&group).map_or(0, Vec::len) as f64),
        0x038f => call_getter(cx, "GetGrpLastErr", id),
        0x00e1 => Ok(time(linear.acceleration)),
        0x00e2 => Ok(time(linear.deceleration)),
        _ => match lookup(GROUP, address) {
            Some(Variable::Setter(name)) => {
                let getter = name.replacen("Set", "Get", 1);
                call_getter(cx, &getter, id)
            }
            Some(Variable::Group(v)) => Ok(read_group_variable(cx, group, v)),
            Some(_) => Err(HMPL_NOT_SUPPORTED),
            None => Err(HCV_ID_NOT_FOUND),
        },
    }
}

/// The value getter `name` answers for axis or group `id`.
fn call_getter(cx: &mut Ctx<'_>, name: &str, id: u8) -> Result<f64, u32> {
    let f = super::all()
        .find(|f| f.name == name)
        .ok_or(HMPL_INTERNAL_ERROR)?;
    match (f.handler)(cx, &Args(vec![Value::Int(i64::from(id))])) {
        Plan::Done(Outcome::Int(v)) => Ok(f64::from(v)),
        Plan::Done(Outcome::Double(v)) => Ok(v),
        Plan::Fail(code) => Err(code),
        _ => Err(HMPL_INTERNAL_ERROR),
    }
}

pub static ROWS: &[Function] = &[
    row(
        "GetConfigVar",
        "17.3.1",
        &[Ty::Int, Ty::Out],
        Ret::DoubleWithStatus,
        Addresses::Controller,
        get_config_var,
    ),
    row(
        "SetConfigVar",
        "17.3.2",
        &[Ty::Int, Ty::Double],
        Ret::Int,
        Addresses::Controller,
        set_config_var,
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_setter_named_is_served_with_an_id_and_a_value() {
        for (_, v) in AXIS.iter().chain(GROUP) {
            if let Variable::Setter(name) = v {
                let f = super::super::all()
                    .find(|f| f.name == *name)
                    .unwrap_or_else(|| panic!("{name} is not served"));
                assert_eq!(f.params.len(), 2, "{name}");
            }
        }
    }

    #[test]
    fn every_group_setter_named_has_its_getter() {
        for (address, v) in GROUP {
            if let Variable::Setter(name) = v {
                let getter = name.replacen("Set", "Get", 1);
                let served = super::super::all().any(|f| f.name == getter);
                // Read from the profile where the manual has no getter.
                assert!(served || matches!(address, 0x00e1 | 0x00e2), "{getter}");
            }
        }
    }

    #[test]
    fn int_values_are_integral_and_within_int() {
        assert_eq!(as_int(33.0), Some(33));
        assert_eq!(as_int(-1.0), Some(-1));
        assert_eq!(as_int(1.5), None);
        assert_eq!(as_int(f64::NAN), None);
        assert_eq!(as_int(1e10), None);
    }
}
