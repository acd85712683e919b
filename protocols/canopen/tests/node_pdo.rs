//! PDOs and SYNC: transmission types, dynamic mapping, RPDO length errors, inhibit time and
//! event timer, SYNC counter and start value (CiA 301 §7.2.2, §7.2.5).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::time::Duration;

use axes::od::Value;
use mcemu_canopen::bus::{sample_dictionary, Bus};
use mcemu_canopen::client::{nmt, SdoClient};
use mcemu_canopen::{CanFrame, NmtCommand, Node, NodeConfig, NodeEvent};

const ID: u8 = 2;

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

fn f(id: u16, data: &[u8]) -> CanFrame {
    CanFrame::new(id, data).unwrap()
}

fn bus() -> Bus {
    let mut bus = Bus::new();
    bus.add(
        Node::new(
            NodeConfig {
                node_id: ID,
                ..NodeConfig::default()
            },
            sample_dictionary(),
        )
        .unwrap(),
    );
    bus.start();
    bus
}

/// Configure PDO `n` of `comm`/`map` with the CiA 301 procedure.
fn configure(bus: &mut Bus, comm: u16, map: u16, cob: u32, ttype: u8, entries: &[u32]) {
    let c = SdoClient::new(ID);
    c.download(bus, comm, 1, &(cob | 0x8000_0000).to_le_bytes())
        .unwrap();
    c.download(bus, map, 0, &[0]).unwrap();
    for (k, e) in entries.iter().enumerate() {
        c.download(bus, map, k as u8 + 1, &e.to_le_bytes()).unwrap();
    }
    c.download(bus, map, 0, &[entries.len() as u8]).unwrap();
    c.download(bus, comm, 2, &[ttype]).unwrap();
    c.download(bus, comm, 1, &cob.to_le_bytes()).unwrap();
}

fn set(bus: &mut Bus, index: u16, value: Value) {
    bus.node_mut(0)
        .unwrap()
        .device_mut()
        .set(index, 0, value)
        .unwrap();
}

fn get(bus: &Bus, index: u16) -> Value {
    bus.node(0).unwrap().od().get(index, 0).unwrap().clone()
}

fn sync(bus: &mut Bus) -> Vec<CanFrame> {
    bus.send(f(0x80, &[]))
}

#[test]
fn rpdo_event_driven_writes_at_once_with_dummy_mapping() {
    let mut bus = bus();
    // 0x2007 (U8), a dummy UNSIGNED16, 0x2006 (I32).
    configure(
        &mut bus,
        0x1400,
        0x1600,
        0x202,
        255,
        &[0x2007_0008, 0x0006_0010, 0x2006_0020],
    );
    nmt(&mut bus, NmtCommand::Start, ID);
    bus.node_mut(0).unwrap().drain_events().count();
    bus.send(f(0x202, &[9, 0xAA, 0xBB, 0x78, 0x56, 0x34, 0x12]));
    assert_eq!(get(&bus, 0x2007), Value::U8(9));
    assert_eq!(get(&bus, 0x2006), Value::I32(0x1234_5678));
    assert_eq!(
        bus.node_mut(0).unwrap().poll_event(),
        Some(NodeEvent::RpdoReceived { pdo: 0 })
    );
}

#[test]
fn rpdo_wrong_length_raises_emcy_0x8210_and_0x8220() {
    let mut bus = bus();
    configure(&mut bus, 0x1400, 0x1600, 0x202, 254, &[0x2006_0020]);
    nmt(&mut bus, NmtCommand::Start, ID);
    // Too short: not processed, EMCY 0x8210 with the communication bit.
    let sent = bus.send(f(0x202, &[1, 2, 3]));
    assert_eq!(sent, vec![f(0x82, &[0x10, 0x82, 0x11, 0, 0, 0, 0, 0])]);
    assert_eq!(get(&bus, 0x2006), Value::I32(0));
    // Repeated: counted, not sent again.
    assert!(bus.send(f(0x202, &[1, 2, 3])).is_empty());
    assert_eq!(bus.node(0).unwrap().counters().rpdo_length_errors, 2);
    // Right length: processed, error reset.
    let sent = bus.send(f(0x202, &[1, 0, 0, 0]));
    assert_eq!(sent, vec![f(0x82, &[0, 0, 0, 0, 0, 0, 0, 0])]);
    assert_eq!(get(&bus, 0x2006), Value::I32(1));
    // Too long: processed, EMCY 0x8220.
    let sent = bus.send(f(0x202, &[2, 0, 0, 0, 9]));
    assert_eq!(sent[0].data()[..2], [0x20, 0x82]);
    assert_eq!(get(&bus, 0x2006), Value::I32(2));
}

