//! SHIO, the high-speed gate of the laser's position-compare mode, and the PWM outputs (digest
//! 001 §2.12, §3.20; S-LASER SHIO examples). Stored and read back (`crate::nmc::laser_state`);
//! the gate pin is echoed on the machine's output `outputs − 2` (the HSIO compare group 0's
//! GATE drives too), high while the gate is on (docs/decisions.md "NMC laser, SHIO and PWM").
//! The travel-driven gate pulses (outMode 2–4), the trigger and the timed pulse trains are not
//! generated: a continuous train (outCount 0) holds its pin high, a counted one leaves it low
//! as it ends.

use axes::command::WriteDigitalOutput;
use mcemu_nmc::laser::ShioPara;
use mcemu_nmc::table::{self, Function};

use super::laser::{
    axis_mask, channel, drive, gate_output, laser, release_switch, switch_output, update,
    SHIO_OUTPUT_MODE,
};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::SHIO_CONFIG_PARA, shio_config_para),
    (table::SHIO_ENABLE_MIN_FRQ, shio_enable_min_frq),
    (table::SHIO_DISABLE_MIN_FRQ, shio_disable_min_frq),
    (table::SHIO_ENABLE_MIN_FRG, shio_enable_min_frq),
    (table::SHIO_DISABLE_MIN_FRG, shio_disable_min_frq),
    (table::SHIO_CHANGE_AXIS_MASK, shio_change_axis_mask),
    (table::SHIO_GATE_ON, shio_gate_on),
    (table::SHIO_GATE_OFF, shio_gate_off),
    (table::SHIO_TRIGGER_ON, shio_trigger_on),
    (table::SHIO_TRIGGER_OFF, shio_trigger_off),
    (table::SHIO_GATE_PULSE, shio_gate_pulse),
    (table::SET_PWM_TO_GATE, set_pwm_to_gate),
    (table::PWM_PULSE_OUT, pwm_pulse_out),
    (table::SET_PWM_PORT, set_pwm_port),
    (table::GET_PWM_PORT, get_pwm_port),
];

/// The SHIO channel argument: 0 only ("目前只为 0").
pub(super) fn shio_channel(c: &mut Call<'_>, name: &str) -> Result<(), Refusal> {
    let ch = c.input.i16()?;
    if ch == 0 {
        Ok(())
    } else {
        Err(Refusal::range(name, ch, "{0}"))
    }
}

/// gateTime in seconds, (0, 0.0009).
pub(super) fn check_gate_time(t: f64) -> Result<(), Refusal> {
    if t.is_finite() && t > 0.0 && t < 0.0009 {
        Ok(())
    } else {
        Err(Refusal::range("gateTime", t, "(0, 0.0009) s"))
    }
}

/// The pulse-train arguments of the gate and PWM pulses: width µs > 0, frequency Hz > 0, count
/// ≥ 0 (0 continuous).
pub(super) fn pulse_args(c: &mut Call<'_>, width: &str) -> Result<(f64, f64, i64), Refusal> {
    let (t, f, n) = (c.input.f64()?, c.input.f64()?, c.input.i64()?);
    if !(t.is_finite() && t > 0.0) {
        return Err(Refusal::range(width, t, "(0, ∞) µs"));
    }
    if !(f.is_finite() && f > 0.0) {
        return Err(Refusal::range("frequency", f, "(0, ∞) Hz"));
    }
    if n < 0 {
        return Err(Refusal::range("outCount", n, "[0, ∞) (0 continuous)"));
    }
    Ok((t, f, n))
}

/// The pulse functions work in `SHIO_OUTPUT_MODE` only ("必须在激光 SHIO 控制模式下使用").
pub(super) fn need_shio_mode(c: &Call<'_>) -> Result<(), Refusal> {
    let mode = laser(c).channels.first().map_or(0, |k| k.mode);
    if mode == SHIO_OUTPUT_MODE {
        Ok(())
    } else {
        Err(Refusal::new(
            mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidState),
            format!(
                "laser channel 0 is in mode {mode}; gate and PWM pulses need SHIO_OUTPUT_MODE (3)"
            ),
        ))
    }
}

/// isArray 0 only (fixed pitch, "仅支持"); outMode [1, 4]; posSrc {0, 1}; gateTime (0, 0.0009)
/// s; delay ≥ 0; travel modes 2–4 need gateDistance > 0 and axes; lowFrqRange [0, 2].
fn shio_config_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let p = ShioPara::read(&mut c.input)?;
    shio_channel(c, "ch")?;
    if p.is_array != 0 {
        return Err(Refusal::range(
            "isArray",
            p.is_array,
            "{0} (fixed pitch only)",
        ));
    }
    if !(1..=4).contains(&p.out_mode) {
        return Err(Refusal::range("outMode", p.out_mode, "[1, 4]"));
    }
    if !(0..=1).contains(&p.pos_src) {
        return Err(Refusal::range(
            "posSrc",
            p.pos_src,
            "{0 encoder, 1 planned}",
        ));
    }
    if !(p.delay.is_finite() && p.delay >= 0.0) {
        return Err(Refusal::range("delay", p.delay, "[0, ∞) s"));
    }
    check_gate_time(p.gate_time)?;
    axis_mask(c, "axisMask", p.axis_mask)?;
    if p.out_mode >= 2 && (p.gate_distance <= 0 || p.axis_mask == 0) {
        return Err(Refusal::range(
            "gateDistance",
            p.gate_distance,
            "(0, ∞) pulses with a non-zero axisMask in outMode 2–4",
        ));
    }
    if !(0..=2).contains(&p.low_frq_range) {
        return Err(Refusal::range("lowFrqRange", p.low_frq_range, "[0, 2]"));
    }
    update(c, |l| l.shio.para = p);
    Ok(())
}

