//! The execution-time calculation (digest 001 §2.7 (11)–(12)): `NMC_CrdStartExeTimeCalc`
//! and `_NMC_CrdGetExeTime` take no handle (the vendor computes it in the host library with its
//! own look-ahead); mcemu's library asks every device it has open through these two rows.
//!
//! While the calculation runs, what the coordinate systems are pushed is kept back (the manual:
//! "all buffer commands are not pushed into the controller"): pushes wait in the pending list
//! as before `NMC_CrdStartMtn`, and reading the time puts the coordinate systems back as they
//! were at the start, so none of it ever runs. The time is the engine's own: a dry run of the
//! group (`estimate_group_time`: the engine applies the commands, steps until the group is at
//! rest, and puts everything back), so it is what running them takes, tick for tick. Per
//! coordinate system, the time of what it held before plus what was pushed, less the time of
//! what it held before: the time the pushed commands add to the program. The sum over the
//! device's coordinate systems, in ms (whole servo periods).

use axes::command::{
    Command, ErrorKind, EstimateGroupTime, GroupContinue, GroupEnable, GroupId, GroupSetOverride,
    Reply,
};
use axes::status::GroupState;
use mcemu_dialects::nmc::code_for_kind;
use mcemu_nmc::errors::RTN_BAD_PAYLOAD;
use mcemu_nmc::table::{self, Function};

use crate::nmc::crd::CrdState;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (
        table::CRD_START_EXE_TIME_CALC_EX,
        crd_start_exe_time_calc_ex,
    ),
    (table::CRD_GET_EXE_TIME_EX, crd_get_exe_time_ex),
];

fn crd_start_exe_time_calc_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let mut crd = c.service.crd();
    let saved = Box::new(crd.clone());
    // Pushes wait in the pending list while the calculation runs, even on a started system.
    for s in crd.iter_mut() {
        s.started = false;
    }
    drop(crd);
    c.service.sys().exe_calc = Some(saved);
    Ok(())
}

fn crd_get_exe_time_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let saved = c.service.sys().exe_calc.take().ok_or_else(|| {
        Refusal::new(
            code_for_kind(ErrorKind::InvalidState),
            "no execution-time calculation is running (NMC_CrdStartExeTimeCalc first)",
        )
    })?;
    let mut crd = c.service.crd();
    for (n, (now, before)) in crd.iter().zip(saved.iter()).enumerate() {
        // A buffer cleared meanwhile holds only what came after the clear.
        let pushed = now
            .pending
            .get(before.pending.len()..)
            .unwrap_or(&now.pending);
        if pushed.is_empty() || before.config.is_none() {
            continue;
        }
        let group = n as GroupId;
        let held = held(c, group, before);
        let mut all = held.clone();
        all.extend_from_slice(pushed);
        c.command(EstimateGroupTime {
            group,
            commands: all,
        });
        c.command(EstimateGroupTime {
            group,
            commands: held,
        });
    }
    // What was pushed never runs: the coordinate systems as they were.
    *crd = *saved;
    drop(crd);
    let period_ms = c.snapshot.period * 1e3;
    if c.plan.commands.is_empty() {
        c.output.f64(0.0);
        return Ok(());
    }
    c.plan.then = Some(Box::new(move |_, result, out| {
        // A refused estimate is the call's refusal already (service.rs).
        let Ok(replies) = result else { return Ok(()) };
        let ticks = replies
            .iter()
            .map(|r| match r {
                Reply::Value { value } => Ok(*value),
                _ => Err(Refusal::new(
                    RTN_BAD_PAYLOAD,
                    "the engine returned no estimate",
                )),
            })
            .collect::<Result<Vec<f64>, Refusal>>()?;
        let added: f64 = ticks
            .chunks(2)
            .map(|pair| match pair {
                [all, held] => all - held,
                _ => 0.0,
            })
            .sum();
        out.f64(added * period_ms);
        Ok(())
    }));
    Ok(())
}

/// What the coordinate system holds as it would start: the group enabled (or a halted path
/// continued) and the override set as `NMC_CrdStartMtn` does, then what was pushed before
/// the calculation and not yet started.
fn held(c: &Call<'_>, group: GroupId, before: &CrdState) -> Vec<Command> {
    let mut out: Vec<Command> = Vec::new();
    let state = c
        .snapshot
        .groups
        .iter()
        .find(|g| g.group == group)
        .map(|g| g.state);
    match state {
        Some(GroupState::Disabled) => out.push(GroupEnable { group }.into()),
        Some(GroupState::Halted) => out.push(GroupContinue { group }.into()),
        _ => {}
    }
    if state.is_some() && before.override_factor != 1.0 {
        out.push(
            GroupSetOverride {
                group,
                factor: before.override_factor,
            }
            .into(),
        );
    }
    if !before.started {
        out.extend(before.pending.iter().cloned());
    }
    out
}
