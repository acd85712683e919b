//! Data collection (digest 001 §2.20 "Data collection", §3.19, S-COLLECT) on the engine's
//! sampler [`NMC_SAMPLER`]: it records every servo tick (one planning period, the manual's
//! minimum interval) on the virtual clock, as the card does.
//!
//! An "address" of `NMC_GetCollectDataAddr` is mcemu's: `0x4000_0000 | dataType << 16 |
//! index`, index the axis by its NMC number (positions, velocities; an `ecat` card's bus drives
//! from 16) or the digital channel (DI, DO). Every value
//! is 8 bytes, a little-endian double in the manual's units (pulses, pulse/ms, 0/1): the
//! manual's example reads the data into a `double` array. The coordinate-system variables
//! (CRD_POS0/1, CRD_VEL0/1) are the engine's group 0 or 1: index the coordinate for a position
//! (pulses of that member axis), 0 for the path velocity (pulse/ms of the first member); the
//! coordinate system must be configured. The laser variables (N/A) are refused as unsupported.
//! `startDelay` is in ms like `interval`: the first sample is taken that long after the
//! trigger (decisions.md, "NMC system functions").

use axes::command::{
    EngineError, GroupId, Reply, SampledVariable, SamplerId, SamplingConfigure, SamplingRead,
    SamplingStart, SamplingStop, SamplingTrigger, MAX_SAMPLERS,
};
use axes::sampling::SamplerState;
use axes::status::Snapshot;
use mcemu_dialects::nmc::code_for_kind;
use mcemu_nmc::errors::{RTN_BAD_PAYLOAD, RTN_UNSUPPORTED};
use mcemu_nmc::payload::Writer;
use mcemu_nmc::sys::{CollectCfg, CollectTrig, COLLECT_DATA_MAX, COLLECT_LIST_MAX};
use mcemu_nmc::table::{self, Function};

use crate::nmc::ecat_bus::EcatBus;
use crate::nmc::service::{scale_of, Call, Handler, NmcService, Refusal};
use crate::nmc::sys_state::{Collect, CollectUnit};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::GET_COLLECT_DATA_ADDR, get_collect_data_addr),
    (table::CONFIG_COLLECT, config_collect),
    (table::COLLECT_ON_OFF, collect_on_off),
    (table::GET_COLLECT_STS, get_collect_sts),
    (table::GET_COLLECT_DATA, get_collect_data),
    (table::CLEAR_COLLECT_STS, clear_collect_sts),
];

/// The engine sampler the NMC collection uses: the last, clear of HMC's channel 0 on.
pub const NMC_SAMPLER: SamplerId = MAX_SAMPLERS - 1;
/// The collection buffer, bytes (the manual gives no size; mcemu's).
const BUFFER_BYTES: u64 = 1 << 20;
/// Bytes of one collected value.
const VALUE_BYTES: i16 = 8;
const ADDRESS_TAG: u64 = 0x4000_0000;

/// `COLLECT_ADDRESS_*` (digest 001 §3.19).
const PRF_POS: i16 = 0;
const AXIS_POS: i16 = 1;
const ENC_POS: i16 = 2;
const CMD_POS: i16 = 3;
const AXIS_VEL: i16 = 4;
const CRD_POS0: i16 = 5;
const CRD_VEL0: i16 = 6;
const ENC_VEL: i16 = 7;
const CMD_VEL: i16 = 8;
const CRD_POS1: i16 = 9;
const CRD_VEL1: i16 = 10;
const LASER_OUTPUT: i16 = 11;
const LASER_POWER: i16 = 13;
const DI: i16 = 14;
const DO: i16 = 15;

/// `COLLECT_STS_*` (mtn_lib20.h, mcemu's bits).
const STS_ON: i16 = 0x1;
const STS_TRIGGERED: i16 = 0x2;
const STS_FULL: i16 = 0x4;

