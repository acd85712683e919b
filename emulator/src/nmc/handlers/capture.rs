//! Capture (digest 001 §2.18, §3.15, §4.6; S-CAPT, S-ADVCAPT, TV60–62): the axis's channel 0
//! is the plain and repeated capture; advanced channel `ch` is channel 1 + `ch` of its
//! position axis. The latch is the encoder counter at the edge.

use axes::command::{CaptureArm, CaptureClear, CaptureEdge, CaptureSource};
use axes::status::CaptureStatus;
use mcemu_dialects::nmc::adv_capture_status;
use mcemu_nmc::errors::RTN_UNSUPPORTED;
use mcemu_nmc::sync_structs::AdvCaptureParam;
use mcemu_nmc::table::{self, Function};

use super::sync_args::{axis_number, count_in};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_SET_CAPT_SNS, mt_set_capt_sns),
    (table::MT_GET_CAPT_SNS, mt_get_capt_sns),
    (table::MT_SET_CAPT, mt_set_capt),
    (table::MT_GET_CAPT_POS, mt_get_capt_pos),
    (table::MT_CLR_CAPT_STS, mt_clr_capt_sts),
    (table::MT_SET_ADV_CAPT_PARAM, mt_set_adv_capt_param),
    (table::MT_CLR_ADV_CAPT_STS, mt_clr_adv_capt_sts),
    (table::MT_GET_ADV_CAPT_POS, mt_get_adv_capt_pos),
    (table::MT_SET_CAPT_REPEAT, mt_set_capt_repeat),
    (table::MT_GET_CAPT_REPEAT_STATUS, mt_get_capt_repeat_status),
    (
        table::MT_GET_CAPT_REPEAT_POS_MULTI,
        mt_get_capt_repeat_pos_multi,
    ),
];

/// `REPEAT_CAPT_MAX_NUM` (TV62).
const REPEAT_CAPT_MAX_NUM: i16 = 64;
/// The plain capture's channel; advanced channel `ch` is `ADV_BASE + ch`.
const PLAIN: u8 = 0;
const ADV_BASE: u8 = 1;

fn channel<'s>(c: &'s Call<'_>, axis: usize, channel: u8) -> Option<&'s CaptureStatus> {
    c.snapshot
        .captures
        .iter()
        .find(|k| usize::from(k.axis) == axis && k.channel == channel)
}

/// A latched count of axis `axis`'s encoder as the encoder reads (`ax_state::EncReport`), in
/// the frame of now: a homing since the edge moves it with the rest.
fn latched_reading(c: &Call<'_>, axis: usize, counts: i64) -> i64 {
    c.status(axis)
        .map_or(counts, |s| c.service.ax().enc_reading(axis, counts, s))
}

fn edge(rising: bool) -> CaptureEdge {
    if rising {
        CaptureEdge::Rising
    } else {
        CaptureEdge::Falling
    }
}

/// mode CAPT_MODE_Z 0 / IO 1 (Z_AND_IO 2 and Z_AFT_IO 3 are stored and refused at arming: the
/// engine latches one signal per channel); ioSrc home 0, limits 1–2, DI0–DI12 3–15; level bit 0
/// the index edge, bit 1 the IO edge (1 rising).
fn mt_set_capt_sns(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (mode, src, level) = (c.input.i16()?, c.input.i16()?, c.input.i16()?);
    if !(0..=3).contains(&mode) {
        return Err(Refusal::range("mode", mode, "[0, 3] (CAPT_MODE_*)"));
    }
    if !(0..=15).contains(&src) {
        return Err(Refusal::range("ioSrc", src, "[0, 15] (CAPT_IO_SRC_*)"));
    }
    if !(0..=3).contains(&level) {
        return Err(Refusal::range(
            "level",
            level,
            "[0, 3] (bit 0 index, bit 1 IO edge)",
        ));
    }
    if let Some(s) = c.service.sync().axes.get_mut(axis) {
        s.capt_mode = mode;
        s.capt_io_src = src;
        s.capt_level = level;
    }
    Ok(())
}

