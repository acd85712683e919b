//! A register map over a real engine on the virtual clock, without sockets (ARCHITECTURE §5:
//! the service layer is tested alone): reads from snapshots, writes as engine commands, and
//! the exception each kind of bad request gets.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use std::sync::Arc;

use axes::{AxisFlags, ParamId};
use common::map_unit::{
    abcd_to_f64, cdab_to_f32, compile_map, f64_to_cdab, register_bytes, shipped_map, start_engine,
    MapUnit,
};
use mcemu_modbus::map::{Binding, MachineShape, MapModel, UnitService};
use mcemu_modbus::model::{DataModel, Peer, RequestContext};
use mcemu_modbus::pdu::{Exception, Request, Response};

const MACHINE: &str = r#"
[[axes]]
[axes.params]
axis_type = "stepper"
units = 1000
rep_mode = "finite"
speed = 100
accel = 1000
decel = 1000
[[axes]]
[axes.params]
axis_type = "stepper"
units = 1000
rep_mode = "finite"
speed = 100
accel = 1000
decel = 1000
[io]
digital_inputs = 4
digital_outputs = 4
"#;

const MAP: &str = r#"
[map]
name = "test"
word_order = "cdab"
[identity]
vendor_name = "mcemu"
[[point]]
table = "coils"
address = 0
name = "out0"
read = "do.0"
write = "do.0"
[[point]]
table = "holding_registers"
address = 900
name = "model"
type = "u16"
init = 226
[[memory]]
name = "user"
table = "holding_registers"
start = 1000
count = 8
persist = true
[[block]]
table = "holding_registers"
base = 0
stride = 20
[[block.point]]
offset = 0
name = "position"
type = "f32"
read = "axis.act_pos"
[[block.point]]
offset = 2
name = "target"
type = "f64"
write = "memory"
[[block.point]]
offset = 6
name = "start"
write = "memory"
on_write = [{ when = "rising_bit0", command = "move_absolute", args = { position = "@target" } }]
[[block.point]]
offset = 7
name = "enable"
read = { bits = { 0 = "enabled" } }
on_write = [{ when = "bit0", command = "enable" }, { when = "!bit0", command = "disable" }]
[[block.point]]
offset = 8
name = "speed"
type = "f32"
read = "axis.param.speed"
write = "axis.param.speed"
[[block.point]]
offset = 10
name = "status"
type = "u32"
read = { bits = { 0 = "enabled", 1 = "moving", 2 = "in_position" } }
[[block.point]]
offset = 12
name = "state"
read = "axis.state"
values = { standstill = 2, disabled = 0 }
default = 9
"#;

/// The machine's shape: 2 axes, 4 digital inputs and outputs.
fn machine() -> MachineShape {
    MachineShape {
        axes: 2,
        digital_inputs: 4,
        digital_outputs: 4,
        ..MachineShape::default()
    }
}

/// `MAP` over both axes of `MACHINE`, as unit 1.
fn rig() -> MapUnit {
    let map = compile_map(MAP, &machine(), &Binding { axes: vec![0, 1] });
    MapUnit::new(start_engine(MACHINE), map, Some(1))
}

/// Holding-register reads and writes through typed requests.
impl MapUnit {
    async fn read(&self, address: u16, quantity: u16) -> Vec<u16> {
        match self
            .run(Request::ReadHoldingRegisters { address, quantity })
            .await
        {
            Ok(Response::Registers { words, .. }) => words,
            other => panic!("read {address}+{quantity}: {other:?}"),
        }
    }

    async fn write(&self, address: u16, words: &[u16]) -> Result<Response, (Exception, String)> {
        self.run(Request::WriteMultipleRegisters {
            address,
            quantity: words.len() as u16,
            values: &register_bytes(words),
        })
        .await
    }
}

