//! The EtherCAT slaves as HMPL addresses them (`slv_slot_id`, digest 004 §2.8): slave n < the
//! number of drives is CiA 402 drive n, whose digital inputs are 0x60FD and outputs 0x60FE:1
//! (pin N = bit N−1, 32 each); the slave after the drives, when the machine has analog
//! channels, is an analog I/O module holding them (chapter 10). No slave has slots: an id with
//! an `HMPL_SLOT_n` part addresses nothing. Chapter 9.3/9.5 (slave GPIO; TV 12–13) and
//! chapter 21 (slave information) are here.

use axes::Command;
use mcemu_dialects::himc::constants::SLOT_SHIFT;
use mcemu_dialects::himc::system::HMPL_ARG_OUT_OF_RANGE;
use serde_json::json;

use crate::reply::Outcome;
use crate::table::{
    row, unary, Addresses::Controller, Args, Ctx, Function, ObjectReply, Plan, Ret, Then, Ty,
};

/// 0x60FD, the drive's digital inputs (CiA 402).
pub(crate) const DIGITAL_INPUTS: u16 = 0x60FD;
/// 0x60FE:1, the drive's physical outputs.
pub(crate) const DIGITAL_OUTPUTS: u16 = 0x60FE;
/// Pins of a drive's digital inputs and outputs (the objects' 32 bits).
const DRIVE_PINS: u32 = 32;

/// A slave an id names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Slave {
    Drive(u16),
    /// The analog I/O module after the drives.
    AnalogModule,
}

/// How many slaves the bus has: the drives, and the analog module if the machine has analog
/// channels.
pub(crate) fn slave_count(cx: &Ctx<'_>) -> usize {
    let io = &cx.snapshot.io;
    cx.snapshot.drives.len() + usize::from(!io.ai.is_empty() || !io.ao.is_empty())
}

/// The slave `slv_slot_id` names; a slot part or an id beyond the bus is
/// `eERR_HMPL_ARG_OUT_OF_RANGE`.
pub(crate) fn slave(cx: &Ctx<'_>, slv_slot_id: i64) -> Result<Slave, u32> {
    if slv_slot_id >> SLOT_SHIFT != 0 {
        return Err(HMPL_ARG_OUT_OF_RANGE);
    }
    let id = usize::try_from(slv_slot_id).map_err(|_| HMPL_ARG_OUT_OF_RANGE)?;
    let drives = cx.snapshot.drives.len();
    if id < drives {
        u16::try_from(id)
            .map(Slave::Drive)
            .map_err(|_| HMPL_ARG_OUT_OF_RANGE)
    } else if id < slave_count(cx) {
        Ok(Slave::AnalogModule)
    } else {
        Err(HMPL_ARG_OUT_OF_RANGE)
    }
}

/// A failed GPIO call: −1, the code latched (as the controller's GPIO, chapter 9).
fn minus_one(cx: &mut Ctx<'_>, code: u32) -> Plan {
    cx.registers.latch(code);
    Plan::Done(Outcome::Int(-1))
}

/// Drive `args[0]` and its pin `args[1]` (1 … 32) as a bit.
fn drive_pin(cx: &Ctx<'_>, args: &Args) -> Result<(u16, u32), u32> {
    match slave(cx, args.int(0))? {
        Slave::Drive(d) => u32::try_from(args.int(1))
            .ok()
            .filter(|p| (1..=DRIVE_PINS).contains(p))
            .map(|p| (d, p - 1))
            .ok_or(HMPL_ARG_OUT_OF_RANGE),
        Slave::AnalogModule => Err(HMPL_ARG_OUT_OF_RANGE),
    }
}

fn drive(cx: &Ctx<'_>, args: &Args) -> Result<u16, u32> {
    match slave(cx, args.int(0))? {
        Slave::Drive(d) => Ok(d),
        Slave::AnalogModule => Err(HMPL_ARG_OUT_OF_RANGE),
    }
}

/// Write the outputs image of `drive` to its 0x60FE:1.
fn write_outputs(drive: u16, image: u32) -> Plan {
    let command: Result<Command, _> = serde_json::from_value(json!({
        "type": "write_object", "slave": drive, "index": DIGITAL_OUTPUTS, "subindex": 1,
        "value": {"u32": image},
    }));
    match command {
        Ok(c) => Plan::Engine(vec![c], Then::Succeed),
        Err(_) => Plan::Fail(mcemu_dialects::himc::system::HMPL_INTERNAL_ERROR),
    }
}

/// §9.3.1–9.3.2: the controller keeps each drive's output image (it is the PDO's master).
fn set_output(cx: &mut Ctx<'_>, args: &Args, value: fn(bool, i64) -> bool) -> Plan {
    let (drive, bit) = match drive_pin(cx, args) {
        Ok(x) => x,
        Err(c) => return minus_one(cx, c),
    };
    let image = cx.registers.slave_outputs.get(&drive).copied().unwrap_or(0);
    let on = value(image >> bit & 1 == 1, args.int(2));
    let image = if on {
        image | 1 << bit
    } else {
        image & !(1 << bit)
    };
    cx.registers.slave_outputs.insert(drive, image);
    write_outputs(drive, image)
}

