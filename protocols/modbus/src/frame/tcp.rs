//! Modbus TCP framing (Modbus Messaging on TCP/IP Implementation Guide V1.0b §3.1.3): a 7-byte
//! MBAP header (transaction id, protocol id 0, length, unit id) before the PDU.

use crate::pdu::limits::MAX_PDU;

/// MBAP header length.
pub const MBAP_LEN: usize = 7;
/// Largest TCP ADU: MBAP + 253-byte PDU.
pub const MAX_ADU: usize = MBAP_LEN + MAX_PDU;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    pub transaction: u16,
    pub protocol: u16,
    pub unit: u8,
}

/// What the bytes at the front of a connection's buffer are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decoded<'a> {
    /// A complete request; `consumed` bytes belong to it.
    Frame {
        header: Header,
        pdu: &'a [u8],
        consumed: usize,
    },
    /// Not enough bytes yet.
    NeedMore,
    /// A well-delimited frame that is not Modbus (protocol id ≠ 0): skip it, no answer.
    Discard { consumed: usize, protocol: u16 },
    /// The length field cannot be right (no room for a function code, or beyond 260 bytes):
    /// the stream cannot be resynchronised, close the connection.
    Close { length: u16 },
}

/// Look at the front of `buf`. Never panics.
pub fn decode(buf: &[u8]) -> Decoded<'_> {
    if buf.len() < MBAP_LEN {
        return Decoded::NeedMore;
    }
    let word = |i: usize| u16::from_be_bytes([buf[i], buf[i + 1]]);
    let (transaction, protocol, length) = (word(0), word(2), word(4));
    // `length` counts the unit id and the PDU.
    if length < 2 || length as usize > 1 + MAX_PDU {
        return Decoded::Close { length };
    }
    let total = 6 + length as usize;
    if buf.len() < total {
        return Decoded::NeedMore;
    }
    if protocol != 0 {
        return Decoded::Discard {
            consumed: total,
            protocol,
        };
    }
    Decoded::Frame {
        header: Header {
            transaction,
            protocol,
            unit: buf[6],
        },
        pdu: &buf[MBAP_LEN..total],
        consumed: total,
    }
}

/// Append a response ADU: the request's transaction and unit ids, then `pdu`.
pub fn encode(header: Header, pdu: &[u8], out: &mut Vec<u8>) {
    out.extend_from_slice(&header.transaction.to_be_bytes());
    out.extend_from_slice(&0u16.to_be_bytes());
    out.extend_from_slice(&((pdu.len() + 1) as u16).to_be_bytes());
    out.push(header.unit);
    out.extend_from_slice(pdu);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_partial_frames_and_bad_headers() {
        let req = [
            0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x11, 0x03, 0x00, 0x6B, 0x00, 0x03,
        ];
        match decode(&req) {
            Decoded::Frame {
                header,
                pdu,
                consumed,
            } => {
                assert_eq!(header.transaction, 1);
                assert_eq!(header.unit, 0x11);
                assert_eq!(pdu, &[0x03, 0x00, 0x6B, 0x00, 0x03]);
                assert_eq!(consumed, 12);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(decode(&req[..11]), Decoded::NeedMore);
        assert_eq!(decode(&req[..3]), Decoded::NeedMore);
        let mut other_protocol = req;
        other_protocol[3] = 1;
        assert_eq!(
            decode(&other_protocol),
            Decoded::Discard {
                consumed: 12,
                protocol: 1
            }
        );
        assert_eq!(
            decode(&[0, 1, 0, 0, 1, 0, 1]),
            Decoded::Close { length: 256 }
        );
        assert_eq!(decode(&[0, 1, 0, 0, 0, 1, 1]), Decoded::Close { length: 1 });
        let mut out = vec![];
        encode(
            Header {
                transaction: 7,
                protocol: 0,
                unit: 0xFF,
            },
            &[0x83, 0x02],
            &mut out,
        );
        assert_eq!(out, [0, 7, 0, 0, 0, 3, 0xFF, 0x83, 0x02]);
    }
}
