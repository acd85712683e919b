//! The coordinate-system buffered outputs, pulses, E-stop inputs, stops and compensation moves
//! of digest 001 §2.7 (rows 0x1601–0x1607, 0x160D, 0x160E): each is pushed like `NMC_CrdBufDo`
//! and acts where the path reaches it, through the engine's group queue
//! (`group_pulse_output`, `group_set_analog_output`, `group_stop_input`,
//! `group_buffered_halt`, `group_axis_move`). docs/decisions.md "NMC buffered I/O and packs".

use axes::command::{
    GroupAxisMove, GroupBufferedHalt, GroupPulseOutput, GroupSetAnalogOutput, GroupStopInput,
    GroupWaitPosition,
};
use mcemu_dialects::nmc::{acceleration_to_engine, velocity_to_engine};
use mcemu_nmc::ax_structs::ESTOP_DI_EX_CH_NUM;
use mcemu_nmc::errors::RTN_UNSUPPORTED;
use mcemu_nmc::table::{self, Function};

use super::adv_buf_io::{configured, pulse_toggles};
use super::crd::{members, state};
use super::crd_segment::{marker, Push};
use super::io_extras::{flag, pulse_channel, pulse_train};
use crate::nmc::crd::CRD_COUNT;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::CRD_BUF_OUT, crd_buf_out),
    (table::CRD_BUF_STOP_MTN, crd_buf_stop_mtn),
    (table::CRD_BUF_SET_ESTOP_DI, crd_buf_set_estop_di),
    (
        table::CRD_BUF_ESTOP_DI_EX_ON_OFF,
        crd_buf_estop_di_ex_on_off,
    ),
    (
        table::CRD_BUF_DO_BIT_PULSE_ENABLE,
        crd_buf_do_bit_pulse_enable,
    ),
    (
        table::CRD_BUF_DO_BIT_PULSE_DISABLE,
        crd_buf_do_bit_pulse_disable,
    ),
    (
        table::CRD_BUF_BEFORE_AX_SYNC_MOVE,
        crd_buf_before_ax_sync_move,
    ),
    (
        table::CRD_ADV_BUF_IO_ON_AFTER_LEN,
        crd_adv_buf_io_on_after_len,
    ),
    (
        table::CRD_ADV_BUF_IO_OFF_BEFORE_LEN,
        crd_adv_buf_io_off_before_len,
    ),
];

/// The watch slots of `group_stop_input`: per-axis E-stop inputs take the axis number, the
/// advanced E-stop groups 32 + group.
const ESTOP_EX_SLOT: u16 = 32;

/// group 0 (BUF_OUT_GROUP_DA): analog output `ch` to the raw value `value` (as `NMC_SetDac`,
/// through the channel's range, bias and limits); group 1 (BUF_OUT_GROUP_PWM): PWM channel
/// `ch` (0, 1) takes its place in the buffer and switches nothing (mcemu has no PWM generator;
/// the manual's table text for ch/value is garbled, §2.7: ch is read as the channel, value as
/// what it outputs).
fn crd_buf_out(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (group, ch, value) = (c.input.i16()?, c.input.i16()?, c.input.i64()?);
    match group {
        0 => {
            let n = c.snapshot.io.ao.len();
            let channel = usize::try_from(ch).ok().filter(|k| *k < n).ok_or_else(|| {
                Refusal::range(
                    "ch",
                    ch,
                    &format!("[0, {}] (analog outputs)", n.saturating_sub(1)),
                )
            })?;
            let raw = i16::try_from(value)
                .map_err(|_| Refusal::range("value", value, "[-32768, 32767] (DAC raw)"))?;
            let d = super::analog::dac(c, channel);
            let out = i32::from(raw)
                .saturating_add(i32::from(d.bias))
                .clamp(i32::from(d.min), i32::from(d.max));
            let out = i16::try_from(out).unwrap_or(if out < 0 { i16::MIN } else { i16::MAX });
            let command = GroupSetAnalogOutput {
                group: p.group(),
                channel: channel as u16,
                value: super::analog::volts(out, d.mode),
            };
            marker(c, p, vec![command.into()])
        }
        1 => {
            if !(0..=1).contains(&ch) {
                return Err(Refusal::range("ch", ch, "[0, 1] (PWM channels)"));
            }
            if value < 0 {
                return Err(Refusal::range("value", value, "[0, ∞)"));
            }
            marker(c, p, Vec::new())
        }
        g => Err(Refusal::range(
            "group",
            g,
            "{0 BUF_OUT_GROUP_DA, 1 BUF_OUT_GROUP_PWM}",
        )),
    }
}