/// The engine variable and unit of `dataType` `index`, checked against the machine.
fn variable(
    snapshot: &Snapshot,
    bus: &EcatBus,
    data_type: i16,
    index: i16,
) -> Result<(SampledVariable, CollectUnit), Refusal> {
    // An axis by its NMC number: local, or an `ecat` card's bus drive from 16.
    let axis = || {
        let count = snapshot.axes.len();
        u8::try_from(index)
            .ok()
            .and_then(|n| bus.engine_axis(n, count))
            .map(|a| (a as u16, a))
            .ok_or_else(|| {
                Refusal::range(
                    "index",
                    index,
                    &format!("{} (the axis)", bus.numbers_text(count)),
                )
            })
    };
    let channel = |n: usize| {
        u16::try_from(index)
            .ok()
            .filter(|c| usize::from(*c) < n)
            .ok_or_else(|| {
                Refusal::range(
                    "index",
                    index,
                    &format!("[0, {}] (the channel)", n.saturating_sub(1)),
                )
            })
    };
    Ok(match data_type {
        PRF_POS | AXIS_POS => {
            let (a, axis) = axis()?;
            (
                SampledVariable::PlannedPosition { axis: a },
                CollectUnit::Position { axis },
            )
        }
        ENC_POS => {
            let (a, axis) = axis()?;
            (
                SampledVariable::ActualPosition { axis: a },
                CollectUnit::Position { axis },
            )
        }
        CMD_POS => {
            let (a, axis) = axis()?;
            (
                SampledVariable::OutputPosition { axis: a },
                CollectUnit::Position { axis },
            )
        }
        CMD_VEL => {
            let (a, axis) = axis()?;
            (
                SampledVariable::PlannedVelocity { axis: a },
                CollectUnit::Velocity { axis },
            )
        }
        AXIS_VEL | ENC_VEL => {
            let (a, axis) = axis()?;
            (
                SampledVariable::ActualVelocity { axis: a },
                CollectUnit::Velocity { axis },
            )
        }
        DI => (
            SampledVariable::DigitalInput {
                channel: channel(snapshot.io.di.len())?,
            },
            CollectUnit::Level,
        ),
        DO => (
            SampledVariable::DigitalOutput {
                channel: channel(snapshot.io.do_.len())?,
            },
            CollectUnit::Level,
        ),
        CRD_POS0 | CRD_POS1 => {
            let (group, members) = crd_members(snapshot, data_type)?;
            let coordinate = u8::try_from(index)
                .ok()
                .filter(|k| usize::from(*k) < members.len())
                .ok_or_else(|| {
                    Refusal::range(
                        "index",
                        index,
                        &format!(
                            "[0, {}] (the coordinate of coordinate system {group})",
                            members.len().saturating_sub(1)
                        ),
                    )
                })?;
            let axis = members.get(usize::from(coordinate)).copied().unwrap_or(0);
            (
                SampledVariable::GroupCoordinate { group, coordinate },
                CollectUnit::Position { axis },
            )
        }
        CRD_VEL0 | CRD_VEL1 => {
            let (group, members) = crd_members(snapshot, data_type)?;
            if index != 0 {
                return Err(Refusal::range("index", index, "{0} (the path velocity)"));
            }
            (
                SampledVariable::GroupVelocity { group },
                CollectUnit::Velocity {
                    axis: members.first().copied().unwrap_or(0),
                },
            )
        }
        LASER_OUTPUT..=LASER_POWER => {
            return Err(Refusal::new(
                RTN_UNSUPPORTED,
                format!("dataType {data_type}: the laser variables are not collected by mcemu"),
            ))
        }
        _ => return Err(Refusal::range("dataType", data_type, "[0, 15]")),
    })
}

/// The group a coordinate-system `dataType` reads and its member axes; the coordinate system
/// must be configured.
fn crd_members(snapshot: &Snapshot, data_type: i16) -> Result<(GroupId, Vec<usize>), Refusal> {
    let group: GroupId = if matches!(data_type, CRD_POS0 | CRD_VEL0) {
        0
    } else {
        1
    };
    let g = snapshot
        .groups
        .iter()
        .find(|g| g.group == group)
        .ok_or_else(|| {
            Refusal::new(
                code_for_kind(axes::command::ErrorKind::InvalidState),
                format!(
                    "dataType {data_type}: coordinate system {group} is not configured \
                     (NMC_CrdConfig first)"
                ),
            )
        })?;
    let members = g
        .members
        .iter()
        .take(usize::from(g.axis_count))
        .map(|a| usize::from(*a))
        .collect();
    Ok((group, members))
}

fn get_collect_data_addr(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (index, data_type) = (c.input.i16()?, c.input.i16()?);
    variable(&c.snapshot, c.service.bus(), data_type, index)?;
    let address = ADDRESS_TAG | (data_type as u64) << 16 | u64::from(index as u16);
    c.output.u64(address).i16(VALUE_BYTES);
    Ok(())
}

/// The type and index an address encodes.
fn decode(address: u64) -> Option<(i16, i16)> {
    if address & !0xFF_FFFF != ADDRESS_TAG {
        return None;
    }
    let data_type = i16::try_from(address >> 16 & 0xFF).ok()?;
    Some((data_type, (address & 0xFFFF) as u16 as i16))
}

