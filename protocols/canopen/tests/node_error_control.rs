//! Heartbeat producer and consumer, node guarding and life guarding, EMCY producer with
//! 0x1001/0x1003 and inhibit time (CiA 301 §7.2.7, §7.2.8).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::time::Duration;

use axes::od::Value;
use mcemu_canopen::bus::{sample_dictionary, Bus};
use mcemu_canopen::client::{nmt, SdoClient};
use mcemu_canopen::{
    CanFrame, ErrorBehaviour, LossCause, NmtCommand, NmtState, Node, NodeConfig, NodeEvent,
};

const ID: u8 = 7;
const MS: Duration = Duration::from_millis(1);

fn bus_with(config: NodeConfig) -> Bus {
    let mut bus = Bus::new();
    bus.add(Node::new(config, sample_dictionary()).unwrap());
    bus.start();
    bus
}

fn config() -> NodeConfig {
    NodeConfig {
        node_id: ID,
        ..NodeConfig::default()
    }
}

fn f(id: u16, data: &[u8]) -> CanFrame {
    CanFrame::new(id, data).unwrap()
}

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

fn events(bus: &mut Bus) -> Vec<NodeEvent> {
    bus.node_mut(0).unwrap().drain_events().collect()
}

/// Times (ms) at which `id` frames went out while advancing to `until`.
fn times_of(bus: &mut Bus, id: u16, until: Duration) -> Vec<u128> {
    bus.record(true);
    bus.advance(until, MS);
    let t = bus
        .log()
        .iter()
        .filter(|(_, f)| f.id() == id)
        .map(|(t, _)| t.as_millis())
        .collect();
    bus.record(false);
    t
}

#[test]
fn heartbeat_producer_period_from_0x1017() {
    let mut bus = bus_with(NodeConfig {
        heartbeat_ms: 100,
        ..config()
    });
    assert_eq!(times_of(&mut bus, 0x707, ms(450)), vec![100, 200, 300, 400]);
    // A new time starts at once; the state byte follows the NMT state.
    bus.record(true);
    SdoClient::new(ID)
        .download(&mut bus, 0x1017, 0, &250u16.to_le_bytes())
        .unwrap();
    assert_eq!(bus.log().last(), Some(&(ms(450), f(0x707, &[0x7F]))));
    assert_eq!(times_of(&mut bus, 0x707, ms(1000)), vec![700, 950]);
    let sent = nmt(&mut bus, NmtCommand::Start, ID);
    assert_eq!(
        sent,
        vec![f(0x707, &[0x05])],
        "a state change is announced at once"
    );
    SdoClient::new(ID)
        .download(&mut bus, 0x1017, 0, &0u16.to_le_bytes())
        .unwrap();
    assert!(times_of(&mut bus, 0x707, ms(3000)).is_empty());
}

#[test]
fn heartbeat_consumer_loss_recovery_and_reaction() {
    for (behaviour, after) in [
        (ErrorBehaviour::PreOperational, NmtState::PreOperational),
        (ErrorBehaviour::NoChange, NmtState::Operational),
        (ErrorBehaviour::Stopped, NmtState::Stopped),
    ] {
        let mut bus = bus_with(NodeConfig {
            error_behaviour: behaviour,
            ..config()
        });
        let c = SdoClient::new(ID);
        // Monitor the master (node 1) with 100 ms.
        c.download(&mut bus, 0x1016, 1, &0x0001_0064u32.to_le_bytes())
            .unwrap();
        nmt(&mut bus, NmtCommand::Start, ID);
        events(&mut bus);
        // Monitoring starts with the first heartbeat.
        assert!(bus.advance(ms(500), MS).is_empty());
        bus.send(f(0x701, &[0x05]));
        bus.advance(ms(580), MS);
        bus.send(f(0x701, &[0x05]));
        assert!(
            bus.advance(ms(680), MS).is_empty(),
            "100 ms after the last one is still in time"
        );
        let sent = bus.advance(ms(682), MS);
        assert_eq!(sent[0], f(0x87, &[0x30, 0x81, 0x11, 0, 0, 0, 0, 0]));
        assert_eq!(bus.node(0).unwrap().nmt_state(), after, "{behaviour:?}");
        let ev = events(&mut bus);
        assert!(ev.contains(&NodeEvent::MasterLost {
            node_id: Some(1),
            cause: LossCause::Heartbeat
        }));
        assert_eq!(
            bus.node(0).unwrap().od().get(0x1003, 1),
            Some(&Value::U32(0x8130))
        );
        // Reported once.
        assert!(bus.advance(ms(900), MS).iter().all(|f| f.id() != 0x87));
        // The master comes back: error reset EMCY (unless stopped, where EMCY is silent).
        let back = bus.send(f(0x701, &[0x05]));
        if after != NmtState::Stopped {
            assert_eq!(back, vec![f(0x87, &[0, 0, 0, 0, 0, 0, 0, 0])]);
        }
        assert!(events(&mut bus).contains(&NodeEvent::MasterRecovered {
            node_id: Some(1),
            cause: LossCause::Heartbeat
        }));
        assert!(!bus.node(0).unwrap().error_active(0x8130));
    }
}