fn mt_get_capt_sns(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let s = c.service.sync().axes.get(axis).cloned().unwrap_or_default();
    c.output
        .i16(s.capt_mode)
        .i16(s.capt_io_src)
        .i16(s.capt_level);
    Ok(())
}

/// Arm channel 0 of `axis` from its capture sense, for `repeat` edges.
fn arm(c: &mut Call<'_>, axis: usize, repeat: u16) -> Result<(), Refusal> {
    let s = c.service.sync().axes.get(axis).cloned().unwrap_or_default();
    let (source, input, rising) = match (s.capt_mode, s.capt_io_src) {
        (0, _) => (CaptureSource::Index, None, s.capt_level & 1 != 0),
        (1, 0) => (CaptureSource::Home, None, s.capt_level & 2 != 0),
        (1, 1) => (CaptureSource::LimitNeg, None, s.capt_level & 2 != 0),
        (1, 2) => (CaptureSource::LimitPos, None, s.capt_level & 2 != 0),
        (1, di) => (CaptureSource::Di, Some((di - 3) as u16), s.capt_level & 2 != 0),
        (m, _) => {
            return Err(Refusal::new(
                RTN_UNSUPPORTED,
                format!("capture mode {m} (index and IO together) is not emulated: use CAPT_MODE_Z or CAPT_MODE_IO"),
            ))
        }
    };
    c.command(CaptureArm {
        axis: axis as u16,
        channel: PLAIN,
        source,
        input,
        source_axis: None,
        edge: edge(rising),
        repeat,
        continuous: false,
        window: None,
    });
    Ok(())
}

fn mt_set_capt(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    arm(c, axis, 1)
}

/// The encoder counter at the newest edge (0 before any), read as `NMC_MtGetEncPos` reads it.
fn mt_get_capt_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let p = channel(c, axis, PLAIN)
        .and_then(|k| k.latches.last())
        .map_or(0, |l| latched_reading(c, axis, l.encoder_counts));
    c.output.i64(p);
    Ok(())
}

/// Disarms and forgets: BIT_AXIS_CAPTSET clears (TV60).
fn mt_clr_capt_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.command(CaptureClear {
        axis: axis as u16,
        channel: PLAIN,
    });
    Ok(())
}

/// count ∈ [0, 64] (TV62): 0 cancels; n arms channel 0 for n edges, forgetting earlier ones.
fn mt_set_capt_repeat(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let n = count_in("count", c.input.i16()?, 0, REPEAT_CAPT_MAX_NUM)?;
    if n == 0 {
        c.command(CaptureClear {
            axis: axis as u16,
            channel: PLAIN,
        });
        return Ok(());
    }
    arm(c, axis, n as u16)
}

fn mt_get_capt_repeat_status(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let n = channel(c, axis, PLAIN).map_or(0, |k| k.latches.len());
    c.output.i16(i16::try_from(n).unwrap_or(i16::MAX));
    Ok(())
}

/// Positions `startNum` … `startNum + count − 1` (count ∈ [1, 32]), those captured.
fn mt_get_capt_repeat_pos_multi(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let start = count_in("startNum", c.input.i16()?, 0, REPEAT_CAPT_MAX_NUM - 1)?;
    let n = count_in("count", c.input.i16()?, 1, 32)?;
    let pos: Vec<i64> = channel(c, axis, PLAIN)
        .map(|k| {
            k.latches
                .iter()
                .skip(start)
                .take(n)
                .map(|l| latched_reading(c, axis, l.encoder_counts))
                .collect()
        })
        .unwrap_or_default();
    mcemu_nmc::sync_structs::write_array(c.output, &pos, |w, p| {
        w.i64(*p);
    });
    Ok(())
}

