// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! The shipped EDS files load without warnings, build dictionaries for any node id, resolve
//! `$NODEID`, carry the documented default PDOs; DCF values, compact arrays, encodings and
//! spelling variants load as CiA 306 says.

use axes::od::{Access, DataType, PdoDirection, Value};
use mcemu_canopen::eds::{Eds, EdsValue, MappedObject, ObjectList, ObjectType, PdoDefault};

fn fixture(name: &str) -> String {
    format!(
        "{}/../../fixtures/canopen/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn drive() -> Eds {
    Eds::load(fixture("cia402-drive.eds")).unwrap()
}

fn e10() -> Eds {
    Eds::load(fixture("ct-e10.eds")).unwrap()
}

/// (index, sub-index, bits) of each mapped object.
type Mapping = Vec<(u16, u8, u8)>;

fn mapping(pdo: &PdoDefault) -> Mapping {
    pdo.mapping
        .iter()
        .map(|m| (m.index, m.subindex, m.bits))
        .collect()
}

#[test]
fn shipped_files_load_without_warnings_and_build_for_every_node_id() {
    for eds in [drive(), e10()] {
        assert!(eds.warnings.is_empty(), "{:?}", eds.warnings);
        assert!(!eds.is_dcf());
        let entries = eds.sub_objects().count();
        for node_id in 1..=127 {
            let od = eds.dictionary(node_id).unwrap();
            assert_eq!(od.len(), entries);
            assert_eq!(eds.default_pdos(node_id).unwrap().len(), 8);
        }
        for index in [0x1000, 0x1001, 0x1018] {
            assert_eq!(eds.object(index).unwrap().list, Some(ObjectList::Mandatory));
        }
    }
}

#[test]
fn the_drive_has_the_cia301_objects_a_real_drive_has() {
    let eds = drive();
    let wanted = [
        0x1000, 0x1001, 0x1003, 0x1005, 0x1006, 0x1008, 0x1009, 0x100A, 0x100C, 0x100D, 0x1010,
        0x1011, 0x1014, 0x1015, 0x1016, 0x1017, 0x1018, 0x1019, 0x1029, 0x1200, 0x1400, 0x1401,
        0x1402, 0x1403, 0x1600, 0x1601, 0x1602, 0x1603, 0x1800, 0x1801, 0x1802, 0x1803, 0x1A00,
        0x1A01, 0x1A02, 0x1A03,
    ];
    for index in wanted {
        assert!(eds.object(index).is_some(), "{index:#06x}");
    }
    let od = eds.dictionary(1).unwrap();
    assert_eq!(od.read(0x1000, 0), Ok(Value::U32(0x0002_0192)));
    assert_eq!(od.read(0x1018, 0), Ok(Value::U8(4)));
    assert_eq!(od.read(0x1005, 0), Ok(Value::U32(0x80)));
    assert_eq!(
        od.read(0x1008, 0),
        Ok(Value::String("mcemu CiA 402 drive".into()))
    );
    assert_eq!(eds.object(0x1018).unwrap().object_type, ObjectType::Record);
    assert_eq!(eds.object(0x1003).unwrap().object_type, ObjectType::Array);
    assert_eq!(eds.device_info.bit_rates_kbit.len(), 8);
    assert_eq!(
        (eds.device_info.nr_of_rx_pdo, eds.device_info.nr_of_tx_pdo),
        (4, 4)
    );
    assert!(eds.dummy_usage.supports(0x0005) && !eds.dummy_usage.supports(0x0001));
}

#[test]
fn node_id_values_follow_the_node() {
    let eds = drive();
    for node_id in [1u8, 2, 64, 127] {
        let id = u32::from(node_id);
        let od = eds.dictionary(node_id).unwrap();
        assert_eq!(od.read(0x1014, 0), Ok(Value::U32(0x80 + id)));
        assert_eq!(od.read(0x1200, 1), Ok(Value::U32(0x600 + id)));
        assert_eq!(od.read(0x1200, 2), Ok(Value::U32(0x580 + id)));
        assert_eq!(od.read(0x1400, 1), Ok(Value::U32(0x200 + id)));
        assert_eq!(od.read(0x1803, 1), Ok(Value::U32(0x4000_0480 + id)));
    }
    assert_eq!(
        eds.sub_object(0x1200, 2).unwrap().default,
        EdsValue::NodeId {
            data_type: DataType::Unsigned32,
            offset: 0x580
        }
    );
    assert!(eds.dictionary(0).is_err() && eds.dictionary(128).is_err());
}

#[test]
fn the_drive_has_the_cia402_pre_defined_pdo_sets() {
    let pdos = drive().default_pdos(3).unwrap();
    type Entries = &'static [(u16, u8, u8)];
    let expected: [(PdoDirection, u16, u32, u8, Entries); 8] = [
        (PdoDirection::Receive, 1, 0x203, 255, &[(0x6040, 0, 16)]),
        (
            PdoDirection::Receive,
            2,
            0x303,
            255,
            &[(0x6040, 0, 16), (0x6060, 0, 8)],
        ),
        (
            PdoDirection::Receive,
            3,
            0x403,
            255,
            &[(0x6040, 0, 16), (0x607A, 0, 32)],
        ),
        (
            PdoDirection::Receive,
            4,
            0x503,
            255,
            &[(0x6040, 0, 16), (0x60FF, 0, 32)],
        ),
        (
            PdoDirection::Transmit,
            1,
            0x4000_0183,
            255,
            &[(0x6041, 0, 16)],
        ),
        (
            PdoDirection::Transmit,
            2,
            0x4000_0283,
            255,
            &[(0x6041, 0, 16), (0x6061, 0, 8)],
        ),
        (
            PdoDirection::Transmit,
            3,
            0x4000_0383,
            1,
            &[(0x6041, 0, 16), (0x6064, 0, 32)],
        ),
        (
            PdoDirection::Transmit,
            4,
            0x4000_0483,
            1,
            &[(0x6041, 0, 16), (0x606C, 0, 32)],
        ),
    ];
    assert_eq!(pdos.len(), expected.len());
    for (pdo, (direction, number, cob_id, transmission_type, map)) in pdos.iter().zip(expected) {
        assert_eq!(pdo.direction, direction);
        assert_eq!(pdo.number, number);
        assert_eq!(pdo.cob_id, cob_id, "{direction:?} {number}");
        assert!(pdo.valid());
        assert_eq!(pdo.can_id() & 0x7F, 3);
        assert_eq!(pdo.transmission_type, transmission_type);
        assert_eq!(mapping(pdo), map, "{direction:?} {number}");
    }
    assert_eq!(pdos[4].communication_index(), 0x1800);
    assert_eq!(pdos[4].mapping_index(), 0x1A00);
}

#[test]
fn mappable_objects_by_direction() {
    let eds = drive();
    let rx: Vec<u16> = eds
        .mappable(PdoDirection::Receive)
        .map(|s| s.index)
        .collect();
    let tx: Vec<u16> = eds
        .mappable(PdoDirection::Transmit)
        .map(|s| s.index)
        .collect();
    assert!(rx.contains(&0x6040) && !rx.contains(&0x6041));
    assert!(tx.contains(&0x6041) && !tx.contains(&0x6040));
    // rw objects go both ways.
    assert!(rx.contains(&0x6065) && tx.contains(&0x6065));
}

#[test]
fn the_e10_is_the_cpu226h_example() {
    let eds = e10();
    // Object index = 0x2000 + parameter number (decisions.md, "EDS/DCF files"). Settings are
    // `rw` (stored parameters), the command and control word `rww` (process data).
    let params: [(u16, &str, DataType, Access); 11] = [
        (282, "P282", DataType::Unsigned16, Access::Rww),
        (281, "P281", DataType::Unsigned16, Access::Rww),
        (290, "P290", DataType::Integer32, Access::Rw),
        (97, "P97", DataType::Integer16, Access::Rw),
        (113, "P113", DataType::Unsigned32, Access::Rw),
        (101, "P101", DataType::Integer16, Access::Rw),
        (102, "P102", DataType::Integer16, Access::Rw),
        (202, "R202", DataType::Unsigned16, Access::Ro),
        (204, "R204", DataType::Unsigned16, Access::Ro),
        (216, "R216", DataType::Integer32, Access::Ro),
        (221, "R221", DataType::Integer16, Access::Ro),
    ];
    for (number, label, data_type, access) in params {
        let object = eds.object(0x2000 + number).unwrap();
        assert_eq!(object.list, Some(ObjectList::Manufacturer));
        let sub = object.sub(0).unwrap();
        assert!(sub.name.starts_with(label), "{}", sub.name);
        assert_eq!((sub.data_type, sub.access), (data_type, access), "{label}");
        assert!(sub.pdo_mappable);
    }

    let pdos = eds.default_pdos(2).unwrap();
    let m = |n: u16, bits| (0x2000 + n, 0, bits);
    let valid: Vec<_> = pdos.iter().filter(|p| p.valid()).collect();
    let image: Vec<(PdoDirection, u32, Mapping)> = valid
        .iter()
        .map(|p| (p.direction, p.can_id(), mapping(p)))
        .collect();
    assert_eq!(
        image,
        [
            (
                PdoDirection::Receive,
                0x202,
                vec![m(282, 16), m(281, 16), m(290, 32)]
            ),
            (
                PdoDirection::Receive,
                0x302,
                vec![m(97, 16), m(113, 32), m(101, 16)]
            ),
            (PdoDirection::Receive, 0x402, vec![m(102, 16)]),
            (
                PdoDirection::Transmit,
                0x182,
                vec![m(202, 16), m(204, 16), m(216, 32)]
            ),
            (PdoDirection::Transmit, 0x282, vec![m(221, 16)]),
        ]
    );
    // Digest 003 §6: 10 bytes in (V0–V9), 18 bytes out (V10–V27).
    let bytes = |d| -> u32 {
        valid
            .iter()
            .filter(|p| p.direction == d)
            .map(|p| p.bits() / 8)
            .sum()
    };
    assert_eq!(bytes(PdoDirection::Transmit), 10);
    assert_eq!(bytes(PdoDirection::Receive), 18);
    assert!(pdos.iter().all(|p| p.transmission_type == 255));
    let tpdo1 = valid
        .iter()
        .find(|p| p.direction == PdoDirection::Transmit)
        .unwrap();
    assert_eq!((tpdo1.inhibit_time, tpdo1.event_timer), (100, 100));
}

#[test]
fn the_e10_enable_and_ready_bits_travel_in_the_first_pdos() {
    let eds = e10();
    let mut od = eds.dictionary(2).unwrap();
    // RPDO1 payload as the PLC sends it: P282 = 1 (bit 0, enable), P281 = 0, P290 = 4000.
    let pdo = &eds.default_pdos(2).unwrap()[0];
    let payload = [0x01, 0x00, 0x00, 0x00, 0xA0, 0x0F, 0x00, 0x00];
    let mut at = 0;
    for MappedObject {
        index,
        subindex,
        bits,
    } in &pdo.mapping
    {
        let len = usize::from(*bits / 8);
        od.write_bytes(*index, *subindex, &payload[at..at + len])
            .unwrap();
        at += len;
    }
    assert_eq!(od.read(0x211A, 0), Ok(Value::U16(1)));
    assert_eq!(od.read(0x2122, 0), Ok(Value::I32(4000)));
    // R204 is read-only to the master; the device sets bit 0 (ready).
    assert!(od.write(0x20CC, 0, Value::U16(1)).is_err());
    od.set(0x20CC, 0, Value::U16(1)).unwrap();
    assert_eq!(od.read_bytes(0x20CC, 0), Ok(vec![0x01, 0x00]));
}

/// The E10 EDS turned into a DCF: node 2 at 1000 kbit/s, as in the manual's example, with
/// configured values.
fn e10_dcf() -> String {
    let text = std::fs::read_to_string(fixture("ct-e10.eds")).unwrap();
    let text = text.replace(
        "[205F]\nParameterName=P95 1st internal speed\nObjectType=0x7\nDataType=0x0003\nAccessType=rw\nDefaultValue=0\n",
        "[205F]\nParameterName=P95 1st internal speed\nObjectType=0x7\nDataType=0x0003\nAccessType=rw\nDefaultValue=0\nParameterValue=-1500\n",
    );
    let text = text.replace(
        "[1017]\nParameterName=Producer heartbeat time\nObjectType=0x7\nDataType=0x0006\nAccessType=rw\nDefaultValue=0\n",
        "[1017]\nParameterName=Producer heartbeat time\nObjectType=0x7\nDataType=0x0006\nAccessType=rw\nDefaultValue=0\nParameterValue=0x64\nDenotation=heartbeat\n",
    );
    text + "\n[DeviceComissioning]\nNodeID=2\nNodeName=E10 axis 5\nBaudrate=1000\nNetNumber=1\nCANopenManager=0\n"
}

#[test]
fn dcf_parameter_values_replace_defaults_and_commissioning_is_read() {
    let dcf = Eds::parse("e10.dcf", &e10_dcf()).unwrap();
    assert!(dcf.is_dcf());
    let c = dcf.commissioning.as_ref().unwrap();
    assert_eq!(c.node_id, Some(2));
    assert_eq!(c.bit_rate_kbit, Some(1000));
    assert_eq!(c.node_name.as_deref(), Some("E10 axis 5"));
    let p95 = dcf.sub_object(0x205F, 0).unwrap();
    assert_eq!(p95.default, EdsValue::Fixed(Value::I16(0)));
    assert_eq!(
        p95.parameter_value,
        Some(EdsValue::Fixed(Value::I16(-1500)))
    );
    let mut od = dcf.dictionary(2).unwrap();
    assert_eq!(od.read(0x205F, 0), Ok(Value::I16(-1500)));
    assert_eq!(od.read(0x1017, 0), Ok(Value::U16(100)));
    od.write(0x1017, 0, Value::U16(5)).unwrap();
    od.restore_defaults();
    assert_eq!(
        od.read(0x1017, 0),
        Ok(Value::U16(100)),
        "the DCF value is the start value"
    );
}

#[test]
fn compact_arrays_take_names_and_dcf_values() {
    let listed = "[ManufacturerObjects]\nSupportedObjects=1\n1=0x2F00\n";
    let shipped = std::fs::read_to_string(fixture("cia402-drive.eds")).unwrap();
    assert!(
        shipped.contains(listed),
        "the shipped manufacturer objects changed"
    );
    let text = shipped.replace(
        listed,
        "[ManufacturerObjects]\nSupportedObjects=2\n1=0x2F00\n2=0x2100\n",
    )
        + "\n[2100]\nParameterName=Gains\nObjectType=0x8\nDataType=0x0003\nAccessType=rw\n\
           PDOMapping=1\nDefaultValue=7\nLowLimit=-100\nHighLimit=100\nCompactSubObj=3\n\n\
           [2100Name]\nNrOfEntries=2\n1=Kp\n3=Kd\n\n\
           [2100Value]\nNrOfEntries=1\n2=-5\n\n\
           [2100Denotation]\nNrOfEntries=1\n1=proportional\n";
    let eds = Eds::parse("compact.eds", &text).unwrap();
    assert!(eds.warnings.is_empty(), "{:?}", eds.warnings);
    let gains = eds.object(0x2100).unwrap();
    assert_eq!(gains.sub_objects.len(), 4);
    let names: Vec<&str> = gains
        .sub_objects
        .values()
        .map(|s| s.name.as_str())
        .collect();
    assert_eq!(
        names,
        ["Highest sub-index supported", "Kp", "Gains 2", "Kd"]
    );
    let od = eds.dictionary(1).unwrap();
    assert_eq!(od.read(0x2100, 0), Ok(Value::U8(3)));
    assert_eq!(od.read(0x2100, 1), Ok(Value::I16(7)));
    assert_eq!(od.read(0x2100, 2), Ok(Value::I16(-5)));
    assert_eq!(od.entry(0x2100, 3).unwrap().def.high, Some(Value::I16(100)));
    assert!(od.check_mappable(0x2100, 3, PdoDirection::Receive).is_ok());
}

#[test]
fn crlf_bom_latin1_and_key_case_do_not_change_the_model() {
    let text = std::fs::read_to_string(fixture("cia402-drive.eds")).unwrap();
    let reference = Eds::parse("x.eds", &text).unwrap();

    let crlf_bom = format!("\u{feff}{}", text.replace('\n', "\r\n"));
    assert_eq!(Eds::parse("x.eds", &crlf_bom).unwrap(), reference);

    // Keys upper case, section names lower case.
    let shouted: String = text
        .lines()
        .map(|line| match line.split_once('=') {
            Some((k, v)) if !line.starts_with(';') => format!("{}={v}\n", k.to_uppercase()),
            _ if line.starts_with('[') => format!("{}\n", line.to_lowercase()),
            _ => format!("{line}\n"),
        })
        .collect();
    let shouted = Eds::parse("x.eds", &shouted).unwrap();
    // Section spellings differ; everything else is the same.
    let strip = |eds: &Eds| -> Vec<(u16, u8, String, String)> {
        eds.sub_objects()
            .map(|s| {
                (
                    s.index,
                    s.subindex,
                    s.name.clone(),
                    format!("{:?}", s.initial()),
                )
            })
            .collect()
    };
    assert_eq!(strip(&shouted), strip(&reference));
    assert_eq!(shouted.device_info, reference.device_info);

    // A Latin-1 comment and name (as Windows tools write them) load.
    let mut latin1 = text.clone().into_bytes();
    latin1.extend_from_slice(b"\n; Gr\xf6\xdfe\n");
    let eds = Eds::parse_bytes("x.eds", &latin1).unwrap();
    assert_eq!(eds.sub_objects().count(), reference.sub_objects().count());
    let renamed = text.replace(
        "ParameterName=Controlword",
        "ParameterName=Steuerwort \u{fc}",
    );
    let latin1: Vec<u8> = renamed
        .chars()
        .map(|c| u8::try_from(u32::from(c)).unwrap_or(b'?'))
        .collect();
    let eds = Eds::parse_bytes("x.eds", &latin1).unwrap();
    assert_eq!(eds.sub_object(0x6040, 0).unwrap().name, "Steuerwort \u{fc}");
}

#[test]
fn values_round_trip_through_the_dictionary_as_bytes() {
    let eds = drive();
    let mut od = eds.dictionary(1).unwrap();
    let cases: [(u16, u8, Value); 6] = [
        (0x6040, 0, Value::U16(0x000F)),
        (0x6060, 0, Value::I8(-1)),
        (0x607A, 0, Value::I32(-123_456)),
        (0x607D, 2, Value::I32(1 << 30)),
        (0x1017, 0, Value::U16(250)),
        (0x1400, 1, Value::U32(0x8000_0201)),
    ];
    for (index, sub, value) in cases {
        let bytes = value.to_le_bytes();
        od.write_bytes(index, sub, &bytes).unwrap();
        assert_eq!(od.read(index, sub), Ok(value.clone()));
        assert_eq!(od.read_bytes(index, sub), Ok(bytes));
    }
    // Limits from the file are enforced by the dictionary.
    assert!(od.write(0x6007, 0, Value::I16(4)).is_err());
    assert!(od.write(0x605D, 0, Value::I16(0)).is_err());
    assert!(od.write(0x1000, 0, Value::U32(0)).is_err(), "const");
}

#[test]
fn unlisted_sections_and_wrong_pdo_counts_are_warnings() {
    let text = std::fs::read_to_string(fixture("ct-e10.eds"))
        .unwrap()
        .replace("NrOfTXPDO=4", "NrOfTXPDO=2")
        + "\n[3000]\nParameterName=Not in any list\nDataType=0x0005\nAccessType=rw\n";
    let eds = Eds::parse("w.eds", &text).unwrap();
    let shown: Vec<String> = eds.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(shown.len(), 2, "{shown:?}");
    assert!(shown[0].starts_with("w.eds: [3000] no object list names this object"));
    assert!(shown[1].starts_with("w.eds: [DeviceInfo] NrOfTXPDO: says 2, but the file has 4"));
    assert!(eds.object(0x3000).unwrap().list.is_none());
}
