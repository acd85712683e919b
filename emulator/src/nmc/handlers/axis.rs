//! Axis handles, the status word, positions, velocities, servo (digest 001 §2.2, §2.4, §2.8).

use axes::command::{Disable, Enable, Reset, ResetFaults};
use axes::{AxisFlags, AxisStatus};
use mcemu_dialects::nmc::{axis_status, latched_faults_of, AxisExtra};
use mcemu_nmc::handle::Handle;
use mcemu_nmc::table::{self, Function};

use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_OPEN, mt_open),
    (table::MT_GET_STS, mt_get_sts),
    (table::MT_GET_STS_EX, mt_get_sts),
    (table::MT_CLR_ERROR, mt_clr_error),
    (table::MT_CLR_STS_BY_BITS, mt_clr_sts_by_bits),
    (table::MT_GET_PRF_POS, mt_get_prf_pos),
    (table::MT_GET_PRF_VEL, mt_get_prf_vel),
    (table::MT_GET_AXIS_POS, mt_get_axis_pos),
    (table::MT_GET_CMD_POS, mt_get_cmd_pos),
    (table::MT_GET_ENC_POS, mt_get_enc_pos),
    (table::MT_SET_SV_ON, mt_set_sv_on),
    (table::MT_SET_SV_OFF, mt_set_sv_off),
    (table::MT_GET_MOTION_IO, mt_get_motion_io),
];

/// Local axes from 0; on an `ecat` card the bus drives from 16 (digest 001 §2.3, TV34).
fn mt_open(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let item = c.input.i16()?;
    let n = c.snapshot.axes.len();
    let bus = c.service.bus();
    let axis = u8::try_from(item)
        .ok()
        .filter(|a| bus.engine_axis(*a, n).is_some())
        .ok_or_else(|| Refusal::range("itemNo", item, &bus.numbers_text(n)))?;
    c.output.u16(Handle::axis(0, axis).encode());
    Ok(())
}

/// The §3.1 word from the dialect (the same 16 bits as a `short`).
fn mt_get_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    // A bus drive in Fault is the drive alarm (ecat_bus).
    let drive_fault = c
        .service
        .bus()
        .drive_of_axis(axis)
        .and_then(|(_, d)| c.snapshot.drives.get(usize::from(d.slave)))
        .is_some_and(|d| d.statusword & axes::cia402::sw::FAULT != 0);
    let extra = AxisExtra {
        drive_fault,
        ..AxisExtra::default()
    };
    let word = c.status(axis).map_or(0, |s| axis_status(s, extra));
    c.output.i16(word as i16);
    Ok(())
}

/// Latched errors whose cause is gone (MVERR, ALM, POSERR, ESTP, limits; digest 001 §4.2).
fn mt_clr_error(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.command(Reset { axis: axis as u16 });
    Ok(())
}

/// Only the latched bits of `stsMask` whose cause is gone (digest 001 §2.4, TV26): the engine's
/// masked reset, a bit whose cause remains staying set (refused with CAUSE_STILL_PRESENT).
fn mt_clr_sts_by_bits(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let mask = c.input.i16()?;
    c.command(ResetFaults {
        axis: axis as u16,
        faults: latched_faults_of(mask as u16),
    });
    Ok(())
}

/// A position in pulses, read from the axis status by `pick` (user units).
fn position(c: &mut Call<'_>, pick: fn(&axes::AxisStatus) -> f64) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let scale = c.scale(axis);
    let p = c.status(axis).map_or(0, |s| pulses(scale, pick(s)));
    c.output.i64(p);
    Ok(())
}

fn mt_get_prf_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    position(c, |s| s.cmd_pos)
}

/// axisPos = prfPos + startPos (`NMC_MtPrfConfig`, digest 001 §2.20, TV70).
fn mt_get_axis_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let scale = c.scale(axis);
    let p = c.status(axis).map_or(0, |s| pulses(scale, s.cmd_pos));
    let start = c.service.ax().axis_loop(axis).start_pos;
    c.output.i64(p.saturating_add(start));
    Ok(())
}

/// The pulses sent to the drive: planned position plus compensation (digest 001 §4.1).
fn mt_get_cmd_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    position(c, |s| s.output_pos)
}

/// The encoder counter (internal mode counts the axis's own pulses, digest 001 §4.1) as the
/// card reads it (`ax_state::EncReport`: homing, `NMC_MtSetEncPos`, `MtSetEncCoe`).
fn mt_get_enc_pos(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let p = c
        .status(axis)
        .map_or(0, |s| c.service.ax().enc_pos(axis, s));
    c.output.i64(p);
    Ok(())
}

/// pulse/ms.
fn mt_get_prf_vel(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let scale = c.scale(axis);
    let v = c.status(axis).map_or(0.0, |s| {
        mcemu_dialects::nmc::velocity_from_engine(scale, s.cmd_vel)
    });
    c.output.f64(v);
    Ok(())
}

fn mt_set_sv_on(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.command(Enable { axis: axis as u16 });
    Ok(())
}

fn mt_set_sv_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    c.command(Disable { axis: axis as u16 });
    Ok(())
}

/// bit0 negative limit, bit1 positive limit, bit2 home, bit3 drive alarm, bit4 in position,
/// bit5 capture source (digest 001 §3.3): the inputs' live active states (TV40), not the
/// latched status bits.
fn mt_get_motion_io(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let v = c.status(axis).map_or(0, motion_io);
    c.output.i64(v);
    Ok(())
}

/// The `NMC_MtGetMotionIO` bits of axis status `s`: the dedicated inputs as they are this tick
/// (after their sense), in-position and the capture latch from the flags.
pub(super) fn motion_io(s: &AxisStatus) -> i64 {
    let mut v = 0i64;
    for (bit, on) in [
        (0, s.inputs.contains(AxisFlags::HW_LIMIT_NEG)),
        (1, s.inputs.contains(AxisFlags::HW_LIMIT_POS)),
        (2, s.inputs.contains(AxisFlags::HOME_SWITCH)),
        (3, s.inputs.contains(AxisFlags::DRIVE_ALARM)),
        (4, s.flags.contains(AxisFlags::IN_POSITION)),
        (5, s.flags.contains(AxisFlags::CAPTURE_TRIGGERED)),
    ] {
        if on {
            v |= 1 << bit;
        }
    }
    v
}
