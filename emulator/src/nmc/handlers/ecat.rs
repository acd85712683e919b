//! EtherCAT (digest 001 §2.1): the master's state on a GCE card (`device.kind = "ecat"`), and
//! the drive and SDO functions. mcemu's machines have no EtherCAT slaves: the slave counts are
//! 0, every axis is a pulse axis (EtherCAT axes would be numbered from 16) and no `devId`
//! names a slave, so those calls answer the code of what is missing (decisions.md).

use mcemu_nmc::errors::RTN_NOT_ON_THIS_CARD;
use mcemu_nmc::table::{self, Function};

use crate::nmc::config::DeviceKind;
use crate::nmc::service::{Call, Handler, Refusal};

pub const HANDLERS: &[(Function, Handler)] = &[
    (
        table::ECAT_LOAD_CONFIG_FROM_FILE,
        ecat_load_config_from_file,
    ),
    (table::ECAT_START, ecat_start),
    (table::ECAT_STOP, ecat_stop),
    (table::ECAT_GET_STS, ecat_get_sts),
    (table::ECAT_GET_RESOURCE, ecat_get_resource),
    (table::ECAT_START_HOME, not_a_drive),
    (table::ECAT_GET_HOME_STS, not_a_drive),
    (table::ECAT_STOP_HOME, not_a_drive),
    (table::ECAT_SDO_READ, ecat_sdo_read),
    (table::ECAT_SDO_WRITE, ecat_sdo_write),
    (table::ECAT_AXIS_GET_ERROR_CODE, not_a_drive),
    (table::ECAT_AXIS_GET_DI, not_a_drive),
];

/// The master exists on GCE cards only ("GCE\\ GCNxx0E-xA 系列", digest 001 §2.1).
fn bus_card(c: &mut Call<'_>) -> Result<(), Refusal> {
    c.device()?;
    if c.service.device.kind == DeviceKind::Ecat {
        Ok(())
    } else {
        Err(Refusal::new(
            RTN_NOT_ON_THIS_CARD,
            "this device is not an EtherCAT card (device.kind = \"ecat\")",
        ))
    }
}

/// The `.gml` file is the vendor tool's (format undocumented, digest 001 §1.5): its name is
/// kept, its content not read. masterIdx is reserved: 0.
fn ecat_load_config_from_file(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    let name = String::from_utf8_lossy(c.input.str()?).into_owned();
    let master = c.input.i16()?;
    if master != 0 {
        return Err(Refusal::range("masterIdx", master, "{0} (reserved)"));
    }
    c.service.stored().ecat_config = Some(name);
    Ok(())
}

fn ecat_start(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    c.service.stored().ecat_started = true;
    Ok(())
}

fn ecat_stop(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    c.service.stored().ecat_started = false;
    Ok(())
}

/// 0 = master started, 1 = not (TV33).
fn ecat_get_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    let started = c.service.stored().ecat_started;
    c.output.u16(u16::from(!started));
    Ok(())
}

/// Online slaves: total, drives, I/O — none in mcemu's machines.
fn ecat_get_resource(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    c.output.i16(0).i16(0).i16(0);
    Ok(())
}

/// Every axis mcemu serves over NMC is a pulse axis: EtherCAT drive functions are refused
/// (the arguments after the handle are not read).
fn not_a_drive(c: &mut Call<'_>) -> Result<(), Refusal> {
    let axis = c.axis()?;
    Err(Refusal::new(
        RTN_NOT_ON_THIS_CARD,
        format!("axis {axis} is a pulse axis, not an EtherCAT drive (those are numbered from 16)"),
    ))
}

/// No slave answers an SDO: `devId` names none (the master must run first).
fn no_slave(c: &mut Call<'_>, dev_id: i16) -> Result<(), Refusal> {
    if !c.service.stored().ecat_started {
        return Err(Refusal::new(
            mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidState),
            "the EtherCAT master is not started (NMC_EcatStart)",
        ));
    }
    Err(Refusal::new(
        mcemu_dialects::nmc::code_for_kind(axes::command::ErrorKind::InvalidSlave),
        format!("devId {dev_id}: the bus has no slaves"),
    ))
}

fn ecat_sdo_read(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    let dev_id = c.input.i16()?;
    let (_index, _sub, _len) = (c.input.u16()?, c.input.u8()?, c.input.u32()?);
    no_slave(c, dev_id)
}

fn ecat_sdo_write(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    let dev_id = c.input.i16()?;
    let (_index, _sub, _len) = (c.input.u16()?, c.input.u8()?, c.input.u32()?);
    let n = usize::from(c.input.u16()?);
    for _ in 0..n {
        c.input.u8()?;
    }
    no_slave(c, dev_id)
}
