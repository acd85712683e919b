//! Profile modes, PTP, JOG and stops (digest 001 §2.5, §4.3): the parameters are the device's
//! (kept by the service), `NMC_MtUpdate` turns them into one engine move.

use axes::command::{
    BufferMode, Command, MoveAbsolute, MoveRelative, MoveVelocity, Reset, SetParameter, Stop,
    StopMode,
};
use axes::param::ParamId;
use mcemu_dialects::nmc::{acceleration_to_engine, velocity_to_engine};
use mcemu_dialects::PulseScale;
use mcemu_nmc::errors::RTN_UNSUPPORTED;
use mcemu_nmc::structs::{JogPara, PtpPara};
use mcemu_nmc::table::{self, Function};

use super::sync_args::axes_of_mask;
use crate::nmc::service::{pulses, AxisSettings, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_SET_PRF_MODE, mt_set_prf_mode),
    (table::MT_GET_PRF_MODE, mt_get_prf_mode),
    (table::MT_SET_PTP_PARA, mt_set_ptp_para),
    (table::MT_GET_PTP_PARA, mt_get_ptp_para),
    (table::MT_SET_PTP_TGT_POS, mt_set_ptp_tgt_pos),
    (table::MT_GET_PTP_TGT_POS, mt_get_ptp_tgt_pos),
    (table::MT_SET_VEL, mt_set_vel),
    (table::MT_GET_VEL, mt_get_vel),
    (table::MT_SET_JOG_PARA, mt_set_jog_para),
    (table::MT_GET_JOG_PARA, mt_get_jog_para),
    (table::MT_UPDATE, mt_update),
    (table::MT_UPDATE_MULTI, mt_update_multi),
    (table::MT_STOP, mt_stop),
    (table::MT_ABRUPT_STOP, mt_abrupt_stop),
    (table::MT_STOP_MULTI, mt_stop_multi),
    (table::MT_ESTP, mt_estp),
    (table::MT_MOVE_PTP_ABS, mt_move_ptp_abs),
    (table::MT_MOVE_PTP_REL, mt_move_ptp_rel),
    (table::MT_MOVE_JOG, mt_move_jog),
];

pub const MT_PTP_PRF_MODE: i16 = 0;
pub const MT_JOG_PRF_MODE: i16 = 1;

/// The §3.2 modes (2 is unused).
fn check_mode(mode: i16) -> Result<(), Refusal> {
    match mode {
        -1 | 0 | 1 | 3..=8 => Ok(()),
        m => Err(Refusal::range(
            "mode",
            m,
            "{-1, 0, 1, 3 … 8} (digest 001 §3.2)",
        )),
    }
}

fn positive(name: &str, v: f64) -> Result<(), Refusal> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Refusal::range(name, v, "(0, ∞) pulse/ms²"))
    }
}

fn non_negative(name: &str, v: f64) -> Result<(), Refusal> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(Refusal::range(name, v, "[0, ∞) pulse/ms"))
    }
}

/// smoothCoef [0,199] ms (TV69).
fn smooth(v: f64) -> Result<(), Refusal> {
    if (0.0..=199.0).contains(&v) {
        Ok(())
    } else {
        Err(Refusal::range("smoothCoef", v, "[0, 199] ms"))
    }
}

fn check_ptp(p: &PtpPara) -> Result<(), Refusal> {
    positive("acc", p.acc)?;
    positive("dec", p.dec)?;
    non_negative("startVel", p.start_vel)?;
    non_negative("endVel", p.end_vel)?;
    smooth(f64::from(p.smooth_coef))
}

fn check_jog(p: &JogPara) -> Result<(), Refusal> {
    positive("acc", p.acc)?;
    positive("dec", p.dec)?;
    smooth(p.smooth_coef)
}

fn mt_set_prf_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let mode = c.input.i16()?;
    check_mode(mode)?;
    c.update(axis, |s| s.prf_mode = mode);
    Ok(())
}

fn mt_get_prf_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.output.i16(c.settings(axis).prf_mode);
    Ok(())
}

fn mt_set_ptp_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let p = PtpPara::read(&mut c.input)?;
    check_ptp(&p)?;
    c.update(axis, |s| s.ptp = p);
    Ok(())
}

fn mt_get_ptp_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.settings(axis).ptp.write(c.output);
    Ok(())
}

fn mt_set_ptp_tgt_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let pos = c.input.i64()?;
    c.update(axis, |s| s.target = pos);
    Ok(())
}

fn mt_get_ptp_tgt_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.output.i64(c.settings(axis).target);
    Ok(())
}

/// PTP takes positive velocities only ("PTP 模式下只接受正数", TV15); JOG's sign is the
/// direction.
fn mt_set_vel(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let vel = c.input.f64()?;
    let mode = c.settings(axis).prf_mode;
    if !vel.is_finite() || (mode == MT_PTP_PRF_MODE && vel < 0.0) {
        let allowed = if mode == MT_PTP_PRF_MODE {
            "[0, ∞) pulse/ms in PTP mode"
        } else {
            "a finite pulse/ms"
        };
        return Err(Refusal::range("vel", vel, allowed));
    }
    c.update(axis, |s| s.vel = vel);
    Ok(())
}

