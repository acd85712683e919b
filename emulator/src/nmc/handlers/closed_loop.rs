//! Closed loop (digest 001 §2.15, S-CLOSED-LOOP) and profile configuration (§2.20, TV67,
//! TV70). The active PID set is the engine's loop gains (kp, ki, kd, kvff) and the DAC limit
//! its output limits, which an analog-servo axis of the engine uses; the control mode, the
//! other PID sets, inversion and bias are kept and read back (the engine does not switch an
//! axis between pulse and analog output at run time, decisions.md). startPos offsets
//! `NMC_MtGetAxisPos`; the encoder coefficient scales `NMC_MtGetEncPos`; the planning
//! coefficient is kept and read back. `NMC_SaveMotionConfig` is served here too.

use axes::param::ParamId;
use mcemu_nmc::ax_structs::{DacMotor, PidPara};
use mcemu_nmc::table::{self, Function};

use super::axis_config::set;
use super::sync_args::{axis_number, nmc_number};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_SET_CTRL_MODE, mt_set_ctrl_mode),
    (table::MT_GET_CTRL_MODE, mt_get_ctrl_mode),
    (table::MT_SET_PID_PARA, mt_set_pid_para),
    (table::MT_GET_PID_PARA, mt_get_pid_para),
    (table::MT_SET_PID_INDEX, mt_set_pid_index),
    (table::MT_GET_PID_INDEX, mt_get_pid_index),
    (table::MT_SET_CLOSE_LOOP_DAC, mt_set_close_loop_dac),
    (table::MT_GET_CLOSE_LOOP_DAC, mt_get_close_loop_dac),
    (table::SET_CLOSE_LOOP_DAC, mt_set_close_loop_dac),
    (table::MT_PRF_CONFIG, mt_prf_config),
    (table::MT_GET_PRF_CONFIG, mt_get_prf_config),
    (table::MT_SET_PRF_COE, mt_set_prf_coe),
    (table::MT_GET_PRF_COE, mt_get_prf_coe),
    (table::MT_SET_ENC_COE, mt_set_enc_coe),
    (table::MT_GET_ENC_COE, mt_get_enc_coe),
    (table::SAVE_MOTION_CONFIG, save_motion_config),
];

/// 0 pulse output (open loop, the default), 1 DA closed loop.
fn mt_set_ctrl_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let mode = c.input.i16()?;
    if !(0..=1).contains(&mode) {
        return Err(Refusal::range("mode", mode, "{0 pulse, 1 DA closed loop}"));
    }
    c.service.ax().axis_loop_mut(axis).ctrl_mode = mode;
    Ok(())
}

fn mt_get_ctrl_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let mode = c.service.ax().axis_loop(axis).ctrl_mode;
    c.output.i16(mode);
    Ok(())
}

fn pid_index(index: i16) -> Result<usize, Refusal> {
    usize::try_from(index)
        .ok()
        .filter(|i| *i < 3)
        .ok_or_else(|| Refusal::range("index", index, "[0, 2]"))
}

/// The engine's loop gains from PID set `p`.
fn apply_pid(c: &mut Call<'_>, axis: usize, p: &PidPara) {
    for (name, value) in [
        (ParamId::Kp, p.kp),
        (ParamId::Ki, p.ki),
        (ParamId::Kd, p.kd),
        (ParamId::Kvff, p.kvff),
    ] {
        set(c, axis, name, value);
    }
}

/// Set `index` [0, 2]; the active set's gains go to the engine at once.
fn mt_set_pid_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let index = pid_index(c.input.i16()?)?;
    let p = PidPara::read(&mut c.input)?;
    for (name, v) in [("kp", p.kp), ("ki", p.ki), ("kd", p.kd), ("kvff", p.kvff)] {
        if !v.is_finite() {
            return Err(Refusal::range(name, v, "a finite gain"));
        }
    }
    let active = {
        let mut ax = c.service.ax();
        let l = ax.axis_loop_mut(axis);
        if let Some(slot) = l.pid.get_mut(index) {
            *slot = p;
        }
        usize::try_from(l.pid_index).ok() == Some(index)
    };
    if active {
        apply_pid(c, axis, &p);
    }
    Ok(())
}

fn mt_get_pid_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let index = pid_index(c.input.i16()?)?;
    let p = c
        .service
        .ax()
        .axis_loop(axis)
        .pid
        .get(index)
        .copied()
        .unwrap_or_default();
    p.write(c.output);
    Ok(())
}