/// minFrq > 0 Hz.
fn shio_enable_min_frq(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let f = c.input.i64()?;
    shio_channel(c, "ch")?;
    if f <= 0 {
        return Err(Refusal::range("minFrq", f, "(0, ∞) Hz"));
    }
    update(c, |l| l.shio.min_frq = Some(f));
    Ok(())
}

fn shio_disable_min_frq(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    shio_channel(c, "ch")?;
    update(c, |l| l.shio.min_frq = None);
    Ok(())
}

fn shio_change_axis_mask(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let mask = c.input.i16()?;
    shio_channel(c, "ch")?;
    axis_mask(c, "axisMask", mask)?;
    update(c, |l| l.shio.para.axis_mask = mask);
    Ok(())
}

fn set_gate(c: &mut Call<'_>, on: bool) {
    if let Some(o) = gate_output(c) {
        c.command(WriteDigitalOutput {
            channel: o,
            value: on,
        });
    }
}

fn shio_gate_on(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    shio_channel(c, "ch")?;
    set_gate(c, true);
    Ok(())
}

fn shio_gate_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    shio_channel(c, "ch")?;
    update(c, |l| l.shio.gate_pulse = None);
    set_gate(c, false);
    Ok(())
}

/// freq > 0 Hz, width (0, 1/freq) s.
fn shio_trigger_on(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (freq, width) = (c.input.f64()?, c.input.f64()?);
    shio_channel(c, "ch")?;
    if !(freq.is_finite() && freq > 0.0) {
        return Err(Refusal::range("freq", freq, "(0, ∞) Hz"));
    }
    if !(width.is_finite() && width > 0.0 && width < 1.0 / freq) {
        return Err(Refusal::range("width", width, "(0, 1/freq) s"));
    }
    update(c, |l| l.shio.trigger = Some((freq, width)));
    Ok(())
}

fn shio_trigger_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    shio_channel(c, "ch")?;
    update(c, |l| l.shio.trigger = None);
    Ok(())
}

fn shio_gate_pulse(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let pulse = pulse_args(c, "gateTime")?;
    shio_channel(c, "ch")?;
    need_shio_mode(c)?;
    update(c, |l| l.shio.gate_pulse = Some(pulse));
    set_gate(c, pulse.2 == 0);
    Ok(())
}

/// pwmCh 0, gateCh 0, onOff {0, 1}: PWM 0 comes out on the gate pin (laser channel 0's switch
/// output moves there).
fn set_pwm_to_gate(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (pwm, gate, on) = (c.input.i16()?, c.input.i16()?, c.input.i16()?);
    if pwm != 0 {
        return Err(Refusal::range("pwmCh", pwm, "{0}"));
    }
    if gate != 0 {
        return Err(Refusal::range("gateCh", gate, "{0}"));
    }
    if !(0..=1).contains(&on) {
        return Err(Refusal::range("onOff", on, "{0, 1}"));
    }
    release_switch(c, 0);
    update(c, |l| l.shio.pwm_to_gate = on == 1);
    drive(c, 0);
    Ok(())
}

/// A PWM pulse train on channel 0 (SHIO mode only): its switch output is high for a
/// continuous train and low when a counted one ends.
fn pwm_pulse_out(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let pulse = pulse_args(c, "onTime")?;
    shio_channel(c, "ch")?;
    need_shio_mode(c)?;
    let l = laser(c);
    let out = switch_output(c, &l, 0).or_else(|| {
        // LASER_NONE: the PWM pin itself.
        super::io_modules::local_outputs(c)
            .checked_sub(4)
            .map(|o| o as u16)
    });
    update(c, |l| {
        if let Some(k) = l.channels.first_mut() {
            k.pwm_pulse = Some(pulse);
        }
    });
    if let Some(o) = out {
        c.command(WriteDigitalOutput {
            channel: o,
            value: pulse.2 == 0,
        });
    }
    Ok(())
}

/// portType 0 (the channel's own pin) or 1 (general output portIdx, one of the controller's
/// own 64, not an extension module's); ch the PWM channel [0, 1].
fn set_pwm_port(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (port_type, idx) = (c.input.i16()?, c.input.i16()?);
    let ch = channel(c)?;
    match port_type {
        0 => {}
        1 => {
            let n = super::io_modules::local_outputs(c);
            if !usize::try_from(idx).is_ok_and(|i| i < n) {
                return Err(Refusal::range(
                    "portIdx",
                    idx,
                    &format!("[0, {}] (general outputs)", n.saturating_sub(1)),
                ));
            }
        }
        t => return Err(Refusal::range("portType", t, "{0 default, 1 GPDO}")),
    }
    release_switch(c, ch);
    update(c, |l| {
        if let Some(k) = l.channels.get_mut(ch) {
            k.pwm_port_type = port_type;
            k.pwm_port_idx = if port_type == 1 { idx } else { 0 };
        }
    });
    drive(c, ch);
    Ok(())
}

fn get_pwm_port(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ch = channel(c)?;
    let k = laser(c).channels.get(ch).cloned().unwrap_or_default();
    c.output.i16(k.pwm_port_type).i16(k.pwm_port_idx);
    Ok(())
}
