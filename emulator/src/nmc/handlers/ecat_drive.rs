//! What the EtherCAT functions and `NMC_MtHome` share about a bus axis's CiA 402 drive
//! (digest 001 §2.1, §3.14, §4.5): which drive an axis handle names, its homing run by the
//! drive in homing mode through its dictionary, and SDO aborts.
//!
//! Drive homing writes, in one batch (all or none): 0x6098 method, 0x6099:01/02 speeds, 0x609A
//! acceleration, 0x607C offset, 0x6060 = 6, then controlword 0x000F and 0x001F (the rising edge
//! of bit 4 starts it, as digest 001 §4.5 infers). The drive stays in homing mode afterwards, so
//! its statusword keeps reporting the outcome (`NMC_EcatGetHomeSts`); the card's own motion
//! commands move the axis whatever the drive's mode (the engine masters the drive,
//! docs/decisions.md). Stopping writes 0x000F: bit 4's falling edge interrupts the homing.

use std::sync::OnceLock;

use axes::cia402::{object_table, DriveConfig, State};
use axes::command::{ErrorKind, WriteObject};
use axes::od::{ObjectDictionary, OdError, Value};
use axes::AxisFlags;
use mcemu_dialects::nmc::{acceleration_to_engine, code_for_kind, velocity_to_engine};
use mcemu_nmc::errors::RTN_NOT_ON_THIS_CARD;

use crate::nmc::ecat_bus::BusDrive;
use crate::nmc::service::{Call, Refusal};

const CONTROLWORD: u16 = 0x6040;
const MODES_OF_OPERATION: u16 = 0x6060;
const HOME_OFFSET: u16 = 0x607C;
const HOMING_METHOD: u16 = 0x6098;
const HOMING_SPEEDS: u16 = 0x6099;
const HOMING_ACCELERATION: u16 = 0x609A;
const HOMING_MODE: i8 = 6;
/// Enable operation, and the same with bit 4 (homing operation start).
const ENABLE_OPERATION: u16 = 0x000F;
const HOMING_START: u16 = 0x001F;

/// An axis handle that names a bus drive: the engine axis, its place k on the bus (axis
/// 16 + k), the drive.
#[derive(Clone, Copy, Debug)]
pub struct BusAxis {
    pub axis: usize,
    pub k: usize,
    pub drive: BusDrive,
}

/// The axis handle that starts the request, which must name a bus drive.
pub fn bus_axis(c: &mut Call<'_>) -> Result<BusAxis, Refusal> {
    let axis = c.axis()?;
    bus_axis_of(c, axis).ok_or_else(|| {
        Refusal::new(
            RTN_NOT_ON_THIS_CARD,
            format!(
                "axis {axis} is a pulse axis, not an EtherCAT drive (those are numbered from 16 \
                 on an \"ecat\" card)"
            ),
        )
    })
}

/// Engine axis `axis` as a bus axis, if a bus drive moves it.
pub fn bus_axis_of(c: &Call<'_>, axis: usize) -> Option<BusAxis> {
    let (k, drive) = c.service.bus().drive_of_axis(axis)?;
    Some(BusAxis { axis, k, drive })
}

/// A refusal carrying CiA 301 abort `code` (`mcemu_nmc::sdo`; `RTN_OBJECT`).
pub fn sdo_abort(code: u32, detail: &str) -> Refusal {
    Refusal::new(
        code_for_kind(ErrorKind::Object),
        mcemu_nmc::sdo::abort_text(code, detail),
    )
}

/// The drives' object dictionary as built (mcemu's drives share one object table), for
/// decoding SDO download data into each object's type.
fn dictionary() -> Option<&'static ObjectDictionary> {
    static OD: OnceLock<Option<ObjectDictionary>> = OnceLock::new();
    OD.get_or_init(|| ObjectDictionary::from_defs(object_table(&DriveConfig::default())).ok())
        .as_ref()
}

/// SDO download data as a value of the object's type: the dictionary's own checks (object,
/// sub-index, access, length).
pub fn decode_object(index: u16, subindex: u8, bytes: &[u8]) -> Result<Value, OdError> {
    dictionary()
        .ok_or(OdError::NoObject { index })?
        .decode(index, subindex, bytes)
}

/// A homing for a drive to run, in the NMC's units: method (CiA 402), pulse/ms, pulse/ms²,
/// pulses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriveHoming {
    pub method: i8,
    pub switch_velocity: f64,
    pub zero_velocity: f64,
    pub acceleration: f64,
    pub offset: i64,
}

