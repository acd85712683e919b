//! How long a classic CAN frame occupies the bus: its bit count (with bit stuffing, worst case
//! or computed from the frame's actual bits) at a given bit rate.
//!
//! Field sizes are ISO 11898-1's: a standard frame is SOF, 11-bit id, RTR, IDE, r0, DLC(4),
//! data, CRC(15), CRC delimiter, ACK slot and delimiter, EOF(7) = 44 + 8·n bits; an extended
//! frame adds SRR, IDE, 18 id bits and r1 = 64 + 8·n. The 3-bit intermission that must follow
//! is counted with the frame, so back-to-back frames give the bus's real maximum rate. Stuff
//! bits are inserted after 5 equal bits from SOF to the end of the CRC (34 + 8·n bits standard,
//! 54 + 8·n extended); the worst case there is ⌊(g − 1) / 4⌋ (Davis et al., "Controller Area
//! Network (CAN) schedulability analysis", 2007).

use std::time::Duration;

use crate::frame::{FrameKind, WireFrame};

/// Intermission between frames (3 recessive bits).
pub const INTERMISSION_BITS: u32 = 3;

/// How stuff bits are counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Stuffing {
    /// The most stuff bits a frame of that format and length can need: the bound that
    /// schedulability analysis uses.
    #[default]
    WorstCase,
    /// The stuff bits this frame's id, data and CRC actually need.
    Exact,
    /// No stuff bits (the lower bound).
    None,
}

/// A bus's bit rate and stuffing rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BitTiming {
    /// Bits per second (e.g. 1 000 000 for 1 Mbit/s), > 0.
    pub bitrate: u32,
    pub stuffing: Stuffing,
}

impl BitTiming {
    /// A bit rate with worst-case stuffing; `None` for 0.
    pub fn new(bitrate: u32) -> Option<Self> {
        (bitrate > 0).then_some(Self {
            bitrate,
            stuffing: Stuffing::WorstCase,
        })
    }

    pub fn with_stuffing(self, stuffing: Stuffing) -> Self {
        Self { stuffing, ..self }
    }

    /// Bus time of `bits` bits.
    pub fn duration_of(&self, bits: u32) -> Duration {
        let nanos = u64::from(bits) * 1_000_000_000 / u64::from(self.bitrate.max(1));
        Duration::from_nanos(nanos)
    }

    /// Bus time of `frame`, intermission included.
    pub fn frame_time(&self, frame: &WireFrame) -> Duration {
        self.duration_of(frame_bits(frame, self.stuffing))
    }
}

/// Bits `frame` occupies on the bus, including stuff bits (per `stuffing`) and the
/// intermission. Error frames are controller reports, not transmissions: 0.
pub fn frame_bits(frame: &WireFrame, stuffing: Stuffing) -> u32 {
    if frame.kind() == FrameKind::Error {
        return 0;
    }
    let data_bits = 8 * frame.data().len() as u32;
    let (fixed, stuffed_region) = if frame.is_extended() {
        (64, 54)
    } else {
        (44, 34)
    };
    let stuff = match stuffing {
        Stuffing::None => 0,
        Stuffing::WorstCase => (stuffed_region + data_bits - 1) / 4,
        Stuffing::Exact => exact_stuff_bits(frame),
    };
    fixed + data_bits + stuff + INTERMISSION_BITS
}

/// The bits from SOF to the end of the data field, most significant first, in a u128 (at
/// most 1 + 38 + 64 = 103 bits), and their count.
fn header_and_data_bits(frame: &WireFrame) -> (u128, u32) {
    let mut bits = Bits::default();
    bits.push(0, 1); // SOF, dominant
    let id = frame.id().raw();
    let remote = u32::from(frame.is_remote());
    if frame.is_extended() {
        bits.push(id >> 18, 11); // base id
        bits.push(1, 1); // SRR, recessive
        bits.push(1, 1); // IDE, recessive: extended
        bits.push(id & 0x3FFFF, 18);
        bits.push(remote, 1);
        bits.push(0, 2); // r1, r0
    } else {
        bits.push(id, 11);
        bits.push(remote, 1);
        bits.push(0, 2); // IDE (dominant: standard), r0
    }
    bits.push(u32::from(frame.dlc()), 4);
    for &byte in frame.data() {
        bits.push(u32::from(byte), 8);
    }
    (bits.value, bits.count)
}

#[derive(Default)]
struct Bits {
    value: u128,
    count: u32,
}

impl Bits {
    fn push(&mut self, value: u32, width: u32) {
        let mask = (1u128 << width) - 1;
        self.value = (self.value << width) | (u128::from(value) & mask);
        self.count += width;
    }
}

/// CAN's CRC-15 (polynomial 0x4599) over the `count` low bits of `bits`, first bit first.
fn crc15(bits: u128, count: u32) -> u32 {
    let mut crc: u32 = 0;
    for i in (0..count).rev() {
        let next = ((bits >> i) & 1) as u32;
        let top = (crc >> 14) & 1;
        crc = (crc << 1) & 0x7FFF;
        if next ^ top == 1 {
            crc ^= 0x4599;
        }
    }
    crc
}