fn mt_get_vel(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.output.f64(c.settings(axis).vel);
    Ok(())
}

fn mt_set_jog_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let p = JogPara::read(&mut c.input)?;
    check_jog(&p)?;
    c.update(axis, |s| s.jog = p);
    Ok(())
}

fn mt_get_jog_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.settings(axis).jog.write(c.output);
    Ok(())
}

/// A parameter write, when `value` differs from what the axis has.
fn set_if_changed(c: &Call<'_>, axis: usize, name: ParamId, value: f64) -> Option<Command> {
    let now = c.snapshot.params.get(axis).map(|p| p.get(name));
    (now != Some(value)).then(|| {
        SetParameter {
            axis: axis as u16,
            name,
            value,
            lenient: false,
        }
        .into()
    })
}

/// What `NMC_MtUpdate` starts for axis `axis` with settings `s`: a PTP move to the target or
/// a jog at the signed velocity; other modes start through their own families.
fn start(c: &Call<'_>, axis: usize, s: &AxisSettings) -> Result<Vec<Command>, Refusal> {
    let scale = c.scale(axis);
    let a = axis as u16;
    match s.prf_mode {
        MT_PTP_PRF_MODE => {
            let p = &s.ptp;
            let mut out: Vec<Command> = [
                (
                    ParamId::StartVelocity,
                    velocity_to_engine(scale, p.start_vel),
                ),
                (ParamId::EndVelocity, velocity_to_engine(scale, p.end_vel)),
                (ParamId::SmoothTime, f64::from(p.smooth_coef) / 1e3),
            ]
            .into_iter()
            .filter_map(|(name, value)| set_if_changed(c, axis, name, value))
            .collect();
            out.push(
                MoveAbsolute {
                    axis: a,
                    position: scale.to_engine(s.target as f64),
                    velocity: Some(velocity_to_engine(scale, s.vel)),
                    acceleration: Some(acceleration_to_engine(scale, p.acc)),
                    deceleration: Some(acceleration_to_engine(scale, p.dec)),
                    jerk: None,
                    buffer_mode: BufferMode::Aborting,
                }
                .into(),
            );
            Ok(out)
        }
        MT_JOG_PRF_MODE => Ok(vec![jog(scale, a, s.vel, &s.jog)]),
        m => Err(Refusal::new(
            RTN_UNSUPPORTED,
            format!("NMC_MtUpdate in profile mode {m}: only PTP (0) and JOG (1) start here"),
        )),
    }
}

fn jog(scale: PulseScale, axis: u16, vel: f64, p: &JogPara) -> Command {
    MoveVelocity {
        axis,
        velocity: velocity_to_engine(scale, vel),
        acceleration: Some(acceleration_to_engine(scale, p.acc)),
        deceleration: Some(acceleration_to_engine(scale, p.dec)),
        jerk: None,
        buffer_mode: BufferMode::Aborting,
    }
    .into()
}

fn mt_update(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let s = c.settings(axis);
    let commands = start(c, axis, &s)?;
    c.plan.commands.extend(commands);
    Ok(())
}

/// Bit n = NMC axis n (absolute numbers; digest 001 §8 item 12 leaves it open,
/// docs/decisions.md), bus drives from bit 16 on an `ecat` card.
fn mask_axes(c: &Call<'_>, mask: i64) -> Result<Vec<usize>, Refusal> {
    axes_of_mask(c, "mask", mask, 63)
}

/// All axes start in the same tick: one batch (TV27).
fn mt_update_multi(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.axis()?;
    let mask = c.input.i64()?;
    for axis in mask_axes(c, mask)? {
        let s = c.settings(axis);
        let commands = start(c, axis, &s)?;
        c.plan.commands.extend(commands);
    }
    Ok(())
}

/// A smooth stop with the deceleration of the running mode (digest 001 §4.2).
fn smooth_stop(c: &Call<'_>, axis: usize) -> Command {
    let s = c.settings(axis);
    let dec = if s.prf_mode == MT_JOG_PRF_MODE {
        s.jog.dec
    } else {
        s.ptp.dec
    };
    Stop {
        axis: axis as u16,
        mode: StopMode::Smooth,
        deceleration: Some(acceleration_to_engine(c.scale(axis), dec)),
    }
    .into()
}

/// On a Follow slave it ends the Follow (`follow_out`: the slave ramps to rest with its
/// deceleration, digest 001 §2.17).
fn mt_stop(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let stop = super::follow::follow_out(c, axis).unwrap_or_else(|| smooth_stop(c, axis));
    c.command(stop);
    Ok(())
}

fn stop_with(c: &mut Call<'_>, mode: StopMode) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.command(Stop {
        axis: axis as u16,
        mode,
        deceleration: None,
    });
    Ok(())
}

