use super::*;

/// A small dictionary with one entry of every access type and a few data types.
fn sample() -> ObjectDictionary {
    ObjectDictionary::from_defs([
        EntryDef::new(
            0x1000,
            0,
            "Device type",
            Access::Const,
            Value::U32(0x0002_0192),
        ),
        EntryDef::new(
            0x1008,
            0,
            "Device name",
            Access::Const,
            Value::String("x".into()),
        ),
        EntryDef::new(0x2000, 0, "Flag", Access::Rw, Value::Bool(false)),
        EntryDef::new(0x2001, 0, "Signed", Access::Rw, Value::I16(0))
            .range(Value::I16(-100), Value::I16(100)),
        EntryDef::new(0x2002, 0, "Command", Access::Wo, Value::U8(0)).pdo(),
        EntryDef::new(0x2003, 0, "Output", Access::Rww, Value::I32(0)).pdo(),
        EntryDef::new(0x2004, 0, "Input", Access::Ro, Value::U16(0)).pdo(),
        EntryDef::new(0x2005, 0, "Process in", Access::Rwr, Value::I64(0)).pdo(),
        EntryDef::new(0x2006, 0, "Blob", Access::Rw, Value::Bytes(vec![]))
            .data_type(DataType::Domain),
        EntryDef::new(0x2007, 0, "Gain", Access::Rw, Value::F32(1.0))
            .range(Value::F32(0.0), Value::F32(10.0)),
        EntryDef::new(0x2008, 0, "Text", Access::Rw, Value::String(String::new())),
        EntryDef::new(0x2009, 0, "Big", Access::Rw, Value::U64(0)),
        EntryDef::new(0x200A, 0, "Wide", Access::Rw, Value::F64(0.0)),
        EntryDef::new(0x200B, 0, "Tiny", Access::Rw, Value::I8(0)),
        EntryDef::new(0x1018, 0, "Identity: entries", Access::Const, Value::U8(1)),
        EntryDef::new(0x1018, 1, "Identity: vendor", Access::Ro, Value::U32(7)),
    ])
    .unwrap()
}

#[test]
fn data_type_codes_round_trip_and_sizes_match_encodings() {
    for dt in DataType::ALL {
        assert_eq!(DataType::from_code(dt.code()), Some(dt), "{dt}");
    }
    assert_eq!(DataType::from_code(0x0010), None); // INTEGER24 is not stored
    let samples = [
        Value::Bool(true),
        Value::I8(-1),
        Value::I16(-2),
        Value::I32(-3),
        Value::I64(-4),
        Value::U8(1),
        Value::U16(2),
        Value::U32(3),
        Value::U64(4),
        Value::F32(0.5),
        Value::F64(0.25),
    ];
    for v in samples {
        assert_eq!(Some(v.to_le_bytes().len()), v.data_type().size(), "{v:?}");
    }
    assert_eq!(DataType::Unsigned16.name(), "UNSIGNED16");
}

#[test]
fn little_endian_encoding_and_decoding() {
    assert_eq!(Value::U16(0x1234).to_le_bytes(), [0x34, 0x12]);
    assert_eq!(Value::I32(-2).to_le_bytes(), [0xFE, 0xFF, 0xFF, 0xFF]);
    assert_eq!(
        Value::U32(0x0002_0192).to_le_bytes(),
        [0x92, 0x01, 0x02, 0x00]
    );
    assert_eq!(Value::F32(1.0).to_le_bytes(), [0, 0, 0x80, 0x3F]);
    assert_eq!(Value::Bool(true).to_le_bytes(), [1]);
    assert_eq!(Value::String("ab".into()).to_le_bytes(), b"ab");
    let cases = [
        (DataType::Integer16, vec![0xFE, 0xFF], Value::I16(-2)),
        (
            DataType::Unsigned32,
            vec![1, 0, 0, 0x80],
            Value::U32(0x8000_0001),
        ),
        (DataType::Integer64, vec![0xFF; 8], Value::I64(-1)),
        (
            DataType::Unsigned64,
            vec![1, 0, 0, 0, 0, 0, 0, 0],
            Value::U64(1),
        ),
        (
            DataType::Real64,
            2.5f64.to_le_bytes().to_vec(),
            Value::F64(2.5),
        ),
        (DataType::Boolean, vec![0], Value::Bool(false)),
        (DataType::Integer8, vec![0x80], Value::I8(-128)),
        (
            DataType::VisibleString,
            b"drive\0\0".to_vec(),
            Value::String("drive".into()),
        ),
        (DataType::Domain, vec![1, 2, 3], Value::Bytes(vec![1, 2, 3])),
        (DataType::OctetString, vec![], Value::Bytes(vec![])),
    ];
    for (dt, bytes, value) in cases {
        assert_eq!(Value::from_le_bytes(dt, &bytes), Ok(value), "{dt}");
    }
    assert_eq!(
        Value::from_le_bytes(DataType::Unsigned16, &[1, 2, 3]),
        Err(DecodeError::TooLong {
            expected: 2,
            found: 3
        })
    );
    assert_eq!(
        Value::from_le_bytes(DataType::Unsigned32, &[1]),
        Err(DecodeError::TooShort {
            expected: 4,
            found: 1
        })
    );
    assert!(matches!(
        Value::from_le_bytes(DataType::Boolean, &[2]),
        Err(DecodeError::Invalid(_))
    ));
    assert!(matches!(
        Value::from_le_bytes(DataType::VisibleString, &[0x41, 0x07]),
        Err(DecodeError::Invalid(_))
    ));
}

