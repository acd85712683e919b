//! Basic axis configuration (digest 001 §2.3, §2.20): what the engine keeps is written as axis
//! parameters (alarm, limits, soft limits, safety limits, following error, arrival band) and
//! read back from the snapshot; what it has no model of (pulse mode, filters, encoder mode
//! words) is stored (`crate::nmc::stored`).

use axes::command::{Command, SetParameter};
use axes::param::{ParamId, DEDICATED_INPUT};
use mcemu_dialects::nmc::{
    acceleration_from_engine, acceleration_to_engine, velocity_from_engine, velocity_to_engine,
};
use mcemu_nmc::axis_config::SafePara;
use mcemu_nmc::table::{self, Function};

use crate::nmc::service::{pulses, Call, Handler, Refusal};
use crate::nmc::stored::DEFAULT_ENC_MODE;

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_SET_ALARM_CFG, mt_set_alarm_cfg),
    (table::MT_GET_ALARM_ON_OFF, mt_get_alarm_on_off),
    (table::MT_GET_ALARM_SNS, mt_get_alarm_sns),
    (table::MT_SET_LMT_CFG, mt_set_lmt_cfg),
    (table::MT_GET_LMT_ON_OFF, mt_get_lmt_on_off),
    (table::MT_GET_LMT_SNS, mt_get_lmt_sns),
    (table::MT_SW_LMT_ON_OFF, mt_sw_lmt_on_off),
    (table::MT_GET_SW_LMT_ON_OFF, mt_get_sw_lmt_on_off),
    (table::MT_SW_LMT_VALUE, mt_sw_lmt_value),
    (table::MT_GET_SW_LMT_VALUE, mt_get_sw_lmt_value),
    (table::MT_SET_STEP_MODE, mt_set_step_mode),
    (table::MT_GET_STEP_MODE, mt_get_step_mode),
    (table::SET_ENC_MODE, set_enc_mode),
    (table::GET_ENC_MODE, get_enc_mode),
    (table::MT_SET_SAFE_PARA, mt_set_safe_para),
    (table::MT_GET_SAFE_PARA, mt_get_safe_para),
    (table::MT_SET_POS_ERR_LMT, mt_set_pos_err_lmt),
    (table::MT_GET_POS_ERR_LMT, mt_get_pos_err_lmt),
    (table::MT_SET_AXIS_VEL_FILTER, mt_set_axis_vel_filter),
    (table::MT_GET_AXIS_VEL_FILTER, mt_get_axis_vel_filter),
    (table::MT_SET_STEP_FILTER, mt_set_step_filter),
    (table::MT_GET_STEP_FILTER, mt_get_step_filter),
    (table::MT_SET_POS_ERR_ACTION, mt_set_pos_err_action),
    (table::MT_GET_POS_ERR_ACTION, mt_get_pos_err_action),
    (table::MT_SET_AXIS_ARRIVAL_PARA, mt_set_axis_arrival_para),
    (table::MT_GET_AXIS_ARRIVAL_PARA, mt_get_axis_arrival_para),
];

/// The manual's position range (digest 001 §1.3: 32-bit pulses).
const POS_MAX: i64 = 2_147_483_647;

fn param(c: &Call<'_>, axis: usize, id: ParamId) -> f64 {
    c.snapshot.params.get(axis).map_or(0.0, |p| p.get(id))
}

pub(super) fn set(c: &mut Call<'_>, axis: usize, name: ParamId, value: f64) {
    c.command(Command::from(SetParameter {
        axis: axis as u16,
        name,
        value,
        lenient: false,
    }));
}

fn flag(name: &str, v: i16) -> Result<bool, Refusal> {
    match v {
        0 => Ok(false),
        1 => Ok(true),
        v => Err(Refusal::range(name, v, "{0, 1}")),
    }
}

/// A level ("sns": 1 high-active, 0 low-active) as the engine's invert flag (1 − sns).
fn invert(sns: bool) -> f64 {
    if sns {
        0.0
    } else {
        1.0
    }
}

fn mt_set_alarm_cfg(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let enable = flag("alarmEnable", c.input.i16()?)?;
    let sns = flag("alarmSns", c.input.i16()?)?;
    set(
        c,
        axis,
        ParamId::DriveAlarmEnable,
        f64::from(u8::from(enable)),
    );
    set(c, axis, ParamId::DriveAlarmInvert, invert(sns));
    Ok(())
}

fn mt_get_alarm_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let on = param(c, axis, ParamId::DriveAlarmEnable) != 0.0;
    c.output.i16(i16::from(on));
    Ok(())
}

fn mt_get_alarm_sns(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let high = param(c, axis, ParamId::DriveAlarmInvert) == 0.0;
    c.output.i16(i16::from(high));
    Ok(())
}

/// Enabling keeps a limit input the machine maps elsewhere; an unmapped one (−1) gets the
/// dedicated input. Triggered limits then block the same direction (digest 001 §4.2).
fn limit_input(c: &Call<'_>, axis: usize, id: ParamId, enable: bool) -> f64 {
    let now = param(c, axis, id);
    match (enable, now >= 0.0) {
        (false, _) => -1.0,
        (true, true) => now,
        (true, false) => DEDICATED_INPUT,
    }
}