#[test]
fn consumer_reports_boot_up_of_a_monitored_node() {
    let mut bus = bus_with(config());
    SdoClient::new(ID)
        .download(&mut bus, 0x1016, 2, &0x0009_0064u32.to_le_bytes())
        .unwrap();
    events(&mut bus);
    bus.send(f(0x709, &[0]));
    assert_eq!(
        events(&mut bus),
        vec![NodeEvent::RemoteBootUp { node_id: 9 }]
    );
    // Heartbeats of unmonitored nodes are none of its business.
    bus.send(f(0x70A, &[0]));
    assert!(events(&mut bus).is_empty());
}

#[test]
fn node_guarding_toggles_and_life_guarding_detects_a_silent_master() {
    let mut bus = bus_with(config());
    let rtr = CanFrame::remote(0x707, 1).unwrap();
    assert_eq!(bus.send(rtr), vec![f(0x707, &[0x7F])]);
    assert_eq!(bus.send(rtr), vec![f(0x707, &[0xFF])]);
    assert_eq!(bus.send(rtr), vec![f(0x707, &[0x7F])]);
    nmt(&mut bus, NmtCommand::Start, ID);
    assert_eq!(bus.send(rtr), vec![f(0x707, &[0x85])]);
    // Reset communication starts the toggle at 0 again.
    nmt(&mut bus, NmtCommand::ResetCommunication, ID);
    assert_eq!(bus.send(rtr), vec![f(0x707, &[0x7F])]);
    // Guard time 50 ms × factor 3: life time 150 ms from the last RTR.
    let c = SdoClient::new(ID);
    c.download(&mut bus, 0x100C, 0, &50u16.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x100D, 0, &[3]).unwrap();
    nmt(&mut bus, NmtCommand::Start, ID);
    let t0 = bus.now();
    bus.send(rtr);
    events(&mut bus);
    assert!(bus.advance(t0 + ms(150), MS).is_empty());
    let sent = bus.advance(t0 + ms(152), MS);
    assert_eq!(sent[0].data()[..2], [0x30, 0x81]);
    assert!(events(&mut bus).contains(&NodeEvent::MasterLost {
        node_id: None,
        cause: LossCause::LifeGuarding
    }));
    assert_eq!(bus.node(0).unwrap().nmt_state(), NmtState::PreOperational);
    bus.send(rtr);
    assert!(events(&mut bus).contains(&NodeEvent::MasterRecovered {
        node_id: None,
        cause: LossCause::LifeGuarding
    }));
    // With a heartbeat producer, guarding RTRs get no answer.
    c.download(&mut bus, 0x1017, 0, &100u16.to_le_bytes())
        .unwrap();
    assert!(bus.send(rtr).is_empty());
}

