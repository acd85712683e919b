//! Axis-level additions (id family 0x13xx): several axes' status at once, packed PTP moves,
//! redefining positions, the home and alarm-clear levels, the inputs' electrical levels and
//! the planning period (digest 001 §2.3–§2.5, §2.8, §2.20, §3.4, §3.6).

use axes::command::{PositionFrame, Reset, SetPosition};
use axes::param::ParamId;
use axes::AxisFlags;
use mcemu_dialects::nmc::{axis_status, velocity_from_engine, AxisExtra};
use mcemu_nmc::ax_structs::{AxisStsPack12Ex, MovePtpPack8, PACK12_AXES, PACK8_AXES};
use mcemu_nmc::structs::PtpPara;
use mcemu_nmc::table::{self, Function};

use super::analog::raw;
use super::axis::motion_io;
use super::motion::{check_ptp_move, ptp_move};
use super::sync_args::axis_after;
use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_GET_STS_MULTI, mt_get_sts_multi),
    (table::MT_GET_STS_PACK12_EX, mt_get_sts_pack12_ex),
    (table::MT_MOVE_PTP_ABS_PACK8, mt_move_ptp_abs_pack8),
    (table::MT_MOVE_PTP_REL_PACK8, mt_move_ptp_rel_pack8),
    (table::MT_SET_AXIS_POS, mt_set_axis_pos),
    (table::MT_SET_ENC_POS, mt_set_enc_pos),
    (table::MT_ZERO_POS, mt_zero_pos),
    (table::MT_SET_SV_CLR, mt_set_sv_clr),
    (table::MT_HOME_SNS, mt_home_sns),
    (table::MT_GET_MOTION_IO_LOGICAL, mt_get_motion_io_logical),
    (table::SET_PROFILE_PERIOD, set_profile_period),
    (table::GET_PROFILE_PERIOD, get_profile_period),
];

/// The §3.1 word of axis `axis`.
fn status_word(c: &Call<'_>, axis: usize) -> i16 {
    c.status(axis)
        .map_or(0, |s| axis_status(s, AxisExtra::default()) as i16)
}

/// The status words of `count` axes from the handle's on, and the clock in 125 µs ticks
/// (digest 001 §2.20; the count must stay within the device's axes).
fn mt_get_sts_multi(c: &mut Call<'_>) -> Result<(), Refusal> {
    let first = c.axis()?;
    let count = c.input.i16()?;
    // The axes numbered on from the handle's (local, or bus drives from 16).
    let left = (0..)
        .take_while(|i| axis_after(c, first, *i).is_some())
        .count();
    let n = usize::try_from(count)
        .ok()
        .filter(|n| (1..=left).contains(n))
        .ok_or_else(|| Refusal::range("count", count, &format!("[1, {left}]")))?;
    let words: Vec<i16> = (0..n)
        .filter_map(|i| axis_after(c, first, i))
        .map(|a| status_word(c, a))
        .collect();
    mcemu_nmc::sync_structs::write_array(c.output, &words, |w, v| {
        w.i16(*v);
    });
    let ticks_125us = (c.snapshot.time() / 125e-6).round();
    c.output.u64(ticks_125us.clamp(0.0, u64::MAX as f64) as u64);
    Ok(())
}

/// The electrical levels of the motion inputs (digest 001 §2.8 "logical level", 0 low, 1 high):
/// each active state through its configured sense (`NMC_MtSetLmtCfg`, `MtSetAlarmCfg`,
/// `MtHomeSns`); in-position and capture are reported as they are.
fn motion_io_logical(c: &Call<'_>, axis: usize) -> i64 {
    let mut v = c.status(axis).map_or(0, motion_io);
    let invert = |id| {
        c.snapshot
            .params
            .get(axis)
            .is_some_and(|p| p.get(id) != 0.0)
    };
    for (bit, id) in [
        (0, ParamId::LimitNegInvert),
        (1, ParamId::LimitPosInvert),
        (2, ParamId::HomeInvert),
        (3, ParamId::DriveAlarmInvert),
    ] {
        if invert(id) {
            v ^= 1 << bit;
        }
    }
    v
}

fn mt_get_motion_io_logical(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = motion_io_logical(c, axis);
    c.output.i64(v);
    Ok(())
}