/// Coordinate system `crdIdx` (−1: this one) stops smoothly where the path reaches this
/// command, as `NMC_CrdStopMtn` would then (its smoothDec; the buffer kept, `NMC_CrdStartMtn`
/// goes on).
fn crd_buf_stop_mtn(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let idx = c.input.i16()?;
    let target = match idx {
        -1 => p.n,
        i => usize::try_from(i)
            .ok()
            .filter(|k| *k < CRD_COUNT)
            .ok_or_else(|| {
                Refusal::range(
                    "crdIdx",
                    i,
                    &format!("[0, {}] or −1 (this one)", CRD_COUNT - 1),
                )
            })?,
    };
    let s = if target == p.n {
        p.s.clone()
    } else {
        state(c, target)
    };
    let axes = members(&s)?;
    let deceleration = (s.ext.smooth_dec > 0.0).then(|| {
        let scale = axes.first().map_or(
            mcemu_dialects::PulseScale {
                pulses_per_unit: 1.0,
            },
            |a| c.scale(*a),
        );
        acceleration_to_engine(scale, s.ext.smooth_dec)
    });
    let command = GroupBufferedHalt {
        group: p.group(),
        target: target as u16,
        deceleration,
    };
    marker(c, p, vec![command.into()])
}

/// From here on, general input `gpiIndex` at `sense` E-stops the coordinate system (the
/// member `axis` with the others: a coordinate system stops as a whole); gpiIndex −1 ends the
/// axis's buffered E-stop input. `axis` must be a member.
fn crd_buf_set_estop_di(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (axis, gpi, sense) = (c.input.i16()?, c.input.i16()?, c.input.i16()?);
    let slot = usize::try_from(axis)
        .ok()
        .filter(|a| p.axes.contains(a))
        .ok_or_else(|| Refusal::range("axis", axis, "an axis of the coordinate system"))?
        as u16;
    let channel = if gpi == -1 {
        None
    } else {
        let bit = super::io::bit_index(c, gpi, c.snapshot.io.di.len())
            .map_err(|_| Refusal::range("gpiIndex", gpi, "a general input, or −1 (none)"))?;
        Some(bit as u16)
    };
    let level = flag("sense", sense)?;
    let command = GroupStopInput {
        group: p.group(),
        slot,
        channel,
        level,
    };
    marker(c, p, vec![command.into()])
}

/// onOff 1: from here on, advanced E-stop group `group`'s input (`NMC_SetEstopDIEx`, a general
/// input) at its level E-stops the coordinate system; 0: no longer. Its axis mask and filter
/// are not applied (the coordinate system stops as a whole, at the first tick of the level).
fn crd_buf_estop_di_ex_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (on, g) = (c.input.i16()?, c.input.i16()?);
    let on = flag("onOff", on)?;
    let g = usize::try_from(g)
        .ok()
        .filter(|g| *g < ESTOP_DI_EX_CH_NUM)
        .ok_or_else(|| {
            Refusal::range(
                "group",
                g,
                &format!("[0, {}] (ESTOP_DI_EX_CH_NUM − 1)", ESTOP_DI_EX_CH_NUM - 1),
            )
        })?;
    let channel = if on {
        let e = c
            .service
            .ax()
            .estop_ex
            .get(g)
            .copied()
            .flatten()
            .ok_or_else(|| {
                Refusal::new(
                    mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidState),
                    format!("advanced E-stop group {g} is not set: NMC_SetEstopDIEx first"),
                )
            })?;
        if e.param.di_type != 0 {
            return Err(Refusal::new(
                RTN_UNSUPPORTED,
                format!(
                    "advanced E-stop group {g} watches diType {}: only general inputs (0) \
                     are watched by a coordinate system's buffer",
                    e.param.di_type
                ),
            ));
        }
        let bit = super::io::bit_index(c, e.param.di_index, c.snapshot.io.di.len())?;
        Some((bit as u16, e.param.di_sense == 1))
    } else {
        None
    };
    let command = GroupStopInput {
        group: p.group(),
        slot: ESTOP_EX_SLOT + g as u16,
        channel: channel.map(|(ch, _)| ch),
        level: channel.is_some_and(|(_, l)| l),
    };
    marker(c, p, vec![command.into()])
}

/// `NMC_DoBitPulseEnable` where the path reaches it (its arguments and checks).
fn crd_buf_do_bit_pulse_enable(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (train, ch) = pulse_train(c)?;
    let bit = usize::from(train.channel);
    let command = GroupPulseOutput {
        group: p.group(),
        channel: train.channel,
        level: Some(train.level),
        level_time: train.level_time,
        other_time: train.other_time,
        toggles: train.toggles,
        after_length: None,
        before_end: None,
    };
    marker(c, p, vec![command.into()])?;
    if let Some(slot) = c.service.io().pulse_channels.get_mut(ch) {
        *slot = Some(bit);
    }
    Ok(())
}