#[test]
fn reads_follow_access_rights() {
    let od = sample();
    assert_eq!(od.read(0x1000, 0), Ok(Value::U32(0x0002_0192)));
    assert_eq!(od.read_bytes(0x1000, 0), Ok(vec![0x92, 0x01, 0x02, 0x00]));
    assert_eq!(od.read(0x2004, 0), Ok(Value::U16(0)));
    assert_eq!(
        od.read(0x2002, 0),
        Err(OdError::WriteOnly {
            index: 0x2002,
            subindex: 0
        })
    );
    assert_eq!(od.read(0x1018, 1), Ok(Value::U32(7)));
}

#[test]
fn missing_object_and_missing_subindex_differ() {
    let mut od = sample();
    assert_eq!(od.read(0x3000, 0), Err(OdError::NoObject { index: 0x3000 }));
    assert_eq!(
        od.read(0x1018, 2),
        Err(OdError::NoSubindex {
            index: 0x1018,
            subindex: 2
        })
    );
    assert_eq!(
        od.write(0x2001, 1, Value::I16(0)),
        Err(OdError::NoSubindex {
            index: 0x2001,
            subindex: 1
        })
    );
}

#[test]
fn writes_check_access_type_length_and_limits() {
    let mut od = sample();
    // Read-only and const objects refuse bus writes, typed or as bytes.
    for index in [0x1000, 0x2004] {
        let expected = Err(OdError::ReadOnly { index, subindex: 0 });
        let value = od.read(index, 0).unwrap();
        assert_eq!(od.write(index, 0, value), expected);
        assert_eq!(od.write_bytes(index, 0, &[0, 0]), expected);
    }
    // Wrong type: no silent widening or narrowing.
    assert_eq!(
        od.write(0x2001, 0, Value::I32(5)),
        Err(OdError::WrongType {
            index: 0x2001,
            subindex: 0,
            expected: DataType::Integer16,
            found: DataType::Integer32
        })
    );
    // Length.
    assert_eq!(
        od.write_bytes(0x2001, 0, &[1, 0, 0]),
        Err(OdError::LengthTooHigh {
            index: 0x2001,
            subindex: 0,
            expected: 2,
            found: 3
        })
    );
    assert_eq!(
        od.write_bytes(0x2001, 0, &[1]),
        Err(OdError::LengthTooLow {
            index: 0x2001,
            subindex: 0,
            expected: 2,
            found: 1
        })
    );
    // Limits, inclusive.
    assert_eq!(
        od.write(0x2001, 0, Value::I16(101)),
        Err(OdError::ValueTooHigh {
            index: 0x2001,
            subindex: 0,
            value: Value::I16(101),
            high: Value::I16(100)
        })
    );
    assert_eq!(
        od.write_bytes(0x2001, 0, &(-101i16).to_le_bytes()),
        Err(OdError::ValueTooLow {
            index: 0x2001,
            subindex: 0,
            value: Value::I16(-101),
            low: Value::I16(-100)
        })
    );
    assert_eq!(od.write(0x2001, 0, Value::I16(-100)), Ok(()));
    assert_eq!(od.write_bytes(0x2001, 0, &100i16.to_le_bytes()), Ok(()));
    assert_eq!(od.read(0x2001, 0), Ok(Value::I16(100)));
    // Float limits, and NaN never passes one.
    assert!(matches!(
        od.write(0x2007, 0, Value::F32(10.5)),
        Err(OdError::ValueTooHigh { .. })
    ));
    assert!(matches!(
        od.write(0x2007, 0, Value::F32(f32::NAN)),
        Err(OdError::InvalidValue { .. })
    ));
    // A BOOLEAN byte other than 0/1 is an invalid value.
    assert!(matches!(
        od.write_bytes(0x2000, 0, &[7]),
        Err(OdError::InvalidValue { .. })
    ));
    // Write-only objects take writes.
    assert_eq!(od.write_bytes(0x2002, 0, &[9]), Ok(()));
    assert_eq!(od.get(0x2002, 0), Some(&Value::U8(9)));
}

