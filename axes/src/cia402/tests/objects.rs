//! The drive's object dictionary seen from a bus: the objects, their types and access, and the
//! errors a master gets.

use super::*;
use crate::od::{Access, DataType, PdoDirection};

/// (index, subindex, data type, access) of the objects the drive must have.
const REQUIRED: &[(u16, u8, DataType, Access)] = &[
    (0x1000, 0, DataType::Unsigned32, Access::Const),
    (0x1001, 0, DataType::Unsigned8, Access::Ro),
    (0x1008, 0, DataType::VisibleString, Access::Const),
    (0x1018, 0, DataType::Unsigned8, Access::Const),
    (0x1018, 1, DataType::Unsigned32, Access::Ro),
    (0x1018, 2, DataType::Unsigned32, Access::Ro),
    (0x1018, 3, DataType::Unsigned32, Access::Ro),
    (0x1018, 4, DataType::Unsigned32, Access::Ro),
    (0x603F, 0, DataType::Unsigned16, Access::Ro),
    (0x6040, 0, DataType::Unsigned16, Access::Rww),
    (0x6041, 0, DataType::Unsigned16, Access::Ro),
    (0x605A, 0, DataType::Integer16, Access::Rw),
    (0x605B, 0, DataType::Integer16, Access::Rw),
    (0x605C, 0, DataType::Integer16, Access::Rw),
    (0x605D, 0, DataType::Integer16, Access::Rw),
    (0x605E, 0, DataType::Integer16, Access::Rw),
    (0x6060, 0, DataType::Integer8, Access::Rww),
    (0x6061, 0, DataType::Integer8, Access::Ro),
    (0x6062, 0, DataType::Integer32, Access::Ro),
    (0x6063, 0, DataType::Integer32, Access::Ro),
    (0x6064, 0, DataType::Integer32, Access::Ro),
    (0x6065, 0, DataType::Unsigned32, Access::Rw),
    (0x6066, 0, DataType::Unsigned16, Access::Rw),
    (0x6067, 0, DataType::Unsigned32, Access::Rw),
    (0x6068, 0, DataType::Unsigned16, Access::Rw),
    (0x606C, 0, DataType::Integer32, Access::Ro),
    (0x6071, 0, DataType::Integer16, Access::Rww),
    (0x6077, 0, DataType::Integer16, Access::Ro),
    (0x607A, 0, DataType::Integer32, Access::Rww),
    (0x607C, 0, DataType::Integer32, Access::Rw),
    (0x607D, 1, DataType::Integer32, Access::Rw),
    (0x607D, 2, DataType::Integer32, Access::Rw),
    (0x607F, 0, DataType::Unsigned32, Access::Rw),
    (0x6080, 0, DataType::Unsigned32, Access::Rw),
    (0x6081, 0, DataType::Unsigned32, Access::Rww),
    (0x6083, 0, DataType::Unsigned32, Access::Rww),
    (0x6084, 0, DataType::Unsigned32, Access::Rww),
    (0x6085, 0, DataType::Unsigned32, Access::Rw),
    (0x6086, 0, DataType::Integer16, Access::Rw),
    (0x6098, 0, DataType::Integer8, Access::Rw),
    (0x6099, 1, DataType::Unsigned32, Access::Rw),
    (0x6099, 2, DataType::Unsigned32, Access::Rw),
    (0x609A, 0, DataType::Unsigned32, Access::Rw),
    (0x60B8, 0, DataType::Unsigned16, Access::Rww),
    (0x60B9, 0, DataType::Unsigned16, Access::Ro),
    (0x60BA, 0, DataType::Integer32, Access::Ro),
    (0x60BB, 0, DataType::Integer32, Access::Ro),
    (0x60BC, 0, DataType::Integer32, Access::Ro),
    (0x60BD, 0, DataType::Integer32, Access::Ro),
    (0x60F4, 0, DataType::Integer32, Access::Ro),
    (0x60FC, 0, DataType::Integer32, Access::Ro),
    (0x60FD, 0, DataType::Unsigned32, Access::Ro),
    (0x60FE, 1, DataType::Unsigned32, Access::Rww),
    (0x60FE, 2, DataType::Unsigned32, Access::Rw),
    (0x60FF, 0, DataType::Integer32, Access::Rww),
    (0x6502, 0, DataType::Unsigned32, Access::Const),
];

