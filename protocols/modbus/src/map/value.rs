//! Point types and word orders: how a value lies in 16-bit registers.
//!
//! Modbus itself only has 16-bit big-endian registers (Application Protocol V1.1b3 §4.2); wider
//! values are a device's convention. The names follow the usual byte-order letters for a 32-bit
//! value A B C D (A most significant): `abcd` is big-endian, high word first; `cdab` low word
//! first (the HIMC, digest 004 §8); `badc` bytes swapped in each word; `dcba` fully little
//! endian. 64-bit values extend the same rule to four words.

use serde::{Deserialize, Serialize};

/// The type of a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PointType {
    /// One bit (coils, discrete inputs) or 0/1 in one register.
    Bool,
    U16,
    I16,
    U32,
    I32,
    F32,
    F64,
    /// ASCII text, two characters per register, first character in the high byte, padded with
    /// NUL; `length` registers.
    String,
}

/// How the words (and bytes) of a value wider than one register are ordered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WordOrder {
    #[default]
    Abcd,
    Cdab,
    Badc,
    Dcba,
}

impl PointType {
    /// Registers the type occupies (`string`: its `length`).
    pub fn registers(self, string_length: u16) -> u16 {
        match self {
            PointType::Bool | PointType::U16 | PointType::I16 => 1,
            PointType::U32 | PointType::I32 | PointType::F32 => 2,
            PointType::F64 => 4,
            PointType::String => string_length,
        }
    }

    /// Whether a value is an integer type (values are rounded to it).
    pub fn is_integer(self) -> bool {
        matches!(
            self,
            PointType::U16 | PointType::I16 | PointType::U32 | PointType::I32
        )
    }

    /// The raw value range an integer type can hold.
    fn range(self) -> (f64, f64) {
        match self {
            PointType::Bool => (0.0, 1.0),
            PointType::U16 => (0.0, f64::from(u16::MAX)),
            PointType::I16 => (f64::from(i16::MIN), f64::from(i16::MAX)),
            PointType::U32 => (0.0, f64::from(u32::MAX)),
            PointType::I32 => (f64::from(i32::MIN), f64::from(i32::MAX)),
            PointType::F32 | PointType::F64 | PointType::String => (f64::MIN, f64::MAX),
        }
    }
}

/// Put the big-endian bytes of a value (most significant first) into words in `order`.
fn order_words(be: &[u8], order: WordOrder, out: &mut [u16]) {
    let n = out.len();
    for (i, w) in out.iter_mut().enumerate() {
        // Word i counted from the most significant, before reordering.
        let (word, swap_bytes) = match order {
            WordOrder::Abcd => (i, false),
            WordOrder::Cdab => (n - 1 - i, false),
            WordOrder::Badc => (i, true),
            WordOrder::Dcba => (n - 1 - i, true),
        };
        let (hi, lo) = (be[2 * word], be[2 * word + 1]);
        *w = if swap_bytes {
            u16::from_be_bytes([lo, hi])
        } else {
            u16::from_be_bytes([hi, lo])
        };
    }
}

/// The inverse of [`order_words`].
fn unorder_words(words: &[u16], order: WordOrder, be: &mut [u8]) {
    let n = words.len();
    for (i, &w) in words.iter().enumerate() {
        let (word, swap_bytes) = match order {
            WordOrder::Abcd => (i, false),
            WordOrder::Cdab => (n - 1 - i, false),
            WordOrder::Badc => (i, true),
            WordOrder::Dcba => (n - 1 - i, true),
        };
        let [hi, lo] = w.to_be_bytes();
        let (hi, lo) = if swap_bytes { (lo, hi) } else { (hi, lo) };
        be[2 * word] = hi;
        be[2 * word + 1] = lo;
    }
}

/// Encode an engineering value (already multiplied by the point's scale) into `out`, which has
/// exactly `registers()` words. Integers are rounded and saturate at their type's range: a read
/// never fails, and a value beyond the type is shown at its limit rather than wrapped. NaN
/// reads as 0 in integer types.
pub fn encode(value: f64, ty: PointType, order: WordOrder, out: &mut [u16]) {
    let (lo, hi) = ty.range();
    let int = |v: f64| -> f64 {
        if v.is_nan() {
            0.0
        } else {
            v.round().clamp(lo, hi)
        }
    };
    match ty {
        PointType::Bool => out[0] = u16::from(value != 0.0 && !value.is_nan()),
        PointType::U16 => out[0] = int(value) as u16,
        PointType::I16 => out[0] = int(value) as i16 as u16,
        PointType::U32 => order_words(&(int(value) as u32).to_be_bytes(), order, out),
        PointType::I32 => order_words(&(int(value) as i32).to_be_bytes(), order, out),
        PointType::F32 => order_words(&(value as f32).to_be_bytes(), order, out),
        PointType::F64 => order_words(&value.to_be_bytes(), order, out),
        PointType::String => out.fill(0),
    }
}

