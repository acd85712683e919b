//! The laser's immediate functions (digest 001 §2.12, §3.20; S-LASER). mcemu has no laser:
//! every setting is stored and read back (`crate::nmc::laser_state`), and the outputs a real
//! card drives are echoed on the machine's I/O image (docs/decisions.md "NMC laser, SHIO and
//! PWM"):
//! - the channel's switch (its PWM / enable pin) is a digital output, high while the laser is
//!   on: by default output `outputs − 4 + ch` (`outputs`: the controller's own, at most 64;
//!   extension modules come after them); general output `portIdx` after
//!   `NMC_SetPWMPort(1, portIdx, ch)`; the gate pin (`outputs − 2`, the HSIO shared with
//!   compare group 0) after `NMC_SetPwmToGate(0, 0, 1)`. `NMC_LaserGetOnOff` reads that output,
//!   so buffered on/off reads back in path order. `LASER_NONE` has no output image;
//! - `LASER_DA` writes the power (the standby power while off) as the raw value of analog
//!   output `index`, which `NMC_GetDac` reads back.
//!
//! Waveform (time-array) and velocity-following outputs are not timed: a time array leaves the
//! channel as its last point does, at once.

use axes::command::{WriteAnalogOutput, WriteDigitalOutput};
use mcemu_nmc::errors::RTN_BAD_PAYLOAD;
use mcemu_nmc::laser::{LaserPower, TimeArrayPara, LASER_GROUP, LASET_POINT};
use mcemu_nmc::sync_structs::read_array;
use mcemu_nmc::table::{self, Function};

use super::analog::volts;
use super::sync_args::axis_number;
use crate::nmc::laser_state::{CmpTable, LaserChannel, LaserState, CMP_TABLES, LASER_CHANNELS};
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::LASER_SET_MODE, laser_set_mode),
    (table::LASER_SET_MODES, laser_set_mode),
    (table::LASER_SET_OUTPUT_TYPE_EX, laser_set_output_type_ex),
    (table::LASER_SET_OUTPUT_TYPE, laser_set_output_type),
    (table::LASER_SET_PARAM, laser_set_param),
    (table::LASER_GET_PARAM, laser_get_param),
    (table::LASER_SET_POWER_EX, laser_set_power_ex),
    (table::LASER_ON_OFF, laser_on_off),
    (table::LASER_GET_POWER, laser_get_power),
    (table::LASER_GET_ON_OFF, laser_get_on_off),
    (table::LASER_SET_FOLLOW_PARAM, laser_set_follow_param),
    (table::SET_LASER_POWER_CMP_TABLE, set_laser_power_cmp_table),
    (table::START_LASER_POWER_COMP, start_laser_power_comp),
    (table::STOP_LASER_POWER_COMP, stop_laser_power_comp),
    (table::LASER_SET_TIME_ARRAY_PARA, laser_set_time_array_para),
    (
        table::LASER_SET_TIME_ARRAY_POWER,
        laser_set_time_array_power,
    ),
    (table::LASER_TIME_ARRAY_EXE, laser_time_array_exe),
];

/// `LASER_NONE`, `LASER_DA` (digest 001 §3.20).
pub(super) const LASER_NONE: i16 = 0;
const LASER_DA: i16 = 1;
/// `TIME_ARRAY_OUTPUT_MODE`, `SHIO_OUTPUT_MODE`.
pub(super) const TIME_ARRAY_OUTPUT_MODE: i16 = 2;
pub(super) const SHIO_OUTPUT_MODE: i16 = 3;

/// A laser channel argument, [0, 1].
pub(super) fn channel(c: &mut Call<'_>) -> Result<usize, Refusal> {
    let ch = c.input.i16()?;
    usize::try_from(ch)
        .ok()
        .filter(|k| *k < LASER_CHANNELS)
        .ok_or_else(|| Refusal::range("ch", ch, "[0, 1]"))
}

pub(super) fn laser(c: &Call<'_>) -> LaserState {
    c.service.stored().laser.clone()
}

pub(super) fn update(c: &Call<'_>, f: impl FnOnce(&mut LaserState)) {
    f(&mut c.service.stored().laser);
}

fn channel_state(c: &Call<'_>, ch: usize) -> LaserChannel {
    laser(c).channels.get(ch).cloned().unwrap_or_default()
}

