//! `frame::tcp::decode` on an arbitrary byte stream, consuming frames in a loop as a
//! connection's read buffer would: never panics, always makes progress or stops, every frame
//! re-encodes to the bytes it came from, a frame's every proper prefix is `NeedMore`, and each
//! PDU goes through `pdu::decode_request`.

#![no_main]

use libfuzzer_sys::fuzz_target;
use mcemu_modbus::frame::tcp::{self, Decoded, MAX_ADU, MBAP_LEN};
use mcemu_modbus::pdu::decode_request;

fuzz_target!(|data: &[u8]| {
    let mut buf = data;
    let mut out = Vec::new();
    let mut first = true;
    loop {
        match tcp::decode(buf) {
            Decoded::Frame {
                header,
                pdu,
                consumed,
            } => {
                assert!(consumed <= buf.len() && consumed <= MAX_ADU);
                assert!(!pdu.is_empty());
                assert_eq!(consumed, MBAP_LEN + pdu.len());
                assert_eq!(header.protocol, 0);
                out.clear();
                tcp::encode(header, pdu, &mut out);
                assert_eq!(out, buf[..consumed]);
                if first {
                    // Bytes arriving one by one: nothing is a frame before the last one.
                    for n in 0..consumed {
                        assert_eq!(tcp::decode(&buf[..n]), Decoded::NeedMore, "prefix {n}");
                    }
                    first = false;
                }
                let _ = decode_request(pdu);
                buf = &buf[consumed..];
            }
            Decoded::Discard { consumed, protocol } => {
                assert_ne!(protocol, 0);
                assert!(consumed > MBAP_LEN && consumed <= buf.len() && consumed <= MAX_ADU);
                buf = &buf[consumed..];
            }
            Decoded::NeedMore => {
                assert!(buf.len() < MAX_ADU);
                break;
            }
            Decoded::Close { length } => {
                assert!(length < 2 || usize::from(length) > MAX_ADU - 6);
                break;
            }
        }
    }
});
