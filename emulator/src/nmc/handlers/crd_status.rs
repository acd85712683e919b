//! Coordinate systems: status, positions, velocity and buffer counts (digest 001 §2.7 "Status",
//! §3.8). The status word comes from the dialect (`mcemu_dialects::nmc::crd_status`).

use axes::command::CoordinateSystem;
use mcemu_dialects::nmc::{crd_status, velocity_from_engine, CrdExtra};
use mcemu_dialects::PulseScale;
use mcemu_nmc::crd::CRD_MAX_AXES;
use mcemu_nmc::table::{self, Function};

use super::crd::{crd, group, here, state};
use crate::nmc::crd::{CrdState, CRD_BUFFER};
use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::CRD_GET_STS, crd_get_sts),
    (table::CRD_GET_STS_EX, crd_get_sts_ex),
    (table::CRD_GET_INNER_STS, crd_get_inner_sts),
    (table::CRD_GET_PRF_POS, crd_get_prf_pos),
    (table::CRD_GE_PRFT_POS, crd_get_prf_pos),
    (table::CRD_GET_AXIS_POS, crd_get_axis_pos),
    (table::CRD_GET_ENC_POS, crd_get_enc_pos),
    (table::CRD_GET_VEL, crd_get_vel),
    (table::CRD_BUF_GET_FREE, crd_buf_get_free),
    (table::CRD_BUF_GET_USED, crd_buf_get_used),
    (table::CRD_GET_USER_SEG_NO, crd_get_user_seg_no),
    (table::CRD_GET_BUF_ALL_CMD_CNT, crd_get_buf_all_cmd_cnt),
    (table::CRD_GET_BUF_LEFT_LENGTH, crd_get_buf_left_length),
];

/// Entries used: the engine queue's and the pending ones.
pub(super) fn used(c: &Call<'_>, n: usize, s: &CrdState) -> usize {
    group(c, n).map_or(0, |g| g.queue_used as usize) + s.pending.len()
}

pub(super) fn free(c: &Call<'_>, n: usize, s: &CrdState) -> usize {
    let engine_free = group(c, n).map_or(CRD_BUFFER, |g| g.queue_free as usize);
    engine_free.saturating_sub(s.pending.len())
}

/// The whole word (bits 0-11); `NMC_CrdGetSts` shows bits 0-5.
pub(super) fn word(c: &Call<'_>, n: usize) -> u32 {
    let s = state(c, n);
    let extra = CrdExtra {
        pending: s.pending.len(),
        free: free(c, n, &s),
    };
    crd_status(group(c, n), extra)
}

fn crd_get_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    c.output.i16((word(c, n) & 0x3F) as i16);
    Ok(())
}

pub(super) fn user_seg(c: &Call<'_>, n: usize) -> i64 {
    group(c, n).map_or(0, |g| i64::from(g.user_segment))
}

fn crd_get_sts_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let (w, seg) = (word(c, n), user_seg(c, n));
    c.output.i16((w & 0x3F) as i16).i64(seg);
    Ok(())
}

fn crd_get_inner_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    c.output.i64(i64::from(word(c, n)));
    Ok(())
}