/// 12 axes from the handle's (zeros past the device's last), both coordinate systems, the
/// first 32 general inputs and outputs, extension modules 2–7, the analog channels (§3.4).
fn mt_get_sts_pack12_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    let first = c.axis()?;
    let mut p = AxisStsPack12Ex::default();
    for i in 0..PACK12_AXES {
        let Some(axis) = axis_after(c, first, i) else {
            break;
        };
        let Some(s) = c.status(axis) else { break };
        let scale = c.scale(axis);
        p.mt_sts[i] = status_word(c, axis);
        p.mt_mio[i] = motion_io(s) as i16;
        p.mt_mio_log[i] = motion_io_logical(c, axis) as i16;
        p.mt_prf_pos[i] = pulses(scale, s.cmd_pos);
        p.mt_enc_pos[i] = c.service.ax().enc_pos(axis, s);
        p.mt_prf_vel[i] = velocity_from_engine(scale, s.cmd_vel);
    }
    for n in 0..2 {
        let (sts, vel, seg, free, used, left, all) = super::crd_status::packed(c, n);
        p.crd_sts[n] = sts;
        p.crd_prf_vel[n] = vel;
        p.crd_user_seg[n] = seg;
        p.crd_free_space[n] = free;
        p.crd_used_space[n] = used;
        p.crd_left_len[n] = left;
        p.crd_all_cmd_cnt[n] = all;
    }
    let io = &c.snapshot.io;
    p.gpi = word32(&io.di, 0);
    p.gpo = word32(&io.do_, 0);
    for m in 0..6 {
        // Extension module 2 + m: channels from 64 on, 32 each (digest 001 §2.8).
        p.ext_di[m] = word32(&io.di, 64 + 32 * m);
        p.ext_do[m] = word32(&io.do_, 64 + 32 * m);
    }
    for (ch, v) in p.adc.iter_mut().enumerate() {
        *v = io.ai.get(ch).map_or(0, |v| raw(*v, 4));
    }
    let stored = c.service.stored();
    for (ch, v) in p.dac.iter_mut().enumerate() {
        *v = stored.dac.get(&ch).map_or(0, |d| d.raw);
    }
    drop(stored);
    p.write(c.output);
    Ok(())
}

/// 32 bits of `bits` from `start` (missing channels 0).
fn word32(bits: &[bool], start: usize) -> i64 {
    (0..32)
        .filter(|i| bits.get(start + i).copied().unwrap_or(false))
        .fold(0, |v, i| v | 1 << i)
}

/// `NMC_MtMovePtpAbsPack8` / `RelPack8`: each axis of the mask (bit i: the first axis + i)
/// moves as `NMC_MtMovePtpAbs/Rel` would, all in one batch (the same tick); every axis's
/// parameters are checked before any moves.
fn pack8(c: &mut Call<'_>, relative: bool) -> Result<(), Refusal> {
    let first = c.axis()?;
    let p = MovePtpPack8::read(&mut c.input)?;
    if p.axis_mask == 0 || (p.axis_mask as u16) >> PACK8_AXES != 0 {
        return Err(Refusal::range(
            "axisMask",
            format!("{:#x}", p.axis_mask),
            "bits 0 … 7, at least one",
        ));
    }
    if !(0..=1).contains(&p.clr_sts_flag) {
        return Err(Refusal::range("clrStsFlag", p.clr_sts_flag, "{0, 1}"));
    }
    let mut moves = Vec::new();
    for i in (0..PACK8_AXES).filter(|i| p.axis_mask & (1 << i) != 0) {
        let axis = axis_after(c, first, i).ok_or_else(|| {
            Refusal::range(
                "axisMask",
                format!("{:#x}", p.axis_mask),
                "bits of axes the device has from the handle's on",
            )
        })?;
        let ptp = PtpPara {
            acc: p.acc[i],
            dec: p.dec[i],
            start_vel: p.start_vel[i],
            end_vel: p.end_vel[i],
            smooth_coef: p.smooth_coef[i],
        };
        check_ptp_move(&ptp, p.max_vel[i])?;
        moves.push((axis, ptp, p.max_vel[i], p.tgt_pos[i]));
    }
    for (axis, ptp, vel, pos) in moves {
        if p.clr_sts_flag == 1 {
            c.command(Reset { axis: axis as u16 });
        }
        let commands = ptp_move(c, axis, ptp, vel, pos, relative)?;
        c.plan.commands.extend(commands);
    }
    Ok(())
}

fn mt_move_ptp_abs_pack8(c: &mut Call<'_>) -> Result<(), Refusal> {
    pack8(c, false)
}

