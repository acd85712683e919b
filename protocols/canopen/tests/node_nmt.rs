//! NMT: boot-up, every transition, broadcast and own id, and the services each state allows
//! (CiA 301 §7.3.2).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::time::Duration;

use axes::od::Value;
use mcemu_canopen::bus::{sample_dictionary, Bus};
use mcemu_canopen::client::{nmt, SdoClient};
use mcemu_canopen::{CanFrame, NmtCommand, NmtState, Node, NodeConfig, NodeEvent};

const ID: u8 = 5;

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
    bus
}

fn f(id: u16, data: &[u8]) -> CanFrame {
    CanFrame::new(id, data).unwrap()
}

fn state(bus: &Bus) -> NmtState {
    bus.node(0).unwrap().nmt_state()
}

#[test]
fn boot_up_message_then_pre_operational() {
    let mut bus = bus();
    assert_eq!(state(&bus), NmtState::Initialising);
    assert_eq!(bus.start(), vec![f(0x705, &[0])]);
    assert_eq!(state(&bus), NmtState::PreOperational);
    let events: Vec<_> = bus.node_mut(0).unwrap().drain_events().collect();
    assert_eq!(
        events,
        vec![NodeEvent::NmtStateChanged {
            from: NmtState::Initialising,
            to: NmtState::PreOperational
        }]
    );
}

#[test]
fn every_transition_for_own_id_and_broadcast() {
    use NmtCommand::*;
    use NmtState::*;
    // (state before, command, state after, boot-up sent)
    let table = [
        (PreOperational, Start, Operational, false),
        (PreOperational, Stop, Stopped, false),
        (PreOperational, EnterPreOperational, PreOperational, false),
        (Operational, Stop, Stopped, false),
        (Operational, EnterPreOperational, PreOperational, false),
        (Operational, Start, Operational, false),
        (Stopped, Start, Operational, false),
        (Stopped, EnterPreOperational, PreOperational, false),
        (Stopped, Stop, Stopped, false),
        (PreOperational, ResetNode, PreOperational, true),
        (Operational, ResetNode, PreOperational, true),
        (Stopped, ResetNode, PreOperational, true),
        (PreOperational, ResetCommunication, PreOperational, true),
        (Operational, ResetCommunication, PreOperational, true),
        (Stopped, ResetCommunication, PreOperational, true),
    ];
    for target in [ID, 0] {
        for (before, cmd, after, boot) in table {
            let mut bus = bus();
            bus.start();
            let reach = match before {
                Operational => Some(Start),
                Stopped => Some(Stop),
                _ => None,
            };
            if let Some(c) = reach {
                nmt(&mut bus, c, ID);
            }
            assert_eq!(state(&bus), before);
            let sent = nmt(&mut bus, cmd, target);
            assert_eq!(state(&bus), after, "{before:?} --{cmd:?}/{target}--> ");
            assert_eq!(sent.contains(&f(0x705, &[0])), boot, "{before:?} {cmd:?}");
        }
    }
}

#[test]
fn commands_for_other_nodes_and_malformed_commands_are_ignored() {
    let mut bus = bus();
    bus.start();
    assert!(nmt(&mut bus, NmtCommand::Start, ID + 1).is_empty());
    assert!(bus.send(f(0, &[0x01])).is_empty());
    assert!(bus.send(f(0, &[0x01, ID, 0])).is_empty());
    assert!(bus.send(f(0, &[0x03, ID])).is_empty());
    assert!(bus.send(CanFrame::remote(0, 2).unwrap()).is_empty());
    assert_eq!(state(&bus), NmtState::PreOperational);
    assert_eq!(bus.node(0).unwrap().counters().ignored, 5);
}

#[test]
fn sdo_is_served_in_pre_operational_and_operational_but_not_in_stopped() {
    let mut bus = bus();
    bus.start();
    let c = SdoClient::new(ID);
    assert_eq!(c.upload(&mut bus, 0x1018, 0).unwrap(), vec![4]);
    nmt(&mut bus, NmtCommand::Start, ID);
    assert_eq!(c.upload(&mut bus, 0x1018, 0).unwrap(), vec![4]);
    nmt(&mut bus, NmtCommand::Stop, ID);
    assert!(bus
        .send(f(0x605, &[0x40, 0x18, 0x10, 0, 0, 0, 0, 0]))
        .is_empty());
    nmt(&mut bus, NmtCommand::EnterPreOperational, ID);
    assert_eq!(c.upload(&mut bus, 0x1018, 0).unwrap(), vec![4]);
}

#[test]
fn stopping_drops_a_transfer_in_progress() {
    let mut bus = bus();
    bus.start();
    let c = SdoClient::new(ID);
    // Segmented upload started, then the node is stopped and started again.
    let r = c
        .request(&mut bus, [0x40, 0x08, 0x20, 0, 0, 0, 0, 0])
        .unwrap();
    assert_eq!(r[0], 0x41);
    nmt(&mut bus, NmtCommand::Stop, ID);
    nmt(&mut bus, NmtCommand::EnterPreOperational, ID);
    // The segment request no longer belongs to a transfer: 0x05040001.
    let err = c
        .request(&mut bus, [0x60, 0, 0, 0, 0, 0, 0, 0])
        .unwrap_err();
    assert_eq!(
        err,
        mcemu_canopen::client::ClientError::Abort(mcemu_canopen::SdoAbort::COMMAND)
    );
}

