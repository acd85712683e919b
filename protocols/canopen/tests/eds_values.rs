// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! Value spellings (CiA 306 §4.6.3): any value of any type written by `format_value` reads back
//! equal; integers read the same in decimal, hex and octal; `$NODEID` expressions resolve to
//! node id + offset; out-of-range text is refused, never wrapped.

use axes::od::{DataType, Value};
use mcemu_canopen::eds::{format_value, parse_value, EdsValue, Reason};
use proptest::prelude::*;

fn any_value() -> impl Strategy<Value = Value> {
    prop_oneof![
        any::<bool>().prop_map(Value::Bool),
        any::<i8>().prop_map(Value::I8),
        any::<i16>().prop_map(Value::I16),
        any::<i32>().prop_map(Value::I32),
        any::<i64>().prop_map(Value::I64),
        any::<u8>().prop_map(Value::U8),
        any::<u16>().prop_map(Value::U16),
        any::<u32>().prop_map(Value::U32),
        any::<u64>().prop_map(Value::U64),
        any::<f32>().prop_map(Value::F32),
        any::<f64>().prop_map(Value::F64),
        // Printable ASCII; INI values are trimmed, so no spaces at the ends.
        "[!-~]([ -~]{0,30}[!-~])?".prop_map(Value::String),
        prop::collection::vec(any::<u8>(), 0..40).prop_map(Value::Bytes),
    ]
}

/// Equality that holds for NaN: the same bits.
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::F32(x), Value::F32(y)) => x.to_bits() == y.to_bits(),
        (Value::F64(x), Value::F64(y)) => x.to_bits() == y.to_bits(),
        _ => a == b,
    }
}

fn fixed(result: Result<EdsValue, Reason>) -> Value {
    match result {
        Ok(EdsValue::Fixed(value)) => value,
        other => panic!("not a fixed value: {other:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4_000, ..ProptestConfig::default() })]

    #[test]
    fn formatted_values_read_back_equal(value in any_value()) {
        let text = format_value(&value);
        let back = fixed(parse_value(&text, value.data_type()));
        prop_assert!(same(&back, &value), "{value:?} → {text:?} → {back:?}");
    }

    #[test]
    fn integers_read_the_same_in_every_base(v in any::<u32>(), negative in any::<bool>()) {
        let value = i64::from(v) * if negative { -1 } else { 1 };
        let expected = Value::I64(value);
        let sign = if value < 0 { "-" } else { "" };
        let magnitude = value.unsigned_abs();
        for text in [
            format!("{value}"),
            format!("{sign}0x{magnitude:X}"),
            format!("{sign}0x{magnitude:x}"),
            format!("{sign}0{magnitude:o}"),
            format!("  {value} "),
        ] {
            prop_assert_eq!(fixed(parse_value(&text, DataType::Integer64)), expected.clone(), "{}", text);
        }
    }

    #[test]
    fn hex_of_a_signed_type_is_its_bit_pattern(v in any::<i16>()) {
        let text = format!("0x{:04X}", v as u16);
        prop_assert_eq!(fixed(parse_value(&text, DataType::Integer16)), Value::I16(v));
        // Decimal is a number, not a pattern: above the type's range it is refused.
        if v < 0 {
            let decimal = (v as u16).to_string();
            let refused = matches!(
                parse_value(&decimal, DataType::Integer16),
                Err(Reason::OutOfRange { .. })
            );
            prop_assert!(refused);
        }
    }

    #[test]
    fn out_of_range_integers_are_refused(v in 256u32..=u32::MAX) {
        for data_type in [DataType::Unsigned8, DataType::Integer8] {
            let refused = matches!(
                parse_value(&v.to_string(), data_type),
                Err(Reason::OutOfRange { .. })
            );
            prop_assert!(refused);
        }
        prop_assert_eq!(fixed(parse_value(&v.to_string(), DataType::Unsigned32)), Value::U32(v));
    }

    #[test]
    fn node_id_expressions_resolve_to_node_plus_offset(
        offset in 0u32..0x1000_0000,
        node_id in 1u8..=127,
        form in 0usize..4,
    ) {
        let text = match form {
            0 => format!("$NODEID+0x{offset:X}"),
            1 => format!("$nodeid + {offset}"),
            2 => format!("0x{offset:x}+$NODEID"),
            _ => format!("$NodeID+0{offset:o}"),
        };
        let value = parse_value(&text, DataType::Unsigned32).unwrap();
        prop_assert!(value.depends_on_node_id());
        prop_assert_eq!(value.resolve(node_id), Some(Value::U32(offset + u32::from(node_id))));
        // The EDS spelling reads back to the same expression.
        prop_assert_eq!(parse_value(&value.to_string(), DataType::Unsigned32).unwrap(), value);
    }

    #[test]
    fn any_text_parses_or_is_refused_without_panicking(text in "\\PC{0,40}", code in 0usize..14) {
        let data_type = DataType::ALL[code];
        if let Ok(value) = parse_value(&text, data_type) {
            prop_assert!(value.resolve(1).is_some_and(|v| v.fits(data_type)));
        }
    }
}

#[test]
fn a_table_of_spellings() {
    use DataType::*;
    let cases: [(&str, DataType, Value); 16] = [
        ("0", Unsigned8, Value::U8(0)),
        ("", Unsigned16, Value::U16(0)),
        ("0x0A", Unsigned8, Value::U8(10)),
        ("012", Unsigned8, Value::U8(10)),
        ("-1", Integer8, Value::I8(-1)),
        ("0xFF", Integer8, Value::I8(-1)),
        ("0x80000000", Integer32, Value::I32(i32::MIN)),
        ("18446744073709551615", Unsigned64, Value::U64(u64::MAX)),
        ("0", Boolean, Value::Bool(false)),
        ("0x1", Boolean, Value::Bool(true)),
        ("3.25", Real32, Value::F32(3.25)),
        ("-1e-3", Real64, Value::F64(-0.001)),
        ("0x3FF0000000000000", Real64, Value::F64(1.0)),
        (
            "mcemu 0.1.0",
            VisibleString,
            Value::String("mcemu 0.1.0".into()),
        ),
        ("0x0102", OctetString, Value::Bytes(vec![1, 2])),
        (
            "de ad be ef",
            Domain,
            Value::Bytes(vec![0xDE, 0xAD, 0xBE, 0xEF]),
        ),
    ];
    for (text, data_type, expected) in cases {
        assert_eq!(fixed(parse_value(text, data_type)), expected, "{text:?}");
    }
}
