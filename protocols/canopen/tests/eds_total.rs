// Tests fail loudly.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

//! The loader is total: any bytes, and any damage to a real file, give a model or an error that
//! names the file, never a panic; and whatever loads builds a dictionary and its default PDOs for
//! every node id (the checks at load cover what building needs).

use mcemu_canopen::eds::Eds;
use proptest::prelude::*;

const DRIVE: &str = include_str!("../../../fixtures/canopen/cia402-drive.eds");
const E10: &str = include_str!("../../../fixtures/canopen/ct-e10.eds");

fn check(bytes: &[u8]) -> Result<(), TestCaseError> {
    match Eds::parse_bytes("fuzz.eds", bytes) {
        Ok(eds) => {
            for node_id in [1, 64, 127] {
                let od = eds.dictionary(node_id);
                prop_assert!(od.is_ok(), "{:?}", od.err());
                let pdos = eds.default_pdos(node_id);
                prop_assert!(pdos.is_ok(), "{:?}", pdos.err());
            }
        }
        Err(err) => {
            prop_assert_eq!(&*err.file, "fuzz.eds");
            prop_assert!(err.to_string().starts_with("fuzz.eds: "));
        }
    }
    Ok(())
}

/// One change to one line of a file.
#[derive(Clone, Debug)]
enum Damage {
    Delete(usize),
    Duplicate(usize),
    /// Replace the value after `=` with this text.
    Value(usize, String),
    /// Cut the line after this many bytes.
    Cut(usize, usize),
    Insert(usize, String),
}

fn damage() -> impl Strategy<Value = Damage> {
    let text = prop_oneof![
        "[0-9A-Fa-fx$+\\-]{0,12}",
        "\\$NODEID[+\\-]0x[0-9A-F]{1,9}",
        "[ -~]{0,20}",
        "\\PC{0,8}",
    ];
    prop_oneof![
        any::<usize>().prop_map(Damage::Delete),
        any::<usize>().prop_map(Damage::Duplicate),
        (any::<usize>(), text.clone()).prop_map(|(l, t)| Damage::Value(l, t)),
        (any::<usize>(), 0usize..20).prop_map(|(l, n)| Damage::Cut(l, n)),
        (any::<usize>(), text).prop_map(|(l, t)| Damage::Insert(l, t)),
    ]
}

fn apply(text: &str, damages: &[Damage]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for d in damages {
        let n = lines.len().max(1);
        match d {
            Damage::Delete(l) if !lines.is_empty() => {
                lines.remove(l % n);
            }
            Damage::Duplicate(l) if !lines.is_empty() => {
                let line = lines[l % n].clone();
                lines.insert(l % n, line);
            }
            Damage::Value(l, t) if !lines.is_empty() => {
                let line = &mut lines[l % n];
                if let Some(at) = line.find('=') {
                    line.truncate(at + 1);
                    line.push_str(t);
                }
            }
            Damage::Cut(l, len) if !lines.is_empty() => {
                let line = &mut lines[l % n];
                let mut cut = (*len).min(line.len());
                while !line.is_char_boundary(cut) {
                    cut -= 1;
                }
                line.truncate(cut);
            }
            Damage::Insert(l, t) => lines.insert(l % n, t.clone()),
            _ => {}
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, ..ProptestConfig::default() })]

    #[test]
    fn damaged_shipped_files_load_or_fail_cleanly(
        e10 in any::<bool>(),
        damages in prop::collection::vec(damage(), 1..6),
    ) {
        let text = apply(if e10 { E10 } else { DRIVE }, &damages);
        check(text.as_bytes())?;
    }

    #[test]
    fn any_bytes_load_or_fail_cleanly(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        check(&bytes)?;
    }

    #[test]
    fn ini_shaped_noise_loads_or_fails_cleanly(
        lines in prop::collection::vec((prop::sample::select(&VOCABULARY[..]), value()), 0..60),
    ) {
        let text: Vec<String> = lines
            .into_iter()
            .map(|(line, value)| if line.ends_with('=') { format!("{line}{value}") } else { line.to_string() })
            .collect();
        check(text.join("\n").as_bytes())?;
    }
}

/// Lines of EDS files: headers as they are, keys to which a value is added.
const VOCABULARY: [&str; 30] = [
    "[1000]",
    "[1001]",
    "[1018]",
    "[1018sub0]",
    "[1018sub1]",
    "[1400]",
    "[1400sub1]",
    "[1600]",
    "[1600sub0]",
    "[1600sub1]",
    "[2000]",
    "[2000Name]",
    "[2000Value]",
    "[MandatoryObjects]",
    "[OptionalObjects]",
    "[DeviceInfo]",
    "[DummyUsage]",
    "[DeviceComissioning]",
    "ParameterName=",
    "ObjectType=",
    "DataType=",
    "AccessType=",
    "DefaultValue=",
    "PDOMapping=",
    "SubNumber=",
    "CompactSubObj=",
    "LowLimit=",
    "HighLimit=",
    "SupportedObjects=",
    "1=",
];

fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "0x7",
            "0x8",
            "0x9",
            "0x0005",
            "0x0007",
            "rw",
            "ro",
            "rww",
            "const",
            "1",
            "2",
            "0",
            "0x1000",
            "0x1018",
            "0x60400010",
            "$NODEID+0x200",
            "255",
            "-1",
        ])
        .prop_map(str::to_string),
        "[ -~]{0,8}",
    ]
}