/// The E-stop deceleration (TSafePara.estpDec = the axis's `fast_decel`), no flag (TV20).
fn mt_abrupt_stop(c: &mut Call<'_>) -> Result<(), Refusal> {
    stop_with(c, StopMode::Abrupt)
}

/// As abrupt, and latches BIT_AXIS_ESTP until `NMC_MtClrError` (TV19).
fn mt_estp(c: &mut Call<'_>) -> Result<(), Refusal> {
    stop_with(c, StopMode::Emergency)
}

fn mt_stop_multi(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.axis()?;
    let mask = c.input.i64()?;
    for axis in mask_axes(c, mask)? {
        let stop = smooth_stop(c, axis);
        c.command(stop);
    }
    Ok(())
}

/// acc, dec, startVel, endVel, maxVel, smoothCoef as `NMC_MtMovePtpAbs/Rel` pass them.
fn read_ptp(c: &mut Call<'_>) -> Result<(PtpPara, f64), Refusal> {
    let (acc, dec, start_vel, end_vel, vel) = (
        c.input.f64()?,
        c.input.f64()?,
        c.input.f64()?,
        c.input.f64()?,
        c.input.f64()?,
    );
    let p = PtpPara {
        acc,
        dec,
        start_vel,
        end_vel,
        smooth_coef: c.input.i16()?,
    };
    check_ptp_move(&p, vel)?;
    Ok((p, vel))
}

/// SetPrfMode + SetPtpPara + SetVel + SetPtpTgtPos + Update in one call (digest 001 §2.5).
fn mt_move_ptp_abs(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (ptp, vel) = read_ptp(c)?;
    let target = c.input.i64()?;
    let commands = ptp_move(c, axis, ptp, vel, target, false)?;
    c.plan.commands.extend(commands);
    Ok(())
}

fn mt_move_ptp_rel(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (ptp, vel) = read_ptp(c)?;
    let distance = c.input.i64()?;
    let commands = ptp_move(c, axis, ptp, vel, distance, true)?;
    c.plan.commands.extend(commands);
    Ok(())
}

/// The parameters of one PTP move as `NMC_MtMovePtpAbs/Rel` and the packed moves pass them.
pub(super) fn check_ptp_move(p: &PtpPara, vel: f64) -> Result<(), Refusal> {
    check_ptp(p)?;
    non_negative("maxVel", vel)
}

/// The commands of one PTP move of axis `axis` to `pos` (`relative`: by `pos`), its settings
/// kept as `NMC_MtGetPtpPara` / `GetPtpTgtPos` read them. The relative move runs as the
/// engine's relative move (from where the plan is when the command applies); the stored target
/// is that end point as seen now.
pub(super) fn ptp_move(
    c: &Call<'_>,
    axis: usize,
    ptp: PtpPara,
    vel: f64,
    pos: i64,
    relative: bool,
) -> Result<Vec<Command>, Refusal> {
    let scale = c.scale(axis);
    let mut s = c.settings(axis);
    (s.prf_mode, s.ptp, s.vel, s.target) = (MT_PTP_PRF_MODE, ptp, vel, pos);
    if relative {
        let here = c.status(axis).map_or(0, |st| pulses(scale, st.target_pos));
        s.target = here.saturating_add(pos);
    }
    let mut commands = start(c, axis, &s)?;
    if relative {
        commands.pop();
        commands.push(
            MoveRelative {
                axis: axis as u16,
                distance: scale.to_engine(pos as f64),
                velocity: Some(velocity_to_engine(scale, vel)),
                acceleration: Some(acceleration_to_engine(scale, ptp.acc)),
                deceleration: Some(acceleration_to_engine(scale, ptp.dec)),
                jerk: None,
                buffer_mode: BufferMode::Aborting,
            }
            .into(),
        );
    }
    c.update(axis, |now| *now = s);
    Ok(commands)
}

/// acc, dec, maxVel (its sign the direction), smoothCoef, clrStsFlag (1: clear first).
fn mt_move_jog(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (acc, dec, vel) = (c.input.f64()?, c.input.f64()?, c.input.f64()?);
    let (smooth_coef, clear) = (c.input.i16()?, c.input.i16()?);
    let p = JogPara {
        acc,
        dec,
        smooth_coef: f64::from(smooth_coef),
    };
    check_jog(&p)?;
    if !vel.is_finite() {
        return Err(Refusal::range("maxVel", vel, "a finite pulse/ms"));
    }
    if !(0..=1).contains(&clear) {
        return Err(Refusal::range("clrStsFlag", clear, "{0, 1}"));
    }
    if clear == 1 {
        c.command(Reset { axis: axis as u16 });
    }
    let scale = c.scale(axis);
    c.command(jog(scale, axis as u16, vel, &p));
    c.update(axis, |s| {
        (s.prf_mode, s.jog, s.vel) = (MT_JOG_PRF_MODE, p, vel);
    });
    Ok(())
}
