//! Gantry and handwheel (digest 001 §2.9–2.10, §4.7; S-GANTRY, S-HANDWHEEL, TV73): the gantry
//! groups and the handwheel are the device's; each change is a `gantry_enable` /
//! `gantry_disable` or `handwheel_in` / `handwheel_out`.

use axes::command::{
    Command, GantryDisable, GantryEnable, HandwheelExcess, HandwheelIn, HandwheelOut,
};
use mcemu_dialects::nmc::{acceleration_to_engine, velocity_to_engine};
use mcemu_nmc::table::{self, Function};

use super::sync_args::{axis_number, finite};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::SET_GANTRY_MASTER, set_gantry_master),
    (table::SET_GANTRY_SLAVE, set_gantry_slave),
    (table::DEL_GANTRY_GROUP, del_gantry_group),
    (table::SET_HAND_WHEEL, set_hand_wheel),
    (table::SET_HAND_WHEEL_INPUT, set_hand_wheel_input),
    (table::SET_HAND_WHEEL_RATIO, set_hand_wheel_ratio),
    (table::CLR_HAND_WHEEL, clr_hand_wheel),
];

/// `MT_GANTRY_MODE` (digest 001 §3.2): what a slave's `NMC_MtGetPrfMode` reads.
const MT_GANTRY_MODE: i16 = 4;

/// group ∈ [0, axes − 1] (a group needs a master of its own).
fn group_no(c: &mut Call<'_>) -> Result<i16, Refusal> {
    let g = c.input.i16()?;
    let axes = c.snapshot.axes.len();
    if usize::try_from(g).is_ok_and(|g| g < axes) {
        Ok(g)
    } else {
        Err(Refusal::range(
            "group",
            g,
            &format!(
                "[0, {}] (one group per axis at most)",
                axes.saturating_sub(1)
            ),
        ))
    }
}

/// A group's master; replaces the group (its slaves are released).
fn set_gantry_master(c: &mut Call<'_>) -> Result<(), Refusal> {
    let master = c.axis()?;
    let g = group_no(c)?;
    let old = {
        let mut s = c.service.sync();
        let old = s
            .gantry
            .iter()
            .position(|(k, ..)| *k == g)
            .map(|i| s.gantry.remove(i));
        s.gantry.push((g, master, Vec::new()));
        old
    };
    if let Some((_, m, slaves)) = old.filter(|(_, _, s)| !s.is_empty()) {
        c.command(GantryDisable { master: m as u16 });
        for (a, _) in slaves {
            c.update(a, |s| s.prf_mode = 0);
        }
    }
    Ok(())
}

/// gantryErrLmt ∈ (0, 32767] (TV73): the engine's fault limit, the smallest of the group's.
fn set_gantry_slave(c: &mut Call<'_>) -> Result<(), Refusal> {
    let slave = c.axis()?;
    let g = group_no(c)?;
    let limit = c.input.i64()?;
    if !(1..=32767).contains(&limit) {
        return Err(Refusal::range("gantryErrLmt", limit, "(0, 32767] pulse"));
    }
    let group = c
        .service
        .sync()
        .gantry
        .iter()
        .find(|(k, ..)| *k == g)
        .cloned();
    let Some((_, master, mut slaves)) = group else {
        return Err(Refusal::range(
            "group",
            g,
            "a group whose master NMC_SetGantryMaster set",
        ));
    };
    if slave == master {
        return Err(Refusal::range(
            "axisHandle",
            slave,
            "an axis other than the group's master",
        ));
    }
    let was_on = !slaves.is_empty();
    slaves.retain(|(a, _)| *a != slave);
    slaves.push((slave, limit));
    if slaves.len() > axes::command::MAX_GANTRY_SLAVES {
        return Err(Refusal::range(
            "slaves",
            slaves.len(),
            "at most 7 per group",
        ));
    }
    if was_on {
        c.command(GantryDisable {
            master: master as u16,
        });
    }
    let fault = slaves.iter().map(|(_, l)| *l).min().unwrap_or(limit);
    c.command(GantryEnable {
        master: master as u16,
        slaves: slaves.iter().map(|(a, _)| *a as u16).collect(),
        warning_limit: 0.0,
        fault_limit: fault as f64 / c.scale(master).pulses_per_unit,
        require_disabled: false,
        closed_loop: false,
    });
    for (a, _) in &slaves {
        c.update(*a, |s| s.prf_mode = MT_GANTRY_MODE);
    }
    if let Some(e) = c.service.sync().gantry.iter_mut().find(|(k, ..)| *k == g) {
        e.2 = slaves;
    }
    Ok(())
}

