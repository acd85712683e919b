//! Position compare, 1-D and 2-D (digest 001 §2.11, §3.16, §4.6; S-CMP-2D, TV63): group g is
//! the engine's compare channel g; `NMC_Comp2DimensOnoff(…, 1, …)` starts it with the points
//! written since the last clear.

use axes::command::{
    CompareOutputMode, CompareStart, CompareStop, PositionSource, WriteDigitalOutput,
};
use mcemu_dialects::nmc::compare_status;
use mcemu_nmc::errors::RTN_UNSUPPORTED;
use mcemu_nmc::sync_structs::{Comp2DimensParam, Comp2DimensSts};
use mcemu_nmc::table::{self, Function};

use super::sync_args::{count_in, local_axis_number};
use crate::nmc::service::{Call, Handler, Refusal};
use crate::nmc::sync_state::CompareGroup;

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::COMP_2DIMENS_SET_PARAM_EX, set_param),
    (table::COMP_2DIMENS_GET_PARAM_EX, get_param),
    (table::COMP_2DIMENS_SET_DATA, set_data),
    (table::COMP_2DIMENS_ONOFF, onoff),
    (table::COMP_2DIMENS_STATUS_EX, status),
];

/// Points a group holds ("≤ 32896 points at once").
const CAPACITY: usize = 32896;

/// The group (0 or 1) and the reserved `chn` (0).
fn group(c: &mut Call<'_>) -> Result<usize, Refusal> {
    c.device()?;
    count_in("group", c.input.i16()?, 0, 1)
}

fn chn(c: &mut Call<'_>) -> Result<(), Refusal> {
    count_in("chn", c.input.i16()?, 0, 0).map(|_| ())
}

fn stored(c: &Call<'_>, g: usize) -> CompareGroup {
    c.service.sync().compare.get(g).cloned().unwrap_or_default()
}

/// The digital output a group drives: GPO `outputChn`, or for the GATE (HSIO) channel the
/// group's own output, the machine's last two (docs/decisions.md).
fn output(c: &Call<'_>, g: usize, p: &Comp2DimensParam) -> Result<u16, Refusal> {
    let outputs = c.snapshot.io.do_.len();
    let channel = if p.chn_type == 1 {
        (super::io_modules::local_outputs(c) + g).checked_sub(2)
    } else {
        usize::try_from(p.output_chn).ok()
    };
    channel
        .filter(|o| *o < outputs)
        .map(|o| o as u16)
        .ok_or_else(|| {
            Refusal::range(
                "outputChn",
                p.output_chn,
                &format!("[0, {}]", outputs.saturating_sub(1)),
            )
        })
}

/// dir1No/dir2No "0~11" (digest 001 §3.16): a local axis; the bus drives (16+) are beyond it.
fn compare_axis(c: &Call<'_>, name: &str, n: i16) -> Result<usize, Refusal> {
    local_axis_number(c, name, i64::from(n), 11)
}

fn set_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    let g = group(c)?;
    let p = Comp2DimensParam::read(&mut c.input)?;
    chn(c)?;
    compare_axis(c, "dir1No", p.dir1_no)?;
    if p.dir2_no != -1 {
        compare_axis(c, "dir2No", p.dir2_no)?;
    }
    for (name, v, high) in [
        ("outputType", p.output_type, 1),
        ("chnType", p.chn_type, 1),
        ("posSrc", p.pos_src, 1),
        ("stLevel", p.st_level, 1),
    ] {
        count_in(name, v, 0, high)?;
    }
    if p.err_zone < 0 {
        return Err(Refusal::range("errZone", p.err_zone, "[0, 32767] pulse"));
    }
    if p.gate_time < 0 || p.min_interval_time < 0 {
        return Err(Refusal::range(
            "gateTime/minIntervalTime",
            format!("{}/{}", p.gate_time, p.min_interval_time),
            "[0, ∞) µs",
        ));
    }
    output(c, g, &p)?;
    if let Some(s) = c.service.sync().compare.get_mut(g) {
        s.param = p;
    }
    Ok(())
}

fn get_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    let g = group(c)?;
    chn(c)?;
    stored(c, g).param.write(c.output);
    Ok(())
}