#[test]
fn rpdo_synchronous_applies_at_the_next_sync() {
    let mut bus = bus();
    configure(&mut bus, 0x1400, 0x1600, 0x202, 1, &[0x6040_0010]);
    nmt(&mut bus, NmtCommand::Start, ID);
    bus.send(f(0x202, &[0x0F, 0]));
    assert_eq!(get(&bus, 0x6040), Value::U16(0));
    bus.node_mut(0).unwrap().drain_events().count();
    sync(&mut bus);
    assert_eq!(get(&bus, 0x6040), Value::U16(0x0F));
    let ev: Vec<_> = bus.node_mut(0).unwrap().drain_events().collect();
    assert_eq!(
        ev,
        vec![
            NodeEvent::RpdoReceived { pdo: 0 },
            NodeEvent::Sync { counter: None }
        ]
    );
}

#[test]
fn rpdo_event_timer_monitors_reception() {
    let mut bus = bus();
    configure(&mut bus, 0x1400, 0x1600, 0x202, 254, &[0x2007_0008]);
    SdoClient::new(ID)
        .download(&mut bus, 0x1400, 5, &100u16.to_le_bytes())
        .unwrap();
    nmt(&mut bus, NmtCommand::Start, ID);
    let t0 = bus.now();
    bus.send(f(0x202, &[1]));
    assert!(bus.advance(t0 + ms(100), ms(1)).is_empty());
    let sent = bus.advance(t0 + ms(102), ms(1));
    assert_eq!(sent[0].data()[..2], [0x50, 0x82]);
    assert_eq!(bus.send(f(0x202, &[1])), vec![f(0x82, &[0; 8])]);
}

#[test]
fn tpdo_cyclic_synchronous_every_nth_sync() {
    let mut bus = bus();
    configure(
        &mut bus,
        0x1800,
        0x1A00,
        0x182,
        3,
        &[0x6041_0010, 0x6064_0020],
    );
    nmt(&mut bus, NmtCommand::Start, ID);
    set(&mut bus, 0x6041, Value::U16(0x0237));
    set(&mut bus, 0x6064, Value::I32(-2));
    let mut seen = Vec::new();
    for k in 1..=9 {
        if !sync(&mut bus).is_empty() {
            seen.push(k);
        }
    }
    assert_eq!(seen, vec![3, 6, 9]);
    set(&mut bus, 0x6041, Value::U16(0x1237));
    sync(&mut bus);
    sync(&mut bus);
    assert_eq!(
        sync(&mut bus),
        vec![f(0x182, &[0x37, 0x12, 0xFE, 0xFF, 0xFF, 0xFF])]
    );
}

#[test]
fn tpdo_acyclic_synchronous_only_after_a_change() {
    let mut bus = bus();
    configure(&mut bus, 0x1800, 0x1A00, 0x182, 0, &[0x6041_0010]);
    nmt(&mut bus, NmtCommand::Start, ID);
    assert_eq!(sync(&mut bus).len(), 1, "first SYNC sends the initial data");
    assert!(sync(&mut bus).is_empty());
    set(&mut bus, 0x6041, Value::U16(1));
    bus.advance_by(ms(1), ms(1));
    assert!(
        bus.advance_by(ms(5), ms(1)).is_empty(),
        "type 0 waits for SYNC"
    );
    assert_eq!(sync(&mut bus), vec![f(0x182, &[1, 0])]);
    assert!(sync(&mut bus).is_empty());
    bus.node_mut(0).unwrap().request_tpdo(0);
    assert_eq!(sync(&mut bus).len(), 1, "an application request");
}

#[test]
fn tpdo_sync_start_value_with_counter() {
    let mut bus = bus();
    let c = SdoClient::new(ID);
    c.download(&mut bus, 0x1019, 0, &[10]).unwrap();
    configure(&mut bus, 0x1800, 0x1A00, 0x182, 2, &[0x6041_0010]);
    c.download(&mut bus, 0x1800, 1, &0x8000_0182u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1800, 6, &[4]).unwrap();
    c.download(&mut bus, 0x1800, 1, &0x0000_0182u32.to_le_bytes())
        .unwrap();
    nmt(&mut bus, NmtCommand::Start, ID);
    let mut seen = Vec::new();
    for counter in 1..=10u8 {
        if !bus.send(f(0x80, &[counter])).is_empty() {
            seen.push(counter);
        }
    }
    assert_eq!(seen, vec![4, 6, 8, 10]);
    // A SYNC without its counter: EMCY 0x8240, no SYNC event.
    bus.node_mut(0).unwrap().drain_events().count();
    let sent = sync(&mut bus);
    assert_eq!(sent[0].data()[..2], [0x40, 0x82]);
    assert!(bus
        .node_mut(0)
        .unwrap()
        .drain_events()
        .all(|e| !matches!(e, NodeEvent::Sync { .. })));
}

