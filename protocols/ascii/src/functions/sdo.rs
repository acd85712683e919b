//! Chapter 17.2, SDO and PDO access (digest 004 §2.16; TV 70) to the CiA 402 drives' object
//! dictionaries through the engine's `read_object` / `write_object`. HMPL passes values as
//! `int64` with a byte length; the object's data type comes from the drive's object table, so
//! the value's low `obj_length` bytes are the object's little-endian encoding. A PDO function
//! takes only PDO-mappable objects. `ForceWritePDO` holds a value only where nothing else
//! writes it: the objects the motion kernel writes every cycle refuse it (decisions.md).

use std::sync::OnceLock;

use axes::cia402::{object_table, DriveConfig};
use axes::od::{EntryDef, Value};
use axes::Command;
use mcemu_dialects::himc::system::{HMPL_ARG_OUT_OF_RANGE, HMPL_NOT_SUPPORTED};
use serde_json::json;

use super::slave::{slave, Slave, DIGITAL_OUTPUTS};
use crate::reply::Outcome;
use crate::table::{
    row, Addresses::Controller, Args, Ctx, Function, ObjectReply, Plan, Ret, Then, Ty,
};

/// Objects the HIMC's motion kernel writes every cycle (controlword, modes, the setpoints).
const KERNEL_WRITTEN: [u16; 5] = [0x6040, 0x6060, 0x607A, 0x60FF, 0x6071];

fn table() -> &'static [EntryDef] {
    static TABLE: OnceLock<Vec<EntryDef>> = OnceLock::new();
    TABLE.get_or_init(|| object_table(&DriveConfig::default()))
}

/// The object `args[1]:args[2]` of drive `args[0]`, if the drive and the object exist (PDO:
/// mappable).
fn object(cx: &Ctx<'_>, args: &Args, pdo: bool) -> Result<(u16, u16, u8, &'static EntryDef), u32> {
    let Slave::Drive(drive) = slave(cx, args.int(0))? else {
        return Err(HMPL_ARG_OUT_OF_RANGE);
    };
    let index = u16::try_from(args.int(1)).map_err(|_| HMPL_ARG_OUT_OF_RANGE)?;
    let subindex = u8::try_from(args.int(2)).map_err(|_| HMPL_ARG_OUT_OF_RANGE)?;
    table()
        .iter()
        .find(|e| e.index == index && e.subindex == subindex && (!pdo || e.pdo_mappable))
        .map(|e| (drive, index, subindex, e))
        .ok_or(HMPL_ARG_OUT_OF_RANGE)
}

fn fail(cx: &mut Ctx<'_>, code: u32, ret: Ret) -> Plan {
    cx.registers.latch(code);
    Plan::Done(match ret {
        Ret::Int64 => Outcome::Int64(-1),
        _ => Outcome::Int(-1),
    })
}

fn read(cx: &mut Ctx<'_>, args: &Args, pdo: bool) -> Plan {
    let (drive, index, subindex, entry) = match object(cx, args, pdo) {
        Ok(o) => o,
        Err(c) => return fail(cx, c, Ret::Int64),
    };
    // ReadSDO's obj_length must be the object's size.
    if !pdo && entry.data_type.size() != usize::try_from(args.int(3)).ok() {
        return fail(cx, HMPL_ARG_OUT_OF_RANGE, Ret::Int64);
    }
    let command: Result<Command, _> = serde_json::from_value(
        json!({"type": "read_object", "slave": drive, "index": index, "subindex": subindex}),
    );
    match command {
        Ok(c) => Plan::Engine(vec![c], Then::Object(ObjectReply::Int64)),
        Err(_) => fail(cx, HMPL_ARG_OUT_OF_RANGE, Ret::Int64),
    }
}