fn update_channel(c: &Call<'_>, ch: usize, f: impl FnOnce(&mut LaserChannel)) {
    update(c, |l| {
        if let Some(k) = l.channels.get_mut(ch) {
            f(k);
        }
    });
}

/// The gate pin (SHIO channel 0): the machine's output `outputs − 2`, the HSIO compare group
/// 0's GATE drives too (docs/decisions.md).
pub(super) fn gate_output(c: &Call<'_>) -> Option<u16> {
    super::io_modules::local_outputs(c)
        .checked_sub(2)
        .map(|o| o as u16)
}

/// The digital output that shows channel `ch` on or off, if it has one (module doc).
pub(super) fn switch_output(c: &Call<'_>, l: &LaserState, ch: usize) -> Option<u16> {
    let k = l.channels.get(ch)?;
    if k.output_type == LASER_NONE {
        return None;
    }
    let outputs = c.snapshot.io.do_.len();
    let local = super::io_modules::local_outputs(c);
    let o = if ch == 0 && l.shio.pwm_to_gate {
        local.checked_sub(2)
    } else if k.pwm_port_type == 1 {
        usize::try_from(k.pwm_port_idx).ok()
    } else {
        (local + ch).checked_sub(4)
    };
    o.filter(|o| *o < outputs).map(|o| o as u16)
}

/// Before channel `ch`'s switch output moves (output type, port, gate mapping): the old one
/// goes low.
pub(super) fn release_switch(c: &mut Call<'_>, ch: usize) {
    let l = laser(c);
    if let Some(o) = switch_output(c, &l, ch) {
        c.command(WriteDigitalOutput {
            channel: o,
            value: false,
        });
    }
}

/// The largest power of output type `t`: DA raw, duty %, frequency Hz (digest 001 §2.12).
fn power_max(t: i16) -> i64 {
    match t {
        LASER_DA => 32767,
        2 => 100,
        _ => 2_000_000,
    }
}

pub(super) fn check_power(name: &str, t: i16, v: f64) -> Result<(), Refusal> {
    let max = power_max(t);
    if v.is_finite() && (0.0..=max as f64).contains(&v) {
        Ok(())
    } else {
        Err(Refusal::range(
            name,
            v,
            &format!("[0, {max}] for output type {t}"),
        ))
    }
}

/// onDelay … standbyPower of `NMC_LaserSetParam` / `NMC_CrdBufLaserSetParam`, checked.
pub(super) fn read_param(c: &mut Call<'_>) -> Result<[i64; 5], Refusal> {
    let v = [
        c.input.i64()?,
        c.input.i64()?,
        c.input.i64()?,
        c.input.i64()?,
        c.input.i64()?,
    ];
    for (name, x) in [("onDelay", v[0]), ("offDelay", v[1])] {
        if !(0..=65535).contains(&x) {
            return Err(Refusal::range(name, x, "[0, 65535] µs"));
        }
    }
    for (name, x) in [
        ("minValue", v[2]),
        ("maxValue", v[3]),
        ("standbyPower", v[4]),
    ] {
        if !(0..=2_000_000).contains(&x) {
            return Err(Refusal::range(name, x, "[0, 2000000]"));
        }
    }
    if v[2] > v[3] {
        return Err(Refusal::range("minValue", v[2], "[0, maxValue]"));
    }
    Ok(v)
}

pub(super) fn store_param(k: &mut LaserChannel, v: [i64; 5]) {
    [
        k.on_delay,
        k.off_delay,
        k.min_value,
        k.max_value,
        k.standby_power,
    ] = v;
}

/// Drive channel `ch`'s outputs from its state now: the switch output, and for `LASER_DA` the
/// analog output (power while on, standby power while off; held within [min, max] when a
/// maximum is set).
pub(super) fn drive(c: &mut Call<'_>, ch: usize) {
    let l = laser(c);
    let Some(k) = l.channels.get(ch) else {
        return;
    };
    if let Some(o) = switch_output(c, &l, ch) {
        c.command(WriteDigitalOutput {
            channel: o,
            value: k.on,
        });
    }
    let ao = usize::try_from(k.index).ok();
    if k.output_type == LASER_DA {
        if let Some(ao) = ao.filter(|a| *a < c.snapshot.io.ao.len()) {
            let mut value = if k.on {
                k.power
            } else {
                k.standby_power as f64
            };
            if k.on && k.max_value > 0 {
                value = value.clamp(k.min_value as f64, k.max_value as f64);
            }
            let raw = value.round().clamp(0.0, 32767.0) as i16;
            let mode = {
                let mut stored = c.service.stored();
                let d = stored.dac.entry(ao).or_default();
                d.raw = raw;
                d.mode
            };
            c.command(WriteAnalogOutput {
                channel: ao as u16,
                value: volts(raw, mode),
            });
        }
    }
}