#[test]
fn tpdo_event_driven_on_change_with_inhibit_and_event_timer() {
    let mut bus = bus();
    configure(&mut bus, 0x1800, 0x1A00, 0x182, 255, &[0x6041_0010]);
    let c = SdoClient::new(ID);
    c.download(&mut bus, 0x1800, 1, &0x8000_0182u32.to_le_bytes())
        .unwrap();
    // Inhibit 10 ms (100 × 100 µs), event timer 50 ms.
    c.download(&mut bus, 0x1800, 3, &100u16.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1800, 5, &50u16.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1800, 1, &0x0000_0182u32.to_le_bytes())
        .unwrap();
    let t0 = bus.now();
    let sent = nmt(&mut bus, NmtCommand::Start, ID);
    assert!(sent.is_empty());
    bus.record(true);
    // Entering Operational sends once (next tick); then changes every ms, inhibit 10 ms.
    for k in 1..=30u16 {
        set(&mut bus, 0x6041, Value::U16(k));
        bus.advance(t0 + ms(u64::from(k)), ms(1));
    }
    // Then quiet: the event timer sends every 50 ms.
    bus.advance(t0 + ms(200), ms(1));
    let times: Vec<u128> = bus
        .log()
        .iter()
        .filter(|(_, f)| f.id() == 0x182)
        .map(|(t, _)| (*t - t0).as_millis())
        .collect();
    assert_eq!(times, vec![1, 11, 21, 31, 81, 131, 181]);
}

#[test]
fn tpdo_rtr_types_and_remote_requests() {
    let mut bus = bus();
    configure(&mut bus, 0x1800, 0x1A00, 0x182, 253, &[0x6041_0010]);
    configure(&mut bus, 0x1801, 0x1A01, 0x282, 252, &[0x6064_0020]);
    nmt(&mut bus, NmtCommand::Start, ID);
    set(&mut bus, 0x6041, Value::U16(7));
    assert!(
        bus.advance_by(ms(10), ms(1)).is_empty(),
        "RTR-only types never send on their own"
    );
    assert_eq!(
        bus.send(CanFrame::remote(0x182, 2).unwrap()),
        vec![f(0x182, &[7, 0])]
    );
    // 252: sampled at SYNC, sent on RTR.
    assert!(
        bus.send(CanFrame::remote(0x282, 4).unwrap()).is_empty(),
        "nothing sampled yet"
    );
    set(&mut bus, 0x6064, Value::I32(5));
    sync(&mut bus);
    set(&mut bus, 0x6064, Value::I32(6));
    assert_eq!(
        bus.send(CanFrame::remote(0x282, 4).unwrap()),
        vec![f(0x282, &[5, 0, 0, 0])]
    );
    // RTR not allowed (bit 30): no answer.
    let c = SdoClient::new(ID);
    c.download(&mut bus, 0x1802, 1, &0x8000_0382u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1A02, 0, &[0]).unwrap();
    c.download(&mut bus, 0x1A02, 1, &0x6041_0010u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1A02, 0, &[1]).unwrap();
    c.download(&mut bus, 0x1802, 2, &[1]).unwrap();
    c.download(&mut bus, 0x1802, 1, &0x4000_0382u32.to_le_bytes())
        .unwrap();
    assert!(bus.send(CanFrame::remote(0x382, 2).unwrap()).is_empty());
}

#[test]
fn default_pdos_follow_the_pre_defined_connection_set() {
    let mut bus = bus();
    let c = SdoClient::new(ID);
    for (index, cob) in [
        (0x1400u16, 0x202u32),
        (0x1401, 0x302),
        (0x1403, 0x502),
        (0x1800, 0x182),
        (0x1803, 0x482),
    ] {
        assert_eq!(
            c.upload(&mut bus, index, 1).unwrap(),
            cob.to_le_bytes(),
            "{index:#x}"
        );
    }
    // A TPDO with nothing mapped is never sent.
    nmt(&mut bus, NmtCommand::Start, ID);
    assert!(bus.advance_by(ms(100), ms(1)).is_empty());
    assert!(sync(&mut bus).is_empty());
}

