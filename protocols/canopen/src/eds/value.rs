//! Values as CiA 306 writes them (`DefaultValue`, `ParameterValue`, `LowLimit`, `HighLimit`):
//! integers in decimal, `0x` hex or leading-`0` octal, `$NODEID` expressions, reals, strings
//! and hex octets; and the way back, so a value written by [`format_value`] reads back equal.

use std::fmt;

use axes::od::{DataType, Value};

use super::error::Reason;

/// Node ids a `$NODEID` value is checked against at load: every id a node can have.
pub const NODE_IDS: std::ops::RangeInclusive<u8> = 1..=127;

/// A value read from a file: fixed, or relative to the node id (`$NODEID+0x180`), which is only
/// known when a dictionary is built for a node.
#[derive(Clone, Debug, PartialEq)]
pub enum EdsValue {
    Fixed(Value),
    /// `$NODEID + offset`, of an integer type; it fits the type for every node id 1–127
    /// (checked at load).
    NodeId {
        data_type: DataType,
        offset: i64,
    },
}

impl EdsValue {
    /// The value for `node_id`; `None` only if a `$NODEID` value does not fit its type for that
    /// id, which cannot happen for ids 1–127.
    pub fn resolve(&self, node_id: u8) -> Option<Value> {
        match self {
            EdsValue::Fixed(value) => Some(value.clone()),
            EdsValue::NodeId { data_type, offset } => {
                integer_value(i128::from(node_id) + i128::from(*offset), 10, *data_type)
            }
        }
    }

    pub fn depends_on_node_id(&self) -> bool {
        matches!(self, EdsValue::NodeId { .. })
    }

    pub fn data_type(&self) -> DataType {
        match self {
            EdsValue::Fixed(value) => value.data_type(),
            EdsValue::NodeId { data_type, .. } => *data_type,
        }
    }
}

/// The EDS spelling, which [`parse_value`] reads back.
impl fmt::Display for EdsValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EdsValue::Fixed(value) => f.write_str(&format_value(value)),
            EdsValue::NodeId { offset: 0, .. } => f.write_str("$NODEID"),
            EdsValue::NodeId { offset, .. } if *offset < 0 => {
                write!(f, "$NODEID-{:#X}", offset.unsigned_abs())
            }
            EdsValue::NodeId { offset, .. } => write!(f, "$NODEID+{offset:#X}"),
        }
    }
}

/// An integer literal and the base it was written in (hex and octal literals of signed types
/// may be two's-complement bit patterns: `0xFFFF` is an INTEGER16 −1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Literal {
    pub value: i128,
    pub radix: u32,
}

/// Parse `[+-]` then `0x…` (hex), `0…` (octal) or decimal digits.
pub(crate) fn parse_integer(text: &str) -> Result<Literal, &'static str> {
    let text = text.trim();
    let (negative, digits) = match text.as_bytes().first() {
        Some(b'-') => (true, text.get(1..).unwrap_or_default()),
        Some(b'+') => (false, text.get(1..).unwrap_or_default()),
        _ => (false, text),
    };
    let (radix, digits) = if let Some(hex) = digits
        .strip_prefix("0x")
        .or_else(|| digits.strip_prefix("0X"))
    {
        (16, hex)
    } else if digits.len() > 1 && digits.starts_with('0') {
        (8, digits.get(1..).unwrap_or_default())
    } else {
        (10, digits)
    };
    if digits.is_empty() {
        return Err("no digits");
    }
    let mut value: i128 = 0;
    for c in digits.chars() {
        let digit = c.to_digit(radix).ok_or(match radix {
            16 => "not a hex digit",
            8 => "a leading 0 means octal: digits 0–7 only",
            _ => "not a decimal digit",
        })?;
        value = value
            .checked_mul(i128::from(radix))
            .and_then(|v| v.checked_add(i128::from(digit)))
            .ok_or("too many digits")?;
    }
    Ok(Literal {
        value: if negative { -value } else { value },
        radix,
    })
}

/// An integer, or `$NODEID` plus an offset.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Integer {
    Literal(Literal),
    NodeId { offset: i128 },
}

const NODE_ID_FORMS: &str = "a $NODEID value is $NODEID, $NODEID+n, $NODEID-n or n+$NODEID";

