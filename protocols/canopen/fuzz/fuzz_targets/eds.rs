//! `Eds::parse_bytes` on arbitrary bytes: never panics; an error names the file and displays; a
//! file that loads builds its dictionary and default PDOs for every node id, every entry starts
//! within its limits, every default PDO maps objects the dictionary lets it map, and every
//! value's EDS spelling reads back as the same value.

#![no_main]

use libfuzzer_sys::fuzz_target;
use mcemu_canopen::eds::{format_value, parse_value, Eds, EdsValue, MAX_PDO_BITS};

fuzz_target!(|data: &[u8]| {
    let eds = match Eds::parse_bytes("fuzz.eds", data) {
        Ok(eds) => eds,
        Err(err) => {
            assert_eq!(&*err.file, "fuzz.eds");
            assert!(err.to_string().starts_with("fuzz.eds: "));
            return;
        }
    };
    for node_id in [1, 127] {
        let od = eds
            .dictionary(node_id)
            .expect("a loaded file builds a dictionary");
        assert_eq!(od.len(), eds.sub_objects().count());
        for pdo in eds
            .default_pdos(node_id)
            .expect("a loaded file has its PDOs")
        {
            assert!(pdo.bits() <= MAX_PDO_BITS);
            for m in &pdo.mapping {
                // Indices 1–7 are dummy entries (data types), not objects.
                if m.index > 7 {
                    assert!(od
                        .check_mappable(m.index, m.subindex, pdo.direction)
                        .is_ok());
                }
            }
        }
    }
    for sub in eds.sub_objects() {
        if let EdsValue::Fixed(value) = sub.initial() {
            let text = format_value(value);
            let back = parse_value(&text, sub.data_type).expect("a formatted value parses");
            // NaN payloads survive as bit patterns; compare spellings, which are exact.
            assert_eq!(format_value(&back.resolve(1).expect("fixed")), text);
        }
    }
    assert!(eds.dictionary(0).is_err() && eds.dictionary(128).is_err());
});