#[test]
fn pdos_stop_with_operational() {
    let mut bus = bus();
    configure(&mut bus, 0x1800, 0x1A00, 0x182, 1, &[0x6041_0010]);
    nmt(&mut bus, NmtCommand::Start, ID);
    assert_eq!(sync(&mut bus).len(), 1);
    nmt(&mut bus, NmtCommand::EnterPreOperational, ID);
    assert!(sync(&mut bus).is_empty());
}

#[test]
fn two_nodes_on_one_bus() {
    let mut bus = Bus::new();
    for id in [2u8, 3] {
        let mut node = Node::new(
            NodeConfig {
                node_id: id,
                ..NodeConfig::default()
            },
            sample_dictionary(),
        )
        .unwrap();
        node.device_mut()
            .set(0x6041, 0, Value::U16(u16::from(id)))
            .unwrap();
        bus.add(node);
    }
    assert_eq!(bus.start(), vec![f(0x702, &[0]), f(0x703, &[0])]);
    // Each answers its own SDO channel only.
    assert_eq!(
        SdoClient::new(3).upload(&mut bus, 0x6041, 0).unwrap(),
        [3, 0]
    );
    assert_eq!(
        SdoClient::new(2).upload(&mut bus, 0x6041, 0).unwrap(),
        [2, 0]
    );
    nmt(&mut bus, NmtCommand::Start, 0);
    assert!(bus
        .nodes()
        .iter()
        .all(|n| n.nmt_state() == mcemu_canopen::NmtState::Operational));
}

/// `Node::accepts` lets a bus of many nodes skip the frames a node does not take: every frame
/// it refuses must be one `on_frame` ignores (no reply, no state change, counted as ignored),
/// in every NMT state and with consumers, SYNC and PDOs configured.
#[test]
fn a_frame_a_node_does_not_accept_is_one_it_ignores() {
    let mut bus = bus();
    let c = SdoClient::new(ID);
    // Heartbeat consumer of node 5, so 0x705 is taken.
    c.download(&mut bus, 0x1016, 1, &((5u32 << 16) | 1000).to_le_bytes())
        .unwrap();
    let states = [
        NmtCommand::EnterPreOperational,
        NmtCommand::Start,
        NmtCommand::Stop,
    ];
    for command in states {
        nmt(&mut bus, command, ID);
        let node = bus.node_mut(0).unwrap();
        for id in 0..0x800u16 {
            for frame in [
                f(id, &[]),
                f(id, &[0x40, 0, 0x10, 0, 0, 0, 0, 0]),
                CanFrame::remote(id, 8).unwrap(),
            ] {
                if node.accepts(&frame) {
                    continue;
                }
                let (state, before) = (node.nmt_state(), node.counters());
                let out = node.on_frame(&frame, bus_now());
                let after = node.counters();
                assert!(out.is_empty(), "{frame:?} in {state:?} answered {out:?}");
                assert_eq!(node.nmt_state(), state, "{frame:?}");
                assert_eq!(after.ignored, before.ignored + 1, "{frame:?} in {state:?}");
                let mut expected = before;
                expected.frames_in += 1;
                expected.ignored += 1;
                assert_eq!(after, expected, "{frame:?} in {state:?}");
            }
        }
    }
}

fn bus_now() -> Duration {
    ms(1)
}

#[test]
fn sparsely_numbered_pdos_all_run() {
    // The dictionary has RPDO 1 and RPDO 3 (0x1400, 0x1402) but no 0x1401, as a user EDS may.
    let mut od = sample_dictionary();
    let three = mcemu_canopen::communication_objects(
        &NodeConfig {
            node_id: ID,
            rpdos: 3,
            ..NodeConfig::default()
        },
        ID,
    );
    for def in three
        .into_iter()
        .filter(|d| d.index == 0x1402 || d.index == 0x1602)
    {
        od.insert(def).unwrap();
    }
    let config = NodeConfig {
        node_id: ID,
        rpdos: 1,
        ..NodeConfig::default()
    };
    let mut bus = Bus::new();
    bus.add(Node::new(config, od).unwrap());
    bus.start();
    configure(&mut bus, 0x1402, 0x1602, 0x402, 255, &[0x2006_0020]);
    nmt(&mut bus, NmtCommand::Start, ID);
    bus.send(f(0x402, &7i32.to_le_bytes()));
    assert_eq!(
        get(&bus, 0x2006),
        Value::I32(7),
        "RPDO 3 wrote its mapped object"
    );
}
