//! Controller services (digest 001 §2.20, §4.9): the ID for the next power-up, system
//! parameters, the battery-backed clock, the system password, the power-fail backed variables.
//!
//! N/A for an emulator, stored and read back: `NMC_DevWriteID` (read by `NMC_DevReadID`, used
//! by nothing until a restart, which forgets it) and `NMC_DevSetPara` (`PARA_IP_ADDRESS` reads
//! the configured IP until one is written; `PARA_WRITE_EN` 1 marks them written).

use std::time::{SystemTime, UNIX_EPOCH};

use axes::command::ErrorKind;
use mcemu_dialects::nmc::code_for_kind;
use mcemu_nmc::errors::RTN_PASSWORD;
use mcemu_nmc::io_structs::{BackGroup2, NmcTime};
use mcemu_nmc::table::{self, Function};

use crate::nmc::service::{pulses, Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::DEV_WRITE_ID, dev_write_id),
    (table::DEV_GET_PARA, dev_get_para),
    (table::DEV_SET_PARA, dev_set_para),
    (table::GET_TIME, get_time),
    (table::SET_TIME, set_time),
    (table::VERIFY_PASSWORD, verify_password),
    (table::CHANGE_PASSWORD, change_password),
    (table::SET_BACKED_VAR_ON_OFF, set_backed_var_on_off),
    (table::GET_BACKED_VAR_ON_OFF, get_backed_var_on_off),
    (table::GET_BACKED_VAR_GROUP2, get_backed_var_group2),
];

/// `PARA_IP_ADDRESS`, `PARA_WRITE_EN` (mtn_lib20.h; mcemu's ids).
const PARA_IP_ADDRESS: u64 = 1;
const PARA_WRITE_EN: u64 = 0xFFFF;

/// A string of at most 15 bytes (16 with its NUL, digest 001 §2.20).
fn short_string(name: &str, s: &[u8]) -> Result<String, Refusal> {
    if s.is_empty() || s.len() > 15 {
        return Err(Refusal::range(
            name,
            format!("{} bytes", s.len()),
            "1 to 15 bytes",
        ));
    }
    Ok(String::from_utf8_lossy(s).into_owned())
}

fn dev_write_id(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let id = short_string("pIdStr", c.input.str()?)?;
    c.service.io().written_id = Some(id);
    Ok(())
}

fn dev_get_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let id = c.input.u64()?;
    let io = c.service.io();
    let v = match (id, io.para.get(&id)) {
        (_, Some(v)) => *v,
        (PARA_IP_ADDRESS, None) => i64::from(u32::from(c.service.device.ip)),
        (PARA_WRITE_EN, None) => i64::from(io.para_written),
        _ => 0,
    };
    drop(io);
    c.output.i64(v);
    Ok(())
}

fn dev_set_para(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (id, value) = (c.input.u64()?, c.input.i64()?);
    let mut io = c.service.io();
    if id == PARA_WRITE_EN {
        if !(0..=1).contains(&value) {
            return Err(Refusal::range("value", value, "{0, 1} for PARA_WRITE_EN"));
        }
        io.para_written = value == 1;
    } else {
        io.para.insert(id, value);
    }
    Ok(())
}

/// Days since 1970-01-01 of a civil date (H. Hinnant's `days_from_civil`).
fn days_from_civil(y: i64, m: i64, d: i64) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (m + 9) % 12;
    let doy = (153 * mp + 2) / 5 + d - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// The civil date of a day number (`civil_from_days`).
fn civil_from_days(z: i64) -> (i64, i64, i64) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    (
        if m <= 2 {
            yoe + era * 400 + 1
        } else {
            yoe + era * 400
        },
        m,
        d,
    )
}

fn host_seconds() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| i64::try_from(d.as_secs()).unwrap_or(0))
}

/// The RTC: the host's clock (UTC) plus what `NMC_SetTime` moved it by.
fn get_time(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let t = host_seconds() + c.service.io().rtc_offset;
    let (days, secs) = (t.div_euclid(86_400), t.rem_euclid(86_400));
    let (y, m, d) = civil_from_days(days);
    let field = |v: i64| i16::try_from(v).unwrap_or(0);
    NmcTime([
        field(y),
        field(m),
        field(d),
        field(secs / 3600),
        field(secs / 60 % 60),
        field(secs % 60),
    ])
    .write(c.output);
    Ok(())
}