/// Stuff bits the transmitter inserts from SOF to the end of the CRC: after 5 equal bits a
/// bit of the other value, which itself starts the next run.
fn exact_stuff_bits(frame: &WireFrame) -> u32 {
    let (bits, count) = header_and_data_bits(frame);
    let crc = crc15(bits, count);
    let all = (bits << 15) | u128::from(crc);
    let total = count + 15;
    let mut stuffed = 0;
    let mut last = 2u8; // no previous bit
    let mut run = 0;
    for i in (0..total).rev() {
        let bit = ((all >> i) & 1) as u8;
        if bit == last {
            run += 1;
        } else {
            last = bit;
            run = 1;
        }
        if run == 5 {
            stuffed += 1;
            // The stuff bit is the complement and begins a new run of length 1.
            last ^= 1;
            run = 1;
        }
    }
    stuffed
}

/// Arbitration priority: the bits a node sends from the id to the RTR bit, dominant (0)
/// winning, so the lower key wins. A standard frame beats an extended one with the same base
/// id (its RTR/IDE bits are dominant where the extended frame sends SRR/IDE recessive), and a
/// data frame beats a remote frame with the same id.
pub fn arbitration_key(frame: &WireFrame) -> u32 {
    let id = frame.id().raw();
    let remote = u32::from(frame.is_remote());
    if frame.is_extended() {
        // base(11) SRR=1 IDE=1 ext(18) RTR
        ((id >> 18) << 21) | (1 << 20) | (1 << 19) | ((id & 0x3FFFF) << 1) | remote
    } else {
        // id(11) RTR IDE=0, then nothing: the extended frame still sending loses or ties later
        (id << 21) | (remote << 20)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use crate::frame::CanId;

    #[test]
    fn worst_case_bits_match_the_literature() {
        let full_std = WireFrame::standard(0x123, &[0; 8]).unwrap();
        let full_ext = WireFrame::extended(0x123, &[0; 8]).unwrap();
        // 135 and 160 bits incl. the 3-bit intermission (Davis et al. 2007, eq. 1).
        assert_eq!(frame_bits(&full_std, Stuffing::WorstCase), 135);
        assert_eq!(frame_bits(&full_ext, Stuffing::WorstCase), 160);
        assert_eq!(frame_bits(&full_std, Stuffing::None), 111);
        let empty = WireFrame::standard(0, &[]).unwrap();
        assert_eq!(frame_bits(&empty, Stuffing::None), 47);
        let one_mbit = BitTiming::new(1_000_000).unwrap();
        assert_eq!(one_mbit.frame_time(&full_std), Duration::from_micros(135));
    }

    #[test]
    fn exact_stuffing_counts_runs() {
        // id 0, no data: SOF + 11 zeros + RTR/IDE/r0 zeros + DLC 0000 = 19 dominant bits,
        // then the CRC of all zeros (0) = 15 more: 34 zeros, a stuff bit after each 5.
        let zeros = WireFrame::standard(0, &[]).unwrap();
        assert_eq!(exact_stuff_bits(&zeros), 6);
        // Alternating bits need none in the data; the count never exceeds the worst case.
        for data in [[0x55u8; 8], [0xFF; 8], [0; 8], [0x0F; 8]] {
            for frame in [
                WireFrame::standard(0x555, &data).unwrap(),
                WireFrame::extended(0x1555_5555, &data).unwrap(),
            ] {
                let exact = frame_bits(&frame, Stuffing::Exact);
                assert!(exact <= frame_bits(&frame, Stuffing::WorstCase), "{frame}");
                assert!(exact >= frame_bits(&frame, Stuffing::None), "{frame}");
            }
        }
        assert!(exact_stuff_bits(&WireFrame::standard(0x7FF, &[0xFF; 8]).unwrap()) >= 15);
    }

    #[test]
    fn crc15_of_a_known_frame() {
        // 0x123 with no data: CRC checked against an independent bitwise implementation
        // of the polynomial division (x^15 + x^14 + x^10 + x^8 + x^7 + x^4 + x^3 + 1).
        let frame = WireFrame::standard(0x123, &[]).unwrap();
        let (bits, count) = header_and_data_bits(&frame);
        assert_eq!(count, 19);
        let mut reg: u32 = 0;
        for i in (0..count).rev() {
            reg = (reg << 1) | ((bits >> i) & 1) as u32;
        }
        // Long division of the message followed by 15 zero bits.
        let mut rem: u64 = u64::from(reg) << 15;
        for shift in (0..count).rev() {
            if rem & (1 << (shift + 15)) != 0 {
                rem ^= 0xC599 << shift;
            }
        }
        assert_eq!(crc15(bits, count), rem as u32);
    }

    #[test]
    fn arbitration_order() {
        let std = |id| WireFrame::standard(id, &[]).unwrap();
        let ext = |id| WireFrame::extended(id, &[]).unwrap();
        let rtr = WireFrame::remote(CanId::standard(0x100).unwrap(), 0).unwrap();
        assert!(arbitration_key(&std(0x100)) < arbitration_key(&std(0x101)));
        assert!(arbitration_key(&std(0x100)) < arbitration_key(&rtr));
        // Same base id: standard data, standard remote, then extended.
        assert!(arbitration_key(&rtr) < arbitration_key(&ext(0x100 << 18)));
        assert!(arbitration_key(&ext(0x0FF << 18 | 0x3FFFF)) < arbitration_key(&std(0x100)));
    }
}
