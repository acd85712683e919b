//! EtherCAT (digest 001 §2.1): the master's state on a GCE card (`device.kind = "ecat"`), its
//! bus (`ecat_bus`: the machine's engine-mastered CiA 402 drives as axes 16, 17, … and SDO
//! slaves 0, 1, …, then `device.io_slaves` I/O slaves), drive homing and SDO access. Cards of
//! other kinds have no bus: their axes are pulse axes and the drive functions say so.

use axes::command::{EngineError, ErrorKind, ReadObject, Reply, WriteObject};
use axes::od::{OdError, Value};
use mcemu_dialects::nmc::{code_for_kind, ecat_home_status};
use mcemu_nmc::errors::RTN_NOT_ON_THIS_CARD;
use mcemu_nmc::table::{self, Function};

use super::ecat_drive::{bus_axis, decode_object, sdo_abort, stop_drive_homing, DriveHoming};
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
    (table::ECAT_START_HOME, ecat_start_home),
    (table::ECAT_GET_HOME_STS, ecat_get_home_sts),
    (table::ECAT_STOP_HOME, ecat_stop_home),
    (table::ECAT_SDO_READ, ecat_sdo_read),
    (table::ECAT_SDO_WRITE, ecat_sdo_write),
    (table::ECAT_AXIS_GET_ERROR_CODE, ecat_axis_get_error_code),
    (table::ECAT_AXIS_GET_DI, ecat_axis_get_di),
];

/// 0x60FD digital inputs (CiA 402; the manual's "驱动器的数字量输入", inferred in the digest).
const DIGITAL_INPUTS: u16 = 0x60FD;

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

/// Online slaves: total, drives, I/O (TV34). Nothing is online before `NMC_EcatStart`.
fn ecat_get_resource(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    let (drives, io) = if c.service.stored().ecat_started {
        let bus = c.service.bus();
        (bus.drives().len(), usize::from(bus.io_slaves()))
    } else {
        (0, 0)
    };
    let count = |n: usize| i16::try_from(n).unwrap_or(i16::MAX);
    c.output
        .i16(count(drives + io))
        .i16(count(drives))
        .i16(count(io));
    Ok(())
}

/// Drive-side CiA 402 homing (TV35): method per CiA 402 (1–35, 37), velSwitch and velZero in
/// pulse/ms (> 0), acc in pulse/ms² (> 0), prmEx reserved (not read for anything).
fn ecat_start_home(c: &mut Call<'_>) -> Result<(), Refusal> {
    let bus = bus_axis(c)?;
    let method = c.input.i32()?;
    let switch = c.input.i32()?;
    let zero = c.input.i32()?;
    let acc = c.input.i32()?;
    let _reserved = c.input.i32()?;
    DriveHoming::checked(method, switch.into(), zero.into(), acc.into(), 0)?.start(c, bus)
}

/// bit2..bit0 = statusword bits 13/12/10 in homing mode (digest 001 §3.14); "in progress"
/// (000) from the request until the drive has stepped.
fn ecat_get_home_sts(c: &mut Call<'_>) -> Result<(), Refusal> {
    let bus = bus_axis(c)?;
    let status = if c.service.bus().homing_pending(bus.k, c.snapshot.tick) {
        0b000
    } else {
        c.snapshot
            .drives
            .get(usize::from(bus.drive.slave))
            .map_or(0b001, |d| ecat_home_status(d.statusword, d.mode))
    };
    c.output.u8(status);
    Ok(())
}

fn ecat_stop_home(c: &mut Call<'_>) -> Result<(), Refusal> {
    let bus = bus_axis(c)?;
    stop_drive_homing(c, bus);
    Ok(())
}

/// 0x603F of the axis's drive (digest 001 §2.1, inferred there).
fn ecat_axis_get_error_code(c: &mut Call<'_>) -> Result<(), Refusal> {
    let bus = bus_axis(c)?;
    let code = c
        .snapshot
        .drives
        .get(usize::from(bus.drive.slave))
        .map_or(0, |d| d.error_code);
    c.output.u16(code);
    Ok(())
}