fn adv_channel(ch: i16) -> Result<usize, Refusal> {
    count_in("ch", ch, 0, 3)
}

/// Arms advanced channel `ch` on both edges, 2 latches: the leading edge (into trigValue's
/// level) then the trailing one. Sources GPI, limits, home, Z; the position thresholds
/// (PRFPOS 5, ENCPOS 6) are refused (not emulated). The filter is checked and not applied.
fn mt_set_adv_capt_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let p = AdvCaptureParam::read(&mut c.input)?;
    let ch = adv_channel(c.input.i16()?)?;
    let axis = axis_number(c, "capPosIndex", i64::from(p.cap_pos_index))?;
    if !(0..=255).contains(&p.filter) {
        return Err(Refusal::range("filter", p.filter, "[0, 255] × 0.1 ms"));
    }
    let watched = || axis_number(c, "trigIndex", i64::from(p.trig_index)).map(|a| a as u16);
    let (source, input, source_axis) =
        match p.trig_src {
            0 => {
                let di = u16::try_from(p.trig_index)
                    .ok()
                    .filter(|d| usize::from(*d) < c.snapshot.io.di.len())
                    .ok_or_else(|| Refusal::range("trigIndex", p.trig_index, "a digital input"))?;
                (CaptureSource::Di, Some(di), None)
            }
            1 => (CaptureSource::LimitNeg, None, Some(watched()?)),
            2 => (CaptureSource::LimitPos, None, Some(watched()?)),
            3 => (CaptureSource::Home, None, Some(watched()?)),
            4 => (CaptureSource::Index, None, Some(watched()?)),
            5 | 6 => return Err(Refusal::new(
                RTN_UNSUPPORTED,
                "position-threshold capture sources (CAPT_EX_SRC_PRFPOS, _ENCPOS) are not emulated",
            )),
            v => return Err(Refusal::range("trigSrc", v, "[0, 6] (CAPT_EX_SRC_*)")),
        };
    let previous = c.service.sync().adv_capture_axis.get(ch).copied().flatten();
    if let Some(prev) = previous.filter(|a| *a != axis) {
        c.command(CaptureClear {
            axis: prev as u16,
            channel: ADV_BASE + ch as u8,
        });
    }
    c.command(CaptureArm {
        axis: axis as u16,
        channel: ADV_BASE + ch as u8,
        source,
        input,
        source_axis,
        edge: CaptureEdge::Both,
        repeat: 2,
        continuous: false,
        window: None,
    });
    if let Some(slot) = c.service.sync().adv_capture_axis.get_mut(ch) {
        *slot = Some(axis);
    }
    Ok(())
}

fn mt_clr_adv_capt_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ch = adv_channel(c.input.i16()?)?;
    let axis = c
        .service
        .sync()
        .adv_capture_axis
        .get_mut(ch)
        .and_then(Option::take);
    if let Some(axis) = axis {
        c.command(CaptureClear {
            axis: axis as u16,
            channel: ADV_BASE + ch as u8,
        });
    }
    Ok(())
}

/// captSts bit 0 leading, bit 1 trailing (the dialect's word); pPosArray[0] leading, [1]
/// trailing, encoder counts.
fn mt_get_adv_capt_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ch = adv_channel(c.input.i16()?)?;
    let axis = c.service.sync().adv_capture_axis.get(ch).copied().flatten();
    let k = axis.and_then(|a| channel(c, a, ADV_BASE + ch as u8));
    let sts = adv_capture_status(k);
    let mut pos = [0i64; 2];
    for (p, l) in pos
        .iter_mut()
        .zip(k.map(|k| k.latches.as_slice()).unwrap_or_default())
    {
        *p = axis.map_or(l.encoder_counts, |a| {
            latched_reading(c, a, l.encoder_counts)
        });
    }
    c.output.i16(sts);
    mcemu_nmc::sync_structs::write_array(c.output, &pos, |w, p| {
        w.i64(*p);
    });
    Ok(())
}
