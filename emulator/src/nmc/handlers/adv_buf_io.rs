//! The advanced buffered I/O channels (digest 001 §2.7, §3.12; rows 0x1609–0x160C): each of
//! the `MAX_ADV_BUFIO_GROUP` channels names one digital output (a general output by group and
//! index, or the gate pin), its active level, and level or pulse mode. `NMC_AdvBufIoOut` drives
//! it now; `NMC_CrdAdvBufIoOnAfterLen` / `OffBeforeLen` (`crd_buf_io`) at a path distance;
//! `NMC_AdvBufIoGetPulseCnt` reads the engine's count of the pulses its trains have output
//! (`IoImage::do_pulses`) since the channel was set.

use axes::command::{PulseDigitalOutput, WriteDigitalOutput};
use mcemu_nmc::buf_pack::{AdvBufIoParam, MAX_ADV_BUFIO_GROUP};
use mcemu_nmc::table::{self, Function};

use crate::nmc::io_state::AdvBufIoChannel;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::ADV_BUF_IO_SET_PARAM, adv_buf_io_set_param),
    (table::ADV_BUF_IO_GET_PARAM, adv_buf_io_get_param),
    (table::ADV_BUF_IO_OUT, adv_buf_io_out),
    (table::ADV_BUF_IO_GET_PULSE_CNT, adv_buf_io_get_pulse_cnt),
];

/// ch ∈ [0, MAX_ADV_BUFIO_GROUP).
fn channel(c: &mut Call<'_>) -> Result<usize, Refusal> {
    let ch = c.input.i16()?;
    usize::try_from(ch)
        .ok()
        .filter(|k| *k < MAX_ADV_BUFIO_GROUP)
        .ok_or_else(|| {
            Refusal::range(
                "ch",
                ch,
                &format!("[0, {}] (MAX_ADV_BUFIO_GROUP − 1)", MAX_ADV_BUFIO_GROUP - 1),
            )
        })
}

/// Channel `ch` (read from the request), set by `NMC_AdvBufIoSetParam`.
pub(super) fn configured(c: &mut Call<'_>) -> Result<AdvBufIoChannel, Refusal> {
    let ch = channel(c)?;
    c.service
        .io()
        .adv_buf_io
        .get(ch)
        .copied()
        .flatten()
        .ok_or_else(|| {
            Refusal::new(
                mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidState),
                format!(
                    "advanced buffered I/O channel {ch} is not set: NMC_AdvBufIoSetParam first"
                ),
            )
        })
}

/// `count` pulses as toggles of a train: [1, 1000000] (0: until ended, as
/// `NMC_DoBitPulseEnable`'s outCount).
pub(super) fn pulse_toggles(name: &str, count: i64) -> Result<u32, Refusal> {
    match count {
        0 => Ok(u32::MAX),
        1..=1_000_000 => Ok((count * 2) as u32),
        _ => Err(Refusal::range(name, count, "[0, 1000000] (0: until ended)")),
    }
}

fn flag(name: &str, v: i16) -> Result<(), Refusal> {
    if (0..=1).contains(&v) {
        Ok(())
    } else {
        Err(Refusal::range(name, v, "{0, 1}"))
    }
}

/// outType 0 general output (`outGroup`·32 + `outIndex`), 1 the gate pin; outSns and
/// pulseMode 0/1; in pulse mode the on and off times [1, 1e9] µs.
fn adv_buf_io_set_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let p = AdvBufIoParam::read(&mut c.input)?;
    let ch = channel(c)?;
    let output = match p.out_type {
        0 => {
            if !(0..32).contains(&p.out_index) {
                return Err(Refusal::range("outIndex", p.out_index, "[0, 31]"));
            }
            let bit = i32::from(p.out_group) * 32 + i32::from(p.out_index);
            let bit = i16::try_from(bit)
                .map_err(|_| Refusal::range("outGroup", p.out_group, "a group of the device"))?;
            super::io::bit_index(c, bit, c.snapshot.io.do_.len())? as u16
        }
        1 => super::laser::gate_output(c).ok_or_else(|| {
            Refusal::new(
                mcemu_nmc::errors::RTN_UNSUPPORTED,
                "the device has no gate output",
            )
        })?,
        t => return Err(Refusal::range("outType", t, "{0 general, 1 gate}")),
    };
    flag("outSns", p.out_sns)?;
    flag("pulseMode", p.pulse_mode)?;
    if p.pulse_mode == 1 {
        super::io_extras::micros("pulseOnTime", p.pulse_on_time)?;
        super::io_extras::micros("pulseOffTime", p.pulse_off_time)?;
    }
    let pulse_base = c
        .snapshot
        .io
        .do_pulses
        .get(usize::from(output))
        .copied()
        .unwrap_or(0);
    if let Some(slot) = c.service.io().adv_buf_io.get_mut(ch) {
        *slot = Some(AdvBufIoChannel {
            param: p,
            output,
            pulse_base,
        });
    }
    Ok(())
}

/// What was set (zeros before).
fn adv_buf_io_get_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ch = channel(c)?;
    let p = c
        .service
        .io()
        .adv_buf_io
        .get(ch)
        .copied()
        .flatten()
        .map_or_else(AdvBufIoParam::default, |k| k.param);
    p.write(c.output);
    Ok(())
}

/// Level mode: value 0 off (inactive level), 1 on (active level); pulse mode: `value` pulses
/// of the channel's on/off times from now, starting at the active level (0: a train running on
/// the output ends).
fn adv_buf_io_out(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let value = c.input.i64()?;
    let k = configured(c)?;
    let active = k.param.out_sns == 1;
    if k.param.pulse_mode == 1 {
        let toggles = match value {
            0 => 0,
            v => pulse_toggles("value", v)?,
        };
        c.command(PulseDigitalOutput {
            channel: k.output,
            level: active,
            level_time: k.param.pulse_on_time as f64 / 1e6,
            other_time: k.param.pulse_off_time as f64 / 1e6,
            toggles,
        });
    } else {
        if !(0..=1).contains(&value) {
            return Err(Refusal::range("value", value, "{0 off, 1 on}"));
        }
        c.command(WriteDigitalOutput {
            channel: k.output,
            value: (value == 1) == active,
        });
    }
    Ok(())
}

/// Pulses the channel's output has put out since `NMC_AdvBufIoSetParam` (its trains'
/// completed pulses, immediate and buffered alike).
fn adv_buf_io_get_pulse_cnt(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let k = configured(c)?;
    let now = c
        .snapshot
        .io
        .do_pulses
        .get(usize::from(k.output))
        .copied()
        .unwrap_or(0);
    c.output.i64(i64::from(now.wrapping_sub(k.pulse_base)));
    Ok(())
}