#[test]
fn every_fixed_size_type_writes_and_reads_back_as_bytes() {
    let mut od = sample();
    let cases: [(u16, Value); 9] = [
        (0x2000, Value::Bool(true)),
        (0x200B, Value::I8(-5)),
        (0x2001, Value::I16(-7)),
        (0x2003, Value::I32(-70_000)),
        (0x2005, Value::I64(-1 << 40)),
        (0x2002, Value::U8(200)),
        (0x2009, Value::U64(u64::MAX)),
        (0x2007, Value::F32(2.5)),
        (0x200A, Value::F64(-0.125)),
    ];
    for (index, value) in cases {
        let bytes = value.to_le_bytes();
        assert_eq!(od.write_bytes(index, 0, &bytes), Ok(()), "{index:#x}");
        assert_eq!(od.get(index, 0), Some(&value), "{index:#x}");
        if od.entry(index, 0).unwrap().def.access.readable() {
            assert_eq!(od.read_bytes(index, 0), Ok(bytes));
        }
    }
}

#[test]
fn variable_length_types_take_any_length_up_to_the_cap() {
    let mut od = sample();
    assert_eq!(od.write_bytes(0x2006, 0, &[1, 2, 3, 4, 5]), Ok(()));
    assert_eq!(od.read(0x2006, 0), Ok(Value::Bytes(vec![1, 2, 3, 4, 5])));
    assert_eq!(od.write(0x2008, 0, Value::String("hello".into())), Ok(()));
    assert_eq!(od.read_bytes(0x2008, 0), Ok(b"hello".to_vec()));
    let huge = vec![0u8; MAX_VARIABLE_LEN + 1];
    assert!(matches!(
        od.write_bytes(0x2006, 0, &huge),
        Err(OdError::LengthTooHigh { .. })
    ));
}

#[test]
fn device_access_bypasses_rights_and_limits_but_not_types() {
    let mut od = sample();
    assert_eq!(od.set(0x2004, 0, Value::U16(0x0237)), Ok(()));
    assert_eq!(od.read(0x2004, 0), Ok(Value::U16(0x0237)));
    assert_eq!(od.set(0x2001, 0, Value::I16(1000)), Ok(()));
    assert!(matches!(
        od.set(0x2004, 0, Value::U32(1)),
        Err(OdError::WrongType { .. })
    ));
    assert_eq!(
        od.set(0x3000, 0, Value::U8(0)),
        Err(OdError::NoObject { index: 0x3000 })
    );
    od.restore_defaults();
    assert_eq!(od.read(0x2004, 0), Ok(Value::U16(0)));
    assert_eq!(od.read(0x2001, 0), Ok(Value::I16(0)));
}

#[test]
fn pdo_mapping_follows_flag_and_direction() {
    let od = sample();
    use PdoDirection::{Receive, Transmit};
    assert!(od.check_mappable(0x2004, 0, Transmit).is_ok()); // ro → TPDO
    assert!(od.check_mappable(0x2005, 0, Transmit).is_ok()); // rwr → TPDO
    assert!(od.check_mappable(0x2003, 0, Receive).is_ok()); // rww → RPDO
    assert!(od.check_mappable(0x2002, 0, Receive).is_ok()); // wo → RPDO
    for (index, dir) in [
        (0x2004, Receive),
        (0x2003, Transmit),
        (0x2002, Transmit),
        (0x2001, Transmit), // not mappable at all
    ] {
        assert_eq!(
            od.check_mappable(index, 0, dir).map(|_| ()),
            Err(OdError::NotMappable { index, subindex: 0 })
        );
    }
}

#[test]
fn table_errors_are_reported() {
    let dup = ObjectDictionary::from_defs([
        EntryDef::new(0x2000, 0, "a", Access::Rw, Value::U8(0)),
        EntryDef::new(0x2000, 0, "b", Access::Rw, Value::U8(0)),
    ]);
    assert_eq!(
        dup,
        Err(DefinitionError::Duplicate {
            index: 0x2000,
            subindex: 0
        })
    );
    let typed =
        ObjectDictionary::from_defs([EntryDef::new(0x2000, 0, "a", Access::Rw, Value::U8(0))
            .range(Value::U16(0), Value::U16(1))]);
    assert!(matches!(typed, Err(DefinitionError::TypeMismatch { .. })));
    let range =
        ObjectDictionary::from_defs([EntryDef::new(0x2000, 0, "a", Access::Rw, Value::U8(5))
            .range(Value::U8(0), Value::U8(1))]);
    assert_eq!(
        range,
        Err(DefinitionError::DefaultOutOfRange {
            index: 0x2000,
            subindex: 0
        })
    );
    let domain =
        ObjectDictionary::from_defs([
            EntryDef::new(0x2000, 0, "a", Access::Rw, Value::U8(5)).data_type(DataType::Domain)
        ]);
    assert!(matches!(domain, Err(DefinitionError::TypeMismatch { .. })));
}

