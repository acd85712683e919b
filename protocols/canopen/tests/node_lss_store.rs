//! LSS slave (CiA 305) commissioning an unconfigured node, and store/restore parameters
//! (0x1010/0x1011) with the image the transport persists.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use axes::od::Value;
use mcemu_canopen::bus::{sample_dictionary, Bus};
use mcemu_canopen::client::{nmt, SdoClient};
use mcemu_canopen::{
    store, CanFrame, Identity, NmtCommand, NmtState, Node, NodeConfig, NodeEvent, ParameterGroup,
};

const IDENTITY: Identity = Identity {
    vendor_id: 0x0000_1234,
    product_code: 0x0000_0402,
    revision: 0x0001_0002,
    serial: 0x00C0_FFEE,
};

fn f(id: u16, data: &[u8]) -> CanFrame {
    CanFrame::new(id, data).unwrap()
}

fn lss(bus: &mut Bus, cs: u8, rest: &[u8]) -> Vec<CanFrame> {
    let mut d = [0u8; 8];
    d[0] = cs;
    d[1..1 + rest.len()].copy_from_slice(rest);
    bus.send(f(0x7E5, &d))
}

fn lss_value(bus: &mut Bus, cs: u8, v: u32) -> Vec<CanFrame> {
    lss(bus, cs, &v.to_le_bytes())
}

fn unconfigured() -> Bus {
    let mut bus = Bus::new();
    let config = NodeConfig {
        node_id: 0xFF,
        identity: IDENTITY,
        ..NodeConfig::default()
    };
    bus.add(Node::new(config, sample_dictionary()).unwrap());
    bus
}