/// The active set [0, 2]: its gains go to the engine.
fn mt_set_pid_index(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let raw = c.input.i16()?;
    let index = pid_index(raw)?;
    let p = {
        let mut ax = c.service.ax();
        let l = ax.axis_loop_mut(axis);
        l.pid_index = raw;
        l.pid.get(index).copied().unwrap_or_default()
    };
    apply_pid(c, axis, &p);
    Ok(())
}

fn mt_get_pid_index(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let index = c.service.ax().axis_loop(axis).pid_index;
    c.output.i16(index);
    Ok(())
}

/// inverse 0/1, bias (zero drift, DAC counts), dacLmt [0, 32767]: the engine's DAC output
/// limits are ±dacLmt.
fn mt_set_close_loop_dac(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let d = DacMotor::read(&mut c.input)?;
    if !(0..=1).contains(&d.inverse) {
        return Err(Refusal::range("inverse", d.inverse, "{0, 1}"));
    }
    if d.dac_lmt < 0 {
        return Err(Refusal::range("dacLmt", d.dac_lmt, "[0, 32767]"));
    }
    c.service.ax().axis_loop_mut(axis).dac = d;
    set(c, axis, ParamId::DacLimitHigh, f64::from(d.dac_lmt));
    set(c, axis, ParamId::DacLimitLow, -f64::from(d.dac_lmt));
    Ok(())
}

fn mt_get_close_loop_dac(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let d = c.service.ax().axis_loop(axis).dac;
    d.write(c.output);
    Ok(())
}

/// mapAxisNo [0, n], port [0, 1], startPos: axisPos = prfPos + startPos (TV70).
fn mt_prf_config(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (map, port, start) = (c.input.i16()?, c.input.i16()?, c.input.i64()?);
    axis_number(c, "mapAxisNo", i64::from(map))?;
    if !(0..=1).contains(&port) {
        return Err(Refusal::range("port", port, "{0, 1}"));
    }
    const POS_MAX: i64 = 2_147_483_647;
    if !(-POS_MAX..=POS_MAX).contains(&start) {
        return Err(Refusal::range(
            "startPos",
            start,
            "[-2147483647, 2147483647] pulses",
        ));
    }
    let mut ax = c.service.ax();
    let l = ax.axis_loop_mut(axis);
    (l.map_axis, l.port, l.start_pos) = (Some(map), port, start);
    Ok(())
}

fn mt_get_prf_config(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let l = c.service.ax().axis_loop(axis);
    // Never written: the axis maps to itself, by its NMC number (a bus drive's is 16 + k).
    let map = l.map_axis.unwrap_or_else(|| {
        nmc_number(c, axis)
            .and_then(|n| i16::try_from(n).ok())
            .unwrap_or(0)
    });
    c.output.i16(map).i16(l.port).i64(l.start_pos);
    Ok(())
}

/// (0, 1] (TV67).
fn mt_set_prf_coe(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let coe = c.input.f64()?;
    if !(coe > 0.0 && coe <= 1.0) {
        return Err(Refusal::range("inCoe", coe, "(0, 1]"));
    }
    c.service.ax().axis_loop_mut(axis).prf_coe = coe;
    Ok(())
}

fn mt_get_prf_coe(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let coe = c.service.ax().axis_loop(axis).prf_coe;
    c.output.f64(coe);
    Ok(())
}

/// The encoder's reported counts are its raw counts × encCoe. The manual states (0, 1] yet
/// its example needs 4 (1000 commanded, 250 counted): (0, 1000] (decisions.md). The reading
/// does not jump: the offset is kept so that it reads the same at the change.
fn mt_set_enc_coe(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let coe = c.input.f64()?;
    if !(coe > 0.0 && coe <= 1000.0) {
        return Err(Refusal::range("encCoe", coe, "(0, 1000]"));
    }
    let status = c.status(axis).copied().unwrap_or_default();
    c.service
        .ax()
        .enc
        .entry(axis)
        .or_default()
        .set_coe(&status, coe);
    Ok(())
}

fn mt_get_enc_coe(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let coe = c.service.ax().enc.get(&axis).map_or(1.0, |e| e.coe);
    c.output.f64(coe);
    Ok(())
}

/// 1 saves the axes' basic configuration in the state directory (applied at every start and
/// `NMC_DevReset`), 0 forgets it (decisions.md).
fn save_motion_config(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let enable = c.input.i16()?;
    let result = match enable {
        1 => crate::nmc::saved_config::save(c.service, &c.snapshot),
        0 => crate::nmc::saved_config::forget(c.service),
        e => return Err(Refusal::range("enable", e, "{0 forget, 1 save}")),
    };
    result.map_err(|e| {
        Refusal::new(
            mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::Fault),
            e,
        )
    })
}