/// Decode the words of a written value into a number (before dividing by the scale). `None`
/// when the words are no value of the type: a bool register other than 0/1, a NaN or infinite
/// float.
pub fn decode(words: &[u16], ty: PointType, order: WordOrder) -> Option<f64> {
    let mut be = [0u8; 8];
    let v = match ty {
        PointType::Bool => match words[0] {
            0 => 0.0,
            1 => 1.0,
            _ => return None,
        },
        PointType::U16 => f64::from(words[0]),
        PointType::I16 => f64::from(words[0] as i16),
        PointType::U32 | PointType::I32 | PointType::F32 => {
            unorder_words(words, order, &mut be[..4]);
            let b = [be[0], be[1], be[2], be[3]];
            match ty {
                PointType::U32 => f64::from(u32::from_be_bytes(b)),
                PointType::I32 => f64::from(i32::from_be_bytes(b)),
                _ => f64::from(f32::from_be_bytes(b)),
            }
        }
        PointType::F64 => {
            unorder_words(words, order, &mut be);
            f64::from_be_bytes(be)
        }
        PointType::String => return None,
    };
    v.is_finite().then_some(v)
}

/// Text into `out` registers (truncated to fit, NUL padded).
pub fn encode_string(text: &str, out: &mut [u16]) {
    out.fill(0);
    for (i, pair) in text.as_bytes().chunks(2).take(out.len()).enumerate() {
        out[i] = u16::from_be_bytes([pair[0], pair.get(1).copied().unwrap_or(0)]);
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn words(value: f64, ty: PointType, order: WordOrder) -> Vec<u16> {
        let mut out = vec![0; ty.registers(0) as usize];
        encode(value, ty, order, &mut out);
        out
    }

    #[test]
    fn the_himc_float_example_is_low_word_first() {
        // Digest 004 §8: 0.85 = 0x3F59999A → reg N = 0x999A, N+1 = 0x3F59.
        assert_eq!(
            words(0.85, PointType::F32, WordOrder::Cdab),
            [0x999A, 0x3F59]
        );
        assert_eq!(
            words(0.85, PointType::F32, WordOrder::Abcd),
            [0x3F59, 0x999A]
        );
        assert_eq!(
            words(0.85, PointType::F32, WordOrder::Badc),
            [0x593F, 0x9A99]
        );
        assert_eq!(
            words(0.85, PointType::F32, WordOrder::Dcba),
            [0x9A99, 0x593F]
        );
    }

    #[test]
    fn every_type_and_order_round_trips() {
        let orders = [
            WordOrder::Abcd,
            WordOrder::Cdab,
            WordOrder::Badc,
            WordOrder::Dcba,
        ];
        let cases: &[(PointType, &[f64])] = &[
            (PointType::Bool, &[0.0, 1.0]),
            (PointType::U16, &[0.0, 1.0, 65535.0]),
            (PointType::I16, &[-32768.0, -1.0, 32767.0]),
            (PointType::U32, &[0.0, 70000.0, 4294967295.0]),
            (PointType::I32, &[-2147483648.0, -70000.0, 2147483647.0]),
            (PointType::F32, &[-1.5, 0.0, 3.0e10_f32 as f64]),
            (PointType::F64, &[-1.0e-300, 0.1, 123456.789]),
        ];
        for &order in &orders {
            for &(ty, values) in cases {
                for &v in values {
                    let w = words(v, ty, order);
                    assert_eq!(decode(&w, ty, order), Some(v), "{ty:?} {order:?} {v}");
                }
            }
        }
    }

    #[test]
    fn integers_round_and_saturate_and_bad_words_are_refused() {
        assert_eq!(words(2.6, PointType::U16, WordOrder::Abcd), [3]);
        assert_eq!(words(-5.0, PointType::U16, WordOrder::Abcd), [0]);
        assert_eq!(words(1e9, PointType::I16, WordOrder::Abcd), [0x7FFF]);
        assert_eq!(words(f64::NAN, PointType::I32, WordOrder::Abcd), [0, 0]);
        assert_eq!(
            words(-2.0, PointType::I32, WordOrder::Cdab),
            [0xFFFE, 0xFFFF]
        );
        assert_eq!(decode(&[2], PointType::Bool, WordOrder::Abcd), None);
        // 0x7FC00000 is a NaN: not a value anyone meant to write.
        assert_eq!(decode(&[0x7FC0, 0], PointType::F32, WordOrder::Abcd), None);
    }

    #[test]
    fn strings_are_high_byte_first_and_nul_padded() {
        let mut out = [0xFFFF; 3];
        encode_string("HIMC", &mut out);
        assert_eq!(out, [0x4849, 0x4D43, 0]);
        encode_string("abc", &mut out);
        assert_eq!(out, [0x6162, 0x6300, 0]);
        encode_string("too long for it", &mut out);
        assert_eq!(out, [0x746F, 0x6F20, 0x6C6F]);
    }
}
