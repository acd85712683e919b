//! Analog outputs and inputs (digest 001 §2.8, §4.8). The engine's analog image is in volts;
//! the NMC's raw values [-32768, 32767] span the channel's range (mode 0 0–5 V, 1 0–10 V, 2
//! 0–10.8 V, 3 ±5 V, 4 ±10 V (default), 5 ±10.8 V). Ranges, raw values, bias and limits are
//! the front-end's (`crate::nmc::stored`).

use axes::command::WriteAnalogOutput;
use mcemu_nmc::table::{self, Function};

use crate::nmc::service::{Call, Handler, Refusal};
use crate::nmc::stored::DacStored;

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::SET_DAC_MODE, set_dac_mode),
    (table::GET_DAC_MODE, get_dac_mode),
    (table::SET_ADC_MODE, set_adc_mode),
    (table::GET_ADC_MODE, get_adc_mode),
    (table::SET_DAC, set_dac),
    (table::GET_DAC, get_dac),
    (table::GET_ADC, get_adc),
    (table::SET_DAC_BIAS, set_dac_bias),
    (table::GET_DAC_BIAS, get_dac_bias),
    (table::SET_DAC_LMT, set_dac_lmt),
    (table::GET_DAC_LMT, get_dac_lmt),
    (table::GET_ADC_VOLTAGE_MULTI, get_adc_voltage_multi),
    (table::SET_DAC_VOLTAGE_MULTI, set_dac_voltage_multi),
    (table::GET_DAC_VOLTAGE_MULTI, get_dac_voltage_multi),
];

/// The volts of range `mode`: (lowest, highest).
fn range(mode: i16) -> Option<(f64, f64)> {
    Some(match mode {
        0 => (0.0, 5.0),
        1 => (0.0, 10.0),
        2 => (0.0, 10.8),
        3 => (-5.0, 5.0),
        4 => (-10.0, 10.0),
        5 => (-10.8, 10.8),
        _ => return None,
    })
}

fn check_mode(name: &str, mode: i16) -> Result<(), Refusal> {
    range(mode)
        .map(|_| ())
        .ok_or_else(|| Refusal::range(name, mode, "[0, 5] (0-5 V … ±10.8 V)"))
}

/// Raw → volts: 32767 is the range's top; a unipolar range takes 0 … 32767.
pub fn volts(raw: i16, mode: i16) -> f64 {
    let (lo, hi) = range(mode).unwrap_or((-10.0, 10.0));
    (f64::from(raw) * hi / 32767.0).clamp(lo, hi)
}

/// Volts → raw, rounded and held within the range's raw values.
pub fn raw(v: f64, mode: i16) -> i16 {
    let (lo, hi) = range(mode).unwrap_or((-10.0, 10.0));
    if !v.is_finite() {
        return 0;
    }
    (v.clamp(lo, hi) * 32767.0 / hi)
        .round()
        .clamp(f64::from(i16::MIN), f64::from(i16::MAX)) as i16
}

/// Analog output `ch` of the device (256+ are extension modules, which mcemu's machines do not
/// have beyond their `analog_outputs`).
fn dac_channel(c: &mut Call<'_>) -> Result<usize, Refusal> {
    c.device()?;
    let ch = c.input.i16()?;
    let n = c.snapshot.io.ao.len();
    usize::try_from(ch).ok().filter(|k| *k < n).ok_or_else(|| {
        Refusal::range(
            "ch",
            ch,
            &format!("[0, {}] (analog outputs)", n.saturating_sub(1)),
        )
    })
}

fn adc_channel(c: &mut Call<'_>) -> Result<usize, Refusal> {
    c.device()?;
    let ch = c.input.i16()?;
    let n = c.snapshot.io.ai.len();
    usize::try_from(ch).ok().filter(|k| *k < n).ok_or_else(|| {
        Refusal::range(
            "ch",
            ch,
            &format!("[0, {}] (analog inputs)", n.saturating_sub(1)),
        )
    })
}

pub(super) fn dac(c: &Call<'_>, ch: usize) -> DacStored {
    c.service.stored().dac.get(&ch).copied().unwrap_or_default()
}

/// Write the output: raw + bias within the limits, in volts of the channel's range.
fn output(c: &mut Call<'_>, ch: usize, d: &DacStored) {
    let out = i32::from(d.raw)
        .saturating_add(i32::from(d.bias))
        .clamp(i32::from(d.min), i32::from(d.max));
    let out = i16::try_from(out).unwrap_or(if out < 0 { i16::MIN } else { i16::MAX });
    c.command(WriteAnalogOutput {
        channel: ch as u16,
        value: volts(out, d.mode),
    });
}

fn set_dac_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = dac_channel(c)?;
    let mode = c.input.i16()?;
    check_mode("mode", mode)?;
    let mut d = dac(c, ch);
    d.mode = mode;
    c.service.stored().dac.insert(ch, d);
    output(c, ch, &d);
    Ok(())
}

fn get_dac_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = dac_channel(c)?;
    c.output.i16(dac(c, ch).mode);
    Ok(())
}