#[test]
fn the_drive_has_every_required_object() {
    let drive = Cia402Drive::new(DriveConfig::default()).unwrap();
    for &(index, subindex, data_type, access) in REQUIRED {
        let entry = drive.od().entry(index, subindex).unwrap();
        assert_eq!(entry.def.data_type, data_type, "{index:#06x}:{subindex}");
        assert_eq!(entry.def.access, access, "{index:#06x}:{subindex}");
    }
    // Process data are PDO-mappable in their direction.
    for (index, direction) in [
        (0x6040, PdoDirection::Receive),
        (0x6060, PdoDirection::Receive),
        (0x607A, PdoDirection::Receive),
        (0x60FF, PdoDirection::Receive),
        (0x6071, PdoDirection::Receive),
        (0x60B8, PdoDirection::Receive),
        (0x6041, PdoDirection::Transmit),
        (0x6061, PdoDirection::Transmit),
        (0x6064, PdoDirection::Transmit),
        (0x606C, PdoDirection::Transmit),
        (0x6077, PdoDirection::Transmit),
        (0x60F4, PdoDirection::Transmit),
        (0x60FD, PdoDirection::Transmit),
        (0x603F, PdoDirection::Transmit),
        (0x60B9, PdoDirection::Transmit),
        (0x60BA, PdoDirection::Transmit),
    ] {
        assert!(
            drive.od().check_mappable(index, 0, direction).is_ok(),
            "{index:#06x}"
        );
    }
    for (index, direction) in [
        (0x6041, PdoDirection::Receive),
        (0x6064, PdoDirection::Receive),
        (0x6040, PdoDirection::Transmit),
        (0x605A, PdoDirection::Transmit),
        (0x1008, PdoDirection::Transmit),
    ] {
        assert_eq!(
            drive.od().check_mappable(index, 0, direction).map(|_| ()),
            Err(OdError::NotMappable { index, subindex: 0 }),
        );
    }
}

#[test]
fn identity_and_constant_objects() {
    let config = DriveConfig {
        name: "axis X".into(),
        vendor_id: 0x0000_00AB,
        product_code: 0x1234,
        revision: 0x0002_0001,
        serial: 42,
        ..DriveConfig::default()
    };
    let drive = Cia402Drive::new(config).unwrap();
    assert_eq!(
        drive.read_bytes(0x1000, 0),
        Ok(vec![0x92, 0x01, 0x02, 0x00])
    );
    assert_eq!(drive.read(0x1008, 0), Ok(Value::String("axis X".into())));
    assert_eq!(drive.read(0x1018, 0), Ok(Value::U8(4)));
    assert_eq!(drive.read(0x1018, 1), Ok(Value::U32(0xAB)));
    assert_eq!(drive.read(0x1018, 2), Ok(Value::U32(0x1234)));
    assert_eq!(drive.read(0x1018, 3), Ok(Value::U32(0x0002_0001)));
    assert_eq!(drive.read(0x1018, 4), Ok(Value::U32(42)));
    // pp, pv, hm, csp, csv, cst.
    assert_eq!(drive.read(0x6502, 0), Ok(Value::U32(0x03A5)));
    assert_eq!(drive.read(0x605A, 0), Ok(Value::I16(2)));
    assert_eq!(drive.read(0x6098, 0), Ok(Value::I8(37)));
}

#[test]
fn masters_cannot_write_what_the_drive_computes() {
    let mut rig = Rig::new();
    for index in [
        0x1000, 0x1001, 0x1008, 0x603F, 0x6041, 0x6061, 0x6062, 0x6063, 0x6064, 0x606C, 0x6077,
        0x60B9, 0x60BA, 0x60F4, 0x60FC, 0x60FD, 0x6502,
    ] {
        let value = rig.drive.read(index, 0).unwrap();
        let bytes = value.to_le_bytes();
        let expected = Err(OdError::ReadOnly { index, subindex: 0 });
        assert_eq!(rig.drive.write(index, 0, value), expected, "{index:#06x}");
        assert_eq!(
            rig.drive.write_bytes(index, 0, &bytes),
            expected,
            "{index:#06x}"
        );
    }
    // …while the drive keeps them current itself.
    rig.operation_enabled();
    assert_eq!(rig.drive.read(0x6041, 0), Ok(Value::U16(0x0237)));
}

