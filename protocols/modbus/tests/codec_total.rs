// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! The codec is total: any bytes decode to a request, a refusal, or a framing verdict, never a
//! panic, and anything it accepts re-encodes consistently.

use mcemu_modbus::frame::{rtu, tcp};
use mcemu_modbus::pdu::{decode_request, encode_response, Response};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 20_000, ..ProptestConfig::default() })]

    #[test]
    fn any_bytes_decode_without_panicking(bytes in prop::collection::vec(any::<u8>(), 0..300)) {
        match decode_request(&bytes) {
            Ok(request) => prop_assert_eq!(Some(&request.function()), bytes.first()),
            Err(refusal) => {
                let mut out = vec![];
                encode_response(&Response::from(refusal), &mut out);
                prop_assert_eq!(out.len(), 2);
                prop_assert!(out[0] & 0x80 != 0);
            }
        }
        let _ = tcp::decode(&bytes);
        let _ = rtu::decode(&bytes);
        let _ = rtu::request_length(&bytes);
    }

    #[test]
    fn rtu_frames_round_trip(unit in any::<u8>(), pdu in prop::collection::vec(any::<u8>(), 1..253)) {
        let mut frame = vec![];
        rtu::encode(unit, &pdu, &mut frame);
        prop_assert_eq!(rtu::decode(&frame), rtu::Decoded::Frame { unit, pdu: &pdu });
    }

    #[test]
    fn tcp_frames_round_trip(t in any::<u16>(), unit in any::<u8>(), pdu in prop::collection::vec(any::<u8>(), 1..253)) {
        let mut frame = vec![];
        let header = tcp::Header { transaction: t, protocol: 0, unit };
        tcp::encode(header, &pdu, &mut frame);
        prop_assert_eq!(
            tcp::decode(&frame),
            tcp::Decoded::Frame { header, pdu: &pdu, consumed: frame.len() }
        );
    }
}