/// Channel `ch`'s train ends where the path reaches this (its output keeps its level); a
/// channel with no train started switches nothing.
fn crd_buf_do_bit_pulse_disable(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let ch = pulse_channel(c.input.i16()?)?;
    let bit = c
        .service
        .io()
        .pulse_channels
        .get_mut(ch)
        .and_then(Option::take);
    let commands = bit
        .map(|bit| {
            GroupPulseOutput {
                group: p.group(),
                channel: bit as u16,
                level: None,
                level_time: 0.0,
                other_time: 0.0,
                toggles: 0,
                after_length: None,
                before_end: None,
            }
            .into()
        })
        .into_iter()
        .collect();
    marker(c, p, commands)
}

/// The compensation move of an axis outside the coordinate system before the motion it follows:
/// `relDistance` pulses at `vel` pulse/ms from where the pushed commands leave it, with
/// `NMC_CrdBufSetPtpMovePara`'s acceleration for the axis (else the coordinate system's
/// synAccMax); the path waits until it arrives, so the motion after it starts from the
/// compensated position.
fn crd_buf_before_ax_sync_move(c: &mut Call<'_>) -> Result<(), Refusal> {
    let mut p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let axis = c.input.i16()?;
    let (distance, vel) = (c.input.i64()?, c.input.f64()?);
    let axis =
        usize::try_from(axis).map_err(|_| Refusal::range("axis", axis, "an axis of the device"))?;
    p.outside(c, axis, "axis")?;
    if !(vel.is_finite() && vel > 0.0) {
        return Err(Refusal::range("vel", vel, "(0, ∞) pulse/ms"));
    }
    let acc =
        p.s.axis_ptp
            .iter()
            .find(|(a, _, _)| *a == axis)
            .map_or(p.s.para.syn_acc_max, |(_, _, a)| *a);
    let to = p.ext_end(c, axis).saturating_add(distance);
    let scale = c.scale(axis);
    let position = scale.to_engine(to as f64);
    let moves = vec![
        GroupAxisMove {
            group: p.group(),
            axis: axis as u16,
            position,
            velocity: Some(velocity_to_engine(scale, vel)),
            acceleration: Some(acceleration_to_engine(scale, acc)),
            deceleration: Some(acceleration_to_engine(scale, acc)),
            jerk: None,
        }
        .into(),
        GroupWaitPosition {
            group: p.group(),
            axis: axis as u16,
            position,
            tolerance: None,
            timeout: None,
            condition: Default::default(),
            source: Default::default(),
        }
        .into(),
    ];
    p.set_ext_end(axis, to);
    marker(c, p, moves)
}

/// outLength ≥ 0 pulses of path.
fn length(p: &Push, v: i64) -> Result<f64, Refusal> {
    if v < 0 {
        return Err(Refusal::range("outLength", v, "[0, ∞) pulses"));
    }
    Ok(p.path_scale().to_engine(v as f64))
}

/// Advanced buffered I/O channel `ch` turns on `outLength` pulses of path after this point: its
/// active level (level mode), or `value` pulses of its on/off times (pulse mode).
fn crd_adv_buf_io_on_after_len(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let (out_length, value) = (c.input.i64()?, c.input.i64()?);
    let k = configured(c)?;
    let after = length(&p, out_length)?;
    let active = k.param.out_sns == 1;
    let (toggles, level_time, other_time) = if k.param.pulse_mode == 1 {
        if value <= 0 {
            return Err(Refusal::range("value", value, "[1, 1000000] pulses"));
        }
        (
            pulse_toggles("value", value)?,
            k.param.pulse_on_time as f64 / 1e6,
            k.param.pulse_off_time as f64 / 1e6,
        )
    } else {
        (0, 0.0, 0.0)
    };
    let command = GroupPulseOutput {
        group: p.group(),
        channel: k.output,
        level: Some(active),
        level_time,
        other_time,
        toggles,
        after_length: Some(after),
        before_end: None,
    };
    marker(c, p, vec![command.into()])
}

/// Advanced buffered I/O channel `ch` turns off (its inactive level; a pulse train ends)
/// `outLength` pulses of path before the end of the motion buffered when the path reaches
/// this point (at once when less is left).
fn crd_adv_buf_io_off_before_len(c: &mut Call<'_>) -> Result<(), Refusal> {
    let p = Push::begin(c)?;
    let _seg_no = c.input.i64()?;
    let out_length = c.input.i64()?;
    let k = configured(c)?;
    let before = length(&p, out_length)?;
    let command = GroupPulseOutput {
        group: p.group(),
        channel: k.output,
        level: Some(k.param.out_sns != 1),
        level_time: 0.0,
        other_time: 0.0,
        toggles: 0,
        after_length: None,
        before_end: Some(before),
    };
    marker(c, p, vec![command.into()])
}