/// mode: `LASER_DISABLE_MODE` 0 … `SHIO_OUTPUT_MODE` 3. `NMC_LaserSetModes` is the manual's
/// text's spelling (digest 001 App. A).
fn laser_set_mode(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let mode = c.input.i16()?;
    let ch = channel(c)?;
    if !(0..=3).contains(&mode) {
        return Err(Refusal::range(
            "mode",
            mode,
            "[0, 3] (LASER_DISABLE_MODE … SHIO_OUTPUT_MODE)",
        ));
    }
    update_channel(c, ch, |k| k.mode = mode);
    Ok(())
}

/// outputType `LASER_NONE` 0 … `LASER_PWM_FRQ_EXT` 4; index: the analog output for
/// `LASER_DA` (one of the machine's), the PWM channel [0, 1] otherwise; optionVal: the PWM
/// frequency (Hz, > 0) for `LASER_PWM_DUTY`, the duty (0, 100] for `LASER_PWM_FRQ`, the pulse
/// width (> 0) for `LASER_PWM_FRQ_EXT`, ignored for `LASER_DA`. The outputs follow at once.
fn set_output_type(c: &mut Call<'_>, t: i16, index: i16, option: f64) -> Result<(), Refusal> {
    let ch = channel(c)?;
    match t {
        LASER_NONE => {}
        LASER_DA => {
            let n = c.snapshot.io.ao.len();
            if !usize::try_from(index).is_ok_and(|i| i < n) {
                return Err(Refusal::range(
                    "index",
                    index,
                    &format!("[0, {}] (analog outputs)", n.saturating_sub(1)),
                ));
            }
        }
        2..=4 => {
            if !(0..=1).contains(&index) {
                return Err(Refusal::range("index", index, "[0, 1] (PWM channels)"));
            }
            let ok = option.is_finite() && option > 0.0 && (t != 3 || option <= 100.0);
            if !ok {
                let allowed = match t {
                    2 => "(0, ∞) Hz",
                    3 => "(0, 100] %",
                    _ => "(0, ∞) µs",
                };
                return Err(Refusal::range("optionVal", option, allowed));
            }
        }
        _ => {
            return Err(Refusal::range(
                "outputType",
                t,
                "[0, 4] (LASER_NONE … LASER_PWM_FRQ_EXT)",
            ))
        }
    }
    release_switch(c, ch);
    update_channel(c, ch, |k| {
        k.output_type = t;
        k.index = index;
        k.option = option;
    });
    drive(c, ch);
    Ok(())
}

fn laser_set_output_type_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (t, index, option) = (c.input.i16()?, c.input.i16()?, c.input.f64()?);
    set_output_type(c, t, index, option)
}

/// The examples' non-Ex form: optionVal a `long` (digest 001 App. A).
fn laser_set_output_type(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (t, index, option) = (c.input.i16()?, c.input.i16()?, c.input.i64()?);
    set_output_type(c, t, index, option as f64)
}

fn laser_set_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let v = read_param(c)?;
    let ch = channel(c)?;
    update_channel(c, ch, |k| store_param(k, v));
    drive(c, ch);
    Ok(())
}

fn laser_get_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ch = channel(c)?;
    let k = channel_state(c, ch);
    c.output
        .i64(k.on_delay)
        .i64(k.off_delay)
        .i64(k.min_value)
        .i64(k.max_value)
        .i64(k.standby_power);
    Ok(())
}

/// outVal within the output type's range (DA [0, 32767], duty [0, 100], frequency
/// [0, 2000000]).
fn laser_set_power_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let v = c.input.f64()?;
    let ch = channel(c)?;
    check_power("outVal", channel_state(c, ch).output_type, v)?;
    update_channel(c, ch, |k| k.power = v);
    drive(c, ch);
    Ok(())
}

