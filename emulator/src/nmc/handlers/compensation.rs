//! Mechanical compensation (digest 001 §2.19, §4.1; S-LEADSCREW, S-BACKLASH, S-2DCOMP, TV72):
//! the lead-screw, backlash and 2-D tables are the engine's compensation tables of the axis
//! (they add up); a table switched off is installed as zeros, so that switching one kind off
//! leaves the others running (the engine's on/off switch is per axis).

use axes::command::{
    BacklashDirection, Command, CompensationBacklash, CompensationLeadScrew, CompensationReference,
    CompensationTable, ReferenceSource,
};
use mcemu_nmc::sync_structs::{Comp2D, Comp2DTable, CompData};
use mcemu_nmc::table::{self, Function};

use super::sync_args::{array_of, axis_number, count_in};
use crate::nmc::service::{Call, Handler, Refusal};
use crate::nmc::sync_state::LeadScrew;

pub const HANDLERS: &[(Function, Handler)] = &[
    (
        table::MT_SET_LEAD_SCREW_COMP_PARA,
        mt_set_lead_screw_comp_para,
    ),
    (table::MT_ENABLE_LEAD_SCREW, mt_enable_lead_screw),
    (table::MT_SET_BACKLASH, mt_set_backlash),
    (table::MT_GET_BACKLASH, mt_get_backlash),
    (table::SET_2D_COMPENSATION_TABLE, set_2d_compensation_table),
    (table::GET_2D_COMPENSATION_TABLE, get_2d_compensation_table),
    (table::SET_2D_COMPENSATION, set_2d_compensation),
    (table::GET_2D_COMPENSATION, get_2d_compensation),
];

/// X·Y·3 ≤ 3000 values.
const MAX_GRID_POINTS: usize = 1000;

/// The lead-screw table of `axis`: corrections at startPos + i·cmpLen/(num − 1), zeros when
/// switched off.
fn lead_screw(c: &Call<'_>, axis: usize, t: &LeadScrew, on: bool) -> Command {
    let ppu = c.scale(axis).pulses_per_unit;
    let n = t.positive.len();
    let step = t.length as f64 / (n.saturating_sub(1).max(1)) as f64;
    let value = |v: &i16| if on { f64::from(*v) / ppu } else { 0.0 };
    CompensationLeadScrew {
        axis: axis as u16,
        positions: (0..n)
            .map(|i| (t.start as f64 + step * i as f64) / ppu)
            .collect(),
        positive: t.positive.iter().map(value).collect(),
        negative: Some(t.negative.iter().map(value).collect()),
        enable: true,
    }
    .into()
}

/// num ∈ [2, 128]; cmpLen > 0; the table takes effect when `NMC_MtEnableLeadScrew(1)`.
fn mt_set_lead_screw_comp_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let n = count_in("num", c.input.i16()?, 2, 128)?;
    let (start, length) = (c.input.i64()?, c.input.i64()?);
    let positive = array_of(c, "pCompPos", n, |r| r.i16())?;
    let negative = array_of(c, "pCompNeg", n, |r| r.i16())?;
    if length <= 0 {
        return Err(Refusal::range("cmpLen", length, "(0, ∞) pulse"));
    }
    let t = LeadScrew {
        start,
        length,
        positive,
        negative,
    };
    let on = c
        .service
        .sync()
        .axes
        .get(axis)
        .is_some_and(|s| s.lead_screw_on);
    let command = lead_screw(c, axis, &t, on);
    c.command(command);
    if let Some(s) = c.service.sync().axes.get_mut(axis) {
        s.lead_screw = Some(t);
    }
    Ok(())
}

fn mt_enable_lead_screw(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let on = count_in("enable", c.input.i16()?, 0, 1)? == 1;
    let table = c
        .service
        .sync()
        .axes
        .get(axis)
        .and_then(|s| s.lead_screw.clone());
    match table {
        Some(t) => {
            let command = lead_screw(c, axis, &t, on);
            c.command(command);
        }
        None if on => {
            return Err(Refusal::range(
                "enable",
                1,
                "0 until NMC_MtSetLeadScrewCompPara gave a table",
            ))
        }
        None => {}
    }
    if let Some(s) = c.service.sync().axes.get_mut(axis) {
        s.lead_screw_on = on;
    }
    Ok(())
}

/// compValue ≥ 0 pulses (0 removes it), compDelta > 0 pulses per planning period, compDir 0
/// positive / 1 negative (TV72).
fn mt_set_backlash(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (value, delta, dir) = (c.input.i64()?, c.input.f64()?, c.input.i64()?);
    if value < 0 {
        return Err(Refusal::range("compValue", value, "[0, ∞) pulse"));
    }
    if !(delta.is_finite() && delta > 0.0) {
        return Err(Refusal::range(
            "compDelta",
            delta,
            "(0, ∞) pulse per period",
        ));
    }
    let direction = match dir {
        0 => BacklashDirection::Positive,
        1 => BacklashDirection::Negative,
        v => return Err(Refusal::range("compDir", v, "{0 positive, 1 negative}")),
    };
    let ppu = c.scale(axis).pulses_per_unit;
    c.command(CompensationBacklash {
        axis: axis as u16,
        amount: value as f64 / ppu,
        step: delta / ppu,
        direction,
        enable: true,
    });
    if let Some(s) = c.service.sync().axes.get_mut(axis) {
        s.backlash = (value, delta, dir);
    }
    Ok(())
}