fn mt_set_lmt_cfg(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let pos_en = flag("posLmtEnable", c.input.i16()?)?;
    let neg_en = flag("negLmtEnable", c.input.i16()?)?;
    let pos_sns = flag("posLmtSns", c.input.i16()?)?;
    let neg_sns = flag("negLmtSns", c.input.i16()?)?;
    let fh = limit_input(c, axis, ParamId::FhLimitIn, pos_en);
    let rh = limit_input(c, axis, ParamId::RhLimitIn, neg_en);
    set(c, axis, ParamId::FhLimitIn, fh);
    set(c, axis, ParamId::RhLimitIn, rh);
    set(c, axis, ParamId::LimitPosInvert, invert(pos_sns));
    set(c, axis, ParamId::LimitNegInvert, invert(neg_sns));
    Ok(())
}

fn mt_get_lmt_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let pos = param(c, axis, ParamId::FhLimitIn) >= 0.0;
    let neg = param(c, axis, ParamId::RhLimitIn) >= 0.0;
    c.output.i16(i16::from(pos)).i16(i16::from(neg));
    Ok(())
}

fn mt_get_lmt_sns(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let pos = param(c, axis, ParamId::LimitPosInvert) == 0.0;
    let neg = param(c, axis, ParamId::LimitNegInvert) == 0.0;
    c.output.i16(i16::from(pos)).i16(i16::from(neg));
    Ok(())
}

fn mt_sw_lmt_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let on = flag("enable", c.input.i16()?)?;
    set(c, axis, ParamId::IgnoreSwLimits, f64::from(u8::from(!on)));
    Ok(())
}

fn mt_get_sw_lmt_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let on = param(c, axis, ParamId::IgnoreSwLimits) == 0.0;
    c.output.i16(i16::from(on));
    Ok(())
}

/// ±2147483647 pulses (digest 001 §2.3), positive above negative.
fn mt_sw_lmt_value(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (pos, neg) = (c.input.i64()?, c.input.i64()?);
    for (name, v) in [("posLmt", pos), ("negLmt", neg)] {
        if !(-POS_MAX..=POS_MAX).contains(&v) {
            return Err(Refusal::range(name, v, "[-2147483647, 2147483647] pulses"));
        }
    }
    if pos <= neg {
        return Err(Refusal::range(
            "posLmt",
            pos,
            &format!("(negLmt = {neg}, 2147483647]"),
        ));
    }
    let scale = c.scale(axis);
    set(c, axis, ParamId::FsLimit, scale.to_engine(pos as f64));
    set(c, axis, ParamId::RsLimit, scale.to_engine(neg as f64));
    Ok(())
}

/// In pulses, within the manual's range (an engine limit of 1e100 reads 2147483647).
fn mt_get_sw_lmt_value(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let scale = c.scale(axis);
    let pos = pulses(scale, param(c, axis, ParamId::FsLimit)).clamp(-POS_MAX, POS_MAX);
    let neg = pulses(scale, param(c, axis, ParamId::RsLimit)).clamp(-POS_MAX, POS_MAX);
    c.output.i64(pos).i64(neg);
    Ok(())
}

/// Stored: mcemu's pulse outputs are positions, not pulse trains (decisions.md).
fn mt_set_step_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let inv = c.input.i16()?;
    let mode = c.input.i16()?;
    flag("inv", inv)?;
    flag("mode", mode)?;
    let mut stored = c.service.stored();
    let a = stored.axis_mut(axis);
    (a.step_inv, a.step_mode) = (inv, mode);
    Ok(())
}

fn mt_get_step_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let a = c.service.stored().axis(axis);
    c.output.i16(a.step_inv).i16(a.step_mode);
    Ok(())
}

/// The encoder channel: an axis's (0 … n−1) or an auxiliary one (256, 257 do not fit the
/// manual's `unsigned char`, digest 001 §2.4 [sic]).
fn enc_channel(c: &Call<'_>, id: u8) -> Result<u8, Refusal> {
    let n = c.snapshot.axes.len();
    if usize::from(id) < n {
        Ok(id)
    } else {
        Err(Refusal::range(
            "encId",
            id,
            &format!("[0, {}] (the axes' encoders)", n.saturating_sub(1)),
        ))
    }
}

/// Stored (TV10): the encoder model is the machine config's (decisions.md).
fn set_enc_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let id = c.input.u8()?;
    let mode = c.input.u16()?;
    let id = enc_channel(c, id)?;
    c.service.stored().enc_mode.insert(id, mode);
    Ok(())
}

fn get_enc_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let id = c.input.u8()?;
    let id = enc_channel(c, id)?;
    let mode = c
        .service
        .stored()
        .enc_mode
        .get(&id)
        .copied()
        .unwrap_or(DEFAULT_ENC_MODE);
    c.output.u16(mode);
    Ok(())
}

fn positive(name: &str, v: f64) -> Result<(), Refusal> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Refusal::range(name, v, "(0, ∞)"))
    }
}