/// Parse an integer literal or a `$NODEID` expression (CiA 306 §4.6.3; case-insensitive,
/// spaces allowed).
pub(crate) fn parse_integer_expr(text: &str) -> Result<Integer, &'static str> {
    let Some(at) = find_node_id(text) else {
        return parse_integer(text).map(Integer::Literal);
    };
    let before = text.get(..at).unwrap_or_default().trim();
    let after = text.get(at + NODEID.len()..).unwrap_or_default().trim();
    let unsigned = |s: &str| match parse_integer(s.trim()) {
        Ok(_) if s.trim_start().starts_with(['+', '-']) => Err(NODE_ID_FORMS),
        Ok(lit) => Ok(lit.value),
        Err(_) if find_node_id(s).is_some() => Err(NODE_ID_FORMS),
        Err(why) => Err(why),
    };
    let offset = match (before, after) {
        ("", "") => 0,
        ("", rest) => {
            if let Some(n) = rest.strip_prefix('+') {
                unsigned(n)?
            } else if let Some(n) = rest.strip_prefix('-') {
                -unsigned(n)?
            } else {
                return Err(NODE_ID_FORMS);
            }
        }
        (rest, "") => match rest.strip_suffix('+') {
            Some(n) => unsigned(n)?,
            None => return Err(NODE_ID_FORMS),
        },
        _ => return Err(NODE_ID_FORMS),
    };
    Ok(Integer::NodeId { offset })
}

const NODEID: &str = "$NODEID";

fn find_node_id(text: &str) -> Option<usize> {
    text.as_bytes()
        .windows(NODEID.len())
        .position(|w| w.eq_ignore_ascii_case(NODEID.as_bytes()))
}

/// An integer of `data_type`: in range, or for a hex or octal literal of a signed type, a bit
/// pattern of its width.
pub(crate) fn integer_value(v: i128, radix: u32, data_type: DataType) -> Option<Value> {
    let pattern = radix != 10;
    Some(match data_type {
        DataType::Integer8 => Value::I8(
            i8::try_from(v)
                .ok()
                .or_else(|| pattern.then(|| u8::try_from(v).ok().map(|u| u as i8))?)?,
        ),
        DataType::Integer16 => Value::I16(
            i16::try_from(v)
                .ok()
                .or_else(|| pattern.then(|| u16::try_from(v).ok().map(|u| u as i16))?)?,
        ),
        DataType::Integer32 => Value::I32(
            i32::try_from(v)
                .ok()
                .or_else(|| pattern.then(|| u32::try_from(v).ok().map(|u| u as i32))?)?,
        ),
        DataType::Integer64 => Value::I64(
            i64::try_from(v)
                .ok()
                .or_else(|| pattern.then(|| u64::try_from(v).ok().map(|u| u as i64))?)?,
        ),
        DataType::Unsigned8 => Value::U8(u8::try_from(v).ok()?),
        DataType::Unsigned16 => Value::U16(u16::try_from(v).ok()?),
        DataType::Unsigned32 => Value::U32(u32::try_from(v).ok()?),
        DataType::Unsigned64 => Value::U64(u64::try_from(v).ok()?),
        _ => return None,
    })
}

fn is_integer(data_type: DataType) -> bool {
    matches!(
        data_type,
        DataType::Integer8
            | DataType::Integer16
            | DataType::Integer32
            | DataType::Integer64
            | DataType::Unsigned8
            | DataType::Unsigned16
            | DataType::Unsigned32
            | DataType::Unsigned64
    )
}

/// The value of an empty `DefaultValue`: zero, false or empty.
pub(crate) fn zero(data_type: DataType) -> Value {
    match data_type {
        DataType::Boolean => Value::Bool(false),
        DataType::Real32 => Value::F32(0.0),
        DataType::Real64 => Value::F64(0.0),
        DataType::VisibleString => Value::String(String::new()),
        DataType::OctetString | DataType::Domain => Value::Bytes(Vec::new()),
        integer => integer_value(0, 10, integer).unwrap_or(Value::U8(0)),
    }
}

