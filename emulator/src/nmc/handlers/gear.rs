//! Electronic gear (digest 001 §2.16, §4.7; S-GEAR, TV58): the settings are the device's until
//! `NMC_MtGearStartMtn` couples each named slave to its master with a `gear_in`.

use axes::command::{Command, Direction, GearIn, GearSetRatio, MasterSource};
use mcemu_nmc::table::{self, Function};

use super::sync_args::{axes_to_start, axis_number, stored_axis};
use crate::nmc::service::{Call, Handler, Refusal};
use crate::nmc::sync_state::AxisSync;

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_GEAR_SET_DIR, mt_gear_set_dir),
    (table::MT_GEAR_GET_DIR, mt_gear_get_dir),
    (table::MT_GEAR_SET_MASTER, mt_gear_set_master),
    (table::MT_GEAR_GET_MASTER, mt_gear_get_master),
    (table::MT_GEAR_SET_RATIO, mt_gear_set_ratio),
    (table::MT_GEAR_GET_RATIO, mt_gear_get_ratio),
    (table::MT_GEAR_START_MTN, mt_gear_start_mtn),
];

/// `MT_GEAR_PRF_MODE` (digest 001 §3.2): what `NMC_MtGetPrfMode` reads once the gear runs.
const MT_GEAR_PRF_MODE: i16 = 7;

fn axis_sync(c: &Call<'_>, axis: usize) -> AxisSync {
    c.service.sync().axes.get(axis).cloned().unwrap_or_default()
}

fn update(c: &Call<'_>, axis: usize, f: impl FnOnce(&mut AxisSync)) {
    if let Some(s) = c.service.sync().axes.get_mut(axis) {
        f(s);
    }
}

fn mt_gear_set_dir(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let dir = c.input.i16()?;
    update(c, axis, |s| s.gear_dir = dir);
    Ok(())
}

fn mt_gear_get_dir(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.output.i16(axis_sync(c, axis).gear_dir);
    Ok(())
}

fn mt_gear_set_master(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (no, kind) = (c.input.i16()?, c.input.i16()?);
    let master = axis_number(c, "masterNo", i64::from(no))?;
    if !(1..=3).contains(&kind) {
        return Err(Refusal::range(
            "masterType",
            kind,
            "{1 planned, 2 feedback, 3 encoder}",
        ));
    }
    if master == axis {
        return Err(Refusal::range(
            "masterNo",
            no,
            "another axis than the slave's",
        ));
    }
    update(c, axis, |s| {
        s.gear_master = no;
        s.gear_master_type = kind;
    });
    Ok(())
}

fn mt_gear_get_master(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let s = axis_sync(c, axis);
    c.output.i16(s.gear_master).i16(s.gear_master_type);
    Ok(())
}

/// The engine's ratio of slave to master travel in user units.
fn ratio(c: &Call<'_>, slave: usize, s: &AxisSync) -> (f64, f64) {
    let master = stored_axis(c, s.gear_master);
    (
        s.gear_slave_even as f64 / c.scale(slave).pulses_per_unit,
        s.gear_master_even as f64 / c.scale(master).pulses_per_unit,
    )
}

/// masterSlope "必须大于 0, 同时不能等于 1" yet "0 表示没有离合区": 0 is no clutch, 1 and
/// negatives are refused (docs/decisions.md). May change during motion: a running gear takes
/// the new ratio through its clutch.
fn mt_gear_set_ratio(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (master_even, slave_even, slope) = (c.input.i64()?, c.input.i64()?, c.input.i64()?);
    if master_even == 0 {
        return Err(Refusal::range("masterEven", master_even, "≠ 0"));
    }
    if slope < 0 || slope == 1 {
        return Err(Refusal::range(
            "masterSlope",
            slope,
            "0 (no clutch) or [2, ∞) pulses",
        ));
    }
    update(c, axis, |s| {
        s.gear_master_even = master_even;
        s.gear_slave_even = slave_even;
        s.gear_master_slope = slope;
    });
    let running = c
        .snapshot
        .couplings
        .iter()
        .any(|k| usize::from(k.slave) == axis && k.kind == axes::status::CouplingKind::Gear);
    if running {
        let (numerator, denominator) = ratio(c, axis, &axis_sync(c, axis));
        c.command(GearSetRatio {
            slave: axis as u16,
            numerator,
            denominator,
        });
    }
    Ok(())
}

fn mt_gear_get_ratio(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let s = axis_sync(c, axis);
    c.output
        .i64(s.gear_master_even)
        .i64(s.gear_slave_even)
        .i64(s.gear_master_slope);
    Ok(())
}

/// The `gear_in` of slave `axis` from its settings.
fn gear_in(c: &Call<'_>, axis: usize) -> Command {
    let s = axis_sync(c, axis);
    let (numerator, denominator) = ratio(c, axis, &s);
    let master = stored_axis(c, s.gear_master);
    GearIn {
        master: master as u16,
        slave: axis as u16,
        numerator,
        denominator,
        master_source: match s.gear_master_type {
            2 => MasterSource::Actual,
            3 => MasterSource::Encoder,
            _ => MasterSource::Commanded,
        },
        clutch_distance: (s.gear_master_slope > 0)
            .then(|| s.gear_master_slope as f64 / c.scale(master).pulses_per_unit),
        acceleration: None,
        phase_offset: 0,
        transition: false,
        direction: match s.gear_dir {
            0 => None,
            d if d > 0 => Some(Direction::Positive),
            _ => Some(Direction::Negative),
        },
    }
    .into()
}

/// Couples the handle's axis and the other axes named, each to its own master, in one batch.
fn mt_gear_start_mtn(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axes = axes_to_start(c)?;
    for &a in &axes {
        let g = gear_in(c, a);
        c.command(g);
    }
    for a in axes {
        c.update(a, |s| s.prf_mode = MT_GEAR_PRF_MODE);
    }
    Ok(())
}
