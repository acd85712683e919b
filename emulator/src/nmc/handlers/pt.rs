//! PT and PVT streams (digest 001 §2.13–2.14, §4.7; S-PT-STATIC, S-PT-STREAM, TV55–57): each
//! call is one engine stream command; positions are pulses relative to the PT start, times ms
//! from it.

use axes::command::{
    PtKind, PtPoint, PtPush, PvtPoint, PvtPush, StreamClear, StreamConfig, StreamMode, StreamStart,
};
use mcemu_dialects::nmc::acceleration_to_engine;
use mcemu_nmc::sync_structs::{PtPara, PvtPara};
use mcemu_nmc::table::{self, Function};

use super::sync_args::{array_of, axes_to_start, count_in, finite};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_PT_SET_STATIC, mt_pt_set_static),
    (table::MT_PT_GET_STATIC, mt_pt_get_static),
    (table::MT_PT_GET_SPACE, mt_pt_get_space),
    (table::MT_PT_PUSH, mt_pt_push),
    (table::MT_PT_BUF_CLR, mt_stream_clear),
    (table::MT_PT_START_MTN, mt_stream_start),
    (table::MT_PT_SET_PARA, mt_pt_set_para),
    (table::MT_PT_GET_PARA, mt_pt_get_para),
    (table::MT_PVT_SET_PARA, mt_pvt_set_para),
    (table::MT_PVT_GET_PARA, mt_pvt_get_para),
    (table::MT_PVT_DATA, mt_pvt_data),
    (table::MT_PVT_BUF_GET_SPACE, mt_pt_get_space),
    (table::MT_PVT_BUF_CLR, mt_stream_clear),
    (table::MT_PVT_START_MTN, mt_stream_start),
];

/// `MT_PT_PRF_MODE` (digest 001 §3.2); PVT has no mode of its own (§8 item 28) and reads it too.
const MT_PT_PRF_MODE: i16 = 5;

/// The stop deceleration (smoothDec, pulse/ms²) in engine units; 0 = the axis's `decel`.
fn stop_deceleration(c: &Call<'_>, axis: usize, smooth_dec: f64) -> Result<Option<f64>, Refusal> {
    if !smooth_dec.is_finite() || smooth_dec < 0.0 {
        return Err(Refusal::range(
            "smoothDec",
            smooth_dec,
            "[0, ∞) pulse/ms² (0: the axis's dec)",
        ));
    }
    Ok((smooth_dec > 0.0).then(|| acceleration_to_engine(c.scale(axis), smooth_dec)))
}

fn loops(loop_count: i64) -> Result<u32, Refusal> {
    u32::try_from(loop_count).map_err(|_| Refusal::range("loopCount", loop_count, "[0, 2³²)"))
}

fn config(
    c: &mut Call<'_>,
    axis: usize,
    mode: StreamMode,
    loop_count: u32,
    smooth_dec: f64,
) -> Result<(), Refusal> {
    let stop_deceleration = stop_deceleration(c, axis, smooth_dec)?;
    c.command(StreamConfig {
        axis: axis as u16,
        mode,
        loop_count,
        stop_deceleration,
    });
    Ok(())
}

/// onOff 1 static (32 points kept, replayed loopCount times), 0 refresh (2 × 32, streamed);
/// clears the buffer.
fn mt_pt_set_static(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (on, loop_count) = (c.input.i16()?, c.input.i64()?);
    let mode = match on {
        0 => StreamMode::Refresh,
        1 => StreamMode::Static,
        v => return Err(Refusal::range("onOff", v, "{0 refresh, 1 static}")),
    };
    let smooth = c
        .service
        .sync()
        .axes
        .get(axis)
        .map_or(0.0, |s| s.pt.smooth_dec);
    config(c, axis, mode, loops(loop_count)?, smooth)
}

fn mt_pt_get_static(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let s = c.status(axis).map(|s| s.stream).unwrap_or_default();
    c.output
        .i16(i16::from(s.mode == StreamMode::Static))
        .i64(i64::from(s.loop_count));
    Ok(())
}

/// Free and used points (refresh mode: of both FIFOs, 64 in all; TV57).
fn mt_pt_get_space(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let s = c.status(axis).map(|s| s.stream).unwrap_or_default();
    let short = |v: u16| i16::try_from(v).unwrap_or(i16::MAX);
    c.output.i16(short(s.space)).i16(short(s.used));
    Ok(())
}