#[test]
fn entries_iterate_in_index_order() {
    let od = sample();
    let keys: Vec<_> = od
        .entries()
        .map(|e| (e.def.index, e.def.subindex))
        .collect();
    let mut sorted = keys.clone();
    sorted.sort_unstable();
    assert_eq!(keys, sorted);
    assert_eq!(od.len(), 16);
    assert!(od.contains_object(0x1018) && !od.contains_object(0x1019));
}

#[test]
fn eds_access_names_round_trip() {
    for a in [
        Access::Ro,
        Access::Wo,
        Access::Rw,
        Access::Rwr,
        Access::Rww,
        Access::Const,
    ] {
        assert_eq!(Access::from_eds(a.eds_name()), Some(a));
    }
    assert_eq!(Access::from_eds(" RW "), Some(Access::Rw));
    assert_eq!(Access::from_eds("rx"), None);
}

#[test]
fn every_error_has_its_cia301_abort_code() {
    let (index, subindex) = (0x6060, 0);
    let cases = [
        (OdError::NoObject { index }, 0x0602_0000),
        (OdError::NoSubindex { index, subindex }, 0x0609_0011),
        (OdError::ReadOnly { index, subindex }, 0x0601_0002),
        (OdError::WriteOnly { index, subindex }, 0x0601_0001),
        (
            OdError::WrongType {
                index,
                subindex,
                expected: DataType::Integer8,
                found: DataType::Unsigned8,
            },
            0x0607_0010,
        ),
        (
            OdError::LengthTooHigh {
                index,
                subindex,
                expected: 1,
                found: 2,
            },
            0x0607_0012,
        ),
        (
            OdError::LengthTooLow {
                index,
                subindex,
                expected: 2,
                found: 1,
            },
            0x0607_0013,
        ),
        (
            OdError::ValueTooHigh {
                index,
                subindex,
                value: Value::I8(9),
                high: Value::I8(8),
            },
            0x0609_0031,
        ),
        (
            OdError::ValueTooLow {
                index,
                subindex,
                value: Value::I8(-9),
                low: Value::I8(-8),
            },
            0x0609_0032,
        ),
        (
            OdError::InvalidValue {
                index,
                subindex,
                detail: "x".into(),
            },
            0x0609_0030,
        ),
        (OdError::NotMappable { index, subindex }, 0x0604_0041),
        (
            OdError::DeviceState {
                index,
                subindex,
                detail: "x".into(),
            },
            0x0800_0022,
        ),
    ];
    for (error, code) in cases {
        assert_eq!(error.sdo_abort_code(), code, "{error}");
        assert_eq!(error.index(), index);
        // Errors travel in replies and traces as JSON.
        let json = serde_json::to_string(&error).unwrap();
        assert_eq!(serde_json::from_str::<OdError>(&json).unwrap(), error);
    }
}

#[test]
fn values_compare_across_integer_widths() {
    use std::cmp::Ordering::*;
    assert_eq!(Value::U32(u32::MAX).compare(&Value::I8(-1)), Some(Greater));
    assert_eq!(Value::I64(-5).compare(&Value::U8(0)), Some(Less));
    assert_eq!(Value::F32(1.5).compare(&Value::F64(1.5)), Some(Equal));
    assert_eq!(Value::String("a".into()).compare(&Value::U8(0)), None);
    assert_eq!(Value::U64(u64::MAX).as_i64(), None);
    assert_eq!(Value::I16(-3).as_i64(), Some(-3));
    assert_eq!(Value::I16(-3).as_u64(), None);
    assert_eq!(Value::Bytes(vec![0xAB, 1]).to_string(), "0xab01");
}

#[test]
fn insert_adds_entries_and_refuses_duplicates_and_bad_defaults() {
    let mut od = sample();
    let before = od.len();
    od.insert(EntryDef::new(
        0x1017,
        0,
        "Producer heartbeat time",
        Access::Rw,
        Value::U16(0),
    ))
    .unwrap();
    assert_eq!(od.len(), before + 1);
    assert_eq!(od.read(0x1017, 0).unwrap(), Value::U16(0));
    assert_eq!(
        od.insert(EntryDef::new(0x1017, 0, "again", Access::Rw, Value::U16(1))),
        Err(DefinitionError::Duplicate {
            index: 0x1017,
            subindex: 0
        })
    );
    let bad = EntryDef::new(0x1019, 0, "bad", Access::Rw, Value::U16(9))
        .range(Value::U16(0), Value::U16(2));
    assert_eq!(
        od.insert(bad),
        Err(DefinitionError::DefaultOutOfRange {
            index: 0x1019,
            subindex: 0
        })
    );
    assert_eq!(od.len(), before + 1);
}