/// Parse a value of `data_type` as a file writes it. An empty text is [`zero`].
///
/// - integers: decimal, `0x` hex, leading-`0` octal; hex/octal may be a signed type's bit
///   pattern; `$NODEID`, `$NODEID+n`, `$NODEID-n`, `n+$NODEID` (checked for node ids 1–127);
/// - BOOLEAN: 0 or 1 (any integer spelling);
/// - REAL32/REAL64: decimal (`1.5`, `-2e3`, `inf`, `NaN`); a `0x` literal is the IEEE bit pattern;
/// - VISIBLE_STRING: the text itself, printable ASCII;
/// - OCTET_STRING, DOMAIN: hex digit pairs, spaces between them allowed, optional `0x`.
pub fn parse_value(text: &str, data_type: DataType) -> Result<EdsValue, Reason> {
    let text = text.trim();
    if text.is_empty() {
        return Ok(EdsValue::Fixed(zero(data_type)));
    }
    let not_a_number = |why| Reason::NotANumber {
        text: text.to_string(),
        why,
    };
    let out_of_range = || Reason::OutOfRange {
        text: text.to_string(),
        data_type,
    };
    if is_integer(data_type) {
        return match parse_integer_expr(text).map_err(not_a_number)? {
            Integer::Literal(lit) => integer_value(lit.value, lit.radix, data_type)
                .map(EdsValue::Fixed)
                .ok_or_else(out_of_range),
            Integer::NodeId { offset } => {
                for node_id in [*NODE_IDS.start(), *NODE_IDS.end()] {
                    if integer_value(i128::from(node_id) + offset, 10, data_type).is_none() {
                        return Err(Reason::NodeIdOutOfRange {
                            text: text.to_string(),
                            data_type,
                            node_id,
                        });
                    }
                }
                let offset = i64::try_from(offset).map_err(|_| out_of_range())?;
                Ok(EdsValue::NodeId { data_type, offset })
            }
        };
    }
    if find_node_id(text).is_some() && data_type != DataType::VisibleString {
        return Err(Reason::NodeIdNotInteger {
            text: text.to_string(),
            data_type,
        });
    }
    let value = match data_type {
        DataType::Boolean => match parse_integer(text).map_err(not_a_number)?.value {
            0 => Value::Bool(false),
            1 => Value::Bool(true),
            _ => {
                return Err(Reason::NotABool {
                    text: text.to_string(),
                })
            }
        },
        DataType::Real32 => match parse_integer(text) {
            Ok(Literal { value, radix: 16 }) => Value::F32(f32::from_bits(
                u32::try_from(value).map_err(|_| out_of_range())?,
            )),
            _ => Value::F32(text.parse().map_err(|_| not_a_number("not a real"))?),
        },
        DataType::Real64 => match parse_integer(text) {
            Ok(Literal { value, radix: 16 }) => Value::F64(f64::from_bits(
                u64::try_from(value).map_err(|_| out_of_range())?,
            )),
            _ => Value::F64(text.parse().map_err(|_| not_a_number("not a real"))?),
        },
        DataType::VisibleString => {
            if !text.bytes().all(|b| (0x20..=0x7E).contains(&b)) {
                return Err(Reason::NotVisibleString {
                    text: text.to_string(),
                });
            }
            Value::String(text.to_string())
        }
        DataType::OctetString | DataType::Domain => {
            Value::Bytes(parse_hex_bytes(text).ok_or_else(|| Reason::NotHexBytes {
                text: text.to_string(),
            })?)
        }
        _ => return Err(out_of_range()),
    };
    Ok(EdsValue::Fixed(value))
}

fn parse_hex_bytes(text: &str) -> Option<Vec<u8>> {
    let text = text
        .strip_prefix("0x")
        .or_else(|| text.strip_prefix("0X"))
        .unwrap_or(text);
    let digits: Vec<u8> = text
        .chars()
        .filter(|c| !c.is_ascii_whitespace())
        .map(|c| c.to_digit(16).and_then(|d| u8::try_from(d).ok()))
        .collect::<Option<_>>()?;
    if !digits.len().is_multiple_of(2) {
        return None;
    }
    Some(
        digits
            .chunks(2)
            .map(|p| p.iter().fold(0, |a, d| a * 16 + d))
            .collect(),
    )
}

