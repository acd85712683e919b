//! The buffered laser and SHIO commands (digest 001 §2.12; S-LASER c, d and the SHIO example
//! b): pushed into the coordinate system's buffer like `NMC_CrdBufDO`, each one entry. Those
//! with an output image switch it when the path reaches them, through the engine's buffered
//! digital output (`GroupSetOutput`): laser on/off (its switch output), the gate on/off and the
//! gate pulse (the gate pin), a time array (its end state on the switch output). The others
//! (power, parameters, follow, SHIO parameters, axis mask, minimum frequency) have no output
//! image the engine can switch in path order: they hold their place in the buffer and are
//! stored when pushed (docs/decisions.md "NMC laser, SHIO and PWM").

use axes::command::{Command, GroupSetOutput};
use mcemu_nmc::table::{self, Function};

use super::crd_segment::{marker, Push};
use super::laser::{
    axis_mask, channel, check_power, gate_output, group, laser, read_param, store_param,
    switch_output, time_array_end, update,
};
use super::shio::{check_gate_time, need_shio_mode, pulse_args, shio_channel};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::CRD_BUF_LASER_ON_OFF, crd_buf_laser_on_off),
    (table::CRD_BUF_LASER_POWER, crd_buf_laser_power),
    (table::CRD_BUF_LASER_SET_FOLLOW, crd_buf_laser_set_follow),
    (table::CRD_BUF_LASER_SET_PARAM, crd_buf_laser_set_param),
    (
        table::CRD_BUF_LASER_TIME_ARRAY_EXE,
        crd_buf_laser_time_array_exe,
    ),
    (table::CRD_BUF_SHIO_GATE_PULSE, crd_buf_shio_gate_pulse),
    (table::CRD_BUF_SHIO_SET_PARAM, crd_buf_shio_set_param),
    (
        table::CRD_BUF_SHIO_CHANGE_AXIS_MASK,
        crd_buf_shio_change_axis_mask,
    ),
    (table::CRD_BUF_SHIO_SET_MIN_FRQ, crd_buf_shio_set_min_frq),
    (table::CRD_BUF_SHIO_CLR_MIN_FRQ, crd_buf_shio_clr_min_frq),
    (table::CRD_BUF_SHIO_SET_MIN_FRG, crd_buf_shio_set_min_frq),
    (table::CRD_BUF_SHIO_CLR_MIN_FRG, crd_buf_shio_clr_min_frq),
    (table::BUF_SHIO_GATE_ON, buf_shio_gate_on),
    (table::BUF_SHIO_GATE_OFF, buf_shio_gate_off),
];

/// The buffered switch of output `o` (none: an entry that switches nothing).
fn switch(p: &Push, o: Option<u16>, value: bool) -> Vec<Command> {
    o.map(|channel| {
        GroupSetOutput {
            group: p.group(),
            channel,
            value,
        }
        .into()
    })
    .into_iter()
    .collect()
}

/// Laser channel `ch` on or off at this point of the path: its switch output, or the stored
/// state when it has none (`LASER_NONE`).
fn push_on_off(c: &mut Call<'_>, p: Push, ch: usize, on: bool) -> Result<(), Refusal> {
    let l = laser(c);
    let o = switch_output(c, &l, ch);
    let commands = switch(&p, o, on);
    marker(c, p, commands)?;
    if o.is_none() {
        update(c, |l| {
            if let Some(k) = l.channels.get_mut(ch) {
                k.on = on;
            }
        });
    }
    Ok(())
}

/// onOff 0 off, 1 on.
fn crd_buf_laser_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let on = c.input.i16()?;
    let ch = channel(c)?;
    if !(0..=1).contains(&on) {
        return Err(Refusal::range("onOff", on, "{0, 1}"));
    }
    push_on_off(c, p, ch, on == 1)
}

/// power within the output type's range; stored when pushed.
fn crd_buf_laser_power(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let power = c.input.i64()?;
    let ch = channel(c)?;
    let t = laser(c).channels.get(ch).map_or(0, |k| k.output_type);
    check_power("power", t, power as f64)?;
    marker(c, p, Vec::new())?;
    update(c, |l| {
        if let Some(k) = l.channels.get_mut(ch) {
            k.power = power as f64;
        }
    });
    Ok(())
}