/// range: the manual supports only ±10 V now ("目前只支持 +/-10V"), mcemu all six; filter
/// [0, 64] ms, stored.
fn set_adc_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = adc_channel(c)?;
    let (mode, filter) = (c.input.i16()?, c.input.i16()?);
    check_mode("range", mode)?;
    if !(0..=64).contains(&filter) {
        return Err(Refusal::range("filterCoe", filter, "[0, 64] ms"));
    }
    let mut stored = c.service.stored();
    let a = stored.adc.entry(ch).or_default();
    (a.range, a.filter) = (mode, filter);
    Ok(())
}

fn get_adc_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = adc_channel(c)?;
    let a = c.service.stored().adc.get(&ch).copied().unwrap_or_default();
    c.output.i16(a.range).i16(a.filter);
    Ok(())
}

fn set_dac(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = dac_channel(c)?;
    let value = c.input.i16()?;
    let mut d = dac(c, ch);
    d.raw = value;
    c.service.stored().dac.insert(ch, d);
    output(c, ch, &d);
    Ok(())
}

/// The raw value last written (TV41).
fn get_dac(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = dac_channel(c)?;
    c.output.i16(dac(c, ch).raw);
    Ok(())
}

/// The input's volts in the channel's range.
fn get_adc(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = adc_channel(c)?;
    let mode = c
        .service
        .stored()
        .adc
        .get(&ch)
        .copied()
        .unwrap_or_default()
        .range;
    let v = c.snapshot.io.ai.get(ch).copied().unwrap_or(0.0);
    c.output.i16(raw(v, mode));
    Ok(())
}

fn set_dac_bias(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = dac_channel(c)?;
    let bias = c.input.i16()?;
    let mut d = dac(c, ch);
    d.bias = bias;
    c.service.stored().dac.insert(ch, d);
    output(c, ch, &d);
    Ok(())
}

fn get_dac_bias(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = dac_channel(c)?;
    c.output.i16(dac(c, ch).bias);
    Ok(())
}

fn set_dac_lmt(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = dac_channel(c)?;
    let (max, min) = (c.input.i16()?, c.input.i16()?);
    if max < min {
        return Err(Refusal::range(
            "maxVal",
            max,
            &format!("[minVal = {min}, 32767]"),
        ));
    }
    let mut d = dac(c, ch);
    (d.max, d.min) = (max, min);
    c.service.stored().dac.insert(ch, d);
    output(c, ch, &d);
    Ok(())
}

fn get_dac_lmt(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ch = dac_channel(c)?;
    let d = dac(c, ch);
    c.output.i16(d.max).i16(d.min);
    Ok(())
}

/// Channels `first` … `first + count − 1` (count ∈ [1, 8]) of `n`.
fn multi(c: &mut Call<'_>, n: usize, what: &str) -> Result<(usize, usize), Refusal> {
    c.device()?;
    let (ch, count) = (c.input.i16()?, c.input.i16()?);
    let count = usize::try_from(count)
        .ok()
        .filter(|k| (1..=8).contains(k))
        .ok_or_else(|| Refusal::range("count", count, "[1, 8]"))?;
    let first = usize::try_from(ch)
        .ok()
        .filter(|k| k + count <= n)
        .ok_or_else(|| {
            Refusal::range(
                "ch",
                ch,
                &format!("channels ch … ch + count − 1 of the {n} {what}"),
            )
        })?;
    Ok((first, count))
}

fn get_adc_voltage_multi(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = c.snapshot.io.ai.len();
    let (first, count) = multi(c, n, "analog inputs")?;
    c.output.u16(count as u16);
    for k in first..first + count {
        let v = c.snapshot.io.ai.get(k).copied().unwrap_or(0.0);
        c.output.f64(v);
    }
    Ok(())
}

fn get_dac_voltage_multi(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = c.snapshot.io.ao.len();
    let (first, count) = multi(c, n, "analog outputs")?;
    c.output.u16(count as u16);
    for k in first..first + count {
        let v = c.snapshot.io.ao.get(k).copied().unwrap_or(0.0);
        c.output.f64(v);
    }
    Ok(())
}

/// Volts within each channel's range; the raw value read back is theirs.
fn set_dac_voltage_multi(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = c.snapshot.io.ao.len();
    let (first, count) = multi(c, n, "analog outputs")?;
    let given = usize::from(c.input.u16()?);
    if given != count {
        return Err(Refusal::range("pDacVolArray", given, "count values"));
    }
    for k in first..first + count {
        let v = c.input.f64()?;
        let mut d = dac(c, k);
        let (lo, hi) = range(d.mode).unwrap_or((-10.0, 10.0));
        if !(v.is_finite() && (lo..=hi).contains(&v)) {
            return Err(Refusal::range(
                "voltage",
                v,
                &format!("[{lo}, {hi}] V (the channel's mode)"),
            ));
        }
        d.raw = raw(v, d.mode);
        c.service.stored().dac.insert(k, d);
        c.command(WriteAnalogOutput {
            channel: k as u16,
            value: v,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_values_span_the_range() {
        assert_eq!(volts(32767, 4), 10.0);
        assert_eq!(volts(-32768, 4), -10.0);
        assert_eq!(volts(-100, 1), 0.0);
        assert_eq!(raw(10.0, 4), 32767);
        assert_eq!(raw(5.0, 0), 32767);
        assert_eq!(raw(f64::NAN, 4), 0);
        assert_eq!(raw(-20.0, 4), -32767);
    }
}