/// onOff 0 off, 1 on; also interrupts a running time array (digest 001 §2.12).
fn laser_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let on = c.input.i16()?;
    let ch = channel(c)?;
    if !(0..=1).contains(&on) {
        return Err(Refusal::range("onOff", on, "{0, 1}"));
    }
    update_channel(c, ch, |k| k.on = on == 1);
    drive(c, ch);
    Ok(())
}

fn laser_get_power(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ch = channel(c)?;
    c.output.f64(channel_state(c, ch).power);
    Ok(())
}

/// The level of the channel's switch output (buffered on/off reads back in path order); the
/// stored state when the channel has no output image.
fn laser_get_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ch = channel(c)?;
    let l = laser(c);
    let on = match switch_output(c, &l, ch) {
        Some(o) => c
            .snapshot
            .io
            .do_
            .get(usize::from(o))
            .copied()
            .unwrap_or(false),
        None => l.channels.get(ch).is_some_and(|k| k.on),
    };
    c.output.i16(i16::from(on));
    Ok(())
}

/// powerFilter [0, 32] (0 off), followAdvMode 0 (ratio·vel) or 1 (ratio·vel + min): stored;
/// the power does not follow the path velocity in mcemu.
fn laser_set_follow_param(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (filter, mode) = (c.input.i16()?, c.input.i16()?);
    let ch = channel(c)?;
    if !(0..=32).contains(&filter) {
        return Err(Refusal::range("powerFilter", filter, "[0, 32]"));
    }
    if !(0..=1).contains(&mode) {
        return Err(Refusal::range("followAdvMode", mode, "{0, 1}"));
    }
    update_channel(c, ch, |k| {
        k.follow_filter = filter;
        k.follow_mode = mode;
    });
    Ok(())
}

/// tableNo [0, 19]; xCount, yCount [2, 10] with as many positions; xCount·yCount powers;
/// powerMin ≤ powerMax. Stored: the power is not compensated in mcemu.
fn set_laser_power_cmp_table(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let table_no = c.input.i16()?;
    let x = read_array(&mut c.input, |r| r.i64())?;
    let y = read_array(&mut c.input, |r| r.i64())?;
    let (x_count, y_count) = (c.input.i16()?, c.input.i16()?);
    let (power_min, power_max) = (c.input.u64()?, c.input.u64()?);
    let power = read_array(&mut c.input, |r| r.u64())?;
    channel(c)?;
    if !(0..CMP_TABLES as i16).contains(&table_no) {
        return Err(Refusal::range("tableNo", table_no, "[0, 19]"));
    }
    for (name, n) in [("xCount", x_count), ("yCount", y_count)] {
        if !(2..=10).contains(&n) {
            return Err(Refusal::range(name, n, "[2, 10]"));
        }
    }
    let (nx, ny) = (x_count as usize, y_count as usize);
    if x.len() != nx || y.len() != ny || power.len() != nx * ny {
        return Err(Refusal::new(
            RTN_BAD_PAYLOAD,
            "the position and power arrays do not hold xCount, yCount and xCount·yCount values",
        ));
    }
    if power_min > power_max {
        return Err(Refusal::range("powerMin", power_min, "[0, powerMax]"));
    }
    let t = CmpTable {
        x,
        y,
        power_min,
        power_max,
        power,
    };
    update(c, |l| {
        l.cmp_tables.insert(table_no, t);
    });
    Ok(())
}

/// pAxisNo: the X and Y axes (two of the device's). Stored until `NMC_StopLaserPowerComp`.
fn start_laser_power_comp(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let axes = read_array(&mut c.input, |r| r.i16())?;
    let ch = channel(c)?;
    let &[ax, ay] = axes.as_slice() else {
        return Err(Refusal::new(
            RTN_BAD_PAYLOAD,
            format!("pAxisNo holds {} axes; 2 expected", axes.len()),
        ));
    };
    axis_number(c, "pAxisNo[0]", i64::from(ax))?;
    axis_number(c, "pAxisNo[1]", i64::from(ay))?;
    update_channel(c, ch, |k| k.comp_axes = Some([ax, ay]));
    Ok(())
}

fn stop_laser_power_comp(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ch = channel(c)?;
    update_channel(c, ch, |k| k.comp_axes = None);
    Ok(())
}