/// `cnts` ∈ [1, 4]; the positions of the coordinate system's axes, `pick`ed from each member's
/// status in pulses (0 past the last member). `user`: in the coordinate system's own
/// coordinates — machine less the origin, seen through the selected transform if one is
/// (`NMC_CrdSetTransRotate`, `SetTransXYZA`: the engine's `frame_position`; `SetTransPolar`
/// on the X and Y axes: the Cartesian point of their θ and r, `here`).
fn positions(
    c: &mut Call<'_>,
    pick: fn(&Call<'_>, usize, &axes::AxisStatus) -> i64,
    user: bool,
) -> Result<(), Refusal> {
    let n = crd(c)?;
    let cnts = c.input.i16()?;
    let count = usize::try_from(cnts)
        .ok()
        .filter(|k| (1..=CRD_MAX_AXES).contains(k))
        .ok_or_else(|| Refusal::range("cnts", cnts, "[1, 4]"))?;
    let s = state(c, n);
    let axes = s.axes();
    let origin = s.origin();
    let transformed = group(c, n)
        .filter(|g| user && g.coordinate_system != CoordinateSystem::MCS)
        .map(|g| g.frame_position);
    c.output.u16(count as u16);
    if user && polar_path(c, n) {
        let at = here(c, n, &s);
        for (k, p) in at.iter().enumerate().take(count) {
            c.output.i64(if k < axes.len() { *p } else { 0 });
        }
        return Ok(());
    }
    for (k, o) in origin.iter().enumerate().take(count) {
        let p = axes.get(k).map_or(0, |a| {
            if let Some(frame) = &transformed {
                return pulses(c.scale(*a), frame.get(k).copied().unwrap_or(0.0));
            }
            let v = c.status(*a).map_or(0, |st| pick(c, *a, st));
            if user {
                v.saturating_sub(*o)
            } else {
                v
            }
        });
        c.output.i64(p);
    }
    Ok(())
}

/// Planned positions in user coordinates (machine less the origin, digest 001 §4.1; under a
/// transform the program's coordinates, "读取规划位置" of the coordinate system).
fn crd_get_prf_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    positions(c, |c, a, s| pulses(c.scale(a), s.cmd_pos), true)
}

/// Planned positions in machine coordinates.
fn crd_get_axis_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    positions(c, |c, a, s| pulses(c.scale(a), s.cmd_pos), false)
}

/// The members' encoders as `NMC_MtGetEncPos` reads them.
fn crd_get_enc_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    positions(c, |c, a, s| c.service.ax().enc_pos(a, s), false)
}

/// The path scale: the first member's (decisions.md).
pub(super) fn path_scale(c: &Call<'_>, s: &CrdState) -> PulseScale {
    s.axes().first().map_or(
        PulseScale {
            pulses_per_unit: 1.0,
        },
        |a| c.scale(*a),
    )
}

/// Path velocity, pulse/ms.
fn crd_get_vel(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let s = state(c, n);
    let v = group(c, n).map_or(0.0, |g| {
        velocity_from_engine(path_scale(c, &s), g.path_velocity)
    });
    c.output.f64(v);
    Ok(())
}

fn crd_buf_get_free(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let s = state(c, n);
    c.output.i64(free(c, n, &s) as i64);
    Ok(())
}

fn crd_buf_get_used(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let s = state(c, n);
    c.output.i64(used(c, n, &s) as i64);
    Ok(())
}

/// The user segment number of the motion running (or last run): buffered commands carry none
/// (decisions.md).
fn crd_get_user_seg_no(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let seg = user_seg(c, n);
    c.output.i64(seg);
    Ok(())
}

fn crd_get_buf_all_cmd_cnt(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    c.output.i64(state(c, n).pushed as i64);
    Ok(())
}

/// The path length still to run in the engine's queue, pulses (pending commands not counted
/// before `NMC_CrdStartMtn`).
fn crd_get_buf_left_length(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = crd(c)?;
    let s = state(c, n);
    let len = group(c, n).map_or(0.0, |g| path_scale(c, &s).from_engine(g.remaining_length));
    c.output.f64(len);
    Ok(())
}

/// What `NMC_MtGetStsPack12Ex` shows of coordinate system `n` (digest 001 §3.4): status word,
/// path velocity (pulse/ms), user segment, free and used entries, length left (pulses) and
/// commands pushed.
pub(super) fn packed(c: &Call<'_>, n: usize) -> (i16, f64, i64, i64, i64, i64, i64) {
    let s = state(c, n);
    let scale = path_scale(c, &s);
    let g = group(c, n);
    (
        (word(c, n) & 0xFFF) as i16,
        g.map_or(0.0, |g| velocity_from_engine(scale, g.path_velocity)),
        user_seg(c, n),
        free(c, n, &s) as i64,
        used(c, n, &s) as i64,
        g.map_or(0, |g| pulses(scale, g.remaining_length)),
        s.pushed as i64,
    )
}

/// The polar transform of the coordinate system's own X and Y axes is set.
fn polar_path(c: &Call<'_>, n: usize) -> bool {
    let transform = c.service.frames().crd.get(n).map(|f| f.transform);
    matches!(
        transform,
        Some(crate::nmc::crd_frames::CrdTransform::Polar { path: true, .. })
    )
}