#[test]
fn an_unconfigured_node_is_commissioned_by_lss() {
    let mut bus = unconfigured();
    assert!(bus.start().is_empty(), "no boot-up without a node id");
    assert_eq!(bus.node(0).unwrap().nmt_state(), NmtState::Initialising);
    assert!(nmt(&mut bus, NmtCommand::Start, 0).is_empty());
    // Identify non-configured remote slave.
    assert_eq!(
        lss(&mut bus, 0x4C, &[]),
        vec![f(0x7E4, &[0x50, 0, 0, 0, 0, 0, 0, 0])]
    );
    // Configure node id needs the configuration state.
    assert!(lss(&mut bus, 0x11, &[10]).is_empty());
    assert!(lss(&mut bus, 0x04, &[1]).is_empty());
    assert_eq!(
        lss(&mut bus, 0x11, &[0]),
        vec![f(0x7E4, &[0x11, 1, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(
        lss(&mut bus, 0x11, &[128]),
        vec![f(0x7E4, &[0x11, 1, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(
        lss(&mut bus, 0x11, &[10]),
        vec![f(0x7E4, &[0x11, 0, 0, 0, 0, 0, 0, 0])]
    );
    // Inquire identity and node id (still unconfigured until it leaves configuration).
    for (cs, v) in [
        (0x5Au8, IDENTITY.vendor_id),
        (0x5B, IDENTITY.product_code),
        (0x5C, IDENTITY.revision),
        (0x5D, IDENTITY.serial),
    ] {
        let mut want = [cs, 0, 0, 0, 0, 0, 0, 0];
        want[1..5].copy_from_slice(&v.to_le_bytes());
        assert_eq!(lss(&mut bus, cs, &[]), vec![f(0x7E4, &want)]);
    }
    assert_eq!(
        lss(&mut bus, 0x5E, &[]),
        vec![f(0x7E4, &[0x5E, 0xFF, 0, 0, 0, 0, 0, 0])]
    );
    // Bit timing: index 5 is reserved; 2 = 500 kbit/s.
    assert_eq!(
        lss(&mut bus, 0x13, &[0, 5]),
        vec![f(0x7E4, &[0x13, 1, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(
        lss(&mut bus, 0x13, &[0, 2]),
        vec![f(0x7E4, &[0x13, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert!(lss(&mut bus, 0x15, &[100, 0]).is_empty());
    assert_eq!(
        lss(&mut bus, 0x17, &[]),
        vec![f(0x7E4, &[0x17, 0, 0, 0, 0, 0, 0, 0])]
    );
    let events: Vec<_> = bus.node_mut(0).unwrap().drain_events().collect();
    assert!(events.contains(&NodeEvent::BitTimingActivated {
        table_index: 2,
        delay_ms: 100
    }));
    assert!(events.contains(&NodeEvent::LssStoreRequested {
        node_id: 10,
        bit_timing: 2
    }));
    // Back to waiting: the node takes id 10 and boots.
    assert_eq!(lss(&mut bus, 0x04, &[0]), vec![f(0x70A, &[0])]);
    assert_eq!(bus.node(0).unwrap().node_id(), 10);
    assert_eq!(
        SdoClient::new(10).upload(&mut bus, 0x1014, 0).unwrap(),
        0x8Au32.to_le_bytes()
    );
    assert_eq!(
        SdoClient::new(10).upload(&mut bus, 0x1800, 1).unwrap(),
        0x18Au32.to_le_bytes()
    );
    assert!(lss(&mut bus, 0x4C, &[]).is_empty(), "configured now");
}

#[test]
fn a_configured_node_takes_a_new_id_at_reset_communication() {
    let mut bus = Bus::new();
    bus.add(
        Node::new(
            NodeConfig {
                node_id: 4,
                identity: IDENTITY,
                ..NodeConfig::default()
            },
            sample_dictionary(),
        )
        .unwrap(),
    );
    bus.start();
    // Switch state selective: vendor, product, revision, serial.
    assert!(lss_value(&mut bus, 0x40, IDENTITY.vendor_id).is_empty());
    assert!(lss_value(&mut bus, 0x41, IDENTITY.product_code).is_empty());
    assert!(lss_value(&mut bus, 0x42, IDENTITY.revision).is_empty());
    assert_eq!(
        lss_value(&mut bus, 0x43, IDENTITY.serial),
        vec![f(0x7E4, &[0x44, 0, 0, 0, 0, 0, 0, 0])]
    );
    lss(&mut bus, 0x11, &[20]);
    assert!(
        lss(&mut bus, 0x04, &[0]).is_empty(),
        "configured nodes wait for a reset"
    );
    assert_eq!(bus.node(0).unwrap().node_id(), 4);
    assert_eq!(
        nmt(&mut bus, NmtCommand::ResetCommunication, 4),
        vec![f(0x714, &[0])]
    );
    // A wrong serial selects nothing.
    lss_value(&mut bus, 0x40, IDENTITY.vendor_id);
    lss_value(&mut bus, 0x41, IDENTITY.product_code);
    lss_value(&mut bus, 0x42, IDENTITY.revision);
    assert!(lss_value(&mut bus, 0x43, IDENTITY.serial + 1).is_empty());
    assert!(lss(&mut bus, 0x5E, &[]).is_empty(), "still waiting");
}

#[test]
fn identify_remote_slave_by_ranges() {
    let mut bus = unconfigured();
    bus.start();
    let ask = |bus: &mut Bus, rev: (u32, u32), serial: (u32, u32)| {
        lss_value(bus, 0x46, IDENTITY.vendor_id);
        lss_value(bus, 0x47, IDENTITY.product_code);
        lss_value(bus, 0x48, rev.0);
        lss_value(bus, 0x49, rev.1);
        lss_value(bus, 0x4A, serial.0);
        lss_value(bus, 0x4B, serial.1)
    };
    let hit = vec![f(0x7E4, &[0x4F, 0, 0, 0, 0, 0, 0, 0])];
    assert_eq!(ask(&mut bus, (0, u32::MAX), (0, u32::MAX)), hit);
    assert_eq!(
        ask(
            &mut bus,
            (IDENTITY.revision, IDENTITY.revision),
            (IDENTITY.serial, IDENTITY.serial)
        ),
        hit
    );
    assert!(ask(&mut bus, (0, 5), (0, u32::MAX)).is_empty());
}

#[test]
fn fastscan_finds_the_identity_bit_by_bit() {
    let mut bus = unconfigured();
    bus.start();
    let scan = |bus: &mut Bus, id: u32, bitcheck: u8, sub: u8, next: u8| {
        let mut d = [0x51, 0, 0, 0, 0, bitcheck, sub, next];
        d[1..5].copy_from_slice(&id.to_le_bytes());
        !bus.send(f(0x7E5, &d)).is_empty()
    };
    assert!(scan(&mut bus, 0, 0x80, 0, 0));
    let ident = [
        IDENTITY.vendor_id,
        IDENTITY.product_code,
        IDENTITY.revision,
        IDENTITY.serial,
    ];
    for sub in 0..4u8 {
        // The master's search: try each bit from the top with 0; no answer means 1.
        let mut guess = 0u32;
        for bit in (0..32u8).rev() {
            if !scan(&mut bus, guess, bit, sub, sub) {
                guess |= 1 << bit;
            }
        }
        assert_eq!(guess, ident[sub as usize]);
        let next = (sub + 1) % 4;
        assert!(scan(&mut bus, guess, 0, sub, next));
    }
    // Selected: the node is in configuration state.
    assert_eq!(
        lss(&mut bus, 0x5E, &[]),
        vec![f(0x7E4, &[0x5E, 0xFF, 0, 0, 0, 0, 0, 0])]
    );
}

fn configured(stored: Option<Vec<u8>>) -> Bus {
    let mut bus = Bus::new();
    let mut node = Node::new(
        NodeConfig {
            node_id: 6,
            ..NodeConfig::default()
        },
        sample_dictionary(),
    )
    .unwrap();
    node.set_stored_image(stored);
    bus.add(node);
    bus.start();
    bus
}

/// Store (0x1010) or restore (0x1011) `sub`; the transport persists; returns the image.
fn persist(bus: &mut Bus, index: u16, sub: u8, signature: &[u8; 4]) -> Vec<u8> {
    let [lo, hi] = index.to_le_bytes();
    let mut d = [0x23, lo, hi, sub, 0, 0, 0, 0];
    d[4..].copy_from_slice(signature);
    assert!(
        bus.send(f(0x606, &d)).is_empty(),
        "confirmed only after the transport persisted"
    );
    let image =
        bus.node_mut(0)
            .unwrap()
            .drain_events()
            .find_map(|e| match e {
                NodeEvent::StoreRequested { image, .. }
                | NodeEvent::RestoreRequested { image, .. } => Some(image),
                _ => None,
            })
            .unwrap();
    let now = bus.now();
    let sent = bus.node_mut(0).unwrap().finish_persist(true, now);
    assert_eq!(sent, vec![f(0x586, &[0x60, lo, hi, sub, 0, 0, 0, 0])]);
    image
}

#[test]
fn stored_parameters_survive_resets_and_power_cycles() {
    let mut bus = configured(None);
    let c = SdoClient::new(6);
    c.download(&mut bus, 0x2000, 0, &77u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1017, 0, &20u16.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x6040, 0, &6u16.to_le_bytes())
        .unwrap();
    let image = persist(&mut bus, 0x1010, 1, b"save");
    c.download(&mut bus, 0x2000, 0, &1u32.to_le_bytes())
        .unwrap();
    nmt(&mut bus, NmtCommand::ResetNode, 6);
    assert_eq!(c.upload(&mut bus, 0x2000, 0).unwrap(), 77u32.to_le_bytes());
    assert_eq!(c.upload(&mut bus, 0x1017, 0).unwrap(), 20u16.to_le_bytes());
    // Process data (rww) is not a stored parameter.
    assert_eq!(c.upload(&mut bus, 0x6040, 0).unwrap(), 0u16.to_le_bytes());
    // Power cycle with the persisted image.
    let mut again = configured(Some(image.clone()));
    assert_eq!(
        c.upload(&mut again, 0x2000, 0).unwrap(),
        77u32.to_le_bytes()
    );
    // Storing communication parameters only keeps the stored application ones.
    c.download(&mut again, 0x2000, 0, &5u32.to_le_bytes())
        .unwrap();
    c.download(&mut again, 0x1017, 0, &30u16.to_le_bytes())
        .unwrap();
    let comm = persist(&mut again, 0x1010, 2, b"save");
    let entries = store::decode(&comm).unwrap();
    assert!(entries
        .iter()
        .any(|e| e.index == 0x2000 && e.value == Value::U32(77)));
    assert!(entries
        .iter()
        .any(|e| e.index == 0x1017 && e.value == Value::U16(30)));
    // Restore defaults of the application group: effective after reset node.
    let restored = persist(&mut again, 0x1011, 3, b"load");
    assert!(store::decode(&restored)
        .unwrap()
        .iter()
        .all(|e| e.index < 0x2000));
    assert_eq!(c.upload(&mut again, 0x2000, 0).unwrap(), 5u32.to_le_bytes());
    nmt(&mut again, NmtCommand::ResetNode, 6);
    assert_eq!(c.upload(&mut again, 0x2000, 0).unwrap(), 0u32.to_le_bytes());
    assert_eq!(
        c.upload(&mut again, 0x1017, 0).unwrap(),
        30u16.to_le_bytes()
    );
    assert_eq!(again.node(0).unwrap().stored_image(), Some(&restored[..]));
    // A damaged image is ignored: defaults.
    let mut broken = image;
    let last = broken.len() - 1;
    broken[last] ^= 1;
    let mut damaged = configured(Some(broken));
    assert_eq!(
        c.upload(&mut damaged, 0x2000, 0).unwrap(),
        0u32.to_le_bytes()
    );
    // The sub-indices read 1: the device saves on command.
    assert_eq!(
        c.upload(&mut damaged, 0x1010, 1).unwrap(),
        1u32.to_le_bytes()
    );
    assert_eq!(ParameterGroup::from_subindex(4), None);
}
