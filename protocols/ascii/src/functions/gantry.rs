//! Chapter 7, gantry pairs (digest 004 §2.6, §7.2–7.5; TV 36–39) through the engine's gantry
//! (`gantry_enable` with the RHS axis as master and the LHS axis as its one slave). HIMC pairs
//! disabled axes, the engine gangs enabled ones: the pair is the controller's
//! (`Registers::gantry_pairs`) from `EnableGantryPair` on, `Enable`/`Disable` of either axis act
//! on both (§7.1.1), and the engine's gantry is engaged with the first motion command to the
//! RHS axis once both are enabled (`functions::axis`). A pair's id is its RHS axis
//! (decisions.md).

use axes::status::CouplingKind;
use serde_json::json;

use super::axis_error;
use super::gear::{axis_arg, enabled};
use crate::reply::Outcome;
use crate::table::{row, unary, Addresses::Axis, Ctx, Function, Plan, Ret, Ty};

/// The pair `axis` belongs to, as (RHS, LHS).
pub(crate) fn pair_of(cx: &Ctx<'_>, axis: u16) -> Option<(u16, u16)> {
    cx.registers
        .gantry_pairs
        .iter()
        .find(|(&r, &l)| r == axis || l == axis)
        .map(|(&r, &l)| (r, l))
}

/// Whether the engine's gantry of `rhs` is engaged.
pub(crate) fn engaged(cx: &Ctx<'_>, rhs: u16) -> bool {
    cx.snapshot
        .couplings
        .iter()
        .any(|c| c.kind == CouplingKind::Gantry && c.master == rhs)
}

pub static ROWS: &[Function] = &[
    // §7.2, TV 38–39: both disabled, neither paired already.
    row(
        "EnableGantryPair",
        "7.2",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Axis,
        |cx, a| {
            let (rhs, lhs) = match (axis_arg(cx, a, 0), axis_arg(cx, a, 1)) {
                (Ok(r), Ok(l)) => (r, l),
                (Err(c), _) | (_, Err(c)) => return Plan::Fail(c),
            };
            if rhs == lhs {
                return Plan::Fail(axis_error(lhs, "eERR_AXIS_CMD_INVALID_SLAVE_ID"));
            }
            for axis in [rhs, lhs] {
                if enabled(cx, axis) {
                    return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_ENABLED"));
                }
                if pair_of(cx, axis).is_some() {
                    return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_GANTRY_MODE"));
                }
            }
            cx.registers.gantry_pairs.insert(rhs, lhs);
            Plan::Done(Outcome::Int(0))
        },
    ),
    // §7.3: either axis of the pair; both disabled.
    unary("DisableGantryPair", "7.3", Ret::Int, Axis, |cx, a| {
        let axis = match axis_arg(cx, a, 0) {
            Ok(x) => x,
            Err(c) => return Plan::Fail(c),
        };
        let Some((rhs, lhs)) = pair_of(cx, axis) else {
            return Plan::Fail(axis_error(axis, "eERR_AXIS_CMD_INVALID_GANTRY_MODE"));
        };
        for x in [rhs, lhs] {
            if enabled(cx, x) {
                return Plan::Fail(axis_error(x, "eERR_AXIS_CMD_INVALID_ENABLED"));
            }
        }
        cx.registers.gantry_pairs.remove(&rhs);
        if engaged(cx, rhs) {
            super::engine(json!({"type": "gantry_disable", "master": rhs}))
        } else {
            Plan::Done(Outcome::Int(0))
        }
    }),
    // §7.4, TV 37: −1 for an axis in no pair.
    unary(
        "GetGantryPairID",
        "7.4",
        Ret::Int,
        Axis,
        |cx, a| match axis_arg(cx, a, 0) {
            Ok(axis) => Plan::Done(Outcome::Int(
                pair_of(cx, axis).map_or(-1, |(rhs, _)| i32::from(rhs)),
            )),
            Err(c) => Plan::Fail(c),
        },
    ),
    row(
        "IsGantryPair",
        "7.5",
        &[Ty::Int, Ty::Int],
        Ret::Int,
        Axis,
        |cx, a| match (axis_arg(cx, a, 0), axis_arg(cx, a, 1)) {
            (Ok(x), Ok(y)) => Plan::Done(Outcome::bool(
                x != y
                    && pair_of(cx, x)
                        .is_some_and(|(r, l)| (r == x || l == x) && (r == y || l == y)),
            )),
            (Err(c), _) | (_, Err(c)) => Plan::Fail(c),
        },
    ),
];