/// An engine value in the manual's units.
fn convert(snapshot: &Snapshot, unit: CollectUnit, v: f64) -> f64 {
    match unit {
        CollectUnit::Position { axis } => scale_of(snapshot, axis).from_engine(v),
        CollectUnit::Velocity { axis } => scale_of(snapshot, axis).from_engine(v) / 1e3,
        CollectUnit::Level => v,
    }
}

/// A trigger value in the manual's units, in the engine's.
fn to_engine(snapshot: &Snapshot, unit: CollectUnit, v: f64) -> f64 {
    match unit {
        CollectUnit::Position { axis } => scale_of(snapshot, axis).to_engine(v),
        CollectUnit::Velocity { axis } => scale_of(snapshot, axis).to_engine(v * 1e3),
        CollectUnit::Level => v,
    }
}

fn config_collect(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let cfg = CollectCfg::read(&mut c.input)?;
    let trig = CollectTrig::read(&mut c.input)?;
    let count = usize::try_from(cfg.count)
        .ok()
        .filter(|n| (1..=COLLECT_LIST_MAX).contains(n))
        .ok_or_else(|| {
            Refusal::range(
                "pCollect->count",
                cfg.count,
                &format!("[1, {COLLECT_LIST_MAX}]"),
            )
        })?;
    if cfg.interval < 0 {
        return Err(Refusal::range(
            "pCollect->interval",
            cfg.interval,
            "[0, 32767] ms (0: every planning period)",
        ));
    }
    let mut variables = Vec::with_capacity(count);
    let mut units = Vec::with_capacity(count);
    for (k, (address, length)) in cfg.address.iter().zip(cfg.length).take(count).enumerate() {
        let (data_type, index) = decode(*address).ok_or_else(|| {
            Refusal::range(
                &format!("pCollect->address[{k}]"),
                format!("{address:#x}"),
                "the addresses NMC_GetCollectDataAddr returns",
            )
        })?;
        let (v, unit) = variable(&c.snapshot, c.service.bus(), data_type, index)?;
        if length != VALUE_BYTES {
            return Err(Refusal::range(
                &format!("pCollect->length[{k}]"),
                length,
                "{8} (the length NMC_GetCollectDataAddr returns)",
            ));
        }
        variables.push(v);
        units.push(unit);
    }
    let channel = |what: &str| {
        usize::try_from(trig.source1)
            .ok()
            .filter(|s| *s < count)
            .and_then(|s| Some((*variables.get(s)?, *units.get(s)?)))
            .ok_or_else(|| {
                Refusal::range(
                    &format!("pTrig->source1 ({what})"),
                    trig.source1,
                    &format!("[0, {}] (a channel of the list)", count - 1),
                )
            })
    };
    if !trig.value.is_finite() {
        return Err(Refusal::range("pTrig->value", trig.value, "finite numbers"));
    }
    let trigger = match trig.mode {
        0 => SamplingTrigger::Immediate,
        1 => {
            let (variable, unit) = channel("COLLECT_MODE_RISE")?;
            SamplingTrigger::Rising {
                variable,
                value: to_engine(&c.snapshot, unit, trig.value),
            }
        }
        2 => {
            let (variable, unit) = channel("COLLECT_MODE_FALL")?;
            SamplingTrigger::Falling {
                variable,
                value: to_engine(&c.snapshot, unit, trig.value),
            }
        }
        m => {
            return Err(Refusal::range(
                "pTrig->mode",
                m,
                "{0, 1, 2} (COLLECT_MODE_*)",
            ))
        }
    };
    if trig.start_delay < 0 {
        return Err(Refusal::range(
            "pTrig->startDelay",
            trig.start_delay,
            "[0, 32767] ms after the trigger",
        ));
    }
    // interval and startDelay ms → servo ticks; interval 0 = every tick (one planning period).
    let period_ms = (c.snapshot.period * 1e3).max(1e-6);
    let interval = ((f64::from(cfg.interval) / period_ms).round() as u32).max(1);
    let delay = (f64::from(trig.start_delay) / period_ms).round() as u32;
    let row_bytes = 8 * count as u64;
    let config = SamplingConfigure {
        sampler: NMC_SAMPLER,
        variables,
        interval,
        points: (BUFFER_BYTES / row_bytes) as u32,
        trigger,
        delay,
    };
    c.command(config.clone());
    let mut sys = c.service.sys();
    sys.collect = Some(Collect { config, units });
    sys.read_bytes = 0;
    Ok(())
}

fn configured(c: &Call<'_>) -> Result<Collect, Refusal> {
    c.service.sys().collect.clone().ok_or_else(|| {
        Refusal::new(
            code_for_kind(axes::command::ErrorKind::InvalidState),
            "no collection configured (NMC_ConfigCollect first)",
        )
    })
}