fn mt_move_ptp_rel_pack8(c: &mut Call<'_>) -> Result<(), Refusal> {
    pack8(c, true)
}

/// The manual's position range (digest 001 §1.3: 32-bit pulses).
const POS_MAX: i64 = 2_147_483_647;

/// Axis `axis`'s encoder reads `wanted` from now on (`NMC_MtSetEncPos`, `NMC_SetEncPos`).
pub(super) fn set_enc_reading(c: &Call<'_>, axis: usize, wanted: i64) {
    if let Some(s) = c.status(axis) {
        c.service
            .ax()
            .enc
            .entry(axis)
            .or_default()
            .set_position(s, wanted);
    }
}

fn moving(c: &Call<'_>, axis: usize) -> Result<(), Refusal> {
    if c.status(axis)
        .is_some_and(|s| s.flags.contains(AxisFlags::MOVING))
    {
        return Err(Refusal::new(
            mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidState),
            "the axis moves: positions are redefined only at rest (digest 001 §2.20)",
        ));
    }
    Ok(())
}

/// The planned (mechanical) position; the encoder keeps counting from where it is. At rest
/// only ("static only", digest 001 §2.20).
fn mt_set_axis_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let pos = c.input.i64()?.clamp(-POS_MAX, POS_MAX);
    moving(c, axis)?;
    let scale = c.scale(axis);
    c.command(SetPosition {
        axis: axis as u16,
        position: scale.to_engine(pos as f64),
        frame: PositionFrame::Commanded,
    });
    Ok(())
}

/// The encoder counter's reading; the plan and the engine's actual position stay (the
/// counter is the NMC report's, decisions.md). At rest only.
fn mt_set_enc_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let pos = c.input.i64()?.clamp(-POS_MAX, POS_MAX);
    moving(c, axis)?;
    set_enc_reading(c, axis, pos);
    Ok(())
}

/// Planned and encoder positions both to 0 (digest 001 §4.1: "zeroes planned and encoder
/// positions"): the engine's commanded and actual positions are each redefined as 0, which
/// moves the encoder's frame (`ax_state::EncReport`) so that it reads 0 too. At rest only.
fn mt_zero_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    moving(c, axis)?;
    for frame in [PositionFrame::Commanded, PositionFrame::Actual] {
        c.command(SetPosition {
            axis: axis as u16,
            position: 0.0,
            frame,
        });
    }
    c.service.ax().enc.entry(axis).or_default().clear_offset();
    Ok(())
}

/// The drive's alarm-clear output: 0 active (low), 1 inactive (digest 001 §2.8). Driving it
/// active clears the axis's latched drive alarm, as `NMC_MtClrError` does, once its cause is
/// gone; the level is kept (decisions.md).
fn mt_set_sv_clr(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let swt = c.input.i16()?;
    if !(0..=1).contains(&swt) {
        return Err(Refusal::range("swt", swt, "{0 active, 1 inactive}"));
    }
    if swt == 0 {
        c.command(Reset { axis: axis as u16 });
    }
    c.service.ax().sv_clr.insert(axis, swt);
    Ok(())
}

/// The home switch's active level, 1 high / 0 low (digest 001 §2.6): the engine's home input
/// inversion, so homing and `NMC_MtGetMotionIO` see it.
fn mt_home_sns(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let sns = c.input.i16()?;
    if !(0..=1).contains(&sns) {
        return Err(Refusal::range("sns", sns, "{0 low, 1 high}"));
    }
    super::axis_config::set(c, axis, ParamId::HomeInvert, f64::from(1 - sns));
    Ok(())
}

/// The planning period in µs, 250, 500 or 1000 (digest 001 §1.4, TV64). Kept and read back:
/// the engine plans every servo tick whatever the value (decisions.md).
fn set_profile_period(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let period = c.input.i16()?;
    if ![250, 500, 1000].contains(&period) {
        return Err(Refusal::range("period", period, "{250, 500, 1000} µs"));
    }
    c.service.ax().profile_period = Some(period);
    Ok(())
}

/// Until set: the engine's servo period when it is one of the three, else 1000 µs.
fn get_profile_period(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let engine = (c.snapshot.period * 1e6).round();
    let default = [250, 500, 1000]
        .into_iter()
        .find(|p| f64::from(*p) == engine)
        .unwrap_or(1000);
    let period = c.service.ax().profile_period.unwrap_or(default);
    c.output.i16(period);
    Ok(())
}