/// pwmEnable, outputType, posSrc ∈ {0, 1}; gateDistance ≥ 0 and > 0 when pwmEnable is 1
/// (one waveform per gateDistance of travel); axisMask names the device's axes.
fn laser_set_time_array_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let p = TimeArrayPara::read(&mut c.input)?;
    let ch = channel(c)?;
    for (name, v) in [
        ("pwmEnable", p.pwm_enable),
        ("outputType", p.output_type),
        ("posSrc", p.pos_src),
        ("stLevelRevs", p.st_level_revs),
    ] {
        if !(0..=1).contains(&v) {
            return Err(Refusal::range(name, v, "{0, 1}"));
        }
    }
    if p.gate_distance < 0 || (p.pwm_enable == 1 && p.gate_distance == 0) {
        return Err(Refusal::range(
            "gateDistance",
            p.gate_distance,
            "[0, ∞) pulses, > 0 with pwmEnable 1",
        ));
    }
    axis_mask(c, "axisMask", p.axis_mask)?;
    update_channel(c, ch, |k| k.time_array = p);
    Ok(())
}

/// An axis mask of the device's axes.
pub(super) fn axis_mask(c: &Call<'_>, name: &str, mask: i16) -> Result<(), Refusal> {
    let n = c.snapshot.axes.len().min(15);
    if mask >= 0 && i32::from(mask) < (1 << n) {
        Ok(())
    } else {
        Err(Refusal::range(
            name,
            format!("{mask:#x}"),
            &format!("[0, {:#x}] (the device's {n} axes)", (1 << n) - 1),
        ))
    }
}

/// A power-time group argument, [0, 11].
pub(super) fn group(c: &mut Call<'_>) -> Result<i16, Refusal> {
    let g = c.input.i16()?;
    if (0..LASER_GROUP as i16).contains(&g) {
        Ok(g)
    } else {
        Err(Refusal::range("group", g, "[0, 11]"))
    }
}

/// count [1, LASET_POINT = 40], each point's power ≥ 0.
fn laser_set_time_array_power(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let g = group(c)?;
    let p = LaserPower::read(&mut c.input)?;
    if !(1..=LASET_POINT as i16).contains(&p.count) {
        return Err(Refusal::range(
            "pLaserPower->count",
            p.count,
            "[1, 40] (LASET_POINT)",
        ));
    }
    if p.points.len() != p.count as usize {
        return Err(Refusal::new(
            RTN_BAD_PAYLOAD,
            format!("{} points sent, count says {}", p.points.len(), p.count),
        ));
    }
    if let Some((_, bad)) = p.points.iter().find(|(_, pw)| *pw < 0) {
        return Err(Refusal::range("pLaserPower->power", bad, "[0, 32767]"));
    }
    update(c, |l| {
        l.power_arrays.insert(g, p);
    });
    Ok(())
}

/// What running group `g` on channel `ch` leaves: (on, power). The array's time course is not
/// modelled: the channel ends as its last point says, off when that power is 0 and no
/// travel-driven PWM goes with it (the vendor header's note).
pub(super) fn time_array_end(c: &Call<'_>, g: i16, ch: usize) -> Result<(bool, f64), Refusal> {
    let l = laser(c);
    let k = l.channels.get(ch).cloned().unwrap_or_default();
    if k.mode != TIME_ARRAY_OUTPUT_MODE {
        return Err(Refusal::new(
            mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidState),
            format!(
                "channel {ch} is in mode {}; time arrays run in TIME_ARRAY_OUTPUT_MODE (2)",
                k.mode
            ),
        ));
    }
    let Some(p) = l.power_arrays.get(&g) else {
        return Err(Refusal::new(
            mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidState),
            format!("power-time group {g} was never set (NMC_LaserSetTimeArrayPower)"),
        ));
    };
    let last = p.points.last().map_or(0, |(_, pw)| *pw);
    let on = last != 0 || k.time_array.pwm_enable == 1;
    Ok((on, f64::from(last)))
}

fn laser_time_array_exe(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let g = group(c)?;
    let ch = channel(c)?;
    let (on, power) = time_array_end(c, g, ch)?;
    update_channel(c, ch, |k| {
        k.on = on;
        k.power = power;
    });
    drive(c, ch);
    Ok(())
}