/// The EDS spelling of a value: decimal integers, 0/1, shortest round-trip reals, the string
/// itself, hex octets. [`parse_value`] reads it back equal (a string's leading and trailing
/// spaces excepted: INI values are trimmed).
pub fn format_value(value: &Value) -> String {
    match value {
        Value::Bool(v) => u8::from(*v).to_string(),
        Value::Bytes(bytes) => bytes.iter().map(|b| format!("{b:02X}")).collect(),
        Value::String(s) => s.clone(),
        Value::F32(v) if v.is_nan() => format!("{:#010X}", v.to_bits()),
        Value::F64(v) if v.is_nan() => format!("{:#018X}", v.to_bits()),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    #[test]
    fn integer_literals() {
        let cases: [(&str, i128, u32); 9] = [
            ("0", 0, 10),
            ("42", 42, 10),
            ("-42", -42, 10),
            ("+7", 7, 10),
            ("0x1A", 26, 16),
            ("0XfF", 255, 16),
            ("010", 8, 8),
            ("-0x10", -16, 16),
            (" 12 ", 12, 10),
        ];
        for (text, value, radix) in cases {
            assert_eq!(
                parse_integer(text),
                Ok(Literal { value, radix }),
                "{text:?}"
            );
        }
        for bad in ["", "-", "0x", "08", "1.5", "12a", "0xG", "--1", "1_000"] {
            assert!(parse_integer(bad).is_err(), "{bad:?}");
        }
        assert_eq!(
            parse_integer(&"9".repeat(60)),
            Err("too many digits"),
            "overflow is an error, not a panic"
        );
    }

    #[test]
    fn node_id_expressions() {
        let cases: [(&str, i128); 7] = [
            ("$NODEID", 0),
            ("$NODEID+0x180", 0x180),
            ("$nodeid + 384", 384),
            ("0x600+$NODEID", 0x600),
            ("$NODEID-1", -1),
            ("$NodeId+0x40000180", 0x4000_0180),
            ("  $NODEID  ", 0),
        ];
        for (text, offset) in cases {
            assert_eq!(
                parse_integer_expr(text),
                Ok(Integer::NodeId { offset }),
                "{text:?}"
            );
        }
        for bad in [
            "$NODEID*2",
            "$NODEID+",
            "2*$NODEID",
            "1+$NODEID+1",
            "$NODEID+$NODEID",
            "$NODEID+-1",
            "0x180-$NODEID",
        ] {
            assert!(parse_integer_expr(bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn typed_values() {
        use DataType::*;
        let fixed = |v| Ok(EdsValue::Fixed(v));
        assert_eq!(parse_value("0xFFFF", Integer16), fixed(Value::I16(-1)));
        assert_eq!(
            parse_value("0x80000000", Integer32),
            fixed(Value::I32(i32::MIN))
        );
        assert_eq!(parse_value("-128", Integer8), fixed(Value::I8(-128)));
        assert_eq!(parse_value("255", Unsigned8), fixed(Value::U8(255)));
        assert_eq!(parse_value("", Unsigned32), fixed(Value::U32(0)));
        assert_eq!(parse_value("1", Boolean), fixed(Value::Bool(true)));
        assert_eq!(parse_value("1.5", Real32), fixed(Value::F32(1.5)));
        assert_eq!(parse_value("0x3F800000", Real32), fixed(Value::F32(1.0)));
        assert_eq!(parse_value("-2e3", Real64), fixed(Value::F64(-2000.0)));
        assert_eq!(
            parse_value("mcemu drive", VisibleString),
            fixed(Value::String("mcemu drive".into()))
        );
        assert_eq!(
            parse_value("01 aB ff", OctetString),
            fixed(Value::Bytes(vec![1, 0xAB, 0xFF]))
        );
        assert_eq!(
            parse_value("$NODEID+0x180", Unsigned32),
            Ok(EdsValue::NodeId {
                data_type: Unsigned32,
                offset: 0x180
            })
        );
    }

    #[test]
    fn typed_value_errors() {
        use DataType::*;
        let reason = |text: &str, dt| parse_value(text, dt).unwrap_err();
        assert!(matches!(
            reason("256", Unsigned8),
            Reason::OutOfRange { .. }
        ));
        assert!(matches!(
            reason("-1", Unsigned16),
            Reason::OutOfRange { .. }
        ));
        assert!(matches!(reason("128", Integer8), Reason::OutOfRange { .. }));
        assert!(matches!(
            reason("0x1FF", Integer8),
            Reason::OutOfRange { .. }
        ));
        assert!(matches!(reason("2", Boolean), Reason::NotABool { .. }));
        assert!(matches!(reason("x", Real32), Reason::NotANumber { .. }));
        assert!(matches!(
            reason("é", VisibleString),
            Reason::NotVisibleString { .. }
        ));
        assert!(matches!(
            reason("123", OctetString),
            Reason::NotHexBytes { .. }
        ));
        assert!(matches!(
            reason("$NODEID", Real32),
            Reason::NodeIdNotInteger { .. }
        ));
        assert_eq!(
            reason("$NODEID+200", Unsigned8),
            Reason::NodeIdOutOfRange {
                text: "$NODEID+200".into(),
                data_type: Unsigned8,
                node_id: 127
            }
        );
        assert!(matches!(
            reason("$NODEID-2", Unsigned8),
            Reason::NodeIdOutOfRange { node_id: 1, .. }
        ));
    }

    #[test]
    fn node_id_values_resolve_per_node() {
        let v = parse_value("$NODEID+0x580", DataType::Unsigned32).unwrap();
        assert_eq!(v.resolve(5), Some(Value::U32(0x585)));
        assert_eq!(v.resolve(127), Some(Value::U32(0x5FF)));
        assert_eq!(v.to_string(), "$NODEID+0x580");
        assert_eq!(parse_value(&v.to_string(), DataType::Unsigned32), Ok(v));
    }
}