/// Write `value` (its low bytes in the object's type); `length` is SDO's obj_length.
fn write(cx: &mut Ctx<'_>, args: &Args, pdo: bool, value: i64, length: Option<i64>) -> Plan {
    let (drive, index, subindex, entry) = match object(cx, args, pdo) {
        Ok(o) => o,
        Err(c) => return fail(cx, c, Ret::Status),
    };
    let Some(size) = entry.data_type.size() else {
        return fail(cx, HMPL_ARG_OUT_OF_RANGE, Ret::Status);
    };
    if length.is_some_and(|l| usize::try_from(l).ok() != Some(size)) {
        return fail(cx, HMPL_ARG_OUT_OF_RANGE, Ret::Status);
    }
    let bytes = value.to_le_bytes();
    let Some(value) = bytes
        .get(..size)
        .and_then(|b| Value::from_le_bytes(entry.data_type, b).ok())
    else {
        return fail(cx, HMPL_ARG_OUT_OF_RANGE, Ret::Status);
    };
    if let (DIGITAL_OUTPUTS, 1, Some(image)) = (index, subindex, value.as_i64()) {
        cx.registers
            .slave_outputs
            .insert(drive, u32::try_from(image).unwrap_or(0));
    }
    let command: Result<Command, _> = serde_json::from_value(json!({
        "type": "write_object", "slave": drive, "index": index, "subindex": subindex,
        "value": value,
    }));
    match command {
        Ok(c) => Plan::Engine(vec![c], Then::Succeed),
        Err(_) => fail(cx, HMPL_ARG_OUT_OF_RANGE, Ret::Status),
    }
}

const SDO_WRITE: &[Ty] = &[Ty::Int, Ty::Int, Ty::Int, Ty::Int, Ty::Int64];
const PDO_WRITE: &[Ty] = &[Ty::Int, Ty::Int, Ty::Int, Ty::Int64];
const OBJECT: &[Ty] = &[Ty::Int, Ty::Int, Ty::Int];

pub static ROWS: &[Function] = &[
    // TV 70: ReadSDO(0, 0x6041, 0, 2) is the statusword; a slave that does not exist → −1.
    row(
        "ReadSDO",
        "17.2.1",
        &[Ty::Int, Ty::Int, Ty::Int, Ty::Int],
        Ret::Int64,
        Controller,
        |cx, a| read(cx, a, false),
    ),
    row(
        "WriteSDO",
        "17.2.3",
        SDO_WRITE,
        Ret::Status,
        Controller,
        |cx, a| {
            let (length, value) = (a.int(3), a.int(4));
            write(cx, a, false, value, Some(length))
        },
    ),
    row(
        "ReadPDO",
        "17.2.5",
        OBJECT,
        Ret::Int64,
        Controller,
        |cx, a| read(cx, a, true),
    ),
    // §17.2.7: the motion kernel may overwrite it in the next cycle.
    row(
        "WritePDO",
        "17.2.7",
        PDO_WRITE,
        Ret::Status,
        Controller,
        |cx, a| {
            let value = a.int(3);
            write(cx, a, true, value, None)
        },
    ),
    row(
        "ForceWritePDO",
        "17.2.8",
        PDO_WRITE,
        Ret::Status,
        Controller,
        |cx, a| {
            let index = u16::try_from(a.int(1)).unwrap_or(0);
            if KERNEL_WRITTEN.contains(&index) {
                return fail(cx, HMPL_NOT_SUPPORTED, Ret::Status);
            }
            let value = a.int(3);
            let plan = write(cx, a, true, value, None);
            if let Plan::Engine(..) = plan {
                let key = (a.int(0), a.int(1), a.int(2));
                cx.registers.forced_pdos.insert(key);
            }
            plan
        },
    ),
    row(
        "ReleasePDO",
        "17.2.9",
        OBJECT,
        Ret::Status,
        Controller,
        |cx, a| {
            let key = (a.int(0), a.int(1), a.int(2));
            if cx.registers.forced_pdos.remove(&key) {
                Plan::Done(Outcome::Int(0))
            } else {
                fail(cx, HMPL_ARG_OUT_OF_RANGE, Ret::Status)
            }
        },
    ),
];
