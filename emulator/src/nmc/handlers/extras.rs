//! PT started by an input edge and its parameters read back, the PTP compare (a velocity
//! change at a position), the 2-D compare status under its comment name, and the damping
//! compensation (digest 001 §2.3, §2.5, §2.8, §2.11, §2.13; Appendix A).

use axes::command::{CaptureEdge, PositionWatchSet, StreamStartOnInput};
use mcemu_dialects::nmc::velocity_to_engine;
use mcemu_nmc::table::{self, Function};

use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_PT_START_MTN_EX, mt_pt_start_mtn_ex),
    (table::MT_SET_PTP_COMPARE_PARA, mt_set_ptp_compare_para),
    (table::MT_GET_PTP_COMPARE_STS, mt_get_ptp_compare_sts),
    // "NMC_Comp2DimensStatus" of the manual's comments is NMC_Comp2DimensStatusEx (digest 001
    // Appendix A).
    (table::COMP_2DIMENS_STATUS, super::compare::status),
    (
        table::MT_SET_AXIS_DAMP_COMP_PARAM,
        mt_set_axis_damp_comp_param,
    ),
];

/// `MT_PT_PRF_MODE` (digest 001 §3.2).
const MT_PT_PRF_MODE: i16 = 5;

/// The PT stream starts on the first edge of general input diIndex [0, 32] (diSns 0 falling,
/// 1 rising) after this call: the engine's `stream_start_on_input`.
fn mt_pt_start_mtn_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (index, sns) = (c.input.i16()?, c.input.i16()?);
    let last = c.snapshot.io.di.len().min(33).saturating_sub(1);
    let input = u16::try_from(index)
        .ok()
        .filter(|i| usize::from(*i) <= last)
        .ok_or_else(|| Refusal::range("diIndex", index, &format!("[0, {last}]")))?;
    let edge = match sns {
        0 => CaptureEdge::Falling,
        1 => CaptureEdge::Rising,
        s => return Err(Refusal::range("diSns", s, "{0 falling, 1 rising}")),
    };
    c.command(StreamStartOnInput {
        axis: axis as u16,
        input,
        edge,
    });
    c.update(axis, |s| s.prf_mode = MT_PT_PRF_MODE);
    Ok(())
}

/// dir 1 positive / 0 negative, comparaPos pulses, upDateVel pulse/ms (> 0): armed until the
/// axis's planned position passes the position moving that way, then its move goes on at
/// upDateVel (a PTP move to its target, a jog in its direction). The engine's position watch
/// (`axes::guard`), judged on the tick.
fn mt_set_ptp_compare_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (dir, pos, vel) = (c.input.i16()?, c.input.i64()?, c.input.f64()?);
    if !(0..=1).contains(&dir) {
        return Err(Refusal::range("dir", dir, "{0 negative, 1 positive}"));
    }
    if !(vel.is_finite() && vel > 0.0) {
        return Err(Refusal::range("upDateVel", vel, "(0, ∞) pulse/ms"));
    }
    let scale = c.scale(axis);
    c.command(PositionWatchSet {
        axis: axis as u16,
        position: scale.to_engine(pos as f64),
        positive: dir == 1,
        speed: velocity_to_engine(scale, vel),
    });
    Ok(())
}

/// Armed (1 until the position is passed), and passed (1 once the velocity changed).
fn mt_get_ptp_compare_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let w = c
        .snapshot
        .position_watches
        .iter()
        .find(|w| usize::from(w.axis) == axis)
        .copied();
    let (active, out) = w.map_or((0, 0), |w| (i16::from(w.armed), i16::from(w.passed)));
    c.output.i16(active).i16(out);
    Ok(())
}

/// enable 0/1, param1 [10, 500], param2 the control frequency in Hz (> 0). Kept only: the
/// engine's plant has no resonance to damp (decisions.md).
fn mt_set_axis_damp_comp_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (enable, p1, p2) = (c.input.i16()?, c.input.i16()?, c.input.i16()?);
    if !(0..=1).contains(&enable) {
        return Err(Refusal::range("enable", enable, "{0, 1}"));
    }
    if !(10..=500).contains(&p1) {
        return Err(Refusal::range("param1", p1, "[10, 500]"));
    }
    if p2 <= 0 {
        return Err(Refusal::range("param2", p2, "(0, 32767] Hz"));
    }
    c.service.ax().damp_comp.insert(axis, (enable, p1, p2));
    Ok(())
}