#[test]
fn emcy_register_history_and_error_reset() {
    let mut bus = bus_with(config());
    let now = bus.now();
    let node = bus.node_mut(0).unwrap();
    let sent = node.raise_error(0x2310, 0x02, [1, 2, 3, 4, 5], now);
    assert_eq!(sent, vec![f(0x87, &[0x10, 0x23, 0x03, 1, 2, 3, 4, 5])]);
    // Already active: not sent again.
    assert!(node.raise_error(0x2310, 0x02, [0; 5], now).is_empty());
    let sent = node.raise_error(0x4210, 0x08, [0; 5], now);
    assert_eq!(sent, vec![f(0x87, &[0x10, 0x42, 0x0B, 0, 0, 0, 0, 0])]);
    let c = SdoClient::new(ID);
    assert_eq!(c.upload(&mut bus, 0x1001, 0).unwrap(), [0x0B]);
    assert_eq!(c.upload(&mut bus, 0x1003, 0).unwrap(), [2]);
    assert_eq!(
        c.upload(&mut bus, 0x1003, 1).unwrap(),
        0x4210u32.to_le_bytes()
    );
    assert_eq!(
        c.upload(&mut bus, 0x1003, 2).unwrap(),
        0x0201_2310u32.to_le_bytes()
    );
    let now = bus.now();
    let sent = bus.node_mut(0).unwrap().clear_error(0x2310, now);
    assert_eq!(sent, vec![f(0x87, &[0, 0, 0x09, 0, 0, 0, 0, 0])]);
    let sent = bus.node_mut(0).unwrap().clear_error(0x4210, now);
    assert_eq!(sent, vec![f(0x87, &[0, 0, 0, 0, 0, 0, 0, 0])]);
    // Writing 0 to 0x1003:00 empties the history.
    c.download(&mut bus, 0x1003, 0, &[0]).unwrap();
    assert_eq!(c.upload(&mut bus, 0x1003, 0).unwrap(), [0]);
    assert_eq!(c.upload(&mut bus, 0x1003, 1).unwrap(), [0; 4]);
}

#[test]
fn history_keeps_the_newest_entries() {
    let mut bus = bus_with(NodeConfig {
        error_history: 3,
        ..config()
    });
    let now = bus.now();
    for code in [0x1000u16, 0x2000, 0x3000, 0x4000, 0x5000] {
        bus.node_mut(0).unwrap().raise_error(code, 0, [0; 5], now);
    }
    let od = bus.node(0).unwrap().od();
    assert_eq!(od.get(0x1003, 0), Some(&Value::U8(3)));
    assert_eq!(od.get(0x1003, 1), Some(&Value::U32(0x5000)));
    assert_eq!(od.get(0x1003, 3), Some(&Value::U32(0x3000)));
}

#[test]
fn emcy_inhibit_time_spaces_messages() {
    let mut bus = bus_with(config());
    // 0x1015 in 100 µs: 10 ms.
    SdoClient::new(ID)
        .download(&mut bus, 0x1015, 0, &100u16.to_le_bytes())
        .unwrap();
    let now = bus.now();
    let node = bus.node_mut(0).unwrap();
    assert_eq!(node.raise_error(0x1000, 0, [0; 5], now).len(), 1);
    assert!(node.raise_error(0x2000, 0, [0; 5], now).is_empty());
    assert!(node.raise_error(0x3000, 0, [0; 5], now).is_empty());
    assert_eq!(node.next_deadline(), Some(now + ms(10)));
    bus.record(true);
    bus.advance(now + ms(30), Duration::from_micros(500));
    let t: Vec<_> = bus
        .log()
        .iter()
        .filter(|(_, f)| f.id() == 0x87)
        .map(|(t, f)| ((*t - now).as_micros(), f.data()[1]))
        .collect();
    assert_eq!(t, vec![(10_000, 0x20), (20_000, 0x30)]);
}

#[test]
fn emcy_cob_id_invalid_silences_the_producer() {
    let mut bus = bus_with(config());
    SdoClient::new(ID)
        .download(&mut bus, 0x1014, 0, &0x8000_0087u32.to_le_bytes())
        .unwrap();
    let now = bus.now();
    assert!(bus
        .node_mut(0)
        .unwrap()
        .raise_error(0x1000, 0, [0; 5], now)
        .is_empty());
    assert_eq!(bus.node(0).unwrap().counters().emcy_dropped, 1);
}

#[test]
fn next_deadline_covers_heartbeat_and_consumers() {
    let mut bus = bus_with(NodeConfig {
        heartbeat_ms: 100,
        ..config()
    });
    assert_eq!(bus.node(0).unwrap().next_deadline(), Some(ms(100)));
    SdoClient::new(ID)
        .download(&mut bus, 0x1016, 1, &0x0001_0032u32.to_le_bytes())
        .unwrap();
    bus.send(f(0x701, &[5]));
    let d = bus.node(0).unwrap().next_deadline().unwrap();
    assert!(d > ms(50) && d <= ms(51), "{d:?}");
}