fn mt_get_backlash(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (v, d, dir) = c
        .service
        .sync()
        .axes
        .get(axis)
        .map_or((0, 0.0, 0), |s| s.backlash);
    c.output.i64(v).f64(d).i64(dir);
    Ok(())
}

fn table_index(c: &mut Call<'_>) -> Result<(), Refusal> {
    count_in("tableIndex", c.input.i16()?, 0, 0).map(|_| ())
}

/// count[k] ≥ 2, X·Y·3 ≤ 3000, step > 0, |angle| ≤ 360°.
fn set_2d_compensation_table(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    table_index(c)?;
    let t = Comp2DTable::read(&mut c.input)?;
    let x = count_in("count[0]", t.count[0], 2, 500)?;
    let y = count_in("count[1]", t.count[1], 2, 500)?;
    if x * y > MAX_GRID_POINTS {
        return Err(Refusal::range(
            "count[0] × count[1]",
            x * y,
            "[4, 1000] (X·Y·3 ≤ 3000 values)",
        ));
    }
    if t.step.iter().any(|s| *s <= 0) {
        return Err(Refusal::range(
            "step",
            format!("{:?}", t.step),
            "(0, ∞) pulse each",
        ));
    }
    // The table's axes turned about its first point (docs/decisions.md, the engine's rule).
    if !(t.angle.is_finite() && t.angle.abs() <= 360.0) {
        return Err(Refusal::range("angle", t.angle, "[-360, 360] degrees"));
    }
    let data = array_of(c, "pData", x * y, CompData::read)?;
    let comp = {
        let mut s = c.service.sync();
        s.comp_table = Some((t, data));
        s.comp
    };
    if comp.enable == 1 {
        apply_2d(c, &comp)?;
    }
    Ok(())
}

fn get_2d_compensation_table(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    table_index(c)?;
    let (t, data) = c.service.sync().comp_table.clone().unwrap_or_default();
    t.write(c.output);
    mcemu_nmc::sync_structs::write_array(c.output, &data, |w, d| d.write(w));
    Ok(())
}

/// One engine table per corrected axis (axisIndex X, Y, Z), referenced to the X and Y axes
/// (axisType 0 planned, 1 encoder); a switched-off table is installed as zeros.
fn apply_2d(c: &mut Call<'_>, comp: &Comp2D) -> Result<(), Refusal> {
    let Some((t, data)) = c.service.sync().comp_table.clone() else {
        return Err(Refusal::range(
            "tableIndex",
            comp.table_index,
            "a table NMC_Set2DCompensationTable wrote",
        ));
    };
    let [rx, ry] = [0, 1].map(|k| comp.axis_index[k]);
    let refs = [rx, ry]
        .iter()
        .map(|a| axis_number(c, "axisIndex[0/1]", i64::from(*a)))
        .collect::<Result<Vec<_>, _>>()?;
    let references: Vec<CompensationReference> = refs
        .iter()
        .zip(comp.axis_type)
        .map(|(a, kind)| CompensationReference {
            axis: *a as u16,
            source: if kind == 1 {
                ReferenceSource::Actual
            } else {
                ReferenceSource::Planned
            },
        })
        .collect();
    let ppu: Vec<f64> = refs.iter().map(|a| c.scale(*a).pulses_per_unit).collect();
    let on = comp.enable == 1;
    for (k, corrected) in comp.axis_index.iter().enumerate() {
        if *corrected < 0 {
            continue;
        }
        let axis = axis_number(c, "axisIndex[k]", i64::from(*corrected))?;
        let scale = c.scale(axis).pulses_per_unit;
        let values = data
            .iter()
            .map(|d| {
                let v = [d.x, d.y, d.z].get(k).copied().unwrap_or(0);
                if on {
                    v as f64 / scale
                } else {
                    0.0
                }
            })
            .collect();
        c.command(CompensationTable {
            axis: axis as u16,
            references: references.clone(),
            start: t
                .pos_begin
                .iter()
                .zip(&ppu)
                .map(|(p, u)| *p as f64 / u)
                .collect(),
            step: t
                .step
                .iter()
                .zip(&ppu)
                .map(|(s, u)| *s as f64 / u)
                .collect(),
            count: t
                .count
                .iter()
                .map(|n| u32::try_from(*n).unwrap_or(0))
                .collect(),
            values,
            enable: true,
            angle: t.angle,
            interpolation: Default::default(),
        });
    }
    Ok(())
}

fn set_2d_compensation(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let comp = Comp2D::read(&mut c.input)?;
    count_in("enable", comp.enable, 0, 1)?;
    count_in("tableIndex", comp.table_index, 0, 0)?;
    for t in comp.axis_type {
        count_in("axisType", t, 0, 1)?;
    }
    let was_on = c.service.sync().comp.enable == 1;
    if comp.enable == 1 || was_on {
        apply_2d(c, &comp)?;
    }
    c.service.sync().comp = comp;
    Ok(())
}

fn get_2d_compensation(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let comp = c.service.sync().comp;
    comp.write(c.output);
    Ok(())
}
