// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! The server is total: any unit id and any PDU bytes, on either framing, give a well-formed
//! response PDU or silence, never a panic; broadcasts are never answered.

use std::sync::Arc;

use mcemu_modbus::memory::MemoryModel;
use mcemu_modbus::model::Peer;
use mcemu_modbus::pdu::limits::MAX_PDU;
use mcemu_modbus::server::{Outcome, Server};
use mcemu_modbus::state::{Framing, FrontendState};
use proptest::prelude::*;

fn server(framing: Framing) -> Server<MemoryModel> {
    let model = Arc::new(MemoryModel::new().with_units([1, 2, 0xFF]));
    Server::new(
        model,
        Arc::new(FrontendState::new("t", framing, &[]).unwrap()),
    )
}

/// PDUs that start with a function code the server knows, so decoding gets past the first byte.
fn pdu() -> impl Strategy<Value = Vec<u8>> {
    let known = prop::sample::select(vec![1u8, 2, 3, 4, 5, 6, 8, 15, 16, 17, 22, 23, 43]);
    prop_oneof![
        prop::collection::vec(any::<u8>(), 0..260),
        (known, prop::collection::vec(any::<u8>(), 0..254)).prop_map(|(f, mut rest)| {
            rest.insert(0, f);
            rest
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3_000, ..ProptestConfig::default() })]

    #[test]
    fn any_request_gets_a_well_formed_answer(
        rtu in any::<bool>(),
        unit in prop::sample::select(vec![0u8, 1, 2, 7, 0xFF]),
        pdu in pdu(),
    ) {
        let framing = if rtu { Framing::Rtu } else { Framing::Tcp };
        let server = server(framing);
        let runtime = tokio::runtime::Builder::new_current_thread().enable_time().build().unwrap();
        let outcome = runtime.block_on(server.handle(unit, &pdu, &Peer::Serial("prop".into())));
        match outcome {
            Outcome::Reply(reply) => {
                prop_assert!(!(rtu && unit == 0), "a broadcast was answered");
                prop_assert!(reply.len() >= 2 && reply.len() <= MAX_PDU, "{reply:02X?}");
                // The reply carries the request's function code (with 0x80 on an exception).
                prop_assert_eq!(reply[0] & 0x7F, pdu.first().copied().unwrap_or(0) & 0x7F);
                if reply[0] & 0x80 != 0 {
                    prop_assert_eq!(reply.len(), 2);
                }
            }
            Outcome::Silent => {
                // Silence only for broadcasts, other units on RTU, and listen-only mode.
                let listen_only = server.state().listen_only();
                prop_assert!(
                    (rtu && (unit == 0 || unit == 7)) || listen_only,
                    "silent for unit {unit} {pdu:02X?}"
                );
            }
            // Only a `close` fault closes, and none is installed.
            Outcome::Close => prop_assert!(false, "closed for unit {unit} {pdu:02X?}"),
        }
    }
}