#[test]
fn heartbeat_and_guarding_run_in_stopped_emcy_does_not() {
    let mut bus = bus();
    bus.start();
    nmt(&mut bus, NmtCommand::Stop, ID);
    // Guarding answers with the Stopped state (4).
    assert_eq!(
        bus.send(CanFrame::remote(0x705, 1).unwrap()),
        vec![f(0x705, &[0x04])]
    );
    let now = bus.now();
    let sent = bus
        .node_mut(0)
        .unwrap()
        .raise_error(0x5000, 0x02, [0; 5], now);
    assert!(sent.is_empty());
    // The error is recorded all the same.
    assert_eq!(
        bus.node(0).unwrap().od().get(0x1001, 0),
        Some(&Value::U8(0x03))
    );
    nmt(&mut bus, NmtCommand::EnterPreOperational, ID);
    SdoClient::new(ID)
        .download(&mut bus, 0x1017, 0, &100u16.to_le_bytes())
        .unwrap();
    nmt(&mut bus, NmtCommand::Stop, ID);
    let beats = bus.advance(Duration::from_millis(350), Duration::from_millis(1));
    assert_eq!(beats.iter().filter(|b| **b == f(0x705, &[0x04])).count(), 3);
}

#[test]
fn reset_node_restores_application_and_communication_values() {
    let mut bus = bus();
    bus.start();
    let c = SdoClient::new(ID);
    c.download(&mut bus, 0x2000, 0, &7u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1017, 0, &50u16.to_le_bytes())
        .unwrap();
    nmt(&mut bus, NmtCommand::ResetCommunication, ID);
    assert_eq!(c.upload(&mut bus, 0x2000, 0).unwrap(), 7u32.to_le_bytes());
    assert_eq!(c.upload(&mut bus, 0x1017, 0).unwrap(), 0u16.to_le_bytes());
    c.download(&mut bus, 0x1017, 0, &50u16.to_le_bytes())
        .unwrap();
    bus.node_mut(0).unwrap().drain_events().count();
    nmt(&mut bus, NmtCommand::ResetNode, ID);
    assert_eq!(c.upload(&mut bus, 0x2000, 0).unwrap(), 0u32.to_le_bytes());
    assert_eq!(c.upload(&mut bus, 0x1017, 0).unwrap(), 0u16.to_le_bytes());
    let events: Vec<_> = bus.node_mut(0).unwrap().drain_events().collect();
    assert!(events.contains(&NodeEvent::ResetNode));
    assert!(events.contains(&NodeEvent::ResetCommunication));
}

#[test]
fn pdo_and_sync_only_where_the_state_allows() {
    let mut bus = bus();
    bus.start();
    let c = SdoClient::new(ID);
    // RPDO1 (0x205) maps 0x2006 (INTEGER32).
    c.download(&mut bus, 0x1400, 1, &0x8000_0205u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1600, 0, &[0]).unwrap();
    c.download(&mut bus, 0x1600, 1, &0x2006_0020u32.to_le_bytes())
        .unwrap();
    c.download(&mut bus, 0x1600, 0, &[1]).unwrap();
    c.download(&mut bus, 0x1400, 1, &0x0000_0205u32.to_le_bytes())
        .unwrap();
    bus.send(f(0x205, &42i32.to_le_bytes()));
    assert_eq!(
        bus.node(0).unwrap().od().get(0x2006, 0),
        Some(&Value::I32(0)),
        "pre-operational"
    );
    nmt(&mut bus, NmtCommand::Start, ID);
    bus.send(f(0x205, &42i32.to_le_bytes()));
    assert_eq!(
        bus.node(0).unwrap().od().get(0x2006, 0),
        Some(&Value::I32(42))
    );
    nmt(&mut bus, NmtCommand::Stop, ID);
    bus.send(f(0x205, &43i32.to_le_bytes()));
    bus.node_mut(0).unwrap().drain_events().count();
    bus.send(f(0x80, &[]));
    assert_eq!(
        bus.node(0).unwrap().od().get(0x2006, 0),
        Some(&Value::I32(42)),
        "stopped"
    );
    assert_eq!(
        bus.node_mut(0).unwrap().poll_event(),
        None,
        "no SYNC event in stopped"
    );
    nmt(&mut bus, NmtCommand::EnterPreOperational, ID);
    bus.send(f(0x80, &[]));
    assert_eq!(
        bus.node_mut(0).unwrap().poll_event(),
        Some(NodeEvent::NmtStateChanged {
            from: NmtState::Stopped,
            to: NmtState::PreOperational
        })
    );
    assert_eq!(
        bus.node_mut(0).unwrap().poll_event(),
        Some(NodeEvent::Sync { counter: None })
    );
}
