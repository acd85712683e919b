//! Opening the device and the device-wide queries (digest 001 §1.2, §2.2, §2.20).

use axes::command::{ResetAll, StopAll, StopMode};
use mcemu_nmc::errors::{RTN_NOT_ON_THIS_CARD, RTN_NO_DEVICE};
use mcemu_nmc::handle::Handle;
use mcemu_nmc::structs::{chars, CardInfo};
use mcemu_nmc::table::{self, Function};

use crate::nmc::config::DeviceKind;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (table::DEV_OPEN, dev_open),
    (table::DEV_OPEN_BY_ID, dev_open_by_id),
    (table::DEV_OPEN_BY_IP, dev_open_by_ip),
    (table::DEV_RESET, dev_reset),
    (table::GET_CARD_INFO, get_card_info),
    (table::GET_CLOCK, get_clock),
];

/// The device handle (the library puts its own slot in).
fn opened(c: &mut Call<'_>) {
    c.output.u16(Handle::device(0).encode());
}

fn dev_open(c: &mut Call<'_>) -> Result<(), Refusal> {
    let n = c.input.i16()?;
    let index = c.service.device.index;
    if n != index {
        return Err(Refusal::new(
            RTN_NO_DEVICE,
            format!("devNo {n}: this device is number {index}"),
        ));
    }
    opened(c);
    Ok(())
}

fn dev_open_by_id(c: &mut Call<'_>) -> Result<(), Refusal> {
    let id = c.input.str()?;
    let own = &c.service.device.id;
    if id != own.as_bytes() {
        return Err(Refusal::new(
            RTN_NO_DEVICE,
            format!(
                "idStr {:?}: this device is {own:?}",
                String::from_utf8_lossy(id)
            ),
        ));
    }
    opened(c);
    Ok(())
}

/// Refused on PCIe and EtherCAT cards (digest 001 §2.2, TV03).
fn dev_open_by_ip(c: &mut Call<'_>) -> Result<(), Refusal> {
    let ip = [c.input.u8()?, c.input.u8()?, c.input.u8()?, c.input.u8()?];
    let d = &c.service.device;
    if d.kind != DeviceKind::Network {
        return Err(Refusal::new(
            RTN_NOT_ON_THIS_CARD,
            format!("this device is a {:?} card: open it by index or ID", d.kind),
        ));
    }
    if ip != d.ip.octets() {
        return Err(Refusal::new(
            RTN_NO_DEVICE,
            format!(
                "pIPv4Array {}.{}.{}.{}: this device is {}",
                ip[0], ip[1], ip[2], ip[3], d.ip
            ),
        ));
    }
    opened(c);
    Ok(())
}

/// Stops every axis abruptly, clears what can be cleared, and returns every NMC setting to
/// its configured value (the controller's reset reloads its saved configuration).
fn dev_reset(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    c.command(StopAll {
        mode: StopMode::Abrupt,
        deceleration: None,
    });
    c.command(ResetAll {});
    c.service.reset_settings();
    // "reset controller (reloads saved motion config)" (digest 001 §2.2).
    let saved = crate::nmc::saved_config::restore(c.service);
    c.plan.commands.extend(saved);
    Ok(())
}

fn get_card_info(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let d = &c.service.device;
    let axes = i16::try_from(c.snapshot.axes.len()).unwrap_or(i16::MAX);
    let [di, do_, ad, da] = c.service.io_counts;
    let info = CardInfo {
        str_ver: chars(concat!("mcemu ", env!("CARGO_PKG_VERSION"))),
        str_oem_ver: chars("0"),
        time: [2026, 1, 1, 0, 0, 0],
        axis_num: axes,
        enc_num: axes,
        di_num: di,
        do_num: do_,
        da_num: da,
        ad_num: ad,
        shio_num: 0,
        ipv4: d.ip.octets(),
        id_str: chars(&d.id),
        uid: super::identity::device_uid(d),
    };
    info.write(c.output);
    Ok(())
}

/// `pClock` in 125 µs ticks of engine time, `pLoop` servo cycles (digest 001 §1.4, TV65).
fn get_clock(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    let ticks_125us = (c.snapshot.time() / 125e-6).round();
    c.output
        .u64(ticks_125us.clamp(0.0, u64::MAX as f64) as u64)
        .u64(c.snapshot.tick);
    Ok(())
}