fn check_password(c: &Call<'_>, given: &[u8]) -> Result<(), Refusal> {
    if c.service.io().password.as_bytes() == given {
        Ok(())
    } else {
        Err(Refusal::new(RTN_PASSWORD, "wrong system password"))
    }
}

/// Needs the system password; year [2000, 2099] (TNMCTime), a real date and time of day.
fn set_time(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let NmcTime([y, mo, d, h, mi, s]) = NmcTime::read(&mut c.input)?;
    let password = c.input.str()?.to_vec();
    let in_range = |name: &str, v: i16, lo: i16, hi: i16| {
        if (lo..=hi).contains(&v) {
            Ok(i64::from(v))
        } else {
            Err(Refusal::range(name, v, &format!("[{lo}, {hi}]")))
        }
    };
    let y = in_range("ear", y, 2000, 2099)?;
    let mo = in_range("mon", mo, 1, 12)?;
    let days_in_month = days_from_civil(y + mo / 12, mo % 12 + 1, 1) - days_from_civil(y, mo, 1);
    let d = in_range("day", d, 1, days_in_month as i16)?;
    let secs = in_range("hour", h, 0, 23)? * 3600
        + in_range("min", mi, 0, 59)? * 60
        + in_range("second", s, 0, 59)?;
    check_password(c, &password)?;
    let target = days_from_civil(y, mo, d) * 86_400 + secs;
    c.service.io().rtc_offset = target - host_seconds();
    Ok(())
}

fn verify_password(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let given = c.input.str()?.to_vec();
    check_password(c, &given)
}

fn change_password(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (old, new) = (c.input.str()?.to_vec(), c.input.str()?.to_vec());
    let new = short_string("pPasswordNew", &new)?;
    check_password(c, &old)?;
    c.service.io().password = new;
    Ok(())
}

fn set_backed_var_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let en = c.input.i16()?;
    if !(0..=1).contains(&en) {
        return Err(Refusal::range("en", en, "{0, 1}"));
    }
    c.service.io().backed = en == 1;
    Ok(())
}

fn get_backed_var_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let on = c.service.io().backed;
    c.output.i16(i16::from(on));
    Ok(())
}

/// What a power failure now would save: coordinate systems 0 and 1 (the engine's groups: their
/// segment counts and first three coordinates) and the first 12 axes' planned, axis and encoder
/// positions, in pulses. Refused while backing is off (nothing is saved then).
fn get_backed_var_group2(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    if !c.service.io().backed {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidState),
            "backed variables are off (NMC_SetBackedVarOnOff(dev, 1))",
        ));
    }
    let mut b = BackGroup2::default();
    let mut slots = b.0.iter_mut();
    let mut put = |v: i64| {
        if let Some(s) = slots.next() {
            *s = v;
        }
    };
    let group = |n: usize| c.snapshot.groups.iter().find(|g| usize::from(g.group) == n);
    for n in 0..2 {
        put(group(n).map_or(0, |g| i64::try_from(g.segment).unwrap_or(i64::MAX)));
    }
    for n in 0..2 {
        for k in 0..3 {
            let v = group(n)
                .and_then(|g| g.coordinates.get(k).copied())
                .unwrap_or(0.0);
            put(v.round().clamp(i64::MIN as f64, i64::MAX as f64) as i64);
        }
    }
    let axis = |a: usize, pick: fn(&axes::AxisStatus) -> f64| {
        c.status(a).map_or(0, |s| pulses(c.scale(a), pick(s)))
    };
    for a in 0..12 {
        put(axis(a, |s| s.cmd_pos));
    }
    for a in 0..12 {
        put(axis(a, |s| s.cmd_pos));
    }
    for a in 0..12 {
        put(axis(a, |s| s.act_pos));
    }
    b.write(c.output);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn civil_dates_round_trip() {
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(
            civil_from_days(days_from_civil(2030, 2, 28) + 1),
            (2030, 3, 1)
        );
        assert_eq!(
            civil_from_days(days_from_civil(2028, 2, 28) + 1),
            (2028, 2, 29)
        );
    }
}
