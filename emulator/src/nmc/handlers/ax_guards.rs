//! The guards that act without a call (digest 001 §2.3, §2.20): the per-axis E-stop input,
//! the advanced E-stop input groups and the communication watchdog. They are the engine's
//! guards (`axes::guard`: input stops and the watchdog, judged on the tick); the handlers arm
//! them and keep what was written in `ax_state` to read it back. Every request moves the
//! watchdog's deadline (`AxState::heard`, TV71).

use axes::command::{GuardInput, InputStopClear, InputStopSet, OutputLevel, StopMode, WatchdogSet};
use mcemu_nmc::ax_structs::{EstopExParam, ESTOP_DI_EX_CH_NUM};
use mcemu_nmc::table::{self, Function};

use super::io_modules::group_start;
use super::sync_args::axis_number;
use crate::nmc::ax_state::{EstopDi, EstopEx, Watchdog};
use crate::nmc::io_state::LOCAL_BITS;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::MT_SET_ESTOP_DI, mt_set_estop_di),
    (table::MT_GET_ESTOP_DI, mt_get_estop_di),
    (table::SET_WATCH_DOG, set_watch_dog),
    (table::SET_ESTOP_DI_EX, set_estop_di_ex),
    (table::GET_ESTOP_DI_EX, get_estop_di_ex),
    (table::CLR_ESTOP_DI_EX, clr_estop_di_ex),
];

/// The engine input-stop slot of advanced group `g`, and of axis `axis`'s `MtSetEstopDI`.
fn ex_slot(g: usize) -> u16 {
    g as u16
}

fn axis_slot(axis: usize) -> Result<u16, Refusal> {
    u16::try_from(ESTOP_DI_EX_CH_NUM + axis)
        .ok()
        .filter(|s| *s < axes::command::MAX_INPUT_STOPS)
        .ok_or_else(|| {
            Refusal::range(
                "axis",
                axis,
                &format!(
                    "[0, {}] for an E-stop input (mcemu's engine)",
                    usize::from(axes::command::MAX_INPUT_STOPS) - ESTOP_DI_EX_CH_NUM - 1
                ),
            )
        })
}

fn level(name: &str, v: i64) -> Result<(), Refusal> {
    if (0..=1).contains(&v) {
        Ok(())
    } else {
        Err(Refusal::range(name, v, "{0 low, 1 high}"))
    }
}

/// General input `gpiIndex` at level `sense` E-stops the axis (latching BIT_AXIS_ESTP);
/// −1 cancels.
fn mt_set_estop_di(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let (gpi, sense) = (c.input.i16()?, c.input.i16()?);
    let inputs = c.snapshot.io.di.len();
    let slot = axis_slot(axis)?;
    if gpi == -1 {
        c.service.ax().estop_di.remove(&axis);
        c.command(InputStopClear { slot });
        return Ok(());
    }
    // A local input, or one of an enabled extension module (the I/O functions' rule).
    let bit = super::io::bit_index(c, gpi, inputs).map_err(|_| {
        Refusal::range(
            "gpiIndex",
            gpi,
            &format!(
                "[0, {}], an input of an enabled extension module, or −1 (none)",
                inputs.min(LOCAL_BITS).saturating_sub(1)
            ),
        )
    })?;
    level("sense", i64::from(sense))?;
    c.command(InputStopSet {
        slot,
        input: GuardInput::Digital {
            channel: bit as u16,
        },
        level: sense == 1,
        filter: 0,
        axes: vec![axis as u16],
    });
    c.service.ax().estop_di.insert(axis, EstopDi { gpi, sense });
    Ok(())
}

/// −1 and 0 when none is set.
fn mt_get_estop_di(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    let e = c.service.ax().estop_di.get(&axis).copied();
    let (gpi, sense) = e.map_or((-1, 0), |e| (e.gpi, e.sense));
    c.output.i16(gpi).i16(sense);
    Ok(())
}

/// timeout ms (≤ 0 off), stopMode 1 stop at once (the E-stop deceleration) / 0 stop with the
/// axes' own deceleration (mcemu has no buffer to let run out, decisions.md), then doValue to
/// DO group groupID. The countdown starts now; every request restarts it.
fn set_watch_dog(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let (timeout, stop_mode) = (c.input.i64()?, c.input.i16()?);
    let (group, do_value) = (c.input.i16()?, c.input.i64()?);
    if timeout <= 0 {
        c.service.ax().watchdog = None;
        c.command(WatchdogSet {
            deadline: None,
            mode: StopMode::Smooth,
            outputs: Vec::new(),
        });
        return Ok(());
    }
    if !(0..=1).contains(&stop_mode) {
        return Err(Refusal::range(
            "stopMode",
            stop_mode,
            "{0 after the buffer, 1 at once}",
        ));
    }
    let do_start = group_start(c, group, c.snapshot.io.do_.len())?;
    // The countdown in whole servo periods: it fires on the first tick `timeout` ms after the
    // last request's.
    let period_ms = (c.snapshot.period * 1e3).max(1e-6);
    let ticks = (timeout as f64 / period_ms - 1e-9).ceil().max(1.0) as u64;
    let count = c.snapshot.io.do_.len().saturating_sub(do_start).min(32);
    let outputs = (0..count)
        .map(|i| OutputLevel {
            channel: (do_start + i) as u16,
            value: do_value & (1 << i) != 0,
        })
        .collect();
    c.command(WatchdogSet {
        deadline: Some(c.snapshot.tick + ticks),
        mode: if stop_mode == 1 {
            StopMode::Abrupt
        } else {
            StopMode::Smooth
        },
        outputs,
    });
    let mut ax = c.service.ax();
    ax.watchdog = Some(Watchdog { ticks });
    ax.last_kick = c.snapshot.tick;
    Ok(())
}