/// count ∈ [1, 32] (TV56); type MT_PT_NORMAL 0 / STOP 1 / EVEN 2.
fn mt_pt_push(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let n = count_in("count", c.input.i16()?, 1, 32)?;
    let pos = array_of(c, "pPosArray", n, |r| r.f64())?;
    let time = array_of(c, "pTimeArray", n, |r| r.i64())?;
    let kind = array_of(c, "pTypeArray", n, |r| r.i16())?;
    let ppu = c.scale(axis).pulses_per_unit;
    let mut points = Vec::with_capacity(n);
    for ((p, t), k) in pos.into_iter().zip(time).zip(kind) {
        let kind = match k {
            0 => PtKind::Normal,
            1 => PtKind::Stop,
            2 => PtKind::Even,
            v => {
                return Err(Refusal::range(
                    "pTypeArray[i]",
                    v,
                    "{0 NORMAL, 1 STOP, 2 EVEN}",
                ))
            }
        };
        points.push(PtPoint {
            position: finite("pPosArray[i]", p)? / ppu,
            time_ms: t as f64,
            kind,
        });
    }
    c.command(PtPush {
        axis: axis as u16,
        points,
    });
    Ok(())
}

fn mt_stream_clear(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.command(StreamClear { axis: axis as u16 });
    Ok(())
}

/// The handle's axis and the other axes start in the same tick.
fn mt_stream_start(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axes = axes_to_start(c)?;
    c.command(StreamStart {
        axes: axes.iter().map(|a| *a as u16).collect(),
    });
    for a in axes {
        c.update(a, |s| s.prf_mode = MT_PT_PRF_MODE);
    }
    Ok(())
}

/// smoothDec is the stop's deceleration when the stream is stopped or runs dry. The engine
/// takes it with the buffer mode, which clears the buffer: applied now when the buffer is
/// empty and idle, else at the next `NMC_MtPtSetStatic` (docs/decisions.md).
fn mt_pt_set_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let p = PtPara::read(&mut c.input)?;
    stop_deceleration(c, axis, p.smooth_dec)?;
    if let Some(s) = c.service.sync().axes.get_mut(axis) {
        s.pt = p;
    }
    let s = c.status(axis).map(|s| s.stream).unwrap_or_default();
    if s.used == 0 && !s.running {
        config(c, axis, s.mode, s.loop_count, p.smooth_dec)?;
    }
    Ok(())
}

/// dataMode 1 static / 0 refresh, loopCount, smoothDec: one `stream_config` (clears the buffer).
fn mt_pvt_set_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let p = PvtPara::read(&mut c.input)?;
    let mode = match p.data_mode {
        0 => StreamMode::Refresh,
        1 => StreamMode::Static,
        v => return Err(Refusal::range("dataMode", v, "{0 refresh, 1 static}")),
    };
    config(c, axis, mode, loops(p.loop_count)?, p.smooth_dec)?;
    if let Some(s) = c.service.sync().axes.get_mut(axis) {
        s.pvt = p;
    }
    Ok(())
}

/// What `NMC_MtPtSetPara` wrote (digest 001 App. A: the C1 table lists it, no section
/// documents it; it reads back `TPtPara`).
fn mt_pt_get_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let p = c
        .service
        .sync()
        .axes
        .get(axis)
        .map(|s| s.pt)
        .unwrap_or_default();
    p.write(c.output);
    Ok(())
}

fn mt_pvt_get_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let p = c
        .service
        .sync()
        .axes
        .get(axis)
        .map(|s| s.pvt)
        .unwrap_or_default();
    p.write(c.output);
    Ok(())
}

/// count ∈ [1, 32]; positions pulse, times ms, velocities pulse/ms.
fn mt_pvt_data(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let n = count_in("count", c.input.i16()?, 1, 32)?;
    let pos = array_of(c, "pPosArray", n, |r| r.f64())?;
    let time = array_of(c, "pTimeArray", n, |r| r.f64())?;
    let vel = array_of(c, "pVelArray", n, |r| r.f64())?;
    let ppu = c.scale(axis).pulses_per_unit;
    let mut points = Vec::with_capacity(n);
    for ((p, t), v) in pos.into_iter().zip(time).zip(vel) {
        points.push(PvtPoint {
            position: finite("pPosArray[i]", p)? / ppu,
            velocity: finite("pVelArray[i]", v)? * 1e3 / ppu,
            time_ms: finite("pTimeArray[i]", t)?,
        });
    }
    c.command(PvtPush {
        axis: axis as u16,
        points,
    });
    Ok(())
}