/// The handle is the group's master.
fn del_gantry_group(c: &mut Call<'_>) -> Result<(), Refusal> {
    let master = c.axis()?;
    let g = group_no(c)?;
    let removed = {
        let mut s = c.service.sync();
        match s
            .gantry
            .iter()
            .position(|(k, m, _)| *k == g && *m == master)
        {
            Some(i) => s.gantry.remove(i),
            None => {
                return Err(Refusal::range(
                    "group",
                    g,
                    "a gantry group whose master is this axis",
                ))
            }
        }
    };
    if !removed.2.is_empty() {
        c.command(GantryDisable {
            master: master as u16,
        });
    }
    for (a, _) in removed.2 {
        c.update(a, |s| s.prf_mode = 0);
    }
    Ok(())
}

fn handwheel_in(
    c: &Call<'_>,
    axis: usize,
    ratio: f64,
    acc: f64,
    vel: f64,
) -> Result<Command, Refusal> {
    for (name, v) in [("ratio", ratio), ("acc", acc), ("vel", vel)] {
        if finite(name, v)? <= 0.0 {
            return Err(Refusal::range(name, v, "(0, ∞)"));
        }
    }
    let scale = c.scale(axis);
    Ok(HandwheelIn {
        axis: axis as u16,
        input: c.service.sync().handwheel_input,
        numerator: ratio / scale.pulses_per_unit,
        denominator: 1.0,
        velocity: velocity_to_engine(scale, vel),
        acceleration: acceleration_to_engine(scale, acc),
        excess: HandwheelExcess::CatchUp,
    }
    .into())
}

/// Axis `axis` follows the handwheel input × ratio (pulses per count), acc pulse/ms², vel
/// pulse/ms; a handwheel on another axis is released first.
fn set_hand_wheel(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let axis = c.input.i16()?;
    let (ratio, acc, vel) = (c.input.f64()?, c.input.f64()?, c.input.f64()?);
    let axis = axis_number(c, "axis", i64::from(axis))?;
    let wheel_in = handwheel_in(c, axis, ratio, acc, vel)?;
    let old = c.service.sync().handwheel;
    if let Some((old, ..)) = old.filter(|(a, ..)| on_handwheel(c, *a)) {
        c.plan
            .commands
            .push(HandwheelOut { axis: old as u16 }.into());
    }
    c.command(wheel_in);
    c.service.sync().handwheel = Some((axis, ratio, acc, vel));
    Ok(())
}

/// index: an axis's encoder [0, n), or 256 / 257 the external encoders (default 256); taken by
/// the next `NMC_SetHandWheel`.
fn set_hand_wheel_input(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let index = c.input.i16()?;
    let axes = c.snapshot.axes.len();
    let ok = usize::try_from(index).is_ok_and(|i| i < axes) || index == 256 || index == 257;
    if !ok {
        return Err(Refusal::range(
            "index",
            index,
            &format!(
                "[0, {}] (an axis encoder) or 256, 257",
                axes.saturating_sub(1)
            ),
        ));
    }
    c.service.sync().handwheel_input = index as u16;
    Ok(())
}

/// The engine has no live ratio change for a handwheel: the axis is released and taken again
/// with the new ratio in one batch, which the engine accepts only once the axis is at rest
/// (docs/decisions.md).
fn set_hand_wheel_ratio(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ratio = c.input.f64()?;
    let Some((axis, _, acc, vel)) = c.service.sync().handwheel else {
        return Err(Refusal::new(
            mcemu_nmc::errors::RTN_ARG_RANGE,
            "no handwheel is on: NMC_SetHandWheel first",
        ));
    };
    let wheel_in = handwheel_in(c, axis, ratio, acc, vel)?;
    c.command(HandwheelOut { axis: axis as u16 });
    c.command(wheel_in);
    c.service.sync().handwheel = Some((axis, ratio, acc, vel));
    Ok(())
}

/// Whether the engine has axis `axis` on a handwheel (a refused `handwheel_in` left none).
fn on_handwheel(c: &Call<'_>, axis: usize) -> bool {
    c.snapshot
        .handwheels
        .iter()
        .any(|h| usize::from(h.axis) == axis)
}

/// Leaves handwheel mode; nothing to do when none is on (S-HANDWHEEL calls it first).
fn clr_hand_wheel(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let wheel = c.service.sync().handwheel.take();
    if let Some((axis, ..)) = wheel.filter(|(a, ..)| on_handwheel(c, *a)) {
        c.command(HandwheelOut { axis: axis as u16 });
    }
    Ok(())
}
