//! The node on arbitrary traffic: the input is a sequence of frames (a time step, an identifier,
//! a length with the RTR bit, data), for a node on the sample dictionary. Never panics; after
//! any sequence the node still answers an SDO upload of 0x1000 (unless the traffic stopped it or
//! left it unconfigured, where CiA 301 says it must stay silent) and reports sane counters.

#![no_main]

use std::time::Duration;

use libfuzzer_sys::fuzz_target;
use mcemu_canopen::bus::sample_dictionary;
use mcemu_canopen::{CanFrame, NmtState, Node, NodeConfig};

const ID: u8 = 5;

fuzz_target!(|data: &[u8]| {
    let config = NodeConfig {
        node_id: ID,
        ..NodeConfig::default()
    };
    let Ok(mut node) = Node::new(config, sample_dictionary()) else {
        return;
    };
    let mut now = Duration::ZERO;
    let mut sent = node.start(now).len() as u64;
    let mut rest = data;
    // [dt ms, id hi (3 bits), id lo, len|rtr, data…]
    while rest.len() >= 4 {
        now += Duration::from_millis(u64::from(rest[0]));
        let id = u16::from(rest[1] & 0x07) << 8 | u16::from(rest[2]);
        let len = usize::from(rest[3] & 0x0F).min(8);
        let rtr = rest[3] & 0x80 != 0;
        let body = rest.get(4..4 + len).unwrap_or(&rest[4..]);
        let frame = if rtr {
            CanFrame::remote(id, len as u8)
        } else {
            CanFrame::new(id, body)
        };
        if let Ok(frame) = frame {
            sent += node.on_frame(&frame, now).len() as u64;
        }
        sent += node.on_tick(now).len() as u64;
        rest = &rest[(4 + len).min(rest.len())..];
    }
    assert!(node.counters().frames_out <= sent + 1);
    if node.node_id() != ID || node.nmt_state() == NmtState::Stopped {
        return;
    }
    if node.nmt_state() == NmtState::Initialising {
        return;
    }
    // Whatever came before (an SDO transfer half done included), a fresh upload request is
    // answered: an abort of the old transfer or the value.
    now += Duration::from_secs(10);
    let _ = node.on_tick(now);
    let upload = CanFrame::new(0x600 + u16::from(ID), &[0x40, 0x00, 0x10, 0, 0, 0, 0, 0])
        .expect("a valid frame");
    let out = node.on_frame(&upload, now);
    assert!(
        out.iter().any(|f| f.id() == 0x580 + u16::from(ID)),
        "no SDO answer after the traffic: {out:?}"
    );
});
