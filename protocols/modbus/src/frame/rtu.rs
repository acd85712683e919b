//! Modbus RTU framing (Modbus over Serial Line V1.02 §2.5.1): address, PDU, CRC-16 low byte
//! first. On a serial line a frame ends with 3.5 characters of silence; over TCP (RTU over
//! TCP) there is no silence, so a request's length is predicted from its first bytes.

use std::time::Duration;

use crate::pdu::fc;

/// Largest RTU ADU: address + 253-byte PDU + CRC.
pub const MAX_ADU: usize = 256;
/// Broadcast address: writes execute, nothing is answered.
pub const BROADCAST: u8 = 0;

/// CRC-16/MODBUS (polynomial 0xA001 reflected, initial 0xFFFF).
pub fn crc16(data: &[u8]) -> u16 {
    let mut crc: u16 = 0xFFFF;
    for &b in data {
        crc ^= u16::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xA001
            } else {
                crc >> 1
            };
        }
    }
    crc
}

/// A frame received between two silences.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decoded<'a> {
    Frame {
        unit: u8,
        pdu: &'a [u8],
    },
    /// Shorter than address + function + CRC.
    TooShort,
    /// Longer than 256 bytes.
    TooLong,
    /// The CRC does not match: dropped and counted, never answered.
    BadCrc,
}

pub fn decode(frame: &[u8]) -> Decoded<'_> {
    if frame.len() < 4 {
        return Decoded::TooShort;
    }
    if frame.len() > MAX_ADU {
        return Decoded::TooLong;
    }
    let (body, crc) = frame.split_at(frame.len() - 2);
    if crc16(body).to_le_bytes() != [crc[0], crc[1]] {
        return Decoded::BadCrc;
    }
    Decoded::Frame {
        unit: body[0],
        pdu: &body[1..],
    }
}

/// Append a response frame.
pub fn encode(unit: u8, pdu: &[u8], out: &mut Vec<u8>) {
    let start = out.len();
    out.push(unit);
    out.extend_from_slice(pdu);
    let crc = crc16(&out[start..]);
    out.extend_from_slice(&crc.to_le_bytes());
}

/// The length a request frame will have, from its first bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Length {
    Known(usize),
    NeedMore,
    /// The function code does not tell (unknown function): the stream cannot be delimited.
    Unknown,
}

/// Predict the total length (address … CRC) of the request starting at `buf[0]`.
pub fn request_length(buf: &[u8]) -> Length {
    let Some(&function) = buf.get(1) else {
        return Length::NeedMore;
    };
    let counted = |count_at: usize, fixed: usize| match buf.get(count_at) {
        Some(&n) => Length::Known(fixed + n as usize),
        None => Length::NeedMore,
    };
    match function {
        fc::READ_COILS
        | fc::READ_DISCRETE_INPUTS
        | fc::READ_HOLDING_REGISTERS
        | fc::READ_INPUT_REGISTERS
        | fc::WRITE_SINGLE_COIL
        | fc::WRITE_SINGLE_REGISTER
        | fc::DIAGNOSTICS => Length::Known(8),
        fc::WRITE_MULTIPLE_COILS | fc::WRITE_MULTIPLE_REGISTERS => counted(6, 9),
        fc::REPORT_SERVER_ID => Length::Known(4),
        fc::MASK_WRITE_REGISTER => Length::Known(10),
        fc::READ_WRITE_MULTIPLE_REGISTERS => counted(10, 13),
        fc::ENCAPSULATED_INTERFACE => Length::Known(7),
        _ => Length::Unknown,
    }
}

/// Silence that ends a frame: 3.5 character times at `baud` with 11-bit characters, fixed at
/// 1.75 ms above 19 200 baud (Modbus over Serial Line §2.5.1.1).
pub fn inter_frame_silence(baud: u32) -> Duration {
    if baud > 19_200 || baud == 0 {
        Duration::from_micros(1750)
    } else {
        Duration::from_secs_f64(3.5 * 11.0 / f64::from(baud))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hex(s: &str) -> Vec<u8> {
        s.split_whitespace()
            .map(|b| u8::from_str_radix(b, 16).unwrap())
            .collect()
    }

    #[test]
    fn crc_of_the_textbook_frame_and_the_cpu226h_frames() {
        // `01 03 00 00 00 0A C5 CD` and CPU 226H §10.1 networks 3, 4, 5 (corrected), 6.
        for frame in [
            "01 03 00 00 00 0A C5 CD",
            "02 10 01 19 00 02 04 00 00 00 01 F1 DD",
            "02 06 01 44 00 64 C9 FB",
            "02 10 00 71 00 02 04 00 64 00 C8 7A 4A",
            "02 03 00 C8 00 1E 44 0F",
        ] {
            let f = hex(frame);
            assert!(
                matches!(decode(&f), Decoded::Frame { unit: _, pdu: _ }),
                "{frame}"
            );
        }
        let mut out = vec![];
        encode(2, &hex("10 01 19 00 02"), &mut out);
        assert_eq!(out, hex("02 10 01 19 00 02 91 C0"));
        let mut bad = hex("02 06 01 44 00 64 C9 FB");
        bad[7] ^= 1;
        assert_eq!(decode(&bad), Decoded::BadCrc);
        assert_eq!(decode(&[1, 3, 0]), Decoded::TooShort);
        assert_eq!(decode(&[0; 300]), Decoded::TooLong);
    }

    #[test]
    fn request_lengths() {
        assert_eq!(request_length(&hex("02 03 00 C8")), Length::Known(8));
        assert_eq!(request_length(&hex("02 10 01 19 00 02")), Length::NeedMore);
        assert_eq!(
            request_length(&hex("02 10 01 19 00 02 04")),
            Length::Known(13)
        );
        assert_eq!(request_length(&hex("02 42")), Length::Unknown);
        assert_eq!(request_length(&[2]), Length::NeedMore);
    }

    #[test]
    fn silence_follows_the_baud_rate() {
        assert_eq!(inter_frame_silence(115_200), Duration::from_micros(1750));
        let t = inter_frame_silence(9600).as_secs_f64();
        assert!((t - 0.004_010_416).abs() < 1e-6, "{t}");
    }
}