/// estpDec = the engine's `fast_decel`, maxVel `max_velocity`, maxAcc `max_accel`: requests
/// above them are clamped (digest 001 §3.6).
fn mt_set_safe_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let p = SafePara::read(&mut c.input)?;
    positive("estpDec", p.estp_dec)?;
    positive("maxVel", p.max_vel)?;
    positive("maxAcc", p.max_acc)?;
    let scale = c.scale(axis);
    set(
        c,
        axis,
        ParamId::FastDecel,
        acceleration_to_engine(scale, p.estp_dec),
    );
    set(
        c,
        axis,
        ParamId::MaxVelocity,
        velocity_to_engine(scale, p.max_vel),
    );
    set(
        c,
        axis,
        ParamId::MaxAccel,
        acceleration_to_engine(scale, p.max_acc),
    );
    Ok(())
}

fn mt_get_safe_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let scale = c.scale(axis);
    SafePara {
        estp_dec: acceleration_from_engine(scale, param(c, axis, ParamId::FastDecel)),
        max_vel: velocity_from_engine(scale, param(c, axis, ParamId::MaxVelocity)),
        max_acc: acceleration_from_engine(scale, param(c, axis, ParamId::MaxAccel)),
    }
    .write(c.output);
    Ok(())
}

/// 0 = no check (decisions.md).
fn mt_set_pos_err_lmt(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = c.input.i64()?;
    if !(0..=POS_MAX).contains(&v) {
        return Err(Refusal::range(
            "posErr",
            v,
            "[0, 2147483647] pulses (0: no check)",
        ));
    }
    let scale = c.scale(axis);
    set(c, axis, ParamId::FeLimit, scale.to_engine(v as f64));
    Ok(())
}

fn mt_get_pos_err_lmt(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = pulses(c.scale(axis), param(c, axis, ParamId::FeLimit)).clamp(0, POS_MAX);
    c.output.i64(v);
    Ok(())
}

/// [0, 5] ms (TV68); stored.
fn mt_set_axis_vel_filter(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = c.input.i16()?;
    if !(0..=5).contains(&v) {
        return Err(Refusal::range("filterCoef", v, "[0, 5] (TV68)"));
    }
    c.service.stored().axis_mut(axis).vel_filter = v;
    Ok(())
}

fn mt_get_axis_vel_filter(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = c.service.stored().axis(axis).vel_filter;
    c.output.i16(v);
    Ok(())
}

/// 0–65535, stored (digest 001 §2.3 marks it N/A for an emulator).
fn mt_set_step_filter(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = c.input.u16()?;
    c.service.stored().axis_mut(axis).step_filter = v;
    Ok(())
}

fn mt_get_step_filter(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = c.service.stored().axis(axis).step_filter;
    c.output.u16(v);
    Ok(())
}

/// bit 0 servo off, bit 1 stop, 0 flag only (the engine's `fe_action`, TV24). The action alone
/// decides: the HMC-born `axis_err_mask` loses its following-error bit, which would switch the
/// drive off whatever the action (docs/decisions.md, NMC front-end).
fn mt_set_pos_err_action(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = c.input.i16()?;
    if !(0..=3).contains(&v) {
        return Err(Refusal::range(
            "actionsBits",
            v,
            "[0, 3] (bit 0 servo off, bit 1 stop)",
        ));
    }
    let err_mask = param(c, axis, ParamId::AxisErrMask) as u32;
    if err_mask & FE_FAULT_BIT != 0 {
        set(
            c,
            axis,
            ParamId::AxisErrMask,
            f64::from(err_mask & !FE_FAULT_BIT),
        );
    }
    set(c, axis, ParamId::FeAction, f64::from(v));
    Ok(())
}

/// `axis_err_mask` bit 0: the following-error fault (HMC AxisStatus bit 0, digest 000 §6.2).
const FE_FAULT_BIT: u32 = 1;

fn mt_get_pos_err_action(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = param(c, axis, ParamId::FeAction);
    c.output.i16(v.clamp(0.0, 3.0) as i16);
    Ok(())
}

/// Band in pulses, settle time in ms (BIT_AXIS_POSREC; 0 allowed, the defaults).
fn mt_set_axis_arrival_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (band, time) = (c.input.i64()?, c.input.i64()?);
    if !(0..=POS_MAX).contains(&band) {
        return Err(Refusal::range(
            "arrivalBand",
            band,
            "[0, 2147483647] pulses",
        ));
    }
    if !(0..=3_600_000).contains(&time) {
        return Err(Refusal::range("stableTime", time, "[0, 3600000] ms"));
    }
    let scale = c.scale(axis);
    set(
        c,
        axis,
        ParamId::InPositionWindow,
        scale.to_engine(band as f64),
    );
    set(c, axis, ParamId::InPositionTime, time as f64 / 1e3);
    Ok(())
}

fn mt_get_axis_arrival_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let band = pulses(c.scale(axis), param(c, axis, ParamId::InPositionWindow));
    let time = (param(c, axis, ParamId::InPositionTime) * 1e3).round() as i64;
    c.output.i64(band).i64(time);
    Ok(())
}