#[tokio::test]
async fn an_hmi_enables_sets_a_target_starts_and_reads_the_position() {
    let r = rig();
    assert_eq!(r.read(7, 1).await, [0]);
    r.write(27, &[1]).await.unwrap(); // enable axis 1
    assert!(r.handle.snapshot().axes[1]
        .flags
        .contains(AxisFlags::ENABLED));
    assert!(!r.handle.snapshot().axes[0]
        .flags
        .contains(AxisFlags::ENABLED));
    assert_eq!(r.read(27, 1).await, [1]);
    // Target and start in one request: stored in address order, so the move sees the target.
    let mut words = f64_to_cdab(12.5).to_vec();
    words.push(1);
    r.write(22, &words).await.unwrap();
    r.handle.advance(1).unwrap();
    assert_eq!(r.read(30, 2).await, [1 | 2, 0], "enabled and moving");
    r.handle
        .advance_until_async(|s| !s.axes[1].flags.contains(AxisFlags::MOVING), 60_000)
        .await
        .unwrap();
    r.handle.advance(100).unwrap();
    assert_eq!(cdab_to_f32(&r.read(20, 2).await), 12.5);
    assert_eq!(r.handle.snapshot().axes[1].act_pos, 12.5);
    assert_eq!(r.read(32, 1).await, [2], "standstill through the lookup");
    // Writing start = 1 again is no rising edge: no new move (target changed meanwhile).
    r.write(22, &f64_to_cdab(30.0)).await.unwrap();
    r.write(26, &[1]).await.unwrap();
    assert_eq!(r.handle.snapshot().axes[1].fifo_len, 0);
    r.write(26, &[0]).await.unwrap();
    r.write(26, &[1]).await.unwrap();
    assert_eq!(r.handle.snapshot().axes[1].fifo_len, 1);
}

#[tokio::test]
async fn parameters_outputs_and_memory_read_back() {
    let r = rig();
    let bits = 7.5f32.to_bits();
    r.write(8, &[bits as u16, (bits >> 16) as u16])
        .await
        .unwrap();
    assert_eq!(r.handle.snapshot().params[0].get(ParamId::Speed), 7.5);
    assert_eq!(cdab_to_f32(&r.read(8, 2).await), 7.5);
    r.run(Request::WriteSingleCoil {
        address: 0,
        value: true,
    })
    .await
    .unwrap();
    assert!(r.handle.snapshot().io.do_[0]);
    assert_eq!(r.read(900, 1).await, [226]);
    r.write(1002, &[0x12, 6]).await.unwrap();
    assert_eq!(r.read(1000, 4).await, [0, 0, 0x12, 6]);
    // FC 22 on memory (the specification's example, §6.16: 0x12 → 0x17); FC 23 writes
    // before it reads.
    r.run(Request::MaskWriteRegister {
        address: 1002,
        and_mask: 0x00F2,
        or_mask: 0x0025,
    })
    .await
    .unwrap();
    assert_eq!(r.read(1002, 1).await, [0x17]);
    let resp = r
        .run(Request::ReadWriteMultipleRegisters {
            read_address: 1003,
            read_quantity: 2,
            write_address: 1004,
            write_quantity: 1,
            values: &[0x12, 0x34],
        })
        .await
        .unwrap();
    assert_eq!(
        resp,
        Response::Registers {
            function: 0x17,
            words: vec![6, 0x1234]
        }
    );
    let unit = r.model.unit(1).unwrap();
    assert_eq!(
        unit.persisted(),
        [("user".to_string(), vec![0, 0, 0x17, 6, 0x1234, 0, 0, 0])]
    );
    unit.restore("user", &[9; 8]).unwrap();
    assert_eq!(r.read(1000, 2).await, [9, 9]);
    assert!(unit.restore("user", &[9; 7]).is_err());
}

#[tokio::test]
async fn each_kind_of_bad_request_gets_its_exception() {
    let r = rig();
    let e = |res: Result<Response, (Exception, String)>| res.unwrap_err();
    // Addresses nothing covers (02): a gap, past the end, a read running off a block, a table
    // the map does not have.
    for request in [
        Request::ReadHoldingRegisters {
            address: 13,
            quantity: 1,
        },
        Request::ReadHoldingRegisters {
            address: 1007,
            quantity: 2,
        },
        Request::ReadHoldingRegisters {
            address: 30,
            quantity: 4,
        },
        Request::ReadInputRegisters {
            address: 0,
            quantity: 1,
        },
    ] {
        assert_eq!(e(r.run(request).await).0, Exception::IllegalDataAddress);
    }
    // A read may cut a wide point; a write may not (02), nor write a read-only point (02).
    assert_eq!(r.read(1, 1).await.len(), 1);
    let (x, why) = e(r.write(3, &[0]).await);
    assert_eq!(x, Exception::IllegalDataAddress);
    assert!(why.contains("cover all"), "{why}");
    let (x, why) = e(r.write(0, &[0, 0]).await);
    assert_eq!(x, Exception::IllegalDataAddress);
    assert!(why.contains("read-only"), "{why}");
    // Not a value of the type (03): a NaN speed; the engine's range check is 03 too.
    assert_eq!(
        e(r.write(8, &[0, 0x7FC0]).await).0,
        Exception::IllegalDataValue
    );
    let minus = (-3.0f32).to_bits();
    let (x, why) = e(r.write(8, &[minus as u16, (minus >> 16) as u16]).await);
    assert_eq!(x, Exception::IllegalDataValue);
    assert!(why.contains("speed"), "{why}");
    // The engine refuses (04) and says why: a move on a disabled axis.
    let (x, why) = e(r.write(6, &[1]).await);
    assert_eq!(x, Exception::ServerDeviceFailure);
    assert!(why.contains("disabled"), "{why}");
    // Nothing of a refused request was half-done by the map's own checks: the read-only
    // failure above wrote nothing.
    assert_eq!(r.read(1000, 1).await, [0]);
    // Unit routing.
    assert!(r.model.serves(1));
    assert!(!r.model.serves(2));
}