/// overRide ≥ 0 (0 cancels), followType 0 planned / 1 actual velocity; stored when pushed.
fn crd_buf_laser_set_follow(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (ratio, kind) = (c.input.f64()?, c.input.i16()?);
    let ch = channel(c)?;
    if !(ratio.is_finite() && ratio >= 0.0) {
        return Err(Refusal::range("overRide", ratio, "[0, ∞) (0 cancels)"));
    }
    if !(0..=1).contains(&kind) {
        return Err(Refusal::range("followType", kind, "{0 planned, 1 actual}"));
    }
    marker(c, p, Vec::new())?;
    update(c, |l| {
        if let Some(k) = l.channels.get_mut(ch) {
            k.follow_override = ratio;
            k.follow_type = kind;
        }
    });
    Ok(())
}

fn crd_buf_laser_set_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _segment = c.input.i64()?;
    let v = read_param(c)?;
    let ch = channel(c)?;
    marker(c, p, Vec::new())?;
    update(c, |l| {
        if let Some(k) = l.channels.get_mut(ch) {
            store_param(k, v);
        }
    });
    Ok(())
}

/// The time array's end state switches the channel at this point (time arrays are not timed).
fn crd_buf_laser_time_array_exe(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let g = group(c)?;
    let ch = channel(c)?;
    let (on, power) = time_array_end(c, g, ch)?;
    push_on_off(c, p, ch, on)?;
    update(c, |l| {
        if let Some(k) = l.channels.get_mut(ch) {
            k.power = power;
        }
    });
    Ok(())
}

/// SHIO mode only; a continuous train (outCount 0) holds the gate high from here, a counted
/// one leaves it low.
fn crd_buf_shio_gate_pulse(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let pulse = pulse_args(c, "gateTime")?;
    shio_channel(c, "ch")?;
    need_shio_mode(c)?;
    let commands = switch(&p, gate_output(c), pulse.2 == 0);
    marker(c, p, commands)?;
    update(c, |l| l.shio.gate_pulse = Some(pulse));
    Ok(())
}

/// delay ms ≥ 0, gateTime (0, 0.0009) s, gateDistance > 0 pulses; stored when pushed.
fn crd_buf_shio_set_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _segment = c.input.i64()?;
    let (delay, gate_time, distance) = (c.input.f64()?, c.input.f64()?, c.input.f64()?);
    shio_channel(c, "ch")?;
    if !(delay.is_finite() && delay >= 0.0) {
        return Err(Refusal::range("delay", delay, "[0, ∞) ms"));
    }
    check_gate_time(gate_time)?;
    if !(distance.is_finite() && distance > 0.0 && distance <= i64::MAX as f64) {
        return Err(Refusal::range("gateDistance", distance, "(0, ∞) pulses"));
    }
    marker(c, p, Vec::new())?;
    update(c, |l| {
        l.shio.para.delay = delay / 1e3;
        l.shio.para.gate_time = gate_time;
        l.shio.para.gate_distance = distance.round() as i64;
    });
    Ok(())
}

fn crd_buf_shio_change_axis_mask(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _segment = c.input.i64()?;
    let mask = c.input.i16()?;
    shio_channel(c, "ch")?;
    axis_mask(c, "axisMask", mask)?;
    marker(c, p, Vec::new())?;
    update(c, |l| l.shio.para.axis_mask = mask);
    Ok(())
}

/// minFrq > 0 Hz.
fn crd_buf_shio_set_min_frq(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _segment = c.input.i64()?;
    let f = c.input.i64()?;
    shio_channel(c, "ch")?;
    if f <= 0 {
        return Err(Refusal::range("minFrq", f, "(0, ∞) Hz"));
    }
    marker(c, p, Vec::new())?;
    update(c, |l| l.shio.min_frq = Some(f));
    Ok(())
}

fn crd_buf_shio_clr_min_frq(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _segment = c.input.i64()?;
    shio_channel(c, "ch")?;
    marker(c, p, Vec::new())?;
    update(c, |l| l.shio.min_frq = None);
    Ok(())
}

fn buf_shio_gate(c: &mut Call<'_>, on: bool) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    shio_channel(c, "ch")?;
    let commands = switch(&p, gate_output(c), on);
    marker(c, p, commands)
}

fn buf_shio_gate_on(c: &mut Call<'_>) -> Result<(), Refusal> {
    buf_shio_gate(c, true)
}

fn buf_shio_gate_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    buf_shio_gate(c, false)
}
