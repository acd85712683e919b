//! The CiA 402 drive's manufacturer DOMAIN 0x2F00 (shipped in `cia402-drive.eds`): SDO block and
//! segmented transfers without a user EDS, its 1 MiB maximum (0x06070012 beyond), and that it is
//! data, not a parameter (0x1010 does not store it; NMT reset node empties it).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use axes::cia402::{obj, Cia402Drive, DriveConfig};
use axes::od::{DataType, Value, MAX_VARIABLE_LEN};
use mcemu_canopen::bus::Bus;
use mcemu_canopen::client::{nmt, ClientError, SdoClient};
use mcemu_canopen::eds::Eds;
use mcemu_canopen::store::decode;
use mcemu_canopen::{CanFrame, NmtCommand, Node, NodeConfig, NodeEvent, SdoAbort};

const ID: u8 = 1;
const DOMAIN: u16 = 0x2F00;

/// The drive with the shipped EDS's objects it lacks (as the binding builds a node), on a bus.
fn drive_bus() -> Bus<Cia402Drive> {
    let mut drive = Cia402Drive::new(DriveConfig::default()).unwrap();
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/canopen/cia402-drive.eds"
    );
    for def in Eds::load(path).unwrap().entry_defs(ID).unwrap() {
        if drive.od().entry(def.index, def.subindex).is_err() {
            drive.od_mut().insert(def).unwrap();
        }
    }
    let mut bus = Bus::new();
    let config = NodeConfig {
        node_id: ID,
        ..NodeConfig::default()
    };
    bus.add(Node::new(config, drive).unwrap());
    bus.start();
    bus
}

fn data(n: usize) -> Vec<u8> {
    (0..n).map(|i| (i * 13 + i / 241) as u8).collect()
}

/// One raw request; the server's single reply.
fn raw(bus: &mut Bus<Cia402Drive>, d: [u8; 8]) -> [u8; 8] {
    let replies = bus.send(CanFrame::new(0x600 + u16::from(ID), &d).unwrap());
    assert_eq!(replies.len(), 1, "{replies:?}");
    replies[0].data().try_into().unwrap()
}

fn abort_of(reply: [u8; 8]) -> SdoAbort {
    assert_eq!(reply[0], 0x80, "not an abort: {reply:02x?}");
    SdoAbort(u32::from_le_bytes([reply[4], reply[5], reply[6], reply[7]]))
}

#[test]
fn the_drive_model_carries_the_domain() {
    let drive = Cia402Drive::new(DriveConfig::default()).unwrap();
    let entry = drive.od().entry(obj::DATA_DOMAIN, 0).unwrap();
    assert_eq!(obj::DATA_DOMAIN, DOMAIN);
    assert_eq!(entry.def.data_type, DataType::Domain);
    assert!(entry.def.access.writable() && entry.def.access.readable());
    assert!(!entry.def.pdo_mappable);
    assert_eq!(entry.def.max_len(), 1 << 20);
}

#[test]
fn block_and_segmented_transfers_of_the_shipped_domain() {
    let mut bus = drive_bus();
    let c = SdoClient::new(ID);
    let big = data(100_000);
    c.block_download(&mut bus, DOMAIN, 0, &big, &[]).unwrap();
    assert_eq!(c.block_upload(&mut bus, DOMAIN, 0, 0).unwrap(), big);
    let small = data(1000);
    c.download(&mut bus, DOMAIN, 0, &small).unwrap();
    assert_eq!(c.upload(&mut bus, DOMAIN, 0).unwrap(), small);
    // Exactly the maximum is taken.
    let full = data(MAX_VARIABLE_LEN);
    c.block_download(&mut bus, DOMAIN, 0, &full, &[]).unwrap();
    assert_eq!(
        bus.node(0).unwrap().od().get(DOMAIN, 0),
        Some(&Value::Bytes(full))
    );
}

/// CiA 301 Table 22: a download longer than the object takes is "length of service parameter
/// too high", refused at the initiate when the size is indicated (before any data moves).
#[test]
fn a_download_longer_than_1_mib_aborts_0x06070012() {
    let mut bus = drive_bus();
    let [s0, s1, s2, s3] = u32::try_from(MAX_VARIABLE_LEN + 1).unwrap().to_le_bytes();
    let [i0, i1] = DOMAIN.to_le_bytes();
    // Segmented initiate, size indicated (0x21).
    assert_eq!(
        abort_of(raw(&mut bus, [0x21, i0, i1, 0, s0, s1, s2, s3])),
        SdoAbort::LENGTH_HIGH
    );
    // Block download initiate, CRC and size indicated (0xC6).
    assert_eq!(
        abort_of(raw(&mut bus, [0xC6, i0, i1, 0, s0, s1, s2, s3])),
        SdoAbort::LENGTH_HIGH
    );
    // Size not indicated (0x20): refused with the segment that passes 1 MiB, not at the
    // server's buffer bound (0x05040005, which is no larger here).
    assert_eq!(raw(&mut bus, [0x20, i0, i1, 0, 0, 0, 0, 0])[0], 0x60);
    let mut toggle = 0u8;
    let mut segments = 0usize;
    let reply = loop {
        let reply = raw(&mut bus, [toggle, 1, 2, 3, 4, 5, 6, 7]);
        segments += 1;
        if reply[0] == 0x80 {
            break reply;
        }
        toggle ^= 0x10;
    };
    assert_eq!(abort_of(reply), SdoAbort::LENGTH_HIGH);
    assert_eq!(segments, MAX_VARIABLE_LEN / 7 + 1);
    // Too long for a fixed-size object too.
    assert_eq!(
        SdoClient::new(ID).download(&mut bus, 0x6065, 0, &[0; 5]),
        Err(ClientError::Abort(SdoAbort::LENGTH_HIGH))
    );
    // The domain still holds nothing.
    assert_eq!(
        bus.node(0).unwrap().od().get(DOMAIN, 0),
        Some(&Value::Bytes(Vec::new()))
    );
}

#[test]
fn the_domain_is_not_stored_and_reset_node_empties_it() {
    let mut bus = drive_bus();
    let c = SdoClient::new(ID);
    c.download(&mut bus, DOMAIN, 0, &data(64)).unwrap();
    // A stored parameter beside it, which the image must carry.
    c.download(&mut bus, 0x6065, 0, &1234u32.to_le_bytes())
        .unwrap();
    bus.node_mut(0).unwrap().drain_events().for_each(drop);
    // 0x1010:01 "save": the node hands the image to the application.
    let [i0, i1] = 0x1010u16.to_le_bytes();
    assert!(bus
        .send(CanFrame::new(0x601, &[0x23, i0, i1, 1, b's', b'a', b'v', b'e']).unwrap())
        .is_empty());
    let image = bus
        .node_mut(0)
        .unwrap()
        .drain_events()
        .find_map(|e| match e {
            NodeEvent::StoreRequested { image, .. } => Some(image),
            _ => None,
        })
        .expect("a store request");
    let stored = decode(&image).unwrap();
    assert!(stored.iter().any(|e| e.index == 0x6065));
    assert!(
        !stored.iter().any(|e| e.index == DOMAIN),
        "the DOMAIN is in the parameter image"
    );
    // NMT reset node: the application area returns to power-on values.
    nmt(&mut bus, NmtCommand::ResetNode, ID);
    assert_eq!(
        c.upload(&mut bus, DOMAIN, 0),
        Ok(Vec::new()),
        "reset node leaves the DOMAIN's data"
    );
}
