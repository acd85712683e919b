//! The SDO aborts a device or the node's own implementation produces beyond the dictionary's
//! checks (CiA 301 Table 22): 0x06090036 (a CiA 402 drive's min/max pair), 0x06040047 (a
//! communication object the node cannot read as defined), 0x08000000 (a device failing inside).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use axes::cia402::{Cia402Drive, DriveConfig};
use axes::od::{Access, DataType, EntryDef, ObjectDictionary, OdError, Value};
use mcemu_canopen::bus::{sample_dictionary, Bus};
use mcemu_canopen::client::{ClientError, SdoClient};
use mcemu_canopen::{Device, Node, NodeConfig, SdoAbort};

const ID: u8 = 4;

fn bus_of<D: Device>(device: D) -> Bus<D> {
    let mut bus = Bus::new();
    let config = NodeConfig {
        node_id: ID,
        ..NodeConfig::default()
    };
    bus.add(Node::new(config, device).unwrap());
    bus.start();
    bus
}

fn abort(code: SdoAbort) -> Result<(), ClientError> {
    Err(ClientError::Abort(code))
}

fn i32_bytes(v: i32) -> [u8; 4] {
    v.to_le_bytes()
}

/// CiA 402 0x607D: min position limit (1) and max position limit (2). A write that would put the
/// maximum below the minimum is refused with 0x06090036 and changes nothing.
#[test]
fn software_position_limits_with_max_below_min_abort_0x06090036() {
    let mut bus = bus_of(Cia402Drive::new(DriveConfig::default()).unwrap());
    let c = SdoClient::new(ID);
    c.download(&mut bus, 0x607D, 2, &i32_bytes(1000)).unwrap();
    c.download(&mut bus, 0x607D, 1, &i32_bytes(-1000)).unwrap();
    // min above max.
    assert_eq!(
        c.download(&mut bus, 0x607D, 1, &i32_bytes(1001)),
        abort(SdoAbort::MAX_BELOW_MIN)
    );
    // max below min.
    assert_eq!(
        c.download(&mut bus, 0x607D, 2, &i32_bytes(-1001)),
        abort(SdoAbort::MAX_BELOW_MIN)
    );
    let od = bus.node(0).unwrap().od();
    assert_eq!(od.get(0x607D, 1), Some(&Value::I32(-1000)));
    assert_eq!(od.get(0x607D, 2), Some(&Value::I32(1000)));
    // Equal limits are consistent (they switch the limits off).
    c.download(&mut bus, 0x607D, 1, &i32_bytes(1000)).unwrap();
    // Moving the window up past itself: max first, then min.
    c.download(&mut bus, 0x607D, 2, &i32_bytes(5000)).unwrap();
    c.download(&mut bus, 0x607D, 1, &i32_bytes(4000)).unwrap();
    assert_eq!(
        bus.node(0).unwrap().od().get(0x607D, 1),
        Some(&Value::I32(4000))
    );
}

/// A user's dictionary (EDS/DCF) may define a communication object with a type the node cannot
/// act on; the node keeps the device's definition, so a write to it is an internal
/// incompatibility of the device (0x06040047), not a value the node silently ignores.
#[test]
fn communication_objects_the_node_cannot_read_abort_0x06040047() {
    let mut od = sample_dictionary();
    // 0x1017 as a string, and TPDO1's mapping with INTEGER32 entries.
    od.insert(EntryDef::new(
        0x1017,
        0,
        "Producer heartbeat time",
        Access::Rw,
        Value::String("0".into()),
    ))
    .unwrap();
    od.insert(EntryDef::new(
        0x1A00,
        0,
        "Number of mapped objects",
        Access::Rw,
        Value::U8(0),
    ))
    .unwrap();
    od.insert(EntryDef::new(
        0x1A00,
        1,
        "Mapped object",
        Access::Rw,
        Value::I32(0),
    ))
    .unwrap();
    let mut bus = bus_of(od);
    let c = SdoClient::new(ID);
    assert_eq!(
        c.download(&mut bus, 0x1017, 0, b"100"),
        abort(SdoAbort::INTERNAL_INCOMPATIBLE)
    );
    // The mapping procedure: TPDO1 invalid, sub-index 0 = 0, then an entry.
    c.download(&mut bus, 0x1800, 1, &0x8000_0184u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1A00, 0, &[0]).unwrap();
    assert_eq!(
        c.download(&mut bus, 0x1A00, 1, &0x2005_0010i32.to_le_bytes()),
        abort(SdoAbort::INTERNAL_INCOMPATIBLE)
    );
    let od = bus.node(0).unwrap().od();
    assert_eq!(od.get(0x1017, 0), Some(&Value::String("0".into())));
    assert_eq!(od.get(0x1A00, 1), Some(&Value::I32(0)));
    // The node's own definitions are unaffected.
    c.download(&mut bus, 0x1014, 0, &0x84u32.to_le_bytes())
        .unwrap();
    assert_eq!(
        bus.node(0)
            .unwrap()
            .od()
            .entry(0x1014, 0)
            .unwrap()
            .def
            .data_type,
        DataType::Unsigned32
    );
}

/// A device whose back end fails (as the CT E10's map does when its engine has stopped).
struct Failing {
    od: ObjectDictionary,
}

impl Device for Failing {
    fn od(&self) -> &ObjectDictionary {
        &self.od
    }

    fn od_mut(&mut self) -> &mut ObjectDictionary {
        &mut self.od
    }

    fn write(&mut self, index: u16, subindex: u8, value: Value) -> Result<(), OdError> {
        self.od.validate(index, subindex, &value)?;
        if index == 0x2000 {
            return Err(OdError::DeviceFailure {
                index,
                subindex,
                detail: "the back end has stopped".into(),
            });
        }
        self.od.write(index, subindex, value)
    }
}

#[test]
fn a_device_failing_inside_aborts_0x08000000() {
    let mut bus = bus_of(Failing {
        od: sample_dictionary(),
    });
    let c = SdoClient::new(ID);
    assert_eq!(
        c.download(&mut bus, 0x2000, 0, &5u32.to_le_bytes()),
        abort(SdoAbort::GENERAL)
    );
    // The dictionary's own checks still come first.
    assert_eq!(
        c.download(&mut bus, 0x2000, 0, &5000u32.to_le_bytes()),
        abort(SdoAbort::VALUE_HIGH)
    );
    assert_eq!(
        bus.node(0).unwrap().od().get(0x2000, 0),
        Some(&Value::U32(0))
    );
    // Other objects are written as before.
    c.download(&mut bus, 0x2001, 0, &7i16.to_le_bytes())
        .unwrap();
    assert_eq!(
        SdoAbort::GENERAL.description(),
        Some("general error"),
        "the abort's CiA 301 text"
    );
}