impl DriveHoming {
    /// The drive's methods (1–35, 37: what the engine's homing runs), speeds and acceleration
    /// above 0, each refused with the argument's name (`NMC_EcatStartHome`'s names).
    pub fn checked(
        method: i32,
        switch_velocity: f64,
        zero_velocity: f64,
        acceleration: f64,
        offset: i64,
    ) -> Result<DriveHoming, Refusal> {
        let method = i8::try_from(method)
            .ok()
            .filter(|m| (1..=35).contains(m) || *m == 37)
            .ok_or_else(|| Refusal::range("method", method, "CiA 402 methods 1 … 35, 37"))?;
        for (name, v) in [
            ("velSwitch", switch_velocity),
            ("velZero", zero_velocity),
            ("acc", acceleration),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Refusal::range(name, v, "(0, ∞)"));
            }
        }
        Ok(DriveHoming {
            method,
            switch_velocity,
            zero_velocity,
            acceleration,
            offset,
        })
    }

    /// Start it on `bus`'s drive (its servo must be on). `NMC_EcatGetHomeSts` reads "in
    /// progress" until the drive has stepped with it.
    pub fn start(self, c: &mut Call<'_>, bus: BusAxis) -> Result<(), Refusal> {
        let enabled = c
            .status(bus.axis)
            .is_some_and(|s| s.flags.contains(AxisFlags::ENABLED));
        if !enabled {
            return Err(Refusal::new(
                code_for_kind(ErrorKind::AxisDisabled),
                format!(
                    "axis {}: the drive is not in Operation enabled (NMC_MtSetSvOn first)",
                    16 + bus.k
                ),
            ));
        }
        let scale = c.scale(bus.axis);
        let ipu = bus.drive.increments_per_unit;
        let increments = |units: f64| (units * ipu).round();
        let per_s =
            |v| increments(velocity_to_engine(scale, v)).clamp(0.0, f64::from(u32::MAX)) as u32;
        let acc = increments(acceleration_to_engine(scale, self.acceleration))
            .clamp(0.0, f64::from(u32::MAX)) as u32;
        let offset = increments(scale.to_engine(self.offset as f64))
            .clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32;
        let slave = bus.drive.slave;
        for (index, subindex, value) in [
            (HOMING_METHOD, 0, Value::I8(self.method)),
            (HOMING_SPEEDS, 1, Value::U32(per_s(self.switch_velocity))),
            (HOMING_SPEEDS, 2, Value::U32(per_s(self.zero_velocity))),
            (HOMING_ACCELERATION, 0, Value::U32(acc)),
            (HOME_OFFSET, 0, Value::I32(offset)),
            (MODES_OF_OPERATION, 0, Value::I8(HOMING_MODE)),
            (CONTROLWORD, 0, Value::U16(ENABLE_OPERATION)),
            (CONTROLWORD, 0, Value::U16(HOMING_START)),
        ] {
            c.command(WriteObject {
                slave,
                index,
                subindex,
                value,
            });
        }
        let k = bus.k;
        c.plan.then = Some(Box::new(move |service, result, _| {
            if result.is_ok() {
                // The snapshot that includes the writes: the drive acts in the next tick.
                let tick = service.engine.snapshot().tick;
                service.bus().homing_requested(k, Some(tick));
            }
            Ok(())
        }));
        Ok(())
    }
}

/// Interrupt `bus`'s drive homing: bit 4 falls. Only a drive in Operation enabled is written
/// (a controlword written to a drive the engine is powering up or down would take it over).
/// A start the drive may not have stepped with yet also leaves homing mode (0x6060 = 0): the
/// drive would otherwise see bit 4's rise and fall in one step as a start.
pub fn stop_drive_homing(c: &mut Call<'_>, bus: BusAxis) {
    let pending = c.service.bus().homing_pending(bus.k, c.snapshot.tick);
    c.service.bus().homing_requested(bus.k, None);
    let operating = c
        .snapshot
        .drives
        .get(usize::from(bus.drive.slave))
        .is_some_and(|d| State::from_statusword(d.statusword) == Some(State::OperationEnabled));
    if operating {
        c.command(WriteObject {
            slave: bus.drive.slave,
            index: CONTROLWORD,
            subindex: 0,
            value: Value::U16(ENABLE_OPERATION),
        });
        if pending {
            c.command(WriteObject {
                slave: bus.drive.slave,
                index: MODES_OF_OPERATION,
                subindex: 0,
                value: Value::I8(0),
            });
        }
    }
}
