//! `SetConfigVar` (§17.3.2, digest 004 §1.11): a controller variable by its HCV id
//! `0xCCNNAAAA` (CC class, NN axis or group, AAAA address). A variable an HMPL setter also
//! writes goes through that setter, so its checks and codes are the setter's (TV 68:
//! `SetConfigVar(0x83000065, 0.0)` is `SetSWRL(0, 0.0)`); the free variables `ltest0…9` and
//! `dtest0…9` are kept in the registers. Unmarked (digest 004 §1.6): accepted unless `strict`.
//!
//! Codes: an id of no listed variable → `eERR_HCV_ID_NOT_FOUND`; a status variable (clock,
//! homing status, last error …) → `eERR_HCV_IS_READ_ONLY`; a listed variable mcemu does not
//! model (P2P settings, drive resolutions …) → `eERR_HMPL_NOT_SUPPORTED`; a value an `int`
//! setter cannot take (not integral, out of `int`) → `eERR_HCV_VALUE_OUT_OF_RANGE`.

use axes::ParamId;
use mcemu_dialects::himc::system::{
    HCV_ID_NOT_FOUND, HCV_IS_READ_ONLY, HCV_VALUE_OUT_OF_RANGE, HMPL_NOT_SUPPORTED,
};
use mcemu_dialects::himc::{AXIS_CLASS, GROUP_CLASS};

use super::{axis_of, set_param};
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
}

/// Table 17.1.1.2, axis variables `0x83NNAAAA`.
const AXIS: &[(u16, Variable)] = &[
    (0x0015, Variable::ReadOnly), // motion_type
    (0x0033, Variable::Setter("SetPosWindow")),
    (0x0034, Variable::Setter("SetPosWindowTime")),
    (0x0065, Variable::Setter("SetSWRL")),
    (0x0066, Variable::Setter("SetSWLL")),
    (0x0067, Variable::Unmodelled),              // vel_lim
    (0x0068, Variable::Unmodelled),              // acc_lim
    (0x0069, Variable::Unmodelled),              // dec_lim
    (0x0079, Variable::Param(ParamId::FeLimit)), // max_pos_err
    (0x007a, Variable::Unmodelled),              // max_comp_lim (no such limit in the engine)
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
    (0x00ca, Variable::Unmodelled),
    (0x00cb, Variable::Unmodelled),
    (0x00cc, Variable::Unmodelled),
    (0x00d4, Variable::Unmodelled),
    (0x00d5, Variable::Unmodelled),
    (0x00d6, Variable::Unmodelled),
    (0x00dd, Variable::Setter("SetGrpVel")),
    (0x00de, Variable::Setter("SetGrpAcc")),
    (0x00df, Variable::Setter("SetGrpDec")),
    (0x00e0, Variable::Setter("SetGrpSMTime")),
    (0x00e1, Variable::Setter("SetGrpAccTime")),
    (0x00e2, Variable::Setter("SetGrpDecTime")),
    (0x00e7, Variable::Unmodelled), // the angular profile: one setter for all four values
    (0x00e8, Variable::Unmodelled),
    (0x00e9, Variable::Unmodelled),
    (0x00ea, Variable::Unmodelled),
    (0x00eb, Variable::Unmodelled),
    (0x00ec, Variable::Unmodelled),
    (0x00f1, Variable::Setter("SetGrpCoordSys")),
    (0x00f2, Variable::Setter("SetGrpBufferMode")),
    (0x00f3, Variable::Setter("SetGrpTransMode")),
    (0x00f4, Variable::Unmodelled), // trans_vel … curvature: one setter for all four
    (0x00f5, Variable::Unmodelled),
    (0x00f6, Variable::Unmodelled),
    (0x00f7, Variable::Unmodelled),
    (0x0104, Variable::Setter("SetGrpVelScale")),
    (0x0119, Variable::Unmodelled), // grp_shaper_fr
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

pub static ROWS: &[Function] = &[row(
    "SetConfigVar",
    "17.3.2",
    &[Ty::Int, Ty::Double],
    Ret::Int,
    Addresses::Controller,
    set_config_var,
)];

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
    fn int_values_are_integral_and_within_int() {
        assert_eq!(as_int(33.0), Some(33));
        assert_eq!(as_int(-1.0), Some(-1));
        assert_eq!(as_int(1.5), None);
        assert_eq!(as_int(f64::NAN), None);
        assert_eq!(as_int(1e10), None);
    }
}