fn collect_on_off(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let en = c.input.i16()?;
    match en {
        1 => {
            let _ = configured(c)?;
            c.command(SamplingStart {
                sampler: NMC_SAMPLER,
            });
            c.service.sys().read_bytes = 0;
        }
        // The manual's example stops first, before any configuration: nothing to stop then.
        0 if c.service.sys().collect.is_none() => {}
        0 => c.command(SamplingStop {
            sampler: NMC_SAMPLER,
        }),
        _ => return Err(Refusal::range("en", en, "{0, 1}")),
    }
    Ok(())
}

/// The status bits and the bytes recorded, from the snapshot.
fn status(c: &Call<'_>) -> (i16, u64) {
    let Some(collect) = c.service.sys().collect.clone() else {
        return (0, 0);
    };
    let Some(s) = c
        .snapshot
        .samplers
        .iter()
        .find(|s| s.sampler == NMC_SAMPLER)
    else {
        return (0, 0);
    };
    let mut sts = 0;
    if matches!(s.state, SamplerState::Armed | SamplerState::Collecting) {
        sts |= STS_ON;
    }
    if s.triggered_at.is_some() {
        sts |= STS_TRIGGERED;
    }
    if s.state == SamplerState::Done {
        sts |= STS_FULL;
    }
    (sts, u64::from(s.points) * collect.row_bytes())
}

fn get_collect_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (sts, bytes) = status(c);
    c.output
        .i16(sts)
        .i64(i64::try_from(bytes).unwrap_or(i64::MAX));
    Ok(())
}

/// The next `len` bytes of the data (≤ 1440, no more than recorded and not yet read): the
/// rows they span are read from the engine, and cut to the bytes once it answers.
fn get_collect_data(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let len = c.input.i16()?;
    let len = usize::try_from(len)
        .ok()
        .filter(|n| *n <= COLLECT_DATA_MAX)
        .ok_or_else(|| Refusal::range("len", len, &format!("[0, {COLLECT_DATA_MAX}] bytes")))?;
    let collect = configured(c)?;
    let (_, recorded) = status(c);
    let read = c.service.sys().read_bytes;
    let left = recorded.saturating_sub(read);
    if len as u64 > left {
        return Err(Refusal::range(
            "len",
            len,
            &format!("[0, {left}] (the bytes collected and not yet read)"),
        ));
    }
    if len == 0 {
        c.output.u16(0);
        return Ok(());
    }
    let row = collect.row_bytes();
    let first = read / row;
    let end = (read + len as u64).div_ceil(row);
    c.command(SamplingRead {
        sampler: NMC_SAMPLER,
        from: first as u32,
        count: Some((end - first) as u32),
    });
    let skip = (read - first * row) as usize;
    let snapshot = c.snapshot.clone();
    c.plan.then = Some(Box::new(
        move |service: &NmcService, result: Result<&[Reply], &EngineError>, out: &mut Writer| {
            // A refused read is the call's refusal already (service.rs).
            let Ok(replies) = result else { return Ok(()) };
            let Some(Reply::Samples { values, .. }) = replies.last() else {
                return Err(Refusal::new(
                    RTN_BAD_PAYLOAD,
                    "the engine returned no samples",
                ));
            };
            let n = collect.units.len().max(1);
            let bytes: Vec<u8> = values
                .iter()
                .enumerate()
                .flat_map(|(k, v)| {
                    let unit = collect
                        .units
                        .get(k % n)
                        .copied()
                        .unwrap_or(CollectUnit::Level);
                    convert(&snapshot, unit, *v).to_le_bytes()
                })
                .collect();
            let data = bytes.get(skip..skip + len).ok_or_else(|| {
                Refusal::new(
                    RTN_BAD_PAYLOAD,
                    "the engine returned fewer samples than recorded",
                )
            })?;
            out.u16(len as u16);
            for b in data {
                out.u8(*b);
            }
            service.sys().read_bytes += len as u64;
            Ok(())
        },
    ));
    Ok(())
}

/// Empties the data and the status: the sampler is set up again, stopped.
fn clear_collect_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let collect = c.service.sys().collect.clone();
    if let Some(collect) = collect {
        c.command(collect.config);
    }
    c.service.sys().read_bytes = 0;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn addresses_round_trip_and_foreign_ones_are_not_addresses() {
        let a = ADDRESS_TAG | (CMD_VEL as u64) << 16 | 3;
        assert_eq!(decode(a), Some((CMD_VEL, 3)));
        assert_eq!(decode(0), None);
        assert_eq!(decode(u64::MAX), None);
        assert_eq!(decode(0x1234), None);
    }
}