/// 0x60FD of the axis's drive: bit 0 negative limit, 1 positive limit, 2 home switch.
fn ecat_axis_get_di(c: &mut Call<'_>) -> Result<(), Refusal> {
    let bus = bus_axis(c)?;
    c.command(ReadObject {
        slave: bus.drive.slave,
        index: DIGITAL_INPUTS,
        subindex: 0,
    });
    c.plan.then = Some(Box::new(|_, result, out| {
        let value = object_value(result)?;
        out.i64(value.as_i64().unwrap_or(0));
        Ok(())
    }));
    Ok(())
}

/// The value a `read_object` batch answered.
fn object_value(result: Result<&[Reply], &EngineError>) -> Result<Value, Refusal> {
    match result {
        Ok([Reply::Object { value }]) => Ok(value.clone()),
        Ok(_) => Err(Refusal::new(
            code_for_kind(ErrorKind::Fault),
            "the engine answered a read_object without a value",
        )),
        Err(e) => Err(sdo_refusal(e)),
    }
}

/// A drive's refusal of an object access: its CiA 301 abort code in the text (a batch wraps
/// each command's refusal as an item).
fn sdo_refusal(e: &EngineError) -> Refusal {
    match e {
        EngineError::Object { error, .. } => sdo_abort(error.sdo_abort_code(), &error.to_string()),
        EngineError::Item { error, .. } => sdo_refusal(error),
        other => Refusal::engine(other),
    }
}

/// The slave `devId` names: Ok(drive's engine slave number). The master must run; an I/O slave
/// has no CoE dictionary (abort 0x06020000).
fn sdo_slave(c: &mut Call<'_>, dev_id: i16) -> Result<u16, Refusal> {
    if !c.service.stored().ecat_started {
        return Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidState),
            "the EtherCAT master is not started (NMC_EcatStart)",
        ));
    }
    let bus = c.service.bus();
    let drives = bus.drives().len();
    let slaves = drives + usize::from(bus.io_slaves());
    match usize::try_from(dev_id) {
        Ok(k) if k < drives => bus.drive(k).map(|d| d.slave).ok_or_else(|| {
            Refusal::new(
                code_for_kind(ErrorKind::InvalidSlave),
                format!("devId {dev_id}"),
            )
        }),
        Ok(k) if k < slaves => Err(sdo_abort(
            0x0602_0000,
            &format!("devId {dev_id} is an I/O slave: it has no CoE object dictionary"),
        )),
        _ => Err(Refusal::new(
            code_for_kind(ErrorKind::InvalidSlave),
            format!(
                "devId {dev_id} is outside [0, {}]: the bus has {slaves} slaves",
                slaves as i64 - 1
            ),
        )),
    }
}

/// SDO upload: the object's little-endian bytes, the first `len` of them (fewer if the object
/// is shorter: the rest of `val` is left as it was).
fn ecat_sdo_read(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    let dev_id = c.input.i16()?;
    let (index, subindex, len) = (c.input.u16()?, c.input.u8()?, c.input.u32()?);
    let slave = sdo_slave(c, dev_id)?;
    c.command(ReadObject {
        slave,
        index,
        subindex,
    });
    c.plan.then = Some(Box::new(move |_, result, out| {
        let bytes = object_value(result)?.to_le_bytes();
        let n = bytes.len().min(usize::try_from(len).unwrap_or(usize::MAX));
        out.u16(n as u16);
        for b in bytes.iter().take(n) {
            out.u8(*b);
        }
        out.u32(0);
        Ok(())
    }));
    Ok(())
}

/// SDO download: `len` bytes, exactly the object's size, little-endian.
fn ecat_sdo_write(c: &mut Call<'_>) -> Result<(), Refusal> {
    bus_card(c)?;
    let dev_id = c.input.i16()?;
    let (index, subindex, _len) = (c.input.u16()?, c.input.u8()?, c.input.u32()?);
    let n = usize::from(c.input.u16()?);
    let mut bytes = Vec::with_capacity(n);
    for _ in 0..n {
        bytes.push(c.input.u8()?);
    }
    let slave = sdo_slave(c, dev_id)?;
    let value = decode_object(index, subindex, &bytes)
        .map_err(|e: OdError| sdo_abort(e.sdo_abort_code(), &e.to_string()))?;
    c.command(WriteObject {
        slave,
        index,
        subindex,
        value,
    });
    c.plan.then = Some(Box::new(|_, result, out| {
        result.map_err(sdo_refusal)?;
        out.u32(0);
        Ok(())
    }));
    Ok(())
}