/// Appends `count` points ((X, Y) pairs; single positions for a 1-D group); count 0 clears.
/// Points written while the group runs take effect at its next start.
fn set_data(c: &mut Call<'_>) -> Result<(), Refusal> {
    let g = group(c)?;
    let values = mcemu_nmc::sync_structs::read_array(&mut c.input, |r| r.i64())?;
    let count = c.input.i16()?;
    chn(c)?;
    let group = stored(c, g);
    let n = count_in("count", count, 0, i16::MAX)?;
    if n == 0 {
        if let Some(s) = c.service.sync().compare.get_mut(g) {
            s.points.clear();
        }
        return Ok(());
    }
    let dims = if group.param.dir2_no < 0 { 1 } else { 2 };
    if values.len() != n * dims {
        return Err(Refusal::new(
            mcemu_nmc::errors::RTN_BAD_PAYLOAD,
            format!(
                "pArrayPos holds {} values, {n} points need {}",
                values.len(),
                n * dims
            ),
        ));
    }
    if group.points.len() + n > CAPACITY {
        return Err(Refusal::range(
            "count",
            n,
            &format!("[0, {}] (the free space)", CAPACITY - group.points.len()),
        ));
    }
    let points = values.chunks(dims).map(|p| {
        [
            p.first().copied().unwrap_or(0),
            p.get(1).copied().unwrap_or(0),
        ]
    });
    if let Some(s) = c.service.sync().compare.get_mut(g) {
        s.points.extend(points);
    }
    Ok(())
}

/// onOff 0 stop, 1 run the points written, 2 one manual output (level mode: the output
/// toggles; a manual pulse is refused, the engine having no timed single pulse).
fn onoff(c: &mut Call<'_>) -> Result<(), Refusal> {
    let g = group(c)?;
    let on = c.input.i16()?;
    chn(c)?;
    let s = stored(c, g);
    let p = s.param;
    let out = output(c, g, &p)?;
    match on {
        0 => c.command(CompareStop { channel: g as u8 }),
        1 => {
            let two_d = p.dir2_no >= 0;
            let x = compare_axis(c, "dir1No", p.dir1_no)?;
            let y = if two_d {
                Some(compare_axis(c, "dir2No", p.dir2_no)?)
            } else {
                None
            };
            let (px, py) = (
                c.scale(x).pulses_per_unit,
                c.scale(y.unwrap_or(x)).pulses_per_unit,
            );
            let start = CompareStart {
                channel: g as u8,
                axis: x as u16,
                axis_y: y.map(|a| a as u16),
                source: if p.pos_src == 1 {
                    PositionSource::Actual
                } else {
                    PositionSource::Commanded
                },
                positions: if two_d {
                    Vec::new()
                } else {
                    s.points.iter().map(|q| q[0] as f64 / px).collect()
                },
                start: None,
                interval: None,
                end: None,
                points: if two_d {
                    s.points
                        .iter()
                        .map(|q| [q[0] as f64 / px, q[1] as f64 / py])
                        .collect()
                } else {
                    Vec::new()
                },
                error_zone: f64::from(p.err_zone) / px,
                // vibrateRange, "jitter filter range" (digest 001 §3.16): HMC's dDisturbValue.
                disturbance: f64::from(p.vibrate_range.max(0)) / px,
                output: out,
                mode: if p.output_type == 1 {
                    CompareOutputMode::Toggle
                } else {
                    CompareOutputMode::Pulse
                },
                // Level mode starts at stLevel, so the first point switches to the other level.
                level: if p.output_type == 1 {
                    p.st_level == 0
                } else {
                    true
                },
                pulse_width: p.gate_time as f64 * 1e-6,
                min_interval: p.min_interval_time as f64 * 1e-6,
            };
            c.command(start);
        }
        2 if p.output_type == 1 => {
            let now = c.snapshot.io.do_.get(usize::from(out)).copied().unwrap_or(false);
            c.command(WriteDigitalOutput {
                channel: out,
                value: !now,
            });
        }
        2 => {
            return Err(Refusal::new(
                RTN_UNSUPPORTED,
                "a manual compare pulse (onOff 2 with outputType 0) is not emulated; level mode toggles",
            ))
        }
        v => return Err(Refusal::range("onOff", v, "{0 stop, 1 run, 2 manual}")),
    }
    Ok(())
}

/// sts 1 busy / 0 idle, points not yet output, outputs so far; before a start the points
/// written count as not yet output.
pub(super) fn status(c: &mut Call<'_>) -> Result<(), Refusal> {
    let g = group(c)?;
    chn(c)?;
    let k = c
        .snapshot
        .compares
        .iter()
        .find(|k| usize::from(k.channel) == g);
    let (sts, used, out) = match k {
        Some(_) => compare_status(k),
        None => (
            0,
            i32::try_from(stored(c, g).points.len()).unwrap_or(i32::MAX),
            0,
        ),
    };
    Comp2DimensSts {
        sts,
        free_space: CAPACITY as i64 - i64::from(used),
        used_space: i64::from(used),
        out_count: i64::from(out),
    }
    .write(c.output);
    Ok(())
}