fn ex_group(group: i16) -> Result<usize, Refusal> {
    usize::try_from(group)
        .ok()
        .filter(|g| *g < ESTOP_DI_EX_CH_NUM)
        .ok_or_else(|| {
            Refusal::range(
                "group",
                group,
                &format!("[0, {}] (ESTOP_DI_EX_CH_NUM − 1)", ESTOP_DI_EX_CH_NUM - 1),
            )
        })
}

/// The engine axes of an advanced group's `axMask`: bit n = local NMC axis n (the `short`
/// reaches no bus drive), at least one bit, each naming an axis.
fn ex_axes(c: &Call<'_>, mask: i16) -> Result<Vec<usize>, Refusal> {
    let bus = c.service.bus();
    let count = c.snapshot.axes.len();
    let local = bus.local_count(count).min(16);
    let bits = mask as u16;
    let axes: Option<Vec<usize>> = (0..16u8)
        .filter(|b| bits & (1 << b) != 0)
        .map(|b| {
            (usize::from(b) < local)
                .then(|| bus.engine_axis(b, count))
                .flatten()
        })
        .collect();
    match axes {
        Some(axes) if !axes.is_empty() => Ok(axes),
        _ => Err(Refusal::range(
            "axMask",
            format!("{mask:#x}"),
            &format!(
                "bits 0 … {} (the local axes; a short reaches no bus drive), at least one",
                local.saturating_sub(1)
            ),
        )),
    }
}

/// An advanced E-stop input group: the axes of axMask stop (BIT_AXIS_ESTP) once the input has
/// been at diSense for `filter` ms. diType 0 a general input; 1–4 the negative limit, positive
/// limit, home or index input of axis diIndex (an NMC number: a bus drive from 16), whose
/// level is its active state.
fn set_estop_di_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let p = EstopExParam::read(&mut c.input)?;
    let g = ex_group(c.input.i16()?)?;
    // axMask is a `short`: bit n = local NMC axis n (the bus drives, from 16, are beyond it).
    let stopped = ex_axes(c, p.ax_mask)?;
    let input = match p.di_type {
        0 => {
            // General inputs: local, or of an enabled extension module.
            let inputs = c.snapshot.io.di.len();
            let bit = super::io::bit_index(c, p.di_index, inputs).map_err(|_| {
                Refusal::range(
                    "diIndex",
                    p.di_index,
                    &format!(
                        "[0, {}] or an input of an enabled extension module",
                        inputs.min(LOCAL_BITS).saturating_sub(1)
                    ),
                )
            })?;
            GuardInput::Digital {
                channel: bit as u16,
            }
        }
        1..=4 => {
            // diIndex names an axis as NMC numbers it: local, or a bus drive from 16.
            let axis = axis_number(c, "diIndex", i64::from(p.di_index))? as u16;
            match p.di_type {
                1 => GuardInput::NegativeLimit { axis },
                2 => GuardInput::PositiveLimit { axis },
                3 => GuardInput::Home { axis },
                _ => GuardInput::Index { axis },
            }
        }
        t => {
            return Err(Refusal::range(
                "diType",
                t,
                "{0 general, 1 negative limit, 2 positive limit, 3 home, 4 index}",
            ))
        }
    };
    if !(0..=255).contains(&p.filter) {
        return Err(Refusal::range("filter", p.filter, "[0, 255]"));
    }
    level("diSense", p.di_sense)?;
    // filter: how long the level must hold, in ms (digest 001 §3.6 gives no unit).
    let period_ms = (c.snapshot.period * 1e3).max(1e-6);
    let filter = (f64::from(p.filter) / period_ms).round() as u32;
    c.command(InputStopSet {
        slot: ex_slot(g),
        input,
        level: p.di_sense == 1,
        filter,
        axes: stopped.into_iter().map(|a| a as u16).collect(),
    });
    if let Some(slot) = c.service.ax().estop_ex.get_mut(g) {
        *slot = Some(EstopEx { param: p });
    }
    Ok(())
}

/// All zeros for a group never set (or cleared).
fn get_estop_di_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let g = ex_group(c.input.i16()?)?;
    let p = c
        .service
        .ax()
        .estop_ex
        .get(g)
        .copied()
        .flatten()
        .map_or_else(EstopExParam::default, |e| e.param);
    p.write(c.output);
    Ok(())
}

/// Disarms the group; the axes' latched BIT_AXIS_ESTP stays until `NMC_MtClrError`.
fn clr_estop_di_ex(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let g = ex_group(c.input.i16()?)?;
    if let Some(slot) = c.service.ax().estop_ex.get_mut(g) {
        *slot = None;
    }
    c.command(InputStopClear { slot: ex_slot(g) });
    Ok(())
}