/// Read `index:subindex` of `drive` and reply it `how`.
fn read(drive: u16, index: u16, subindex: u8, how: ObjectReply) -> Plan {
    let command: Result<Command, _> = serde_json::from_value(
        json!({"type": "read_object", "slave": drive, "index": index, "subindex": subindex}),
    );
    match command {
        Ok(c) => Plan::Engine(vec![c], Then::Object(how)),
        Err(_) => Plan::Fail(mcemu_dialects::himc::system::HMPL_INTERNAL_ERROR),
    }
}

fn get_pin(cx: &mut Ctx<'_>, args: &Args, inputs: bool) -> Plan {
    match drive_pin(cx, args) {
        Ok((d, bit)) if inputs => read(d, DIGITAL_INPUTS, 0, ObjectReply::Bit(bit)),
        Ok((d, bit)) => read(d, DIGITAL_OUTPUTS, 1, ObjectReply::Bit(bit)),
        Err(c) => minus_one(cx, c),
    }
}

/// §9.5.3–9.5.6: the mask of pins from `start` (1-based; 1 for the plain ones) on.
fn get_all(cx: &mut Ctx<'_>, args: &Args, inputs: bool, start: i64) -> Plan {
    let d = match drive(cx, args) {
        Ok(d) => d,
        Err(c) => return minus_one(cx, c),
    };
    let Some(shift) = u32::try_from(start)
        .ok()
        .filter(|s| (1..=DRIVE_PINS).contains(s))
        .map(|s| s - 1)
    else {
        return minus_one(cx, HMPL_ARG_OUT_OF_RANGE);
    };
    if inputs {
        read(d, DIGITAL_INPUTS, 0, ObjectReply::BitsFrom(shift))
    } else {
        read(d, DIGITAL_OUTPUTS, 1, ObjectReply::BitsFrom(shift))
    }
}

/// §21.1 channel types.
const CH_GPI: i64 = 1;
const CH_GPO: i64 = 2;
const CH_AI: i64 = 3;
const CH_AO: i64 = 4;

const SS: &[Ty] = &[Ty::Int, Ty::Int];

pub static ROWS: &[Function] = &[
    row(
        "SetSlvGPO",
        "9.3.1",
        &[Ty::Int, Ty::Int, Ty::Int],
        Ret::Status,
        Controller,
        |cx, a| set_output(cx, a, |_, on| on != 0),
    ),
    row(
        "ToggleSlvGPO",
        "9.3.2",
        SS,
        Ret::Status,
        Controller,
        |cx, a| set_output(cx, a, |now, _| !now),
    ),
    // §9.3.3, unmarked (digest 004 §1.6), accepted unless `strict`: pin N = bit N−1 of the mask.
    row(
        "SetSlvAllGPO",
        "9.3.3",
        SS,
        Ret::Status,
        Controller,
        |cx, a| match drive(cx, a) {
            Ok(d) => {
                let image = a.int(1) as u32;
                cx.registers.slave_outputs.insert(d, image);
                write_outputs(d, image)
            }
            Err(c) => minus_one(cx, c),
        },
    ),
    row("GetSlvGPI", "9.5.1", SS, Ret::Int, Controller, |cx, a| {
        get_pin(cx, a, true)
    }),
    row("GetSlvGPO", "9.5.2", SS, Ret::Int, Controller, |cx, a| {
        get_pin(cx, a, false)
    }),
    unary("GetSlvAllGPI", "9.5.3", Ret::Int, Controller, |cx, a| {
        get_all(cx, a, true, 1)
    }),
    unary("GetSlvAllGPO", "9.5.4", Ret::Int, Controller, |cx, a| {
        get_all(cx, a, false, 1)
    }),
    // TV 12: GPI 8 and 11 from start 8 → 9.
    row(
        "GetSlvAllGPIByStartIdx",
        "9.5.5",
        SS,
        Ret::Int,
        Controller,
        |cx, a| {
            let start = a.int(1);
            get_all(cx, a, true, start)
        },
    ),
    // TV 13: GPO 9 and 10 from start 8 → 6.
    row(
        "GetSlvAllGPOByStartIdx",
        "9.5.6",
        SS,
        Ret::Int,
        Controller,
        |cx, a| {
            let start = a.int(1);
            get_all(cx, a, false, start)
        },
    ),
    // §21.1: 1 GPI, 2 GPO, 3 AI, 4 AO.
    row("GetSlvChNum", "21.1", SS, Ret::Int, Controller, |cx, a| {
        let kind = a.int(1);
        let io = &cx.snapshot.io;
        let n = match (slave(cx, a.int(0)), kind) {
            (Err(c), _) => return Plan::Fail(c),
            (Ok(Slave::Drive(_)), CH_GPI | CH_GPO) => DRIVE_PINS as usize,
            (Ok(Slave::AnalogModule), CH_AI) => io.ai.len(),
            (Ok(Slave::AnalogModule), CH_AO) => io.ao.len(),
            (Ok(_), CH_GPI..=CH_AO) => 0,
            (Ok(_), _) => return Plan::Fail(HMPL_ARG_OUT_OF_RANGE),
        };
        Plan::Done(Outcome::Int(i32::try_from(n).unwrap_or(i32::MAX)))
    }),
    // §21.2: no slave has slots.
    unary(
        "GetSlvSlotNum",
        "21.2",
        Ret::Int,
        Controller,
        |cx, a| match slave(cx, a.int(0)) {
            Ok(_) => Plan::Done(Outcome::Int(0)),
            Err(c) => Plan::Fail(c),
        },
    ),
];
