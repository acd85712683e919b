//! A device with its own write rules behind the node (the pattern of the CiA 402 binding).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use axes::od::{ObjectDictionary, OdError, Value};
use mcemu_canopen::bus::{sample_dictionary, Bus};
use mcemu_canopen::client::{nmt, ClientError, SdoClient};
use mcemu_canopen::{CanFrame, Device, NmtCommand, Node, NodeConfig, SdoAbort};

/// Refuses writes to 0x2000 while "busy", as a drive refuses homing parameters while homing.
struct Busy {
    od: ObjectDictionary,
    busy: bool,
}

impl Device for Busy {
    fn od(&self) -> &ObjectDictionary {
        &self.od
    }

    fn od_mut(&mut self) -> &mut ObjectDictionary {
        &mut self.od
    }

    fn write(&mut self, index: u16, subindex: u8, value: Value) -> Result<(), OdError> {
        if self.busy && matches!(index, 0x2000 | 0x2006) {
            return Err(OdError::DeviceState {
                index,
                subindex,
                detail: "busy".into(),
            });
        }
        self.od.write(index, subindex, value)
    }
}

#[test]
fn device_rules_reach_sdo_and_rpdo() {
    let mut bus: Bus<Busy> = Bus::new();
    let device = Busy {
        od: sample_dictionary(),
        busy: true,
    };
    bus.add(
        Node::new(
            NodeConfig {
                node_id: 1,
                ..NodeConfig::default()
            },
            device,
        )
        .unwrap(),
    );
    bus.start();
    let c = SdoClient::new(1);
    assert_eq!(
        c.download(&mut bus, 0x2000, 0, &1u32.to_le_bytes()),
        Err(ClientError::Abort(SdoAbort::DEVICE_STATE))
    );
    // RPDO1 maps 0x2006; the refused value is counted, the node goes on.
    c.download(&mut bus, 0x1400, 1, &0x8000_0201u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1600, 0, &[0]).unwrap();
    c.download(&mut bus, 0x1600, 1, &0x2006_0020u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1600, 0, &[1]).unwrap();
    c.download(&mut bus, 0x1400, 1, &0x0000_0201u32.to_le_bytes())
        .unwrap();
    nmt(&mut bus, NmtCommand::Start, 1);
    bus.send(CanFrame::new(0x201, &[1, 0, 0, 0]).unwrap());
    assert_eq!(bus.node(0).unwrap().counters().rpdo_write_errors, 1);
    bus.node_mut(0).unwrap().device_mut().busy = false;
    bus.send(CanFrame::new(0x201, &[1, 0, 0, 0]).unwrap());
    assert_eq!(
        bus.node(0).unwrap().od().get(0x2006, 0),
        Some(&Value::I32(1))
    );
    c.download(&mut bus, 0x2000, 0, &1u32.to_le_bytes())
        .unwrap();
}