/// The shipped generic map drives an axis through its command register and maps the I/O the
/// machine has, and no more.
#[tokio::test]
async fn the_generic_map_runs_a_command_code() {
    let map = shipped_map("generic", &machine(), &Binding { axes: vec![0, 1] });
    let r = MapUnit::new(start_engine(MACHINE), map, None);
    let handle = r.handle.clone();
    r.run(Request::WriteSingleCoil {
        address: 16,
        value: true,
    })
    .await
    .unwrap();
    let target = 7.25f64.to_be_bytes();
    let words: Vec<u16> = target
        .chunks(2)
        .map(|c| u16::from_be_bytes([c[0], c[1]]))
        .collect();
    r.write(32, &words).await.unwrap();
    r.write(40, &[1]).await.unwrap(); // command 1: move absolute, velocity 0 = the axis speed
    handle
        .advance_until_async(
            |s| s.axes[1].act_pos == 7.25 && !s.axes[1].flags.contains(AxisFlags::MOVING),
            60_000,
        )
        .await
        .unwrap();
    let pos = match r
        .run(Request::ReadInputRegisters {
            address: 32,
            quantity: 4,
        })
        .await
        .unwrap()
    {
        Response::Registers { words, .. } => words,
        other => panic!("{other:?}"),
    };
    assert_eq!(abcd_to_f64(&pos), 7.25);
    // Machine I/O: coil 1000 + 2 is DO 2.
    r.run(Request::WriteSingleCoil {
        address: 1002,
        value: true,
    })
    .await
    .unwrap();
    assert!(handle.snapshot().io.do_[2]);
    let e = r
        .run(Request::ReadCoils {
            address: 1004,
            quantity: 1,
        })
        .await
        .unwrap_err();
    assert_eq!(
        e.0,
        Exception::IllegalDataAddress,
        "the machine has 4 outputs"
    );
}

/// An RTU broadcast reaches every unit of the line.
#[tokio::test]
async fn a_broadcast_writes_every_unit() {
    let (handle, _guard) = start_engine(MACHINE);
    let service = |axis| {
        let unit = compile_map(MAP, &machine(), &Binding { axes: vec![axis] });
        Arc::new(UnitService::new(unit, handle.clone()))
    };
    let model = MapModel::new(vec![(Some(1), service(0)), (Some(2), service(1))]);
    let broadcast = RequestContext {
        unit: 0,
        broadcast: true,
        peer: Peer::Serial("line".into()),
    };
    // Register 7 is each unit's enable: both axes come up.
    model
        .execute(
            &broadcast,
            &Request::WriteSingleRegister {
                address: 7,
                value: 1,
            },
        )
        .await
        .unwrap();
    let s = handle.snapshot();
    assert!(s.axes.iter().all(|a| a.flags.contains(AxisFlags::ENABLED)));
}

/// `read_in` answers from the snapshot it is given (a caller inside the servo tick has that
/// tick's engine), `read` from the latest published one; memory is the unit's either way.
#[tokio::test]
async fn read_in_takes_the_engine_values_from_the_given_snapshot() {
    use mcemu_modbus::map::schema::Table;
    use mcemu_modbus::tables::TableAccess;

    let r = rig();
    let service = r.model.unit(1).unwrap();
    r.write(1000, &[7]).await.unwrap();
    let published = r.handle.snapshot();
    let mut other = (*published).clone();
    other.axes[0].act_pos = 12.5;
    let words = service
        .read_in(&other, Table::HoldingRegisters, 0, 2)
        .unwrap();
    assert_eq!(
        cdab_to_f32(&words),
        12.5,
        "position from the given snapshot"
    );
    let words = TableAccess::read(&**service, Table::HoldingRegisters, 0, 2).unwrap();
    assert_eq!(
        cdab_to_f32(&words),
        0.0,
        "position from the published snapshot"
    );
    assert_eq!(
        service
            .read_in(&other, Table::HoldingRegisters, 1000, 1)
            .unwrap(),
        [7]
    );
}
