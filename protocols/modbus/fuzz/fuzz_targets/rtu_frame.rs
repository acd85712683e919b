//! `frame::rtu::decode` and `frame::rtu::request_length` on arbitrary bytes: never panic; a
//! frame with a good CRC re-encodes to itself; and a decodable request frame has the length
//! that `request_length` predicts from its first bytes (RTU over TCP delimits requests that
//! way), except FC 8 with other than 2 data bytes, which the prediction cannot know. Then the
//! input is consumed as an RTU-over-TCP stream.
//!
//! The first input byte chooses whether the rest gets a correct CRC appended (odd) or is used
//! as it is (even), so the fuzzer reaches the decoded paths without forging CRCs.

#![no_main]

use libfuzzer_sys::fuzz_target;
use mcemu_modbus::frame::rtu::{self, Decoded, Length, MAX_ADU};
use mcemu_modbus::pdu::{decode_request, Request};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let mut frame = rest.to_vec();
    if mode & 1 == 1 {
        let crc = rtu::crc16(&frame);
        frame.extend_from_slice(&crc.to_le_bytes());
    }

    match rtu::decode(&frame) {
        Decoded::Frame { unit, pdu } => {
            assert_eq!(unit, frame[0]);
            assert_eq!(pdu.len() + 3, frame.len());
            let mut out = Vec::new();
            rtu::encode(unit, pdu, &mut out);
            assert_eq!(out, frame);
            if let Ok(request) = decode_request(pdu) {
                let predictable = match request {
                    Request::Diagnostics { data, .. } => data.len() == 2,
                    _ => true,
                };
                if predictable {
                    assert_eq!(
                        rtu::request_length(&frame),
                        Length::Known(frame.len()),
                        "{request:?}"
                    );
                }
            }
        }
        Decoded::TooShort => assert!(frame.len() < 4),
        Decoded::TooLong => assert!(frame.len() > MAX_ADU),
        Decoded::BadCrc => assert!((4..=MAX_ADU).contains(&frame.len())),
    }

    // RTU over TCP: delimit requests by predicted length, as the transport will.
    let mut buf = frame.as_slice();
    loop {
        match rtu::request_length(buf) {
            Length::Known(n) => {
                assert!(n >= 4, "{n}");
                if n > buf.len() {
                    break;
                }
                let _ = rtu::decode(&buf[..n]);
                buf = &buf[n..];
            }
            Length::NeedMore => {
                assert!(buf.len() < 11, "{} bytes", buf.len());
                break;
            }
            Length::Unknown => break,
        }
    }
});