#[test]
fn bus_writes_get_the_right_errors() {
    let mut drive = Cia402Drive::new(DriveConfig::default()).unwrap();
    let cases: Vec<(Result<(), OdError>, u32)> = vec![
        (drive.write(0x6000, 0, Value::U8(0)), 0x0602_0000),
        (drive.write(0x6040, 1, Value::U16(0)), 0x0609_0011),
        (drive.write(0x6040, 0, Value::I16(6)), 0x0607_0010),
        (drive.write(0x6040, 0, Value::U32(6)), 0x0607_0010),
        (drive.write_bytes(0x6040, 0, &[6, 0, 0, 0]), 0x0607_0012),
        (drive.write_bytes(0x607A, 0, &[1, 2]), 0x0607_0013),
        (drive.write(0x605A, 0, Value::I16(9)), 0x0609_0031),
        (drive.write(0x605A, 0, Value::I16(-1)), 0x0609_0032),
        (
            drive.write_bytes(0x605D, 0, &0i16.to_le_bytes()),
            0x0609_0032,
        ),
        (drive.write(0x605E, 0, Value::I16(5)), 0x0609_0031),
        (drive.write(0x6007, 0, Value::I16(4)), 0x0609_0031),
        (drive.write(0x6060, 0, Value::I8(2)), 0x0609_0030),
        (drive.write(0x6086, 0, Value::I16(1)), 0x0609_0030),
        (drive.write(0x6098, 0, Value::I8(0)), 0x0609_0030),
        (drive.write(0x6041, 0, Value::U16(0)), 0x0601_0002),
    ];
    for (n, (result, code)) in cases.into_iter().enumerate() {
        assert_eq!(
            result.map_err(|e| e.sdo_abort_code()),
            Err(code),
            "case {n}"
        );
    }
    // Good writes, typed and as bytes.
    assert_eq!(drive.write_bytes(0x6040, 0, &[0x06, 0x00]), Ok(()));
    assert_eq!(drive.read(0x6040, 0), Ok(Value::U16(6)));
    assert_eq!(drive.write_bytes(0x607A, 0, &(-5i32).to_le_bytes()), Ok(()));
    assert_eq!(
        drive.read_bytes(0x607A, 0),
        Ok(vec![0xFB, 0xFF, 0xFF, 0xFF])
    );
    assert_eq!(drive.write(0x6060, 0, Value::I8(8)), Ok(()));
    assert_eq!(drive.write(0x605A, 0, Value::I16(8)), Ok(()));
}

#[test]
fn drive_config_is_validated() {
    for ipu in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let config = DriveConfig {
            increments_per_unit: ipu,
            ..DriveConfig::default()
        };
        assert!(matches!(
            Cia402Drive::new(config),
            Err(DriveConfigError::IncrementsPerUnit(_))
        ));
    }
    let config = DriveConfig {
        name: "Achse \u{00fc}".into(),
        ..DriveConfig::default()
    };
    assert!(matches!(
        Cia402Drive::new(config),
        Err(DriveConfigError::NotVisibleString { field: "name", .. })
    ));
    // The config is TOML/JSON with defaults and no unknown keys.
    let config: DriveConfig =
        serde_json::from_str(r#"{ "axis": 2, "increments_per_unit": 10000 }"#).unwrap();
    assert_eq!(config.axis, 2);
    assert_eq!(config.name, DriveConfig::default().name);
    assert!(serde_json::from_str::<DriveConfig>(r#"{ "axes": 2 }"#).is_err());
}

#[test]
fn same_inputs_same_outputs() {
    // Determinism: two rigs fed the same writes at the same ticks agree bit for bit.
    let run = || {
        let mut rig = Rig::new();
        rig.mode(OperationMode::ProfilePosition);
        rig.set(obj::PROFILE_VELOCITY, 0, Value::U32(30_000));
        rig.operation_enabled();
        let mut trace = Vec::new();
        for k in 0..40 {
            if k % 10 == 0 {
                rig.set(obj::TARGET_POSITION, 0, Value::I32(k * 37));
                rig.cw(0x1F);
            } else {
                rig.cw(0x0F);
            }
            trace.push((rig.sw(), rig.int(obj::POSITION_ACTUAL), rig.last.clone()));
        }
        trace
    };
    assert_eq!(run(), run());
}

/// 0x607D: a write that would make the max position limit less than the min is refused with
/// `MaxBelowMin` (SDO abort 0x06090036) and stores nothing; equal limits are accepted.
#[test]
fn software_position_limits_keep_max_at_or_above_min() {
    let mut drive = Cia402Drive::new(DriveConfig::default()).unwrap();
    assert_eq!(drive.write(0x607D, 2, Value::I32(-10)), Ok(()));
    let e = drive.write(0x607D, 1, Value::I32(-9)).unwrap_err();
    assert_eq!(e.sdo_abort_code(), 0x0609_0036, "{e}");
    assert_eq!(
        e,
        OdError::MaxBelowMin {
            index: 0x607D,
            subindex: 1,
            min: Value::I32(-9),
            max: Value::I32(-10),
        }
    );
    assert_eq!(drive.read(0x607D, 1), Ok(Value::I32(i32::MIN)));
    assert_eq!(drive.write(0x607D, 1, Value::I32(-10)), Ok(()));
    let e = drive.write(0x607D, 2, Value::I32(-11)).unwrap_err();
    assert_eq!(e.sdo_abort_code(), 0x0609_0036, "{e}");
    assert_eq!(drive.read(0x607D, 2), Ok(Value::I32(-10)));
}
